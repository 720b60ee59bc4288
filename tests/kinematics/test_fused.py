"""The fused pass (`kinematics.fused`: one compiled walk through the solution order per block of
samples) against the per-group path it replaces for mechanisms of drivers, RRR and RRP dyads:
the same statuses, poses, rates, condition numbers and error bounds, at ordinary samples, near
dead centres and change points, and where the chain cannot be assembled; cut into blocks or in
one; and its rates against finite differences of its own positions (an independent check)."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.kinematics import fused, kernels, solver
from linkwork.kinematics.solution import Status

FIVE = ["crank-rocker", "jansen-linkage", "watt-i-six-bar", "stephenson-iii-six-bar",
        "slider-crank-offset"]
# dead centres / limit positions (double-rocker, slider-crank), change points (parallelogram,
# Galloway's kite), unassembled ranges (double-rocker), two RRR and an RRP in one chain (Holst)
MORE = ["double-rocker", "parallelogram", "galloway-kite", "holst-mechanism", "five-bar"]


def _inputs(mech, n=6_001):
    """Inputs over two turns about the design input, and samples within 1e-9 … 1e-13 of every
    place where the status changes along them (the edges of unreachable ranges: the dyads'
    limit positions), found by bisection on the per-group path's statuses."""
    nd = len(mech.drivers)
    u0 = np.array([mech.driver_input_at_design(d) for d in mech.drivers])
    t = np.linspace(-2 * np.pi, 2 * np.pi, n)
    u = u0 + t[:, None] * (1.0 + 0.37 * np.arange(nd))  # several drivers: a slanted path
    if nd > 1:
        return u
    solver.FUSED = False
    try:
        st = linkwork.solve(mech, u).status == Status.UNREACHABLE
        near = []
        for i in np.flatnonzero(st[1:] != st[:-1]):
            a, b = u[i, 0], u[i + 1, 0]
            sa = st[i]
            for _ in range(60):
                mid = 0.5 * (a + b)
                if (linkwork.solve(mech, [mid]).status[0] == Status.UNREACHABLE) == sa:
                    a = mid
                else:
                    b = mid
            near += [a, b, a - 1e-13, b + 1e-13, a - 1e-9, b + 1e-9]
    finally:
        solver.FUSED = True
    return np.concatenate([u[:, 0], near])


def _both(mech, u, monkeypatch, **kw):
    monkeypatch.setattr(solver, "FUSED", True)
    a = linkwork.solve(mech, u, **kw)
    monkeypatch.setattr(solver, "FUSED", False)
    b = linkwork.solve(mech, u, **kw)
    monkeypatch.setattr(solver, "FUSED", True)
    return a, b


def _assert_same(a, b, mech):
    np.testing.assert_array_equal(a.status, b.status)
    # the same arithmetic in the same order: equal but for numba's contractions
    L = mech.length_scale
    np.testing.assert_array_equal(np.isnan(a._C), np.isnan(b._C))
    A, B = np.nan_to_num(a._C), np.nan_to_num(b._C)
    d = np.abs(A - B) / np.maximum(np.abs(B), L)
    assert d.max() <= 1e-13
    np.testing.assert_allclose(a.condition, b.condition, rtol=1e-12)
    np.testing.assert_allclose(a.errors, b.errors, rtol=1e-9)


@pytest.mark.parametrize("name", FIVE + MORE)
def test_fused_pass_gives_the_per_group_solution(name, monkeypatch):
    mech = linkwork.load(f"library:{name}")
    assert fused.tables(mech, solver.plan(mech)) is not None  # the fused pass is taken
    monkeypatch.setattr(kernels, "INTERPRETED_UP_TO", -1)  # compiled, both
    u = _inputs(mech)
    # several drivers on laws of time take their rates at a slanted path's inputs from no law:
    # given here, so that the rates are compared too
    kw = {} if len(mech.drivers) == 1 else {"velocities": [[1.0, 0.5]],
                                            "accelerations": [[0.2, -0.1]]}
    a, b = _both(mech, u, monkeypatch, **kw)
    _assert_same(a, b, mech)
    assert np.isfinite(a._C[1:]).any()
    if name in ("double-rocker", "slider-crank-offset"):
        assert (a.status == Status.UNREACHABLE).any() or name == "slider-crank-offset"
    # blocks cut the batch anywhere, in either path: the same solution
    monkeypatch.setattr(solver, "KERNEL_BLOCK", 997)
    c, d = _both(mech, u, monkeypatch, **kw)
    for x, whole in ((c, a), (d, b)):
        np.testing.assert_array_equal(x._C, whole._C)
        np.testing.assert_array_equal(x.status, whole.status)
        np.testing.assert_array_equal(x.errors, whole.errors)


@pytest.mark.parametrize("name", FIVE)
def test_fused_pass_interpreted_matches_the_per_group_path(name, monkeypatch):
    """A small batch runs the fused loops interpreted (no numba): the same solution."""
    mech = linkwork.load(f"library:{name}")
    monkeypatch.setattr(kernels, "INTERPRETED_UP_TO", 10**9)
    u = mech.driver_input_at_design(mech.drivers[0]) + np.linspace(-3.5, 3.5, 41)
    a, b = _both(mech, u, monkeypatch)
    _assert_same(a, b, mech)


@pytest.mark.parametrize("name", FIVE + ["double-rocker"])
def test_fused_rates_are_the_derivatives_of_its_positions(name, monkeypatch):
    """Velocities and accelerations of every point against central differences of the
    positions (five-point differences, step h in the input at unit input speed), at the samples marked ok; and every
    joint's point where both of its links carry it."""
    mech = linkwork.load(f"library:{name}")
    monkeypatch.setattr(kernels, "INTERPRETED_UP_TO", -1)
    u = mech.driver_input_at_design(mech.drivers[0]) + np.linspace(-np.pi, np.pi, 5_001)
    h = 2e-4
    sols = [linkwork.solve(mech, u + k * h, velocities=1.0) for k in (-2, -1, 0, 1, 2)]
    sol = sols[2]
    ok = np.logical_and.reduce([s.status == Status.OK for s in sols])
    # away from dead centres (at every point of the stencil): the differences' own error small
    ok &= np.logical_and.reduce([s.condition < 20 for s in sols])
    assert ok.sum() > 1_000
    L = mech.length_scale
    for p in mech.points:
        x = [s.point(p).position for s in sols]
        # five-point differences, O(h⁴)
        v = (x[0] - 8 * x[1] + 8 * x[3] - x[4]) / (12 * h)
        a = (-x[0] + 16 * x[1] - 30 * x[2] + 16 * x[3] - x[4]) / (12 * h**2)
        m = sol.point(p)
        np.testing.assert_allclose(m.velocity[ok], v[ok], rtol=1e-6, atol=1e-7 * L, err_msg=p)
        np.testing.assert_allclose(m.acceleration[ok], a[ok], rtol=1e-6, atol=1e-5 * L, err_msg=p)
    for j in mech.joints:
        if j.kind != "revolute":
            continue
        s = mech.points[j.point]
        P, Q = sol.point_on(j.links[0], s), sol.point_on(j.links[1], s)
        good = sol.status == Status.OK
        for q in ("position", "velocity", "acceleration"):
            np.testing.assert_allclose(getattr(P, q)[good], getattr(Q, q)[good],
                                       atol=1e-9 * L, err_msg=f"{j.name}.{q}")


def test_mechanisms_with_other_groups_keep_the_per_group_path():
    """Newton groups, cams, intermittent pairs, RPR dyads: no tables, today's path."""
    for name in ("alt-eight-link", "geneva-4", "swinging-block", "radial-roller-cam"):
        mech = linkwork.load(f"library:{name}")
        assert fused.tables(mech, solver.plan(mech)) is None, name


def test_the_loops_run_as_asked(monkeypatch):
    """`solve(compiled=...)` and `compiled_loops` choose the compiled or the interpreted loops
    whatever the batch's size (spied on); the default still goes by size."""
    mech = linkwork.load("library:crank-rocker")
    linkwork.solve(mech, [0.1])  # the branch scan is done once per mechanism, before
    ran = []
    for kind in ("_interpreted", "_compiled"):
        real = getattr(kernels, kind)
        monkeypatch.setattr(kernels, kind, lambda real=real, kind=kind: ran.append(kind) or real())
    many, few = np.linspace(0.0, 6.0, kernels.INTERPRETED_UP_TO + 1), np.array([0.2, 0.3])
    for kw, u, want in ((dict(compiled=True), few, "_compiled"),
                        (dict(compiled=False), many, "_interpreted"),
                        ({}, few, "_interpreted"), ({}, many, "_compiled")):
        ran.clear()
        a = linkwork.solve(mech, u, **kw)
        assert set(ran) == {want}, kw
    ran.clear()
    with linkwork.kinematics.compiled_loops(True):
        b = linkwork.solve(mech, u)
    assert set(ran) == {"_compiled"}
    np.testing.assert_array_equal(a.status, b.status)
