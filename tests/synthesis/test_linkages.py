"""Linkages synthesized for prescribed positions (`linkwork.synthesis.linkages`), checked by the
engine: the mechanism file written, loaded and solved at each position's input angle must put
the coupler's points where the positions (moved here with rotation matrices) put them, to
1e-9; the moving pivots the engine finds stay on circles about their fixed pivots; the
generating four-bar (closed form in test_burmester) is found among the Burmester four-bars with
its Grashof type and its transmission angles from the cosine law; the circuit defect the design
check reports is exactly where the engine lands on the other assembly."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.kinematics import Status, solve
from linkwork.synthesis.burmester import burmester_points, centre_point_curve, dyad
from linkwork.synthesis.linkages import Linkage, linkages
from linkwork.synthesis.positions import Positions, SynthesisError
from four_bar_by_hand import A_LEN, B_LEN, C_LEN, O2, O4, generated, move


def engine_reproduces(lk: Linkage, tmp_path, tol=1e-9) -> float:
    """Write the file, load it, solve at the input angles; the largest distance (relative to
    the positions' size) of the coupler points P, Q and the pins from where the positions and
    the dyads put them."""
    path = tmp_path / "synth.toml"
    path.write_text(lk.mechanism_text())
    mech = linkwork.load(path)
    pos = lk.positions
    theta = lk.input_angles()
    sol = solve(mech, theta, order=1)
    assert np.all(sol.status != Status.UNREACHABLE)
    worst = 0.0
    for name in ("P", "Q", "A", "B"):
        local = mech.points[name]
        want = np.array([move(pos.poses[lk.ref], pos.poses[k], local) for k in range(len(pos))])
        got = sol.point(name).position
        worst = max(worst, float(np.max(np.hypot(*(got - want).T))) / pos.size)
    # the pins stay on their circles (or, for a slider, on the line of stroke)
    A = sol.point("A").position
    r = np.hypot(*(A - mech.points["A0"]).T)
    worst = max(worst, float(np.ptp(r)) / pos.size)
    B = sol.point("B").position
    if "B0" in mech.points:
        r = np.hypot(*(B - mech.points["B0"]).T)
        worst = max(worst, float(np.ptp(r)) / pos.size)
    else:
        g = lk.guide
        off = (B - B[0]) @ np.array([-g[1], g[0]])
        worst = max(worst, float(np.abs(off).max()) / pos.size)
    return worst


FIVE, A5, B5 = generated([20, 50, 80, 110, 140])


def test_the_generating_four_bar_is_found_first_and_reproduced(tmp_path):
    found = linkages(burmester_points(FIVE).dyads)
    best = found[0]
    assert np.allclose(best.input.centre.xy, O2, atol=1e-9) and np.allclose(best.output.centre.xy, O4, atol=1e-9)
    c = best.check
    assert c.kind == "four-bar" and c.grashof == "Grashof" and "crank-rocker" in c.name
    assert c.input_turns_fully and c.sense == 1
    assert not (c.order_defect or c.circuit_defect or c.branch_defect)
    assert c.pose_error <= 1e-9 and c.usable()
    assert best.lengths == pytest.approx({"input": A_LEN, "coupler": B_LEN, "output": C_LEN, "frame": 4.0}, rel=1e-9)
    # transmission angles at the positions from the cosine law on the diagonal A–O4
    f = np.hypot(*(O4 - A5).T)
    mu = np.arccos((B_LEN**2 + C_LEN**2 - f**2) / (2 * B_LEN * C_LEN))
    assert c.transmission == pytest.approx(np.minimum(mu, np.pi - mu), abs=1e-9)
    assert engine_reproduces(best, tmp_path) <= 1e-9


def test_every_circuit_defect_is_where_the_engine_lands_elsewhere(tmp_path):
    found = linkages(burmester_points(FIVE).dyads)
    assert len(found) == 12  # 4 real points: 6 pairs, each crank once the input
    for lk in found:
        c = lk.check
        if c.circuit_defect:
            assert c.pose_error > 1e-3
        else:
            assert c.pose_error <= 1e-9
            assert engine_reproduces(lk, tmp_path) <= 1e-9


def test_four_positions_two_chosen_centre_points(tmp_path):
    pos, A, B = generated([10, 45, 80, 120])
    K = centre_point_curve(pos)
    # a second centre point of the curve: on the line through P12 at 40°
    from linkwork.synthesis.burmester import curve_samples
    pts = curve_samples(K, samples=36)
    pts = pts[np.isfinite(pts).all(axis=1) & (np.hypot(*pts.T) < 20)]
    for M in pts[::5]:
        if np.hypot(*(M - O2)) < 0.5:
            continue
        lk = Linkage(dyad(pos, O2), dyad(pos, M))
        if lk.check.circuit_defect:
            continue
        assert lk.check.pose_error <= 1e-9
        assert engine_reproduces(lk, tmp_path) <= 1e-9


def test_four_positions_slider_crank_from_the_asymptote(tmp_path):
    pos, A, B = generated([10, 45, 80, 120])
    slider = centre_point_curve(pos).slider()
    assert slider.is_slider
    D = np.array([move(pos.poses[0], pos.poses[k], slider.circle.xy) for k in range(4)])
    u = (D[-1] - D[0]) / np.hypot(*(D[-1] - D[0]))
    assert np.abs((D - D[0]) @ np.array([-u[1], u[0]])).max() < 1e-9  # collinear homologous points
    lk = Linkage(dyad(pos, O2), slider)
    assert lk.kind == "slider-crank" and abs(abs(lk.guide @ u) - 1) < 1e-9
    assert lk.check.pose_error <= 1e-9 and not lk.check.circuit_defect
    assert engine_reproduces(lk, tmp_path) <= 1e-9


def test_three_positions_chosen_moving_pivots(tmp_path):
    rng = np.random.default_rng(5)
    pos = Positions.from_poses([[0.0, 0.0, 0.0], [1.0, 0.4, 0.35], [1.8, 1.2, 0.8]])
    for _ in range(6):
        za, zb = rng.uniform(-1, 2, 2), rng.uniform(-1, 2, 2)
        lk = Linkage(dyad(pos, circle=za), dyad(pos, circle=zb))
        if lk.check.circuit_defect or lk.kind != "four-bar":
            continue
        assert engine_reproduces(lk, tmp_path) <= 1e-9


def test_bad_pairs_are_refused():
    d = dyad(FIVE, O2)
    with pytest.raises(SynthesisError, match="coincide"):
        Linkage(d, dyad(FIVE, O2))
    slider = centre_point_curve(FIVE.subset([0, 1, 2, 3])).slider()
    with pytest.raises(SynthesisError, match="slider"):
        Linkage(slider, dyad(FIVE.subset([0, 1, 2, 3]), O2))
    with pytest.raises(SynthesisError, match="different positions"):
        Linkage(d, dyad(FIVE.subset([0, 1, 2, 3]), O4))


def test_four_positions_without_chosen_pivots(tmp_path):
    from linkwork.synthesis.linkages import four_position_linkages

    pos, A, B = generated([10, 45, 80, 120])
    found = four_position_linkages(pos, candidates=8)
    assert found and found[0].check.usable()
    for lk in found[:3]:
        assert engine_reproduces(lk, tmp_path) <= 1e-9


def slider_crank_poses(degrees, r=1.0, l=3.5, e=0.4):
    """Coupler poses (origin at the crank pin A, x-axis towards the slider pin B) of the offset
    slider-crank A0 = (0, 0), crank r, coupler l, slider on the line y = e, by hand."""
    th = np.radians(degrees)
    A = r * np.column_stack([np.cos(th), np.sin(th)])
    B = np.column_stack([A[:, 0] + np.sqrt(l**2 - (e - A[:, 1]) ** 2), np.full(len(th), e)])
    return Positions.from_poses(np.column_stack([A, np.arctan2(*(B - A).T[::-1])])), A, B


def test_five_positions_of_a_slider_crank_give_the_slider(tmp_path):
    pos, A, B = slider_crank_poses([10, 50, 100, 160, 230])
    bp = burmester_points(pos)
    sliders = [d for d in bp.dyads if d.is_slider]
    assert len(sliders) == 1
    s = sliders[0]
    # the slider's pin is B, its guide the line y = 0.4: the centre at infinity normal to it
    assert np.allclose(s.circle.xy, B[0], atol=1e-9)
    assert abs(s.centre.direction.xy[0]) <= 1e-9
    assert any(np.allclose(d.centre.xy, [0, 0], atol=1e-9) and np.allclose(d.circle.xy, A[0], atol=1e-9)
               for d in bp.dyads if not d.is_slider)
    found = [lk for lk in linkages(bp.dyads) if lk.kind == "slider-crank"]
    crank = [lk for lk in found if np.allclose(lk.input.centre.xy, [0, 0], atol=1e-9)]
    assert crank and crank[0].check.pose_error <= 1e-9
    assert engine_reproduces(crank[0], tmp_path) <= 1e-9


def test_five_general_positions_have_no_slider():
    assert not any(d.is_slider for d in burmester_points(FIVE).dyads)


def test_the_ranking_screen_agrees_with_the_engine_check():
    """`linkages` ranks by `Linkage.screen` (closed form, no engine): its branch defect and
    least transmission angle are the engine's (`check`) for every candidate of an automatic
    four-position search."""
    from linkwork.synthesis.linkages import four_position_linkages

    pos, _, _ = generated([10, 45, 80, 120])
    found = four_position_linkages(pos, candidates=6)
    checked = [lk for lk in found if lk.geometry_ok]
    assert len(checked) >= 4
    for lk in checked:
        branch, mu = lk.screen
        c = lk.check
        assert branch == c.branch_defect
        if not branch:
            assert mu == pytest.approx(c.min_transmission, abs=1e-9)
    # ranked: usable ones (by the screen) first
    flags = [lk.geometry_ok and not lk.screen[0] and lk.screen[1] >= np.radians(30) for lk in found]
    assert flags == sorted(flags, reverse=True)
