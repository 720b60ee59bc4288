"""Drivers on motion laws of time, solved at input values (`solver._law_rates`): the rates are
the law's at the time it takes those values, checked against the same mechanism solved at
those times (the law evaluated directly: the independent route). Where the law takes a value at
no single time, or several drivers' laws at no common time, the rates are not known: NaN and a
warning, the positions still solved. They were zero, silently (the workbench showed the
Heusinger valve gear at rest)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import linkwork
from linkwork.errors import LinkworkWarning
from linkwork.io import resolve
from linkwork.model.laws import PolynomialLaw

ROCKER = resolve("library:crank-rocker")[1]


def _with_law(coefficients, duration=1.0):
    text = ROCKER.replace('speed = "60 rpm"',
                          f'law = {{ type = "polynomial", coefficients = {list(coefficients)}, '
                          f'duration = {duration} }}')
    assert text != ROCKER
    return linkwork.load_text(text)


def _same_motion(a, b, mech):
    for p in mech.points:
        for what in ("position", "velocity", "acceleration"):
            x, y = getattr(a.point(p), what), getattr(b.point(p), what)
            scale = max(1.0, float(np.max(np.abs(y))))
            np.testing.assert_allclose(x, y, rtol=0, atol=1e-9 * scale, err_msg=f"{p} {what}")


def test_a_law_that_only_goes_forward_gives_its_rates_at_the_inputs():
    mech = _with_law([90, 200, 100])  # θ = 90° + 200°·t + 100°·t², forward over [0, 1]
    t = np.array([0.0, 0.1, 0.37, 0.8, 1.0])
    u = np.radians(90 + 200 * t + 100 * t ** 2)
    _same_motion(linkwork.solve(mech, u), linkwork.solve(mech, times=t), mech)


def test_the_time_of_a_value_is_the_laws_inverse():
    law = PolynomialLaw((1.0, 2.0, 3.0), 2.0)  # 1 + 2t + 3t², rising over [0, 2]
    t = np.array([0.0, 0.25, 1.0, 1.9, 2.0])
    np.testing.assert_allclose(law.time_of(1 + 2 * t + 3 * t ** 2), t, atol=1e-13)
    # the positive root of 3t² + 2t + (1 − v) = 0, written out
    v = 5.0
    assert law.time_of(np.array([v]))[0] == pytest.approx((-2 + np.sqrt(4 - 12 * (1 - v))) / 6,
                                                          abs=1e-13)
    assert np.isnan(law.time_of(np.array([0.5, 1 + 4 + 12 + 0.1]))).all()  # outside the span
    assert np.isnan(PolynomialLaw((0.0, 1.0, -1.0)).time_of(np.array([0.1]))).all()  # goes back


def test_a_law_that_goes_back_leaves_the_rates_unknown_and_says_so():
    mech = _with_law([90, 200, -200])  # forward to 140° at t = 0.5, then back to 90°
    u = np.radians([120.0])  # reached twice (t = 0.19 and 0.81): no single time
    with pytest.warns(LinkworkWarning, match="does not take the value at exactly one time"):
        sol = linkwork.solve(mech, u)
    assert np.isfinite(sol.point("C").position).all()
    assert np.isnan(sol.point("C").velocity).all() and np.isnan(sol.point("C").acceleration).all()


def test_a_linear_law_holds_its_speed_at_any_input():
    """A law of one speed at every time needs no time: the five-bar's two linear laws at inputs
    their laws never reach together get each driver's speed (the same as given explicitly)."""
    mech = linkwork.load("library:five-bar")
    speeds = [d.law.uniform_speed for d in mech.drivers]
    assert speeds == pytest.approx([2 * np.pi, np.pi])  # 360°/s and 180°/s in the file
    u = np.radians([[40.0, 40.0], [66.0, 98.0]])
    with warnings.catch_warnings():
        warnings.simplefilter("error", LinkworkWarning)  # no warning: nothing unknown
        a = linkwork.solve(mech, u)
    b = linkwork.solve(mech, u, velocities=[speeds], accelerations=[[0.0, 0.0]])
    _same_motion(a, b, mech)


def test_the_valve_gear_at_its_inputs_moves_as_at_its_times():
    mech = linkwork.load("library:heusinger-valve-gear")
    t = np.array([0.0, 51 / 360, 0.4, 0.77])
    by_time = linkwork.solve(mech, times=t)
    _same_motion(linkwork.solve(mech, by_time.inputs), by_time, mech)
    assert np.abs(by_time.point("P23").velocity).max() > 100  # not at rest
