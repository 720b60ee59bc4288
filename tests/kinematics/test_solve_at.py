"""`kinematics.solve_at`: where commands and the workbench ask for a mechanism — inputs, times or
its design position — and a chain driven by given point velocities at its drawn position only."""

import numpy as np
import pytest

import linkwork
from linkwork.errors import InputError, StructureError
from linkwork.kinematics import solve_at


def test_a_driven_mechanism_at_inputs_times_and_its_design_position():
    mech = linkwork.load("library:crank-rocker")
    u = np.radians([0.0, 30.0, 200.0])
    at = solve_at(mech, u)
    assert np.array_equal(at.input, u)
    design = mech.driver_input_at_design(mech.drivers[0])
    assert solve_at(mech).input[0] == pytest.approx(design)
    # times: the driver's law (a constant speed from the design input)
    t = np.array([0.0, 0.25])
    timed = solve_at(mech, times=t)
    w = mech.drivers[0].law.derivatives(t)[1]
    assert timed.input == pytest.approx(design + w * t)
    assert solve_at(mech, u, order=1).order == 1


def test_a_chain_driven_by_given_velocities_is_solved_at_its_drawn_position_only():
    free = linkwork.load("library:rosenauer-free-watt-chain")  # velocities given, no accelerations
    sol = solve_at(free)
    assert len(sol) == 1 and sol.order == 1
    with pytest.raises(InputError, match=r"drawn position only, and takes no --at"):
        solve_at(free, ["30"], asked="--at")
    with pytest.raises(InputError, match="takes no at or times"):
        solve_at(free, times=[0.0], asked="at or times")
    # accelerations asked for where the data give none: the data missing are named
    with pytest.raises(StructureError, match="the acceleration of A"):
        solve_at(free, order=2)
