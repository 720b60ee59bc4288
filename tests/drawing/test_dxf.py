"""The DXF export, read back with ezdxf (a second reader, not our writer): the path
polylines hold exactly the positions an independent whole-motion solve gives, the links and
hinges sit at the solved positions, the header names the file's length unit; sliding blocks sit
on their pins along their guides, the guides and slots span the strokes the closed forms give,
and every fixed pivot stands on hatched ground."""

from __future__ import annotations

import ezdxf
import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from linkwork.drawing.dxf import finite_runs

runner = CliRunner()


def _paths(doc) -> dict[str, list[np.ndarray]]:
    out: dict[str, list[np.ndarray]] = {}
    for e in doc.modelspace().query("LWPOLYLINE[layer=='PATHS']"):
        name = e.get_xdata("LINKWORK")[0].value.removeprefix("path ")
        out.setdefault(name, []).append(np.array([(x, y) for x, y, *_ in e.get_points()]))
    return out


@pytest.mark.parametrize("name", ["crank-rocker", "slider-crank-centric", "double-rocker"])
def test_paths_are_the_solver_positions(tmp_path, name):
    out = tmp_path / "m.dxf"
    r = runner.invoke(app, ["draw", f"library:{name}", "--show", "mechanism,paths", "-o", str(out)])
    assert r.exit_code == 0, r.output
    doc = ezdxf.readfile(out)
    mech = linkwork.load(f"library:{name}")
    assert doc.header["$INSUNITS"] == {"mm": 4, "m": 6, "in": 1}[mech.length_unit]
    motion = linkwork.whole_motion(mech, order=1)
    paths = _paths(doc)
    moving = [p for p in mech.points if mech.point_owner[p] != mech.frame]
    assert sorted(paths) == sorted(moving)
    for p in moving:
        xy = motion.point(p).position
        ok = np.isfinite(xy).all(axis=1)
        got = np.concatenate(paths[p])
        # every reachable sample once, in order, exactly (a lone reachable sample is no line)
        runs = finite_runs(xy)
        assert len(paths[p]) == len(runs)
        np.testing.assert_array_equal(got, np.concatenate(runs))
        assert len(got) <= ok.sum()


def test_links_and_hinges_at_the_drawn_position(tmp_path):
    out = tmp_path / "m.dxf"
    r = runner.invoke(app, ["draw", "library:crank-rocker", "--at", "40", "-o", str(out)])
    assert r.exit_code == 0, r.output
    mech = linkwork.load("library:crank-rocker")
    sol = linkwork.solve(mech, [np.radians(40.0)])
    doc = ezdxf.readfile(out)
    msp = doc.modelspace()
    hinges = {j.point for j in mech.joints if getattr(j, "point", None)}
    centres = np.array([(c.dxf.center.x, c.dxf.center.y) for c in msp.query("CIRCLE[layer=='JOINTS']")])
    assert len(centres) == len(hinges)
    for p in hinges:
        assert np.min(np.linalg.norm(centres - sol.point(p).position[0], axis=1)) < 1e-9
    vertices = np.array([v[:2] for e in msp.query("LWPOLYLINE[layer=='LINKS']")
                         for v in e.get_points()])
    for link in mech.links:
        if link.name == mech.frame:
            continue
        for p in link.points:
            assert np.min(np.linalg.norm(vertices - sol.point(p).position[0], axis=1)) < 1e-9
    assert not msp.query("LWPOLYLINE[layer=='PATHS']")  # only with --show paths


def test_other_layers_are_refused(tmp_path):
    r = runner.invoke(app, ["draw", "library:crank-rocker", "--show", "poles",
                            "-o", str(tmp_path / "m.dxf")])
    assert r.exit_code != 0 and "DXF" in r.output


def test_cam_profiles_and_roller(tmp_path):
    out = tmp_path / "cam.dxf"
    r = runner.invoke(app, ["draw", "library:radial-roller-cam", "-o", str(out)])
    assert r.exit_code == 0, r.output
    mech = linkwork.load("library:radial-roller-cam")
    cam = next(j for j in mech.joints if j.kind == "cam")
    centre = linkwork.solve(mech).point(cam.point).position[0]
    polys = [np.array([v[:2] for v in e.get_points()])
             for e in ezdxf.readfile(out).modelspace().query("LWPOLYLINE[layer=='PROFILES']")]
    assert len(polys) == 2
    # the roller: a closed circle of the roller's radius about the solved roller centre
    dist = [np.linalg.norm(p - centre, axis=1) for p in polys]
    assert any(np.allclose(d, cam.radius, rtol=0, atol=1e-9) for d in dist)


# ---------------------------------------------------------------------------- symbols
def _doc(tmp_path, name: str, at: str = "40"):
    out = tmp_path / f"{name}.dxf"
    r = runner.invoke(app, ["draw", f"library:{name}", "--at", at, "-o", str(out)])
    assert r.exit_code == 0, r.output
    return ezdxf.readfile(out).modelspace()


def _line_distance(x: np.ndarray, p: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Distance of the points x from the line through p along the unit vector u."""
    d = np.atleast_2d(x) - p
    return np.abs(d[:, 0] * u[1] - d[:, 1] * u[0])


def test_slider_block_on_its_guide_over_the_whole_stroke(tmp_path):
    """Centric slider-crank, crank 50, rod 200 (the file's drawing): the block is a rectangle
    about the solved crosshead pin B, its long side along the guide's axis (x); the guide is a
    line parallel to the axis beside the block, spanning the stroke 200 − 50 … 200 + 50 from
    the crank axis (the dead centres, closed form), hatched on its far side."""
    msp = _doc(tmp_path, "slider-crank-centric")
    mech = linkwork.load("library:slider-crank-centric")
    B = linkwork.solve(mech, [np.radians(40.0)]).point("B").position[0]
    (block,) = msp.query("LWPOLYLINE[layer=='SLIDERS']")
    corners = np.array([v[:2] for v in block.get_points()])
    assert block.closed and len(corners) == 4
    np.testing.assert_allclose(corners.mean(axis=0), B, atol=1e-9)
    sides = np.diff(np.vstack([corners, corners[:1]]), axis=0)
    lengths = np.linalg.norm(sides, axis=1)
    long = sides[np.argmax(lengths)]
    assert abs(long[1]) < 1e-9 * lengths.max()  # along the axis [1, 0]
    assert lengths.max() / lengths.min() == pytest.approx(7 / 4)
    (guide,) = msp.query("LINE[layer=='GUIDES']")
    a, b = np.array(guide.dxf.start)[:2], np.array(guide.dxf.end)[:2]
    assert a[1] == pytest.approx(b[1], abs=1e-9)  # parallel to the axis y = 0
    offset = abs(a[1])
    assert 0 < offset < lengths.min()  # beside the block, not through it
    assert min(a[0], b[0]) < 200 - 50 and max(a[0], b[0]) > 200 + 50
    hatches = [h for h in msp.query("HATCH") if h.dxf.pattern_name == "ANSI31"]
    far = [h for h in hatches
           if all(abs(v[1]) >= offset - 1e-9 for path in h.paths for v in path.vertices)
           and any(abs(v[1]) > offset + 1e-9 for path in h.paths for v in path.vertices)]
    assert far, "the guide's hatching lies beyond its line"


def test_guide_on_a_moving_lever_runs_through_its_pivot(tmp_path):
    """Oscillating crank slotted lever: the block at A slides along the lever, whose line passes
    through the lever's pivot B (the file's construction): the guide line drawn through the
    solved A passes through B."""
    msp = _doc(tmp_path, "oscillating-crank-slotted-lever", "70")
    mech = linkwork.load("library:oscillating-crank-slotted-lever")
    sol = linkwork.solve(mech, [np.radians(70.0)])
    (guide,) = msp.query("LINE[layer=='GUIDES']")
    a, b = np.array(guide.dxf.start)[:2], np.array(guide.dxf.end)[:2]
    u = (b - a) / np.linalg.norm(b - a)
    A, B = sol.point("A").position[0], sol.point("B").position[0]
    assert _line_distance(np.array([A, B]), a, u).max() < 1e-9
    (block,) = msp.query("LWPOLYLINE[layer=='SLIDERS']")
    np.testing.assert_allclose(np.array([v[:2] for v in block.get_points()]).mean(axis=0), A, atol=1e-9)


def test_slot_outline_holds_the_pin_over_its_stroke(tmp_path):
    """PMKS teaching slider-crank: the pin C slides in a slot on the frame along y = 10.01 (the
    line through the crank pivot A). The slot is a closed outline of two straight sides and two
    half circles (bulge 1), centred on that line, the solved pin on its centre line, spanning
    the pin's stroke between the dead centres |AC| = l ± r (closed form from the file)."""
    msp = _doc(tmp_path, "pmks-teaching-slider-crank", "30")
    mech = linkwork.load("library:pmks-teaching-slider-crank")
    A, B, C = (mech.points[p] for p in ("A", "B", "C"))
    r, l = np.linalg.norm(B - A), np.linalg.norm(C - B)
    pin = linkwork.solve(mech, [np.radians(30.0)]).point("C").position[0]
    (slot,) = msp.query("LWPOLYLINE[layer=='GUIDES']")
    pts = np.array(list(slot.get_points("xyb")))
    assert slot.closed and len(pts) == 4
    assert sorted(pts[:, 2]) == [0, 0, 1, 1]  # two half circles
    xy = pts[:, :2]
    d = np.abs(xy[:, 1] - A[1])  # the sides at half the slot's width either side of y = A.y
    assert d[0] > 0 and np.allclose(d, d[0], rtol=0, atol=1e-9)
    assert pin[1] == pytest.approx(A[1], abs=1e-9)
    assert xy[:, 0].min() < A[0] - (l + r) and xy[:, 0].max() > A[0] - (l - r)
    assert xy[:, 0].min() < pin[0] < xy[:, 0].max()


def test_every_fixed_pivot_stands_on_hatched_ground(tmp_path):
    """Crank-rocker: each of the frame's two hinges (O2, O4) has a bearing block whose narrow
    end holds the hinge, a ground line below it, and an ANSI31 hatch (45°) under that line."""
    msp = _doc(tmp_path, "crank-rocker")
    mech = linkwork.load("library:crank-rocker")
    pivots = [mech.points[j.point] for j in mech.joints
              if type(j).__name__ == "Revolute" and mech.frame in j.links]
    bearings = [np.array([v[:2] for v in e.get_points()]) for e in msp.query("LWPOLYLINE[layer=='FRAME']")]
    grounds = [(np.array(e.dxf.start)[:2], np.array(e.dxf.end)[:2]) for e in msp.query("LINE[layer=='FRAME']")]
    hatches = list(msp.query("HATCH[layer=='HATCHING']"))
    assert len(bearings) == len(grounds) == len(hatches) == len(pivots) == 2
    for O in pivots:
        (tri,) = [t for t in bearings if np.linalg.norm(t.mean(axis=0) - O) < np.ptp(t, axis=0).max()]
        top = tri[np.argsort(-tri[:, 1])[:2]]
        np.testing.assert_allclose(top.mean(axis=0), O + [0, top[0, 1] - O[1]], atol=1e-9)
        assert top[0, 1] < O[1]  # just below the hinge's centre
        (g0, g1), = [g for g in grounds if abs(g[0][0] + g[1][0] - 2 * O[0]) < 1e-9]
        assert g0[1] == pytest.approx(g1[1]) and g0[1] < tri[:, 1].min() + 1e-9
        (h,) = [h for h in hatches if abs(np.mean([v[0] for p in h.paths for v in p.vertices]) - O[0]) < 1e-6]
        assert h.dxf.pattern_name == "ANSI31" and h.pattern.lines[0].angle == pytest.approx(45)
        assert max(v[1] for p in h.paths for v in p.vertices) <= g0[1] + 1e-9
