"""The compiled loops of `kinematics.kernels` and the same loops interpreted (small batches)
give the same solution: one source, two executions, held to each other on the lower-pair
library at random inputs, and across the size that switches between them."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.kinematics import kernels
from linkwork.kinematics.branches import branch_schedule
from linkwork.kinematics.solver import plan

LIBRARY = ["crank-rocker", "double-rocker", "jansen-linkage", "watt-i-six-bar",
           "stephenson-iii-six-bar", "slider-crank-offset", "pmks-stephenson-iii"]


def _solve(mech, u, monkeypatch, interpreted: bool):
    monkeypatch.setattr(kernels, "INTERPRETED_UP_TO", 10**9 if interpreted else -1)
    sol = linkwork.solve(mech, u)
    points = {p: np.stack([sol.point(p).position, sol.point(p).velocity,
                           sol.point(p).acceleration]) for p in mech.points}
    return sol, points


@pytest.mark.parametrize("name", LIBRARY)
def test_interpreted_and_compiled_loops_agree(name, monkeypatch):
    mech = linkwork.load(f"library:{name}")
    assert any(s.compiled for s in plan(mech))  # the loops are in use here
    u = np.random.default_rng(7).uniform(-np.pi, np.pi, (40, len(mech.drivers)))
    a, pa = _solve(mech, u, monkeypatch, interpreted=True)
    b, pb = _solve(mech, u, monkeypatch, interpreted=False)
    np.testing.assert_array_equal(a.status, b.status)
    ok = a.status == 0
    L = mech.length_scale
    for p in mech.points:
        scale = L * np.array([1.0, 1.0, 1.0])[:, None, None] + np.abs(pb[p])
        np.testing.assert_array_less(np.abs(pa[p] - pb[p])[:, ok] / scale[:, ok], 1e-12)
    np.testing.assert_allclose(a.errors[ok], b.errors[ok], rtol=1e-9)
    np.testing.assert_allclose(a.condition[ok], b.condition[ok], rtol=1e-9)


def test_the_switch_is_by_batch_size(monkeypatch):
    """Below and above the limit: the interpreted and the compiled loops run (spied on)."""
    mech = linkwork.load("library:crank-rocker")
    branch_schedule(mech)  # its scan of 2 049 inputs is done once per mechanism, before
    ran = []
    for kind in ("_interpreted", "_compiled"):
        real = getattr(kernels, kind)
        monkeypatch.setattr(kernels, kind, lambda real=real, kind=kind: ran.append(kind) or real())
    monkeypatch.setattr(kernels, "INTERPRETED_UP_TO", 5)
    linkwork.solve(mech, np.radians([10.0, 20.0]))
    assert set(ran) == {"_interpreted"}
    ran.clear()
    linkwork.solve(mech, np.radians(np.arange(6.0)))
    assert set(ran) == {"_compiled"}
