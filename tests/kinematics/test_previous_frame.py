"""Continuation from the previous frame of a drag: `solve(mech, ..., previous=earlier)`.

The march of the Newton-solved groups starts from that of a mechanism of the same structure
solved before, every point solved again for the new dimensions and checked as a march's step is
(`continuation._carry`); where a step fails, the march goes on from the last point taken, as a
march from the design position does after a rejected step. Checked here: the answers are those
of a fresh solve (to rounding: the Newton starting values differ) and of closed forms; a change
of assembly branch, which a Newton solve started from the previous frame's poses walks into,
is detected, reported (`continuation.carried`) and not taken.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork import Status
from linkwork.kinematics import continuation, solver
from linkwork.kinematics.branches import branch_schedule
from linkwork.model import Mechanism
from mechanism_texts import four_bar_text


def with_points(mech: Mechanism, **points) -> Mechanism:
    """`mech` with design points moved (as the workbench's drag builds each frame)."""
    new = {**mech.points, **{k: np.asarray(v, float) for k, v in points.items()}}
    return Mechanism.build(name=mech.name, points=new, links={ln.name: list(ln.points) for ln in mech.links},
                           joints=list(mech.joints), drivers=list(mech.drivers), frame=mech.frame,
                           length_unit=mech.length_unit)


def poses(sol) -> np.ndarray:
    return np.array([sol.pose_derivatives(ln)[0] for ln in sol.mechanism.link_names])


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def four_bar_hinge(m: Mechanism, u: np.ndarray) -> np.ndarray:
    """B of the four-bar O2–A–B–O4 at crank angles u, from the two circles about A and O4,
    on the side of A–O4 the drawing puts it (a crank-rocker keeps that side)."""
    O2, A0, B0, O4 = (m.points[k] for k in ("O2", "A", "B", "O4"))
    r = np.hypot(*(A0 - O2))
    a, b = np.hypot(*(B0 - A0)), np.hypot(*(B0 - O4))
    side = np.sign(_cross(O4 - A0, B0 - A0))
    A = O2 + r * np.stack([np.cos(u), np.sin(u)], -1)
    d = O4 - A
    L = np.hypot(d[:, 0], d[:, 1])
    x = (a * a - b * b + L * L) / (2 * L)
    h = np.sqrt(a * a - x * x)
    e = d / L[:, None]
    n = np.stack([-e[:, 1], e[:, 0]], -1)
    return A + x[:, None] * e + (side * h)[:, None] * n


def test_a_drag_of_a_newton_solved_four_bar_follows_the_closed_form(newton):
    base = linkwork.load_text(four_bar_text())
    assert {s.kind for s in solver.plan(base)} == {"driver", "generic"}
    u0 = base.driver_input_at_design(base.drivers[0])
    u = u0 + np.array([-2.5, -0.4, 0.0, 0.7, 2.0, 5.0])  # 5 rad: beyond half a turn
    previous = base
    linkwork.solve(base, u)
    for k in range(8):
        a = 2 * np.pi * k / 8
        m = with_points(base, B=base.points["B"] + 0.8 * np.array([np.cos(a), np.sin(a)]))
        sol = linkwork.solve(m, u, previous=previous)
        got = continuation.carried(m)
        assert got is not None and got.reason is None and got.carried == got.points > 2
        assert (sol.status == Status.OK).all()
        np.testing.assert_allclose(sol.point("B").position, four_bar_hinge(m, u), atol=1e-9)
        fresh = linkwork.solve(with_points(m), u)  # the same drawing, a new object: no march kept
        assert continuation.carried(fresh.mechanism) is None
        np.testing.assert_allclose(poses(sol), poses(fresh), rtol=0, atol=1e-12 * m.length_scale)
        previous = m


@pytest.mark.parametrize("point,radius", [("P45", 4.0), ("P23", 3.0)])  # P23 turns the design input
def test_a_drag_with_two_drivers_equals_the_fresh_solve(point, radius):
    base = linkwork.load("library:heusinger-valve-gear")
    design = np.array([base.driver_input_at_design(d) for d in base.drivers])
    at = (design + [0.4, 0.0])[None]
    linkwork.solve(base, at)
    previous = base
    for k in range(6):
        a = 2 * np.pi * k / 6
        m = with_points(base, **{point: base.points[point] + radius * np.array([np.cos(a), np.sin(a)])})
        at_m = np.array([[design[0] + 0.4, m.driver_input_at_design(m.drivers[1])]])
        sol = linkwork.solve(m, at_m, previous=previous)
        got = continuation.carried(m)
        assert got.reason is None and got.carried == got.points > 2
        fresh = linkwork.solve(with_points(m), at_m)
        assert sol.status[0] == fresh.status[0] == Status.OK
        np.testing.assert_allclose(poses(sol), poses(fresh), rtol=0, atol=1e-12 * m.length_scale)
        previous = m


def _naive(previous_sol, mech: Mechanism, u: float) -> tuple[bool, np.ndarray]:
    """A Newton solve of `mech`'s Newton group at u started from the previous frame's poses
    there (what a drag would do without checking the way from the design position): whether it
    converges, and the poses it converges to."""
    solvers = solver.plan(mech)
    gen = continuation._Generic(mech, solvers)
    names = [mech.link_names[i] for i in gen.links]
    start = np.array([[previous_sol.pose_derivatives(ln)[0, 0] for ln in names]])
    ok, q, *_ = continuation._attempt(mech, solvers, gen, branch_schedule(mech), np.array([[u]]),
                                      np.zeros(1), np.ones((1, 1)), np.ones((1, 1)), start)
    return bool(ok[0]), q[0]


@pytest.mark.parametrize("point,by,du,reachable", [
    ("E", (45.7, 14.5), 1.66, True),     # a large jump: the naive solve takes another branch
    ("G", (3.05, -10.98), -2.96, False),  # the design's branch no longer reaches u at all
])
def test_a_change_of_branch_is_detected_and_not_taken(point, by, du, reachable):
    base = linkwork.load("library:alt-eight-link")
    u = base.driver_input_at_design(base.drivers[0]) + du
    before = linkwork.solve(base, [u])
    assert before.status[0] == Status.OK
    m = with_points(base, **{point: base.points[point] + np.array(by)})
    fresh = linkwork.solve(with_points(m), [u])
    assert (fresh.status[0] != Status.UNREACHABLE) == reachable
    # the hazard: Newton from the previous frame's poses converges, to other poses
    converged, naive = _naive(before, m, u)
    gen = continuation._Generic(m, solver.plan(m))
    fresh_q = poses(fresh)[gen.links, 0]
    assert converged
    assert not np.allclose(naive, fresh_q, atol=1e-3 * m.length_scale, equal_nan=False)
    # the carried march notices, says where, and the answer is the fresh solve's
    sol = linkwork.solve(m, [u], previous=base)
    got = continuation.carried(m)
    assert got.reason is not None and got.carried < got.points
    assert "another assembly branch" in got.reason or "do not converge" in got.reason
    assert "marched again" in str(got)
    assert sol.status[0] == fresh.status[0]
    np.testing.assert_allclose(poses(sol), poses(fresh), rtol=0, atol=1e-9 * m.length_scale)


def test_a_mechanism_of_another_structure_is_not_carried_over():
    five = linkwork.load("library:alt-eight-link")
    other = linkwork.load("library:rosenauer-shaping-machine")
    u = five.driver_input_at_design(five.drivers[0]) + 0.5
    linkwork.solve(other, [0.1])
    sol = linkwork.solve(five, [u], previous=other)
    got = continuation.carried(five)
    assert got.carried == 0 and "another structure" in got.reason
    fresh = linkwork.solve(with_points(five), [u])
    np.testing.assert_allclose(poses(sol), poses(fresh), rtol=0, atol=1e-12 * five.length_scale)


def test_the_change_point_scan_below_a_newton_group_carries_the_march_too():
    """alt-ten-link: a dyad with change points below the Newton group, whose scan (`branches.
    branch_schedule`, before the solve's own guesses) marches that group over a turn; it starts
    from the previous frame's march as well, and the solve is the fresh one."""
    base = linkwork.load("library:alt-ten-link")
    u = base.driver_input_at_design(base.drivers[0]) + np.array([0.3, 1.0, -2.0])
    linkwork.solve(base, u)
    previous = base
    for k in range(3):
        m = with_points(base, O1=base.points["O1"] + 0.002 * base.length_scale * np.array([np.cos(k), np.sin(k)]))
        sol = linkwork.solve(m, u, previous=previous)
        got = continuation.carried(m)
        assert got is not None and got.reason is None and got.carried > 0
        fresh = linkwork.solve(with_points(m), u)
        assert np.array_equal(sol.status, fresh.status)
        np.testing.assert_allclose(poses(sol), poses(fresh), rtol=0, atol=1e-12 * m.length_scale)
        previous = m
