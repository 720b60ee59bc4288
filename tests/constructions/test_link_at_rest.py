"""Acceleration plans where a link is momentarily at rest and the drawing's points coincide.

The Heusinger valve gear at its design position (t = 0): the radius rod is at rest (ω = 0), the
auxiliary point Q = P_8P_78 ∩ K_5P_67 falls on the hinge P_78 and R on P_9XI, and the lever's
points lie on the normal to the valve guide, so the two lines of p9x run parallel. Near it they
nearly do. Reading a link's α off two coincident points, or cutting two nearly parallel lines,
gave wrong numbers (α_radius_rod 1.11 for 0.281 at t = 0; 1e-6 relative errors in a sweep
through it). Every constructed value is compared with the engine (its linear solves on the
constraint Jacobian, an independent method) by ``Construction.check``; the engine's α at the
design position is checked once more by finite differences of its ω. A smaller case: a four-bar
(and its curved-slot twin) with its coupler at rest, its α by a closed form derived below.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.constructions import construct
from linkwork.io.files import load_text
from mechanism_texts import four_bar_text

TOL = 1e-9
NEAR = [0.0, 1e-12, -1e-12, 1e-9, -1e-9, 1e-6, -1e-6, 1e-3, -1e-3]


@pytest.fixture(scope="module")
def heusinger():
    return linkwork.load("library:heusinger-valve-gear")


@pytest.mark.parametrize("t", NEAR)
@pytest.mark.parametrize("name", ["acceleration-plan", "velocity-plan", "rotated-velocities"])
def test_heusinger_at_and_near_its_design_position(heusinger, name, t):
    sol = linkwork.solve(heusinger, times=[t])
    con = construct(name, heusinger, sol)
    assert not con.degenerate.any(), con.messages(0)
    assert con.max_error() <= TOL
    con.check(TOL)


def test_heusinger_radius_rod_at_rest_has_the_engines_alpha(heusinger):
    """At t = 0 the radius rod is at rest and accelerates: α = dω/dt by central differences of
    the engine's ω (a second method), and the construction agrees with it."""
    h = 1e-4
    sol = linkwork.solve(heusinger, times=[-h, 0.0, h])
    w = sol.link("radius_rod").omega
    alpha = sol.link("radius_rod").alpha[1]
    assert abs(w[1]) <= 1e-12 * abs(alpha)
    assert alpha == pytest.approx((w[2] - w[0]) / (2 * h), rel=1e-6)
    assert abs(alpha) > 0.1  # a link at rest that accelerates: ω²·l = 0, α·l ≠ 0
    con = construct("acceleration-plan", heusinger, linkwork.solve(heusinger, times=[0.0]))
    con.check(TOL)


def test_heusinger_sweep_through_its_design_position(heusinger):
    """One drawing script for all samples of a sweep through t = 0: every sample drawn (the
    p9x lines, parallel at t = 0, no longer leave it undetermined) and right."""
    steps = np.logspace(-12, -1, 12)
    times = np.concatenate([-steps[::-1], [0.0], steps])
    sol = linkwork.solve(heusinger, times=times)
    con = construct("acceleration-plan", heusinger, sol)
    assert not con.degenerate.any(), con.messages(len(steps))
    assert con.max_error() <= TOL
    con.check(TOL)


def four_bar_at_rest(curved_slot: bool) -> str:
    """Crank O2A and rocker O4B upright (the rocker replaced by a block in a circular slot
    about O4 with ``curved_slot``: the same motion of the coupler)."""
    return four_bar_text(name="coupler at rest", B=(30, 20), O4=(30, 0), curved_slot=curved_slot)


@pytest.mark.parametrize("curved_slot", [False, True], ids=["rocker", "curved-slot"])
@pytest.mark.parametrize("name", ["acceleration-plan", "relative-normals"])
def test_four_bar_with_its_coupler_at_rest(name, curved_slot):
    """Crank O2A and rocker O4B both upright: v_A and v_B are both horizontal, so the coupler is
    at rest. By hand (J the quarter turn, ω the crank's rate, α_crank = 0): v_A = ω·J·O2A =
    (−10ω, 0) = v_B = ω4·J·O4B = (−20ω4, 0), so ω4 = ω/2; a_A = (0, −10ω²) and
    a_B = a_A + α3·J·AB = (−10α3, −10ω² + 30α3) = −ω4²·O4B + α4·J·O4B = (−20α4, −5ω²), so
    α3 = ω²/6 and α4 = ω²/12."""
    mech = load_text(four_bar_at_rest(curved_slot))
    sol = linkwork.solve(mech, [mech.driver_input_at_design(mech.drivers[0])])
    w = sol.link("crank").omega[0]
    assert abs(w) > 0
    assert sol.link("coupler").omega[0] == pytest.approx(0.0, abs=1e-12 * abs(w))
    assert sol.link("coupler").alpha[0] == pytest.approx(w * w / 6, rel=1e-12)
    if not curved_slot:
        assert sol.link("rocker").alpha[0] == pytest.approx(w * w / 12, rel=1e-12)
    con = construct(name, mech, sol)
    assert not con.degenerate.any(), con.messages(0)
    con.check(TOL)
