"""The velocity and acceleration plans of the intermittent pairs: the Geneva wheel and the star
wheel (Pöschl §25: "analysed exactly like the slotted crank"; the star wheel's pin gear rolls its
pitch circles; at rest the locking arc holds the wheel).

Every constructed velocity and acceleration (the wheel's ω and α, its points, the driver's
points at the slot and the pitch point) is compared with the engine's exact values by
``Construction.check`` (1e-9 relative) over a whole turn of the driver, every phase included;
the speed ratios are checked against Pöschl's closed forms (digest 002a, T8 and §25b), and the
step texts against the parts they name.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.constructions import acceleration_plan, rotated_velocities, velocity_plan
from linkwork.kinematics import solve
from linkwork.model.intermittent import DWELL, ENGAGED, ENTRY, EXIT, GEAR

from intermittent_mechanisms import D, geneva, tan_formula

TURN = np.linspace(0.0, 2 * np.pi, 121)[:-1]


def turn(name):
    mech = linkwork.load(f"library:{name}")
    return mech, solve(mech, mech.driver_input_at_design(mech.drivers[0]) + TURN, order=2)


@pytest.mark.parametrize("name, pair, phases", [
    ("geneva-4", "pin", {DWELL, ENGAGED}),
    ("geneva-6", "pin", {DWELL, ENGAGED}),
    ("star-wheel", "index", {DWELL, ENTRY, GEAR, EXIT}),
])
@pytest.mark.parametrize("build", [velocity_plan, rotated_velocities, acceleration_plan],
                         ids=["plan", "rotated", "acceleration"])
def test_whole_turn_matches_the_engine(name, pair, phases, build):
    mech, sol = turn(name)
    assert set(np.unique(sol.joint(pair)["phase"])) == phases  # every phase is drawn
    con = build(mech, sol)
    assert not con.degenerate.any(), con.messages()
    con.check()
    wheel = mech.joint(pair).links[1]
    assert f"omega_{wheel}" in con.results
    if build is acceleration_plan:
        assert f"alpha_{wheel}" in con.results
    # one position at a time: the same drawing
    for i in (0, 17, 40, 77):
        build(mech, sol.inputs[i:i + 1, 0] if sol.inputs.ndim == 2 else sol.inputs[i:i + 1]).check()


def test_geneva_mid_engagement_speed_ratio():
    """At mid-engagement the pin stands on the line of centres: ω_cross/ω_disc = r/(D − r) =
    1/(√2 − 1) for four slots (Pöschl §25a, D₄ = a√2, r = a), the wheel turning against the
    disc; the acceleration of the cross is zero there (the ratio is stationary)."""
    mech = linkwork.load("library:geneva-4")
    con = acceleration_plan(mech, np.array([mech.driver_input_at_design(mech.drivers[0])]))
    w_disc = 2 * np.pi  # 60 rpm
    w = con.results["omega_cross"].constructed[0]
    assert w == pytest.approx(-w_disc / (np.sqrt(2) - 1), rel=1e-12)
    assert abs(con.results["alpha_cross"].constructed[0]) <= 1e-9 * w * w


def test_star_wheel_pin_gear_ratios():
    """In the pin gear the ratio is constant, r/(D − r): 60/40 for the group on r = 60 and
    50/50 for the group on r = 50 (D = 100; the mechanism's description); at rest ω = 0."""
    mech, sol = turn("star-wheel")
    con = velocity_plan(mech, sol)
    w = con.results["omega_star"].constructed / (2 * np.pi)
    phase = sol.joint("index")["phase"]
    gear = phase == GEAR
    assert gear.any()
    assert np.all(np.isclose(w[gear], -1.5, rtol=1e-12) | np.isclose(w[gear], -1.0, rtol=1e-12))
    assert np.isclose(w[gear], -1.5, rtol=1e-12).any() and np.isclose(w[gear], -1.0, rtol=1e-12).any()
    assert np.all(np.abs(w[phase == DWELL]) <= 1e-12)


def test_geneva_step_texts_name_the_pin_the_slot_and_the_wheel():
    mech = linkwork.load("library:geneva-4")
    at = np.array([mech.driver_input_at_design(mech.drivers[0]) + 0.3])
    v = [s.text for s in velocity_plan(mech, at).steps]
    slot = next(t for t in v if "radial slot" in t)
    assert "pin B of disc" in slot and "wheel cross" in slot and "CB" in slot
    assert "perpendicular to CB" in slot and "parallel to the slot" in slot
    a = [s.text for s in acceleration_plan(mech, at).steps]
    acc = next(t for t in a if "Coriolis" in t and "cross" in t)
    assert "B*" in acc and "perpendicular to CB" in acc and "parallel to the slot" in acc
    r = [s.text for s in rotated_velocities(mech, at).steps]
    assert any("radial slot" in t and "parallel to CB" in t and "perpendicular to the slot" in t for t in r)


def test_star_wheel_step_texts_per_phase():
    mech, sol = turn("star-wheel")
    phase = sol.joint("index")["phase"]
    words = {GEAR: ("pitch point T_index", "MC", "roll"), DWELL: ("rests", "locking arc", "frame"),
             ENTRY: ("radial slot", "A_1", "driver"), EXIT: ("radial slot", "A_3", "driver")}
    for k, want in words.items():
        i = int(np.argmax(phase == k))
        texts = " ".join(s.text for s in acceleration_plan(mech, sol.inputs[i:i + 1, 0]).steps)
        for w in want:
            assert w in texts, (k, w)
    # a batch over several phases names each phase's step once
    texts = [s.text for s in velocity_plan(mech, sol).steps]
    assert sum("radial slot" in t for t in texts) == 1
    assert sum("Pin gear" in t for t in texts) == 1
    assert sum("rests" in t for t in texts) == 1


@pytest.mark.parametrize("name, pair", [("geneva-4", "pin"), ("geneva-6", "pin"), ("star-wheel", "index")])
def test_phase_boundaries(name, pair):
    """Exactly where a phase begins (a pin at the slot's mouth or foot, the wheel coming to
    rest), the sample takes the phase that begins there; the plans draw that phase's law."""
    from linkwork.model.intermittent import indexing_schedule
    mech = linkwork.load(f"library:{name}")
    sch = indexing_schedule(mech, mech.joint(pair))
    x0 = mech.driver_input_at_design(mech.drivers[0])
    drawn = solve(mech, np.array([x0])).joint(pair)["driver_angle"][0]
    at = np.array([x0 - drawn + sch.origin + ph.start for ph in sch.phases])
    sol = solve(mech, at, order=2)
    assert list(sol.joint(pair)["phase"]) == [ph.kind for ph in sch.phases]
    acceleration_plan(mech, sol).check()


@pytest.mark.parametrize("n, r", [(3, None), (4, 80.0), (5, 90.0), (8, None)],
                         ids=["3-shock-free", "4-entering-at-an-angle", "5-entering-at-an-angle", "8-shock-free"])
def test_geneva_wheels_of_any_slots_against_the_slotted_crank_formula(n, r):
    """Wheels of 3 to 8 slots, shock-free or with a pin entering at an angle (a velocity jump
    at entry): every sample drawn and checked; while engaged the wheel's constructed ω is the
    slotted crank's, dψ/dφ of tan ψ = λ sin φ/(1 − λ cos φ) (Pöschl §25a), by central
    differences of that closed form."""
    mech = geneva(n, r)
    phi = np.linspace(-np.pi, np.pi, 181)
    sol = solve(mech, phi, order=2)
    con = acceleration_plan(mech, sol)
    con.check()
    engaged = sol.joint("G")["phase"] == ENGAGED
    lam = (D * np.sin(np.pi / n) if r is None else r) / D
    h = 1e-6
    dpsi = (tan_formula(phi + h, lam) - tan_formula(phi - h, lam)) / (2 * h)
    w = con.results["omega_wheel"].constructed
    np.testing.assert_allclose(w[engaged], -dpsi[engaged], rtol=1e-7, atol=1e-9)  # unit driver speed


def test_slide_pairs_refuses_the_pins_by_name():
    """Paper 3's slide-pair parallelogram needs the sliding link to turn with the guide (a block);
    a Geneva pin turns relative to the wheel: refused, naming the pair and why."""
    from linkwork.constructions import slide_pairs
    from linkwork.errors import InputError
    mech = linkwork.load("library:geneva-4")
    with pytest.raises(InputError, match="the geneva pair 'pin' slide in the wheel's slots but turn "
                                         "relative to the wheel"):
        slide_pairs(mech, np.array([mech.driver_input_at_design(mech.drivers[0])]))
