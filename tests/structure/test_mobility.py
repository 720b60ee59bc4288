"""Mobility: the seeds' counts, each checked against the numbers the seeds work out, and the real
mobility from the Jacobian's rank on over-closed, under-constrained, singular and wedge chains.

Every expected number below is quoted from a seed digest (section cited) or derived by hand in
the comment next to it; none is the code's own output.
"""

from fractions import Fraction

import pytest

import linkwork
from linkwork.errors import InputError
from linkwork.io.files import library_names
from linkwork.structure import chain_counts, counts, mobility
from linkwork.structure.mobility import (grubler_constrained, kutzbach, link_types,
                                         structure_report)
from mechanism_texts import TRIPLE_PARALLEL_CRANKS, four_bar_text

# ---------------------------------------------------------------------------- the seeds' counts
# (name, counts, h + 2z − 3n + 4 − γ as the seed evaluates it, where it comes from)
SEED_COUNTS = [
    # Heusinger valve gear: 13 hinges, 3 sliders, 12 links; 2·16 − 3·12 + 4 = 0
    ("Heusinger valve gear", chain_counts(12, g=13, s=3), 0, "001d §112, lines 6471–6479"),
    # its hinge chain (sliders replaced by hinges): 16 hinges, frame with 5 joints
    ("Heusinger hinge chain", chain_counts(12, g=16), 0, "001d §113"),
    # rolling-lever valve gear (Wälzhebelsteuerung): 1 + 2·(4+1) − 15 + 4 = 0
    ("rolling-lever valve gear", chain_counts(5, g=4, s=1, h_n=1), 0, "001c §98 Ex. 32; 001d §109 l. 6334"),
    # the same with a fixed lever pivot: 1 + 2·8 − 3·7 + 4 = 0
    ("rolling-lever gear, fixed pivot", chain_counts(7, g=6, s=2, h_n=1), 0, "001d §111 l. 6410–6414"),
    # Sulzer valve gear, two non-self-closed higher pairs: 2 + 2·6 − 3·6 + 4 = 0
    ("Sulzer valve gear", chain_counts(6, g=4, s=2, h_n=2), 0, "001d §121 Task 4"),
    # Proell–Schwabe: 5 simple hinges + the double hinge 234, 2 sliders, one self-closed pair
    # counted twice: 2 + 2·9 − 3·8 + 4 = 0
    ("Proell–Schwabe valve gear", chain_counts(8, g1=5, g2=1, s=2, h_p=1), 0, "001c §98 Ex. 33"),
    # Holst mechanism and shaping machine (Stephenson chains with sliders): 2·7 − 18 + 4 = 0
    ("Holst mechanism", chain_counts(6, g=6, s=1), 0, "001d §119"),
    ("shaping machine", chain_counts(6, g=5, s=2), 0, "001d §120"),
    # self-closing grab: g₁ = 6, g₂ = 2, g = 10: 2·10 − 3·8 + 4 = 0
    ("self-closing grab (Pašgrābis)", chain_counts(8, g1=6, g2=2), 0, "001c §94 Ex. 31"),
    # Watt chain with the double joint 234, then also 156: g = 5 + 2 = 7 and 3 + 2·2 = 7
    ("Watt chain, one double joint", chain_counts(6, g1=5, g2=1), 0, "001c §94 l. 5486–5492"),
    ("Watt chain, two double joints", chain_counts(6, g1=3, g2=2), 0, "001c §94 l. 5486–5492"),
    # hinged pentagon: not constrained (2·5 − 15 + 4 = −1)
    ("hinged pentagon", chain_counts(5, g=5), -1, "001c §86"),
    # three-link hinge chain: no relative motion (2·3 − 9 + 4 = 1)
    ("three-link hinge chain", chain_counts(3, g=3), 1, "001a §4"),
    # triple parallel cranks: n = 5, g = 6 > 3n/2 − 2 = 5.5: over-closed, one redundant link
    ("triple parallel cranks", chain_counts(5, g=6), 1, "001c §101 l. 5875–5877"),
    # pantograph of Fig. 291: n = 8, g = 11, free term −1: two redundant links
    ("pantograph Fig. 291", chain_counts(8, g=11), 2, "001c §101 l. 5923–5925"),
    # chain with one closed slider group (Fig. 276): 2·6 − 3·5 + 4 = 1 = γ
    ("slider-group chain Fig. 276", chain_counts(5, g=3, s=3, gamma=1), 0, "001c §95"),
    # the wedge (3-link slider chain) moves: 2·3 − 9 + 4 = 1 = γ
    ("wedge", chain_counts(3, s=3, gamma=1), 0, "001c §95 Figs. 273–274"),
    # a four-bar with four sliders is not constrained
    ("four sliders", chain_counts(4, s=4, gamma=1), -1, "001c §95 Fig. 270"),
]


@pytest.mark.parametrize("name,c,criterion,source", SEED_COUNTS, ids=[s[0] for s in SEED_COUNTS])
def test_rosenauer_criterion_as_the_seeds_evaluate_it(name, c, criterion, source):
    assert c.criterion == criterion
    assert c.constrained == (criterion == 0)
    assert c.mobility == 1 - criterion


def test_lower_and_higher_pair_totals_of_the_seed_examples():
    # Heusinger: z = 16 (001d §112); Proell–Schwabe: g = 7, z = 9, h = 2 (001c §98)
    assert chain_counts(12, g=13, s=3).z == 16
    ps = chain_counts(8, g1=5, g2=1, s=2, h_p=1)
    assert (ps.g, ps.z, ps.h) == (7, 9, 2)
    # Sulzer: z = 6, h = 2 (001d §121)
    assert (chain_counts(6, g=4, s=2, h_n=2).z, chain_counts(6, g=4, s=2, h_n=2).h) == (6, 2)


@pytest.mark.parametrize("name,n,g1,g2", [
    # Pöschl: Peaucellier n = 8, g = 10 with A, B, C, O₂ double (002b §66a)
    ("Peaucellier inversor", 8, 2, 4),
    # Hart's inversor n = 6, g = 7 (002b §66b)
    ("Hart inversor", 6, 7, 0),
    # Stephenson's reversing gear, joints 16, 12, 14, 23, 34, 35, 56 (002b Beispiel 15)
    ("Stephenson link motion", 6, 7, 0),
    # four-bar (002a T18)
    ("four-bar", 4, 4, 0),
])
def test_grubler_3n_minus_2g_equals_4(name, n, g1, g2):
    c = chain_counts(n, g1=g1, g2=g2)
    assert c.grubler == 4
    assert grubler_constrained(n, c.g)


def test_rosenkranz_indicator_counts_its_slider_as_a_pair():
    # Pöschl's Beispiel 16: n = 6, g = 7 with the direct pole 56 at infinity (a slider)
    c = chain_counts(6, g=6, s=1)
    assert c.grubler == 4 and c.constrained


def test_peaucellier_hinge_multiplicities():
    c = chain_counts(8, g1=2, g2=4)
    assert (c.g1, c.g2, c.g) == (2, 4, 10)


def test_eight_link_chains_with_multiple_joints_keep_g_equal_10():
    # the book's table for Figs. 259–265 (001c §94, lines 5544–5547)
    table = [(10, 0, 0), (8, 1, 0), (7, 0, 1), (6, 2, 0), (5, 1, 1), (4, 0, 2), (2, 4, 0)]
    for g1, g2, g3 in table:
        c = chain_counts(8, g1=g1, g2=g2, g3=g3)
        assert c.g == 10 and c.constrained


def test_free_term_names_the_redundant_links():
    # (44) x = −2 constrained; (55a) −3/2 one redundant link; (55b) −1 two (001c §101)
    assert chain_counts(6, g=7).free_term == Fraction(-2)
    assert chain_counts(5, g=6).free_term == Fraction(-3, 2)
    assert chain_counts(8, g=11).free_term == Fraction(-1)
    assert chain_counts(5, g=6).redundant_links == 1
    assert chain_counts(8, g=11).redundant_links == 2


@pytest.mark.parametrize("n", [3, 4, 5, 6])
def test_all_slider_chains_with_2n_minus_3_sliders_are_constrained(n):
    # (51): s = 2n − 3 (001c §96); their closed slider groups: the loops of the chain,
    # s − n + 1 of them (hand: cycle rank of a connected graph)
    s = 2 * n - 3
    assert chain_counts(n, s=s, gamma=s - n + 1).constrained


@pytest.mark.parametrize("n,h", [(2, 2), (3, 5)])
def test_higher_pair_chains_h_equals_3n_minus_4(n, h):
    # (54): n = 2 → h = 2 (one self-closed pair), n = 3 → h = 5 (001c §99)
    assert chain_counts(n, h_n=h).constrained
    if h == 2:
        assert chain_counts(n, h_p=1).constrained


def test_kutzbach_count():
    # hand: four-bar 3·3 − 2·4 = 1; slider-crank with pin in slot 3·2 − 2·2 − 1 = 1
    assert kutzbach(4, lower=4) == 1
    assert kutzbach(3, lower=2, higher=1) == 1


def test_bad_counts_are_user_errors():
    with pytest.raises(InputError):
        chain_counts(0, g=1)
    with pytest.raises(InputError):
        chain_counts(4, g=-1)


# ---------------------------------------------------------------------------- library mechanisms
# hand counts from the library files (die blocks of pins in slots unfolded as the seeds draw
# them: +1 link, +1 hinge, +1 slider)
LIBRARY_COUNTS = {
    "crank-rocker": dict(n=4, g=4, s=0),
    "double-crank": dict(n=4, g=4, s=0),
    "double-rocker": dict(n=4, g=4, s=0),
    "parallelogram": dict(n=4, g=4, s=0),
    "antiparallelogram": dict(n=4, g=4, s=0),
    "pmks-teaching-four-bar": dict(n=4, g=4, s=0),
    # Rosenauer's slider-crank, type I: 3 hinges + 1 slider (001a §4)
    "slider-crank-centric": dict(n=4, g=3, s=1),
    "slider-crank-offset": dict(n=4, g=3, s=1),
    "pmks-slider-crank-tracer": dict(n=4, g=3, s=1),  # pin C in a slot: block unfolded
    "pmks-teaching-slider-crank": dict(n=4, g=3, s=1),
    "oscillating-crank-slotted-lever": dict(n=4, g=3, s=1),
    "rotating-crank-slotted-lever": dict(n=4, g=3, s=1),
    "ellipsograph": dict(n=4, g=2, s=2),
    # six-bars: n = 6 → g = 7 (001c §90)
    "stephenson-iii-six-bar": dict(n=6, g=7, s=0),
    "watt-i-six-bar": dict(n=6, g=7, s=0),
    "pmks-stephenson-iii": dict(n=6, g=7, s=0),
    # Whitworth: a shaping machine, g = 5, s = 2 as Rosenauer counts it (001d §120)
    "whitworth-quick-return": dict(n=6, g=5, s=2),
    # Römer: 7 hinges, 1 slider, the gear mesh as a higher pair
    "roemer-mechanism": dict(n=7, g=7, s=1, h=1),
    # Jansen: 8 links, 4 simple and 3 double hinges (hand count of the file's joints)
    "jansen-linkage": dict(n=8, g=10, s=0, g2=3),
    # Geneva and star wheels (Pöschl §25): frame, driver, wheel; two hinges and the pin's
    # intermittent pair, h = 1 in every phase: F = 3·2 − 2·2 − 1 = 1
    "geneva-4": dict(n=3, g=2, s=0, h=1),
    "geneva-6": dict(n=3, g=2, s=0, h=1),
    "star-wheel": dict(n=3, g=2, s=0, h=1),
}


@pytest.mark.parametrize("name", sorted(LIBRARY_COUNTS))
def test_library_counts_by_hand(name):
    want = LIBRARY_COUNTS[name]
    c = counts(linkwork.load(f"library:{name}"))
    assert (c.n, c.g, c.s, c.h) == (want["n"], want["g"], want["s"], want.get("h", 0))
    if "g2" in want:
        assert c.g2 == want["g2"]
    assert c.constrained


OVERCLOSED_LIBRARY = {"roberval-balance", "pantograph"}


@pytest.mark.parametrize("name", library_names())
def test_every_library_mechanism_moves_with_its_drivers(name):
    # the library's promise: each mechanism runs from its drivers (constrained motion)
    mech = linkwork.load(f"library:{name}")
    m = mobility(mech)
    if mech.given:
        # a chain driven by given point velocities: as many degrees of freedom as they state
        assert m.real_mobility == sum(g.count for g in mech.given) and not mech.drivers
        return
    assert m.real_mobility == len(mech.drivers)
    assert m.inputs_needed == 0 and not m.surplus_drivers
    # the books' over-closed chains (übergeschlossen: Roberval's balance and the pantograph,
    # a parallelogram with a repeated link) move although Grübler's count says they cannot
    assert m.overclosed == (name in OVERCLOSED_LIBRARY)
    if m.overclosed:
        assert m.count_mobility < m.real_mobility
    else:
        assert m.count_mobility == m.real_mobility


def test_curved_slot_counts_as_block_hinge_and_slider():
    # Rosenauer §4, Fig. 30: a four-bar whose rocker is a block in a circular slot has
    # 3 revolutes + 1 curved sliding pair and is still constrained
    text = four_bar_text(name="curved slot", curved_slot=True)
    m = mobility(linkwork.load_text(text))
    assert (m.counts.n, m.counts.g, m.counts.s) == (4, 3, 1)
    assert m.counts.constrained and m.real_mobility == 1 and m.constrained


def test_six_bars_have_four_binary_and_two_ternary_links():
    # n = 6: n₂ = 4, n₃ = 2 (001c §90, lines 5271–5273)
    for name in ("stephenson-iii-six-bar", "watt-i-six-bar", "pmks-stephenson-iii"):
        assert link_types(linkwork.load(f"library:{name}")) == {2: 4, 3: 2}


# ---------------------------------------------------------------------------- real mobility
ROBERVAL = """
name = "Roberval balance"
description = "two beams pivoted one above the other on the post, pan posts hinged to their ends"
[points]
U  = [0, 10]
L  = [0, 0]
UL = [-20, 10]
UR = [20, 10]
LL = [-20, 0]
LR = [20, 0]
[links]
frame = ["U", "L"]
upper = ["UL", "U", "UR"]
lower = ["LL", "L", "LR"]
left  = ["UL", "LL"]
right = ["UR", "LR"]
[joints]
U  = { type = "revolute", links = ["frame", "upper"] }
L  = { type = "revolute", links = ["frame", "lower"] }
UL = { type = "revolute", links = ["upper", "left"] }
LL = { type = "revolute", links = ["left", "lower"] }
UR = { type = "revolute", links = ["upper", "right"] }
LR = { type = "revolute", links = ["right", "lower"] }
[driver]
joint = "U"
"""

# pantograph about o: arm o-a-P, lower arm P-c-B, sides a-b and b-c of the parallelogram
# a P c b; B = 2b. The tracer pin b runs in a vertical slot. Both braces: a1-b1 parallel to ab
# and a2-c2 parallel to bc, joining the midpoints of opposite sides.
PANTOGRAPH = """
name = "pantograph"
[points]
o  = [0, 0]
a  = [10, 10]
P  = [20, 20]
c  = [30, 10]
B  = [40, 0]
b  = [20, 0]
a1 = [15, 15]
b1 = [25, 5]
a2 = [15, 5]
c2 = [25, 15]
[links]
frame = ["o"]
arm   = ["o", "a", "a1", "P"]
lower = ["P", "c2", "c", "B"]
ab    = ["a", "a2", "b"]
bc    = ["b", "b1", "c"]
{braces_links}
[joints]
o = { type = "revolute", links = ["frame", "arm"] }
a = { type = "revolute", links = ["arm", "ab"] }
P = { type = "revolute", links = ["arm", "lower"] }
c = { type = "revolute", links = ["lower", "bc"] }
b = { type = "revolute", links = ["ab", "bc"] }
{guide}
{braces_joints}
[driver]
joint = "o"
reference = "a"
"""
BRACES_LINKS = 'brace1 = ["a1", "b1"]\nbrace2 = ["a2", "c2"]'
BRACES_JOINTS = """a1 = { type = "revolute", links = ["arm", "brace1"] }
b1 = { type = "revolute", links = ["brace1", "bc"] }
a2 = { type = "revolute", links = ["ab", "brace2"] }
c2 = { type = "revolute", links = ["brace2", "lower"] }"""
GUIDE = 'guide = { type = "slot", links = ["frame", "ab"], axis = [0, 1], point = "b" }'


def _pantograph(braces: bool, guide: bool):
    text = (PANTOGRAPH.replace("{braces_links}", BRACES_LINKS if braces else "")
            .replace("{braces_joints}", BRACES_JOINTS if braces else "")
            .replace("{guide}", GUIDE if guide else ""))
    return linkwork.load_text(text)


def test_triple_parallel_cranks_are_over_closed():
    m = mobility(linkwork.load_text(TRIPLE_PARALLEL_CRANKS))
    # count: n = 5, g = 6 → F = 3·4 − 2·6 = 0 (001c §101); the parallel cranks move: F = 1
    assert m.count_mobility == 0
    assert m.real_mobility == 1
    assert m.overclosed and m.overclosure == 1
    assert len(m.redundant) == 1
    # hand statics: the self-stress has forces (1, −2, 1) in the three cranks, so every hinge
    # takes part in the redundancy
    assert set(m.dependent_pairs) == {"O1", "O2", "O3", "A1", "A2", "A3"}
    assert m.finite_motion is True
    assert m.constrained
    assert "übergeschlossen" in m.verdict()


def test_roberval_balance_is_over_closed():
    m = mobility(linkwork.load_text(ROBERVAL))
    # two parallelograms on one post: n = 5, g = 6 → count 0; it swings: 1 (hand)
    assert (m.count_mobility, m.real_mobility, m.overclosure) == (0, 1, 1)
    # hand statics: equal tensions in both pan posts, reactions at both beam pivots
    assert set(m.dependent_pairs) == {"U", "L", "UL", "LL", "UR", "LR"}


def test_pantograph_with_both_braces_carries_two_redundant_constraints():
    m = mobility(_pantograph(braces=True, guide=True))
    # unfolded: n = 8, g = 10 hinges, s = 1 → 2·11 − 24 + 4 = 2, count F = −1; each brace
    # parallel to a side of the parallelogram repeats it: 2 redundant, real F = 1 (hand)
    assert (m.counts.n, m.counts.g, m.counts.s) == (8, 10, 1)
    assert m.count_mobility == -1
    assert m.real_mobility == 1 and m.overclosure == 2
    assert m.finite_motion is True and m.constrained
    assert {"a1", "b1", "a2", "c2"} <= set(m.dependent_pairs)


def test_pantograph_with_guide_and_no_braces_is_constrained():
    m = mobility(_pantograph(braces=False, guide=True))
    # 5 hinges and a pin in a slot on 4 moving links: 12 − 10 − 1 = 1 (hand)
    assert m.count_mobility == m.real_mobility == 1
    assert m.constrained and not m.redundant


def test_free_pantograph_needs_one_more_input():
    m = mobility(_pantograph(braces=False, guide=False))
    # a hinged five-link chain: 2·5 − 15 + 4 = −1, two freedoms, one driver (001c §86)
    assert m.real_mobility == 2 == m.count_mobility
    assert m.inputs_needed == 1 and not m.constrained
    assert "needs 1 more input" in m.verdict()


TWO_DRIVERS = four_bar_text(name="four-bar with two drivers", driver=("O2", "O4"))


def test_a_driver_too_many_is_named():
    m = mobility(linkwork.load_text(TWO_DRIVERS))
    # a four-bar has one freedom (Grübler): the second driver is one too many
    assert m.real_mobility == 1
    assert len(m.surplus_drivers) == 1 and m.surplus_drivers[0] in ("O2", "O4")
    assert m.inputs_needed == 0 and not m.constrained


FLAT_PARALLELOGRAM = four_bar_text(name="parallelogram drawn in its change position",
                                   A=(20, 0), B=(60, 0),
                                   links=("frame", "crank", "coupler", "follower"))


def test_change_position_is_a_singular_design_not_an_over_closure():
    m = mobility(linkwork.load_text(FLAT_PARALLELOGRAM))
    # all four hinges on one line: the parallel crank may switch to the antiparallel one
    # (Wechsellage, 002b §44); the Jacobian loses one rank there, the chain has F = 1 next to it
    assert m.real_mobility == 2
    assert m.finite_motion is True and m.off_design_mobility == 1
    assert m.singular and not m.overclosed
    assert "Wechsellage" in m.verdict()


STRETCHED_TWO_BAR = """
name = "two bars stretched between two pivots"
[points]
O1 = [0, 0]
B  = [10, 0]
O2 = [20, 0]
[links]
frame = ["O1", "O2"]
l1 = ["O1", "B"]
l2 = ["B", "O2"]
[joints]
O1 = { type = "revolute", links = ["frame", "l1"] }
B  = { type = "revolute", links = ["l1", "l2"] }
O2 = { type = "revolute", links = ["l2", "frame"] }
[driver]
joint = "O1"
"""


def test_infinitesimal_mobility_only():
    m = mobility(linkwork.load_text(STRETCHED_TWO_BAR))
    # the three-link hinge chain is rigid (001a §4); stretched straight, B may move across the
    # line to first order only (hand: both circles about O1 and O2 touch at B)
    assert m.count_mobility == 0
    assert m.real_mobility == 1
    assert m.finite_motion is False
    assert m.singular and not m.overclosed
    assert "infinitesimal" in m.verdict()


WEDGE = """
name = "wedge"
[points]
O = [0, 0]
P = [10, 0]
Q = [0, 10]
W = [5, 5]
[links]
frame  = ["O"]
slider = ["P"]
wedge  = ["Q", "W"]
[joints]
gx = { type = "prismatic", links = ["frame", "slider"], axis = [1, 0], point = "P" }
gy = { type = "prismatic", links = ["frame", "wedge"], axis = [0, 1], point = "Q" }
gw = { type = "prismatic", links = ["slider", "wedge"], axis = [1, 1], point = "W" }
[driver]
joint = "gx"
"""


def test_wedge_moves_and_is_not_over_closed():
    m = mobility(linkwork.load_text(WEDGE))
    # Rosenauer's exception (001c §95): n = 3, s = 3, γ = 1: 2·3 − 9 + 4 = 1 = γ, constrained
    assert m.counts.gamma == 1 and m.counts.constrained
    assert m.real_mobility == 1 == m.count_mobility
    assert len(m.redundant) == 1 and m.redundant[0].wedge
    assert not m.overclosed and m.constrained


FOUR_SLIDERS = """
name = "four sliders"
[points]
O  = [0, 0]
p1 = [10, 0]
p2 = [10, 10]
p3 = [0, 12]
p4 = [-3, 5]
[links]
frame = ["O", "p4"]
l1 = ["p1", "p2"]
l2 = ["p2", "p3"]
l3 = ["p3", "p4"]
[joints]
s1 = { type = "prismatic", links = ["frame", "l1"], axis = [1, 0], point = "p1" }
s2 = { type = "prismatic", links = ["l1", "l2"], axis = [0, 1], point = "p2" }
s3 = { type = "prismatic", links = ["l2", "l3"], axis = [1, 1], point = "p3" }
s4 = { type = "prismatic", links = ["l3", "frame"], axis = [1, -2], point = "p4" }
[driver]
joint = "s1"
"""


def test_four_sliders_are_not_constrained():
    m = mobility(linkwork.load_text(FOUR_SLIDERS))
    # 001c §95: a four-bar with four sliders is not constrained (two freedoms)
    assert m.counts.gamma == 1
    assert m.real_mobility == 2 == m.count_mobility
    assert m.inputs_needed == 1


def test_report_of_an_over_closed_mechanism_has_no_solution_order():
    rep = structure_report(linkwork.load_text(TRIPLE_PARALLEL_CRANKS))
    assert rep.groups is None
    assert "over-constrained" in rep.structure_error
    assert rep.mobility.real_mobility == 1


def test_report_of_a_library_six_bar():
    rep = structure_report(linkwork.load("library:stephenson-iii-six-bar"))
    assert rep.structure_error is None and len(rep.groups) == 3
    doc = rep.as_dict()
    assert doc["real_mobility"] == 1 and doc["counts"]["g"] == 7
    assert doc["solution_order"][0] == ["crank"]


def test_design_jacobian_by_hand():
    from linkwork.kinematics.jacobian import design_jacobian

    mech = linkwork.load("library:crank-rocker")
    J = design_jacobian(mech, drivers=True)
    # 4 hinges × (x, y) + 1 driver; 3 moving links × (x, y, θ)
    assert J.matrix.shape == (9, 9)
    assert J.rows[:2] == (("O2", "x"), ("O2", "y")) and J.rows[-1] == ("O2", "driver")
    col = {c: i for i, c in enumerate(J.columns)}
    row = {r: i for i, r in enumerate(J.rows)}
    # hinge A = (0, 10) between crank and coupler: residual p_coupler(A) − p_crank(A), with
    # p(A) = (x − 10 sin θ, y + 10 cos θ) on each link, so ∂/∂θ at θ = 0 is ∓(−10, 0)
    assert J.matrix[row["A", "x"], col["crank", "θ"]] == pytest.approx(10.0)
    assert J.matrix[row["A", "x"], col["coupler", "θ"]] == pytest.approx(-10.0)
    assert J.matrix[row["A", "y"], col["crank", "θ"]] == pytest.approx(0.0)
    assert J.matrix[row["A", "x"], col["coupler", "x"]] == pytest.approx(1.0)
    assert J.matrix[row["A", "x"], col["crank", "x"]] == pytest.approx(-1.0)
    # hinge B = (30, 30): the joint's links are coupler, rocker, so the residual is
    # p_rocker(B) − p_coupler(B), and ∂p_rocker(B)/∂θ = (−30, 30) enters with a plus
    assert J.matrix[row["B", "x"], col["rocker", "θ"]] == pytest.approx(-30.0)
    assert J.matrix[row["B", "y"], col["rocker", "θ"]] == pytest.approx(30.0)
    # the driver fixes the crank's angle, in length units (× the drawing's diagonal)
    assert J.matrix[row["O2", "driver"], col["crank", "θ"]] == pytest.approx(mech.length_scale)
    assert J.rank() == 9


def _peaucellier_text():
    """Peaucellier's inversor (Pöschl §66a): AO₁ = O₁O₂ = r = 10, bars O₂B = O₂C = a = 25,
    rhombus ABQC of side b = 10, drawn at crank angle 60° (coordinates: test setup)."""
    import math

    import numpy as np

    r, a, b = 10.0, 25.0, 10.0
    O1, O2 = np.array([0.0, 0.0]), np.array([-r, 0.0])
    A = O1 + r * np.array([math.cos(math.pi / 3), math.sin(math.pi / 3)])
    d = np.hypot(*(A - O2))
    u = (A - O2) / d
    x = (a * a - b * b + d * d) / (2 * d)  # B, C on the circles about O₂ (a) and A (b)
    h = math.sqrt(a * a - x * x)
    nrm = np.array([-u[1], u[0]])
    B, C = O2 + x * u + h * nrm, O2 + x * u - h * nrm
    Q = B + C - A
    pts = {"O1": O1, "O2": O2, "A": A, "B": B, "C": C, "Q": Q}
    points = "\n".join(f"{k} = [{float(v[0])!r}, {float(v[1])!r}]" for k, v in pts.items())
    return f"""
name = "Peaucellier inversor"
[points]
{points}
[links]
frame = ["O1", "O2"]
crank = ["O1", "A"]
AB = ["A", "B"]
AC = ["A", "C"]
BQ = ["B", "Q"]
CQ = ["C", "Q"]
O2B = ["O2", "B"]
O2C = ["O2", "C"]
[joints]
O1 = {{ type = "revolute", links = ["frame", "crank"] }}
O2b = {{ type = "revolute", links = ["frame", "O2B"], point = "O2" }}
O2c = {{ type = "revolute", links = ["frame", "O2C"], point = "O2" }}
Ab = {{ type = "revolute", links = ["crank", "AB"], point = "A" }}
Ac = {{ type = "revolute", links = ["crank", "AC"], point = "A" }}
Bq = {{ type = "revolute", links = ["AB", "BQ"], point = "B" }}
Bo = {{ type = "revolute", links = ["AB", "O2B"], point = "B" }}
Cq = {{ type = "revolute", links = ["AC", "CQ"], point = "C" }}
Co = {{ type = "revolute", links = ["AC", "O2C"], point = "C" }}
Q = {{ type = "revolute", links = ["BQ", "CQ"] }}
[driver]
joint = "O1"
"""


def test_peaucellier_file_counts_its_double_hinges():
    mech = linkwork.load_text(_peaucellier_text())
    c = counts(mech)
    # Pöschl §66a: n = 8, g = 10 with A, B, C and O₂ counted double: g₁ = 2 (O₁, Q), g₂ = 4
    assert (c.n, c.g1, c.g2, c.g) == (8, 2, 4, 10)
    assert c.grubler == 4
    m = mobility(mech)
    assert m.real_mobility == 1 and m.constrained and not m.redundant
    # and it is Peaucellier's: Q runs on the line at (a² − b²)/(2r) = 26.25 from O₂ (eq. 104);
    # the rhombus closes while |O₂A| = 20 cos(φ/2) ≥ a − b = 15, i.e. φ ≤ 82.8°
    import numpy as np

    sol = linkwork.solve(mech, np.radians(np.linspace(-80, 80, 17)))
    assert sol.point("Q").position[:, 0] == pytest.approx(np.full(17, -10.0 + 26.25), abs=1e-9)
