"""Alt's dwell linkage (Pöschl §37) and Pröll's substitution (Rosenauer §29), checked with the
engine and with curvature theory computed another way: the dwell link's length against the
circle through three nearby positions of the coupler point; the output rocker at rest (ω, α
zero; with a circling point also the jerk) in the engine's solution of the written six-bar;
the substituted crank's moving pivot has its centre of curvature at the new pivot (osculating
circle of its path, not Euler–Savary), and the new four-bar gives every coupler point the same
centre of curvature as the old one."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.errors import InputError
from linkwork.instant.curvature import curvature_centre, instant
from linkwork.instant.third_order import stationary_curvature
from linkwork.kinematics import solve
from linkwork.synthesis.positions import SynthesisError
from linkwork.synthesis.second_order import alt_dwell, proell_substitution

MECH = linkwork.load("library:crank-rocker")
AT = np.radians(60.0)


def circle_radius(p, q, r):
    a, b, c = np.hypot(*(q - r)), np.hypot(*(p - r)), np.hypot(*(p - q))
    cross = (q - p)[0] * (r - p)[1] - (q - p)[1] * (r - p)[0]
    return a * b * c / (2 * abs(cross))


def test_dwell_link_is_the_radius_of_curvature_and_the_output_rests():
    d = alt_dwell(MECH, AT, "C")
    h = 1e-3
    sol = solve(MECH, [AT - h, AT, AT + h], order=1)
    C = sol.point("C").position
    assert d.radius == pytest.approx(circle_radius(*C), rel=1e-5)
    assert np.allclose(d.coupler_point, C[1], atol=1e-12)
    six = d.mechanism()
    assert len(six.links) == 6
    s = solve(six, [AT], order=3)
    out = s.link(d.output_link)
    w = MECH.drivers[0].law.speed
    assert abs(out.omega[0]) <= 1e-9 * w
    assert abs(out.alpha[0]) <= 1e-7 * w**2
    assert abs(out.jerk[0]) > 1e-6 * w**3  # an ordinary point: a second-order dwell only
    # the six-bar reproduces the four-bar: C moves as before
    s2 = solve(six, [AT - 0.2, AT + 0.3], order=1)
    s1 = solve(MECH, [AT - 0.2, AT + 0.3], order=1)
    assert np.allclose(s2.point("C").position, s1.point("C").position, atol=1e-9)


def test_a_circling_point_gives_a_third_order_dwell():
    sol = solve(MECH, [AT], order=3)
    cubic = stationary_curvature(sol, "coupler")
    pts = cubic.points(181)[0]
    ok = np.isfinite(pts).all(axis=1)
    centre = sol.point("A").position[0]
    pick = pts[ok][np.argmin(np.abs(np.hypot(*(pts[ok] - centre).T) - 20.0))]
    design = sol.local("coupler", pick[None, :])[0]
    d = alt_dwell(MECH, AT, design)
    s = solve(d.mechanism(), [AT], order=3)
    out = s.link(d.output_link)
    w = MECH.drivers[0].law.speed
    assert abs(out.omega[0]) <= 1e-9 * w
    assert abs(out.alpha[0]) <= 1e-7 * w**2
    assert abs(out.jerk[0]) <= 1e-6 * w**3
    # the output angle over ±3°: flatter than the second-order dwell's
    ordinary = alt_dwell(MECH, AT, "C")
    span = AT + np.radians(np.linspace(-3, 3, 7))
    flat = np.ptp(solve(d.mechanism(), span, order=1).link(d.output_link).angle)
    less = np.ptp(solve(ordinary.mechanism(), span, order=1).link(ordinary.output_link).angle)
    assert flat < less


@pytest.mark.parametrize("replace, pivot", [("input", [5.0, -8.0]), ("input", [-6.0, 4.0]),
                                            ("output", [30.0, -10.0])])
def test_proell_substitution_keeps_the_coupler_motion_to_second_order(replace, pivot):
    sub = proell_substitution(MECH, AT, pivot, replace=replace)
    old = solve(MECH, [AT], order=2)
    # the new moving pivot's path in the old four-bar: its osculating circle's centre is the pivot
    a3 = old.local("coupler", sub.moving_pivot[None, :])[0]
    centre = curvature_centre(old, "coupler", a3).centre.xy[0]
    assert np.allclose(centre, pivot, atol=1e-9 * 40)
    new = sub.mechanism()
    s = solve(new, None, order=2)  # at its design position: the input AT
    assert np.allclose(s.point("A").position[0], old.point("A").position[0], atol=1e-9)
    assert np.allclose(instant(s, "coupler").pole.xy, instant(old, "coupler").pole.xy, atol=1e-9)
    for p in ("A", "B", "C"):
        here = new.points[p]  # the file is drawn at AT: design = where the point is there
        want = curvature_centre(old, "coupler", MECH.points[p]).centre.xy[0]
        got = curvature_centre(s, "coupler", here).centre.xy[0]
        assert np.allclose(got, want, atol=1e-8 * 40), p


def test_bad_requests_are_refused():
    with pytest.raises(InputError, match="four-bar"):
        alt_dwell(linkwork.load("library:slider-crank-offset"), 0.3, "B")
    with pytest.raises(InputError, match="not a point of the coupler"):
        alt_dwell(MECH, AT, "O4")
    sol = solve(MECH, [AT], order=2)
    P = instant(sol, "coupler").pole.xy[0]
    with pytest.raises(SynthesisError, match="pole"):
        proell_substitution(MECH, AT, P)
    with pytest.raises(InputError, match="replace"):
        proell_substitution(MECH, AT, [1.0, 2.0], replace="coupler")


def input_jet(sol, pivot, design):
    """The angle of the line pivot → (coupler point `design`) and its first three time
    derivatives in the solution `sol`: Im of log z and its derivatives, z = X − pivot."""
    pm = sol.point_on("coupler", design)
    z0 = complex(*(pm.position[0] - pivot))
    z1, z2, z3 = (complex(*v[0]) for v in (pm.velocity, pm.acceleration, pm.jerk))
    q1 = z1 / z0
    q2 = z2 / z0 - q1**2
    q3 = z3 / z0 - 3 * z2 * z1 / z0**2 + 2 * q1**3
    return np.angle(z0), q1.imag, q2.imag, q3.imag


def coupler_jet(sol, design):
    pm, lm = sol.point_on("coupler", design), sol.link("coupler")
    return (np.concatenate([pm.position[0], pm.velocity[0], pm.acceleration[0], pm.jerk[0]]),
            np.array([lm.omega[0], lm.alpha[0], lm.jerk[0]]))


@pytest.mark.parametrize("replace, pivot", [("input", [5.0, -8.0]), ("input", [-6.0, 4.0]),
                                            ("output", [30.0, -10.0]), ("output", [60.0, 5.0])])
def test_proell_substitution_to_third_order_keeps_the_jerk(replace, pivot):
    """The engine's jets of the coupler (a point's position, velocity, acceleration, jerk and the
    coupler's ω, α, dα/dt) in the old and the new four-bar, the new one driven with the old
    motion of its own input."""
    old = solve(MECH, [AT], order=3)
    w = MECH.drivers[0].law.speed
    jets = {}
    for order in (2, 3):
        sub = proell_substitution(MECH, AT, pivot, replace=replace, order=order)
        assert sub.order == order
        new = sub.mechanism()
        # the pivot stays on its ray from the pole
        P = sub.pole
        u, v = np.subtract(pivot, P), sub.pivot - P
        assert abs(u[0] * v[1] - u[1] * v[0]) <= 1e-9 * np.hypot(*u) * np.hypot(*v)
        if replace == "output":
            s = solve(new, [AT], order=3)
        else:
            a3 = old.local("coupler", sub.moving_pivot[None, :])[0]
            th, w1, w2, w3 = input_jet(old, sub.pivot, a3)
            design = new.driver_input_at_design(new.drivers[0])
            s = solve(new, [design], velocities=[w1], accelerations=[w2], jerks=[w3], order=3)
        jets[order] = [coupler_jet(s, new.points["C"]), coupler_jet(old, MECH.points["C"])]
    (pt3, ln3), (pt_old, ln_old) = jets[3]
    size = 40.0
    scale = np.repeat([size, size * w, size * w**2, size * w**3], 2)
    assert np.allclose(pt3 / scale, pt_old / scale, atol=1e-9)
    assert np.allclose(ln3 / [w, w**2, w**3], ln_old / [w, w**2, w**3], atol=1e-9)
    # second order only: the jerk differs
    (pt2, ln2), _ = jets[2]
    assert np.allclose(pt2[:6] / scale[:6], pt_old[:6] / scale[:6], atol=1e-9)
    assert abs(ln2[2] - ln_old[2]) > 1e-6 * w**3


def test_third_order_substitution_pivot_is_the_centre_of_a_circling_point():
    sub = proell_substitution(MECH, AT, [5.0, -8.0], order=3)
    old = solve(MECH, [AT], order=3)
    a3 = old.local("coupler", sub.moving_pivot[None, :])[0]
    cubic = stationary_curvature(old, "coupler")
    assert abs(cubic.residual(sub.moving_pivot[None, :])[0]) <= 1e-12
    # the circle through five nearby positions of A3 about the pivot: radius constant to h⁴
    h = 1e-2
    X = solve(MECH, AT + h * np.arange(-2, 3), order=1).point_on("coupler", a3).position
    r = np.hypot(*(X - sub.pivot).T)
    r2 = np.hypot(*(solve(MECH, AT + 2 * h * np.arange(-2, 3), order=1).point_on("coupler", a3).position
                    - sub.pivot).T)
    spread, spread2 = np.ptp(r), np.ptp(r2)
    assert spread2 / spread == pytest.approx(16.0, rel=0.15)  # fourth order in h
