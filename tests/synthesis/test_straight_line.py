"""Straight-line linkages, checked independently of the designs:

* the Ball point by the engine's sampled path: curvature from finite differences of positions
  (the osculating circle's radius is infinite) and its derivative vanish there, to the order
  the differencing allows, while they do not at an ordinary coupler point;
* Chebyshev's proportions against the classical 4 : 5 : 2 (Rosenauer §36, the library file);
* Watt's deviation against the closed form x = y⁵/(4cr³) (series derived by hand in the
  module docstring and checked here by its convergence order);
* Evans's tracer through its three exact places (start, middle, end: the trammel positions)
  solved by the engine at inputs computed here from the trammel geometry;
* Hart's line straight to 1e-9 over the whole motion, at right angles to the frame, and its
  points against the library's hand-made Hart file;
* the straightness metric against closed forms (a circular arc: its sagitta's half; points on
  a line: 0).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork
from linkwork.errors import InputError
from linkwork.kinematics import solve
from linkwork.synthesis._file import mechanism_file
from linkwork.synthesis.positions import SynthesisError
from linkwork.synthesis.straight_line import (ball_point_linkage, chebyshev_linkage, evans_linkage,
                                              hart_straight_line, path_straightness, straightness,
                                              watt_linkage)

MECH = linkwork.load("library:crank-rocker")


def curvature_and_slope(mech, point, at, h):
    """κ and dκ/ds of the path of `point` at input `at` by central differences of the engine's
    positions (steps h in the input)."""
    u = at + h * np.arange(-3, 4)
    X = solve(mech, u, order=1).point(point).position

    def kappa(i):  # at sample i, from its neighbours
        d1 = (X[i + 1] - X[i - 1]) / (2 * h)
        d2 = (X[i + 1] - 2 * X[i] + X[i - 1]) / h**2
        return (d1[0] * d2[1] - d1[1] * d2[0]) / np.hypot(*d1) ** 3, np.hypot(*d1)

    k = [kappa(i) for i in (2, 3, 4)]
    return k[1][0], (k[2][0] - k[0][0]) / (2 * h) / k[1][1]


@pytest.mark.parametrize("deg", [60.0, 150.0, 250.0])
def test_ball_point_path_is_straight_to_third_order(deg):
    at = math.radians(deg)
    des = ball_point_linkage(MECH, at)
    mech = des.mechanism()
    assert len(mech.links) == 4
    U = np.asarray(des.points[des.tracer])
    size = 40.0
    h = 2e-3
    k, dk = curvature_and_slope(mech, des.tracer, at, h)
    k_c, dk_c = curvature_and_slope(mech, "C", at, h)
    # an ordinary coupler point: curvature of order 1/size; at U both vanish to the error of
    # the differences (relative h² ≈ 4e-6, amplified by the differencing of rounding)
    assert abs(k_c) > 1e-2 / size
    assert abs(k) < 1e-6 * abs(k_c) * max(1.0, np.hypot(*U) / size) ** 2 + 1e-7 / size
    assert abs(dk) < 1e-3 * abs(dk_c) + 1e-5 / size**2
    # the deviation from the tangent grows with the 4th power of the run along it (an
    # ordinary point: the 2nd, an inflection: the 3rd)
    u = at + np.array([0.005, 0.01])
    s0 = solve(mech, [at], order=1)
    X0, v = s0.point(des.tracer).position[0], s0.point(des.tracer).velocity[0]
    t = v / np.hypot(*v)
    X = solve(mech, u, order=1).point(des.tracer).position
    along, off = (X - X0) @ t, (X - X0) @ np.array([-t[1], t[0]])
    order = math.log(off[1] / off[0]) / math.log(along[1] / along[0])
    assert order == pytest.approx(4.0, abs=0.15)


def test_chebyshev_proportions_are_the_classical_ones():
    des = chebyshev_linkage(80.0)
    L = des.lengths
    assert L["frame"] / L["coupler"] == pytest.approx(2.0, rel=1e-12)
    assert L["rocker"] / L["coupler"] == pytest.approx(2.5, rel=1e-12)
    lib = linkwork.load("library:chebyshev-straight-line")
    for name in ("O2", "O4", "A", "B"):
        assert np.allclose(des.points[{"P": "M"}.get(name, name)], lib.points[name], atol=1e-9)
    # the tracer meets its height at both stroke ends (a rocker vertical), solved by the engine
    mech = des.mechanism()
    ends = solve(mech, [math.pi / 2, math.atan2(80.0, 60.0) - (math.atan2(80, 60) - math.atan2(60, 80))],
                 order=1).point("M").position
    assert np.allclose(ends[:, 1], 80.0, atol=1e-9)
    assert sorted(ends[:, 0]) == pytest.approx([0.0, 80.0], abs=1e-9)
    assert des.straightness.stroke == pytest.approx(80.0, rel=1e-6)
    assert 0 < des.straightness.deviation < 0.002 * 80


def test_chebyshev_from_the_deviation_allowed():
    des = chebyshev_linkage(deviation=0.05)
    assert des.straightness.deviation == pytest.approx(0.05, rel=1e-6)
    L = des.lengths
    assert (L["frame"], L["rocker"]) == pytest.approx((2 * L["coupler"], 2.5 * L["coupler"]), rel=1e-12)
    with pytest.raises(InputError, match="stroke or the deviation"):
        chebyshev_linkage(10.0, deviation=0.1)


def watt_closed_form(stroke, r, c):
    """Minimax deviation of x = k y⁵ over |y| ≤ h: the line x = m y with the error equal and
    opposite at y = h and at the interior extremum y₁ = t h, 4t⁵ + 5t⁴ = 1 (solved here by
    bisection), E = 4 k (t h)⁵."""
    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if 4 * mid**5 + 5 * mid**4 < 1 else (lo, mid)
    t, h, k = lo, stroke / 2, 1 / (4 * c * r**3)
    return 4 * k * (t * h) ** 5


def test_watt_deviation_against_the_closed_form():
    r, c = 50.0, 20.0
    errs = []
    for s in (5.0, 2.5):
        des = watt_linkage(s, arm=r, coupler=c)
        got = des.straightness.deviation
        want = watt_closed_form(s, r, c)
        errs.append(abs(got / want - 1))
    assert errs[0] < 5e-3
    assert errs[1] < errs[0] / 3  # the series' next term: (s/r)²
    # Pöschl's eq. 103 in the drawn middle position
    mech = des.mechanism()
    frame = np.hypot(*np.subtract(mech.points["Cb"], mech.points["Ca"]))
    assert r**2 + (c / 2) ** 2 == pytest.approx((frame / 2) ** 2, rel=1e-12)


@pytest.mark.parametrize("solve_for", ["coupler", "arm"])
def test_watt_from_stroke_and_deviation(solve_for):
    kw = {"arm": 50.0} if solve_for == "coupler" else {"coupler": 30.0}
    des = watt_linkage(20.0, deviation=1e-3, **kw)
    assert des.straightness.deviation <= 1e-3
    assert des.straightness.deviation == pytest.approx(1e-3, rel=1e-6)
    # independent of the design's own measurement: a fresh engine path of the written file
    again = path_straightness(des.mechanism(), "Q", stroke=20.0, samples=4001)
    assert again.deviation == pytest.approx(1e-3, rel=1e-5)


@pytest.mark.parametrize("fraction", [0.7, 1.3, -0.4])
def test_evans_tracer_passes_its_three_trammel_places(fraction):
    s, a = 100.0, math.radians(40.0)
    des = evans_linkage(s, angle=a, fraction=fraction)
    mech = des.mechanism()
    L = s / (2 * math.sin(a))
    D = np.asarray(mech.points["D"])
    # the rocker D–C at the start: C on the bar from A = (−L cos a, 0) to B = (0, L sin a)
    A0, B0 = np.array([-L * math.cos(a), 0.0]), np.array([0.0, L * math.sin(a)])
    C0 = A0 + fraction * (B0 - A0)
    C1 = np.array([C0[0], -C0[1]])  # the end: the mirror image in line AO
    Cm = np.asarray(mech.points["C"])
    ang = [math.atan2(*(p - D)[::-1]) for p in (C0, Cm, C1)]
    design = mech.driver_input_at_design(mech.drivers[0])
    ang = [design + (x - ang[1]) for x in ang]
    B = solve(mech, ang, order=1).point("B").position
    assert np.allclose(B, [[0, s / 2], [0, 0], [0, -s / 2]], atol=1e-9 * s)
    assert des.straightness.stroke == pytest.approx(s, rel=1e-3)  # along the best line


def test_evans_matches_the_library_file():
    lib = linkwork.load("library:evans-straight-line")
    des = evans_linkage(2 * 100 * math.sin(math.radians(45)), fraction=0.7, lever=400.0)
    # the library draws the start position; the design the middle one: same fixed pivots
    assert np.allclose(des.points["D"], lib.points["D"], atol=1e-9)
    assert np.allclose(des.points["E"], lib.points["E"], atol=1e-9)


def test_evans_lever_from_the_deviation_allowed():
    des = evans_linkage(100.0, fraction=0.8, deviation=0.1)
    assert des.straightness.deviation == pytest.approx(0.1, rel=1e-6)
    # a fresh engine path of the written file
    again = path_straightness(des.mechanism(), "B", stroke=100.0 * (1 - 1e-9), samples=4001)
    assert again.deviation == pytest.approx(0.1, rel=1e-5)
    with pytest.raises(SynthesisError, match="even a lever"):
        evans_linkage(100.0, fraction=0.8, deviation=0.01)


def four_bar(points, name="four-bar"):
    return linkwork.io.load_text(mechanism_file(
        name=name, description="", length_unit="mm", points=points,
        links={"frame": ["O1", "O2"], "crank_a": ["O1", "A"], "coupler": ["A", "B"], "crank_b": ["O2", "B"]},
        joints={"O1": ("revolute", ("frame", "crank_a"), ""), "A": ("revolute", ("crank_a", "coupler"), ""),
                "B": ("revolute", ("coupler", "crank_b"), ""), "O2": ("revolute", ("crank_b", "frame"), "")},
        driver="O1", speed="1 rad/s"), source=name)


def test_hart_line_is_straight_and_matches_the_library():
    lib = linkwork.load("library:hart-straight-line")
    fb = four_bar({k: lib.points[k] for k in ("O1", "O2", "A", "B")})
    des = hart_straight_line(fb)
    for k in ("C", "D", "Q"):
        assert np.allclose(des.points[k], lib.points[k], atol=1e-7), k
    st = des.straightness
    assert st.deviation <= 1e-9 * st.stroke
    assert abs(st.direction @ np.array([1.0, 0.0])) <= 1e-9  # ⟂ O1O2


@pytest.mark.parametrize("deg", [30.0, 100.0, 200.0])
def test_hart_line_from_the_crank_rocker(deg):
    des = hart_straight_line(MECH, math.radians(deg))
    mech = des.mechanism()
    assert len(mech.links) == 6
    st = des.straightness
    assert st.stroke > 1.0
    assert st.deviation <= 1e-9 * st.stroke
    assert abs(st.direction @ np.array([1.0, 0.0])) <= 1e-9
    # C and D at one fraction of the cranks (Pöschl §66c, the digest's check)
    assert des.lengths["C_fraction"] == pytest.approx(des.lengths["D_fraction"], rel=1e-9)


def test_straightness_closed_forms():
    R, half = 10.0, 0.5
    phi = np.linspace(-half, half, 20001)
    arc = R * np.column_stack([np.sin(phi), np.cos(phi)])
    st = straightness(arc)
    sagitta = R * (1 - math.cos(half))
    assert st.deviation == pytest.approx(sagitta / 2, rel=1e-6)
    assert st.stroke == pytest.approx(2 * R * math.sin(half), rel=1e-12)
    line = np.column_stack([np.linspace(0, 3, 7), 2 * np.linspace(0, 3, 7) + 1])
    assert straightness(line).deviation <= 1e-15 * 7
    with pytest.raises(InputError):
        straightness(np.zeros((3, 2)))
    with pytest.raises(InputError):
        straightness([[1.0, 2.0]])


def test_watt_from_stroke_and_overall_size():
    des = watt_linkage(20.0, frame=130.0, coupler=50.0)
    assert des.lengths["arm"] == pytest.approx(60.0, rel=1e-12)  # 4·60² + 50² = 130²
    mech = des.mechanism()
    assert np.hypot(*np.subtract(mech.points["Cb"], mech.points["Ca"])) == pytest.approx(130.0, rel=1e-12)
    assert des.straightness.deviation == pytest.approx(watt_closed_form(20.0, 60.0, 50.0), rel=0.05)


def test_bad_requests_are_refused():
    with pytest.raises(InputError, match="two of"):
        watt_linkage(10.0, arm=5.0)
    with pytest.raises(InputError, match="two of"):
        watt_linkage(10.0, frame=50.0, deviation=0.1)
    with pytest.raises(InputError, match="farther apart"):
        watt_linkage(10.0, frame=50.0, arm=30.0)
    with pytest.raises(InputError, match="positive"):
        chebyshev_linkage(-1.0)
    with pytest.raises(InputError, match="midpoint"):
        evans_linkage(10.0, fraction=0.5)
    with pytest.raises(SynthesisError, match="stroke is too long"):
        path_straightness(MECH, "C", stroke=1000.0)
    with pytest.raises(InputError, match="no point"):
        path_straightness(MECH, "Z", stroke=1.0)
