"""Higher pairs against independent closed forms and second methods.

- An eccentric disc with a roller (or a knife edge) on a translating follower is the
  slider-crank through the disc's centre (Pöschl §43: the equivalent linkage); with an
  oscillating follower it is the four-bar; with a flat face it is the Scotch yoke. Positions,
  velocities, accelerations and jerks come out of the higher pair's Newton path and are checked
  against those closed forms, and against linkwork's own closed-form RRP/RRR paths for the
  equivalent linkage (a different code path: circle–line and circle–circle intersections).
- Two circles in profile contact give the roller's result.
- A disc rolling without slip on a fixed circle turns by (R + r)/r times the polar angle of
  its centre (the epicycloid's rolling condition).
- The contact report: the pressure angle of a translating roller follower on an eccentric is
  asin(e·cos φ / (R + ρ)) in closed form; the contact point's run along the profile equals the
  finite difference of its arc length.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.errors import ModelError
from higher_pair_mechanisms import (E, R, RHO, ROLL_CRANK, ROLL_O2, ROLL_R, ROLL_R0, ROLL_ROD,
                                    eccentric, rolling_disc)
from linkwork.geometry.profiles import CircleProfile
from linkwork.model import CamContact, Mechanism, Prismatic, Revolute

PHI = np.radians(np.arange(0.0, 360.0, 7.5) + 0.3)


def slider_crank_closed_form(phi, rod, offset=0.0):
    """Follower height y and its derivatives in φ (ω = 1) of the slider-crank with crank e, rod
    `rod`, slider on x = offset: y = e sin φ + √(rod² − (offset − e cos φ)²)."""
    c, s = np.cos(phi), np.sin(phi)
    g = offset - E * c              # horizontal gap from the crank pin
    g1, g2, g3 = E * s, E * c, -E * s  # its derivatives
    w = np.sqrt(rod**2 - g * g)
    w1 = -g * g1 / w
    w2 = -(g1 * g1 + g * g2 + w1 * w1) / w
    w3 = -(3 * g1 * g2 + g * g3 + 3 * w1 * w2) / w
    return (E * s + w, E * c + w1, -E * s + w2, -E * c + w3)


@pytest.mark.parametrize("follower,rod", [("roller", R + RHO), ("knife", R)])
@pytest.mark.parametrize("offset", [0.0, 7.0])
def test_eccentric_is_a_slider_crank(follower, rod, offset):
    mech = eccentric(follower, offset=offset)
    sol = linkwork.solve(mech, PHI, order=3)
    assert (sol.status == linkwork.Status.OK).all()
    C = sol.point("C")
    want = slider_crank_closed_form(PHI, rod, offset)
    scale = [E, E, E, E]
    for got, exp, sc in zip((C.position[:, 1], C.velocity[:, 1], C.acceleration[:, 1], C.jerk[:, 1]),
                            want, scale):
        np.testing.assert_allclose(got, exp, rtol=0, atol=1e-10 * sc)
    np.testing.assert_allclose(C.position[:, 0], offset, atol=1e-12)


def test_eccentric_matches_the_closed_form_slider_crank_path():
    """The same motion from linkwork's closed-form circle–line group (the RRP dyad)."""
    cam = linkwork.solve(eccentric("roller"), PHI, order=3)
    y0 = np.sqrt((R + RHO) ** 2 - E**2)
    sc = Mechanism.build(
        name="equivalent slider-crank", points={"O": [0, 0], "E": [E, 0], "C": [0, y0]},
        links={"frame": ["O"], "crank": ["O", "E"], "rod": ["E", "C"], "slider": ["C"]},
        joints=[Revolute("O", "O", ("frame", "crank")), Revolute("E", "E", ("crank", "rod")),
                Revolute("C", "C", ("rod", "slider")),
                Prismatic("G", "C", ("frame", "slider"), np.array([0.0, 1.0]))],
        drivers=[{"joint": "O"}])
    ref = linkwork.solve(sc, PHI, order=3)
    for k in ("position", "velocity", "acceleration", "jerk"):
        np.testing.assert_allclose(getattr(cam.point("C"), k), getattr(ref.point("C"), k),
                                   rtol=0, atol=1e-10 * E)


def test_oscillating_roller_follower_is_a_four_bar():
    """A roller on a rocker pivoted at B0: the four-bar O–E–C–B0 with coupler R + ρ, solved by
    linkwork's closed-form RRR dyad."""
    B0, arm = np.array([45.0, 5.0]), 30.0
    # roller centre on the circle about E of radius R + ρ and about B0 of radius `arm`
    d = np.hypot(*(B0 - [E, 0]))
    a = ((R + RHO) ** 2 - arm**2 + d * d) / (2 * d)
    h = np.sqrt((R + RHO) ** 2 - a * a)
    ex = (B0 - [E, 0]) / d
    C = np.array([E, 0]) + a * ex + h * np.array([-ex[1], ex[0]])
    pts = {"O": [0, 0], "E": [E, 0], "C": C, "B0": B0}
    cam = Mechanism.build(
        name="oscillating roller", points=pts,
        links={"frame": ["O", "B0"], "cam": ["O", "E"], "rocker": ["C", "B0"]},
        joints=[Revolute("O", "O", ("frame", "cam")), Revolute("B0", "B0", ("frame", "rocker")),
                CamContact("K", ("cam", "rocker"), "disc", "roller", point="C", radius=RHO)],
        drivers=[{"joint": "O"}], profiles={"disc": CircleProfile((E, 0.0), R)})
    fb = Mechanism.build(
        name="four-bar", points=pts,
        links={"frame": ["O", "B0"], "crank": ["O", "E"], "coupler": ["E", "C"], "rocker": ["C", "B0"]},
        joints=[Revolute("O", "O", ("frame", "crank")), Revolute("E", "E", ("crank", "coupler")),
                Revolute("C", "C", ("coupler", "rocker")), Revolute("B0", "B0", ("rocker", "frame"))],
        drivers=[{"joint": "O"}])
    s1, s2 = linkwork.solve(cam, PHI, order=3), linkwork.solve(fb, PHI, order=3)
    for k in ("angle", "omega", "alpha", "jerk"):
        np.testing.assert_allclose(getattr(s1.link("rocker"), k), getattr(s2.link("rocker"), k),
                                   rtol=0, atol=1e-11)


def test_flat_face_on_an_eccentric_is_a_scotch_yoke():
    """The face rests on the disc's top: y = R + e sin φ exactly, and its derivatives."""
    sol = linkwork.solve(eccentric("flat"), PHI, order=4)
    D = sol.pose_derivatives("follower")
    want = [E * np.sin(PHI), E * np.cos(PHI), -E * np.sin(PHI), -E * np.cos(PHI), E * np.sin(PHI)]
    for k in range(5):
        np.testing.assert_allclose(D[k, :, 1], want[k], rtol=0, atol=1e-10 * E)
    rep = sol.joint("K")
    # the contact lies straight above the disc's centre, the normal points up
    np.testing.assert_allclose(rep["point"][:, 0], E * np.cos(PHI), atol=1e-10 * E)
    np.testing.assert_allclose(rep["normal"], np.tile([0.0, 1.0], (PHI.size, 1)), atol=1e-12)
    # flat face on a translating follower: pressure angle zero
    np.testing.assert_allclose(rep["pressure_angle"], 0.0, atol=1e-9)
    # the contact runs along the face at the rate of x = e cos φ (the face does not move sideways)
    np.testing.assert_allclose(rep["follower_speed"], -E * np.sin(PHI), atol=1e-10 * E)


def test_two_circle_profiles_in_contact_equal_the_roller():
    roller = linkwork.solve(eccentric("roller"), PHI, order=2)
    base = eccentric("roller")
    y0 = float(base.points["C"][1])
    two = Mechanism.build(
        name="two profiles", points=dict(base.points),
        links={"frame": ["O"], "cam": ["O", "E"], "follower": ["C", "F"]},
        joints=[Revolute("O", "O", ("frame", "cam")),
                Prismatic("F", "F", ("frame", "follower"), np.array([0.0, 1.0])),
                CamContact("K", ("cam", "follower"), "disc", "profile", mate="wheel")],
        drivers=[{"joint": "O"}],
        profiles={"disc": CircleProfile((E, 0.0), R), "wheel": CircleProfile((0.0, y0), RHO)})
    sol = linkwork.solve(two, PHI, order=2)
    for k in ("position", "velocity", "acceleration"):
        np.testing.assert_allclose(getattr(sol.point("C"), k), getattr(roller.point("C"), k),
                                   rtol=0, atol=1e-10 * E)
    np.testing.assert_allclose(sol.joint("K")["point"], roller.joint("K")["point"], atol=1e-10 * E)


def test_pressure_angle_and_contact_speeds():
    sol = linkwork.solve(eccentric("roller"), PHI, order=2)
    rep = sol.joint("K")
    # the normal is the line E–C: sin α = horizontal gap / (R + ρ)
    np.testing.assert_allclose(rep["pressure_angle"], np.arcsin(np.abs(E * np.cos(PHI)) / (R + RHO)),
                               atol=1e-12)
    # the contact point's run along the disc: the finite difference of its arc length R·u
    h = 1e-6
    up = linkwork.solve(eccentric("roller"), PHI + h).joint("K")["u"]
    dn = linkwork.solve(eccentric("roller"), PHI - h).joint("K")["u"]
    np.testing.assert_allclose(rep["profile_speed"], R * (up - dn) / (2 * h), atol=1e-6 * R)
    # the contact point lies on the disc and on the roller
    P = rep["point"]
    Ew = np.stack([E * np.cos(PHI), E * np.sin(PHI)], axis=1)
    np.testing.assert_allclose(np.hypot(*(P - Ew).T), R, atol=1e-10 * R)
    np.testing.assert_allclose(np.hypot(*(P - sol.point("C").position).T), RHO, atol=1e-10 * R)
    # in the cam's own coordinates the contact lies on the disc as drawn, in the follower's on
    # the roller as drawn (both links' coordinates are the drawing's at the design position)
    on_cam, on_follower = rep["point_on_profile"], rep["point_on_follower"]
    np.testing.assert_allclose(np.hypot(on_cam[:, 0] - E, on_cam[:, 1]), R, atol=1e-10 * R)
    C0 = eccentric("roller").points["C"]
    np.testing.assert_allclose(np.hypot(*(on_follower - C0).T), RHO, atol=1e-10 * R)


def test_disc_rolling_on_a_fixed_circle():
    """A disc (radius r) rolls without slip on a fixed circle (radius R0) about O, its centre W
    led by a rod from a crank. Independent of the pair: W lies on the circle of radius R0 + r
    about O and at |AW| from the crank pin A (circle–circle), and the disc turns by
    (R0 + r)/r times W's polar angle."""
    R0, r, O2, crank, rod = ROLL_R0, ROLL_R, ROLL_O2, ROLL_CRANK, ROLL_ROD
    mech = rolling_disc()
    W = mech.points["W"]
    phi = np.radians(np.linspace(60.0, 120.0, 13))
    sol = linkwork.solve(mech, phi, order=2)
    # every sample assembles; the error bound (`precision`, κ ≈ 50 for this group: κ³ε-ish for
    # the accelerations) stays near the 1e-9 of an `ok`, and the values are checked below
    assert (sol.status != linkwork.Status.UNREACHABLE).all() and (sol.errors < 1e-8).all()
    Aw = O2 + crank * np.stack([np.cos(phi), np.sin(phi)], axis=1)
    dA = np.hypot(*Aw.T)
    a = ((R0 + r) ** 2 - rod**2 + dA * dA) / (2 * dA)
    ex = Aw / dA[:, None]
    Ww = a[:, None] * ex + np.sqrt((R0 + r) ** 2 - a * a)[:, None] * np.stack([-ex[:, 1], ex[:, 0]], 1)
    np.testing.assert_allclose(sol.point("W").position, Ww, atol=1e-10 * R0)
    psi = np.unwrap(np.arctan2(Ww[:, 1], Ww[:, 0])) - np.arctan2(W[1], W[0])
    np.testing.assert_allclose(sol.pose_derivatives("disc")[0, :, 2], (R0 + r) / r * psi, atol=1e-10)
    # no slip: the disc's point at the contact stands still
    np.testing.assert_allclose(sol.joint("T")["sliding_velocity"], 0.0, atol=1e-9 * R0)
    v_contact = sol.point_on("disc", sol.local("disc", sol.joint("T")["point"])).velocity
    np.testing.assert_allclose(v_contact, 0.0, atol=1e-9 * R0)
    # its angular velocity from the finite difference of its angle
    h = 1e-6
    up = linkwork.solve(mech, phi + h).pose_derivatives("disc")[0, :, 2]
    dn = linkwork.solve(mech, phi - h).pose_derivatives("disc")[0, :, 2]
    np.testing.assert_allclose(sol.link("disc").omega, (up - dn) / (2 * h), atol=1e-6)


def test_drawing_without_contact_is_refused():
    with pytest.raises(ModelError, match="does not touch profile 'disc'.*gap 0.959"):
        Mechanism.build(
            name="gap", points={"O": [0, 0], "E": [E, 0], "C": [0, np.sqrt(35**2 - 100) + 1], "F": [0, -20]},
            links={"frame": ["O"], "cam": ["O", "E"], "follower": ["C", "F"]},
            joints=[Revolute("O", "O", ("frame", "cam")),
                    Prismatic("F", "F", ("frame", "follower"), np.array([0.0, 1.0])),
                    CamContact("K", ("cam", "follower"), "disc", "roller", point="C", radius=RHO)],
            drivers=[{"joint": "O"}], profiles={"disc": CircleProfile((E, 0.0), R)})


def test_unknown_profile_is_named():
    with pytest.raises(ModelError, match="no profile 'disk'.*defined: disc"):
        Mechanism.build(
            name="typo", points={"O": [0, 0], "E": [E, 0], "C": [0, 33.0], "F": [0, -20]},
            links={"frame": ["O"], "cam": ["O", "E"], "follower": ["C", "F"]},
            joints=[Revolute("O", "O", ("frame", "cam")),
                    Prismatic("F", "F", ("frame", "follower"), np.array([0.0, 1.0])),
                    CamContact("K", ("cam", "follower"), "disk", "roller", point="C", radius=RHO)],
            drivers=[{"joint": "O"}], profiles={"disc": CircleProfile((E, 0.0), R)})


def test_pressure_angle_in_a_dwell():
    """In a dwell the pitch curve is a circle about the cam's centre O, so the common normal
    passes through O; the follower moves along x = e (offset e = 5): sin α = e/|OC| there,
    although the follower's velocity is zero and gives no direction."""
    mech = linkwork.load("library:designed-cam-offset-roller")
    sol = linkwork.solve(mech, np.radians(np.arange(0.0, 360.0, 2.0)))
    v = sol.point("C").velocity
    dwell = np.hypot(*v.T) < 1e-9 * mech.length_scale
    assert dwell.sum() > 20
    C = sol.point("C").position[dwell]
    np.testing.assert_allclose(np.sin(sol.joint("K")["pressure_angle"][dwell]), 5.0 / np.hypot(*C.T),
                               rtol=1e-9)
