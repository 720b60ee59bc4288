"""Samples without forces are marked, not invented: unreachable positions and the dead centre
of a slider-crank driven at its slider (where the crank's torque would have to be infinite)
give NaN and `solved` False, the others are computed."""

import warnings

import numpy as np

import linkwork
from linkwork.forces import kinetostatics
from linkwork.model.inertia import Dynamics, MassProperties
from mechanism_texts import slider_crank_text


def _masses(mech):
    return {ln: MassProperties(1.0, mech.points[mech.link(ln).points[0]], 0.01) for ln in mech.moving_links}


def test_unreachable_and_dead_centre_samples_are_marked():
    mech = linkwork.load_text(slider_crank_text(name="driven at the slider", A=(30, 40), B=(150, 0),
                                                driver="guide"))
    dead = 50 + np.hypot(120, 40) - 150  # the slide at which crank and rod lie in line
    s = np.array([0.0, 0.5 * dead, dead, dead + 5.0])  # the last one cannot be assembled
    sol = linkwork.solve(mech, s, velocities=10.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fa = kinetostatics(Dynamics.build(mech, _masses(mech)), sol)
    assert fa.solved.tolist() == [True, True, False, False]
    assert np.isnan(fa.effort[2:]).all() and np.isfinite(fa.effort[:2]).all()
    assert np.isnan(fa.reactions["O"].force[2:]).all()
    assert sol.status[3] == linkwork.Status.UNREACHABLE
