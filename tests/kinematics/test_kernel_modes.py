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
