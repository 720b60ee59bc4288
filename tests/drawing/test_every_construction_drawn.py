"""Every construction that draws on a library mechanism at its design position is drawn as the
workbench and `linkwork draw --construction` draw it (its last step, over the mechanism), or the
drawing layer refuses with a `LinkworkError`: never another exception. (The numbers are
tests/constructions/test_every_construction.py's; this is the drawing of them: a line's span
once held a tuple in place of a point, which only the SVG writer tripped over.)"""

import re
import warnings

import numpy as np
import pytest

import linkwork
from linkwork.constructions import CONSTRUCTIONS, construct
from linkwork.drawing import Scene, scene_figure
from linkwork.errors import LinkworkError
from linkwork.io.files import library_names
from linkwork.kinematics import solve_at


@pytest.mark.parametrize("name", library_names())
def test_each_construction_is_drawn(name):
    mech = linkwork.load(f"library:{name}")
    drawn = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # over-closed chains' warnings
        sol = solve_at(mech)
        for c in CONSTRUCTIONS:
            try:
                con = construct(c, mech, sol)
            except LinkworkError:
                continue
            try:
                fig = scene_figure(Scene(mech, sol), ["mechanism"], construction=con,
                                   step=len(con.steps) - 1)
                svg, transforms = fig.svg_and_transforms()
            except LinkworkError as exc:
                assert str(exc), c
                continue
            assert "<svg" in svg and svg.rstrip().endswith("</svg>"), c
            assert "mechanism" in transforms, c
            # no number of the drawing is NaN or infinite (a point at infinity is a note)
            assert not re.search(r"\b(nan|inf)\b", svg, re.IGNORECASE), c
            drawn += 1
    assert drawn  # the velocity plan at least: every library mechanism has one or refuses
