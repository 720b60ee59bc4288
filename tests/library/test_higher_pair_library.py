"""The library's mechanisms with higher pairs, each against its seed facts and an independent
closed form.

- Eccentric disc cams (Pöschl §43, Abb. 46 Nr. 20; §49, Abb. 56, 57, 59): an eccentric circle
  with a roller is exactly the slider-crank (centric or offset) through the disc's centre, with a
  flat face the Scotch yoke, with an oscillating roller lever the four-bar; the closed forms are
  derived here from the design dimensions, not from the solver.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

import linkwork
from linkwork import Status

PHI = np.radians(np.arange(0.0, 360.0, 2.5) + 0.7)


@lru_cache(maxsize=None)
def mech(name: str):
    return linkwork.load(f"library:{name}")


def solve(name: str, phi=PHI, order: int = 3):
    sol = linkwork.solve(mech(name), phi, order=order)
    assert (sol.status == Status.OK).all()
    return sol


# ---------------------------------------------------------------------------- eccentric cams
E_, R_, RHO_ = 10.0, 30.0, 8.0  # disc eccentricity, radius and roller radius of the files


def offset_slider_crank(phi, crank, rod, offset):
    """Slider on the line x = offset driven by crank `crank` (pin at angle φ, ω = 1) and rod
    `rod`: y = crank·sin φ + √(rod² − (offset − crank·cos φ)²) and its first three derivatives."""
    c, s = np.cos(phi), np.sin(phi)
    g, g1, g2, g3 = offset - crank * c, crank * s, crank * c, -crank * s
    w = np.sqrt(rod**2 - g * g)
    w1 = -g * g1 / w
    w2 = -(g1 * g1 + g * g2 + w1 * w1) / w
    w3 = -(3 * g1 * g2 + g * g3 + 3 * w1 * w2) / w
    return crank * s + w, crank * c + w1, -crank * s + w2, -crank * c + w3


@pytest.mark.parametrize("name,offset", [("radial-roller-cam", 0.0), ("offset-roller-cam", 15.0)])
def test_roller_on_an_eccentric_is_the_slider_crank_through_its_centre(name, offset):
    m = mech(name)
    assert np.allclose(m.points["E"], [E_, 0.0]) and m.joint("K").radius == RHO_
    w = 2 * np.pi  # 60 rpm
    sol = solve(name)
    C = sol.point("C")
    y, y1, y2, y3 = offset_slider_crank(PHI, E_, R_ + RHO_, offset)
    np.testing.assert_allclose(C.position[:, 0], offset, atol=1e-12)
    np.testing.assert_allclose(C.position[:, 1], y, atol=1e-10 * R_)
    np.testing.assert_allclose(C.velocity[:, 1], w * y1, atol=1e-10 * R_ * w)
    np.testing.assert_allclose(C.acceleration[:, 1], w**2 * y2, atol=1e-9 * R_ * w**2)
    np.testing.assert_allclose(C.jerk[:, 1], w**3 * y3, atol=1e-8 * R_ * w**3)
    # the pressure angle: between the line of stroke and the normal E–C (the rod of the
    # equivalent slider-crank): sin α = |offset − e cos φ|/(R + ρ)
    np.testing.assert_allclose(sol.joint("K")["pressure_angle"],
                               np.arcsin(np.abs(offset - E_ * np.cos(PHI)) / (R_ + RHO_)), atol=1e-12)


def test_lift_of_the_roller_cams():
    """Stroke of the slider-crank: √((l + r)² − f²) − √((l − r)² − f²) with r = e, l = R + ρ."""
    phi = np.radians(np.arange(0.0, 360.0, 0.25))
    for name, f in [("radial-roller-cam", 0.0), ("offset-roller-cam", 15.0)]:
        y = linkwork.solve(mech(name), phi).point("C").position[:, 1]
        l, r = R_ + RHO_, E_
        assert np.ptp(y) == pytest.approx(np.sqrt((l + r) ** 2 - f * f) - np.sqrt((l - r) ** 2 - f * f),
                                          abs=1e-4)


def test_flat_face_on_an_eccentric_is_a_scotch_yoke():
    """Pöschl §49 (Abb. 57): the flat follower's motion is the projection of the disc centre's on
    the stem: y = R + e·sin φ, and so its derivatives; the pressure angle is zero."""
    w = 2 * np.pi
    sol = solve("flat-faced-cam", order=4)
    C = sol.point("C")
    np.testing.assert_allclose(C.position[:, 1], R_ + E_ * np.sin(PHI), atol=1e-10 * R_)
    np.testing.assert_allclose(C.velocity[:, 1], w * E_ * np.cos(PHI), atol=1e-10 * R_ * w)
    np.testing.assert_allclose(C.acceleration[:, 1], -w**2 * E_ * np.sin(PHI), atol=1e-9 * R_ * w**2)
    np.testing.assert_allclose(C.jerk[:, 1], -w**3 * E_ * np.cos(PHI), atol=1e-8 * R_ * w**3)
    np.testing.assert_allclose(sol.joint("K")["pressure_angle"], 0.0, atol=1e-9)
    # the contact lies straight above the disc's centre (the face's normal through it)
    np.testing.assert_allclose(sol.joint("K")["point"][:, 0], E_ * np.cos(PHI), atol=1e-10 * R_)


def four_bar_output(phi, O, a, b, c, B0, C0):
    """Rocker angle of the four-bar O–A–C–B0 (crank a at angle φ, coupler b, rocker c), on the
    assembly branch of the design point C0, by intersecting two circles."""
    A = O + a * np.stack([np.cos(phi), np.sin(phi)], axis=1)
    d = B0 - A
    D = np.hypot(*d.T)
    x = (b * b - c * c + D * D) / (2 * D)
    h = np.sqrt(b * b - x * x)
    ex = d / D[:, None]
    u, v = B0 - O - [a, 0.0], C0 - O - [a, 0.0]  # the design: crank pin at (a, 0)
    side = np.sign(u[0] * v[1] - u[1] * v[0])
    C = A + x[:, None] * ex + side * h[:, None] * np.stack([-ex[:, 1], ex[:, 0]], axis=1)
    return np.arctan2(C[:, 1] - B0[1], C[:, 0] - B0[0])


def test_oscillating_roller_lever_is_the_four_bar_through_the_disc_centre():
    """Pöschl §43 Nr. 20, §49 Abb. 59: crank O–E (e), coupler E–C (R + ρ), rocker C–B0. Angles
    from circle intersections; ω, α from central differences of that closed form."""
    m = mech("oscillating-roller-cam")
    B0, C0 = m.points["B0"], m.points["C"]
    arm = float(np.hypot(*(C0 - B0)))
    assert arm == pytest.approx(40.0, abs=1e-12)
    sol = solve("oscillating-roller-cam", order=2)

    def psi(phi):
        return four_bar_output(phi, np.zeros(2), E_, R_ + RHO_, arm, B0, C0)

    got = sol.pose_derivatives("rocker")
    ref = np.arctan2(C0[1] - B0[1], C0[0] - B0[0])
    np.testing.assert_allclose(np.angle(np.exp(1j * (got[0, :, 2] + ref - psi(PHI)))), 0.0, atol=1e-11)
    w, h = 2 * np.pi, 1e-4
    d1 = np.angle(np.exp(1j * (psi(PHI + h) - psi(PHI - h)))) / (2 * h)
    d2 = np.angle(np.exp(1j * (psi(PHI + h) - 2 * psi(PHI) + psi(PHI - h)))) / h**2
    np.testing.assert_allclose(got[1, :, 2], w * d1, atol=1e-7 * w)
    np.testing.assert_allclose(got[2, :, 2], w**2 * d2, atol=1e-4 * w**2)


# ---------------------------------------------------------------------------- Pöschl's arc cam
# Pöschl §22d (Abb. 22) and §49 (Abb. 56): a lift from the inner dwell (base circle) to the outer
# dwell by two convex circular arcs. The dimensions are the file's design choices (the book's
# figures are lost): base circle r0, lift h, flank R1, nose R2, roller ρ, outer dwell ±30° about
# the −y axis of the cam's drawing.
R0, LIFT, R1, R2, RHO_P = 40.0, 15.0, 80.0, 30.0, 10.0


def poeschl_arcs():
    """The cam's arcs (centre, radius, start angle, sweep about the centre; ccw), derived from the
    tangency conditions |OK1| = R1 − r0, |OK2| = r0 + h − R2, |K1K2| = R1 − R2."""
    beta = np.radians(30.0)
    ok1, ok2, k12 = R1 - R0, R0 + LIFT - R2, R1 - R2
    down = -np.pi / 2  # the outer dwell's middle
    K2 = ok2 * np.array([np.cos(down - beta), np.sin(down - beta)])
    # K1: |OK1| = ok1 and |K1K2| = k12, on the side that puts the flank before the nose (ccw)
    gap = np.arccos((ok1**2 + ok2**2 - k12**2) / (2 * ok1 * ok2))
    K1 = ok1 * np.array([np.cos(down - beta + gap), np.sin(down - beta + gap)])
    mirror = np.array([-1.0, 1.0])
    T0 = -K1 * R0 / ok1            # where the flank leaves the base circle
    T2 = K1 + R1 * (K2 - K1) / k12  # flank to nose
    T3 = (R0 + LIFT) * np.array([np.cos(down - beta), np.sin(down - beta)])
    pts = [T0, T2, T3, T3 * mirror, T2 * mirror, T0 * mirror, T0]
    centres = [K1, K2, np.zeros(2), K2 * mirror, K1 * mirror, np.zeros(2)]
    radii = [R1, R2, R0 + LIFT, R2, R1, R0]
    arcs = []
    for c, r, p, q in zip(centres, radii, pts[:-1], pts[1:]):
        a0 = np.arctan2(*(p - c)[::-1])
        sweep = np.mod(np.arctan2(*(q - c)[::-1]) - a0, 2 * np.pi)
        arcs.append((c, r, a0, sweep))
    return arcs


def arc_cam_follower(phi, arcs, rho):
    """Height of a roller centre on the line x = 0 over the arc cam turned by φ, and its first two
    derivatives in φ (ω = 1): on each arc the slider-crank through the arc's centre (crank |OK|,
    rod R + ρ); the arc in contact is the one whose contact point lies within its sweep. Also
    returns the index of that arc."""
    y = np.full((3,) + phi.shape, np.nan)
    which = np.full(phi.shape, -1)
    for i, (c, r, a0, sweep) in enumerate(arcs):
        crank, th0 = np.hypot(*c), np.arctan2(c[1], c[0])
        kx, ky = crank * np.cos(phi + th0), crank * np.sin(phi + th0)
        w = np.sqrt((r + rho) ** 2 - kx * kx)
        yy = ky + w
        # the contact's direction from the centre, in the cam's drawing
        ang = np.arctan2(yy - ky, -kx) - phi
        inside = np.mod(ang - a0, 2 * np.pi) <= sweep
        kx1, ky1 = -ky, kx
        w1 = -kx * kx1 / w
        w2 = -(kx1 * kx1 + kx * (-kx) + w1 * w1) / w
        sel = inside & (which < 0)
        y[:, sel] = np.stack([yy, ky1 + w1, -ky + w2])[:, sel]
        which[sel] = i
    return y, which


def test_poeschl_cam_profile_is_the_arcs_of_the_design():
    m = mech("poeschl-arc-cam")
    prof = m.profiles["cam"]
    arcs = poeschl_arcs()
    # every arc's points lie on its circle, and the curvature jumps at the joins by 1/R differences
    for i, (c, r, a0, sweep) in enumerate(arcs):
        s0 = prof.segment_starts[i]
        s = s0 + np.linspace(0.0, 1.0, 7) * r * sweep
        np.testing.assert_allclose(np.hypot(*(prof.derivatives(s, 0)[0] - c).T), r, atol=1e-9)
    from linkwork.geometry.profiles import curvature_jumps
    _, before, after = curvature_jumps(prof)
    np.testing.assert_allclose(sorted(np.abs(1 / np.asarray(before) - 1 / np.asarray(after))),
                               sorted(abs(R - Rn) for R, Rn in
                                      [(R1, R2), (R2, R0 + LIFT), (R0 + LIFT, R2), (R2, R1), (R1, R0), (R0, R1)]),
                               atol=1e-9)


def test_poeschl_cam_follows_the_slider_cranks_through_the_arc_centres():
    """Pöschl §49: for the arcs 0–2 and 2–4 the equivalent mechanisms are the slider-cranks
    O K1 M1 C1 and O K2 M2 C2; on the dwell arcs the follower rests."""
    m = mech("poeschl-arc-cam")
    w = m.drivers[0].law.speed
    assert w == pytest.approx(4 * np.pi)  # n = 120/min, ω = 4π/s (Pöschl Example 6)
    phi = np.radians(np.arange(0.0, 360.0, 0.5) + 0.123)
    sol = linkwork.solve(m, phi)
    assert (sol.status == Status.OK).all()
    want, which = arc_cam_follower(phi, poeschl_arcs(), RHO_P)
    assert (which >= 0).all() and set(which) == set(range(6))
    C = sol.point("C")
    np.testing.assert_allclose(C.position[:, 1], want[0], atol=1e-9 * R0)
    np.testing.assert_allclose(C.velocity[:, 1], w * want[1], atol=1e-9 * R0 * w)
    np.testing.assert_allclose(C.acceleration[:, 1], w**2 * want[2], atol=1e-8 * R0 * w**2)
    dwell_in, dwell_out = which == 5, which == 2
    np.testing.assert_allclose(C.position[dwell_in, 1], R0 + RHO_P, atol=1e-9)
    np.testing.assert_allclose(C.position[dwell_out, 1], R0 + LIFT + RHO_P, atol=1e-9)
    np.testing.assert_allclose(C.velocity[dwell_in | dwell_out, 1], 0.0, atol=1e-9)


def test_poeschl_cam_acceleration_jumps_at_the_joins():
    """Pöschl §22d, §49: where arcs of different curvature meet, the acceleration has two values,
    those of the two equivalent slider-cranks at the angle where the roller centre passes the
    join's normal (J + ρ·n_J, n_J the common normal)."""
    m = mech("poeschl-arc-cam")
    arcs = poeschl_arcs()
    jumps = 0
    for i in range(6):
        c, r, a0, sweep = arcs[i]
        nJ = np.array([np.cos(a0 + sweep), np.sin(a0 + sweep)])
        M = c + (r + RHO_P) * nJ  # the roller centre in the cam's drawing when it passes the join
        phiJ = np.pi / 2 - np.arctan2(M[1], M[0])
        eps = 1e-7
        sol = linkwork.solve(m, np.array([phiJ - eps, phiJ + eps]))
        got = sol.point("C").acceleration[:, 1] / m.drivers[0].law.speed ** 2
        # the cam turns ccw: the points under the follower run backwards along the path
        want_before, _ = arc_cam_follower(np.array([phiJ - eps]), [arcs[(i + 1) % 6]], RHO_P)
        want_after, _ = arc_cam_follower(np.array([phiJ + eps]), [arcs[i]], RHO_P)
        assert got[0] == pytest.approx(want_before[2, 0], abs=1e-5 * R0)
        assert got[1] == pytest.approx(want_after[2, 0], abs=1e-5 * R0)
        jumps += abs(got[1] - got[0]) > 1e-3 * R0
    assert jumps == 6  # every join changes the curvature


def join_angle(arc) -> float:
    """Cam angle at which the roller centre passes the end of `arc`: it lies on the follower's
    line there, at J + ρ·n_J in the cam's drawing (n_J the common normal at the join J)."""
    c, r, a0, sweep = arc
    M = c + (r + RHO_P) * np.array([np.cos(a0 + sweep), np.sin(a0 + sweep)])
    return float(np.mod(np.pi / 2 - np.arctan2(M[1], M[0]), 2 * np.pi))


def test_poeschl_check_criterion_over_the_lift():
    """Pöschl §22d: from rest in the inner dwell to rest in the outer dwell, ∫ b dr = 0: the
    positive and negative areas of the b–r line are equal. Integrated by Simpson's rule over each
    arc of the lift (the cam turning ccw, the roller climbs arcs 4 and 3 from the base circle 5
    to the outer dwell 2)."""
    from scipy.integrate import simpson

    m = mech("poeschl-arc-cam")
    arcs = poeschl_arcs()
    a, b_, c = join_angle(arcs[4]), join_angle(arcs[3]), join_angle(arcs[2])
    assert a < b_ < c
    total, peak, rise = 0.0, 0.0, 0.0
    for lo, hi in ((a, b_), (b_, c)):
        # just inside the piece: at a join itself the solver takes one of the two sides
        s = np.linspace(lo + 1e-10, hi - 1e-10, 4001)
        C = linkwork.solve(m, s).point("C")
        y, acc = C.position[:, 1], C.acceleration[:, 1]
        total += simpson(acc, x=y)
        peak = max(peak, np.abs(acc).max())
        rise += y[-1] - y[0]
    assert rise == pytest.approx(LIFT, abs=1e-6)
    assert peak > 0
    assert abs(total) <= 1e-9 * peak * LIFT


# ---------------------------------------------------------------------------- elliptical gears
def test_elliptical_gears_follow_the_focal_rolling_law():
    """Two equal ellipses (a, e; p = a(1 − e²)) about their foci 2a apart. Seen from its focus an
    ellipse is r = p/(1 + e cos ϑ), ϑ from the near vertex. Wheel 1, turned by φ from touching with
    its far vertex, reaches the line of centres with r1 = p/(1 − e cos φ); rolling keeps the
    contact there (it is the relative pole), so wheel 2 touches with r2 = 2a − r1 = p/(1 + e cos ψ).
    Eliminating: cos ψ = ((1 + e²) cos φ − 2e)/(1 + e² − 2e cos φ), hence
    (1 − cos ψ)/(1 + cos ψ) = ((1 + e)/(1 − e))²(1 − cos φ)/(1 + cos φ), i.e.
    tan(ψ/2) = (1 + e)/(1 − e)·tan(φ/2), wheel 2 turning the other way; ω2/ω1 = −r1/r2, between
    −(1 + e)/(1 − e) (φ = 0) and −(1 − e)/(1 + e) (φ = π)."""
    m = mech("elliptical-gears")
    a, b = 50.0, 40.0
    e = np.sqrt(1 - (b / a) ** 2)
    p = a * (1 - e * e)
    assert e == pytest.approx(0.6)
    phi = np.radians(np.arange(-179.0, 180.0, 1.0) + 0.25)
    sol = linkwork.solve(m, phi)
    assert (sol.status == Status.OK).all()
    psi = -sol.pose_derivatives("wheel2")[0, :, 2]
    np.testing.assert_allclose(np.tan(psi / 2), (1 + e) / (1 - e) * np.tan(phi / 2), rtol=1e-9)
    r1 = p / (1 - e * np.cos(phi))
    ratio = sol.link("wheel2").omega / sol.link("wheel1").omega
    np.testing.assert_allclose(ratio, -r1 / (2 * a - r1), rtol=1e-9)
    ends = linkwork.solve(m, np.array([0.0, np.pi]))
    r = ends.link("wheel2").omega / ends.link("wheel1").omega
    assert r == pytest.approx([-(1 + e) / (1 - e), -(1 - e) / (1 + e)], rel=1e-9)
    # the contact is the relative pole: on the line of centres at r1 from O1, and nothing slides
    rep = sol.joint("mesh")
    np.testing.assert_allclose(rep["point"], np.c_[r1, np.zeros_like(r1)], atol=1e-9 * a)
    np.testing.assert_allclose(rep["sliding_velocity"], 0.0, atol=1e-9 * a)
    # the axle's link stands still: wheel 2 turns about its focus O2
    np.testing.assert_allclose(sol.point("O2").position, np.tile(m.points["O2"], (phi.size, 1)), atol=1e-9 * a)
    np.testing.assert_allclose(sol.link("axle").omega, 0.0, atol=1e-9)


def test_elliptical_gears_counts():
    """Rosenauer's count with a self-closed higher pair (h = 2h_p): n = 4, g = 3, h = 2:
    2 + 2·3 − 3·4 + 4 = 0, constrained."""
    from linkwork.structure.mobility import counts

    c = counts(mech("elliptical-gears"))
    assert (c.n, c.g, c.s, c.h_n, c.h_p, c.h) == (4, 3, 0, 0, 1, 2)
    assert c.criterion == 0 and c.constrained


# ---------------------------------------------------------------------------- rolling lever
K1_RL, R1_RL, R2_RL = np.array([310.0, -300.0]), 300.0, 200.0  # the bank's centre and radius, the lever's radius


def _line_cross(P, d, Q, e):
    """Intersection of the lines P + s·d and Q + t·e (rows: samples)."""
    den = d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0]
    w = Q - P
    s = (w[:, 0] * e[:, 1] - w[:, 1] * e[:, 0]) / den
    return P + s[:, None] * d


def _cross(a, b):
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def test_rolling_lever_counts():
    """Rosenauer §98 Ex. 32 and §109: n = 5, g = 4, s = 1, h = 1: 1 + 2·5 − 3·5 + 4 = 0."""
    from linkwork.structure.mobility import counts

    c = counts(mech("rolling-lever-valve-gear"))
    assert (c.n, c.g, c.s, c.h_n, c.h_p, c.h) == (5, 4, 1, 1, 0, 1)
    assert c.criterion == 0 and c.constrained


def test_rolling_lever_equals_its_equivalent_linkage():
    """Pöschl §53, Rosenauer §121 Method II: with circular arcs the lever's centre K2 stays at
    R1 + R2 from the bank's centre K1, so the bar K1K2 replaces the higher pair exactly; the
    six-bar of lower pairs moves as the gear at every crank angle."""
    from linkwork.model import Mechanism, Prismatic, Revolute

    m = mech("rolling-lever-valve-gear")
    P = dict(m.points)
    assert np.hypot(*(P["K2"] - K1_RL)) == pytest.approx(R1_RL + R2_RL)
    P["K1"] = K1_RL
    six = Mechanism.build(
        name="equivalent six-bar", points=P,
        links={"frame": ["O", "K1"], "crank": ["O", "A"], "rod": ["A", "D"], "lever": ["D", "B", "K2"],
               "bar": ["K1", "K2"], "valve": ["B", "V"]},
        joints=[Revolute("O", "O", ("frame", "crank")), Revolute("A", "A", ("crank", "rod")),
                Revolute("D", "D", ("rod", "lever")), Revolute("B", "B", ("lever", "valve")),
                Revolute("K1", "K1", ("frame", "bar")), Revolute("K2", "K2", ("bar", "lever")),
                Prismatic("guide", "V", ("frame", "valve"), np.array([0.0, 1.0]))],
        drivers=[{"joint": "O", "law": m.drivers[0].law}])
    phi = np.radians(np.arange(0.0, 360.0, 3.0) + 0.4)
    a, b = linkwork.solve(m, phi, order=3), linkwork.solve(six, phi, order=3)
    assert (a.status == Status.OK).all() and (b.status == Status.OK).all()
    for p in ("B", "D", "K2"):
        for k, tol in (("position", 1e-9), ("velocity", 1e-8), ("acceleration", 1e-7), ("jerk", 1e-6)):
            np.testing.assert_allclose(getattr(a.point(p), k), getattr(b.point(p), k), atol=tol * 500,
                                       err_msg=f"{p} {k}")
    # the valve's lift is a real one
    assert np.ptp(a.point("B").position[:, 1]) > 40


def test_rolling_lever_pole_sliding_and_inflection_circle():
    """Rosenauer 1937 paper 8 and §109/§121 Task 3 on the lever 3:

    - its pole P35 is where the normal to the slide through B meets the common normal at E (for
      circular arcs the line K1K2): the lever's point there stands still;
    - the sliding velocity at E is |E P35|·ω3, and the contact runs along the bank at R1·Ω, Ω the
      angular velocity of K1K2 (|P K2|·ω3/(R1 + R2));
    - Euler–Savary on the common normal, 1/PW = 1/PCα − 1/PCe (Cα = K2 the lever's curvature
      centre, Ce = K1 the bank's; abscissae from P), gives the inflection point W: the lever's point
      there moves with zero path curvature; the inflection circle through P, B and W has the
      inflection pole W0 diametrically opposite P, and the lever's point at P accelerates by
      ω3²·(W0 − P) (the pole acceleration)."""
    m = mech("rolling-lever-valve-gear")
    phi = np.radians(np.arange(0.0, 360.0, 5.0) + 0.4)
    sol = linkwork.solve(m, phi)
    B = sol.point("B").position
    K2 = sol.point("K2").position
    K1 = np.broadcast_to(K1_RL, B.shape)
    n = K2 - K1
    P = _line_cross(B, np.tile([1.0, 0.0], (len(B), 1)), K1, n)
    w3 = sol.link("lever").omega
    lever = lambda Q: sol.point_on("lever", sol.local("lever", Q))  # noqa: E731
    np.testing.assert_allclose(lever(P).velocity, 0.0, atol=1e-8 * 500 * np.abs(w3).max())
    rep = sol.joint("E")
    E = rep["point"]
    np.testing.assert_allclose(_cross(E - K1, n), 0.0, atol=1e-8 * 500 * 500)  # E on K1K2
    np.testing.assert_allclose(np.abs(rep["sliding_velocity"]), np.hypot(*(E - P).T) * np.abs(w3),
                               rtol=1e-8, atol=1e-9)
    Omega = np.hypot(*(P - K2).T) * np.abs(w3) / (R1_RL + R2_RL)
    np.testing.assert_allclose(np.abs(rep["profile_speed"]), R1_RL * Omega, rtol=1e-8, atol=1e-9)
    # Euler–Savary: abscissae along the unit normal from P
    un = n / np.hypot(*n.T)[:, None]
    pa, pe = ((K2 - P) * un).sum(1), ((K1 - P) * un).sum(1)
    W = P + (1.0 / (1.0 / pa - 1.0 / pe))[:, None] * un
    vw, aw = lever(W).velocity, lever(W).acceleration
    np.testing.assert_allclose(_cross(vw, aw) / (np.hypot(*vw.T) ** 2 * np.hypot(*aw.T)), 0.0, atol=1e-8)
    # the inflection circle through P, B, W; W0 opposite P; the pole point's acceleration
    centre = _circumcentre(P, B, W)
    W0 = 2 * centre - P
    np.testing.assert_allclose(W0[:, 0], B[:, 0], atol=1e-7 * 500)  # on the slide line through B
    np.testing.assert_allclose(lever(P).acceleration, (w3**2)[:, None] * (W0 - P),
                               atol=1e-7 * 500 * (w3**2).max())


def _circumcentre(A, B, C):
    a2, b2, c2 = (A * A).sum(1), (B * B).sum(1), (C * C).sum(1)
    d = 2 * (A[:, 0] * (B[:, 1] - C[:, 1]) + B[:, 0] * (C[:, 1] - A[:, 1]) + C[:, 0] * (A[:, 1] - B[:, 1]))
    ux = (a2 * (B[:, 1] - C[:, 1]) + b2 * (C[:, 1] - A[:, 1]) + c2 * (A[:, 1] - B[:, 1])) / d
    uy = (a2 * (C[:, 0] - B[:, 0]) + b2 * (A[:, 0] - C[:, 0]) + c2 * (B[:, 0] - A[:, 0])) / d
    return np.c_[ux, uy]
