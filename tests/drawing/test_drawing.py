"""SVG output is valid XML and holds the labelled objects; scales; layers; label placement;
PNG/PDF from the same SVG; the CLI commands draw and plot."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from linkwork.constructions import CONSTRUCTIONS, construct
from linkwork.drawing import LAYERS, Scale, Scales, nice_ceil, scene_at, scene_figure
from linkwork.drawing.svg import label_markup, text_width

NS = {"s": "http://www.w3.org/2000/svg"}
runner = CliRunner()


def parse(svg: str) -> ET.Element:
    return ET.fromstring(svg.encode("utf-8"))


def texts(root: ET.Element) -> list[str]:
    return ["".join(t.itertext()).replace("\u200a", "") for t in root.iter("{http://www.w3.org/2000/svg}text")]


# ---------------------------------------------------------------------------- scales
@pytest.mark.parametrize("x,want", [(0.3, 0.5), (1.0, 1.0), (1.01, 2.0), (2.2, 2.5), (3, 5), (7, 10),
                                    (0.0021, 0.0025), (180, 200)])
def test_nice_ceil(x, want):
    assert nice_ceil(x) == pytest.approx(want)


def test_scale_text_and_factors():
    s = Scales(Scale("length", "mm", 2.0), Scale("velocity", "mm/s", 50.0), Scale("acceleration", "mm/s\u00b2", 500.0))
    assert s.kv == pytest.approx(2.0 / 50.0)  # mm of mechanism per mm/s
    assert s.ka == pytest.approx(2.0 / 500.0)
    assert s.velocity.text() == "M_v: 1 mm \u2259 50 mm/s"
    r = Scales.rosenauer(Scale("length", "mm", 1.0), omega=4.0)
    assert r.kv == pytest.approx(0.25) and r.ka == pytest.approx(1 / 16)
    with pytest.raises(linkwork.LinkworkError):
        Scale("length", "mm", -1.0)


def test_auto_scales_fit_the_sheet():
    mech = linkwork.load("library:crank-rocker")
    sc = scene_at(mech, np.radians(30))
    s = sc.auto_scales()
    assert sc.extent() / s.length.per_mm <= 0.62 * 277 + 1e-9
    assert s.velocity is not None and s.acceleration is not None


# ---------------------------------------------------------------------------- SVG
def test_label_markup_subscripts():
    assert label_markup("W_0", 3.0).startswith("W<tspan")
    assert ">0</tspan>" in label_markup("W_0", 3.0)
    assert ">13</tspan>" in label_markup("P_{13}", 3.0)
    m = label_markup("M_l: 1 mm", 3.0)
    assert ">l</tspan>" in m and m.endswith(": 1 mm</tspan>")
    assert text_width("P_13", 3.0) < text_width("P13x", 3.0)


@pytest.mark.parametrize("mech_name", ["crank-rocker", "slider-crank-offset", "pmks-teaching-slider-crank",
                                       "watt-i-six-bar", "whitworth-quick-return", "roemer-mechanism"])
def test_every_layer_gives_valid_svg(mech_name):
    mech = linkwork.load(f"library:{mech_name}")
    value = mech.driver_input_at_design(mech.drivers[0]) + 0.4
    sc = scene_at(mech, value)
    layers = [x for x in LAYERS if x != "construction"]
    root = parse(scene_figure(sc, layers).to_svg())
    ids = {e.get("id") for e in root.iter() if e.get("id")}
    assert "layer-mechanism" in ids and "labels" in ids and "legend" in ids
    for p in mech.points:
        assert f"label-point-{p}" in ids
    # every link with two distinct points is drawn as a bar or a plate
    for ln in mech.moving_links:
        xy = np.array([mech.points[p] for p in mech.link(ln).points])
        if len(xy) > 1 and np.ptp(xy, axis=0).max() > 0:
            assert f"link-{ln}" in ids


def test_svg_contains_the_labelled_construction_objects():
    mech = linkwork.load("library:crank-rocker")
    sol = linkwork.solve(mech, np.radians([230.0]))
    con = construct("bobillier", mech, sol)
    root = parse(scene_figure(linkwork.drawing.Scene(mech, sol), ["mechanism"], construction=con).to_svg())
    t = " ".join(texts(root))
    for lab in ("P", "Q", "W0", "inflection circle", "O2", "O4", "A", "B"):
        assert lab in t
    ids = {e.get("id") for e in root.iter() if e.get("id")}
    assert {"el-P", "el-Q", "el-W0", "el-wendekreis", "el-axis"} <= ids
    # lines by role: results heavier than auxiliary lines
    w = {e.get("id"): float(e.get("stroke-width", "0")) for e in root.iter() if e.get("id", "").startswith("el-")}
    assert w["el-axis"] > w["el-lAB"]


@pytest.mark.parametrize("name", list(CONSTRUCTIONS))
def test_each_construction_draws(name):
    # each construction on a mechanism it applies to (slide pairs need a slide between moving
    # links, the rolling lever its valve gear)
    lib = {"klein": "slider-crank-offset", "slide-pairs": "rotating-crank-slotted-lever",
           "rolling-lever": "rolling-lever-valve-gear"}.get(name, "crank-rocker")
    mech = linkwork.load(f"library:{lib}")
    sol = linkwork.solve(mech, np.radians([230.0]))
    con = construct(name, mech, sol)
    con.check()
    fig = scene_figure(linkwork.drawing.Scene(mech, sol), ["mechanism"], construction=con)
    root = parse(fig.to_svg())
    assert root.find(".//s:g[@id='layer-construction']", NS) is not None
    # one step drawing per step, each valid, later steps draw more
    sizes = []
    for k in range(len(con.steps)):
        f = scene_figure(linkwork.drawing.Scene(mech, sol), ["mechanism"], construction=con, step=k)
        svg = f.to_svg()
        parse(svg)
        assert con.steps[k].text.split()[0] in svg
        sizes.append(svg.count("<g id=\"el-"))
    assert sizes == sorted(sizes)


def test_animated_svg():
    mech = linkwork.load("library:slider-crank-centric")
    sol = linkwork.solve(mech, np.radians([40.0]))
    con = construct("klein", mech, sol)
    svg = scene_figure(linkwork.drawing.Scene(mech, sol), ["mechanism"], construction=con).to_svg(animate=1.5)
    root = parse(svg)
    sets = root.findall(".//s:set", NS)
    assert len(sets) >= len(con.steps)
    assert {float(s.get("begin")[:-1]) for s in sets} >= {1.5 * k for k in range(len(con.steps))}


def test_labels_do_not_overlap():
    mech = linkwork.load("library:crank-rocker")
    sc = scene_at(mech, np.radians(230))
    root = parse(scene_figure(sc, ["mechanism", "velocities", "accelerations", "poles"]).to_svg())
    boxes = []
    for g in root.find(".//s:g[@id='labels']", NS):
        r = g.find("s:rect", NS)
        x, y, w, h = (float(r.get(k)) for k in ("x", "y", "width", "height"))
        boxes.append((x, y, x + w, y + h))
    overlap = 0.0
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            a, b = boxes[i], boxes[j]
            dx = min(a[2], b[2]) - max(a[0], b[0])
            dy = min(a[3], b[3]) - max(a[1], b[1])
            if dx > 0 and dy > 0:
                overlap += dx * dy
    total = sum((b[2] - b[0]) * (b[3] - b[1]) for b in boxes)
    assert overlap <= 0.02 * total


def test_png_and_pdf_from_the_same_svg(tmp_path):
    mech = linkwork.load("library:crank-rocker")
    fig = scene_figure(scene_at(mech, np.radians(30)), ["mechanism", "velocities"])
    png, pdf, svg = (fig.save(tmp_path / f"a.{s}") for s in ("png", "pdf", "svg"))
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert pdf.read_bytes()[:5] == b"%PDF-"
    parse(svg.read_text())
    with pytest.raises(linkwork.LinkworkError, match="svg, .png and .pdf"):
        fig.save(tmp_path / "a.jpg")


def test_unknown_layer():
    mech = linkwork.load("library:crank-rocker")
    with pytest.raises(linkwork.LinkworkError, match="unknown layer"):
        scene_figure(scene_at(mech, 0.3), ["mechanism", "wendekreis"])


# ---------------------------------------------------------------------------- CLI
def test_cli_draw_construction_steps(tmp_path):
    out = tmp_path / "klein.svg"
    r = runner.invoke(app, ["draw", "library:slider-crank-centric", "--at", "40", "--construction", "klein",
                            "--steps", "-o", str(out)])
    assert r.exit_code == 0, r.output
    files = sorted(tmp_path.glob("klein-*.svg"))
    assert len(files) == 7
    for f in files:
        parse(f.read_text())
    assert "a_A" in r.output and "relative error" in r.output


def test_cli_draw_layers_png(tmp_path):
    out = tmp_path / "m.png"
    r = runner.invoke(app, ["draw", "library:crank-rocker", "--at", "230", "--show",
                            "mechanism,paths,velocities,inflection,gamma", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert out.read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("args,msg", [
    (["library:parallelogram", "--at", "30", "--construction", "euler-savary"], "infinity"),
    (["library:crank-rocker", "--construction", "klein"], "not a slider-crank"),
    (["library:crank-rocker", "--show", "nope"], "unknown layer"),
    (["library:crank-rocker", "--construction", "rittershaus"], "unknown construction"),
    (["library:crank-rocker", "--steps"], "need a --construction"),
])
def test_cli_draw_clear_errors(tmp_path, args, msg):
    r = runner.invoke(app, ["draw", *args, "-o", str(tmp_path / "x.svg")])
    assert r.exit_code == 2
    assert msg in r.output


def test_cli_plot(tmp_path):
    r = runner.invoke(app, ["plot", "library:slider-crank-centric", "--point", "B", "--quantity",
                            "acceleration", "-o", str(tmp_path / "a.png")])
    assert r.exit_code == 0, r.output
    r = runner.invoke(app, ["plot", "library:slider-crank-centric", "--point", "B", "--vs",
                            "-o", str(tmp_path / "vs.pdf")])
    assert r.exit_code == 0, r.output
    r = runner.invoke(app, ["plot", "library:crank-rocker", "--link", "rocker", "--quantity", "velocity",
                            "--against", "time", "-o", str(tmp_path / "w.svg")])
    assert r.exit_code == 0, r.output
    r = runner.invoke(app, ["plot", "library:crank-rocker", "--point", "Z", "-o", str(tmp_path / "z.png")])
    assert r.exit_code == 2 and "no point 'Z'" in r.output
