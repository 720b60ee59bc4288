"""A user's point name with `_` in it keeps its underscore in the vector labels of the
two-points and Hartmann constructions (v, a, u of a point: the file's name, not the books'
notation; it was set as a subscript, or its underscore dropped)."""

from __future__ import annotations

import numpy as np

import linkwork
from linkwork.constructions import construct
from linkwork.drawing.svg import segments


FOUR_BAR = """
name = "crank-rocker with a pin named pin_A"
units = { length = "mm" }
[points]
O2 = [0, 0]
pin_A = [0, 10]
B = [30, 30]
O4 = [40, 0]
C = [15, 25]
[links]
frame = ["O2", "O4"]
crank = ["O2", "pin_A"]
coupler = ["pin_A", "B", "C"]
rocker = ["B", "O4"]
[joints]
O2 = { type = "revolute", links = ["frame", "crank"] }
pin_A = { type = "revolute", links = ["crank", "coupler"] }
B = { type = "revolute", links = ["coupler", "rocker"] }
O4 = { type = "revolute", links = ["rocker", "frame"] }
[driver]
joint = "O2"
speed = "60 rpm"
"""


def test_names_with_underscores_are_printed_as_written():
    mech = linkwork.load_text(FOUR_BAR)
    sol = linkwork.solve(mech, np.radians([30.0]))
    for kind, opts in (("two-points", {}), ("hartmann", {"point": "C"})):
        con = construct(kind, mech, sol, **opts)
        labels = [e.label for e in con.elements.values()
                  if getattr(e, "label", None) and e.label[:2] in ("v_", "a_", "u_", "K_")]
        names = ["".join(t for t, _ in segments(lab)) for lab in labels]
        assert any("pin_A" in n for n in names), (kind, labels)
        assert not any("pinA" in n for n in names), (kind, labels)
