"""The slider-crank against its closed forms and the piston table of seed 004.

Seed digest 004 (German steam-engine text, §174–§176): the piston acceleration at the dead
centres is 4 r π² n² (1 ± r/l) (n in rev/s), and the crank angle of maximum piston velocity,
for rod ratios l/r = 2 … 10, is tabulated to the arc-minute together with the angle at which the
rod is perpendicular to the crank. Linkwork's velocities are maximised numerically here; the
cubic sin⁶α − n² sin⁴α − n⁴ sin²α + n⁴ = 0 of §176 is the second method.

Both ways of modelling the piston are checked: a block with a prismatic pair (RRP dyad) and the
rod's end as a pin in a slot of the frame (one-link group).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

import linkwork
from mechanism_texts import slider_crank_text

ARCMIN = np.radians(1 / 60)


def slider_crank(r: float, l: float, e: float = 0.0, *, kind: str = "block", rpm: float = 300.0):
    """Crank O (pivot) – A, rod A – B, piston B on the line y = e; drawn at the crank angle 0, so
    the input is the crank angle from the x-axis (the outer dead centre when e = 0)."""
    xb = r + np.sqrt(l * l - e * e)
    text = slider_crank_text(name=f"slider-crank r={r} l={l} e={e}", A=(float(r), 0),
                             B=(float(xb), float(e)), slot=kind == "slot", speed=f"{rpm} rpm",
                             units="mm")
    return linkwork.load_text(text)


def piston(mech, theta, order=2):
    sol = linkwork.solve(mech, np.atleast_1d(theta), order=order)
    return sol.point("B")


KINDS = ["block", "slot"]


# ---------------------------------------------------------------------------- closed form x(θ)
def closed_form(r, l, e, theta, w):
    """Piston position, velocity and acceleration along the line of stroke, ω constant."""
    g, g1, g2 = r * np.sin(theta) - e, r * np.cos(theta), -r * np.sin(theta)
    S = np.sqrt(l * l - g * g)
    S1 = -g * g1 / S
    S2 = -(g1 * g1 + g * g2) / S - (g * g1) ** 2 / S ** 3
    x = r * np.cos(theta) + S
    x1 = -r * np.sin(theta) + S1
    x2 = -r * np.cos(theta) + S2
    return x, w * x1, w * w * x2


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("r,l,e", [(50.0, 200.0, 0.0), (50.0, 200.0, 20.0), (30.0, 75.0, -12.5),
                                   (10.0, 21.0, 9.0)])
def test_piston_motion_equals_closed_form(kind, r, l, e):
    m = slider_crank(r, l, e, kind=kind)
    w = m.drivers[0].law.speed
    theta = np.linspace(0.0, 2 * np.pi, 73)
    p = piston(m, theta)
    x, v, a = closed_form(r, l, e, theta, w)
    np.testing.assert_allclose(p.position[:, 0], x, rtol=0, atol=1e-10 * l)
    np.testing.assert_allclose(p.position[:, 1], e, rtol=0, atol=1e-10 * l)
    np.testing.assert_allclose(p.velocity[:, 0], v, rtol=0, atol=1e-10 * l * w)
    np.testing.assert_allclose(p.velocity[:, 1], 0.0, atol=1e-10 * l * w)
    np.testing.assert_allclose(p.acceleration[:, 0], a, rtol=0, atol=1e-9 * l * w * w)


# ---------------------------------------------------------------------------- dead centres
@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("ratio", [2.0, 3.5, 4.0, 6.0])
def test_dead_centre_accelerations(kind, ratio):
    """Seed 004, end of §174: v²/r ± v²/l = 4 r π² n² (1 ± r/l), larger at the outer dead
    centre (crank pointing at the piston), both directed towards the crank at the outer and away
    from it at the inner dead centre."""
    r, rpm = 50.0, 300.0
    l = ratio * r
    n = rpm / 60.0  # revolutions per second
    m = slider_crank(r, l, kind=kind, rpm=rpm)
    p = piston(m, [0.0, np.pi])
    outer, inner = p.acceleration[:, 0]
    np.testing.assert_allclose(outer, -4 * r * np.pi ** 2 * n ** 2 * (1 + r / l), rtol=1e-12)
    np.testing.assert_allclose(inner, +4 * r * np.pi ** 2 * n ** 2 * (1 - r / l), rtol=1e-12)
    np.testing.assert_allclose(p.velocity[:, 0], 0.0, atol=1e-12 * r * 2 * np.pi * n)


# ---------------------------------------------------------------------------- §176 table
# rod ratio n: (crank angle of maximum piston velocity, crank angle where rod ⟂ crank), (deg, min)
TABLE = {2: ((67, 42), (63, 26)), 3: ((73, 11), (71, 34)), 4: ((76, 43), (75, 58)),
         5: ((79, 7), (78, 41)), 6: ((80, 48), (80, 32)), 7: ((82, 2), (81, 52)),
         8: ((82, 59), (82, 52)), 9: ((83, 44), (83, 40)), 10: ((84, 20), (84, 17))}


def _dm(dm):
    return np.radians(dm[0] + dm[1] / 60)


def _max_velocity_angle(n: int, kind: str = "block") -> float:
    """Crank angle from the outer dead centre at which linkwork's piston speed is largest."""
    m = slider_crank(1.0, float(n), kind=kind)
    res = minimize_scalar(lambda t: piston(m, t, order=1).velocity[0, 0],  # v < 0 on (0, π)
                          bounds=(0.1, np.pi - 0.1), method="bounded",
                          options={"xatol": 1e-10})
    assert res.success
    return float(res.x)


_SEED_ROUNDING = pytest.mark.xfail(
    strict=True, reason="seed 004 prints 80° 48' for n = 6; the exact angle is 80° 46.97' "
    "(the cubic of §176 gives the same), so the table is 1.03' off")


@pytest.mark.parametrize("n", [pytest.param(n, marks=_SEED_ROUNDING) if n == 6 else n
                               for n in sorted(TABLE)])
def test_crank_angle_of_maximum_piston_velocity_matches_table(n):
    assert abs(_max_velocity_angle(n) - _dm(TABLE[n][0])) <= ARCMIN


def test_table_entry_for_rod_ratio_6_is_off_by_just_over_one_arcminute():
    assert abs(_max_velocity_angle(6) - _dm(TABLE[6][0])) <= 1.1 * ARCMIN


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("n", sorted(TABLE))
def test_zero_piston_acceleration_solves_the_cubic(n, kind):
    """Second method (§176): at the maximum piston velocity the acceleration vanishes and
    s = sin²α is a root of s³ − n² s² − n⁴ s + n⁴ = 0 in (0, 1)."""
    m = slider_crank(1.0, float(n), kind=kind)
    alpha = brentq(lambda t: piston(m, t).acceleration[0, 0], 0.5, np.pi / 2, xtol=1e-14)
    roots = np.roots([1.0, -n ** 2, -n ** 4, n ** 4])
    s = [z.real for z in roots if abs(z.imag) < 1e-12 and 0 < z.real < 1]
    assert len(s) == 1
    assert alpha == pytest.approx(np.arcsin(np.sqrt(s[0])), abs=1e-10)
    assert _max_velocity_angle(n, kind) == pytest.approx(alpha, abs=1e-6)


@pytest.mark.parametrize("n", sorted(TABLE))
def test_crank_angle_where_rod_is_perpendicular_to_crank(n):
    """Third column of the table, from linkwork's positions: OA · AB = 0."""
    m = slider_crank(1.0, float(n))

    def dot(t):
        sol = linkwork.solve(m, [t], order=1)
        a, b = sol.point("A").position[0], sol.point("B").position[0]
        return float(a @ (b - a))

    alpha = brentq(dot, 0.5, np.pi / 2, xtol=1e-14)
    assert abs(alpha - _dm(TABLE[n][1])) <= ARCMIN
    assert alpha == pytest.approx(np.arctan(n), abs=1e-10)


# ---------------------------------------------------------------------------- offset stroke
@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("r,l,e", [(50.0, 200.0, 20.0), (30.0, 75.0, -12.5), (10.0, 21.0, 9.0),
                                   (40.0, 100.0, 55.0)])
def test_offset_stroke(kind, r, l, e):
    """Stroke √((l+r)² − e²) − √((l−r)² − e²): the piston's extremes, found where linkwork's
    piston velocity vanishes."""
    m = slider_crank(r, l, e, kind=kind)
    grid = np.linspace(0.0, 2 * np.pi, 73)
    v = piston(m, grid, order=1).velocity[:, 0]
    turns = np.flatnonzero(np.sign(v[:-1]) != np.sign(v[1:]))
    ends = [brentq(lambda t: piston(m, t, order=1).velocity[0, 0], grid[k], grid[k + 1], xtol=1e-14)
            for k in turns]
    assert len(ends) == 2
    x = piston(m, ends, order=1).position[:, 0]
    stroke = np.sqrt((l + r) ** 2 - e * e) - np.sqrt((l - r) ** 2 - e * e)
    assert abs(x[0] - x[1]) == pytest.approx(stroke, rel=1e-12)


def test_library_slider_cranks_strokes():
    for name in ("slider-crank-centric", "slider-crank-offset"):
        m = linkwork.load(f"library:{name}")
        P = m.points
        r = np.hypot(*(P["A"] - P["O"]))
        l = np.hypot(*(P["B"] - P["A"]))
        e = P["B"][1] - P["O"][1]
        u = np.linspace(0.0, 2 * np.pi, 7201)
        x = linkwork.solve(m, u, order=1).point("B").position[:, 0]
        stroke = np.sqrt((l + r) ** 2 - e * e) - np.sqrt((l - r) ** 2 - e * e)
        assert np.ptp(x) == pytest.approx(stroke, rel=1e-6), name
