"""Assur groups: names, classes and orders of the solution-order groups, against the structure
read by hand off each mechanism (the expected letters are read along the pairs of the file)."""

import pytest

import linkwork
from linkwork.errors import StructureError
from linkwork.io.files import resolve
from linkwork.structure import assur_groups, mechanism_class, solution_order
from linkwork.structure.assur import dyad_type
from mechanism_texts import SCOTCH_YOKE, TRIPLE_PARALLEL_CRANKS, four_bar_text


def test_dyad_type_reads_either_way():
    assert dyad_type("RRR") == "RRR"
    assert dyad_type("PRR") == "RRP" and dyad_type("RRP") == "RRP"
    assert dyad_type("RPR") == "RPR"
    assert dyad_type("PRP") == "PRP"
    assert dyad_type("RPP") == "PPR" and dyad_type("PPR") == "PPR"
    with pytest.raises(ValueError):
        dyad_type("RR")


# (library mechanism, [(kind, dyad type or None, links of the group)]) read off the files
LIBRARY_GROUPS = {
    # crank, then coupler + rocker hinged to crank and frame: R-R-R
    "crank-rocker": [("driver", None, {"crank"}), ("dyad", "RRR", {"coupler", "rocker"})],
    # rod hinged to the crank and to the block, block on the frame's guide: R-R-P
    "slider-crank-offset": [("driver", None, {"crank"}), ("dyad", "RRP", {"rod", "block"})],
    # the pin C in the frame's slot is the die block folded: rod + block, R-R-P again
    "pmks-slider-crank-tracer": [("driver", None, {"AB"}), ("dyad", "RRP", {"BCD"})],
    # block on the crank pin (R), sliding in the lever (P), lever on the frame (R): R-P-R
    "oscillating-crank-slotted-lever": [("driver", None, {"crank"}),
                                        ("dyad", "RPR", {"block", "lever"})],
    # Whitworth: the slotted lever R-P-R, then the rod and the ram on its guide R-R-P
    "whitworth-quick-return": [("driver", None, {"crank"}), ("dyad", "RPR", {"block", "lever"}),
                               ("dyad", "RRP", {"rod", "ram"})],
    # Stephenson III: four-bar dyad, then a second R-R-R dyad
    "stephenson-iii-six-bar": [("driver", None, {"crank"}), ("dyad", "RRR", None),
                               ("dyad", "RRR", None)],
}


@pytest.mark.parametrize("name", sorted(LIBRARY_GROUPS))
def test_library_groups(name):
    groups = assur_groups(linkwork.load(f"library:{name}"))
    want = LIBRARY_GROUPS[name]
    assert len(groups) == len(want)
    for g, (kind, dyad, links) in zip(groups, want):
        assert g.kind == kind
        assert g.dyad == dyad
        if links is not None:
            assert set(g.links) == links
    assert mechanism_class(groups) == 2


def test_groups_follow_the_one_solution_order():
    mech = linkwork.load("library:jansen-linkage")
    assert [g.links for g in assur_groups(mech)] == [g.links for g in solution_order(mech)]


def test_roemer_mechanism_has_a_triad_and_a_gear_dyad():
    groups = assur_groups(linkwork.load("library:roemer-mechanism"))
    # gear II on its axle meshing with gear I: by the equivalent link through the pitch-circle
    # centres (Rosenauer §97) a hinged dyad
    assert groups[1].kind == "dyad" and groups[1].dyad == "RRR" and groups[1].higher
    # coupler ABC is ternary with the three legs KA, MC (hinges) and the rod BL (slider): a
    # triad, class III, attached by three pairs
    triad = groups[2]
    assert set(triad.links) == {"link_ka", "link_mc", "coupler", "rod_bl"}
    assert (triad.kind, triad.assur_class, triad.order) == ("triad", 3, 3)
    assert mechanism_class(groups) == 3


TANGENT = """
name = "tangent mechanism"
[points]
O = [0, 0]
K = [20, 20]
S = [10, 10]
[links]
frame   = ["O"]
crank   = ["O", "K"]
block_b = ["S"]
block_a = ["S"]
[joints]
O     = { type = "revolute", links = ["frame", "crank"] }
along = { type = "prismatic", links = ["crank", "block_b"], axis = [1, 1], point = "S" }
S     = { type = "revolute", links = ["block_b", "block_a"] }
guide = { type = "prismatic", links = ["frame", "block_a"], axis = [1, 0], point = "S" }
[driver]
joint = "O"
"""


def test_dyad_types_with_two_sliders():
    # Scotch yoke: block hinged on the crank pin (R), sliding in the yoke (P), yoke on the
    # frame's guide (P): R-P-P, the PPR type
    groups = assur_groups(linkwork.load_text(SCOTCH_YOKE))
    assert groups[1].dyad == "PPR"
    # a block sliding along the crank (P), hinged (R) to a block on the frame's guide (P): PRP
    groups = assur_groups(linkwork.load_text(TANGENT))
    assert groups[1].dyad == "PRP"


# a six-bar driven so that no dyad appears: the four links Q1..Q4 form a closed loop inside the
# group, Q1 hangs on the crank and Q3 on the frame (two outer pairs)
CLASS_IV = """
name = "six-bar with a class IV group"
[points]
A0  = [0, 0]
A   = [10, 10]
H12 = [30, 40]
H23 = [60, 40]
H34 = [50, 20]
H41 = [25, 15]
D   = [60, 0]
[links]
frame = ["A0", "D"]
crank = ["A0", "A"]
Q1 = ["A", "H12", "H41"]
Q2 = ["H12", "H23"]
Q3 = ["H23", "H34", "D"]
Q4 = ["H34", "H41"]
[joints]
A0  = { type = "revolute", links = ["frame", "crank"] }
A   = { type = "revolute", links = ["crank", "Q1"] }
H12 = { type = "revolute", links = ["Q1", "Q2"] }
H23 = { type = "revolute", links = ["Q2", "Q3"] }
H34 = { type = "revolute", links = ["Q3", "Q4"] }
H41 = { type = "revolute", links = ["Q4", "Q1"] }
D   = { type = "revolute", links = ["Q3", "frame"] }
[driver]
joint = "A0"
"""


def test_class_four_group():
    groups = assur_groups(linkwork.load_text(CLASS_IV))
    g = groups[1]
    assert set(g.links) == {"Q1", "Q2", "Q3", "Q4"}
    # Artobolevsky: a closed loop of four links inside the group → class IV; attached by A and
    # D → order 2
    assert (g.kind, g.assur_class, g.order) == ("group", 4, 2)
    assert mechanism_class(groups) == 4


# Heusinger-like group (001d §112, structural note): two ternaries T1 and T2 hinged together,
# each with two legs; four outer pairs
HEUSINGER_GROUP = """
name = "double triad"
[points]
O  = [0, 0]
Kp = [10, 5]
P1 = [30, 30]
G2 = [50, 0]
P2 = [45, 35]
M  = [40, 50]
P3 = [70, 55]
P4 = [65, 40]
G3 = [90, 70]
G4 = [80, 10]
[links]
frame = ["O", "G2", "G3", "G4"]
crank = ["O", "Kp"]
L1 = ["Kp", "P1"]
L2 = ["G2", "P2"]
T1 = ["P1", "P2", "M"]
T2 = ["M", "P3", "P4"]
L3 = ["P3", "G3"]
L4 = ["P4", "G4"]
[joints]
O  = { type = "revolute", links = ["frame", "crank"] }
Kp = { type = "revolute", links = ["crank", "L1"] }
P1 = { type = "revolute", links = ["L1", "T1"] }
G2 = { type = "revolute", links = ["frame", "L2"] }
P2 = { type = "revolute", links = ["L2", "T1"] }
M  = { type = "revolute", links = ["T1", "T2"] }
P3 = { type = "revolute", links = ["T2", "L3"] }
P4 = { type = "revolute", links = ["T2", "L4"] }
G3 = { type = "revolute", links = ["L3", "frame"] }
G4 = { type = "revolute", links = ["L4", "frame"] }
[driver]
joint = "O"
"""


def test_heusinger_like_six_link_group_is_class_three_order_four():
    groups = assur_groups(linkwork.load_text(HEUSINGER_GROUP))
    assert len(groups) == 2
    g = groups[1]
    # six links, nine hinges, no loop inside, two ternaries: class III; four outer pairs
    assert len(g.links) == 6 and g.unfolded_pairs == 9
    assert (g.kind, g.assur_class, g.order) == ("group", 3, 4)


def test_piston_driven_engine_starts_from_the_block():
    text = resolve("library:slider-crank-centric")[1]
    # drive the block along its guide instead of the crank
    text = text.split("[driver]")[0] + '[driver]\njoint = "guide"\nspeed = "100 mm/s"\n'
    groups = assur_groups(linkwork.load_text(text))
    assert groups[0].kind == "driver" and groups[0].links == ("block",)
    assert groups[0].letters == "P"
    # the crank (frame hinge) and the rod (hinged to crank and block): R-R-R
    assert groups[1].dyad == "RRR"


def test_curved_slot_dyad():
    text = four_bar_text(name="crank and coupler with its end in a circular slot",
                         curved_slot=True)
    groups = assur_groups(linkwork.load_text(text))
    # the coupler alone is a group (2 + 1 constraints); with its die block unfolded: hinge on
    # the crank, hinge to the block, block sliding in the curved slot: R-R-P
    g = groups[1]
    assert g.links == ("coupler",) and g.dyad == "RRP"
    assert g.unfolded_links == 2 and any("Kulisse" in n for n in g.notes)


def test_driver_between_moving_links_gives_a_driven_group():
    # the ellipsograph is driven at the hinge between block A and the rod
    groups = assur_groups(linkwork.load("library:ellipsograph"))
    assert len(groups) == 1 and groups[0].kind == "driven group"
    assert mechanism_class(groups) is None


def test_over_constrained_mechanism_has_no_groups():
    # the third parallel crank repeats the others' constraint (001c §101): no solution order
    with pytest.raises(StructureError):
        assur_groups(linkwork.load_text(TRIPLE_PARALLEL_CRANKS))
