"""Coulomb friction (the documented option): closed forms for a block dragged on a guide
(μ·m·g against the sliding) and a balanced crank in a journal (μ·ρ·m·g against the turning),
and the power balance with the friction's dissipation booked, on a slider-crank with friction
in every pair."""

from importlib import resources

import numpy as np
import pytest

import linkwork
from linkwork.errors import ModelError
from linkwork.forces import kinetostatics
from linkwork.io import dynamics_from_text
from linkwork.model.inertia import Dynamics, Loads, MassProperties, PairFriction

BLOCK = """
name = "block on a guide"
units = { length = "m" }
[points]
G = [0, 0]
P = [1, 0]
[links]
frame = ["G"]
block = ["P"]
[joints]
guide = { type = "prismatic", links = ["frame", "block"], axis = [1, 0], point = "P" }
[driver]
joint = "guide"
"""

CRANK = """
name = "balanced crank"
units = { length = "mm" }
[points]
O = [0, 0]
A = [100, 0]
[links]
frame = ["O"]
crank = ["O", "A"]
[joints]
O = { type = "revolute", links = ["frame", "crank"] }
[driver]
joint = "O"
"""


def test_block_dragged_on_a_guide():
    mech = linkwork.load_text(BLOCK)
    m, mu, g, a = 4.0, 0.3, 9.81, 0.5
    dyn = Dynamics.build(mech, {"block": MassProperties(m, np.array([1.0, 0.0]), 0.1)},
                         Loads(gravity=np.array([0, -g]), friction=(PairFriction("guide", mu),)))
    v = np.array([2.0, -1.0, 0.0])
    fa = kinetostatics(dyn, linkwork.solve(mech, [0.0, 0.1, 0.2], velocities=v, accelerations=a))
    np.testing.assert_allclose(fa.effort, m * a + mu * m * g * np.sign(v), rtol=1e-14)
    np.testing.assert_allclose(fa.reactions["guide"].force[:, 0], -mu * m * g * np.sign(v), atol=1e-12)
    np.testing.assert_allclose(fa.reactions["guide"].components["normal"], m * g, rtol=1e-14)


def test_balanced_crank_in_a_journal():
    # centre of mass on the axis: |R| = m·g, friction torque μ·ρ·m·g against the turning
    mech = linkwork.load_text(CRANK)
    m, mu, rho, g = 2.0, 0.1, 15.0, 9.81
    dyn = Dynamics.build(mech, {"crank": MassProperties(m, np.array([0.0, 0.0]), 0.02)},
                         Loads(gravity=np.array([0, -g]), friction=(PairFriction("O", mu, rho),)))
    w = np.array([3.0, -3.0, 3.0])
    fa = kinetostatics(dyn, linkwork.solve(mech, [0.0, 1.0, 2.0], velocities=w))
    np.testing.assert_allclose(fa.effort, mu * rho * 1e-3 * m * g * np.sign(w), rtol=1e-14)
    np.testing.assert_allclose(fa.reactions["O"].force, np.tile([0, m * g], (3, 1)), atol=1e-12)


def test_slider_crank_with_friction_everywhere():
    text = (resources.files("linkwork") / "library" / "slider-crank-centric.toml").read_text()
    text += """
[loads]
gravity = true
forces = [{ link = "block", point = "B", force = [-800, 0] }]
friction = [{ joint = "O", coefficient = 0.05, radius = 10 }, { joint = "A", coefficient = 0.05, radius = "8 mm" },
            { joint = "B", coefficient = 0.05, radius = 6 }, { joint = "guide", coefficient = 0.1 }]
"""
    dyn = dynamics_from_text(text)
    sol = linkwork.whole_motion(dyn.mechanism, step=np.radians(5))
    fa = kinetostatics(dyn, sol)
    ok = fa.solved
    assert ok.all()
    # the power balance holds with the friction's power among the loads ...
    assert np.max(np.abs(fa.power_residual) / fa.power_scale) < 1e-9
    np.testing.assert_allclose(fa.virtual_work["O"], fa.effort, rtol=1e-9, atol=1e-9 * np.abs(fa.effort).max())
    # ... and friction only dissipates: the motor works harder than without it
    plain = dynamics_from_text(text.split("friction = [")[0])
    fp = kinetostatics(plain, sol)
    w = sol.link("crank").omega
    assert np.all((fa.effort - fp.effort) * w >= -1e-12)
    assert np.mean((fa.effort - fp.effort) * w) > 0


def test_revolute_friction_needs_the_journal_radius():
    mech = linkwork.load_text(CRANK)
    with pytest.raises(ModelError, match="journal radius"):
        Dynamics.build(mech, loads=Loads(friction=(PairFriction("O", 0.1),)))
