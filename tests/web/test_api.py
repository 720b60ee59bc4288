"""The workbench's HTTP API (`linkwork.web`): every endpoint answers what the Python API answers
(the same documents as the command line's JSON), positions also against closed forms of the
crank-rocker drawn in `library:crank-rocker` (crank O2A = 10 mm about the origin); bad input,
paths out of the working folder, oversized bodies and bugs give JSON errors, never a trace."""

from __future__ import annotations

import json
import math
import re
import tomllib
import warnings

import numpy as np
import pytest
from typer.testing import CliRunner

with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the test client's notice about its HTTP library
    from fastapi.testclient import TestClient

import linkwork
from linkwork.cli import app as cli_app
from linkwork.constructions import construct
from linkwork.instant.export import curvature_document, poles_document
from linkwork.io import resolve
from linkwork.io.library import library_names
from linkwork.kinematics.export import to_document
from linkwork.structure import structure_report
from linkwork.web import create_app

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

SRC = {"library": "crank-rocker"}
MECH = linkwork.load("library:crank-rocker")


def same(a, b) -> None:
    """Two JSON documents equal after a JSON round trip (tuples become lists, floats as sent)."""
    assert json.loads(json.dumps(a)) == json.loads(json.dumps(b))


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    root = tmp_path_factory.mktemp("work")
    (root / "mine.toml").write_text(resolve("library:crank-rocker")[1])
    (root / "sub").mkdir()
    (root / "sub" / "other.toml").write_text(resolve("library:slider-crank-centric")[1])
    outside = tmp_path_factory.mktemp("outside")
    (outside / "secret.toml").write_text(resolve("library:double-crank")[1])
    (root / "link.toml").symlink_to(outside / "secret.toml")
    (root / "notes.txt").write_text("not a mechanism")
    return root


@pytest.fixture(scope="module")
def client(workdir):
    return TestClient(create_app(workdir), raise_server_exceptions=False)


def post(client, path, **body):
    return client.post(path, json=body)


# ---------------------------------------------------------------------------- reading
def test_library_lists_the_library_and_the_working_folder(client):
    r = client.get("/api/library")
    assert r.status_code == 200
    doc = r.json()
    assert [e["name"] for e in doc["mechanisms"]] == library_names()
    titles = {e["name"]: e["title"] for e in doc["mechanisms"]}
    assert titles["crank-rocker"] == tomllib.loads(resolve("library:crank-rocker")[1])["name"]
    # the symlink leads out of the folder and is not listed; the text file is no mechanism
    assert doc["files"] == ["mine.toml", "sub/other.toml"]


def test_library_text(client):
    r = client.get("/api/library/crank-rocker")
    assert r.status_code == 200 and r.json()["text"] == resolve("library:crank-rocker")[1]
    r = client.get("/api/library/no-such")
    assert r.status_code == 404 and "no mechanism 'no-such'" in r.json()["error"]


def test_mechanism_info(client):
    r = post(client, "/api/mechanism", source=SRC)
    assert r.status_code == 200, r.text
    doc = r.json()
    assert doc["points"] == {"O2": [0, 0], "A": [0, 10], "B": [30, 30], "O4": [40, 0], "C": [15, 25]}
    assert doc["links"]["coupler"] == ["A", "B", "C"] and doc["frame"] == "frame"
    assert doc["owners"]["O4"] == "frame" and doc["owners"]["C"] == "coupler"
    # the input is the angle of O2→A: straight up in the drawing
    assert doc["drivers"] == [{"joint": "O2", "kind": "revolute", "design_input": pytest.approx(math.pi / 2)}]
    assert {"mechanism", "poles", "centrodes", "inflection"} <= set(doc["layers"])
    assert "velocity-plan" in doc["constructions"]
    assert doc["text"] == resolve("library:crank-rocker")[1]


def test_a_file_of_the_working_folder(client):
    r = post(client, "/api/mechanism", source={"file": "sub/other.toml"})
    assert r.status_code == 200 and r.json()["source"] == "sub/other.toml"


# ---------------------------------------------------------------------------- numbers
def test_solve_equals_the_python_api_and_the_closed_form(client):
    at = [0.1, 0.7, 2.5]
    r = post(client, "/api/solve", source=SRC, at=at)
    assert r.status_code == 200
    doc = r.json()
    same({k: v for k, v in doc.items() if k != "warnings"}, to_document(linkwork.solve(MECH, at)))
    for s, th in zip(doc["samples"], at):  # the crank's end on its circle of radius 10
        assert s["points"]["A"]["position"] == pytest.approx([10 * math.cos(th), 10 * math.sin(th)], abs=1e-12)
        # 60 rpm: |v_A| = 10·2π mm/s
        assert np.hypot(*s["points"]["A"]["velocity"]) == pytest.approx(20 * math.pi, rel=1e-12)


def test_solve_at_times_and_orders(client):
    r = post(client, "/api/solve", source=SRC, times=[0.0, 0.25], order=1)
    assert r.status_code == 200
    same(r.json()["samples"], to_document(linkwork.solve(MECH, times=[0.0, 0.25], order=1))["samples"])
    # a quarter turn at 60 rpm after the design position (90°): the crank points left
    assert r.json()["samples"][1]["points"]["A"]["position"] == pytest.approx([-10, 0], abs=1e-12)


def test_whole_motion(client):
    r = post(client, "/api/motion", source=SRC)
    assert r.status_code == 200
    full = to_document(linkwork.whole_motion(MECH))
    same({k: v for k, v in r.json().items() if k != "warnings"}, full)
    r = post(client, "/api/motion", source=SRC, detail="status")
    short = r.json()["samples"]
    assert [(s["input"], s["status"]) for s in short] == [(s["input"], s["status"]) for s in full["samples"]]


def test_poles(client):
    r = post(client, "/api/poles", source=SRC, at=[0.3], schedule=True)
    assert r.status_code == 200
    doc = r.json()
    same({k: v for k, v in doc.items() if k != "warnings"},
         poles_document(linkwork.solve(MECH, [0.3], order=1), True))
    poles = {p["label"]: p["pole"] for p in doc["samples"][0]["poles"]}
    # the frame's poles with crank and rocker are their fixed pivots O2 and O4
    assert (poles["P12"]["x"], poles["P12"]["y"]) == pytest.approx((0, 0), abs=1e-12)
    assert (poles["P14"]["x"], poles["P14"]["y"]) == pytest.approx((40, 0), abs=1e-12)


def test_curvature(client):
    r = post(client, "/api/curvature", source=SRC, link="coupler", points=["C", [5, 5]], at=[0.3, 1.2])
    assert r.status_code == 200, r.text
    sol = linkwork.solve(MECH, [0.3, 1.2], order=3)
    want = curvature_document(sol, "coupler", None, [("C", "C"), ("5,5", np.array([5.0, 5.0]))])
    same({k: v for k, v in r.json().items() if k != "warnings"}, want)
    # B moves on the circle about O4: its curvature centre is O4 (radius |O4B| = √1000)
    r = post(client, "/api/curvature", source=SRC, link="coupler", points=["B"], at=[0.3])
    cc = r.json()["samples"][0]["curvature_centres"]["B"]
    assert (cc["centre"]["x"], cc["centre"]["y"]) == pytest.approx((40, 0), abs=1e-9)
    assert abs(cc["radius"]) == pytest.approx(math.sqrt(1000), rel=1e-10)


def test_structure(client):
    r = post(client, "/api/structure", source=SRC)
    assert r.status_code == 200
    same({k: v for k, v in r.json().items() if k != "warnings"}, structure_report(MECH).as_dict())
    assert r.json()["counts"]["mobility"] == 1  # 3(4 − 1) − 2·4


def test_construction(client):
    r = post(client, "/api/construction", source=SRC, name="velocity-plan", at=[0.4])
    assert r.status_code == 200
    con = construct("velocity-plan", MECH, linkwork.solve(MECH, [0.4]))
    assert r.json()["steps"] == [s.text for s in con.steps] and r.json()["description"] == con.describe()
    r = post(client, "/api/construction", source=SRC, name="no-such")
    assert r.status_code == 422


# ---------------------------------------------------------------------------- drawings
def _dot(svg: str, ident: str) -> tuple[float, float]:
    m = re.search(rf'<circle[^>]*id="{ident}"[^>]*>', svg)
    assert m, f"no {ident} in the drawing"
    tag = m.group(0)
    return float(re.search(r'cx="([-\d.]+)"', tag).group(1)), float(re.search(r'cy="([-\d.]+)"', tag).group(1))


def test_drawing_is_linkwork_draw(client, tmp_path):
    """With fit = drawing the SVG is the very file `linkwork draw` writes."""
    out = tmp_path / "d.svg"
    res = CliRunner().invoke(cli_app, ["draw", "library:crank-rocker", "--at", "30", "--show",
                                       "mechanism,poles,inflection", "-o", str(out)])
    assert res.exit_code == 0, res.output
    r = post(client, "/api/drawing", source=SRC, at=[math.radians(30)],
             layers=["mechanism", "poles", "inflection"], fit="drawing")
    assert r.status_code == 200
    assert r.json()["svg"] == out.read_text()


def test_drawing_places_points_where_the_engine_puts_them(client):
    for th in (0.2, 2.0):
        r = post(client, "/api/drawing", source=SRC, at=[th])
        doc = r.json()
        assert doc["status"] == "ok" and doc["input"] == [th]
        xy = linkwork.solve(MECH, [th]).point("C").position[0]
        assert doc["points"]["C"] == pytest.approx(list(xy), abs=1e-12)
        t = doc["transforms"]["mechanism"]
        want = (t["origin"][0] + (xy[0] - t["lo"][0]) / t["per_mm"],
                t["origin"][1] + (t["hi"][1] - xy[1]) / t["per_mm"])
        assert _dot(doc["svg"], "point-C") == pytest.approx(want, abs=1e-3)  # SVG: 3 decimals
        # the poses place every point: position = R(θ)·design + (x, y) of its link
        for p, xy_p in doc["points"].items():
            x, y, turn = doc["poses"][MECH.point_owner[p]]
            d = MECH.points[p]
            assert xy_p == pytest.approx([x + math.cos(turn) * d[0] - math.sin(turn) * d[1],
                                          y + math.sin(turn) * d[0] + math.cos(turn) * d[1]], abs=1e-12)
        # the crank turned from its design position (90°) to th
        assert doc["poses"]["crank"] == pytest.approx([0, 0, th - math.pi / 2], abs=1e-12)
    # fit = motion: every frame of the motion shares one layout
    a = post(client, "/api/drawing", source=SRC, at=[0.2]).json()["transforms"]
    b = post(client, "/api/drawing", source=SRC, at=[2.0]).json()["transforms"]
    assert a == b


def test_drawing_without_the_whole_motion(client):
    """The frames of a drag: the same position, no paths."""
    r = post(client, "/api/drawing", source=SRC, at=[0.7], layers=["mechanism", "paths"], motion=False)
    assert r.status_code == 200
    doc = r.json()
    xy = linkwork.solve(MECH, [0.7]).point("C").position[0]
    assert doc["points"]["C"] == pytest.approx(list(xy), abs=1e-12)
    assert "path-C" not in doc["svg"] and "could not be computed" in doc["svg"]
    assert "path-C" in post(client, "/api/drawing", source=SRC, at=[0.7], layers=["mechanism", "paths"]).json()["svg"]


def test_a_drawing_says_where_its_time_went(client):
    """The Server-Timing header of a drawing (the bench and the browser's tools read it): each
    stage once, in the order the work happens, the whole request (`app`) last."""
    r = post(client, "/api/drawing", source=SRC, at=[0.7], layers=["mechanism"], motion=False)
    parts = [p.strip().split(";dur=") for p in r.headers["server-timing"].split(",")]
    assert [name for name, _ in parts] == ["load", "solve", "scene", "svg", "encode", "cpu", "app"]
    ms = {name: float(v) for name, v in parts}
    assert all(v >= 0 for v in ms.values())
    assert ms["app"] >= ms["load"] + ms["solve"] + ms["scene"] + ms["svg"]


def test_drawing_with_a_construction_and_its_steps(client):
    r = post(client, "/api/drawing", source=SRC, at=[0.4], layers=["mechanism"],
             construction="velocity-plan", step=1)
    assert r.status_code == 200
    assert "velocity" in r.json()["transforms"] or len(r.json()["transforms"]) == 2
    assert len(r.json()["steps"]) > 2
    r = post(client, "/api/drawing", source=SRC, construction="velocity-plan", step=999)
    assert r.status_code == 400 and "steps" in r.json()["error"]


# ---------------------------------------------------------------------------- editing
def test_moved_design_points(client):
    # a crank of 12 instead of 10: A on the circle of radius 12
    src = {"library": "crank-rocker", "points": {"A": [0, 12]}}
    r = post(client, "/api/solve", source=src, at=[1.0])
    assert r.json()["samples"][0]["points"]["A"]["position"] == pytest.approx(
        [12 * math.cos(1.0), 12 * math.sin(1.0)], abs=1e-12)
    r = post(client, "/api/mechanism", source=src)
    assert r.json()["points"]["A"] == [0, 12]
    r = post(client, "/api/mechanism", source={"library": "crank-rocker", "points": {"Z": [0, 1]}})
    assert r.status_code == 400 and "no point 'Z'" in r.json()["error"]


def test_an_unassemblable_position_is_an_error_with_the_engines_message(client):
    # crank 25: at 180° |A O4| = 65 exceeds coupler + rocker = √925 + √1000 ≈ 62.0
    src = {"library": "crank-rocker", "points": {"A": [0, 25]}}
    assert math.sqrt(925) + math.sqrt(1000) < 65
    r = post(client, "/api/drawing", source=src, at=[math.pi])
    assert r.status_code == 400 and "cannot be assembled" in r.json()["error"]
    r = post(client, "/api/solve", source=src, at=[math.pi])
    assert r.json()["samples"][0]["status"] == "unreachable"


# ---------------------------------------------------------------------------- refusals
def test_a_bad_file_gives_its_message(client):
    text = resolve("library:crank-rocker")[1].replace('coupler = ["A", "B", "C"]', 'coupler = ["A", "B", "X"]')
    r = post(client, "/api/mechanism", source={"text": text, "name": "bad.toml"})
    assert r.status_code == 400
    err = r.json()
    assert err["kind"] == "MechanismFileError"
    line = next(i for i, t in enumerate(text.splitlines(), 1) if t.startswith("coupler"))
    assert err["error"].startswith(f"bad.toml:{line}, key 'links.coupler'") and "'X'" in err["error"]
    r = post(client, "/api/mechanism", source={"text": "name = [", "name": "x.toml"})
    assert r.status_code == 400 and "not valid TOML" in r.json()["error"]


@pytest.mark.parametrize("name", ["../outside.toml", "/etc/passwd", "sub/../../x.toml", "link.toml",
                                  "notes.txt", "missing.toml", ""])
def test_files_outside_the_working_folder_are_refused(client, name):
    r = post(client, "/api/mechanism", source={"file": name})
    assert r.status_code in (400, 404)
    assert "error" in r.json() and "Traceback" not in r.text


def test_no_working_folder_no_files():
    c = TestClient(create_app(None), raise_server_exceptions=False)
    r = post(c, "/api/mechanism", source={"file": "mine.toml"})
    assert r.status_code == 400 and "no working folder" in r.json()["error"]
    assert c.get("/api/library").json()["files"] == []


@pytest.mark.parametrize("body", [
    {"source": {}},
    {"source": {"library": "crank-rocker", "text": "x"}},
    {"source": {"library": "../crank-rocker"}},
    {"source": SRC, "extra": 1},
    {"source": SRC, "at": [1e13]},
    {"source": SRC, "at": []},
    {"source": SRC, "at": [0.1], "times": [0.1]},
    {"source": SRC, "at": [0.0] * 20_001},
    {"source": {"text": "x" * 200_001}},
])
def test_invalid_requests(client, body):
    r = client.post("/api/solve", json=body)
    assert r.status_code == 422, r.text
    assert r.json()["kind"] == "RequestValidationError" and r.json()["error"]


def test_non_finite_numbers_are_refused(client):
    for raw in ('{"source": {"library": "crank-rocker"}, "at": [NaN]}',
                '{"source": {"library": "crank-rocker"}, "at": [Infinity]}',
                '{"source": {"library": "crank-rocker", "points": {"A": [0, NaN]}}}'):
        r = client.post("/api/solve", content=raw, headers={"content-type": "application/json"})
        assert r.status_code == 422, raw


def test_several_drivers_need_a_value_each(client):
    r = post(client, "/api/solve", source=SRC, at=[[0.1, 0.2]])
    assert r.status_code == 400 and "one value per driver" in r.json()["error"]


def test_oversized_bodies_are_refused(client):
    r = client.post("/api/solve", content=b"{" + b" " * 1_100_000 + b"}",
                    headers={"content-type": "application/json"})
    assert r.status_code == 413 and "larger than" in r.json()["error"]

    def chunks():  # no Content-Length: counted as it arrives
        for _ in range(30):
            yield b" " * 50_000

    r = client.post("/api/solve", content=chunks(), headers={"content-type": "application/json"})
    assert r.status_code == 413


def test_a_bug_is_a_500_without_a_trace(client, monkeypatch):
    import linkwork.web.app as web_app

    def broken(sol):
        raise RuntimeError("secret internals")

    monkeypatch.setattr(web_app, "to_document", broken)
    r = post(client, "/api/solve", source=SRC)
    assert r.status_code == 500
    assert r.json()["kind"] == "InternalError"
    assert "secret" not in r.text and "Traceback" not in r.text and "File " not in r.text


def test_openapi_schema_is_published(client):
    doc = client.get("/api/openapi.json").json()
    for path in ("/api/library", "/api/library/{name}", "/api/mechanism", "/api/solve", "/api/motion",
                 "/api/poles", "/api/curvature", "/api/structure", "/api/construction", "/api/drawing"):
        assert path in doc["paths"]
    assert "Source" in doc["components"]["schemas"]


# ---------------------------------------------------------------------------- linkwork serve
def test_serve_binds_locally_unless_told(monkeypatch, workdir):
    import uvicorn
    calls = []
    monkeypatch.setattr(uvicorn, "run", lambda app, **kw: calls.append({**kw, "app": app}))
    runner = CliRunner()
    r = runner.invoke(cli_app, ["serve", "--host", "0.0.0.0"])
    assert r.exit_code == 2 and "--expose" in r.output and not calls
    r = runner.invoke(cli_app, ["serve", "library:crank-rocker", "--port", "0"])
    assert r.exit_code == 0, r.output
    assert calls[-1]["host"] == "127.0.0.1"
    # on this computer it answers requests to its own names only (DNS rebinding)
    served = TestClient(calls[-1]["app"], raise_server_exceptions=False)
    assert served.get("/api/library", headers={"host": "127.0.0.1:8765"}).status_code == 200
    assert served.get("/api/library", headers={"host": "rebound.example"}).status_code == 400
    assert re.search(r"http://127\.0\.0\.1:\d+/\?library=crank-rocker", r.output)
    r = runner.invoke(cli_app, ["serve", "--host", "0.0.0.0", "--expose", "--port", "0"])
    assert r.exit_code == 0 and "warning" in r.output and calls[-1]["host"] == "0.0.0.0"
    r = runner.invoke(cli_app, ["serve", str(workdir / "mine.toml"), "--port", "0"])
    assert r.exit_code == 0 and "?file=mine.toml" in r.output
    r = runner.invoke(cli_app, ["serve", "library:nope"])
    assert r.exit_code == 2 and "no mechanism 'nope'" in r.output


def test_the_page_and_only_its_files_are_served(client):
    r = client.get("/")
    assert r.status_code == 200 and '<script src="/static/app.js">' in r.text
    assert client.get("/static/style.css").status_code == 200
    for path in ("/static/../app.py", "/static/..%2fapp.py", "/static/%2e%2e/sources.py",
                 "/static/../../io/files.py"):
        r = client.get(path)
        assert r.status_code == 404 and "import" not in r.text, path


def test_drawing_traces_the_paths_asked(client):
    def ids(**extra):
        r = post(client, "/api/drawing", source=SRC, layers=["mechanism", "paths"], **extra)
        assert r.status_code == 200, r.text
        return set(re.findall(r'id="(path-[^"]+)"', r.json()["svg"]))

    assert ids() == {"path-A", "path-B", "path-C"}  # every moving point by default
    assert ids(paths=["C"]) == {"path-C"}
    assert ids(paths=[]) == set()
    r = post(client, "/api/drawing", source=SRC, layers=["paths"], paths=["Z"])
    assert r.status_code == 400 and "no point 'Z'" in r.json()["error"]


def _png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


def test_drawing_as_png(client):
    pytest.importorskip("cairosvg")
    body = dict(source=SRC, layers=["mechanism", "poles"], at=[1.0])
    svg = post(client, "/api/drawing", **body).json()["svg"]
    w_mm, h_mm = (float(v) for v in re.search(r'width="([\d.]+)mm" height="([\d.]+)mm"', svg).groups())
    for dpi in (200.0, 96.0):
        r = post(client, "/api/drawing.png", **body, dpi=dpi)
        assert r.status_code == 200 and r.headers["content-type"] == "image/png"
        w, h = _png_size(r.content)  # the paper's size at the resolution asked
        assert abs(w - w_mm / 25.4 * dpi) <= 1 and abs(h - h_mm / 25.4 * dpi) <= 1
    r = post(client, "/api/drawing.png", **body, dpi=5000)
    assert r.status_code == 422 and r.json()["kind"] == "RequestValidationError"


def test_motion_as_csv(client):
    from linkwork.kinematics.export import csv_lines
    r = post(client, "/api/motion.csv", source=SRC)
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/csv")
    sol = linkwork.whole_motion(MECH)
    assert r.text == "".join(csv_lines(sol, units=True))
    head, *rows = r.text.splitlines()
    assert len(rows) == len(sol)
    col = head.split(",").index("C.x [mm]")
    assert [float(row.split(",")[col]) for row in rows] == pytest.approx(sol.point("C").position[:, 0], rel=1e-15)


def test_motion_status_with_error_bounds_that_are_not_finite(client):
    """A Stephenson six-bar (the crank-rocker with a dyad C–F–O6) passes two samples whose error
    bound is not finite: they come back as null, the answer stays JSON."""
    text = resolve("library:crank-rocker")[1]
    text = (text.replace('C  = [15, 25]\n', 'C  = [15, 25]\nF = [45, 45]\nO6 = [70, 30]\n')
            .replace('frame   = ["O2", "O4"]', 'frame = ["O2", "O4", "O6"]')
            .replace('rocker  = ["B", "O4"]\n', 'rocker  = ["B", "O4"]\nl5 = ["C", "F"]\nl6 = ["F", "O6"]\n')
            + '\n[joints.C]\ntype = "revolute"\nlinks = ["coupler", "l5"]\n'
              '[joints.F]\ntype = "revolute"\nlinks = ["l5", "l6"]\n'
              '[joints.O6]\ntype = "revolute"\nlinks = ["l6", "frame"]\n')
    sol = linkwork.whole_motion(linkwork.io.load_text(text))
    bad = ~np.isfinite(sol.errors)
    assert bad.any()
    r = post(client, "/api/motion", source={"text": text}, detail="status")
    assert r.status_code == 200, r.text
    errors = [s["error"] for s in r.json()["samples"]]
    assert [e is None for e in errors] == bad.tolist()


def test_the_server_solves_with_the_compiled_loops(monkeypatch):
    """`linkwork serve` makes its application with compiled=True: when it starts, the
    kinematics' compiled loops are made ready and then used for every batch; the drawing is
    the one of the interpreted loops (to the last bits numba's fused multiply-adds change)."""
    from linkwork.kinematics import kernels, warmup
    from linkwork.web.app import compile_kernels
    monkeypatch.setattr(warmup, "READY", warmup.threading.Event())
    body = dict(source={"library": "crank-rocker", "points": {"C": [16.0, 24.0]}}, at=[2.0],
                layers=["mechanism"], motion=False)
    before = TestClient(create_app(None)).post("/api/drawing", json=body).json()
    compile_kernels()
    assert warmup.READY.is_set()
    ran = []  # the requests' loops are the compiled ones, a drawing's single sample too
    real = kernels._compiled
    monkeypatch.setattr(kernels, "_compiled", lambda: ran.append(1) or real())
    # an application not made for serving keeps the loops chosen by batch size, even in a
    # process where another part (a sweep) has loaded the compiled ones
    TestClient(create_app(None)).post("/api/drawing", json=body).json()
    assert not ran
    after = TestClient(create_app(None, compiled=True)).post("/api/drawing", json=body).json()
    assert ran
    for p, xy in before["points"].items():
        assert after["points"][p] == pytest.approx(xy, abs=1e-12)
