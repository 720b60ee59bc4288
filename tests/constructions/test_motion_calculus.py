"""Pöschl's graphical calculus (ch. II §7, §10, §11): derived scales against the book's numbers,
and the constructions against the exact derivative and integrals of harmonic motion."""

import numpy as np
import pytest

from linkwork.constructions.motion_calculus import (derivative_scale, differentiate, integral_scale,
                                                    integrate, integrate_reciprocal, reciprocal_scale)
from linkwork.errors import InputError

PI = np.pi


def test_scales_of_example_1():
    # Pöschl §11, Example 1: a = 10 cm, ω = π/s, l_x = 2.5 cm/cm, l_b = 5π² cm/s² per cm
    assert integral_scale(1.0, 2.5, 5 * PI ** 2) == pytest.approx(12.5 * PI ** 2)  # l_{v²/2}
    assert integral_scale(2.0, 2.5, 0.1 / PI) == pytest.approx(0.5 / PI)  # l_t, H₂ = 2 cm
    assert reciprocal_scale(2.5, 2.5, 2 * PI) == pytest.approx(0.5 / PI)  # l_t, H′₂ = 2.5 cm


def test_scales_of_example_2():
    # Example 2: H₁ = 3 cm, l_x = 0.2 m/cm, l_b = 10 m/s² per cm → l_{v²/2} = 6; l_t = 0.04 s/cm
    assert integral_scale(3.0, 0.2, 10.0) == pytest.approx(6.0)
    assert integral_scale(4.0, 0.2, 0.05) == pytest.approx(0.04)
    assert reciprocal_scale(5.0, 0.2, 1.0) == pytest.approx(0.04)


def test_derivative_scale_is_eq_3():
    # l_v = l_x/(H₁ l_t); then l_b = l_v/(H₂ l_t) = l_x/(H₁H₂l_t²) (eq. 4)
    l_v = derivative_scale(2.5, 0.1, 2.0)
    assert l_v == pytest.approx(12.5)
    assert derivative_scale(l_v, 0.1, 4.0) == pytest.approx(2.5 / (2.0 * 4.0 * 0.1 ** 2))


def test_chords_of_harmonic_motion():
    # x = a sin ωt: the chord over [t, t+h] has slope aω cos(ω t_mid)·sin(ωh/2)/(ωh/2), exactly
    a, w = 10.0, PI
    t = np.linspace(0.0, 2.0, 41)
    d = differentiate(t, a * np.sin(w * t), l_t=0.1, l_x=2.5, H=2.0)
    h = t[1] - t[0]
    tm = (t[1:] + t[:-1]) / 2
    want = a * w * np.cos(w * tm) * np.sin(w * h / 2) / (w * h / 2)
    np.testing.assert_allclose(d.x, tm, rtol=1e-12)
    np.testing.assert_allclose(d.y, want, rtol=1e-10, atol=1e-10)
    # and drawn: V = H·tan α in cm
    np.testing.assert_allclose(d.Y, want / derivative_scale(2.5, 0.1, 2.0), rtol=1e-10, atol=1e-10)


def test_energy_integral_of_harmonic_motion():
    # b(x) = −ω²x from the left turning point: ∫b dx = v²/2 = ω²(a² − x²)/2, exact at the strip
    # boundaries (mean ordinates of a straight line are exact)
    a, w = 10.0, PI
    x = np.linspace(-a, a, 401)
    strips = np.linspace(-a, a, 9)
    z = integrate(x, -w * w * x, strips, l_x=2.5, l_y=5 * PI ** 2, H=1.0)
    want = w * w * (a * a - strips ** 2) / 2
    np.testing.assert_allclose(z.y, want, rtol=1e-12, atol=1e-9 * a * a * w * w)
    assert z.l_y == pytest.approx(12.5 * PI ** 2)


def test_time_from_the_velocity_line():
    # t = ∫dx/v with v = ω√(a² − x²): ωt = arcsin(x/a) − arcsin(x₀/a), strips away from the turning points
    a, w = 10.0, PI
    x = np.linspace(-9.0, 9.0, 3601)
    v = w * np.sqrt(a * a - x * x)
    strips = np.linspace(-9.0, 9.0, 13)
    t = integrate_reciprocal(x, v, strips, l_x=2.5, l_y=2 * PI, H=2.5, samples=32)
    want = (np.arcsin(strips / a) - np.arcsin(strips[0] / a)) / w
    np.testing.assert_allclose(t.y, want, rtol=2e-4, atol=1e-5)
    assert t.l_y == pytest.approx(0.5 / PI)


def test_bad_input_is_refused():
    x = np.linspace(-1, 1, 11)
    with pytest.raises(InputError, match="turning point"):
        integrate_reciprocal(x, x, [-1, 1], l_x=1, l_y=1, H=1)
    with pytest.raises(InputError, match="must be positive"):
        integrate(x, x, [-1, 1], l_x=1, l_y=1, H=0)
    with pytest.raises(InputError, match="increase"):
        differentiate(x[::-1], x, l_t=1, l_x=1, H=1)
    with pytest.raises(InputError, match="leave the given line"):
        integrate(x, x, [-2, 1], l_x=1, l_y=1, H=1)


# ---------------------------------------------------------------------------- ch. III: plans
from linkwork.constructions.motion_calculus import path_jerk, plan, plan_scale, subnormal  # noqa: E402


def _angle(a, b):
    """Angle between the rows of a and b (radians)."""
    return np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.sum(a * b, 1)))


def test_plan_of_the_crank_pin_is_a_circle():
    # a crank pin r = 0.3 m at ω = 2π/s: v-plan a circle rω about P, its tangent at V is the
    # centripetal acceleration −ω² r (a quarter turn ahead of v), read at |a| = rω²
    r, w = 0.3, 2 * PI
    t = np.linspace(0.0, 1.0, 73)
    v = r * w * np.stack([-np.sin(w * t), np.cos(w * t)], 1)
    p = plan(t, v, scale=plan_scale(v))
    assert p.scale == 0.5  # 1.885 m/s on at most 5 cm: the round scale 0.5 m/s per cm
    np.testing.assert_allclose(np.linalg.norm(p.W, axis=1), r * w / 0.5, rtol=1e-12)
    a = -w * w * r * np.stack([np.cos(w * t), np.sin(w * t)], 1)
    inner = slice(1, -1)
    assert np.max(_angle(p.tangent()[inner], a[inner])) < 1e-12  # a circle's tangent is exact
    np.testing.assert_allclose(p.rate()[inner], a[inner], rtol=0, atol=2e-3 * r * w * w)


MECHANISMS = [("crank-rocker", "C"), ("slider-crank-offset", "B"), ("jansen-linkage", None),
              ("watt-i-six-bar", None), ("double-crank", None)]


@pytest.mark.parametrize("name,point", MECHANISMS)
def test_plans_tangents_are_acceleration_and_jerk(name, point):
    # any point of any mechanism: the v-plan's tangent at V is the engine's acceleration, the
    # b-plan's the engine's jerk; and those are the finite differences of the engine's velocities
    # and accelerations (an independent check of the identity the plan draws)
    import linkwork
    mech = linkwork.load(f"library:{name}")
    point = point or list(mech.points)[-1]
    t = np.linspace(0.0, 0.2, 201)  # a fifth of a turn at the library's speeds, fine steps
    sol = linkwork.solve(mech, times=t, order=3)
    assert np.all(sol.status != 2)
    m = sol.point(point)
    vp = plan(t, m.velocity, scale=plan_scale(m.velocity))
    bp = plan(t, m.acceleration, scale=plan_scale(m.acceleration))
    inner = slice(1, -1)
    big_a = np.linalg.norm(m.acceleration, axis=1) > 1e-3 * np.max(np.linalg.norm(m.acceleration, axis=1))
    big_j = np.linalg.norm(m.jerk, axis=1) > 1e-3 * np.max(np.linalg.norm(m.jerk, axis=1))
    ok_a, ok_j = big_a.copy(), big_j.copy()
    ok_a[[0, -1]] = ok_j[[0, -1]] = False
    assert np.max(_angle(vp.tangent()[ok_a], m.acceleration[ok_a])) < 1e-2
    assert np.max(_angle(bp.tangent()[ok_j], m.jerk[ok_j])) < 1e-2
    amax, jmax = np.max(np.abs(m.acceleration)), np.max(np.abs(m.jerk))
    np.testing.assert_allclose(vp.rate()[inner], m.acceleration[inner], atol=1e-3 * amax)
    np.testing.assert_allclose(bp.rate()[inner], m.jerk[inner], atol=1e-3 * jmax)
    # the engine against finite differences of its own positions (second method: positions only)
    h = 1e-4
    for tk in (0.05, 0.13):
        P = np.array([linkwork.solve(mech, times=[tk + d * h], order=1).point(point).position[0]
                      for d in (-2, -1, 0, 1, 2)])
        fd_a = (P[3] - 2 * P[2] + P[1]) / h ** 2
        fd_j = (P[4] - 2 * P[3] + 2 * P[1] - P[0]) / (2 * h ** 3)
        k = int(round(tk / (t[1] - t[0])))
        np.testing.assert_allclose(m.acceleration[k], fd_a, atol=1e-4 * amax)
        np.testing.assert_allclose(m.jerk[k], fd_j, atol=2e-3 * jmax)


def test_path_jerk_on_a_circle_and_a_line():
    # uniform circular motion: the jerk vector is −ω² v but s''' = 0
    r, w = 2.0, 3.0
    t = np.linspace(0, 1, 11)
    e = np.stack([-np.sin(w * t), np.cos(w * t)], 1)
    pos_v, acc = r * w * e, -r * w * w * np.stack([np.cos(w * t), np.sin(w * t)], 1)
    np.testing.assert_allclose(path_jerk(pos_v, acc, -w * w * pos_v, e), 0.0, atol=1e-12)
    # a spiral-free check: s = t⁴ along a fixed line → s''' = 24 t
    d = np.array([0.6, 0.8])
    tt = np.linspace(0.1, 1, 5)
    got = path_jerk((4 * tt ** 3)[:, None] * d, (12 * tt ** 2)[:, None] * d, (24 * tt)[:, None] * d,
                    np.tile(d, (5, 1)))
    np.testing.assert_allclose(got, 24 * tt, rtol=1e-14)


def test_path_jerk_is_the_third_derivative_of_arc_length():
    # a point on an ellipse x = 3 cos t², y = sin t²: s(t) by quadrature, s''' by differences
    from scipy.integrate import quad
    def r(t, k=0):
        u = t * t
        du = [u, 2 * t, 2.0, 0.0][k] if k else u
        c, s_ = np.cos(u), np.sin(u)
        if k == 0:
            return np.array([3 * c, s_])
        d1 = np.array([-3 * s_, c])
        d2 = np.array([-3 * c, -s_])
        d3 = np.array([3 * s_, -c])
        up, upp = 2 * t, 2.0
        if k == 1:
            return d1 * up
        if k == 2:
            return d2 * up ** 2 + d1 * upp
        return d3 * up ** 3 + 3 * d2 * up * upp
    speed = lambda t: np.linalg.norm(r(t, 1))
    t0 = 0.9
    v, a, j = r(t0, 1), r(t0, 2), r(t0, 3)
    got = path_jerk(v[None], a[None], j[None], (v / np.linalg.norm(v))[None])[0]
    h = 1e-3
    # s''' = d²|v|/dt² by central differences of the speed (the quadrature's constant drops out)
    want = (speed(t0 + h) - 2 * speed(t0) + speed(t0 - h)) / h ** 2
    assert quad(speed, 0, t0)[0] > 0
    assert got == pytest.approx(want, rel=1e-5)


def test_subnormal_of_harmonic_motion():
    # x = a sin ωt: v² = ω²(a² − x²), so v dv/dx = −ω² x, the acceleration (Pöschl eq. 29)
    a, w = 10.0, PI
    x = np.linspace(-9.5, 9.5, 381)
    v = w * np.sqrt(a * a - x * x)
    for k in (40, 190, 300):
        sn = subnormal(x, v, k, l_s=2.5, l_v=2 * PI)
        assert sn.l_a == pytest.approx((2 * PI) ** 2 / 2.5)
        # the tangent through three drawn points is off by O(h²) on the ellipse v–s line
        assert sn.acceleration == pytest.approx(-w * w * x[k], rel=5e-5, abs=1e-9)
    with pytest.raises(InputError, match="inner point"):
        subnormal(x, v, 0, l_s=1, l_v=1)


def test_plan_refuses_gaps():
    with pytest.raises(InputError, match="not all finite"):
        plan(np.arange(3.0), np.array([[0, 1], [np.nan, 1], [1, 1.0]]), scale=1)


# ---------------------------------------------------------------------------- the seeds' examples
def _slider_crank(n: float, r: float = 50.0):
    import linkwork
    from linkwork.io.files import load_text
    L = n * r
    return load_text(f"""
name = "slider-crank l/r = {n}"
units = {{ length = "mm" }}
[points]
O = [0, 0]
A = [0, {r}]
B = [{float(np.sqrt(L * L - r * r))!r}, 0]
[links]
frame = ["O"]
crank = ["O", "A"]
rod = ["A", "B"]
block = ["B"]
[joints]
O = {{ type = "revolute", links = ["frame", "crank"] }}
A = {{ type = "revolute", links = ["crank", "rod"] }}
B = {{ type = "revolute", links = ["rod", "block"] }}
guide = {{ type = "prismatic", links = ["frame", "block"], axis = [1, 0], point = "B" }}
[driver]
joint = "O"
speed = "1 rad/s"
"""), linkwork


def _piston_stroke(mech, linkwork, phi_deg):
    # the outward stroke from the outer dead centre: s = −x grows while the crank turns 0 → 180°
    sol = linkwork.solve(mech, np.radians(phi_deg))
    m = sol.point("B")
    return -m.position[:, 0], -m.velocity[:, 0]


@pytest.mark.parametrize("n,printed", [(2, (67, 42)), (3, (73, 11)), (4, (76, 43)), (5, (79, 7)),
                                       (6, (80, 48)), (7, (82, 2)), (8, (82, 59)), (9, (83, 44)),
                                       (10, (84, 20))])
def test_greatest_piston_speed_where_the_subnormal_vanishes(n, printed):
    # steam-engine text §176 (seed 004): the crank angle of the greatest piston speed (zero piston
    # acceleration) for the rod ratio n = l/r; on the v–s line it is where the subnormal vanishes
    mech, lw = _slider_crank(n)
    phi = np.arange(40.0, 100.0, 0.02)
    s, v = _piston_stroke(mech, lw, phi)
    a = np.array([subnormal(s, v, k, l_s=10.0, l_v=10.0).acceleration for k in range(1, len(s) - 1)])
    j = np.flatnonzero(np.diff(np.sign(a)))[0]
    zero = phi[j + 1] + (phi[j + 2] - phi[j + 1]) * a[j] / (a[j] - a[j + 1])  # a falls through zero
    # the text's cubic in sin²α, sin⁶α − n² sin⁴α − n⁴ sin²α + n⁴ = 0, has one root in (0, 1)
    y = [r.real for r in np.roots([1.0, -n ** 2, -n ** 4, n ** 4]) if abs(r.imag) < 1e-12 and 0 < r.real < 1]
    assert len(y) == 1
    assert zero == pytest.approx(np.degrees(np.arcsin(np.sqrt(y[0]))), abs=0.1 / 60)
    # the table is printed to the arc-minute (within about one minute of the exact root)
    assert abs(zero - (printed[0] + printed[1] / 60)) < 1.1 / 60


def test_piston_acceleration_at_the_dead_centres():
    # seed 004, end of §174: at the dead centres a = 4 r π² n² (1 ± r/l); the library's centric
    # slider-crank has r = 50 mm, l = 200 mm, 120 rpm (n = 2/s): 800 π²·(1 ± 1/4) mm/s²
    import linkwork
    mech = linkwork.load("library:slider-crank-centric")
    want_outer, want_inner = 800 * PI ** 2 * 1.25, 800 * PI ** 2 * 0.75
    for start, want in ((0.0, want_outer), (180.0, want_inner)):
        # the subnormal a little past the dead centre, where v ≠ 0 (at the dead centre the v–s
        # tangent is vertical and the construction fails, as the text says of Mohr's and Proell's)
        phi = start + np.arange(0.2, 0.8, 0.01)
        s, v = _piston_stroke(mech, linkwork, phi)
        if start:  # the return stroke: s = x grows
            s, v = -s, -v
        a = subnormal(s, v, 1, l_s=10.0, l_v=100.0).acceleration
        assert abs(a) == pytest.approx(want, rel=2e-4)


def test_example_2_crank_pin_with_empirical_acceleration():
    # Pöschl §11 Example 2 (steam-engine crank pin): over the periodic path a = 2 m the driving
    # acceleration b(x) is integrated with H₁ = 3 cm at l_x = 0.2 m/cm, l_b = 10 m/s² per cm,
    # so l_{v²/2} = 6; the end ordinate 8.5 cm gives the constant resistance w = 25.5 m/s². The
    # book's b(x) is in its (missing) figure; here a half sine with the same area, ∫b dx = 51 m²/s².
    a_path, l_x, l_b = 2.0, 0.2, 10.0
    c = 51.0 * PI / 4
    x = np.linspace(0.0, a_path, 2001)
    z = integrate(x, c * np.sin(PI * x / a_path), np.linspace(0, a_path, 11), l_x=l_x, l_y=l_b, H=3.0)
    assert z.l_y == pytest.approx(6.0)
    assert z.Y[-1] == pytest.approx(8.5, rel=1e-6)  # the end ordinate B′B of the book
    w = z.l_y * z.Y[-1] / a_path
    assert w == pytest.approx(25.5, rel=1e-6)
    # v² = v₀² + 2∫(b − w)dx with v₀² = 24 m²/s² (the axis shifted 24/12 = 2 cm at l_{v²} = 12)
    assert 24.0 / (2 * z.l_y) == pytest.approx(2.0)
    v = np.sqrt(24.0 + 2 * (c * a_path / PI * (1 - np.cos(PI * x / a_path)) - w * x))
    assert v[0] == pytest.approx(4.9, abs=0.01) and v[-1] == pytest.approx(v[0], rel=1e-6)
    # the time by the integral of the reciprocal, H′₂ = 5 cm, l_v = 1 m/s per cm: l_t = 0.04 s/cm
    t = integrate_reciprocal(x, v, np.linspace(0, a_path, 21), l_x=l_x, l_y=1.0, H=5.0, samples=32)
    assert t.l_y == pytest.approx(0.04)
    from scipy.integrate import quad
    period = quad(lambda xx: 1 / np.sqrt(24.0 + 2 * (c * a_path / PI * (1 - np.cos(PI * xx / a_path))
                                                        - w * xx)), 0, a_path)[0]
    assert t.y[-1] == pytest.approx(period, rel=1e-4)
