"""Mechanism files shared by several test modules (TOML text for `linkwork.load_text`).

Each is a hand-made drawing; the numbers the tests assert about them come from the seeds or
from hand derivations in the tests themselves.
"""

TRIPLE_PARALLEL_CRANKS = """
name = "triple parallel cranks"
description = "Rosenauer's trijparallēlkloķu ķēde (Fig. 287): three equal parallel cranks"
[points]
O1 = [0, 0]
O2 = [20, 0]
O3 = [40, 0]
A1 = [5, 10]
A2 = [25, 10]
A3 = [45, 10]
[links]
frame = ["O1", "O2", "O3"]
c1 = ["O1", "A1"]
c2 = ["O2", "A2"]
c3 = ["O3", "A3"]
coupler = ["A1", "A2", "A3"]
[joints]
O1 = { type = "revolute", links = ["frame", "c1"] }
O2 = { type = "revolute", links = ["frame", "c2"] }
O3 = { type = "revolute", links = ["frame", "c3"] }
A1 = { type = "revolute", links = ["c1", "coupler"] }
A2 = { type = "revolute", links = ["c2", "coupler"] }
A3 = { type = "revolute", links = ["c3", "coupler"] }
[driver]
joint = "O1"
"""


SCOTCH_YOKE = """
name = "Scotch yoke"
[points]
O = [0, 0]
A = [10, 0]
Y = [10, 20]
[links]
frame = ["O"]
crank = ["O", "A"]
block = ["A"]
yoke  = ["Y"]
[joints]
O     = { type = "revolute", links = ["frame", "crank"] }
A     = { type = "revolute", links = ["crank", "block"] }
slot  = { type = "prismatic", links = ["yoke", "block"], axis = [0, 1], point = "A" }
guide = { type = "prismatic", links = ["frame", "yoke"], axis = [1, 0], point = "Y" }
[driver]
joint = "O"
"""
