"""Curvature theory checked against independent sources: osculating circles fitted to densely
sampled positions, the core engine's accelerations (and, for relative motion, the engine's
absolute motions combined by the Coriolis theorem), the seeds' closed forms and the digests'
worked numbers."""

import numpy as np
import pytest

import linkwork
from linkwork.geometry import Line, Point, intersect
from linkwork.instant import (acceleration_pole, bobillier_pole_tangent, bresse_circle,
                              collineation_axis, conjugate, curvature_centre, envelope,
                              euler_savary, inflection_circle, instant, kennedy_poles,
                              line_envelope, path, poles, return_circle)

import instant_mechanisms as im
from instant_mechanisms import cross, osculating_centre, perp, relative_kinematics


def _on_circle(circle, k=12):
    """(k, N, 2) points spread over each circle of the batch (lines: points along them)."""
    c, r = circle.centre.xy, circle.radius
    ang = np.linspace(0.1, 2 * np.pi, k, endpoint=False)
    return np.stack([c + r[:, None] * np.c_[np.cos(a) * np.ones_like(r), np.sin(a) * np.ones_like(r)]
                     for a in ang])


def _f1():
    # Rosenauer digest 001c, fixture F1: 14 = (0,0), 34 = (4,0), 1.5 / 3.5 / 3.0, θ = 1 rad
    text, pts = im.four_bar(4.0, 1.5, 3.5, 3.0, 1.0, point=(1.0, 1.2))
    return linkwork.load_text(text), pts


# ---------------------------------------------------------------------------- Euler–Savary
@pytest.mark.parametrize("rel", [None, "rocker", "crank"])
def test_path_curvature_centres_equal_osculating_circles(rel):
    mech, _ = _f1()
    u = np.radians([57.3, 80.0, 140.0, 250.0])
    sol = linkwork.solve(mech, u, order=2)
    frame = rel or "frame"

    def positions(x):
        s = linkwork.solve(mech, x, order=1)
        return s.local(frame, s.point("C").position)

    ref = osculating_centre(positions, u, 2e-3)
    got = path(sol, "coupler", "C", rel)
    assert np.allclose(got.position, positions(u), atol=1e-12)
    scale = got.radius
    assert np.all(np.linalg.norm(got.centre.xy - ref, axis=1) < 1e-6 * np.maximum(scale, 1))
    # drawn in the frame at each sample: the same centres mapped by the reference link's pose
    cc = curvature_centre(sol, "coupler", "C", rel)
    back = sol.local(frame, cc.centre.xy)
    assert np.allclose(back, got.centre.xy, atol=1e-9)


def test_f1_numbers():
    # digest 001c F1 (Bobillier construction and finite differences, computed independently)
    mech, pts = _f1()
    sol = linkwork.solve(mech, [1.0], velocities=[1.0], order=2)
    ic = inflection_circle(sol, "coupler")
    assert np.allclose(ic.centre.xy[0], [-13.517234, 2.229332], atol=2e-6)
    assert np.isclose(2 * ic.radius[0], 35.182799, atol=2e-6)
    P = instant(sol, "coupler").pole
    for joint, W in (("A", [-9.576861, -14.915078]), ("B", [3.979654, 0.408275])):
        ray = Line.through(P, Point.from_xy(sol.point(joint).position))
        pair = intersect(ic, ray)
        cand = np.stack([pair.plus.xy[0], pair.minus.xy[0]])
        far = cand[np.argmax(np.linalg.norm(cand - P.xy[0], axis=1))]
        assert np.allclose(far, W, atol=2e-6)
    assert np.allclose(curvature_centre(sol, "coupler", "C").centre.xy[0], [0.652070, 2.309340], atol=2e-6)
    assert np.isclose(sol.link("coupler").omega[0], -0.279327, atol=1e-6)
    assert np.isclose(sol.link("rocker").omega[0], 0.259600, atol=1e-6)


def test_euler_savary_agrees_with_velocity_acceleration_curvature():
    rng = np.random.default_rng(3)
    mech, _ = _f1()
    sol = linkwork.solve(mech, np.radians([30.0, 75.0, 160.0]), order=2)
    for rel, link in ((None, "coupler"), ("crank", "coupler"), ("coupler", "rocker")):
        ins = instant(sol, link, rel)
        for _ in range(5):
            s = rng.uniform(-6, 6, 2)
            cc = curvature_centre(sol, link, s, rel)
            es = euler_savary(ins.pole, ins.inflection_pole, Point.from_xy(cc.position))
            d = np.linalg.norm(es.xy - cc.centre.xy, axis=1)
            assert np.all(d < 1e-8 * np.maximum(1, cc.radius)), (rel, link, d)


# ---------------------------------------------------------------------------- circles
@pytest.mark.parametrize("link,rel", [("coupler", None), ("rocker", "crank"), ("crank", "rocker"),
                                      ("frame", "coupler")])
def test_circles_by_engine_accelerations(link, rel):
    # (pairs joined by a hinge turn about it: their circles shrink to the hinge, see
    # test_rotation_about_a_hinge)
    mech, _ = _f1()
    u = np.radians([20.0, 75.0, 200.0])
    sol = linkwork.solve(mech, u, velocities=np.array([1.0, -2.0, 1.5]),
                         accelerations=np.array([0.3, 0.0, -4.0]), order=2)
    frame = rel or "frame"
    # inflection circle: zero normal acceleration
    for xy in _on_circle(inflection_circle(sol, link, rel)):
        v, a = relative_kinematics(sol, link, frame, xy)
        an = cross(v, a) / np.linalg.norm(v, axis=1)
        assert np.all(np.abs(an) < 1e-9 * (np.linalg.norm(a, axis=1) + 1)), an
    # Bresse circle: zero tangential acceleration
    for xy in _on_circle(bresse_circle(sol, link, rel)):
        v, a = relative_kinematics(sol, link, frame, xy)
        at = (v * a).sum(1) / np.linalg.norm(v, axis=1)
        assert np.all(np.abs(at) < 1e-9 * (np.linalg.norm(a, axis=1) + 1)), at
    # acceleration pole: zero acceleration
    G = acceleration_pole(sol, link, rel).xy
    v, a = relative_kinematics(sol, link, frame, G)
    ref = np.abs(relative_kinematics(sol, link, frame, G + 1.0)[1]).max()
    assert np.all(np.linalg.norm(a, axis=1) < 1e-10 * ref)


def test_return_circle_is_the_mirror_image_in_the_pole_tangent():
    mech, _ = _f1()
    sol = linkwork.solve(mech, np.radians([20.0, 75.0, 200.0]), order=2)
    for link, rel in (("coupler", None), ("crank", "rocker")):
        ins = instant(sol, link, rel)
        ic, rc = inflection_circle(sol, link, rel), return_circle(sol, link, rel)
        P = ins.pole.xy
        assert np.allclose(rc.radius, ic.radius)
        assert np.allclose(rc.centre.xy, 2 * P - ic.centre.xy, atol=1e-9)
        # the inflection circle's centre lies on the pole normal, at D/2 towards W
        assert np.allclose(ic.centre.xy, P + 0.5 * ins.diameter[:, None] * ins.pole_normal.xy, atol=1e-9)
        assert np.allclose((ins.pole_tangent.xy * ins.pole_normal.xy).sum(1), 0, atol=1e-12)


def test_pole_agrees_with_poles_and_pole_velocity_with_differences():
    mech, _ = _f1()
    u = np.radians([30.0, 100.0])
    sol = linkwork.solve(mech, u, order=2)
    P = poles(sol)
    for link, rel in (("coupler", "frame"), ("rocker", "crank"), ("crank", "coupler")):
        ins = instant(sol, link, rel)
        assert np.allclose(ins.pole.xy, P[link, rel].xy, atol=1e-9)
        if rel != "frame":
            continue
        h = 1e-5
        Pp = poles(linkwork.solve(mech, u + h, order=1))[link, rel].xy
        Pm = poles(linkwork.solve(mech, u - h, order=1))[link, rel].xy
        assert np.allclose(ins.pole_velocity.xy, (Pp - Pm) / (2 * h), rtol=1e-6, atol=1e-6)
        # the point of the link at the pole has the acceleration b_Ω
        pm = sol.point_on(link, sol.local(link, ins.pole.xy))
        assert np.allclose(pm.acceleration, ins.pole_acceleration.xy, atol=1e-9)


# ---------------------------------------------------------------------------- seed closed forms
def test_slider_crank_inflection_pole_on_the_line_of_stroke():
    # Rosenauer §26 (after Grübler): W₀ lies on the slider's line; digest 001a E.2 numbers
    sol = linkwork.solve(linkwork.load_text(im.slider_crank(1.0, 3.0, 0.0, np.radians(60))),
                         np.radians([60.0]), order=2)
    ins = instant(sol, "rod")
    assert np.allclose(ins.pole.xy[0], [3.37228, 5.84096], atol=1e-5)
    assert np.allclose(ins.inflection_pole.xy[0], [-64.0, 0.0], atol=1e-6)
    assert np.isclose(ins.diameter[0], 67.625, atol=1e-3)
    sol = linkwork.solve(linkwork.load_text(im.slider_crank(1.0, 3.5, 0.4, np.radians(50))),
                         np.radians([50.0]), order=2)
    ins = instant(sol, "rod")
    assert np.allclose(ins.pole.xy[0], [4.12359, 4.91431], atol=1e-5)
    assert np.allclose(ins.inflection_pole.xy[0], [-44.5412, 0.4], atol=1e-4)
    assert np.isclose(ins.diameter[0], 48.8737, atol=1e-4)
    rng = np.random.default_rng(2)
    for slot in (False, True):
        for _ in range(6):
            e = rng.uniform(-1, 1)
            mech = linkwork.load_text(im.slider_crank(1.0, rng.uniform(3, 6), e, 0.3, slot=slot))
            sol = linkwork.solve(mech, rng.uniform(0, 2 * np.pi, 5), order=2)
            W = instant(sol, "rod").inflection_pole.xy
            assert np.allclose(W[:, 1], e, atol=1e-9)
            # Aronhold II: the pin on the straight guide lies on the inflection circle
            assert inflection_circle(sol, "rod").contains(Point.from_xy(sol.point("B").position)).all()


@pytest.mark.parametrize("slot", [False, True])
def test_swinging_block_radius_is_half_the_pole_distance(slot):
    # Pöschl §24d, eq. (69): the rod point at the pivot B moves on a path of radius ΩB/2,
    # centre at the midpoint of ΩB
    mech = linkwork.load_text(im.swinging_block(1.0, (4.0, 0.5), 0.8, slot=slot))
    sol = linkwork.solve(mech, np.radians([10.0, 45.8, 120.0, 250.0]), order=2)
    B = np.array([4.0, 0.5])
    on_rod = sol.local("rod", np.broadcast_to(B, (len(sol), 2)))
    cc = curvature_centre(sol, "rod", on_rod)
    Om = instant(sol, "rod").pole.xy
    assert np.allclose(cc.radius, np.linalg.norm(Om - B, axis=1) / 2, rtol=1e-9)
    assert np.allclose(cc.centre.xy, (Om + B) / 2, atol=1e-9)
    # Aronhold I: the fixed point through which the rod slides lies on the return circle, it is
    # the conjugate of the rod's normal direction, and the rod line's envelope is that point
    assert return_circle(sol, "rod").contains(Point.from_xy(np.broadcast_to(B, (len(sol), 2)))).all()
    u = (B - mech.points["A"]) / np.linalg.norm(B - mech.points["A"])
    assert np.allclose(conjugate(sol, "rod", perp(u)).xy, B, atol=1e-9)
    env = line_envelope(sol, "rod", "A", u)
    assert np.allclose(env.centre.xy, B, atol=1e-9)
    assert np.allclose(env.contact[:, 0], B, atol=1e-9)
    assert np.allclose(env.radius, 0, atol=1e-9)


def test_rolling_disc():
    # Rosenauer §43 Ex. 11: D equals the disc's radius and W₀ is the disc's centre; the cycloid
    # point A has its centre of curvature at the reflection of A in the pole (ρ = 2·PA)
    r = 1.5
    mech = linkwork.load_text(im.rolling_wheel(r))
    x = np.array([-1.0, 0.3, 2.0, 4.1])
    sol = linkwork.solve(mech, x, velocities=np.array([1.0, -2.0, 0.5, 3.0]),
                         accelerations=np.array([0.0, 1.0, -2.0, 0.7]), order=2)
    ins = instant(sol, "wheel")
    centre = sol.point("O").position
    assert np.allclose(centre, np.c_[x, np.full(4, r)])
    assert np.allclose(ins.diameter, r)
    assert np.allclose(ins.inflection_pole.xy, centre, atol=1e-12)
    ic = inflection_circle(sol, "wheel")
    assert np.allclose(ic.radius, r / 2) and np.allclose(ic.centre.xy, centre - (0, r / 2))
    A = sol.point("A").position
    P = ins.pole.xy
    assert np.allclose(P, np.c_[x, np.zeros(4)], atol=1e-12)
    assert np.allclose(curvature_centre(sol, "wheel", "A").centre.xy, 2 * P - A, atol=1e-9)


def test_acceleration_pole_canonical_numbers():
    # digest 001b §4: rolling with D = 2, ω = 1.3, τ = 0.7 (CCW) puts Γ at (−0.707092, 1.707122)
    # in the frame with P at the origin, y along the pole normal (towards W₀); Pöschl eq. (85)
    mech = linkwork.load_text(im.rolling_wheel(2.0))
    k = linkwork.solve(mech, [0.0], velocities=[1.0], accelerations=[0.0]).link("wheel").omega[0]
    sol = linkwork.solve(mech, [0.0], velocities=[1.3 / k], accelerations=[0.7 / k], order=2)
    ins = instant(sol, "wheel")
    assert np.isclose(ins.omega[0], 1.3) and np.isclose(ins.alpha[0], 0.7)
    n = ins.pole_normal.xy[0]
    x_axis = np.array([n[1], -n[0]])
    G = ins.acceleration_pole.xy[0] - ins.pole.xy[0]
    assert np.allclose([G @ x_axis, G @ n], [-0.707092, 1.707122], atol=1e-6)
    H = ins.tangential_pole.xy[0] - ins.pole.xy[0]
    assert np.allclose([H @ x_axis, H @ n], [-4.828571, 0.0], atol=1e-6)  # B₀ = (−Dω²/τ, 0)


def test_ellipsograph_curvature_numbers():
    # digest 001b §4: AB = 1, φ = 60°, D one quarter from A: P = (0.5, 0.866025),
    # W_d = (0.321429, −0.061859), C_d = (0.083333, −1.299038); and W₀ = O, D = AB
    mech = linkwork.load_text(im.ellipsograph(1.0, np.radians(60)))
    sol = linkwork.solve(mech, order=2)
    ins = instant(sol, "rod")
    assert np.allclose(ins.pole.xy[0], [0.5, 0.866025], atol=1e-6)
    assert np.allclose(ins.inflection_pole.xy[0], [0, 0], atol=1e-12)
    assert np.isclose(ins.diameter[0], 1.0)
    assert np.allclose(curvature_centre(sol, "rod", "D").centre.xy[0], [0.083333, -1.299038], atol=1e-6)
    ic = inflection_circle(sol, "rod")
    D = Point.from_xy(sol.point("D").position)
    pair = intersect(ic, Line.through(ins.pole, D))
    cand = np.stack([pair.plus.xy[0], pair.minus.xy[0]])
    Wd = cand[np.argmax(np.linalg.norm(cand - ins.pole.xy[0], axis=1))]
    assert np.allclose(Wd, [0.321429, -0.061859], atol=1e-6)
    # the inflection circle is the moving centrode (Cardan circle about the rod's midpoint)
    assert np.allclose(ic.centre.xy[0], sol.point("M").position[0]) and np.isclose(ic.radius[0], 0.5)


# ---------------------------------------------------------------------------- Bobillier
def test_bobillier_and_the_collineation_axis():
    mech, _ = _f1()
    sol = linkwork.solve(mech, np.radians([20.0, 57.3, 140.0, 260.0]), order=2)
    ins = instant(sol, "coupler")
    t = ins.pole_tangent.xy
    for a, b in (("A", "B"), ("C", "A"), ("B", "C")):
        tb = bobillier_pole_tangent(sol, "coupler", a, b).xy
        assert np.allclose(np.abs(cross(tb, t)), 0, atol=1e-9), (a, b)
    # Rosenauer §75: the collineation point of the rays through the crank pins is the
    # relative pole of crank and rocker (line AB meets the line of the fixed pivots there)
    col = collineation_axis(sol, "coupler", "A", "B")
    K = kennedy_poles(sol)
    assert np.allclose(col.q.xy, K["crank", "rocker"].xy, atol=1e-9)
    assert col.axis.contains(ins.pole).all()


def test_envelope_of_a_carried_circle():
    # the envelope of a circle carried by the coupler is a parallel curve of its centre's path;
    # its centre of curvature is the centre's conjugate (Rosenauer §15, Pöschl §38)
    mech, _ = _f1()
    u = np.radians([40.0, 150.0])
    sol = linkwork.solve(mech, u, order=2)
    rho = 0.4
    env = envelope(sol, "coupler", "C", rho)
    for k, sign in ((0, -1.0), (1, 1.0)):
        def positions(x, sign=sign):
            s = linkwork.solve(mech, x, order=1)
            pm = s.point("C")
            nrm = perp(pm.velocity) / np.linalg.norm(pm.velocity, axis=1)[:, None]
            P = poles(s)["frame", "coupler"].xy
            side = np.sign(((pm.position - P) * nrm).sum(1))[:, None]
            return pm.position + sign * rho * side * nrm
        assert np.allclose(env.contact[:, k], positions(u), atol=1e-9)
        ref = osculating_centre(positions, u, 2e-3)
        assert np.allclose(env.centre.xy, ref, atol=1e-6)
        assert np.allclose(env.radius[:, k], np.linalg.norm(positions(u) - ref, axis=1), atol=1e-6)


# ---------------------------------------------------------------------------- degenerate
def test_parallelogram_translation():
    mech = linkwork.load_text(im.parallelogram(0.7))
    sol = linkwork.solve(mech, np.radians([20.0, 100.0]), order=2)
    ins = instant(sol, "coupler")
    assert ins.translating.all() and ins.pole.is_infinite.all() and np.isinf(ins.diameter).all()
    # every coupler point moves on a circle of the crank's radius
    cc = curvature_centre(sol, "coupler", "B")
    assert np.allclose(cc.radius, 3.0)
    assert np.allclose(cc.centre.xy, sol.point("B").position - sol.point("A").position, atol=1e-12)


def test_instantaneous_translation_with_angular_acceleration():
    # a four-bar coupler at the instant its ω passes through zero: the pole is at infinity and
    # the inflection "circle" is a straight line whose points have zero normal acceleration
    mech, _ = _f1()
    w = lambda x: linkwork.solve(mech, np.atleast_1d(x), order=1).link("coupler").omega
    grid = np.radians(np.linspace(0, 359, 360))
    s = np.sign(w(grid))
    k = int(np.flatnonzero(s[:-1] * s[1:] < 0)[0])
    lo, hi = grid[k], grid[k + 1]
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if np.sign(w(mid)[0]) == s[k]:
            lo = mid
        else:
            hi = mid
    sol = linkwork.solve(mech, [lo], order=2)
    ins = instant(sol, "coupler", tol=1e-6)
    assert ins.translating[0] and ins.pole.is_infinite[0] and ins.alpha[0] != 0
    ic = inflection_circle(sol, "coupler", tol=1e-6)
    assert ic.is_line[0]
    through, d = ic.anchor.xy[0], perp(ic.normal.xy)[0]
    xy = through + np.outer([-3.0, 0.0, 2.0, 5.0], d)
    for p in xy:
        v, a = relative_kinematics(sol, "coupler", "frame", p[None])
        assert abs(cross(v, a)[0]) / np.linalg.norm(v) < 1e-6 * np.linalg.norm(a)


def test_rotation_about_a_hinge():
    # links joined by a hinge turn about it: the pole stays put (u = 0, D = 0), the inflection
    # circle shrinks to the hinge and every path is a circle about it
    mech, _ = _f1()
    sol = linkwork.solve(mech, np.radians([20.0, 200.0]), velocities=[1.0, 2.0],
                         accelerations=[0.5, 0.0], order=2)
    ins = instant(sol, "coupler", "rocker")
    B = sol.point("B").position
    assert np.allclose(ins.pole.xy, B) and np.allclose(ins.diameter, 0)
    assert np.allclose(ins.pole_velocity.xy, 0) and np.isnan(ins.pole_normal.xy).all()
    assert np.allclose(inflection_circle(sol, "coupler", "rocker").radius, 0)
    assert np.allclose(curvature_centre(sol, "coupler", "C", "rocker").centre.xy, B, atol=1e-9)


def test_cardan_circles():
    # internal rolling with ρ_p = 2ρ_π: D = 2ρ_π, the inflection circle is the moving centrode
    # and its points move on straight lines (Rosenauer §15 eq. 10, §31; digest 001a E.1 item 10)
    mech = linkwork.load_text(im.cardan(1.0))
    sol = linkwork.solve(mech, np.radians([10.0, 100.0, 220.0]), order=2)
    ins = instant(sol, "planet")
    assert np.allclose(ins.diameter, 2.0)
    ic = inflection_circle(sol, "planet")
    assert np.allclose(ic.centre.xy, sol.point("O").position) and np.allclose(ic.radius, 1.0)
    for ang in np.radians([0.0, 77.0, 190.0]):
        s = mech.points["O"] + np.array([np.cos(ang), np.sin(ang)])
        cc = curvature_centre(sol, "planet", s)
        assert cc.centre.is_infinite.all() and np.isinf(cc.radius).all()
