"""The cam follower group solved in its own two unknowns (`kinematics.cam_group`) against the
generic path (six pose coordinates, Jacobian from jets), which shares no code with it but the
profiles: translating and oscillating followers with rollers, knife edges and flat faces, on
an eccentric disc and on a random spline cam, positions to fourth derivatives."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from higher_pair_mechanisms import eccentric
from linkwork.kinematics import cam_group, groups, solver
from linkwork.model import CamContact, Mechanism, Prismatic, Revolute
from linkwork.geometry.profiles import SplineProfile

PHI = np.radians(np.arange(0.0, 360.0, 7.0))


# the input's rates: a driver that speeds up (and its acceleration changes), so that the terms
# of the cam's and the base's accelerations enter the follower's rates
RATES = dict(velocities=1.3, accelerations=0.7, jerks=-0.4, snaps=0.25)


def _generic(monkeypatch, mech, inputs, order):
    monkeypatch.setattr(cam_group, "recognise", lambda mech, group: None)
    solver.plan.cache_clear() if hasattr(solver.plan, "cache_clear") else None
    try:
        return linkwork.solve(mech, inputs, order=order, **RATES)
    finally:
        monkeypatch.undo()
        solver.plan.cache_clear() if hasattr(solver.plan, "cache_clear") else None


def _rocker(follower: str) -> Mechanism:
    """A lever pivoted at H carrying a roller / knife at C, or a flat face through C, on a
    random smooth spline cam about O."""
    rng = np.random.default_rng(7)
    t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    r = 30.0 + rng.uniform(-3.0, 3.0, t.size)
    cam = SplineProfile(np.column_stack([r * np.cos(t), r * np.sin(t)]), closed=True)
    H = np.array([60.0, 10.0])
    u = float(cam.nearest(np.array([0.0, 60.0])))  # touch near the top of the cam
    D = cam.derivatives(np.array(u), 1)
    n = np.array([-D[1][1], D[1][0]]) / np.hypot(*D[1])
    n = n if n @ D[0] > 0 else -n  # outwards
    rho = 6.0 if follower == "roller" else 0.0
    C = D[0] + rho * n
    axis = D[1] / np.hypot(*D[1])
    return Mechanism.build(
        name=f"rocker, {follower}", points={"O": [0, 0], "M": [5.0, 0.0], "H": H, "C": C},
        links={"frame": ["O", "H"], "cam": ["O", "M"], "lever": ["H", "C"]},
        joints=[Revolute("O", "O", ("frame", "cam")), Revolute("H", "H", ("frame", "lever")),
                CamContact("K", ("cam", "lever"), "cam", follower, point="C", radius=rho,
                           axis=axis if follower == "flat" else None)],
        drivers=[{"joint": "O"}], profiles={"cam": cam})


def _random_cam(seed: int = 7) -> SplineProfile:
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    r = 30.0 + rng.uniform(-3.0, 3.0, t.size)
    return SplineProfile(np.column_stack([r * np.cos(t), r * np.sin(t)]), closed=True)


def _touching(cam, at: np.ndarray, rho: float) -> np.ndarray:
    """The centre of a roller of radius ρ (the tip of a knife for ρ = 0) touching `cam` from
    outside at the profile point nearest to `at`."""
    u = float(cam.nearest(at))
    D = cam.derivatives(np.array(u), 1)
    n = np.array([-D[1][1], D[1][0]]) / np.hypot(*D[1])
    return D[0] + rho * (n if n @ D[0] > 0 else -n)


def _on_arm(follower: str, lower: str) -> Mechanism:
    """The cam stands still (a track on the frame); the follower's hinge (`lower` = 'hinge') or
    guide ('guide') is carried by a crank turning about O, so the base moves: the terms of the
    base's motion in the rates."""
    cam = _random_cam(11)
    rho = 5.0 if follower == "roller" else 0.0
    C = _touching(cam, np.array([8.0, 60.0]), rho)
    H = np.array([30.0, 40.0])
    low = (Revolute("H", "H", ("arm", "lever")) if lower == "hinge" else
           Prismatic("H", "H", ("arm", "lever"), C / np.hypot(*C)))
    t = cam.derivatives(np.array(float(cam.nearest(C))), 1)[1]
    return Mechanism.build(
        name=f"{follower} on an arm's {lower}", points={"O": [0, 0], "H": H, "C": C},
        links={"frame": ["O"], "arm": ["O", "H"], "lever": ["H", "C"]},
        joints=[Revolute("O", "O", ("frame", "arm")), low,
                CamContact("K", ("frame", "lever"), "cam", follower, point="C", radius=rho,
                           axis=t / np.hypot(*t) if follower == "flat" else None)],
        drivers=[{"joint": "O"}], profiles={"cam": cam})


def _sliding_cam(follower: str) -> Mechanism:
    """A cam that translates (a wedge cam on a slider driven along x, with a drawn rotation of
    nothing): the cam's origin moves, its angle does not; a rocker hinged on the frame."""
    x = np.linspace(-60.0, 60.0, 13)
    y = 10.0 + 6.0 * np.sin(x / 17.0) + 0.02 * x
    cam = SplineProfile(np.column_stack([x, y]))
    rho = 4.0 if follower == "roller" else 0.0
    C = _touching(cam, np.array([2.0, 30.0]), rho)
    if C[1] < 10:
        C = C + 2 * rho * np.array([0.0, 1.0])
    return Mechanism.build(
        name=f"sliding cam, {follower}", points={"S": [0, -20.0], "H": [45.0, 25.0], "C": C},
        links={"frame": ["S", "H"], "slider": ["S"], "lever": ["H", "C"]},
        joints=[Prismatic("S", "S", ("frame", "slider"), np.array([1.0, 0.0])),
                Revolute("H", "H", ("frame", "lever")),
                CamContact("K", ("slider", "lever"), "cam", follower, point="C", radius=rho)],
        drivers=[{"joint": "S"}], profiles={"cam": cam})


CASES = [("translating roller", lambda: eccentric("roller", offset=4.0)),
         ("translating knife", lambda: eccentric("knife", offset=-3.0)),
         ("translating flat", lambda: eccentric("flat")),
         ("rocker roller", lambda: _rocker("roller")),
         ("rocker knife", lambda: _rocker("knife")),
         ("rocker flat", lambda: _rocker("flat")),
         ("arm hinge roller", lambda: _on_arm("roller", "hinge")),
         ("arm hinge knife", lambda: _on_arm("knife", "hinge")),
         ("arm guide roller", lambda: _on_arm("roller", "guide")),
         ("arm guide knife", lambda: _on_arm("knife", "guide")),
         ("arm hinge flat", lambda: _on_arm("flat", "hinge")),
         ("arm guide flat", lambda: _on_arm("flat", "guide")),
         ("sliding roller", lambda: _sliding_cam("roller")),
         ("sliding knife", lambda: _sliding_cam("knife"))]


@pytest.mark.parametrize("name,build", CASES, ids=[c[0] for c in CASES])
def test_two_unknowns_equal_the_generic_path(monkeypatch, name, build):
    mech = build()
    plan = solver.plan(mech)
    assert any(s.cam is not None for s in plan)  # the fast path is the one under test
    phi = (PHI if name.startswith("translating") else np.linspace(-12.0, 12.0, 41)
           if name.startswith("sliding") else np.radians(np.arange(-20.0, 20.0, 1.0)))
    fast = linkwork.solve(mech, phi, order=4, **RATES)
    slow = _generic(monkeypatch, build(), phi, 4)
    # the same samples assemble (ok or singular may differ near the error bound's tolerance:
    # the two paths' condition numbers are of different systems)
    assert ((fast.status == 2) == (slow.status == 2)).all()
    ok = fast.status == 0
    assert ok.sum() > 0.8 * phi.size
    L = mech.length_scale
    link = "follower" if name.startswith("translating") else "lever"
    Df, Ds = fast.pose_derivatives(link), slow.pose_derivatives(link)
    for k in range(5):
        np.testing.assert_allclose(Df[k][ok], Ds[k][ok], rtol=0, atol=1e-9 * L * 10**k,
                                   err_msg=f"order {k}")
    for key in ("u", "pressure_angle", "sliding_velocity", "profile_speed"):
        np.testing.assert_allclose(fast.joint("K")[key][ok], slow.joint("K")[key][ok],
                                   rtol=1e-9, atol=1e-9 * L, err_msg=key)
