"""Large batches of the compiled kernels are solved in blocks of `solver.KERNEL_BLOCK` samples
(so that the work arrays stay that size): cut into blocks or solved whole, a batch gives the
same solution, across change points too (the branch signs are taken per block)."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.kinematics import kernels, solver


@pytest.mark.parametrize("name", ["parallelogram", "slider-crank-offset", "jansen-linkage",
                                  "watt-i-six-bar"])
def test_blocks_give_the_solution_of_one_batch(name, monkeypatch):
    mech = linkwork.load(f"library:{name}")
    assert all(s.compiled for s in solver.plan(mech))
    u = mech.driver_input_at_design(mech.drivers[0]) + np.linspace(-7.0, 7.0, 12_001)
    monkeypatch.setattr(kernels, "INTERPRETED_UP_TO", -1)  # the compiled loops in both
    whole = linkwork.solve(mech, u)
    monkeypatch.setattr(solver, "KERNEL_BLOCK", 5_000)  # blocks of 5 000, 5 000 and 2 001
    cut = linkwork.solve(mech, u)
    np.testing.assert_array_equal(cut.status, whole.status)
    L = mech.length_scale
    for p in mech.points:
        a, b = cut.point(p), whole.point(p)
        for q in ("position", "velocity", "acceleration"):
            np.testing.assert_allclose(getattr(a, q), getattr(b, q), rtol=1e-12, atol=1e-12 * L,
                                       err_msg=f"{p}.{q}")
    np.testing.assert_allclose(cut.condition, whole.condition, rtol=1e-12)
    np.testing.assert_allclose(cut.errors, whole.errors, rtol=1e-9)
