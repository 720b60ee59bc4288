"""A Newton-solved sample's status rests on its own error bound, not on the path Newton came by
(`groups.backward_error`).

Newton's final residual at a polished sample is rounding noise of the equations (0.3 … 3
ε·coordinates), and which value it takes depends on where Newton started: a march carried over
from a drag's previous frame, or marched afresh. Added to the error bound it moved samples of
the Proell–Schwabe valve gear, whose bounds lie near the tolerance, between ok and singular.
It now counts as the rounding every group's bound already carries. Checked here: the statuses
and bounds of the two paths agree; and the bound still holds where it matters, against the
50-digit reference of four-bars next to their dead centres solved by Newton's method
(`mp_reference`, as tests/kinematics/test_precision.py does for the closed forms).
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork import Status
from linkwork.kinematics import continuation, groups, solver
from linkwork.kinematics.precision import EPS, TOLERANCE, coordinate_size
from linkwork.web.sources import moved
from mechanism_texts import four_bar_text
from test_precision import _relative_errors

import mp_reference as R

pytestmark = pytest.mark.filterwarnings("ignore::linkwork.errors.LinkworkWarning")


@pytest.mark.parametrize("point, shift", [("P58", (0.2, 0.1)), ("P12", (0.1, 0.0)),
                                          ("P67", (0.3, 0.0))])
def test_statuses_do_not_depend_on_a_carried_march(point, shift):
    base = linkwork.load("library:proell-schwabe-valve-gear")
    u = linkwork.whole_motion(base).inputs[:, 0]
    x = base.points[point]
    where = {point: (x[0] + shift[0], x[1] + shift[1])}
    carried, fresh = moved(base, where), moved(base, where)
    a = linkwork.solve(carried, u, previous=base)
    b = linkwork.solve(fresh, u)
    assert continuation.carried(carried).carried > 0  # the march did start from base's
    assert continuation.carried(fresh) is None
    np.testing.assert_array_equal(a.status, b.status)
    assert ((a.status == Status.OK).sum(), (a.status == Status.SINGULAR).sum()) != (0, 0)
    # the bounds: κ and the sizes agree to rounding, no noise term is left
    np.testing.assert_allclose(a.errors, b.errors, rtol=1e-9)


def test_a_residual_above_rounding_is_counted():
    mech = linkwork.load("library:heusinger-valve-gear")
    L, level = mech.length_scale, groups.ROUNDING_RESIDUAL * EPS * coordinate_size(mech)
    r = np.array([0.0, 0.5, 1.0, 1.01, 1e3]) * level * L
    got = groups.backward_error(mech, np.append(r, np.nan))
    np.testing.assert_array_equal(got[:3], 0.0)
    np.testing.assert_allclose(got[3:5], r[3:] / L, rtol=1e-15)
    assert np.isnan(got[5])
    # the long-double polish (precision._newton) measures against its own unit roundoff
    ld = float(np.finfo(np.longdouble).eps)
    got = groups.backward_error(mech, r * ld / EPS, ld)
    np.testing.assert_array_equal(got[:3], 0.0)
    np.testing.assert_allclose(got[3:5], r[3:] * ld / EPS / L, rtol=1e-15)


def _rockers(count: int, seed: int = 5) -> list:
    """Random four-bars whose crank rocks (dead centres in its input), well drawn, no
    change-point chain; drawn at sizes 1e-3 … 1e4 (as test_precision's)."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        size = float(rng.choice([1e-3, 1.0, 37.5, 1e4]))
        P = [(0.0, 0.0)] + [tuple(size * rng.uniform(-1, 1, 2)) for _ in range(4)]
        d = [np.hypot(*np.subtract(P[i], P[j])) for i, j in ((0, 1), (1, 2), (2, 3), (0, 3), (1, 4))]
        s_, p_, q_, l_ = sorted(d[:4])
        if min(d) < 0.15 * size or abs(s_ + l_ - p_ - q_) < 1e-3 * size:
            continue
        if not R.fold_inputs(*P[:4]):
            continue
        mech = linkwork.load_text(four_bar_text(O2=P[0], A=P[1], B=P[2], O4=P[3],
                                                coupler_points={"C": P[4]}))
        if linkwork.solve(mech).condition[0] < 1e2:
            out.append(P)
    return out


@pytest.mark.parametrize("pts", _rockers(4))
def test_the_bound_of_newton_samples_holds_next_to_dead_centres(newton, pts):
    """Samples 1e-13 … 1e-1 rad before each dead centre the design's branch reaches (the
    condition number up to ~1e7), the dyad solved by Newton's method: where the bound claims
    digits the 50-digit reference has them, and an ok sample is right to the tolerance."""
    O2, A, B, O4, C = pts
    mech = linkwork.load_text(four_bar_text(O2=O2, A=A, B=B, O4=O4, coupler_points={"C": C}))
    assert any(s.kind == "generic" for s in solver.plan(mech))
    u0 = mech.driver_input_at_design(mech.drivers[0])
    w = 2.0
    checked = ok = 0
    for fold in R.fold_inputs(O2, A, B, O4):
        f = float(np.angle(np.exp(1j * float(fold))))  # the turn from the design, within ±π
        u = u0 + f - np.sign(f) * np.logspace(-13, -1, 13)
        sol = linkwork.solve(mech, u, velocities=np.full(u.shape, w))
        for n in range(len(u)):
            ref = R.four_bar(O2, A, B, O4, u[n], w, C=C, u0=u0)
            if ref is None or sol.status[n] == Status.UNREACHABLE:
                continue  # beyond the dead centre the design's branch reaches first
            err = _relative_errors(mech, sol, n, ref, w)
            if not np.isfinite(err):
                assert sol.status[n] == Status.SINGULAR
                continue
            assert err <= sol.errors[n] or sol.errors[n] >= 1e-2, (n, err, sol.errors[n])
            if sol.status[n] == Status.OK:
                assert err <= TOLERANCE
                ok += 1
            checked += 1
    assert checked >= 5 and ok >= 1
