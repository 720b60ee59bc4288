"""The whole motion of the Galloway kite (Rosenauer §100: crank O2A = frame O2O4 = 40, coupler
AB = rocker BO4 = 70) runs through its fold — the crank on the frame, A on O4 — rather than
turning back there as at a limit, onto the continuous branch: B stays on the bisector of the
angle AO2O4 at the signed distance f(θ) = 40·cos(θ/2) − √(70² − (40·sin(θ/2))²) along the
direction θ/2 (the cosine rule in the kite's symmetric half), a formula smooth in θ that gives
the file's concave kite on the first turn and the convex one on the second; so the chain comes
back to its design position only after two turns, and the whole motion covers both. The sample
exactly at a fold is marked (its pose is not defined by the pairs), the others are ok."""

from __future__ import annotations

import numpy as np

import linkwork
from linkwork import Status
from linkwork.kinematics.motion import input_limits


def _kite_B(theta: np.ndarray) -> np.ndarray:
    half = theta / 2
    f = 40 * np.cos(half) - np.sqrt(70 ** 2 - (40 * np.sin(half)) ** 2)
    return f[:, None] * np.c_[np.cos(half), np.sin(half)]


def test_the_kite_is_a_crank_and_its_whole_motion_covers_two_turns():
    mech = linkwork.load("library:galloway-kite")
    assert input_limits(mech) is None  # the fold is no limit
    sol = linkwork.whole_motion(mech)
    u = sol.inputs[:, 0]
    u0 = mech.driver_input_at_design(mech.drivers[0])
    assert u[0] == u0 and abs(u[-1] - u[0] - 4 * np.pi) < 1e-12
    np.testing.assert_allclose(np.diff(u), np.radians(1.0), rtol=1e-12)
    # the folds at θ ≡ 0 (mod 2π): 360° and 720° are samples here (the design is at 100°)
    fold = np.abs((u + np.pi) % (2 * np.pi) - np.pi) < 1e-9
    assert fold.sum() == 2
    assert (sol.status[fold] != Status.OK).all()
    assert (sol.status[~fold] != Status.UNREACHABLE).all()
    good = ~fold
    th = sol.link("crank").angle  # the crank's angle, continuous over both turns
    np.testing.assert_allclose(th[good] - th[0], (u - u0)[good], atol=1e-12)
    B = sol.point("B").position
    np.testing.assert_allclose(B[good], _kite_B(th[good]), atol=1e-9 * 100)
    # the chain is back at its design position after two turns, not after one
    np.testing.assert_allclose(B[-1], B[0], atol=1e-9)
    one_turn = np.flatnonzero(np.isclose(u - u0, 2 * np.pi, atol=1e-12))[0]
    assert np.hypot(*(B[one_turn] - B[0])) > 50  # the convex kite: B at 88.6, not 37.2, from O2


def test_the_kite_passes_the_fold_continuously():
    """Next to each fold B is within a step's travel of the fold's limit on the continuous branch
    (110, 0) at the first (A = O4 and B beyond it) and (−30, 0) at the second, where the other
    assembly would put it 140 away."""
    sol = linkwork.whole_motion(linkwork.load("library:galloway-kite"))
    u = sol.inputs[:, 0]
    B = sol.point("B").position
    folds = np.flatnonzero(np.abs((u + np.pi) % (2 * np.pi) - np.pi) < 1e-9)
    speed = np.hypot(*sol.point("B").velocity.T) / np.pi  # mm per radian at 30 rpm (π rad/s)
    for k, limit in zip(folds, ([110.0, 0.0], [-30.0, 0.0])):
        for n in (k - 1, k + 1):
            assert np.hypot(*(B[n] - limit)) <= 1.01 * np.radians(1.0) * np.nanmax(speed[k - 2:k + 3])
