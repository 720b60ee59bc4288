"""The drawing of finite-position synthesis (`linkwork.drawing.synthesis_layers`): every drawn
pole, carried to the sheet and back through the figure's own transform, is the pole P_ij to
1e-9 and is a fixed point of the displacement i → j (carried with rotation matrices written out
here); the SVG text places it where the transform says (to the 0.001 mm the text is written
with); the drawn curve points satisfy the cubics, and each drawn centre point has a circle
point whose four homologous points are concyclic (a second test of the curve)."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "synthesis"))
from four_bar_by_hand import O2, O4, generated, move  # noqa: E402

from linkwork.drawing.synthesis_layers import draw_positions, pole_ident  # noqa: E402
from linkwork.synthesis.burmester import (burmester_points, centre_point_curve, circle_point_curve,  # noqa: E402
                                          dyad)
from linkwork.synthesis.positions import Positions  # noqa: E402

POS4 = generated([10, 45, 80, 120])[0]
POS5 = generated([10, 40, 70, 100, 130])[0]
POS3 = Positions.from_poses([[0.0, 0.0, 0.0], [1.0, 0.4, 0.35], [1.8, 1.2, 0.8]])


def _prims(fig, ident_prefix):
    return {p.ident: p for p in fig.prims if p.ident and p.ident.startswith(ident_prefix)}


def _to_paper_and_back(fig, xy):
    t = fig.transforms()["mechanism"]
    (ox, oy), lo, hi, s = t["origin"], t["lo"], t["hi"], t["per_mm"]
    paper = np.array([ox + (xy[0] - lo[0]) / s, oy + (hi[1] - xy[1]) / s])
    back = np.array([lo[0] + (paper[0] - ox) * s, hi[1] - (paper[1] - oy) * s])
    return paper, back


@pytest.mark.parametrize("pos", [POS3, POS4, POS5], ids=["3", "4", "5"])
def test_every_drawn_pole_is_the_pole(pos):
    fig = draw_positions(pos)
    dots = _prims(fig, "pole-P")
    svg = fig.to_svg()
    n = len(pos)
    assert len(dots) == n * (n - 1) // 2
    for i in range(n):
        for j in range(i + 1, n):
            drawn = dots[pole_ident(i, j)].data["xy"]
            paper, back = _to_paper_and_back(fig, drawn)
            P = pos.pole(i, j).xy
            assert np.hypot(*(back - P)) <= 1e-9 * pos.size
            # a fixed point of the displacement i → j, carried by hand
            assert np.hypot(*(move(pos.poses[i], pos.poses[j], back) - back)) <= 1e-9 * pos.size
            m = re.search(rf'<circle id="{pole_ident(i, j)}" cx="([-0-9.]+)" cy="([-0-9.]+)"', svg)
            assert m, pole_ident(i, j)
            assert np.allclose([float(m[1]), float(m[2])], paper, atol=6e-4)
            assert f'id="label-{pole_ident(i, j)}"' in svg or f"P{i + 1}{j + 1}" in svg


def test_pole_triangle_has_the_three_poles_as_corners():
    fig = draw_positions(POS3)
    tri = _prims(fig, "pole-triangle-")["pole-triangle-123"].data["xy"]
    want = [POS3.pole(0, 1).xy, POS3.pole(0, 2).xy, POS3.pole(1, 2).xy]
    assert np.allclose(tri, want, atol=1e-12)


def test_drawn_curves_satisfy_the_cubics():
    fig = draw_positions(POS4)
    curves = _prims(fig, "")
    for ident, cubic in (("centre-point-curve", centre_point_curve(POS4)),
                         ("circle-point-curve", circle_point_curve(POS4))):
        xy = curves[ident].data["xy"]
        xy = xy[np.isfinite(xy).all(1)]
        assert len(xy) > 500
        # relative to the size of the cubic's terms there (it grows as |x|³ far out)
        size = np.abs(cubic.unit).max() * (1 + np.hypot(*((xy - cubic.centre) / cubic.scale).T)) ** 3
        assert (np.abs(cubic(xy)) / size).max() <= 1e-12
    # a second test: centre points picked along the drawn curve have a circle point whose four
    # homologous points (carried by hand) lie on one circle about them
    xy = curves["centre-point-curve"].data["xy"]
    near = xy[np.isfinite(xy).all(1)]
    near = near[np.hypot(*(near - POS4.origin.mean(0)).T) < 3 * POS4.size][::97]
    assert len(near) >= 3
    K = centre_point_curve(POS4)
    for M in near:
        Z = K.mate(M).xy
        D = np.array([move(POS4.poses[0], POS4.poses[k], Z) for k in range(4)])
        r = np.hypot(*(D - M).T)
        assert np.ptp(r) <= 1e-7 * max(r.max(), POS4.size)


def test_dyads_are_marked_with_their_circles():
    fig = draw_positions(POS4, [dyad(POS4, O2), dyad(POS4, O4)])
    p = _prims(fig, "")
    assert np.allclose(p["centre-point-1"].data["xy"], O2, atol=1e-12)
    assert np.allclose(p["centre-point-2"].data["xy"], O4, atol=1e-12)
    c = p["dyad-circle-2"].data
    for Z in p["homologous-2"].data["xy"]:
        assert abs(np.hypot(*(Z - c["centre"])) - c["r"]) <= 1e-9 * POS4.size


def test_five_positions_mark_the_burmester_points():
    bp = burmester_points(POS5)
    fig = draw_positions(POS5, bp.dyads)
    centres = [p.data["xy"] for p in fig.prims if p.ident and p.ident.startswith("centre-point-")]
    assert len(centres) == len(bp.dyads) >= 2
    # the generating four-bar's pivots are among them
    for pivot in (O2, O4):
        assert min(np.hypot(*(c - pivot)) for c in centres) <= 1e-7 * POS5.size
    assert "centre-point-curve" not in {p.ident for p in fig.prims}


def test_a_translation_puts_its_pole_in_the_legend():
    pos = Positions.from_poses([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.5]])
    fig = draw_positions(pos)
    assert pole_ident(0, 1) not in {p.ident for p in fig.prims}
    assert any("P_{12} at infinity" in n for n in fig.legend)
    fig.to_svg()


@pytest.mark.parametrize("degrees, kind", [([10, 45, 80, 120], "4"), ([20, 50, 80, 110, 140], "5")])
def test_synth_poses_draw_writes_the_figure(tmp_path, degrees, kind):
    from typer.testing import CliRunner

    from linkwork.cli import app

    pos = generated(degrees)[0]
    args = [a for x, y, t in pos.poses for a in ("--pose", f"{float(x)!r},{float(y)!r},{float(np.degrees(t))!r}")]
    pivots = ["--centre", "0,0", "--centre", "4,0"] if kind == "4" else []
    svg = tmp_path / "poses.svg"
    r = CliRunner().invoke(app, ["synth", "poses", *args, *pivots, "-o", str(tmp_path / "g.toml"), "--draw", str(svg)])
    assert r.exit_code == 0, r.output
    text = svg.read_text()
    n = len(degrees)
    assert text.count('id="pole-P') == n * (n - 1) // 2
    assert ('id="centre-point-curve"' in text) == (kind == "4")
    assert 'id="centre-point-1"' in text and 'id="centre-point-2"' in text
