"""Continuation of the Newton-solved groups: the design's assembly branch is kept where the
solution swings fast, limit positions are closed in on, and what was marched before does not
change a solve.

Groups with a closed form are forced onto the Newton path (as in test_generic_vs_closed_form),
so that the expected values come from closed forms written out here: the slotted lever's angle
from its slot line passing through the crank pin, the five-bar's coupler hinge from two circles,
the rocker's limit positions from the cosine law.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork import Status
from linkwork.kinematics import solver
from linkwork.kinematics.motion import input_limits
from mechanism_texts import four_bar_text, joint, mechanism_text, revolute, two_crank_five_bar_text


@pytest.fixture
def newton(newton):
    """Load mechanism texts whose groups (but the driver's) are all solved by Newton's method
    (the `newton` fixture of conftest.py, with a loader that checks it)."""
    def load(text):
        mech = linkwork.load_text(text)
        assert {s.kind for s in solver.plan(mech)} == {"driver", "generic"}
        return mech

    return load


def _wrap(a: np.ndarray) -> np.ndarray:
    return np.angle(np.exp(1j * a))


# ---------------------------------------------------------------------------- a fast swing
# Crank O–A (r = 100) turning fully; lever pivoted at B, |OB| = r + δ, its slot line through the
# crank pin A at the small offset e from B. Where the pin passes B (at the distance δ) the lever
# swings through nearly half a turn while the crank turns by a few δ/r radians: within one
# 2° step, so a fixed-step march lands on the other branch (the lever reversed on its slot line)
# and stays there for the rest of the turn.
R_CRANK, DELTA, OFFSET, BETA = 100.0, 0.5, 0.1, np.radians(125.3)
A_D = np.array([R_CRANK, 0.0])
B = (R_CRANK + DELTA) * np.array([np.cos(BETA), np.sin(BETA)])
_d = A_D - B
AXIS_ANGLE = np.arctan2(_d[1], _d[0]) - np.arcsin(OFFSET / np.hypot(*_d))
AXIS = np.array([np.cos(AXIS_ANGLE), np.sin(AXIS_ANGLE)])
TAIL = B + [30.0, 50.0]  # the lever's second point


def _slotted_lever(kind: str) -> str:
    """'slot': the pin runs in the lever's slot (one-link group); 'prismatic': a block pinned at
    A slides along the lever (RPR dyad)."""
    points = {"O": (0, 0), "A": A_D, "B": B, "T": TAIL}
    block = {} if kind == "slot" else {"block": ["A"]}
    links = {"frame": ["O", "B"], "crank": ["O", "A"]} | block | {"lever": ["B", "T"]}
    if kind == "slot":
        pairs = [joint("slot", "slot", "lever", "crank", axis=AXIS, point="A")]
    else:
        pairs = [revolute("A", "crank", "block"),
                 joint("slot", "prismatic", "lever", "block", axis=AXIS, point="A")]
    return mechanism_text(name="slotted lever swinging past its pivot", points=points,
                          links=links, driver="O", speed="1 rad/s",
                          joints=[revolute("O", "frame", "crank"), *pairs,
                                  revolute("B", "lever", "frame")])


def _lever_angle(turn: np.ndarray) -> np.ndarray:
    """Lever rotation φ from the design position when the crank has turned by `turn`. The slot
    direction a = R(φ)·axis keeps the signed distance of the slot line from B as drawn,
    a × (A − B) = axis × (A_d − B) = e, with the pin ahead of B along a (a·(A − B) > 0, as
    drawn): the angle of a is that of A − B less arcsin(e / |A − B|)."""
    A = R_CRANK * np.stack([np.cos(turn), np.sin(turn)], axis=-1)
    d = A - B
    e = AXIS[0] * _d[1] - AXIS[1] * _d[0]
    alpha = np.arctan2(d[:, 1], d[:, 0]) - np.arcsin(e / np.hypot(d[:, 0], d[:, 1]))
    return alpha - AXIS_ANGLE


@pytest.mark.parametrize("kind", ["slot", "prismatic"])
def test_lever_swinging_past_its_pivot_stays_on_the_design_branch(kind, newton):
    mech = newton(_slotted_lever(kind))
    u0 = mech.driver_input_at_design(mech.drivers[0])
    # a turn either way, and densely the swing (the pin nearest to B at the crank turn BETA),
    # which the march reaches upwards at BETA and downwards at BETA − 2π
    swing = BETA + np.radians(np.linspace(-3.0, 3.0, 241))
    turn = np.concatenate([np.radians(np.arange(-360.0, 360.0, 0.25)), swing, swing - 2 * np.pi])
    expected = _lever_angle(turn)
    # the lever turns by more than 120° during one 2° step of the crank near the swing
    jump = _wrap(_lever_angle(BETA + np.radians([1.0])) - _lever_angle(BETA - np.radians([1.0])))
    assert abs(jump[0]) > np.radians(120.0)
    sol = linkwork.solve(mech, u0 + turn)
    assert (sol.status != Status.UNREACHABLE).all()
    drawn = np.arctan2(*(TAIL - B)[::-1])  # a link's angle is that of its first two points
    np.testing.assert_allclose(_wrap(sol.link("lever").angle - drawn - expected), 0.0, atol=1e-9)


# ---------------------------------------------------------------------------- limit positions
ROCKER_DRIVEN = four_bar_text(name="four-bar driven by its rocker", rocker_points=("O4", "B"),
                              driver="O4", speed="1 rad/s")


def _rocker_angle_for(dist_o2b: float) -> float:
    """Angle of O4→B at which |O2 B| = dist, B above the frame (cosine law)."""
    a, b = 10.0, np.hypot(30, 20)
    c, d = np.hypot(10, 30), 40.0
    cos_psi = (c * c + d * d - dist_o2b ** 2) / (2 * c * d)
    return np.pi - np.arccos(cos_psi)


def test_limits_of_a_newton_solved_rocker_are_where_crank_and_coupler_align(newton):
    mech = newton(ROCKER_DRIVEN)
    a, b = 10.0, np.hypot(30, 20)
    lo, hi = input_limits(mech)
    assert [lo, hi] == pytest.approx(sorted([_rocker_angle_for(a + b), _rocker_angle_for(b - a)]),
                                     abs=1e-9)
    # the whole motion runs up to both limits and assembles everywhere on the way
    sol = linkwork.whole_motion(mech)
    assert (sol.status != Status.UNREACHABLE).all()
    assert sol.input.min() == lo and sol.input.max() == hi
    # at the limits crank and coupler are aligned: |O2 B| = b ± a
    dist = np.hypot(*sol.point("B").position[[np.argmin(sol.input), np.argmax(sol.input)]].T)
    np.testing.assert_allclose(sorted(dist), [b - a, b + a], rtol=1e-6)


def test_samples_beyond_a_limit_position_are_unreachable(newton):
    mech = newton(ROCKER_DRIVEN)
    a, b = 10.0, np.hypot(30, 20)
    lo, hi = sorted([_rocker_angle_for(a + b), _rocker_angle_for(b - a)])
    u = np.array([lo - 1e-3, lo + 1e-3, hi - 1e-3, hi + 1e-3, 0.5 * (lo + hi)])
    sol = linkwork.solve(mech, u)
    assert list(sol.status == Status.UNREACHABLE) == [True, False, False, True, False]


# ---------------------------------------------------------------------------- the cache
@pytest.mark.parametrize("kind", ["slot", "prismatic"])
def test_a_solve_does_not_depend_on_what_was_marched_before(kind, newton):
    """The march is kept per mechanism and extended on demand; its steps do not depend on the
    range asked for, so solving after other solves gives the same bits as solving first."""
    u = 4.0 * np.sin(np.arange(50.0))  # both sides of the design value, up to ±4 rad
    fresh = linkwork.solve(newton(_slotted_lever(kind)), u)
    mech = newton(_slotted_lever(kind))
    for v in ([0.3], [-0.2, 0.1], [6.5], [-1.0, -6.5]):  # shorter and longer marches first
        linkwork.solve(mech, v)
    again = linkwork.solve(mech, u)
    for ln in mech.moving_links:
        np.testing.assert_array_equal(again.link(ln).angle, fresh.link(ln).angle)
        np.testing.assert_array_equal(again.link(ln).omega, fresh.link(ln).omega)


# ---------------------------------------------------------------------------- several drivers
FIVE_BAR = two_crank_five_bar_text()


def test_several_drivers_march_through_far_apart_samples_on_the_design_branch(newton):
    """Samples up to ±0.6 rad apart, in random order: the march subdivides between them. The
    hinge P is where the circles about A (radius |AP|) and B (radius |BP|) meet, on the side of
    AB it is drawn on."""
    mech = newton(FIVE_BAR)
    P = {k: np.array(v, dtype=float) for k, v in mech.points.items()}
    d0 = np.array([mech.driver_input_at_design(d) for d in mech.drivers])
    turn = np.random.default_rng(7).uniform(-0.6, 0.6, (40, 2))
    sol = linkwork.solve(mech, d0 + turn)
    assert (sol.status == Status.OK).all()

    def rot(t, v):
        c, s = np.cos(t), np.sin(t)
        return np.stack([c * v[0] - s * v[1], s * v[0] + c * v[1]], -1)

    A = rot(turn[:, 0], P["A"])
    Bw = P["O5"] + rot(turn[:, 1], P["B"] - P["O5"])
    r1, r2 = np.hypot(*(P["P"] - P["A"])), np.hypot(*(P["P"] - P["B"]))
    ab, ap = P["B"] - P["A"], P["P"] - P["A"]
    side = np.sign(ab[0] * ap[1] - ab[1] * ap[0])
    D = Bw - A
    dist = np.hypot(D[:, 0], D[:, 1])
    along = (r1 * r1 - r2 * r2 + dist * dist) / (2 * dist)
    h = np.sqrt(r1 * r1 - along * along)
    e = D / dist[:, None]
    expected = A + along[:, None] * e + side * h[:, None] * np.stack([-e[:, 1], e[:, 0]], -1)
    np.testing.assert_allclose(sol.point("P").position, expected, atol=1e-9 * mech.length_scale)
