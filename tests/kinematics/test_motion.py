"""Whole motion, limit positions, unreachable and singular samples, against closed forms."""

import numpy as np
import pytest

import linkwork
from linkwork import Status
from mechanism_texts import four_bar_text

ROCKER_DRIVEN = four_bar_text(name="four-bar driven by its rocker", rocker_points=("O4", "B"),
                              driver="O4", speed="1 rad/s")

a, b = 10.0, np.hypot(30, 20)            # crank, coupler
c, d = np.hypot(10, 30), 40.0            # rocker O4B, frame O2O4


def _rocker_angle_for(dist_o2b: float) -> float:
    """Angle of O4→B (from the x-axis) at which |O2 B| = dist, B above the frame (cosine law)."""
    cos_psi = (c * c + d * d - dist_o2b ** 2) / (2 * c * d)
    return np.pi - np.arccos(cos_psi)


def test_rocker_limits_are_where_crank_and_coupler_align():
    mech = linkwork.load_text(ROCKER_DRIVEN)
    from linkwork.kinematics.motion import input_limits
    lo, hi = input_limits(mech)
    # limit positions: crank and coupler stretched (|O2B| = a + b) or folded (|O2B| = b − a)
    expected = sorted([_rocker_angle_for(a + b), _rocker_angle_for(b - a)])
    assert [lo, hi] == pytest.approx(expected, abs=1e-9)


def test_whole_motion_of_rocker_goes_back_and_forth():
    mech = linkwork.load_text(ROCKER_DRIVEN)
    sol = linkwork.whole_motion(mech)
    u = sol.input
    assert u[0] == pytest.approx(u[-1])
    assert (sol.status != Status.UNREACHABLE).all()
    omega = sol.link("rocker").omega
    # forward to the upper limit, back to the lower one, forward again to the design position
    changes = np.flatnonzero(np.diff(np.sign(omega)))
    assert len(changes) == 2
    # the limit samples are dead positions of the driven dyad
    assert (sol.status[[changes[0], changes[1]]] == Status.SINGULAR).all() or \
        (sol.status[[changes[0] + 1, changes[1] + 1]] == Status.SINGULAR).all()


def test_crank_whole_motion_is_one_turn():
    sol = linkwork.whole_motion(linkwork.load("library:crank-rocker"))
    assert len(sol) == 361
    assert sol.input[-1] - sol.input[0] == pytest.approx(2 * np.pi)
    np.testing.assert_allclose(sol.point("B").position[0], sol.point("B").position[-1], atol=1e-9)


def test_unreachable_samples_are_marked_not_invented():
    mech = linkwork.load_text(ROCKER_DRIVEN)
    sol = linkwork.solve(mech, np.radians([110.0, 0.0]))
    # at 0° the rocker tip B = (40 + c, 0) is farther than a + b from O2: cannot assemble
    assert 40 + c > a + b
    assert sol.status[1] == Status.UNREACHABLE and sol.status[0] == Status.OK
    assert np.isnan(sol.point("B").position[1]).all()
    assert np.isnan(sol.link("coupler").omega[1])


def test_change_point_is_flagged_singular():
    parallelogram = four_bar_text(name="four-bar driven by its rocker", B=(40, 10), driver="O2",
                                  speed="1 rad/s")
    mech = linkwork.load_text(parallelogram)
    sol = linkwork.solve(mech, np.radians([0.0, 45.0]))  # at 0° all four hinges are collinear
    assert sol.status[0] == Status.SINGULAR and sol.condition[0] > 1e8
    assert sol.status[1] == Status.OK


def test_condition_is_given_for_every_assembled_sample():
    sol = linkwork.whole_motion(linkwork.load("library:crank-rocker"))
    assert np.isfinite(sol.condition).all() and (sol.condition >= 1).all()


def test_exports_pandas_csv_parquet_agree(tmp_path):
    import pandas as pd
    sol = linkwork.solve(linkwork.load("library:crank-rocker"), np.radians([0.0, 90.0]))
    df = sol.to_pandas()
    np.testing.assert_array_equal(df["C.x"], sol.point("C").position[:, 0])
    np.testing.assert_array_equal(df["coupler.alpha"], sol.link("coupler").alpha)
    sol.to_parquet(tmp_path / "s.parquet")
    sol.to_csv(tmp_path / "s.csv")
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "s.parquet"), df)
    back = pd.read_csv(tmp_path / "s.csv")
    np.testing.assert_allclose(back["B.ay"], df["B.ay"], rtol=1e-15)
