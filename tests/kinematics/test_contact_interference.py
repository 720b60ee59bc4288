"""A roller inside an elliptical track (the track is the cam, turning about its centre; the
follower translates along the y-axis), the roller's radius between the track's smallest and
largest radius of curvature. Turning from the design position (the minor axis on the follower's
line), the contact runs towards the end of the major axis; at a quarter turn the major axis lies
on the follower's line and, by symmetry, the roller touches the track at two mirror points (it
bridges the hollow, too large to reach its bottom: radius of curvature there b²/a < r). Past the
quarter turn the contact followed on solves the pair's equations, but the roller then overlaps
the track at the mirror point: the motion goes on from the mirror contact instead (the contact
switches), never through the track.

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
    assert ok.all() and quarter.any()
    # past the quarter turn the roller touches the mirror point: the contact has jumped there
    u = sol.joint("K")["u"]
    x = A * np.cos(u) * np.cos(phi) - B * np.sin(u) * np.sin(phi)  # the contact, frame x
    after = phi > np.pi / 2 + 1e-9
    assert (x[phi < np.pi / 2 - 1e-9] * x[after].mean() < 0).all()
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


def _centre_height(phi: float) -> float:
    """The roller's centre on the follower's line (frame y) where the roller of radius R inside
    the track, turned by φ, touches it from inside at the top: the largest s at which the
    point s·e (e the line's direction in the track's coordinates) is R from the ellipse. The
    distance by the foot of the perpendicular (a grid, then Newton's method on
    (c(t) − p)·c′(t) = 0), s by bisection: nothing of linkwork's."""
    e = np.array([np.sin(phi), np.cos(phi)])  # R(−φ)·(0, 1)
    grid = np.linspace(0, 2 * np.pi, 4001)[:-1]

    def dist(s):
        p = s * e
        t = grid[np.argmin(np.hypot(A * np.cos(grid) - p[0], B * np.sin(grid) - p[1]))]
        for _ in range(30):
            c, d1 = np.array([A * np.cos(t), B * np.sin(t)]), np.array([-A * np.sin(t), B * np.cos(t)])
            d2 = -np.array([A * np.cos(t), B * np.sin(t)])
            t -= ((c - p) @ d1) / (d1 @ d1 + (c - p) @ d2)
        return float(np.hypot(A * np.cos(t) - p[0], B * np.sin(t) - p[1]))

    # from the top of the track's inside downwards, the first s where the roller fits
    hi = 1.0 / np.hypot(e[0] / A, e[1] / B) - R  # where it meets the track along the line
    ss = np.linspace(hi, 0.0, 400)
    k = next(i for i, s in enumerate(ss) if dist(s) >= R)
    lo_, hi_ = ss[k], ss[k - 1] if k else ss[k]
    for _ in range(80):
        mid = 0.5 * (lo_ + hi_)
        lo_, hi_ = (mid, hi_) if dist(mid) >= R else (lo_, mid)
    return 0.5 * (lo_ + hi_)


def test_the_motion_goes_on_past_the_two_point_contact():
    """A whole turn of the track: the roller is picked up again past each two-point contact
    (the continuation stops there), and its height is the closed form's at every sample."""
    phi = np.radians(np.arange(0.0, 360.0, 7.5))
    sol = linkwork.solve(track(), phi)
    assert (sol.status == Status.OK).all()
    want = np.array([_centre_height(p) for p in phi])
    np.testing.assert_allclose(sol.point("C").position[:, 1], want, atol=1e-7)
    # where ok, the track is at least as flat as the roller at the contact
    assert (rho(sol.joint("K")["u"]) >= R - 1e-9).all()


def _distance_to_track(p: np.ndarray) -> float:
    """Distance from p (track coordinates) to the ellipse: a grid, then Newton's method on the
    foot of the perpendicular."""
    grid = np.linspace(0, 2 * np.pi, 4001)[:-1]
    t = grid[np.argmin(np.hypot(A * np.cos(grid) - p[0], B * np.sin(grid) - p[1]))]
    for _ in range(30):
        c, d1 = np.array([A * np.cos(t), B * np.sin(t)]), np.array([-A * np.sin(t), B * np.cos(t)])
        t -= ((c - p) @ d1) / (d1 @ d1 - (c - p) @ c)
    return float(np.hypot(A * np.cos(t) - p[0], B * np.sin(t) - p[1]))


def test_a_rocker_in_the_track_goes_on_past_the_two_point_contact():
    """The follower a lever hinged off the track's centre (its roller's centre on a circle): the
    contact is sought afresh past each two-point contact too. Every sample solved is a place
    the roller can be (inside the track, R from it, on its circle about the hinge), and the
    lever swings without jumps."""
    H = np.array([-60.0, B - R])
    m = Mechanism.build(
        name="rocker in an elliptical track",
        points={"O": [0, 0], "M": [10.0, 0.0], "C": [0.0, B - R], "H": H},
        links={"frame": ["O", "H"], "track": ["O", "M"], "lever": ["C", "H"]},
        joints=[Revolute("O", "O", ("frame", "track")), Revolute("H", "H", ("frame", "lever")),
                CamContact("K", ("track", "lever"), "ellipse", "roller", point="C", radius=R)],
        drivers=[{"joint": "O"}], profiles={"ellipse": EllipseProfile((0.0, 0.0), (A, B))})
    phi = np.radians(np.arange(0.0, 360.0, 5.0))
    sol = linkwork.solve(m, phi)
    assert (sol.status == Status.OK).mean() > 0.9
    ok = sol.status == Status.OK
    C = sol.point("C").position
    np.testing.assert_allclose(np.hypot(*(C[ok] - H).T), 60.0, atol=1e-9)
    for p, f in zip(C[ok], phi[ok]):
        local = np.array([[np.cos(f), np.sin(f)], [-np.sin(f), np.cos(f)]]) @ p
        assert local[0] ** 2 / A**2 + local[1] ** 2 / B**2 < 1  # inside the track
        assert _distance_to_track(local) == pytest.approx(R, abs=1e-7)
    swing = np.degrees(np.abs(np.diff(sol.pose_derivatives("lever")[0, ok, 2])))
    assert swing.max() < 10.0
