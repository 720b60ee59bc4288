"""A carried march that fails a step marches across to the failed point and takes the previous
march up again beyond it (`continuation._carry_points`): every point the new march then holds
is the pose a fresh solve of the new mechanism finds at its input (the design's branch, checked
point by point against solves from scratch), and the answer is the fresh solve's."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.kinematics import continuation, solver
from linkwork.kinematics.contact import row_index
from linkwork.web.sources import moved


def lanes_agree_with_fresh_solves(m) -> int:
    """Every accepted point of `m`'s marches (links' rows) against a solve of a new object of
    the same drawing at the point's input (nothing carried); the number of points checked."""
    solvers = solver.plan(m)
    gen = continuation._Generic(m, solvers)
    names = {i: n for n, i in row_index(m).items()}
    rows = [(k, names[i]) for k, i in enumerate(gen.links) if names[i] in m.link_names]
    lanes = continuation._marches[(m, solvers)]
    design = m.driver_input_at_design(m.drivers[0])
    checked = 0
    for sense, lane in lanes.items():
        if not lane.lam:
            continue
        lam = np.array(lane.lam)
        fresh = linkwork.solve(moved(m, {}), (design + sense * lam / gen.weights[0])[:, None])
        for k, name in rows:
            got = np.array(lane.P)[:, k]
            want = fresh.pose_derivatives(name)[0]  # (orders, samples, 3): the poses
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-7 * m.length_scale)
        checked += lam.size
    return checked


def poses(sol) -> np.ndarray:
    return np.array([sol.pose_derivatives(ln)[0] for ln in sol.mechanism.link_names])


def test_a_step_failed_by_a_hair_is_marched_across_and_the_march_taken_up_again():
    # Proell–Schwabe valve gear, P12 moved by 0.1 mm: the old march's step at input 0.122
    # (near a pose at rest, where the smoothness test is tightest) fails for the new
    # dimensions by 0.1 %; the rest of the old march still serves
    base = linkwork.load("library:proell-schwabe-valve-gear")
    u = base.driver_input_at_design(base.drivers[0]) + 1.5 * np.pi
    linkwork.solve(base, [u])
    m = moved(base, {"P12": base.points["P12"] + np.array([0.1, 0.0])})
    sol = linkwork.solve(m, [u], previous=base)
    got = continuation.carried(m)
    assert got.reason is not None and got.gaps >= 1 and got.resumed > 0
    assert got.carried > got.points - 5
    assert "taken up again" in str(got)
    fresh = linkwork.solve(moved(m, {}), [u])
    assert sol.status[0] == fresh.status[0]
    np.testing.assert_allclose(poses(sol), poses(fresh), rtol=0, atol=1e-9 * m.length_scale)
    assert lanes_agree_with_fresh_solves(m) > 200


@pytest.mark.parametrize("point,by,du", [("E", (45.7, 14.5), 1.66)])
def test_a_march_taken_up_again_across_a_change_of_branch_stays_on_the_designs(point, by, du):
    # the old march's poses lead Newton onto another branch over part of the way: the steps
    # there fail, are marched across, and no point of the other branch is taken
    base = linkwork.load("library:alt-eight-link")
    u = base.driver_input_at_design(base.drivers[0]) + du
    linkwork.solve(base, [u])
    m = moved(base, {point: base.points[point] + np.array(by)})
    sol = linkwork.solve(m, [u], previous=base)
    got = continuation.carried(m)
    assert got.reason is not None and got.carried < got.points
    fresh = linkwork.solve(moved(m, {}), [u])
    np.testing.assert_allclose(poses(sol), poses(fresh), rtol=0, atol=1e-9 * m.length_scale)
    assert lanes_agree_with_fresh_solves(m) > 20
