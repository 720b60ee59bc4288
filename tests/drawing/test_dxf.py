"""The DXF export, read back with ezdxf (a second reader, not our writer): the path
polylines hold exactly the positions an independent whole-motion solve gives, the links and
hinges sit at the solved positions, and the header names the file's length unit."""

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
