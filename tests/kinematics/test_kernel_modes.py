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


@pytest.mark.parametrize("name", ["crank-rocker", "jansen-linkage", "slider-crank-offset"])
def test_point_rows_loop_matches_the_general_point_loop(name):
    """A point of a link (`kernels.point_motion_2`, rows of their own) against the same point
    given per sample (`kernels.point_motion`, the general loop), compiled both (equal but for
    numba's contractions), and against
    the link's pose derivatives in NumPy (r = R(θ)s, v = ṫ + ω ⊥r, a = ẗ + α ⊥r − ω² r)."""
    mech = linkwork.load(f"library:{name}")
    u = mech.driver_input_at_design(mech.drivers[0]) + np.linspace(-3.0, 3.0, 9001)
    sol = linkwork.solve(mech, u, compiled=True)
    L = mech.length_scale
    for p, s in mech.points.items():
        link = mech.point_owner[p]
        with kernels.compiled_loops(True):
            fast = sol.point_on(link, s)
            general = sol.point_on(link, np.broadcast_to(s, (len(u), 2)).copy())
        D = sol.pose_derivatives(link)
        c, sn = np.cos(D[0, :, 2]), np.sin(D[0, :, 2])
        r = np.stack([c * s[0] - sn * s[1], sn * s[0] + c * s[1]], axis=-1)
        perp = np.stack([-r[:, 1], r[:, 0]], axis=-1)
        w, al = D[1, :, 2][:, None], D[2, :, 2][:, None]
        numpy = (D[0, :, :2] + r, D[1, :, :2] + w * perp, D[2, :, :2] + al * perp - w * w * r)
        ok = sol.status == 0
        for q, ref in zip(("position", "velocity", "acceleration"), numpy):
            a, b = getattr(fast, q), getattr(general, q)
            scale = L + np.abs(b)
            np.testing.assert_array_less(np.abs(a - b)[ok] / scale[ok], 1e-13, err_msg=p)
            np.testing.assert_array_less(np.abs(a - ref)[ok] / (L + np.abs(ref))[ok], 1e-12,
                                         err_msg=p)


def test_sincos_is_the_c_librarys_to_two_ulps():
    """`kernels._sincos` (the drivers' cos and sin without a library call) against the C
    library's (Python's math), compiled and as Python, over inputs up to its limit and at
    multiples of π/4, where the reduction cancels; its three parts of π/2 against mpmath."""
    import math

    import mpmath

    mpmath.mp.prec = 200
    parts = kernels._PIO2_A, kernels._PIO2_B, kernels._PIO2_C
    assert abs(sum(mpmath.mpf(p) for p in parts) - mpmath.pi / 2) < mpmath.mpf(2) ** -120
    rng = np.random.default_rng(3)
    t = np.concatenate([rng.uniform(-s, s, 4000) for s in (1.0, 10.0, 1e3, 1e5)] +
                       [rng.uniform(-1, 1, 4000) * kernels.SINCOS_LIMIT,
                        np.arange(-2**19, 2**19, 997) * (np.pi / 4)])
    t = t[np.abs(t) <= kernels.SINCOS_LIMIT]
    ref_c = np.array([math.cos(x) for x in t])
    ref_s = np.array([math.sin(x) for x in t])
    # compiled, and its source run by Python (the interpreted loops take NumPy's cos and sin)
    for fn, idx in ((kernels._compiled()["_sincos"], slice(None)),
                    (kernels._sincos, slice(None, None, 7))):
        got = np.array([fn(x) for x in t[idx]])
        for k, ref in enumerate((ref_c[idx], ref_s[idx])):
            ulps = np.abs(got[:, k] - ref) / np.spacing(np.abs(ref))
            assert ulps.max() <= 2.0


def test_drivers_of_many_turns_take_the_library_sincos():
    """Beyond `SINCOS_LIMIT` the fused pass's driver runs sample by sample with the C
    library's cos and sin: the same crank as at the same angle less whole turns."""
    mech = linkwork.load("library:crank-rocker")
    u0 = mech.driver_input_at_design(mech.drivers[0])
    turns = 2 * np.pi * 200_000  # beyond the limit
    assert turns > kernels.SINCOS_LIMIT
    u = u0 + np.linspace(0.0, 2 * np.pi, 5001)
    with kernels.compiled_loops(True):
        a = linkwork.solve(mech, u)
        b = linkwork.solve(mech, u + turns)
    L = mech.length_scale
    for p in mech.points:
        # the angle itself carries the turns' rounding (ε·|θ| ≈ 3e-10 rad)
        np.testing.assert_allclose(b.point(p).position, a.point(p).position, atol=1e-8 * L)
