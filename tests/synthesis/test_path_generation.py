"""Path generation (`linkwork.synthesis.path`): target points on the coupler curve of the
closed-form four-bar (test four_bar_by_hand) must be met (the engine, solving the written
file at the crank angles found, puts the coupler point on them to 1e-9); points that no
coupler curve passes through exactly get a least-squares four-bar whose reported error is the
engine's distance from them."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from four_bar_by_hand import B_LEN, four_bar
from linkwork.errors import InputError
from linkwork.kinematics import solve
from linkwork.synthesis.path import path_generator

TH = np.radians([0, 40, 80, 130, 180, 230])


def coupler_curve(theta):
    A, B = four_bar(theta)
    e = (B - A) / B_LEN
    return A + 1.0 * e + 1.2 * np.column_stack([-e[:, 1], e[:, 0]])


def engine_distance(gen, tmp_path):
    path = tmp_path / "path.toml"
    path.write_text(gen.linkage.mechanism_text())
    sol = solve(linkwork.load(path), gen.linkage.input_angles(), order=1)
    return np.hypot(*(sol.point("P").position - gen.targets).T)


@pytest.mark.parametrize("timing", [False, True])
def test_points_of_a_coupler_curve_are_met(timing, tmp_path):
    n = 5 if timing else 6
    T = coupler_curve(TH[:n])
    gen = path_generator(T, timing=TH[:n] if timing else None)
    assert gen.error < 1e-9
    assert engine_distance(gen, tmp_path).max() < 1e-9
    if timing:
        assert np.allclose(np.diff(gen.angles), np.diff(TH[:n]), atol=1e-12)
    c = gen.linkage.check
    assert c.pose_error < 1e-9


def test_least_squares_through_points_of_no_coupler_curve(tmp_path):
    t = np.radians(np.arange(0, 360, 30))
    T = np.column_stack([np.sign(np.cos(t)) * np.abs(np.cos(t)) ** 0.3, np.sign(np.sin(t)) * np.abs(np.sin(t)) ** 0.3])
    gen = path_generator(T, starts=4)
    d = engine_distance(gen, tmp_path)
    assert gen.error > 1e-6
    assert d.max() == pytest.approx(gen.error, rel=1e-9)


def test_bad_targets_are_refused():
    with pytest.raises(InputError, match="at least three"):
        path_generator([[0, 0], [1, 1]])
    with pytest.raises(InputError, match="timing"):
        path_generator([[0, 0], [1, 1], [2, 0]], timing=[0, 1])
