"""A drag's frame takes the design contact of a higher pair it draws as the frame before it
(`contact._design`, `continuation.follow`): the contact a search on the profiles finds for the
moved drawing itself; a point of the pair's links moved, it is searched for again."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.kinematics import contact
from linkwork.kinematics.continuation import follow
from linkwork.model import design_contact
from linkwork.web.sources import moved


def fields(c) -> list:
    return [np.asarray(getattr(c, f)).tolist() for f in vars(c)]


@pytest.mark.parametrize("point,taken", [
    ("P12", True),    # the crank's pin: not on the rolling pair's links
    ("P234", False),  # the wheel's hinge: a point of the pair's link
])
def test_a_frame_takes_the_design_contact_of_a_pair_drawn_alike(point, taken):
    base = linkwork.load("library:proell-schwabe-valve-gear")
    before = contact._design(base, "roll")
    m = moved(base, {point: base.points[point] + np.array([0.1, 0.0])})
    follow(m, base)
    got = contact._design(m, "roll")
    assert (got is before) == taken
    assert fields(got) == fields(design_contact(m, m.joint("roll")))  # the search's numbers
