"""Bounded solves: the continuation has a step budget (a clear `SolveError` where the poses
change too fast to follow), and inputs far out are reduced by the motion's period."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.errors import SolveError
from linkwork.io.files import resolve


def test_nearly_parallel_guides_end_in_a_clear_error():
    """The ellipsograph with guide B turned to [1, 1e-9]: both guides nearly horizontal, so AB
    (50 long, B held 40 above A's line) can hardly turn; following the rod's input would take
    steps of 1e-13. The budget ends it with the input where the march stopped."""
    _, text = resolve("library:ellipsograph")
    mech = linkwork.load_text(text.replace("axis = [0, 1]", "axis = [1, 1e-9]"))
    u0 = mech.driver_input_at_design(mech.drivers[0])
    with pytest.raises(SolveError, match="continuation steps"):
        linkwork.solve(mech, [u0 + np.radians(10.0)])


def test_far_inputs_are_reduced_by_the_period():
    """The Römer mechanism (gears 40 : 20) repeats after one turn of gear I: an input 1e9° out
    (2 777 777 turns and 280°) gives the poses of 280°, not a march of 1e9 degrees. Positions
    compared with the sample one period's multiple nearer; its own bound marks what the input's
    rounding (ε·1.7e7 rad) costs."""
    mech = linkwork.load("library:roemer-mechanism")
    L = mech.length_scale
    u0 = mech.driver_input_at_design(mech.drivers[0])
    far = u0 + np.radians(1e9)
    k = np.floor((far - u0) / (2 * np.pi))
    near = far - 2 * np.pi * k  # exact enough: the same rounding as the solver's reduction
    sol = linkwork.solve(mech, [far, near])
    assert (sol.status != linkwork.Status.UNREACHABLE).all()
    for p in mech.points:
        np.testing.assert_allclose(sol.point(p).position[0], sol.point(p).position[1], rtol=0,
                                   atol=1e-6 * L, err_msg=p)
    # the gears' angles are the turned ones, not reduced: gear II turns twice as fast, back
    w1 = sol.link("gear_1").angle
    w2 = sol.link("gear_2").angle
    np.testing.assert_allclose((w2[0] - w2[1]) / (w1[0] - w1[1]), -2.0, rtol=1e-9)
    assert sol.errors[0] > sol.errors[1]  # the far input's rounding is in its bound


def test_a_crawling_march_stops_long_before_its_budget(monkeypatch):
    """The same nearly parallel guides: the march's pace over its last `CRAWL_WINDOW` attempts
    cannot reach the input within the budget, so it stops then, not after all `MAX_ATTEMPTS`
    (each attempt of a higher pair costs milliseconds: the budget alone took tens of seconds)."""
    from linkwork.kinematics import continuation

    attempts = []
    settle = continuation._Lane.settle
    monkeypatch.setattr(continuation._Lane, "settle",
                        lambda self, *a: (attempts.append(1), settle(self, *a))[1])
    _, text = resolve("library:ellipsograph")
    mech = linkwork.load_text(text.replace("axis = [0, 1]", "axis = [1, 1e-9]"))
    u0 = mech.driver_input_at_design(mech.drivers[0])
    with pytest.raises(SolveError, match="would take more than 2000 continuation steps"):
        linkwork.solve(mech, [u0 + np.radians(10.0)])
    assert len(attempts) < continuation.MAX_ATTEMPTS / 4


def test_roller_centre_on_the_cam_axis_runs_through_its_branch_crossing():
    """The offset roller cam with its axis O drawn 1e-12 from the roller's centre C (found by
    scanning near-degenerate drawings): the disc's centre E turns about O at |OE| = R + ρ, so
    the roller touches the disc wherever the cam stands and the follower hardly moves. Where E
    passes C's height that motion crosses the other one (the follower thrown by 2·(E − C)_y):
    the tangent there grows from 1e-12, which the march took for a limit position and closed
    in on forever (SolveError). It now runs on; the follower's displacement s is the root
    nearest zero of |E(θ) − C − s·ŷ| = R + ρ, written out here."""
    _, text = resolve("library:offset-roller-cam")
    text = text.replace("O = [0, 0]", "O = [15.000000000001, 37.66961640367472]")
    mech = linkwork.load_text(text)
    u0 = mech.driver_input_at_design(mech.drivers[0])
    turn = np.linspace(-np.pi, np.pi, 13)
    sol = linkwork.solve(mech, u0 + turn)
    assert (sol.status != linkwork.Status.UNREACHABLE).all()
    O, E0, C0 = (np.array(mech.points[p], dtype=float) for p in ("O", "E", "C"))
    c, s = np.cos(turn), np.sin(turn)
    d = E0 - O
    w = O + np.stack([c * d[0] - s * d[1], s * d[0] + c * d[1]], axis=-1) - C0
    root = np.sqrt(w[:, 1] ** 2 - (w ** 2).sum(axis=1) + 38.0 ** 2)
    lift = np.where(np.abs(w[:, 1] - root) <= np.abs(w[:, 1] + root), w[:, 1] - root, w[:, 1] + root)
    np.testing.assert_allclose(sol.point("C").position[:, 1] - C0[1], lift, atol=1e-9 * mech.length_scale)
    np.testing.assert_allclose(sol.point("C").position[:, 0], C0[0], atol=1e-9 * mech.length_scale)
