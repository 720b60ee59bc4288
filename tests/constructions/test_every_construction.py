"""Every construction on every library mechanism at its design position (the drawing's own
position, where coincidences of the drawing happen): it draws and agrees with the engine to
1e-8 relative, or it refuses with a `LinkworkError` that says why — never another exception
(a crash) and never a drawing whose numbers disagree with the engine."""

import warnings

import numpy as np
import pytest

import linkwork
from linkwork.constructions import CONSTRUCTIONS, construct
from linkwork.errors import LinkworkError
from linkwork.io.files import library_names


@pytest.mark.parametrize("name", library_names())
def test_each_construction_draws_right_or_says_why_not(name):
    mech = linkwork.load(f"library:{name}")
    if mech.given:
        at = None  # the drawn position, from the given point velocities
    elif len(mech.drivers) > 1:
        at = np.array([[mech.driver_input_at_design(d) for d in mech.drivers]])
    else:
        at = np.array([mech.driver_input_at_design(mech.drivers[0])])
    wrong = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # over-closed chains' warnings
        for c in CONSTRUCTIONS:
            try:
                con = construct(c, mech, at)
            except LinkworkError as exc:
                assert str(exc), c
                continue
            e = con.max_error()
            if not e <= 1e-8:
                wrong[c] = e
    assert not wrong, wrong
