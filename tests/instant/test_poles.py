"""Poles: the velocity method and the three-pole theorem must agree (two independent ways), the
pole counts and schedules are Rosenauer's (§84, §85, §91, §92) and Pöschl's (§51), and the
poles the theorem cannot reach are those of chains without four-bar loops (Rosenauer 1937)."""

import re
from dataclasses import replace
from itertools import combinations

import numpy as np
import pytest

import linkwork
from linkwork.instant import (agreement, kennedy_poles, pole_count, pole_discrepancy,
                              pole_line_count, pole_lines, pole_schedule, poles)

import instant_mechanisms as im

TOL = 1e-9


def _agree(mech, inputs):
    sol = linkwork.solve(mech, inputs, order=1)
    ok = sol.status == linkwork.Status.OK
    assert ok.any()
    P, K = poles(sol), kennedy_poles(sol)
    ag = agreement(P, K, mech.length_scale)
    for pair, d in ag.items():
        both = ok & np.isfinite(d)
        assert both.sum() >= ok.sum() - 1, f"{pair}: undefined too often"
        assert np.all(d[both] < TOL), f"{P.label(*pair)} {pair}: {d[both].max():.2e}"
    return sol, P, K


# ---------------------------------------------------------------------------- counting
@pytest.mark.parametrize("n,poles_,lines", [(3, 3, 1), (4, 6, 4), (5, 10, 10), (6, 15, 20),
                                            (7, 21, 35), (8, 28, 56), (9, 36, 84), (10, 45, 120)])
def test_counts_are_rosenauers_tables(n, poles_, lines):
    # Rosenauer §84 (lines 5049–5056) and §85 (lines 5083–5097)
    assert pole_count(n) == poles_
    assert pole_line_count(n) == lines


def test_four_bar_schedule_is_the_textbooks():
    # Rosenauer §75: |14−34 / 12−23| → 13 and |12−14 / 23−34| → 24, frame 4
    text, _ = im.four_bar(4.0, 1.5, 3.5, 3.0, 1.0)
    text = text.replace('frame = "frame"', 'frame = "l4"')
    for old, new in (("frame", "l4"), ("crank", "l1"), ("coupler", "l2"), ("rocker", "l3")):
        text = text.replace(f"{old} = [", f"{new} = [").replace(f'"{old}"', f'"{new}"')
    # order the links 1, 2, 3, 4 as Rosenauer numbers them
    head, rest = text.split("[links]")
    links, joints = rest.split("[joints]")
    rows = sorted(r for r in links.strip().splitlines())
    mech = linkwork.load_text(head + "[links]\n" + "\n".join(rows) + "\n[joints]" + joints)
    sch = pole_schedule(mech)
    assert sch.links == ("l1", "l2", "l3", "l4")
    assert [s.text(sch.links) for s in sch.derived] == ["P13 = P12P23 ∩ P14P34", "P24 = P12P14 ∩ P23P34"]
    assert sch.unreachable == ()
    assert len(sch.primary) == 4


@pytest.mark.parametrize("builder,derived", [
    (im.watt, {"13", "14", "15", "24", "26", "35", "36", "46"}),       # Rosenauer §91
    (im.stephenson, {"13", "14", "24", "25", "26", "35", "36", "56"}),  # Rosenauer §92
    (im.rosenkranz, {"13", "26", "46", "25", "15", "14", "35", "34"}),  # Pöschl Beispiel 16
])
def test_six_bars_every_pole_reachable(builder, derived):
    mech = linkwork.load_text(builder())
    sch = pole_schedule(mech)
    assert sch.unreachable == ()
    assert len(sch.steps) == 15 and len(sch.primary) == 7
    got = {s.text(sch.links).split(" = ")[0][1:] for s in sch.derived}
    assert got == derived
    sol, P, K = _agree(mech, mech.driver_input_at_design(mech.drivers[0]) + np.radians([-4, 0, 3, 7]))
    lines = pole_lines(P, mech.length_scale)
    assert len(lines) == 20
    assert max(float(np.nanmax(pl.residual)) for pl in lines) < 1e-9


def test_watt_check_lines():
    # the four lines Rosenauer leaves undrawn as checks (§91): 35–36–56, 24–26–46, 13–14–34, 34–36–46
    mech = linkwork.load_text(im.watt())
    sol = linkwork.solve(mech, np.radians([3.0, 10.0]), order=1)
    P = poles(sol)
    L = mech.length_scale
    for trio in ("3 5 6", "2 4 6", "1 3 4", "3 4 6"):
        i, j, k = (f"l{x}" for x in trio.split())
        res = next(pl.residual for pl in pole_lines(P, L) if set(pl.links) == {i, j, k})
        assert np.all(res < 1e-10)


def test_chain_without_four_bar_loops_needs_more_than_the_theorem():
    # Rosenauer 1937 (LU Mech. II No. 7): three hinge pentagons, no four-bar. The ten hinges
    # are the only poles the three-pole theorem reaches; velocities give all 28.
    mech = linkwork.load_text(im.no_four_bar_loops())
    sch = pole_schedule(mech)
    assert len(sch.primary) == 10
    assert len(sch.unreachable) == 28 - 10 - len(sch.derived)
    assert len(sch.unreachable) > 0
    assert "not reachable by the three-pole theorem" in sch.text()
    sol = linkwork.solve(mech, np.radians([-2.0, 0.0, 2.0]), order=1)
    assert (sol.status == linkwork.Status.OK).all()
    P, K = poles(sol), kennedy_poles(sol, sch)
    for pair in sch.unreachable:
        assert np.isnan(K[pair].coords).all()
        assert np.isfinite(P[pair].coords).all()
    # and the velocity poles obey the three-pole theorem on every one of the 56 lines
    assert max(float(np.nanmax(pl.residual)) for pl in pole_lines(P, mech.length_scale)) < 1e-9


# ---------------------------------------------------------------------------- links on one hinge
def _jansen():
    """Jansen's linkage at crank angles all round: three links share each of the hinges A, B
    and D, so for every position many pairs of its pole lines are one line."""
    mech = linkwork.load("library:jansen-linkage")
    u0 = mech.driver_input_at_design(mech.drivers[0])
    sol = linkwork.solve(mech, u0 + np.radians([0.0, 50.0, 110.0, 180.0, 250.0, 320.0]), order=1)
    assert (sol.status == linkwork.Status.OK).all()
    return mech, sol


def _unit_line(P, a, b, L):
    """(N, 3) unit line through the poles a and b of P, lengths in units of L."""
    p, q = (np.asarray(P[x].coords) * [1 / L, 1 / L, 1] for x in (a, b))
    ln = np.cross(p, q)
    return ln / np.linalg.norm(ln, axis=1, keepdims=True)


def test_jansen_every_pole_by_the_theorem_is_the_velocity_pole():
    mech, sol = _jansen()
    sch = pole_schedule(mech)
    assert sch.unreachable == ()
    P, K = poles(sol), kennedy_poles(sol, sch)
    for pair, d in agreement(P, K, mech.length_scale).items():
        assert np.isfinite(K[pair].coords).all(), f"{P.label(*pair)} undetermined"
        assert np.all(d < TOL), f"{P.label(*pair)}: {d.max():.2e}"


def test_jansen_schedule_lines_are_different_lines():
    # The two lines printed for a pole give it on their own (kennedy_poles otherwise picks the
    # best pair of all a step keeps), and every two lines a step keeps are different lines:
    # the sine of their angle, measured on the velocity poles, is far from 0.
    mech, sol = _jansen()
    L = mech.length_scale
    sch = pole_schedule(mech)
    printed = replace(sch, steps=tuple(replace(s, lines=s.lines[:2]) for s in sch.steps))
    P = poles(sol)
    for pair, d in agreement(P, kennedy_poles(sol, printed), L).items():
        assert np.all(d < TOL), f"{P.label(*pair)}: {d.max():.2e}"
    for st in sch.derived:
        for a, b in combinations(st.lines, 2):
            sine = np.linalg.norm(np.cross(_unit_line(P, *a.poles, L), _unit_line(P, *b.poles, L)), axis=1)
            assert sine.min() > 1e-3, f"{st.text(sch.links)}: {a.text(sch.links)} = {b.text(sch.links)}"


def test_jansen_schedule_reads_like_a_textbook():
    mech = linkwork.load("library:jansen-linkage")
    sch = pole_schedule(mech)
    text = sch.lines()
    assert "P35 = hinge A1 (common to three links)" in text
    # the foot's pole: the line of the crank pivot O and P28, and the line B D of link_c
    assert "P18 = P12P28 ∩ P16P68" in text
    for st in sch.derived:
        assert re.fullmatch(r"P\d\d = P\d\dP\d\d ∩ P\d\dP\d\d", st.text(sch.links))
        for src in st.lines[:2]:  # each printed line is P_im P_km for a third link m
            assert len(set(st.pair) | set(src.poles[0]) | set(src.poles[1])) == 3


def test_only_coincident_lines_leave_a_pole_unreachable():
    # Coupler, rocker and arm share B: the lines P13P35 and P14P45 to P15 are both O4 B, and the
    # lines to P25 are both A B. The poles are not NaN in disguise but reported unreachable.
    mech = linkwork.load_text(im.four_bar_with_driven_arm())
    sch = pole_schedule(mech)
    assert [sch.links.index(ln) + 1 for ln in ("frame", "crank", "coupler", "rocker", "arm")] == [1, 2, 3, 4, 5]
    assert sch.lines()[-1] == "not reachable by the three-pole theorem: P15, P25"
    L = mech.length_scale
    u0 = np.array([mech.driver_input_at_design(d) for d in mech.drivers])
    inputs = u0 + np.radians([[0.0, 0.0], [5.0, 10.0], [-5.0, 20.0]])
    found = []
    for arm_speed in (0.5, -2.0):
        sol = linkwork.solve(mech, inputs, velocities=np.array([[1.0, arm_speed]] * 3), order=1)
        P, K = poles(sol), kennedy_poles(sol, sch)
        for pair, d in agreement(P, K, L).items():
            if pair in sch.unreachable:
                assert np.isnan(K[pair].coords).all()
            else:
                assert np.all(d < TOL), f"{P.label(*pair)}: {d.max():.2e}"
        # the theorem's one line O4 B does hold P15, but where on it depends on the second input
        O4B = _unit_line(P, ("frame", "rocker"), ("coupler", "rocker"), L)
        p15 = np.asarray(P["frame", "arm"].coords) * [1 / L, 1 / L, 1]
        assert np.allclose((O4B * p15).sum(1) / np.linalg.norm(p15, axis=1), 0, atol=1e-12)
        found.append(P["frame", "arm"])
    assert np.all(pole_discrepancy(*found, L) > 1e-3)


# ---------------------------------------------------------------------------- agreement
def test_random_four_bars_agree():
    rng = np.random.default_rng(7)
    for _ in range(25):
        pts = rng.uniform(-10, 10, size=(4, 2))
        mech = linkwork.load_text(im.four_bar_from_points(*pts))
        u0 = mech.driver_input_at_design(mech.drivers[0])
        _agree(mech, u0 + np.radians(rng.uniform(-15, 15, 6)))


@pytest.mark.parametrize("slot", [False, True])
def test_random_slider_cranks_agree(slot):
    rng = np.random.default_rng(11)
    for _ in range(10):
        r = rng.uniform(1, 3)
        mech = linkwork.load_text(im.slider_crank(r, rng.uniform(3.5, 8), rng.uniform(-1, 1),
                                                  rng.uniform(0, 2 * np.pi), slot=slot))
        u0 = mech.driver_input_at_design(mech.drivers[0])
        _agree(mech, u0 + np.radians(rng.uniform(-30, 30, 6)))


@pytest.mark.parametrize("slot", [False, True])
def test_random_crank_slotted_levers_agree(slot):
    rng = np.random.default_rng(5)
    for _ in range(10):
        mech = linkwork.load_text(im.slotted_lever(rng.uniform(0.5, 1.5), (rng.uniform(-1, 1), -3),
                                                   rng.uniform(0, 2 * np.pi), slot=slot))
        u0 = mech.driver_input_at_design(mech.drivers[0])
        _agree(mech, u0 + np.radians(rng.uniform(-40, 40, 6)))


@pytest.mark.parametrize("builder", [im.watt, im.stephenson, im.rosenkranz])
def test_random_six_bars_agree(builder):
    rng = np.random.default_rng(13)
    for _ in range(8):
        mech = linkwork.load_text(builder(rng))
        u0 = mech.driver_input_at_design(mech.drivers[0])
        sol, P, _ = _agree(mech, u0 + np.radians(rng.uniform(-6, 6, 5)))
        assert max(float(np.nanmax(pl.residual)) for pl in pole_lines(P, mech.length_scale)) < 1e-9


def test_swinging_blocks_agree():
    for slot in (False, True):
        mech = linkwork.load_text(im.swinging_block(1.0, (4.0, 0.5), 0.8, slot=slot))
        _agree(mech, np.radians([20.0, 45.8, 90, 200]))


def test_library_six_bars_and_slotted_levers_agree():
    for name in ("pmks-stephenson-iii", "crank-rocker", "pmks-slider-crank-tracer",
                 "pmks-teaching-slider-crank"):
        mech = linkwork.load(f"library:{name}")
        u0 = mech.driver_input_at_design(mech.drivers[0])
        _agree(mech, u0 + np.radians([-5.0, 0.0, 5.0]))


def test_poles_at_infinity_agree():
    # parallelogram: the coupler translates, P13 at infinity normal to the cranks
    mech = linkwork.load_text(im.parallelogram(0.7))
    sol, P, K = _agree(mech, np.radians([20.0, 40.0, 110.0]))
    for p in (P["frame", "coupler"], K["frame", "coupler"]):
        assert p.is_infinite.all()
        crank = np.c_[np.cos(np.radians([20, 40, 110])), np.sin(np.radians([20, 40, 110]))]
        assert np.allclose(np.abs((p.direction.xy * crank).sum(1)), 1.0)
    # slider: P14 at infinity normal to the guide, from both methods
    mech = linkwork.load_text(im.slider_crank(1.0, 3.0, 0.0, 1.0))
    sol, P, K = _agree(mech, np.radians([30.0, 60.0, 150.0]))
    for p in (P["frame", "slider"], K["frame", "slider"]):
        assert p.is_infinite.all() and np.allclose(np.abs(p.direction.xy[:, 1]), 1.0)


def test_gear_pitch_points_are_poles():
    # planet on a fixed sun: P(frame, planet) is the pitch point; both methods agree
    mech = linkwork.load_text(im.planetary(2.0, 1.0))
    sol, P, K = _agree(mech, np.radians([0.0, 40.0, 200.0]))
    ang = np.radians([0.0, 40.0, 200.0])
    assert np.allclose(P["frame", "planet"].xy, 2.0 * np.c_[np.cos(ang), np.sin(ang)])
    # rack and pinion: the wheel's pole relative to the frame is the contact point on y = 0
    mech = linkwork.load_text(im.rolling_wheel(1.5))
    sol, P, K = _agree(mech, np.array([0.0, 0.7, 2.0]))
    assert np.allclose(P["frame", "wheel"].xy, np.c_[[0.0, 0.7, 2.0], [0.0, 0.0, 0.0]], atol=1e-12)


def test_velocity_pole_has_equal_velocities_in_both_links():
    # Rosenauer §62, eq. (33): at P_ij the coincident points of i and j have equal velocities
    mech = linkwork.load_text(im.stephenson())
    sol = linkwork.solve(mech, np.radians([2.0, 8.0]), order=1)
    P = poles(sol)
    for a, b in P:
        X = P[a, b].xy
        fin = np.isfinite(X).all(axis=1)
        va = sol.point_on(a, sol.local(a, np.where(fin[:, None], X, 0)))
        vb = sol.point_on(b, sol.local(b, np.where(fin[:, None], X, 0)))
        assert np.allclose(va.velocity[fin], vb.velocity[fin], atol=1e-9)


def test_discrepancy_is_projective():
    from linkwork.geometry import Point
    a = Point(np.array([[1.0, 0.0, 0.0], [3.0, 4.0, 1.0]]))
    b = Point(np.array([[-2.0, 0.0, 0.0], [3.0, 4.0 + 1e-6, 1.0]]))
    d = pole_discrepancy(a, b, 1.0)
    assert d[0] == 0.0 and 0 < d[1] < 1e-6


def test_circular_slot_and_internal_gear_agree():
    mech = linkwork.load_text(im.circular_slot_four_bar())
    sch = pole_schedule(mech)
    assert sch.lines() == ["P12 = hinge O2", "P13 = hinge O4", "P23 = n(A) ∩ P12P13"]
    _agree(mech, np.radians([40.0, 50.2, 60.0]))
    mech = linkwork.load_text(im.cardan(1.0))
    assert "P13 = pitch point of gear mesh" in pole_schedule(mech).lines()
    sol, P, K = _agree(mech, np.radians([0.0, 33.0, 250.0]))
    ang = np.radians([0.0, 33.0, 250.0])
    assert np.allclose(P["frame", "planet"].xy, 2.0 * np.c_[np.cos(ang), np.sin(ang)])
