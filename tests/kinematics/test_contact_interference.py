"""A roller inside an elliptical track (the track is the cam, turning about its centre; the
follower translates along the y-axis), the roller's radius between the track's smallest and
largest radius of curvature. Turning from the design position (the minor axis on the follower's
line), the contact runs towards the end of the major axis; at a quarter turn the major axis lies
on the follower's line and, by symmetry, the roller touches the track at two mirror points (it
bridges the hollow, too large to reach its bottom: radius of curvature there b²/a < r). Past the
quarter turn the contact followed on solves the pair's equations, but the roller then overlaps
the track at the mirror point: those samples must be unreachable, not `ok`.

Independent expectation: the symmetry of the ellipse (the quarter turn), and the radius of
curvature (a² sin² t + b² cos² t)^{3/2} / (ab) of x = a cos t, y = b sin t at every contact
reported `ok`."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork import Status
from linkwork.geometry.profiles import EllipseProfile
from linkwork.model import CamContact, Mechanism, Prismatic, Revolute

A, B, R = 40.0, 25.0, 20.0  # semi-axes; the roller's radius lies between b²/a and a²/b


def rho(t):
    return (A**2 * np.sin(t) ** 2 + B**2 * np.cos(t) ** 2) ** 1.5 / (A * B)


def track():
    return Mechanism.build(
        name="roller in an elliptical track",
        points={"O": [0, 0], "M": [10.0, 0.0], "C": [0.0, B - R], "F": [0.0, -30.0]},
        links={"frame": ["O"], "track": ["O", "M"], "follower": ["C", "F"]},
        joints=[Revolute("O", "O", ("frame", "track")),
                Prismatic("F", "F", ("frame", "follower"), np.array([0.0, 1.0])),
                CamContact("K", ("track", "follower"), "ellipse", "roller", point="C", radius=R)],
        drivers=[{"joint": "O"}], profiles={"ellipse": EllipseProfile((0.0, 0.0), (A, B))})


def test_a_roller_bridging_a_hollow_is_not_followed_into_the_track():
    assert B**2 / A < R < A**2 / B
    phi = np.radians(np.linspace(60.0, 100.0, 81))
    sol = linkwork.solve(track(), phi)
    ok = sol.status == Status.OK
    quarter = np.isclose(phi, np.pi / 2, atol=1e-12)
    assert ok[phi <= np.pi / 2].all() and quarter.any()
    assert (sol.status[phi > np.pi / 2 + 1e-9] == Status.UNREACHABLE).all()
    assert np.isnan(sol.point("C").position[phi > np.pi / 2 + 1e-9]).all()
    # where ok, the track is at least as flat as the roller at the contact
    assert (rho(sol.joint("K")["u"][ok]) >= R).all()
    # at the quarter turn the roller's centre lies on the major axis: y = the chord's height
    # of the two mirror contacts, found from the reported contact and its mirror image
    u = sol.joint("K")["u"][quarter][0]
    P = np.array([A * np.cos(u), B * np.sin(u)])
    inward = -np.array([B * np.cos(u), A * np.sin(u)])
    centre = P + R * inward / np.hypot(*inward)
    assert centre[1] == pytest.approx(0.0, abs=1e-9)


def test_a_roller_smaller_than_every_hollow_is_never_cut():
    m = track()
    small = Mechanism.build(
        name="small roller", points={**m.points, "C": [0.0, B - 10.0]},
        links={"frame": ["O"], "track": ["O", "M"], "follower": ["C", "F"]},
        joints=[Revolute("O", "O", ("frame", "track")),
                Prismatic("F", "F", ("frame", "follower"), np.array([0.0, 1.0])),
                CamContact("K", ("track", "follower"), "ellipse", "roller", point="C", radius=10.0)],
        drivers=[{"joint": "O"}], profiles={"ellipse": EllipseProfile((0.0, 0.0), (A, B))})
    assert B**2 / A > 10.0
    sol = linkwork.solve(small, np.linspace(0, 2 * np.pi, 73))
    assert (sol.status == Status.OK).all()
