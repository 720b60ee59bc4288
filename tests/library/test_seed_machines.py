"""The seeds' machines in the library, each against the fact its seed states about it.

Every expected number comes from outside the solver: a closed form of the drawing (cosine
rule, circle intersections written out here, the seeds' formulas: Peaucellier's
O2A·O2Q = a² − b², Hart's O1P·O1Q = b² − a², the conchoid r = a + b/cos φ, the quick-return
time ratio), or a velocity construction of the seed carried out with the projection theorem
(*Projektionssatz*: two points of one rigid link have equal velocity components along the line
joining them) on the solved positions only, never on the solver's velocities of the group it
checks.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork import Status
from library_solutions import mech, motion


def P(name: str, point: str) -> np.ndarray:
    return np.asarray(mech(name).points[point], dtype=float)


def unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def circle_meet(c1, r1, c2, r2, sign):
    """Closed-form intersection of two circles (batch-first); `sign` picks the side of c1→c2."""
    c1, c2 = np.broadcast_arrays(np.asarray(c1, float), np.asarray(c2, float))
    d = np.linalg.norm(c2 - c1, axis=-1)
    a = (r1 ** 2 - r2 ** 2 + d ** 2) / (2 * d)
    h = np.sqrt(np.maximum(r1 ** 2 - a ** 2, 0.0))
    e = (c2 - c1) / d[..., None]
    n = np.stack([-e[..., 1], e[..., 0]], axis=-1)
    return c1 + a[..., None] * e + sign * h[..., None] * n


def line_meet(p1, d1, p2, d2):
    """Intersection of the lines p1 + s·d1 and p2 + t·d2 (batch-first)."""
    p1, d1, p2, d2 = np.broadcast_arrays(*(np.asarray(x, float) for x in (p1, d1, p2, d2)))
    cross = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
    w = p2 - p1
    s = (w[..., 0] * d2[..., 1] - w[..., 1] * d2[..., 0]) / cross
    return p1 + s[..., None] * d1


def from_projections(u1, c1, u2, c2):
    """The velocity v with v·u1 = c1 and v·u2 = c2 (two projection-theorem conditions)."""
    M = np.stack([u1, u2], axis=-2)
    return np.linalg.solve(M, np.stack([c1, c2], axis=-1)[..., None])[..., 0]


def ok(name):
    return motion(name).status == Status.OK


# ------------------------------------------------------------------ straight-line linkages
def test_elliptic_straight_line_is_exact():
    """Rosenauer §31: B runs exactly on the vertical through O, y_B = AB·sin φ."""
    sol = motion("elliptic-straight-line")
    phi = sol.link("crank").angle
    B = sol.point("B").position
    assert np.ptp(phi) > 2 * np.pi - 0.1  # the crank turns fully
    np.testing.assert_allclose(B[:, 0], 0.0, atol=1e-9 * 100)
    np.testing.assert_allclose(B[:, 1], 100 * np.sin(phi), atol=1e-9 * 100)


def test_watt_tracing_point_divides_the_coupler_inversely_as_the_arms():
    """Rosenauer §37: where the arms are parallel, the point O with AO : OB = b : a keeps its
    direction of motion (its path has an inflection: v × a = 0); the coupler's midpoint does not.
    Over the straight stretch O stays near the line, against the circle-intersection closed form."""
    m = mech("watt-straight-line")
    sol = linkwork.solve(m, [0.0], order=2)  # the drawn position: arm a along +x from Ca
    v, acc = sol.point("O").velocity[0], sol.point("O").acceleration[0]
    assert abs(v[0] * acc[1] - v[1] * acc[0]) <= 1e-9 * np.linalg.norm(v) * np.linalg.norm(acc) + 1e-12
    mid = sol.point_on("coupler", (P("watt-straight-line", "A") + P("watt-straight-line", "B")) / 2)
    vm, am = mid.velocity[0], mid.acceleration[0]
    assert abs(vm[0] * am[1] - vm[1] * am[0]) > 1e-3 * np.linalg.norm(vm) * np.linalg.norm(am)
    # closed form: A on its arm, B from the circles about A (AB = 30) and Cb (b = 40)
    th = np.radians(np.linspace(-8, 8, 33))
    Ca, Cb = P("watt-straight-line", "Ca"), P("watt-straight-line", "Cb")
    A = Ca + 60 * np.c_[np.cos(th), np.sin(th)]
    B = circle_meet(A, 30.0, Cb, 40.0, -1)
    O = A + (B - A) * (12.0 / 30.0)
    s = linkwork.solve(m, th)
    np.testing.assert_allclose(s.point("O").position, O, atol=1e-9 * 100)
    assert np.abs(O[:, 0]).max() < 0.05  # straight to 1/20 mm over ±8° of the arm


def test_chebyshev_midpoint_passes_three_points_of_one_line():
    """Rosenauer §36 with frame : rockers : coupler = 2 : 2.5 : 1: the midpoint P is on y = 80
    exactly where rocker a stands at atan2(80, 60) (drawn), at 90° and at atan2(60, 80)
    (the other rocker vertical): cosine rule of the proportions."""
    m = mech("chebyshev-straight-line")
    th = np.array([np.arctan2(80, 60), np.pi / 2, np.arctan2(60, 80)])
    Pxy = linkwork.solve(m, th).point("P").position
    np.testing.assert_allclose(Pxy, [[40, 80], [0, 80], [80, 80]], atol=1e-9 * 100)
    # between them P leaves the line by less than 0.4 % of the frame (closed form of the
    # crossed four-bar)
    t = np.linspace(np.arctan2(60, 80), np.pi / 2, 41)
    A = 100 * np.c_[np.cos(t), np.sin(t)]
    B = circle_meet(A, 40.0, P("chebyshev-straight-line", "O4"), 100.0, -1)
    mid = (A + B) / 2
    np.testing.assert_allclose(linkwork.solve(m, t).point("P").position, mid, atol=1e-9 * 100)
    assert np.abs(mid[:, 1] - 80).max() < 0.004 * 80


@pytest.mark.parametrize("name, k", [("evans-straight-line", 0.7), ("evans-straight-line-second-form", 1.3),
                                     ("evans-straight-line-third-form", -0.3)])
def test_evans_tracing_point_passes_its_start_o_and_the_mirror_point(name, k):
    """Rosenauer §§32–34: by the construction (D on the bisector of CC' and the line AO, E on that of
    AA') B passes exactly through its start B, through O and through B'' with B''O = OB; the input
    angles are those of C about D at C, C' = A' + k·(O − A') and C'' (C mirrored in AO)."""
    m = mech(name)
    D, C0 = P(name, "D"), P(name, "C")
    Cp, C2 = np.array([-100.0 + 100.0 * k, 0.0]), C0 * [1, -1]
    np.testing.assert_allclose(C0, [-70.710678118655 * (1 - k), 70.710678118655 * k], atol=1e-9)
    th = np.arctan2(*(np.stack([C0, Cp, C2]) - D)[:, ::-1].T)
    B = linkwork.solve(m, th).point("B").position
    h = 100 * np.sin(np.radians(45))
    np.testing.assert_allclose(B, [[0, h], [0, 0], [0, -h]], atol=1e-9 * 100)


def test_peaucellier_product_is_constant_and_q_runs_straight():
    """Pöschl §66a, eqs. (104): O2A·O2Q = a² − b² = 100² − 70², and Q on x = (a² − b²)/(2r)."""
    sol = motion("peaucellier-inversor")
    O2 = P("peaucellier-inversor", "O2")
    A, Q = sol.point("A").position - O2, sol.point("Q").position - O2
    np.testing.assert_allclose(np.hypot(*A.T) * np.hypot(*Q.T), 100 ** 2 - 70 ** 2, rtol=1e-9)
    good = ok("peaucellier-inversor")  # not the dead centres O2A = a − b, where the bound is wide
    np.testing.assert_allclose(Q[good, 0], (100 ** 2 - 70 ** 2) / (2 * 40), atol=1e-9 * 100)
    assert np.ptp(Q[:, 1]) > 100  # a long straight stroke, not a point


def test_hart_inversor_product_is_constant_and_q_runs_straight():
    """Pöschl §66b, eq. (105): O1P·O1Q = b² − a² (Ptolemy) and O1Q·cos ϑ = (b² − a²)/(2r)."""
    sol = motion("hart-inversor")
    O1, O2 = P("hart-inversor", "O1"), P("hart-inversor", "O2")
    Pp, Q = sol.point("P").position - O1, sol.point("Q").position - O1
    np.testing.assert_allclose(np.hypot(*Pp.T) * np.hypot(*Q.T), 50 ** 2 - 20 ** 2, rtol=1e-9)
    axis = unit(O2 - O1)
    np.testing.assert_allclose(Q @ axis, (50 ** 2 - 20 ** 2) / (2 * 45), atol=1e-9 * 100)


def test_hart_line_from_a_four_bar_is_exact():
    """Pöschl §66c: Q runs exactly on the perpendicular to O1O2 through its drawn position."""
    sol = motion("hart-straight-line")
    n = "hart-straight-line"
    axis = unit(P(n, "O2") - P(n, "O1"))
    Q = sol.point("Q").position
    np.testing.assert_allclose(Q @ axis, P(n, "Q") @ axis, atol=1e-9 * 500)
    assert np.ptp(Q @ np.array([-axis[1], axis[0]])) > 50


def test_conchoidograph_traces_the_conchoid_of_nicomedes():
    """Rosenauer §27/§35: about the pole A2 (d = 60 from the guide) the point B at c = 100 from
    A1 lies at r = d/cos φ + c, φ the angle of A2B from the normal to the guide."""
    sol = motion("conchoidograph")
    rel = sol.point("B").position - P("conchoidograph", "A2")
    r = np.hypot(*rel.T)
    cos_phi = np.abs(rel[:, 0]) / r
    # B lies beyond A2 from A1: A1 at distance d/cos φ on the other side, B = A1 + c·(unit)
    np.testing.assert_allclose(r, 100 - 60 / cos_phi, atol=1e-9 * 100)
    A1 = sol.point("A1").position
    np.testing.assert_allclose(A1[:, 0], 0.0, atol=1e-9 * 100)


def test_swinging_block_swings_by_asin_r_over_d_and_slides_by_the_cosine_rule():
    """Pöschl §24d: the block's swing is ±asin(r/d) about OB; the rod's slide through it is
    |BA| = √(r² + d² − 2rd·cos θ)."""
    sol = motion("swinging-block")
    th = sol.link("crank").angle
    BA = np.hypot(*(sol.point("A").position - P("swinging-block", "B")).T)
    np.testing.assert_allclose(BA, np.sqrt(30 ** 2 + 80 ** 2 - 2 * 30 * 80 * np.cos(th)), rtol=1e-9)
    d = P("swinging-block", "B") - sol.point("A").position  # along the rod, through the block
    swing = np.arctan2(d[:, 1], d[:, 0])  # from the line OB (the x-axis)
    # sampled at 1°: the extremes lie between samples, within 1e-3 rad
    assert abs(np.abs(swing).max() - np.arcsin(30 / 80)) < 1e-3


# ------------------------------------------------------------------ governors
def _pole_and_inflection_pole(name):
    from linkwork import instant
    sol = linkwork.solve(mech(name), [0.0], order=2)
    c = instant.inflection_circle(sol, "rod")
    centre = c.anchor.coords[0, :2] + c.normal.xy[0] * c.radius[0]
    return sol, centre, c.radius[0]


def test_kley_ball_follows_the_offset_slider_crank():
    """Rosenauer §28: in the spindle's plane Kley's governor is an offset slider-crank; for the
    sleeve at height y2 the ball A1 is where the circles about C1 (arm 120) and about A2 (rod 100)
    meet, on the drawn side of C1A2, up to the first dead centre (arm and rod in line), where the
    motion turns back on the other branch."""
    sol = motion("kley-governor")
    first = np.flatnonzero(sol.status != Status.OK)[0]
    assert first > 20
    A2 = sol.point("A2").position[:first]
    np.testing.assert_allclose(A2[:, 0], 0.0, atol=1e-9 * 200)
    A1 = circle_meet(P("kley-governor", "C1"), 120.0, A2, 100.0, 1)
    np.testing.assert_allclose(sol.point("A1").position[:first], A1, atol=1e-9 * 200)


def test_kley_inflection_circle_by_bobillier():
    """Rosenauer §28 steps 1–5: the pole P = C1A1 ∩ the horizontal through A2; A2 = W2 (its path is
    straight) and W1 on PA1 from Euler–Savary (A1P² = A1W1·A1C1): the inflection circle passes
    through P, A2 and W1."""
    n = "kley-governor"
    _, centre, radius = _pole_and_inflection_pole(n)
    C1, A1, A2 = P(n, "C1"), P(n, "A1"), P(n, "A2")
    Pp = line_meet(C1, A1 - C1, A2, np.array([1.0, 0.0]))
    e = unit(A1 - Pp)
    tA, tC = np.linalg.norm(A1 - Pp), (C1 - Pp) @ e
    W1 = Pp + (tA + tA ** 2 / (tC - tA)) * e
    for pt in (Pp, A2, W1):
        assert abs(np.linalg.norm(pt - centre) - radius) < 1e-9 * 200


def test_proell_has_kleys_pole_and_inflection_circle_and_moves_the_ball_alike():
    """Rosenauer §29: Pröll's substitution keeps the pole and the inflection circle of the rod in
    the drawn position, so with the same sleeve motion the ball A1 has the same velocity and
    acceleration there (second-order contact), and departs only to third order."""
    from linkwork import instant
    sk, ck, rk = _pole_and_inflection_pole("kley-governor")
    sp, cp, rp = _pole_and_inflection_pole("proell-governor")
    np.testing.assert_allclose(cp, ck, atol=1e-9 * 200)
    assert abs(rp - rk) < 1e-9 * 200
    pk = instant.poles(sk)["rod", "spindle"]
    pp = instant.poles(sp)["rod", "spindle"]
    np.testing.assert_allclose(pp.xy if hasattr(pp, "xy") else pp, pk.xy if hasattr(pk, "xy") else pk,
                               atol=1e-9 * 200)
    for q in ("velocity", "acceleration"):
        np.testing.assert_allclose(getattr(sp.point("A1"), q), getattr(sk.point("A1"), q), atol=1e-9 * 200)
    s = np.array([-1.0, -0.5, 0.5, 1.0]) * 4  # sleeve displacements from the drawing, mm
    dk = linkwork.solve(mech("kley-governor"), s).point("A1").position
    dp = linkwork.solve(mech("proell-governor"), s).point("A1").position
    gap = np.hypot(*(dp - dk).T)
    assert (gap > 0).all() and gap[3] / gap[2] > 6  # doubling the step: ≈ 2³ apart


# ------------------------------------------------------------------ special and over-closed chains
def test_galloway_kite_stays_symmetric_about_its_diagonal():
    """Rosenauer §100: with O2A = O2O4 and AB = BO4 the four-bar is a kite, symmetric about O2B:
    B lies on the bisector of the angle AO2O4 (direction θ/2 for the crank at θ), at the distance
    the cosine rule gives, through the change point θ = 0 where A meets O4."""
    sol = motion("galloway-kite")
    good = ok("galloway-kite")  # at the change point itself B is free on its circle (singular)
    assert (~good).sum() <= 2
    th = sol.link("crank").angle[good]
    B = sol.point("B").position[good]
    half = np.c_[np.cos(th / 2), np.sin(th / 2)]
    np.testing.assert_allclose(B[:, 0] * half[:, 1] - B[:, 1] * half[:, 0], 0.0, atol=1e-9 * 100)
    dist = np.abs(40 * np.cos(th / 2) - np.sqrt(70 ** 2 - (40 * np.sin(th / 2)) ** 2))
    np.testing.assert_allclose(np.hypot(*B.T), dist, atol=1e-9 * 100)
    assert np.nanmin(np.hypot(*(sol.point("A").position - P("galloway-kite", "O4")).T)) < 1.0


@pytest.mark.parametrize("name, second", [("five-bar", "O5"), ("crank-slider", "slide")])
def test_two_driver_chains_follow_both_laws(name, second):
    """The README's two-driver examples: C where the circles about A and B meet (closed form of
    both drivers' laws), at every time of the whole motion."""
    sol = motion(name)
    t = sol.time
    th2 = np.radians(30 + 360 * t)
    A = 20 * np.c_[np.cos(th2), np.sin(th2)]
    if name == "five-bar":
        th5 = np.radians(80 + 180 * t)
        B = P(name, "O5") + 20 * np.c_[np.cos(th5), np.sin(th5)]
        C = circle_meet(A, 60.0, B, 60.0, 1)
    else:
        B = P(name, "B") + np.c_[20 * t, 0 * t]
        C = circle_meet(A, 50.0, B, 40.0, 1)
    np.testing.assert_allclose(sol.point("B").position, B, atol=1e-9 * 100)
    np.testing.assert_allclose(sol.point("C").position, C, atol=1e-9 * 100)
    held = linkwork.solve(mech(name), [[np.radians(90), v] for v in (
        np.radians([80, 100, 120]) if name == "five-bar" else [0.0, 2.5, 5.0])])
    np.testing.assert_allclose(held.point("A").position, [[0, 20]] * 3, atol=1e-9 * 100)


def test_roberval_pans_translate_and_move_oppositely():
    """The Roberval balance (Rosenauer §101): each pan column is the coupler of a parallelogram, so it
    translates (never turns), and the pans rise and fall by 60·sin β for the beam at β."""
    sol = motion("roberval-balance")
    beta = sol.link("upper_beam").angle
    for pan, sign in (("pan_left", -1), ("pan_right", 1)):
        np.testing.assert_allclose(sol.pose_derivatives(pan)[0, :, 2], 0.0, atol=1e-12)
        pt = "PL" if pan == "pan_left" else "PR"
        np.testing.assert_allclose(sol.point(pt).position[:, 1] - P("roberval-balance", pt)[1],
                                   sign * 60 * np.sin(beta), atol=1e-9 * 100)


def test_pantograph_copies_b_enlarged_by_one_over_k():
    """Rosenauer §101: od/oD = bd/BD = ob/oB = k, so B = o + (b − o)/k at every position; b runs on
    the crank's circle, B on the circle of radius 20/k about M/k."""
    sol = motion("pantograph")
    good = ok("pantograph")  # not the crank's two dead centres
    b, B = sol.point("b").position[good], sol.point("B").position[good]
    np.testing.assert_allclose(B, b / 0.4, atol=1e-9 * 100)
    np.testing.assert_allclose(np.hypot(*(B - P("pantograph", "M") / 0.4).T), 20 / 0.4, atol=1e-9 * 100)


# ------------------------------------------------------------------ multi-loop chains
def _rot(v):
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def _proj(v, a, b):
    """v's component along the unit vector from a to b."""
    return (v * unit(b - a)).sum(-1)


@pytest.mark.parametrize("name", ["alt-eight-link", "alt-ten-link"])
def test_alt_chains_by_rosenauers_two_auxiliary_points(name):
    """Rosenauer, paper 7 (1937): from the crank's ω alone, Q = AD ∩ O1E (a point of link 4)
    moves across O1E and like A along AD; R = BG ∩ O2H (of link 5) likewise; then F from Q and R,
    E, D, G, H from F, and (ten links) K from B and G, M from K: each step the projection theorem
    on the solved positions. The solver's velocities must agree."""
    m, sol = mech(name), motion(name)
    good = ok(name)
    X = {p: sol.point(p).position[good] for p in m.points}
    w = m.drivers[0].law.speed
    C, O1, O2 = (P(name, p) for p in ("C", "O1", "O2"))
    vA, vB = w * _rot(X["A"] - C), w * _rot(X["B"] - C)
    Q = line_meet(X["A"], X["D"] - X["A"], O1, X["E"] - O1)
    R = line_meet(X["B"], X["G"] - X["B"], O2, X["H"] - O2)
    zero = np.zeros(len(Q))
    vQ = from_projections(unit(X["E"] - O1), zero, unit(X["D"] - X["A"]), _proj(vA, X["A"], X["D"]))
    vR = from_projections(unit(X["H"] - O2), zero, unit(X["G"] - X["B"]), _proj(vB, X["B"], X["G"]))
    v = {"F": from_projections(unit(X["F"] - Q), _proj(vQ, Q, X["F"]),
                               unit(X["F"] - R), _proj(vR, R, X["F"]))}
    v["E"] = from_projections(unit(X["E"] - X["F"]), _proj(v["F"], X["F"], X["E"]), unit(X["E"] - O1), zero)
    v["H"] = from_projections(unit(X["H"] - X["F"]), _proj(v["F"], X["F"], X["H"]), unit(X["H"] - O2), zero)
    v["D"] = from_projections(unit(X["D"] - X["F"]), _proj(v["F"], X["F"], X["D"]),
                              unit(X["D"] - X["A"]), _proj(vA, X["A"], X["D"]))
    v["G"] = from_projections(unit(X["G"] - X["F"]), _proj(v["F"], X["F"], X["G"]),
                              unit(X["G"] - X["B"]), _proj(vB, X["B"], X["G"]))
    if name == "alt-ten-link":
        O3 = P(name, "O3")
        v["K"] = from_projections(unit(X["K"] - X["G"]), _proj(v["G"], X["G"], X["K"]),
                                  unit(X["K"] - X["B"]), _proj(vB, X["B"], X["K"]))
        v["M"] = from_projections(unit(X["M"] - X["K"]), _proj(v["K"], X["K"], X["M"]), unit(X["M"] - O3), zero)
    scale = m.length_scale * abs(w)
    for p, vp in v.items():
        np.testing.assert_allclose(sol.point(p).velocity[good], vp, atol=1e-8 * scale, err_msg=p)
    # the structure Rosenauer counts: 3n/2 − 2 hinges, no four-bar loop
    import networkx as nx
    n = len(m.links)
    assert len(m.joints) == 3 * n // 2 - 2
    g = nx.Graph([j.links for j in m.joints])
    assert not [c for c in nx.simple_cycles(g, length_bound=4)]
    assert min(len(c) for c in nx.simple_cycles(g, length_bound=6)) == 5  # pentagons


# ------------------------------------------------------------------ slider mechanisms of the seeds
def test_holst_slider_velocity_from_the_pole_26():
    """Rosenauer §119: the pole 26 of the ternary link is AB ∩ CF; B's velocity (crank about A)
    gives the link's ω about it, D's velocity follows, and E's along the guide by the projection
    theorem on DE."""
    name = "holst-mechanism"
    m, sol = mech(name), motion(name)
    X = {p: sol.point(p).position for p in m.points}
    A, F = P(name, "A"), P(name, "F")
    w = m.drivers[0].law.speed
    vB = w * _rot(X["B"] - A)
    p26 = line_meet(A, X["B"] - A, F, X["C"] - F)
    rB = X["B"] - p26
    w2 = (vB * _rot(rB)).sum(-1) / (rB * rB).sum(-1)
    vD = w2[:, None] * _rot(X["D"] - p26)
    u = unit(X["E"] - X["D"])
    vE = (vD * u).sum(-1) / u[:, 0]
    good = ok(name)
    np.testing.assert_allclose(sol.point("E").velocity[good, 0], vE[good], atol=1e-8 * 120 * abs(w))
    np.testing.assert_allclose(sol.point("E").velocity[:, 1], 0.0, atol=1e-12)


def test_rosenauer_shaper_ram_velocity_from_the_pole_36():
    """Rosenauer §120: the pole 36 of the bar is the normal to the ram's guide at B cut with the
    rocker O2C; the crank pin's velocity splits into a slide along the bar and the bar's own
    velocity about 36 (V_a^26 = V_a^23 + V_a^36), which fixes the bar's ω and so the ram's speed."""
    name = "rosenauer-shaping-machine"
    m, sol = mech(name), motion(name)
    X = {p: sol.point(p).position for p in ("A", "B", "C")}
    O1, O2 = P(name, "O1"), P(name, "O2")
    w = m.drivers[0].law.speed
    vA = w * _rot(X["A"] - O1)
    p36 = line_meet(X["B"], np.array([0.0, 1.0]), O2, X["C"] - O2)
    u = unit(X["B"] - X["C"])
    cross = lambda a, b: a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    w3 = cross(vA, u) / cross(_rot(X["A"] - p36), u)
    vB = w3[:, None] * _rot(X["B"] - p36)
    good = ok(name)
    np.testing.assert_allclose(sol.point("B").velocity[good], vB[good], atol=1e-8 * 200 * abs(w))


def test_poeschl_shaper_reverses_where_crank_and_lever_are_perpendicular():
    """Pöschl §24b: the lever, and with it the slide, stands still where the crank AB is
    perpendicular to the lever CB, at crank angles −90° ± acos(r/d); the slide's two strokes take
    the crank arcs 2·acos(r/d) and 2π − 2·acos(r/d): time ratio (π + 2 asin(r/d))/(π − 2 asin(r/d))."""
    m = mech("poeschl-quick-return-shaper")
    r, d = 40.0, 100.0
    dead = -np.pi / 2 + np.array([-1, 1]) * np.arccos(r / d)
    s = linkwork.solve(m, dead)
    np.testing.assert_allclose(s.point("E").velocity[:, 0], 0.0, atol=1e-9 * 200 * np.pi)
    # between the dead centres the slide moves one way on the short arc, the other on the long
    short = linkwork.solve(m, np.linspace(dead[0], dead[1], 50)[1:-1]).point("E").velocity[:, 0]
    long_ = linkwork.solve(m, np.linspace(dead[1], dead[0] + 2 * np.pi, 90)[1:-1]).point("E").velocity[:, 0]
    assert (np.sign(short) == np.sign(short[0])).all() and (np.sign(long_) == -np.sign(short[0])).all()
    ratio = (2 * np.pi - np.ptp(dead)) / np.ptp(dead)
    np.testing.assert_allclose(ratio, (np.pi + 2 * np.arcsin(r / d)) / (np.pi - 2 * np.arcsin(r / d)), rtol=1e-12)
    # and the stroke: the slide's extremes are at the dead centres (the 1° samples lie within)
    E = motion("poeschl-quick-return-shaper").point("E").position[:, 0]
    lo, hi = np.sort(s.point("E").position[:, 0])
    assert lo <= E.min() + 1e-9 and hi >= E.max() - 1e-9 and hi - lo - np.ptp(E) < 0.01


# ------------------------------------------------------------------ valve gears
def test_stephenson_link_and_valve_velocities_by_projection():
    """Pöschl §54: the link 3 hangs on the rods 2, 4 and the hanger 5: C moves like A along AC, D
    like B along BD, E across the hanger; two of these fix the link's motion (the third checks
    it), and the die F's velocity along the link's radius KF gives the valve rod's along its guide."""
    name = "stephenson-link-motion"
    m, sol = mech(name), motion(name)
    X = {p: sol.point(p).position for p in m.points}
    O, H = P(name, "O"), P(name, "H")
    w = m.drivers[0].law.speed
    vA, vB = w * _rot(X["A"] - O), w * _rot(X["B"] - O)
    # the link's velocity field v(X) = vE + ω3·rot(X − E), with vE ⟂ EH: unknowns s (vE = s·n) and ω3
    n = _rot(unit(X["E"] - H))
    uc, ud = unit(X["C"] - X["A"]), unit(X["D"] - X["B"])
    M = np.stack([np.stack([(n * uc).sum(-1), (_rot(X["C"] - X["E"]) * uc).sum(-1)], -1),
                  np.stack([(n * ud).sum(-1), (_rot(X["D"] - X["E"]) * ud).sum(-1)], -1)], -2)
    rhs = np.stack([(vA * uc).sum(-1), (vB * ud).sum(-1)], -1)
    s_, w3 = np.linalg.solve(M, rhs[..., None])[..., 0].T
    field = lambda Y: s_[:, None] * n + w3[:, None] * _rot(Y - X["E"])
    good = ok(name)
    scale = 1000 * abs(w)
    for p in ("C", "D", "E"):
        np.testing.assert_allclose(sol.point_on("link_3", P(name, p)).velocity[good], field(X[p])[good],
                                   atol=1e-8 * scale, err_msg=p)
    r = unit(X["F"] - X["K"])
    v_valve = (field(X["F"]) * r).sum(-1) / r[:, 0]
    np.testing.assert_allclose(sol.point("F").velocity[good, 0], v_valve[good], atol=1e-8 * scale)


def test_heusinger_lead_does_not_depend_on_the_cut_off():
    """The Heusinger gear's constant lead (Rosenauer §112): at the crank's dead centre the link
    stands upright and the slot's arc is centred on the radius rod's end 79, so raising or
    lowering the die (the reversing arm at any setting) leaves 79 and the valve where they are;
    away from the dead centre the setting does move the valve."""
    m = mech("heusinger-valve-gear")
    settings = np.radians([172.0, 176.0, 180.0, 184.0, 188.0])
    at_dead = linkwork.solve(m, np.c_[np.zeros(5), settings])
    np.testing.assert_allclose(at_dead.point("P79").position, np.tile(P("heusinger-valve-gear", "K5"), (5, 1)),
                               atol=1e-9 * 3000)
    np.testing.assert_allclose(np.ptp(at_dead.point("P9X").position[:, 0]), 0.0, atol=1e-9 * 3000)
    assert np.ptp(at_dead.point("P67").position[:, 1]) > 50  # the die did move in the slot
    away = linkwork.solve(m, np.c_[np.full(5, np.pi / 2), settings])
    assert np.ptp(away.point("P9X").position[:, 0]) > 5


def _rosenauer_79(name, X, v56, v1xi, upper8, pivot_x):
    """Rosenauer §112/§113: R = (line 78–8XII) ∩ (the line of link 6), a point of 7, moves across
    78–8XII and like 67 along link 6; Q = (union link XI) ∩ (the normal to X's motion at 9X), a
    point of 9, moves like 1XI along XI and along that normal only as 9X does (not at all);
    then 79 from R and Q."""
    R = line_meet(X["P78"], upper8 - X["P78"], X["P67"], X["P67"] - X["six"])
    vR = from_projections(unit(upper8 - X["P78"]), np.zeros(len(R)),
                          unit(X["P67"] - X["six"]), (v56 * unit(X["P67"] - X["six"])).sum(-1))
    nX = pivot_x(X)  # the direction in which 9X cannot move
    Q = line_meet(X["P9XI"], X["P1XI"] - X["P9XI"], X["P9X"], nX)
    vQ = from_projections(unit(X["P1XI"] - X["P9XI"]), (v1xi * unit(X["P1XI"] - X["P9XI"])).sum(-1),
                          unit(nX), np.zeros(len(Q)))
    return from_projections(unit(X["P79"] - R), _proj(vR, R, X["P79"]),
                            unit(X["P79"] - Q), _proj(vQ, Q, X["P79"]))


def test_heusinger_slotted_gear_velocity_of_79_by_rosenauers_construction():
    name = "heusinger-valve-gear"
    m, sol = mech(name), motion(name)
    X = {p: sol.point(p).position for p in m.points}
    X["six"] = X["K5"]  # the block folded into the die pin: link 6 lies along the slot's radius
    # the point of the slotted link under the die, turning about the pivot P5
    v5 = sol.link("slotted_link").omega[:, None] * _rot(X["P67"] - P(name, "P5"))
    v79 = _rosenauer_79(name, X, v5, sol.point("P1XI").velocity, X["P8"],
                        lambda X: np.tile([0.0, 1.0], (len(X["P9X"]), 1)))
    np.testing.assert_allclose(sol.point("P79").velocity, v79, atol=1e-8 * 3000 * 2 * np.pi)


def test_heusinger_hinge_chain_velocity_of_79_by_rosenauers_construction():
    name = "heusinger-hinge-chain"
    m, sol = mech(name), motion(name)
    assert (len(m.links), len(m.joints)) == (12, 16)  # Rosenauer's n = 12, g = 16
    X = {p: sol.point(p).position for p in m.points}
    X["six"] = X["P56"]
    v79 = _rosenauer_79(name, X, sol.point("P56").velocity, sol.point("P1XI").velocity,
                        np.tile(P(name, "P8"), (len(sol), 1)),
                        lambda X: X["P9X"] - P(name, "PXXII"))
    w = m.drivers[0].law.speed
    np.testing.assert_allclose(sol.point("P79").velocity, v79, atol=1e-8 * 3000 * abs(w))


def test_roemer_slide_velocity_by_rosenauers_construction_one():
    """Rosenauer 1937, paper 1, Construction I (digest 000 §3.3) on the solved positions only:
    gear I turns at ω (60 rpm, counter-clockwise), gear II at −ω·r1/r2 (the gears turn in
    opposite senses). Q = KA ∩ BN and R = MC ∩ BN, on the normal BN to the slide at B, are points
    of the coupler ABC whose pole lies on BN, so their velocities run along the slide s; each
    has K's (M's) velocity component along KA (MC) by the projection theorem; and along BN the
    velocities vary linearly, so B's is interpolated between Q's and R's."""
    name = "roemer-mechanism"
    m, sol = mech(name), motion(name)
    good = ok(name)
    w1 = 2 * np.pi  # 60 rpm
    np.testing.assert_allclose(sol.link("gear_1").omega[good], w1, rtol=1e-12)
    np.testing.assert_allclose(sol.link("gear_2").omega[good], -w1 * 40 / 20, rtol=1e-9)
    pos = {p: sol.point(p).position[good] for p in ("O1", "O2", "K", "M", "A", "B", "C")}

    def J(v):  # a quarter turn counter-clockwise
        return np.stack([-v[..., 1], v[..., 0]], axis=-1)

    vK = w1 * J(pos["K"] - pos["O1"])
    vM = -w1 * 2 * J(pos["M"] - pos["O2"])
    s = np.array([0.0, 1.0])  # the fixed guide of BL
    n = J(s)  # BN
    Q = line_meet(pos["B"], n, pos["K"], pos["A"] - pos["K"])
    R = line_meet(pos["B"], n, pos["M"], pos["C"] - pos["M"])
    eKA, eMC = unit(pos["A"] - pos["K"]), unit(pos["C"] - pos["M"])
    vQ = (np.sum(vK * eKA, axis=1) / (eKA @ s))[:, None] * s
    vR = (np.sum(vM * eMC, axis=1) / (eMC @ s))[:, None] * s
    t = ((pos["B"] - Q) @ n) / ((R - Q) @ n)
    vB = vQ + t[:, None] * (vR - vQ)
    fair = (np.abs(eKA @ s) > 0.05) & (np.abs(eMC @ s) > 0.05) & (np.abs((R - Q) @ n) > 1.0)
    assert fair.mean() > 0.9
    scale = np.abs(sol.point("B").velocity[good]).max()
    np.testing.assert_allclose(sol.point("B").velocity[good][fair], vB[fair], atol=1e-9 * scale)


def test_eight_link_chain_by_rosenauers_auxiliary_points_q_and_r():
    """Rosenauer 1937, paper 4, Example V (digest 000 §6.5) on the solved positions only: the
    crank O1KD at ω (60 rpm) gives D and K; E's velocity is normal to O2E with D's component
    along DE; L (on DLE) and M (on O2ME) follow by the projection theorem. Q = BL ∩ KA and
    R = BL ∩ MC, taken as points of ABC, get their velocities from two projections each (along
    KA and BL, along MC and BL); the normals to them meet at the pole P of ABC, about which
    A, B and C turn."""
    name = "rosenauer-eight-link-chain"
    m, sol = mech(name), motion(name)
    good = ok(name)
    x = {p: sol.point(p).position[good] for p in m.points}

    def J(v):  # a quarter turn counter-clockwise
        return np.stack([-v[..., 1], v[..., 0]], axis=-1)

    def dot(a, b):
        return np.sum(a * b, axis=-1)

    w1 = 2 * np.pi  # 60 rpm
    vD, vK = w1 * J(x["D"] - x["O1"]), w1 * J(x["K"] - x["O1"])
    eDE = unit(x["E"] - x["D"])
    wr = dot(vD, eDE) / dot(J(x["E"] - x["O2"]), eDE)
    vE, vM = wr[:, None] * J(x["E"] - x["O2"]), wr[:, None] * J(x["M"] - x["O2"])
    eDL, eEL = unit(x["L"] - x["D"]), unit(x["L"] - x["E"])
    vL = from_projections(eDL, dot(vD, eDL), eEL, dot(vE, eEL))
    eKA, eBL, eMC = unit(x["A"] - x["K"]), unit(x["B"] - x["L"]), unit(x["C"] - x["M"])
    Q = line_meet(x["L"], eBL, x["K"], eKA)
    R = line_meet(x["L"], eBL, x["M"], eMC)
    vQ = from_projections(eKA, dot(vK, eKA), eBL, dot(vL, eBL))
    vR = from_projections(eMC, dot(vM, eMC), eBL, dot(vL, eBL))
    P = line_meet(Q, J(vQ), R, J(vR))
    w = dot(vQ, J(Q - P)) / dot(Q - P, Q - P)
    fair = np.abs(dot(J(unit(vQ)), unit(vR))) > 0.05  # the normals meet at a finite pole
    assert fair.mean() > 0.9
    for p in ("A", "B", "C"):
        v = sol.point(p).velocity[good]
        expect = w[:, None] * J(x[p] - P)
        np.testing.assert_allclose(v[fair], expect[fair], atol=1e-8 * np.abs(v).max())
