"""The relative pole of an intermittent pair's driver and wheel (Aronhold–Kennedy): on the line
of centres MC (P13 = M, P23 = C), and on the normal to the slot at the pin while engaged, at the
pitch point in a star wheel's pin gear, at the driver's pivot while the wheel rests. The
schedule's construction must agree with the poles from the velocities, and the three-pole ratio
P12P13 : P12P23 = ω₂₃ : ω₁₃ (Pöschl §51, seed digest 002b test 11) must give the wheel's speed."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from intermittent_mechanisms import D, geneva
from linkwork.instant.poles import agreement, kennedy_poles, pole_schedule, poles
from linkwork.kinematics.intermittent import engagement


@pytest.mark.parametrize("n", [4, 6])
def test_geneva_pole_by_three_pole_theorem_and_from_velocities(n):
    mech = geneva(n)
    phi = np.radians(np.arange(-180.0, 180.0, 4.0) + 1e-3)
    phi[45] = 0.0  # mid-engagement
    sol = linkwork.solve(mech, phi)
    schedule = pole_schedule(mech)
    assert not schedule.unreachable
    assert "n(G)" in schedule.text()
    vel, ken = poles(sol), kennedy_poles(sol, schedule)
    gap = agreement(vel, ken, mech.length_scale)[("disc", "wheel")]
    assert np.nanmax(gap) < 1e-9
    P = ken["disc", "wheel"].xy
    assert np.isfinite(P).all()
    np.testing.assert_allclose(P[:, 1], 0.0, atol=1e-9 * D)  # on the line of centres
    # the three-pole ratio: ω_wheel/ω_disc = (P − M)/(P − C) along the line of centres
    ratio = P[:, 0] / (P[:, 0] - D)
    w = sol.link("wheel").omega / sol.link("disc").omega
    np.testing.assert_allclose(w, ratio, rtol=0, atol=1e-9)
    rest = sol.joint("G")["phase"] == 0
    np.testing.assert_allclose(P[rest], 0.0, atol=1e-12)  # at the disc's pivot M while locked
    mid = np.argmin(np.abs(phi))
    r = D * np.sin(np.pi / n)
    assert P[mid, 0] == pytest.approx(r, rel=1e-9)  # at mid-engagement: the pin itself


def test_star_wheel_pole_is_the_pitch_point_in_the_pin_gear():
    mech = linkwork.load("library:star-wheel")
    sol = linkwork.whole_motion(mech, step=np.radians(2.0))
    ken = kennedy_poles(sol)
    gap = agreement(poles(sol), ken, mech.length_scale)[("driver", "star")]
    assert np.nanmax(gap) < 1e-9
    P = ken["driver", "star"].xy
    e = engagement(sol, "index")
    gear = e.phase == "gear"
    rel = sol.joint("index")
    # pitch point: r from M on MC, with r the pitch radius of the group in mesh
    M = mech.points["M"]
    radii = {0: np.hypot(*(mech.points["A1"] - M)), 1: np.hypot(*(mech.points["B1"] - M))}
    want = np.array([radii[s % 2] for s in rel["slot"][gear]])
    np.testing.assert_allclose(P[gear, 0], want, rtol=1e-12)
    np.testing.assert_allclose(P[gear, 1], 0.0, atol=1e-9)
