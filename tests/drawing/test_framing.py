"""Framing (``--frame``): with ``mechanism`` the mechanism stays the subject, layers larger than
the sheet are cut at a frame around it, with arrows to centres off the sheet; with ``all``
everything drawn fits. Every curve of the instantaneous geometry has its own style and a label."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from linkwork.drawing import scene_at, scene_figure
from linkwork.errors import InputError
from linkwork.instant import return_circle

SVG = "{http://www.w3.org/2000/svg}"
ALL = ["mechanism", "poles", "pole-lines", "centrodes", "inflection", "return", "bresse", "gamma"]


def figure(frame):
    mech = linkwork.load("library:crank-rocker")
    sc = scene_at(mech, np.radians(30))
    fig = scene_figure(sc, ALL, frame=frame)
    return mech, sc, fig, ET.fromstring(fig.to_svg().encode())


def to_paper(fig, xy):
    tf = fig.transforms()["mechanism"]
    return np.array([tf["origin"][0] + (xy[0] - tf["lo"][0]) / tf["per_mm"],
                     tf["origin"][1] + (tf["hi"][1] - xy[1]) / tf["per_mm"]])


def test_frame_mechanism_keeps_labels_and_points_inside_the_frame():
    mech, sc, fig, root = figure("mechanism")
    r = root.find(f".//{SVG}g[@id='frame-mechanism']/{SVG}rect")
    x0, y0 = float(r.get("x")), float(r.get("y"))
    x1, y1 = x0 + float(r.get("width")), y0 + float(r.get("height"))
    for p in mech.points:
        q = to_paper(fig, sc.pos(p))
        assert x0 < q[0] < x1 and y0 < q[1] < y1
    for g in root.find(f".//{SVG}g[@id='labels']"):
        b = g.find(f"{SVG}rect")
        bx, by = float(b.get("x")), float(b.get("y"))
        assert x0 - 1e-6 <= bx and bx + float(b.get("width")) <= x1 + 1e-6
        assert y0 - 1e-6 <= by and by + float(b.get("height")) <= y1 + 1e-6


def test_arrow_points_to_the_return_circle_centre_off_the_sheet():
    mech, sc, fig, root = figure("mechanism")
    c = return_circle(sc.sol, "coupler")[0]
    centre = c.centre.xy
    lo, hi = fig.clip["mechanism"]
    assert not np.all((centre >= lo) & (centre <= hi))  # this position's return circle is large
    colour = "#b36b00"
    arrows = list(root.find(f".//{SVG}g[@id='layer-return']").iter(f"{SVG}line"))
    assert len(arrows) == 1
    ln = arrows[0]
    a = np.array([float(ln.get("x1")), float(ln.get("y1"))])
    b = np.array([float(ln.get("x2")), float(ln.get("y2"))])
    want = to_paper(fig, centre) - b
    assert ln.get("stroke") == colour
    cosine = np.dot(b - a, want) / (np.linalg.norm(b - a) * np.linalg.norm(want))
    assert cosine > 1 - 1e-6
    text = " ".join("".join(t.itertext()) for t in root.iter(f"{SVG}text"))
    assert "centre of the return circle (coupler)" in text


def test_each_curve_has_its_own_style_and_a_label():
    mech, sc, fig, root = figure("mechanism")
    ret = root.find(f".//{SVG}*[@id='return-circle']")
    mov = root.find(f".//{SVG}*[@id='centrode-moving-coupler']")
    fix = root.find(f".//{SVG}*[@id='centrode-fixed-coupler']")
    styles = {(e.get("stroke"), e.get("stroke-dasharray")) for e in (ret, mov, fix)}
    assert len(styles) == 3
    assert ret.get("stroke-dasharray") != mov.get("stroke-dasharray")
    labels = {"".join(t.itertext()) for t in root.find(f".//{SVG}g[@id='labels']").iter(f"{SVG}text")}
    for want in ("return circle (coupler)", "inflection circle (coupler)", "Bresse circle (coupler)",
                 "fixed centrode (coupler)", "moving centrode (coupler)"):
        assert want in labels


def test_frame_all_fits_every_circle_on_the_sheet():
    mech, sc, fig, root = figure("all")
    assert root.find(f".//{SVG}g[@id='frame-mechanism']") is None
    w, h = (float(v) for v in root.get("viewBox").split()[2:])
    c = return_circle(sc.sol, "coupler")[0]
    q = to_paper(fig, c.centre.xy)
    r = float(c.radius) / fig.transforms()["mechanism"]["per_mm"]
    assert q[0] - r >= 0 and q[0] + r <= w and q[1] - r >= 0 and q[1] + r <= h


def test_unknown_frame_is_refused(tmp_path):
    mech = linkwork.load("library:crank-rocker")
    with pytest.raises(InputError, match="unknown frame"):
        scene_figure(scene_at(mech, 0.5), ["mechanism"], frame="sheet")
    r = CliRunner().invoke(app, ["draw", "library:crank-rocker", "--frame", "all", "--show",
                                 "mechanism,return", "-o", str(tmp_path / "x.svg")])
    assert r.exit_code == 0, r.output


def test_step_frames_are_the_same_size():
    from linkwork.constructions import construct
    mech = linkwork.load("library:crank-rocker")
    sc = scene_at(mech, np.radians(230))
    con = construct("acceleration-plan", mech, sc.sol)
    seen = set()
    for k in range(len(con.steps)):
        fig = scene_figure(sc, ["mechanism"], construction=con, step=k)
        root = ET.fromstring(fig.to_svg().encode())
        tf = fig.transforms()
        seen.add((root.get("viewBox"),) + tuple((n, tuple(np.round(t["origin"], 6)), tuple(np.round(t["lo"], 9)),
                                                  tuple(np.round(t["hi"], 9))) for n, t in sorted(tf.items())))
    assert len(seen) == 1


def _segments(root, layer):
    out = []
    for el in root.find(f".//{SVG}g[@id='layer-{layer}']").iter():
        if el.tag == f"{SVG}line":
            out.append(np.array([[float(el.get("x1")), float(el.get("y1"))], [float(el.get("x2")), float(el.get("y2"))]]))
        elif el.tag == f"{SVG}path":
            nums = [float(v) for v in el.get("d").replace("M", " ").replace("L", " ").split()]
            out.append(np.array(nums).reshape(-1, 2))
    return out


def test_pole_lines_reach_their_poles_and_do_not_double_a_bar():
    from linkwork.instant import pole_schedule, poles
    mech = linkwork.load("library:crank-rocker")
    sc = scene_at(mech, np.radians(30))
    fig = scene_figure(sc, ["mechanism", "poles", "pole-lines"], frame="all")
    root = ET.fromstring(fig.to_svg().encode())
    segs = _segments(root, "pole-lines")
    ps = poles(sc.sol)

    def dist(q, seg):
        a, b = seg[0], seg[-1]
        t = np.clip(np.dot(q - a, b - a) / np.dot(b - a, b - a), 0, 1)
        return np.linalg.norm(a + t * (b - a) - q)
    # every derived pole (Aronhold–Kennedy) lies on a drawn line
    for st in pole_schedule(mech).derived:
        P = ps[st.pair][0]
        if P.is_finite:
            q = to_paper(fig, P.xy)
            assert min(dist(q, s) for s in segs) < 0.05
    # no pole line runs along the inside of a binary link's bar
    for ln in mech.moving_links:
        pts = mech.link(ln).points
        if len(pts) != 2:
            continue
        a, b = (to_paper(fig, sc.pos(p)) for p in pts)
        for f in (0.25, 0.5, 0.75):
            q = a + f * (b - a)
            assert min(dist(q, s) for s in segs) > 0.05


def test_inset_draws_the_cut_layers_whole_at_their_own_scale():
    mech, sc, fig, root = figure("inset")
    assert set(fig.spaces) == {"mechanism", "inset"}
    main, inset = fig.spaces["mechanism"], fig.spaces["inset"]
    assert inset.per_mm > main.per_mm and inset.unit == main.unit
    # the mechanism panel is cut at its frame, as with --frame mechanism ...
    assert root.find(f".//{SVG}g[@id='frame-mechanism']") is not None
    # ... but no arrows there: the centres off the sheet are drawn (and labelled) in the inset
    assert not list(root.find(f".//{SVG}g[@id='layer-return']").iter(f"{SVG}line"))
    tf = fig.transforms()["inset"]
    lo, hi = np.array(tf["lo"]), np.array(tf["hi"])
    c = return_circle(sc.sol, "coupler")[0]
    for q in (c.centre.xy + c.radius * np.array([1, 0]), c.centre.xy - c.radius * np.array([0, 1])):
        assert np.all(q >= lo - 1e-9) and np.all(q <= hi + 1e-9)  # the return circle whole
    clo, chi = fig.clip["mechanism"]
    assert np.all(clo >= lo) and np.all(chi <= hi)  # and the frame, marked in it
    assert root.find(f".//{SVG}*[@id='inset-frame']") is not None
    text = " ".join("".join(t.itertext()) for t in root.iter(f"{SVG}text"))
    assert "centre of the return circle (coupler)" in text and "M_l (inset)" not in text
    assert "(inset): 1 mm" in text  # its scale bar in the legend


def test_no_inset_when_nothing_runs_past_the_frame():
    mech = linkwork.load("library:crank-rocker")
    fig = scene_figure(scene_at(mech, np.radians(30)), ["mechanism", "poles"], frame="inset")
    assert set(fig.spaces) == {"mechanism"}
    assert "inset" not in fig.to_svg()


def test_cli_frame_inset(tmp_path):
    out = tmp_path / "i.svg"
    r = CliRunner().invoke(app, ["draw", "library:crank-rocker", "--at", "30", "--show", ",".join(ALL),
                                 "--frame", "inset", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert 'id="inset-frame"' in out.read_text()
    r = CliRunner().invoke(app, ["draw", "library:crank-rocker", "--frame", "corner", "-o", str(out)])
    assert r.exit_code != 0 and "inset" in r.output
