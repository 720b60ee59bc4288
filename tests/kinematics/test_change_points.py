"""Assembly branches across change points (`linkwork.kinematics.branches`).

Expectations: the change points of four-bars whose lengths satisfy s + l = p + q are the crank
angles where all four pivots fall on one line (closed form); the motion through them is checked
against finite differences of positions (velocities continuous, no switch of assembly)."""

import math

import numpy as np
import pytest

import linkwork
from linkwork.errors import LinkworkWarning
from linkwork.kinematics.branches import Schedule, branch_schedule
from linkwork.kinematics.solution import Status
from mechanism_texts import four_bar_from_lengths, four_bar_text, joint, mechanism_text, revolute


def _four_bar(crank: float, coupler: float, follower: float, frame: float, theta_deg: float) -> str:
    """A four-bar drawn with the crank at θ (degrees) and the hinge B left of A→O4."""
    return four_bar_from_lengths(frame, crank, coupler, follower, theta_deg, speed="1 rad/s",
                                 links=("frame", "crank", "coupler", "follower"))


KITE = (20.0, 20.0, 40.0, 40.0)  # crank = coupler, follower = frame: s + l = p + q


@pytest.mark.parametrize("name", ["parallelogram", "antiparallelogram"])
def test_change_points_are_where_the_pivots_are_collinear(name):
    mech = linkwork.load(f"library:{name}")
    ((group, sch),) = branch_schedule(mech).items()
    assert group.links == ("coupler", "follower")
    # crank along the frame line, towards O4 and away from it
    got = np.sort(np.mod(np.array(sch.change_points) + 1e-6, np.pi)) - 1e-6
    np.testing.assert_allclose(got, [0.0, 0.0], atol=1e-7)
    assert sch.period == pytest.approx(2 * np.pi)


def test_kite_change_points_and_continuous_motion_over_two_turns():
    mech = linkwork.load_text(_four_bar(*KITE, theta_deg=60))
    ((_, sch),) = branch_schedule(mech).items()
    np.testing.assert_allclose(np.sort(np.mod(np.array(sch.change_points) + 1e-6, 2 * np.pi)) - 1e-6,
                               [0.0, np.pi], atol=1e-7)
    h = np.radians(0.25)
    u = math.radians(60) + h * np.arange(2 * 1440 + 1)  # two turns, through four change points
    sol = linkwork.solve(mech, u, velocities=np.ones(u.shape))
    singular = sol.status == Status.SINGULAR
    distance = np.minimum(np.mod(u, np.pi), np.pi - np.mod(u, np.pi))
    at_change = distance < 1e-9
    # singular at the change points and next to them, where the error bound exceeds the
    # tolerance (`precision`: within two degrees here; more on the second turn, whose angles
    # round to more), ok elsewhere
    assert singular[at_change].all()
    assert not singular[distance > 8.5 * h].any()
    for ln in ("coupler", "follower"):
        angle = np.unwrap(sol.link(ln).angle)
        omega = sol.link(ln).omega
        fd = (angle[2:] - angle[:-2]) / (2 * h)  # central difference, O(h²)
        inner = ~(singular[2:] | singular[1:-1] | singular[:-2])
        np.testing.assert_allclose(omega[1:-1][inner], fd[inner], rtol=0, atol=1e-4, err_msg=ln)
        # at the change points themselves the rates are indeterminate: NaN, not invented
        assert np.isnan(omega[at_change]).all()


def test_kite_keeps_its_branch_where_the_design_sign_would_switch():
    """Past the change point at crank angle π the hinge B lies on the other side of AO4 than in
    the drawing: the design's sign alone would have switched to the other assembly there."""
    mech = linkwork.load_text(_four_bar(*KITE, theta_deg=60))
    sol = linkwork.solve(mech, np.radians([60.0, 200.0, 300.0, 420.0]))
    B, A = sol.point("B").position, sol.point("A").position
    O4 = mech.points["O4"]
    side = np.sign((O4[0] - A[:, 0]) * (B[:, 1] - A[:, 1]) - (O4[1] - A[:, 1]) * (B[:, 0] - A[:, 0]))
    assert list(side) == [1.0, -1.0, -1.0, 1.0]  # flipped between π and 2π, back after 2π


def test_crank_rocker_has_no_change_points():
    assert branch_schedule(linkwork.load("library:crank-rocker")) == {}


def test_signs_count_the_change_points_passed():
    turn = Schedule(1.0, (1.0, 2.0), 2 * np.pi, 0.0)
    u = np.array([0.5, 1.5, 2.5, 1.1 + 2 * np.pi, -0.5, 1.9 - 2 * np.pi])
    # crossed: none; 1.0; 1.0 and 2.0; 1.0, 2.0, 1.0+2π; none; 2.0−2π going back
    np.testing.assert_array_equal(turn.signs(u), [1, -1, 1, -1, 1, -1])
    slide = Schedule(-1.0, (3.0,), None, 0.0)
    np.testing.assert_array_equal(slide.signs(np.array([2.9, 3.0, 10.0, -5.0])), [-1, 1, 1, -1])


ISOSCELES_SLIDER_CRANK = mechanism_text(
    name="slider-crank with rod = crank",
    points={"O": (0, 0), "A": (8.660254037844386, 5.0), "B": (17.32050807568877, 0)},
    links={"frame": ["O"], "crank": ["O", "A"], "rod": ["A", "B"]},
    joints=[revolute("O", "frame", "crank"), revolute("A", "crank", "rod"),
            joint("B", "slot", "frame", "rod", axis=[1, 0])],
    driver="O", speed="1 rad/s")


def test_isosceles_slider_crank_runs_through_its_change_points():
    """Rod = crank = r: the rod's circle about A cuts the line of stroke at x = 2r cos θ and at
    x = 0, which meet at θ = ±90° (change points). The motion drawn (B at 2r cos θ) goes on
    through them: B = 2r cos θ, v = −2rω sin θ over the whole turn; keeping the drawing's side
    of A's foot would leave B standing at O for half the turn."""
    mech = linkwork.load_text(ISOSCELES_SLIDER_CRANK)
    ((group, sch),) = branch_schedule(mech).items()
    np.testing.assert_allclose(np.sort(np.mod(sch.change_points, 2 * np.pi)),
                               [np.pi / 2, 3 * np.pi / 2], atol=1e-7)
    th = np.radians(np.arange(30.0, 390.0, 1.0))
    sol = linkwork.solve(mech, th)
    ok = sol.status == Status.OK
    assert (ok | (np.abs(np.cos(th)) < 1e-9)).all()
    B = sol.point("B")
    np.testing.assert_allclose(B.position[ok, 0], 20 * np.cos(th[ok]), atol=1e-9)
    np.testing.assert_allclose(B.velocity[ok, 0], -20 * np.sin(th[ok]), atol=1e-9)
    # at the change points the chord vanishes: its square root turns rounding ε into √ε
    np.testing.assert_allclose(B.position[~ok, 0], 0.0, atol=20 * 1e-7)


def test_a_drawing_at_a_change_point_is_warned_about():
    """All four pivots drawn on one line: the drawing cannot tell the parallelogram from the
    antiparallelogram, and says so once, naming the group; the CLI prints it as a warning."""
    text = four_bar_text(name="flat parallelogram (warning test)", O2=(0, 0), A=(20, 0),
                         B=(60, 0), O4=(40, 0), links=("frame", "crank", "coupler", "follower"),
                         rocker_points=("B", "O4"), speed="1 rad/s")
    with pytest.warns(LinkworkWarning, match="group coupler, follower at a change or dead"):
        sol = linkwork.solve(linkwork.load_text(text), [0.5])
    assert sol.status[0] == Status.OK
