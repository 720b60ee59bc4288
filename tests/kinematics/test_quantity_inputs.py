"""`solve` takes pint quantities for its inputs and rates, converted at the boundary: the
expectation is the same solve with the numbers converted by hand (π/180 per degree, 10 mm per
cm, 2π/60 rad/s per rpm), so the conversion is checked against arithmetic done separately."""

from __future__ import annotations

import math

import numpy as np
import pytest

import linkwork
from linkwork.errors import InputError
from linkwork.units import Q_


def _same(a, b):
    for p in a.mechanism.points:
        np.testing.assert_array_equal(a.point(p).position, b.point(p).position)
        np.testing.assert_array_equal(a.point(p).velocity, b.point(p).velocity)
        np.testing.assert_array_equal(a.point(p).acceleration, b.point(p).acceleration)


def test_degrees_equal_radians():
    mech = linkwork.load("library:crank-rocker")
    deg = [0.0, 30.0, 75.0, 200.0]
    by_hand = linkwork.solve(mech, [d * math.pi / 180 for d in deg], velocities=2 * math.pi,
                             accelerations=0.5)
    with_units = linkwork.solve(mech, Q_(deg, "deg"), velocities=Q_(60, "rpm"),
                                accelerations=Q_(0.5, "rad/s^2"))
    _same(by_hand, with_units)
    listed = linkwork.solve(mech, [Q_(d, "deg") for d in deg], velocities=Q_(60, "rpm"),
                            accelerations=Q_(0.5, "rad/s^2"))
    _same(by_hand, listed)


def test_one_quantity_per_driver_of_each_kind():
    mech = linkwork.load("library:crank-slider")
    by_hand = linkwork.solve(mech, [[math.pi / 6, 20.0], [math.pi / 4, 35.0]],
                             velocities=[[1.0, 10.0]])
    with_units = linkwork.solve(mech, [Q_([30, 45], "deg"), Q_([2.0, 3.5], "cm")],
                                velocities=[Q_(1, "rad/s"), Q_(1, "cm/s")])
    _same(by_hand, with_units)


def test_times_in_milliseconds():
    mech = linkwork.load("library:crank-rocker")
    _same(linkwork.solve(mech, times=[0.0, 0.25, 0.5]),
          linkwork.solve(mech, times=Q_([0, 250, 500], "ms")))


def test_length_for_a_revolute_driver_names_the_driver():
    mech = linkwork.load("library:crank-rocker")
    name = mech.drivers[0].joint
    with pytest.raises(InputError, match=f"driver '{name}'"):
        linkwork.solve(mech, Q_([0, 30], "mm"))
    with pytest.raises(InputError, match=f"driver '{name}'"):
        linkwork.solve(mech, [0.0, 0.5], velocities=Q_(3, "mm/s"))


def test_angle_for_a_prismatic_driver_names_the_driver():
    mech = linkwork.load("library:crank-slider")
    name = mech.drivers[1].joint
    with pytest.raises(InputError, match=f"driver '{name}'"):
        linkwork.solve(mech, [Q_(30, "deg"), Q_(10, "deg")])
