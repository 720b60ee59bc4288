"""Poles through higher pairs: the relative pole of a cam pair lies on the common normal, that of
a rolling pair is the contact point (Aronhold–Kennedy with higher pairs). The schedule's
construction (`kennedy_poles`) must agree with the poles computed from the velocities
(`poles`), an independent route."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from higher_pair_mechanisms import eccentric, rolling_disc
from linkwork.instant.poles import agreement, kennedy_poles, pole_schedule, poles


@pytest.mark.parametrize("build", [lambda: eccentric("roller"), lambda: eccentric("knife"),
                                   lambda: eccentric("flat"), lambda: eccentric("roller", offset=7.0),
                                   rolling_disc], ids=["roller", "knife", "flat", "offset", "rolling"])
def test_kennedy_poles_agree_with_velocity_poles(build):
    mech = build()
    phi = np.radians(np.linspace(65.0, 115.0, 11)) if mech.name == "rolling disc" else \
        np.radians(np.arange(5.0, 360.0, 20.0))
    sol = linkwork.solve(mech, phi)
    schedule = pole_schedule(mech)
    assert not schedule.unreachable
    gaps = agreement(poles(sol), kennedy_poles(sol, schedule), mech.length_scale)
    for pair, gap in gaps.items():
        assert np.nanmax(gap) < 1e-9, pair


def test_schedule_names_the_higher_pairs():
    text = pole_schedule(eccentric("roller")).text()
    assert "P23 = n(K) ∩ P12P13" in text
    assert "contact point of rolling pair T" in pole_schedule(rolling_disc()).text()


def test_cam_pole_on_the_common_normal():
    """P(cam, follower) lies on the line through the contact point along the common normal."""
    sol = linkwork.solve(eccentric("roller", offset=7.0), np.radians([10.0, 50.0, 130.0]))
    rep = sol.joint("K")
    P = poles(sol)["cam", "follower"].xy
    d = P - rep["point"]
    cross = d[:, 0] * rep["normal"][:, 1] - d[:, 1] * rep["normal"][:, 0]
    np.testing.assert_allclose(cross, 0.0, atol=1e-9 * 40)
