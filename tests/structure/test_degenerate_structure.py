"""Structure reports of degenerate chains: the slider-crank whose rod is as long as its crank,
and a wheel that spins freely about its own pivot (Proell–Schwabe)."""

from __future__ import annotations

import math

import numpy as np

import linkwork
from linkwork.structure.mobility import structure_report
from mechanism_texts import slider_crank_text


def test_slider_crank_with_crank_equal_to_rod():
    """r = l = 10, centric. Its folded "dead centre" puts the block on the crank pivot, a change
    position at the crank normal to the stroke; followed through it (as the solver does) the
    block runs s = 2r cos φ (hand: the rod and the crank make an isosceles triangle on the
    stroke), so the dead centres are φ = 0 and π, s = ±20, stroke 40, no quick return."""
    mech = linkwork.load_text(slider_crank_text(name="isosceles slider-crank", A=(10, 0), B=(20, 0)))
    (loop,) = structure_report(mech).loops
    d = loop.as_dict()
    assert d["links"] == {"crank": "crank", "rod": "rod", "block": "block", "guide": "frame"}
    dead = d["dead_positions"]
    np.testing.assert_allclose(np.mod(dead["input"], 2 * math.pi), [0.0, math.pi], atol=1e-12)
    np.testing.assert_allclose(dead["slider_position"], [20.0, -20.0])
    assert dead["stroke"] == 40.0 and dead["time_ratio"] == 1.0
    np.testing.assert_allclose(np.mod(dead["change_positions"], 2 * math.pi),
                               [math.pi / 2, 3 * math.pi / 2], atol=1e-12)
    # the kinematics goes the same way: s = 2r cos φ through the change positions
    u = np.radians([0.0, 60.0, 120.0, 180.0, 240.0, 300.0])
    sol = linkwork.solve(mech, u)
    np.testing.assert_allclose(sol.point("B").position[:, 0], 20 * np.cos(u), atol=1e-9)


WHEEL_ON_COUPLER = """
name = "four-bar with a wheel on the coupler's hinge B"
[points]
O2 = [0, 0]
A = [0, 10]
B = [30, 30]
O4 = [40, 0]
W = [35, 30]
[links]
frame = ["O2", "O4"]
crank = ["O2", "A"]
coupler = ["A", "B"]
rocker = ["B", "O4"]
wheel = ["B", "W"]
[joints]
O2 = { type = "revolute", links = ["frame", "crank"] }
A = { type = "revolute", links = ["crank", "coupler"] }
B = { type = "revolute", links = ["coupler", "rocker"] }
O4 = { type = "revolute", links = ["rocker", "frame"] }
axle = { type = "revolute", links = ["coupler", "wheel"], point = "B" }
[driver]
joint = "O2"
"""


def test_a_wheel_spinning_on_its_axle_is_a_free_spin_not_a_missing_input():
    """A wheel hinged on B and touching nothing else turns on its axle whatever the crank
    does (as the Proell–Schwabe wheel would without its rolling condition): four moving links
    and five hinges, 3·4 − 2·5 = 2 freedoms (hand: the four-bar's one and the wheel's spin), one
    driver; the other freedom is the wheel's own spin, named as such."""
    from linkwork.structure.mobility import mobility

    m = mobility(linkwork.load_text(WHEEL_ON_COUPLER))
    assert m.real_mobility == 2
    assert m.free_spins == (("wheel", "axle"),)
    assert m.inputs_needed == 0
    assert "free spin: link 'wheel'" in m.verdict()
    assert "under-constrained" not in m.verdict()
    report = structure_report(linkwork.load_text(WHEEL_ON_COUPLER), limits=False)
    assert report.structure_error is None or "spins freely" in report.structure_error
