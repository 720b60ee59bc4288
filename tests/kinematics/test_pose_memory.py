"""`solver._pose_memory`: a large solve takes the pose memory of the last one once no solution
refers to it, and never the memory of a solution still alive."""

from __future__ import annotations

import gc

import numpy as np

import linkwork
from linkwork.kinematics import solver


def test_live_solutions_keep_their_memory_and_dropped_ones_lend_it(monkeypatch):
    monkeypatch.setattr(solver, "SPARE_FROM", 1)  # every pose array through the spare
    monkeypatch.setattr(solver, "_SPARE", [None])
    mech = linkwork.load("library:crank-rocker")
    u = np.linspace(0.0, 6.0, 5000)
    a = linkwork.solve(mech, u)
    expect = a._C.copy()
    b = linkwork.solve(mech, u + 0.1)  # a is alive: fresh memory
    assert not np.shares_memory(a._C, b._C)
    np.testing.assert_array_equal(a._C, expect)  # untouched by b's solve
    spare = solver._SPARE[0].__array_interface__["data"][0]  # b's memory (an address only)
    del b
    gc.collect()
    c = linkwork.solve(mech, u + 0.2)  # b's memory, no one refers to it any more
    assert c._C.base.__array_interface__["data"][0] == spare
    assert not np.shares_memory(c._C, a._C)
    np.testing.assert_array_equal(a._C, expect)
    # the same answer as in fresh memory (every row written, the frame's zeroed)
    monkeypatch.setattr(solver, "SPARE_FROM", 1 << 60)
    fresh = linkwork.solve(mech, u + 0.2)
    np.testing.assert_array_equal(np.isnan(c._C), np.isnan(fresh._C))
    np.testing.assert_array_equal(np.nan_to_num(c._C), np.nan_to_num(fresh._C))


def test_a_view_of_a_point_or_link_keeps_nothing_and_a_kept_pose_keeps_its_memory(monkeypatch):
    """Reading points copies out of the pose array: dropping the solution frees it for the
    next solve; holding on to its pose array (a view) does not."""
    monkeypatch.setattr(solver, "SPARE_FROM", 1)
    monkeypatch.setattr(solver, "_SPARE", [None])
    mech = linkwork.load("library:crank-rocker")
    u = np.linspace(0.0, 6.0, 5000)
    sol = linkwork.solve(mech, u)
    C = sol.point("C").position
    keep = sol._C[0]  # a view of the pose memory
    del sol
    gc.collect()
    other = linkwork.solve(mech, u + 1.0)
    assert not np.shares_memory(other._C, keep)
    assert not np.shares_memory(other._C, C)
