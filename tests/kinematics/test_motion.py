"""Whole motion, limit positions, unreachable and singular samples, against closed forms."""

import numpy as np
import pytest

import linkwork
from linkwork import Status
from mechanism_texts import four_bar_text, slider_crank_text

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


# ---------------------------------------------------------------- limit positions, closed forms
SLIDER_DRIVEN = slider_crank_text(name="slider-crank driven at its slider", A=(0, 10),
                                  B=(np.sqrt(875.0), 5), driver="guide", speed=1)  # a 10, b 30, e 5


def _bisected_limits(mech):
    """The limits as the step-by-step definition finds them: the input scanned on 1441 points
    out to one turn (or 4 length scales) either side, each side's first sample that `solve`
    marks unreachable bracketed, and 60 bisection steps, one `solve` of one sample each."""
    d = mech.drivers[0]
    u0 = mech.driver_input_at_design(d)
    span = 4 * mech.length_scale if mech.joint(d.joint).kind == "prismatic" else 2 * np.pi
    grid = np.linspace(0.0, span, 1441)
    out = []
    for sign in (-1.0, 1.0):
        ok = linkwork.solve(mech, u0 + sign * grid, order=1).status != Status.UNREACHABLE
        k = int(np.argmin(ok))
        lo, hi = grid[k - 1], grid[k]
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if linkwork.solve(mech, np.array([u0 + sign * mid]), order=1).status[0] \
                    != Status.UNREACHABLE:
                lo = mid
            else:
                hi = mid
        out.append(u0 + sign * lo)
    return tuple(out)


def test_double_rocker_limits_from_the_cosine_rule():
    from linkwork.kinematics.motion import input_limits
    # frame d = 50, input a = 40, coupler b = 20, output c = 50: the input's limits are where
    # coupler and output stretch (|A O4| = b + c) or fold (|A O4| = c − b); cosine rule in
    # the triangle O2 A O4 for the input angle
    a_, b_, c_, d_ = 40.0, 20.0, 50.0, 50.0
    lo, hi = input_limits(linkwork.load("library:double-rocker"))
    expected = [np.arccos((a_**2 + d_**2 - D**2) / (2 * a_ * d_)) for D in (c_ - b_, b_ + c_)]
    assert [lo, hi] == pytest.approx(expected, abs=1e-12)


def test_slider_driven_slider_crank_limits():
    from linkwork.kinematics.motion import input_limits
    # crank 10, rod 30, guide 5 above the crank pivot: B at (x, 5) assembles while
    # b − a ≤ |O B| ≤ a + b, i.e. √(20² − 5²) ≤ x ≤ √(40² − 5²); the input is x − x_design.
    # The dyad counts as assembled down to h² = −1e-12·L1² (rounding at a limit position), which
    # here moves the limits outwards by some 7e-12: the tolerance is 1e-11
    lo, hi = input_limits(linkwork.load_text(SLIDER_DRIVEN))
    x0 = np.sqrt(875.0)
    assert [lo, hi] == pytest.approx([np.sqrt(375.0) - x0, np.sqrt(1575.0) - x0], abs=1e-11)
    assert lo < np.sqrt(375.0) - x0 and hi > np.sqrt(1575.0) - x0  # outwards, not inwards


@pytest.mark.parametrize("source", ["library:double-rocker", "library:hart-inversor",
                                    "library:pmks-stephenson-iii", "slider", "rocker"])
def test_limits_are_the_step_by_step_bisection_to_the_last_bit(source):
    from linkwork.kinematics.motion import input_limits
    mech = (linkwork.load_text(SLIDER_DRIVEN) if source == "slider" else
            linkwork.load_text(ROCKER_DRIVEN) if source == "rocker" else linkwork.load(source))
    assert input_limits(mech) == _bisected_limits(mech)
