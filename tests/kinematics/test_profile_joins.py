"""The tangent cam (*Tangentennocken*, Pöschl ch. IV): a base circle and a nose circle joined by
two straight flanks, with a radial roller follower. Where the contact runs onto a flank the
follower's acceleration jumps from 0 (the base circle's dwell) to (R0 + r)·ω²; where it runs from
the flank onto the nose, from the flank's law s = (R0 + r)/cos ψ to the slider-crank of the nose
(crank ON, rod rn + r). The crossings and both one-sided limits come from these closed forms and
from the crossing angles solved here by geometry alone."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

import linkwork
from linkwork.errors import ModelError
from linkwork.geometry.profiles import ArcTo, LineTo, PathProfile
from linkwork.kinematics.joins import join_crossings
from linkwork.model import CamContact, Mechanism, Prismatic, Revolute

R0, RN, D, RHO = 20.0, 8.0, 25.0, 5.0   # base radius, nose radius, centre distance ON, roller
GAMMA = np.arccos((R0 - RN) / D)         # the flanks' normals: n(±γ)


def n(a):
    return np.array([np.cos(a), np.sin(a)])


def tangent_cam() -> Mechanism:
    N = np.array([D, 0.0])
    b_lo, b_hi = R0 * n(-GAMMA), R0 * n(GAMMA)
    nose_lo, nose_hi = N + RN * n(-GAMMA), N + RN * n(GAMMA)
    # counter-clockwise: base arc from +γ round to −γ, lower flank, nose arc, upper flank
    cam = PathProfile(tuple(b_hi), [ArcTo(tuple(b_lo), center=(0.0, 0.0)), LineTo(tuple(nose_lo)),
                                    ArcTo(tuple(nose_hi), center=tuple(N)), LineTo(tuple(b_hi))],
                      closed=True, smooth=True)
    # follower on the y-axis, roller on the base circle at the design position (cam angle 0)
    return Mechanism.build(
        name="tangent cam", points={"O": [0, 0], "C": [0, R0 + RHO], "F": [0, 60.0], "N": N},
        links={"frame": ["O"], "cam": ["O", "N"], "follower": ["C", "F"]},
        joints=[Revolute("O", "O", ("frame", "cam")),
                Prismatic("F", "F", ("frame", "follower"), np.array([0.0, 1.0])),
                CamContact("K", ("cam", "follower"), "cam", "roller", point="C", radius=RHO)],
        drivers=[{"joint": "O"}], profiles={"cam": cam})


def _rot(phi, v):
    c, s = np.cos(phi), np.sin(phi)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def test_tangent_cam_acceleration_jumps_at_the_joins():
    mech = tangent_cam()
    phi = np.radians(np.arange(0.0, 360.0, 1.0))  # ω = 1: the input is ON's angle from the x-axis
    crossings = join_crossings(linkwork.solve(mech, phi), "K")
    # the contact runs clockwise round the cam: base → upper flank → nose → lower flank → base
    assert len(crossings) == 4

    # 1. base → upper flank: the flank's normal n(γ), turned by φ, points up the follower's axis
    phi_a = np.pi / 2 - GAMMA
    a = crossings[0]
    assert a.input == pytest.approx(phi_a, abs=1e-10)
    assert a.curvature == pytest.approx((1 / R0, 0.0))
    assert a.before.point("C").acceleration[0, 1] == pytest.approx(0.0, abs=1e-9)  # dwell
    # on the flank s = (R0 + r)/cos ψ, ψ = φ − φa, and d²(sec ψ)/dψ² = 1 at ψ = 0
    assert a.after.point("C").acceleration[0, 1] == pytest.approx(R0 + RHO, rel=1e-9)
    np.testing.assert_allclose(a.before.point("C").velocity, a.after.point("C").velocity, atol=1e-12)

    # 2. upper flank → nose: the roller centre on the nose's normal through the join point
    N = np.array([D, 0.0])
    phi_b = brentq(lambda p: _rot(p, N + (RN + RHO) * n(GAMMA))[0], phi_a, np.pi / 2)
    b = crossings[1]
    assert b.input == pytest.approx(phi_b, abs=1e-10)
    psi = phi_b - phi_a
    sec = 1 / np.cos(psi)
    flank = (R0 + RHO) * (sec * np.tan(psi) ** 2 + sec**3)

    def nose(p):  # the nose: crank ON at θ = φ − π/2 from the axis, rod rn + r
        t = p - np.pi / 2
        return D * np.cos(t) + np.sqrt((RN + RHO) ** 2 - (D * np.sin(t)) ** 2)

    h = 1e-4
    nose_acc = (nose(phi_b + h) - 2 * nose(phi_b) + nose(phi_b - h)) / h**2
    assert b.before.point("C").acceleration[0, 1] == pytest.approx(flank, rel=1e-9)
    assert b.after.point("C").acceleration[0, 1] == pytest.approx(nose_acc, rel=1e-6)
    assert b.after.point("C").position[0, 1] == pytest.approx(nose(phi_b), rel=1e-12)

    # 3., 4. the cam is symmetric about ON: the mirror crossings at π − φ, the jumps reversed
    c, d = crossings[2], crossings[3]
    assert c.input == pytest.approx(np.pi - phi_b, abs=1e-10)
    assert d.input == pytest.approx(np.pi - phi_a, abs=1e-10)
    assert c.point_jump("C")[1] == pytest.approx(-b.point_jump("C")[1], rel=1e-9)
    assert d.point_jump("C")[1] == pytest.approx(-(R0 + RHO), rel=1e-9)
    assert d.jump("cam") == pytest.approx(0.0, abs=1e-12)  # the driver turns uniformly


def test_no_crossings_on_a_smooth_profile():
    from higher_pair_mechanisms import eccentric
    sol = linkwork.solve(eccentric("roller"), np.radians(np.arange(0.0, 360.0, 5.0)))
    assert join_crossings(sol, "K") == []


def test_a_lower_pair_has_no_profile():
    sol = linkwork.solve(tangent_cam(), [0.1])
    with pytest.raises(ModelError, match="not a higher pair"):
        join_crossings(sol, "O")
