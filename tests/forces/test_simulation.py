"""Forward dynamics against closed forms: a balanced disc under a constant torque (q = ½·(T/I)·t²),
a balanced crank on a torsion spring (q = A·cos(√(k/I)·t)), and a free crank-rocker whose
kinetic energy ½·J(q)·q̇² stays constant."""

import numpy as np
import pytest

import linkwork
from linkwork.errors import InputError
from linkwork.forces.reduced import reduced_inertia
from linkwork.forces.simulation import simulate
from linkwork.model.inertia import Dynamics, Loads, MassProperties, TorsionSpring

DISC = """
name = "disc"
units = { length = "mm" }
[points]
O = [0, 0]
A = [100, 0]
[links]
frame = ["O"]
disc = ["O", "A"]
[joints]
O = { type = "revolute", links = ["frame", "disc"] }
[driver]
joint = "O"
"""


def test_disc_under_constant_torque():
    mech = linkwork.load_text(DISC)
    I, T = 0.05, 0.2
    dyn = Dynamics.build(mech, {"disc": MassProperties(3.0, np.zeros(2), I)})
    m = simulate(dyn, T, 2.0, samples=11)
    np.testing.assert_allclose(m.input, 0.5 * T / I * m.time**2, atol=1e-9)
    np.testing.assert_allclose(m.acceleration, T / I, rtol=1e-12)


def test_torsion_pendulum():
    mech = linkwork.load_text(DISC)
    I, k, A = 0.05, 2.0, 0.3
    dyn = Dynamics.build(mech, {"disc": MassProperties(3.0, np.zeros(2), I)},
                         Loads(torsion_springs=(TorsionSpring("O", k),)))
    m = simulate(dyn, 0.0, 1.5, start=A, samples=16)
    np.testing.assert_allclose(m.input, A * np.cos(np.sqrt(k / I) * m.time), atol=1e-8)


def test_free_crank_rocker_keeps_its_energy():
    dyn = linkwork.io.load_dynamics("library:crank-rocker")
    m = simulate(dyn, 0.0, 0.5, speed=6.0, samples=11)
    J = reduced_inertia(dyn, m.input).inertia
    E = 0.5 * J * m.speed**2
    np.testing.assert_allclose(E, E[0], rtol=1e-7)
    assert m.input[-1] > m.input[0] + 1.0  # it turned on


def test_bad_duration_refused():
    dyn = linkwork.io.load_dynamics("library:crank-rocker")
    with pytest.raises(InputError, match="positive duration"):
        simulate(dyn, 0.0, -1.0)
