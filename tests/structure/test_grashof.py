"""Grashof classes, inversion names, transmission angles and limit positions, against hand-made
examples of each class (closed forms worked out in the comments) and against the solver's
sampled motion and its bisected input limits (an independent numerical route)."""

import math

import numpy as np
import pytest

import linkwork
from linkwork.errors import StructureError
from linkwork.kinematics.motion import input_limits, whole_motion
from linkwork.structure import classify_four_bar, classify_slider_crank, four_bar_transmission, loops
from mechanism_texts import (SCOTCH_YOKE, four_bar_from_lengths, four_bar_text, hinged_loop_text,
                             slider_crank_text)

# ---------------------------------------------------------------------------- four-bar classes
# (frame, input, coupler, output) → (Grashof, type); s + l against p + q worked by hand
FOUR_BARS = [
    # s = 1 (input), l = 3: 1 + 3 < 3 + 2 → Grashof, shortest next to the frame, driven
    ((3, 1, 3, 2), "Grashof", "crank-rocker"),
    # shortest is the output: the crank-rocker driven at its rocker
    ((3, 2, 3, 1), "Grashof", "rocker-crank"),
    # shortest is the frame: double crank (Doppelkurbel)
    ((1, 3, 3, 2), "Grashof", "double crank"),
    # shortest is the coupler: Grashof double rocker
    ((3, 3, 1, 2), "Grashof", "double rocker"),
    # s + l = 2 + 5 = 7 > 3 + 3.5 = 6.5 → non-Grashof, every inversion a double rocker
    ((5, 2, 3, 3.5), "non-Grashof", "double rocker"),
    # s + l = 2 + 5 = 7 = 3 + 4 → change point
    ((2, 3, 5, 4), "change point", "double crank"),
]


@pytest.mark.parametrize("lengths,grashof,kind", FOUR_BARS)
def test_four_bar_classes(lengths, grashof, kind):
    c = classify_four_bar(*lengths)
    assert (c.grashof, c.type) == (grashof, kind)


def test_grashof_turning_links():
    # Pöschl §42: fixing the shortest gives a double crank, a neighbour of it a crank-rocker with
    # the shortest as crank, otherwise a double rocker
    c = classify_four_bar(3, 1, 3, 2)
    assert c.input_turns_fully and not c.output_turns_fully and not c.coupler_turns_fully
    c = classify_four_bar(3, 3, 1, 2)
    assert not c.input_turns_fully and not c.output_turns_fully and c.coupler_turns_fully
    c = classify_four_bar(5, 2, 3, 3.5)
    assert not (c.input_turns_fully or c.output_turns_fully or c.coupler_turns_fully)


def test_change_point_specials():
    assert "kite" in classify_four_bar(4, 4, 2, 2).special
    assert classify_four_bar(4, 2, 4, 2, crossed=False).special.startswith("parallel crank")
    assert classify_four_bar(4, 2, 4, 2, crossed=True).special.startswith("antiparallel crank")


def test_bad_lengths():
    with pytest.raises(StructureError):
        classify_four_bar(3, 0, 3, 2)
    with pytest.raises(StructureError):
        four_bar_transmission(10, 1, 1, 1)  # cannot be assembled


# the library's own descriptions state each class (independent of this code)
@pytest.mark.parametrize("name,grashof,kind,special", [
    ("crank-rocker", "Grashof", "crank-rocker", None),
    ("double-crank", "Grashof", "double crank", None),
    ("double-rocker", "Grashof", "double rocker", None),
    ("parallelogram", "change point", "double crank", "parallel crank"),
    ("antiparallelogram", "change point", "double crank", "antiparallel crank"),
    # base loops of the six-bars: "crank-rocker O2-A-B-O4" (file descriptions)
    ("stephenson-iii-six-bar", "Grashof", "crank-rocker", None),
    ("watt-i-six-bar", "Grashof", "crank-rocker", None),
])
def test_library_four_bars(name, grashof, kind, special):
    (lp,) = loops(linkwork.load(f"library:{name}"))
    assert lp.chain == "four-bar"
    assert (lp.grashof, lp.type) == (grashof, kind)
    if special:
        assert special in lp.name


# ---------------------------------------------------------------------------- closed forms
def _angle_between(u, v):
    cos = np.einsum("ij,ij->i", u, v) / (np.hypot(*u.T) * np.hypot(*v.T))
    return np.arccos(np.clip(cos, -1, 1))


def test_transmission_angle_of_a_crank_rocker():
    # d = 3, a = 1, b = 3, c = 2 (×10): the diagonal A–O4 runs from d − a = 2 to d + a = 4, so
    # cos μ = (b² + c² − f²)/(2bc) = (9 + 4 − 4)/12 = 3/4 and (9 + 4 − 16)/12 = −1/4
    lo, hi = math.acos(3 / 4), math.acos(-1 / 4)
    assert four_bar_transmission(30, 10, 30, 20) == pytest.approx((lo, hi))
    mech = linkwork.load_text(four_bar_from_lengths(30, 10, 30, 20, 60))
    (lp,) = loops(mech)
    assert lp.transmission == pytest.approx((lo, hi))
    assert lp.min_transmission == pytest.approx(lo)  # min(μ_min, 180° − μ_max) = 41.4°
    # sampled motion: the angle between coupler and output at B
    sol = whole_motion(mech, step=math.radians(0.05))
    A, B, O4 = (sol.point(p).position for p in ("A", "B", "O4"))
    mu = _angle_between(A - B, O4 - B)
    assert mu.min() == pytest.approx(lo, abs=1e-5) and mu.max() == pytest.approx(hi, abs=1e-5)


def test_dead_positions_of_a_crank_rocker():
    mech = linkwork.load_text(four_bar_from_lengths(30, 10, 30, 20, 60))
    (lp,) = loops(mech)
    dp = lp.dead_positions
    # rocker limits where crank and coupler are in line, |O2B| = b + a = 4 or b − a = 2: the
    # angle at O4 has cos = (d² + c² − g²)/(2dc) = −1/4 and 3/4; swing = difference
    swing = math.acos(-1 / 4) - math.acos(3 / 4)
    assert dp["output_swing"] == pytest.approx(swing)
    # crank angles there: cos β = (d² + g² − c²)/(2dg) = 21/24 (stretched) and 9/12 (folded,
    # crank pointing away); δ = β_folded − β_stretched; time ratio (π + δ)/(π − δ)
    delta = math.acos(9 / 12) - math.acos(21 / 24)
    assert dp["dead_position_angle"] == pytest.approx(delta)
    assert dp["time_ratio"] == pytest.approx((math.pi + delta) / (math.pi - delta))
    assert sorted(math.remainder(x, 2 * math.pi) for x in dp["input"]) == pytest.approx(
        sorted([math.acos(21 / 24), math.acos(9 / 12) - math.pi]))
    # sampled motion: the output's extreme angles about O4
    sol = whole_motion(mech, step=math.radians(0.01))
    B, O4 = sol.point("B").position, np.array([30.0, 0.0])
    psi = np.arctan2(B[:, 1] - O4[1], B[:, 0] - O4[0])
    assert psi.max() - psi.min() == pytest.approx(swing, abs=1e-6)
    assert sorted(dp["output_angle"]) == pytest.approx([psi.min(), psi.max()], abs=1e-6)


def test_input_limits_of_a_rocking_input():
    # library double rocker: frame 50, input 40, coupler 20, output 50. Input limits where
    # coupler and output are in line: |A O4| = c − b = 30 or c + b = 70;
    # cos φ = (a² + d² − f²)/(2ad) = 3200/4000 = 0.8 and −800/4000 = −0.2
    mech = linkwork.load("library:double-rocker")
    (lp,) = loops(mech)
    assert lp.input_turns_fully is False
    assert lp.input_limits == pytest.approx((math.acos(0.8), math.acos(-0.2)))
    assert lp.input_limits == pytest.approx(input_limits(mech), abs=1e-9)


def test_input_limits_of_a_non_grashof_four_bar_match_bisection():
    # the base loop of the PMKS Stephenson III (non-Grashof: 12.2 + 21.9 > 17.1 + 15.1)
    text = hinged_loop_text(name="base loop", units="m", driver="A",
                            hinges={"A": (7, 4), "B": (5, 16), "C": (25, 25), "D": (23, 10)},
                            links=("ground", "AB", "BC", "CD"), link_points={"CD": ["D", "C"]})
    mech = linkwork.load_text(text)
    (lp,) = loops(mech)
    assert lp.grashof == "non-Grashof"
    assert lp.input_limits == pytest.approx(input_limits(mech), abs=1e-9)


def test_rocker_driven_crank_rocker_limits():
    # the crank-rocker driven at its rocker (d 30, a 10, b 30, c 20 as above, driver O4 … here
    # the input is the output of the classification: rocker limits where crank and coupler
    # align, as in test_motion's closed form)
    mech = linkwork.load_text(four_bar_from_lengths(30, 10, 30, 20, 60, driver="O4"))
    (lp,) = loops(mech)
    assert lp.type == "rocker-crank" and lp.input_turns_fully is False
    assert lp.input_limits == pytest.approx(input_limits(mech), abs=1e-9)


# ---------------------------------------------------------------------------- slider-cranks
def test_slider_crank_chain_classes():
    # r + e against l (hand): 1 + 0.5 < 3 Grashof; 2 + 0.5 = 2.5 change point; 2 + 0.5 > 2 not
    assert classify_slider_crank(1, 3, 0.5).grashof == "Grashof"
    assert classify_slider_crank(2, 2.5, 0.5).grashof == "change point"
    assert classify_slider_crank(2, 2, 0.5).grashof == "non-Grashof"
    # Rosenauer's types by the fixed link (001a §4)
    assert [classify_slider_crank(1, 3, 0, f).inversion for f in ("guide", "rod", "crank", "block")] \
        == ["I", "II", "III", "IV"]
    assert "oscillating crank-slotted lever" in classify_slider_crank(1, 3, 0, "rod").name
    assert "Gnome" in classify_slider_crank(1, 3, 0, "crank").name
    assert classify_slider_crank(1, 3, 0).centric and not classify_slider_crank(1, 3, 0.2).centric
    with pytest.raises(StructureError):
        classify_slider_crank(1, 3, 0, "rocker")


@pytest.mark.parametrize("name,inversion", [
    ("slider-crank-centric", "I"),
    ("slider-crank-offset", "I"),
    ("pmks-slider-crank-tracer", "I"),
    # the library describes these as the coupler-fixed and the crank's-neighbour-fixed inversions
    ("oscillating-crank-slotted-lever", "II"),
    ("rotating-crank-slotted-lever", "III"),
    ("whitworth-quick-return", "III"),
])
def test_library_slider_crank_inversions(name, inversion):
    (lp,) = loops(linkwork.load(f"library:{name}"))
    assert lp.chain == "slider-crank" and lp.inversion == inversion
    assert lp.grashof == "Grashof"


HAND_PUMP = """
name = "hand pump (fixed block)"
[points]
F = [0, 0]
S = [5, 0]
H = [5, 40]
K = [-3, 46]
[links]
frame   = ["F", "S"]
plunger = ["S", "H"]
crank   = ["H", "K"]
handle  = ["K", "F"]
[joints]
S = { type = "prismatic", links = ["frame", "plunger"], axis = [0, 1], point = "S" }
H = { type = "revolute", links = ["plunger", "crank"] }
K = { type = "revolute", links = ["crank", "handle"] }
F = { type = "revolute", links = ["handle", "frame"] }
[driver]
joint = "F"
"""


def test_type_four_fixed_block():
    (lp,) = loops(linkwork.load_text(HAND_PUMP))
    # crank HK = 10, rod KF = √(9 + 2116), offset = distance of F from the plunger's line x = 5
    assert lp.lengths == pytest.approx({"crank": 10.0, "rod": math.sqrt(2125), "offset": 5.0})
    # the sliding link next to the rod is the frame itself: the block is fixed, type IV
    assert lp.inversion == "IV" and lp.links["block"] == "frame"


def test_offset_slider_crank_stroke_and_quick_return():
    mech = linkwork.load("library:slider-crank-offset")
    (lp,) = loops(mech)
    r, l, e = 50.0, 200.0, 20.0  # from the file's comment
    assert lp.lengths == pytest.approx({"crank": r, "rod": l, "offset": e})
    dp = lp.dead_positions
    # dead centres: crank and rod in line, |OB| = l ± r, B on y = e
    stroke = math.sqrt((l + r) ** 2 - e * e) - math.sqrt((l - r) ** 2 - e * e)
    assert dp["stroke"] == pytest.approx(stroke)
    # δ = asin(e/(l − r)) − asin(e/(l + r)) (the crank positions' deviation from a line)
    delta = math.asin(e / (l - r)) - math.asin(e / (l + r))
    assert dp["dead_position_angle"] == pytest.approx(delta)
    # the solver's motion: the block's travel along the guide
    sol = whole_motion(mech, step=math.radians(0.01))
    x = sol.point("B").position[:, 0]
    assert x.max() - x.min() == pytest.approx(stroke, abs=1e-6)


def test_centric_slider_crank_transmission_angle():
    mech = linkwork.load("library:slider-crank-centric")
    (lp,) = loops(mech)
    # μ = 90° − |β|, sin β = r sin φ / l: from 90° − asin(r/l) to 90° (r = 50, l = 200)
    assert lp.transmission == pytest.approx((math.pi / 2 - math.asin(0.25), math.pi / 2))
    assert lp.dead_positions["stroke"] == pytest.approx(100.0)  # 2r
    assert lp.dead_positions["time_ratio"] == pytest.approx(1.0)
    sol = whole_motion(mech, step=math.radians(0.05))
    A, B = sol.point("A").position, sol.point("B").position
    beta = np.abs(np.arctan2(A[:, 1] - B[:, 1], np.abs(A[:, 0] - B[:, 0])))
    assert (math.pi / 2 - beta).min() == pytest.approx(lp.transmission[0], abs=1e-5)




def test_swinging_crank_limits():
    # r = 30, l = 20, e = 0 (pin B in the frame's slot y = 0): |30 sin φ| ≤ 20, so the crank
    # swings between ±asin(2/3); drawn at φ = 20°
    phi = math.radians(20)
    ax, ay = 30 * math.cos(phi), 30 * math.sin(phi)
    mech = linkwork.load_text(slider_crank_text(
        name="slider-crank whose crank only swings", A=(ax, ay), B=(ax + math.sqrt(400 - ay * ay), 0),
        O=(0, 0), slot=True))
    (lp,) = loops(mech)
    # l + e = 20 < 30: the chain's fully turning link is the rod, whose neighbour is the die
    # block; the frame, the other sliding link, is then Rosenauer's link 3: type IV (the pump
    # handle swings while the short link turns against the block)
    assert lp.grashof == "Grashof" and lp.inversion == "IV"
    assert lp.links["crank"] == "rod" and lp.links["block"] == "frame"
    assert lp.input_turns_fully is False
    assert lp.input_limits == pytest.approx((-math.asin(2 / 3), math.asin(2 / 3)))
    assert lp.input_limits == pytest.approx(input_limits(mech), abs=1e-9)


def test_oscillating_crank_slotted_lever_quick_return():
    mech = linkwork.load("library:oscillating-crank-slotted-lever")
    (lp,) = loops(mech)
    dp = lp.dead_positions
    # crank 30, frame 60, slot through the lever pivot: the lever swings ±asin(30/60) = ±30°;
    # at its limits the crank is square to the lever, 60° either side of C→B (cos = 30/60), so
    # the crank turns 120° on the quick stroke and 240° on the slow one: time ratio 2
    assert dp["output_swing"] == pytest.approx(math.radians(60))
    assert dp["time_ratio"] == pytest.approx(2.0)
    assert sorted(dp["input"]) == pytest.approx(sorted([math.radians(-30), math.radians(-150)]))
    sol = whole_motion(mech, step=math.radians(0.01))
    D = sol.point("D").position
    psi = np.arctan2(D[:, 1] + 60, D[:, 0])  # lever B→D, B = (0, −60)
    assert psi.max() - psi.min() == pytest.approx(math.radians(60), abs=1e-6)


def test_piston_driven_engine_limits_are_the_dead_centres():
    from linkwork.io.files import resolve

    text = resolve("library:slider-crank-centric")[1]
    text = text.split("[driver]")[0] + '[driver]\njoint = "guide"\nspeed = "100 mm/s"\n'
    mech = linkwork.load_text(text)
    (lp,) = loops(mech)
    # B at x = 225.96 in the file; dead centres at x = l + r = 250 and l − r = 150
    x0 = 225.959179422654
    assert lp.input_limits == pytest.approx((150 - x0, 250 - x0))
    assert lp.input_limits == pytest.approx(input_limits(mech), abs=1e-7)


# ---------------------------------------------------------------------------- two sliders
def test_two_slider_chains_are_named():
    # both sliders on the frame: the elliptic trammel (Kreuzschieber); both on the yoke: the
    # Scotch yoke (Kreuzschleife) — Rosenauer's adjacent sliders, basic task V (001c §78)
    (lp,) = loops(linkwork.load("library:ellipsograph"))
    assert lp.chain == "two-slider" and "elliptic trammel" in lp.name
    (lp,) = loops(linkwork.load_text(SCOTCH_YOKE))
    assert lp.chain == "two-slider" and "Scotch yoke" in lp.name


KULISSE = four_bar_text(name="four-bar with the rocker replaced by a curved slot",
                        curved_slot=True)


def test_curved_slot_acts_as_the_rocker_it_replaces():
    # Rosenauer §4, Fig. 30: B's arc about O4 may be a block in a circular slot of radius O4B
    # without changing the motion: frame 40, crank 10, coupler √1300, "rocker" √1000
    mech = linkwork.load_text(KULISSE)
    (lp,) = loops(mech)
    assert lp.chain == "four-bar" and lp.type == "crank-rocker"
    assert list(lp.lengths.values()) == pytest.approx([40, 10, math.sqrt(1300), math.sqrt(1000)])
    sol = whole_motion(mech, step=math.radians(0.01))
    B = sol.point("B").position
    psi = np.arctan2(B[:, 1], B[:, 0] - 40)
    assert lp.dead_positions["output_swing"] == pytest.approx(psi.max() - psi.min(), abs=1e-6)
