"""The centrodes of a motion, cut out as profiles and rolled on each other without slip, give the
motion back (Rosenauer §5: every plane motion is the rolling of the moving centrode on the fixed
one). The coupler of the library crank-rocker rolls on its fixed centrode, led only by a Scotch
yoke on one coupler point; the crank and the rocker are gone, yet the crank pin and the rocker pin
must stay on their circles about O2 and O4 — a property of the four-bar, not of the rolling pair."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork import Status, instant
from linkwork.errors import InputError
from linkwork.model import Mechanism, Prismatic, RollingContact, Slot


def _rolled_coupler():
    four_bar = linkwork.load("library:crank-rocker")
    # crank 40°…100°: the pole stays within 200 mm and C moves one way (checked below)
    sol = linkwork.solve(four_bar, np.radians(np.linspace(40.0, 100.0, 1201)), order=3)
    cen = instant.centrodes(sol, "coupler")
    fixed, moving = instant.centrode_profiles(cen)
    P = cen.fixed_xy[np.argmin(np.abs(np.degrees(sol.inputs) - 90.0))]  # the pole at the design (90°)
    pts = {p: four_bar.points[p] for p in ("O2", "A", "B", "O4", "C")} | {"P": P, "Y": [15.0, -10.0]}
    mech = Mechanism.build(
        name="crank-rocker coupler rolled on its centrode",
        points=pts,
        links={"frame": ["O2", "O4", "P"], "yoke": ["Y", "C"], "coupler": ["A", "B", "C"]},
        joints=[Prismatic("Y", "Y", ("frame", "yoke"), np.array([1.0, 0.0])),
                Slot("C", "C", ("yoke", "coupler"), np.array([0.0, 1.0])),
                RollingContact("T", ("frame", "coupler"), ("fixed", "moving"))],
        drivers=[{"joint": "Y"}], profiles={"fixed": fixed, "moving": moving})
    return four_bar, sol, mech


def test_rolled_centrodes_reproduce_the_coupler_motion():
    four_bar, sol, mech = _rolled_coupler()
    cx = sol.point("C").position[:, 0]
    assert np.all(np.diff(cx) < 0)  # the yoke's input is a coordinate of the motion
    slide = np.linspace(cx[5] - 15.0, cx[-5] - 15.0, 41)  # displacement of the yoke from x = 15
    rolled = linkwork.solve(mech, slide)
    # assembled everywhere (the error bound may call some samples singular: it is a bound, and
    # profiles are not polished in extended precision; the circles below are what tell)
    assert (rolled.status != Status.UNREACHABLE).all()
    O2, O4 = np.asarray(four_bar.points["O2"]), np.asarray(four_bar.points["O4"])
    crank = np.hypot(*(np.asarray(four_bar.points["A"]) - O2))
    rocker = np.hypot(*(np.asarray(four_bar.points["B"]) - O4))
    np.testing.assert_allclose(np.hypot(*(rolled.point("A").position - O2).T), crank, rtol=1e-8)
    np.testing.assert_allclose(np.hypot(*(rolled.point("B").position - O4).T), rocker, rtol=1e-8)
    # and the coupler turns as in the four-bar at the same position of C (interpolated)
    angle = np.interp(rolled.point("C").position[:, 0], cx[::-1], sol.link("coupler").angle[::-1])
    np.testing.assert_allclose(rolled.link("coupler").angle, angle, atol=1e-6)


def test_centrodes_through_infinity_are_refused():
    """The parallelogram's coupler translates: its pole is at infinity, no profile exists."""
    sol = linkwork.solve(linkwork.load("library:parallelogram"), np.radians([10.0, 20.0, 30.0]), order=3)
    with pytest.raises(InputError, match="infinity"):
        instant.centrode_profiles(instant.centrodes(sol, "coupler"))
