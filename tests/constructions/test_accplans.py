"""False position with two trials, accelerations after false position and across cam and
rolling contacts, the chained plan of relative normal accelerations and the papers' special
drawings (Rosenauer 1937, papers 3, 4, 5, 8; digest 000 §2.5–2.9, §5–7, §10).

Every constructed velocity and acceleration is compared with the engine (the solver's linear
solves on the constraint Jacobian, an independent method) to 1e-9 relative by
``Construction.check``; the stated properties (rows, transfer rule, parallelograms, check
lines) are checked here against the engine's values, never against the construction's own.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import linkwork
from linkwork.constructions import (acceleration_plan, relative_normals, rolling_lever, rotated_velocities,
                                    slide_pairs, velocity_plan)
from linkwork.kinematics import Status, solve
from linkwork.topology.constructibility import Chain, plan_velocities

DATA = Path(__file__).parent / "data"


def load(name: str):
    return linkwork.load(name if name.startswith("library:") else DATA / f"{name}.toml")


def positions(mech, spread=0.15):
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = solve(mech, x0 + np.linspace(-spread, spread, 9))
    ok = np.asarray(sol.status) == Status.OK
    assert ok.sum() >= 5
    return solve(mech, np.asarray(sol.inputs).reshape(len(sol), -1)[ok, 0])


# ------------------------------------------------------------------ false position, two trials
def test_dreispann_on_jkb_needs_two_trials():
    """Burmester's Dreispann standing on the ternary link JKB and driven by the binary link HJ:
    Rosenauer's rule fails, and a trial rate of the other cranks (FK, DB) alone does not make it
    direct either (paper 7's remark is not enough). Leaving out the binary link AC and adding a
    trial crank makes it direct; the check ac ⟂ AC closes it (digest 000 §2.9)."""
    s = plan_velocities(load("dreispann-on-jkb"))
    assert not s.direct and s.complete
    assert s.check is not None and s.check[0] == "ac"
    assert s.scale_by[0] == "hj" and s.trial[0] in ("fk", "db")
    assert s.steps[-1].kind == "check"
    assert "two trials" in s.verdict()
    assert s.as_dict()["false_position"]["trials"] == 2
    # every link but the left-out one is reached by the trial script
    assert {st.link for st in s.steps} >= {"agh", "efg", "cde"}


@pytest.mark.parametrize("build", [velocity_plan, rotated_velocities, acceleration_plan],
                         ids=["plan", "rotated", "acceleration"])
def test_two_trial_false_position_matches_the_engine(build):
    mech = load("dreispann-on-jkb")
    con = build(mech, positions(mech))
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    # both trial rows are drawn, and the rows' points are the results
    keys = set(con.elements)
    assert any(k.startswith("v.trial2.") for k in keys)
    assert any(k.startswith("v.rows.") for k in keys)
    texts = [st.text for st in con.steps]
    assert any(t.startswith("first trial") for t in texts)
    assert any(t.startswith("second trial") for t in texts)


def test_similar_point_rows_are_straight():
    """The classical statement behind false position: the images of one point for different
    trial rates lie on one line (the images are affine in the trial rate). Each drawn result
    (equal to the engine's velocity, by `check`) lies on the line of its two trial images."""
    mech = load("dreispann-on-jkb")
    con = velocity_plan(mech, positions(mech))
    con.check()
    rows = [k for k in con.elements if k.startswith("v.rows.") and not k.endswith(".pt")]
    assert len(rows) == 7  # A, C, D, E, F, G, H: the moving joints
    pat = re.compile(r"^v\.trial(\d)\.(?:direct\.)?[^.]+\.([^.]+)$")
    trial = {}
    for key, e in con.elements.items():
        m = pat.match(key)
        if m:
            trial[(int(m.group(1)), m.group(2))] = e.obj.xy
    for k in rows:
        P = k.rsplit(".", 1)[1]
        x = con.elements[k + ".pt"].obj.xy
        if P == "H":  # the given driver's pin: the same in both trials, not redrawn
            assert (1, P) not in trial
            continue
        d1, d2 = trial[(2, P)] - trial[(1, P)], x - trial[(1, P)]
        cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
        assert np.all(abs(cross) <= 1e-9 * np.linalg.norm(d1, axis=1) * (np.linalg.norm(d2, axis=1) + 1)), k


# ------------------------------------------------------------------ cam and rolling contacts
CONTACTS = ["rolling-lever-valve-gear", "radial-roller-cam", "offset-roller-cam", "flat-faced-cam",
            "oscillating-roller-cam", "sulzer-valve-gear", "elliptical-gears", "designed-cam-knife",
            "poeschl-arc-cam", "proell-schwabe-valve-gear"]


@pytest.mark.parametrize("name", CONTACTS)
def test_accelerations_across_cam_and_rolling_contacts(name):
    """A cam contact crossed by its equivalent link C₁C₂ between the elements' centres of
    curvature (Rosenauer 1937 paper 8; §121), in the limits a slider (a flat face, a straight
    flank) and a point (a knife edge); a rolling contact by the acceleration of the relative
    pole's point ω_rel²·ρ₁ρ₂/(ρ₁ + ρ₂) along the normal (paper 8's j_p = ω·V_p)."""
    mech = linkwork.load(f"library:{name}")
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = solve(mech, x0 + np.array([0.05, 0.4, 1.1, 2.0]))
    ok = np.asarray(sol.status) == Status.OK
    con = acceleration_plan(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9
    # only dead centres of the mechanism itself are left out
    assert not (con.degenerate & ok & ~_dead_centres(con)).any()
    # the contact's own points were constructed on both sides and checked
    assert any(k.startswith("a_") and "@" in k for k in con.results)


def _dead_centres(con) -> np.ndarray:
    mask = np.zeros(len(con.degenerate), bool)
    for note in con.notes:
        if "dead centre or change point" in note.message:
            mask |= note.mask
    return mask


def test_roller_centre_lies_on_the_common_normal():
    """The normal of a roller passes through its centre (a fact of every position): the
    translating follower's images are copied, never cut from two lines that coincide."""
    s = plan_velocities(linkwork.load("library:radial-roller-cam"))
    assert all(st.kind != "meet" for st in s.steps if st.link == "follower" and st.point in ("K", "F", "C")
               and st.aux is None)


# ------------------------------------------------------------------ the chained plan
def test_chained_plan_has_two_images_where_loops_do_not_close():
    """Paper 4, Ex. V (the closed 8-link chain): the plan of relative normal accelerations is
    laid off link after link; it is homothetic to each link with factor ω² (engine ω), and at
    the hinges that close a loop it does not close: two images j, j′. The triad group (ABC with
    KA, BL, CM: 4 links, 6 hinges) closes 6 − 4 = 2 loops, so two hinges have two images. The
    acceleration laid off at either image is the engine's (the transfer rule)."""
    mech = load("closed-8-link")
    sol = positions(mech)
    con = acceleration_plan(mech, sol)
    con.check()
    el = con.elements
    twice = sorted({k.split(".")[2] for k in el if k.startswith("a.twice.")})
    assert len(twice) == 2 and set(twice) <= {"A", "B", "C"}
    for P in twice:
        x1, x2 = el[f"a.twice.{P}.1"].obj.xy, el[f"a.twice.{P}.2"].obj.xy
        assert np.all(np.linalg.norm(x2 - x1, axis=1) > 1e-6 * np.linalg.norm(x1, axis=1).max())
        aP = sol.point(P).acceleration
        scale = np.linalg.norm(aP, axis=1).max()
        for k in ("a1", "a2"):
            arrow = el[f"a.twice.{P}.{k}"].obj
            assert np.allclose(arrow.vector, aP, atol=1e-9 * scale)
    # the plan figure of ABC: homothetic to the link with factor ω²_ABC
    w2 = sol.link("abc").omega ** 2
    pts = {p: el[f"a.tri.abc.{p}.plan"].obj.xy for p in ("A", "B", "C")}
    for X, Y in (("A", "B"), ("B", "C"), ("C", "A")):
        d = sol.point(Y).position - sol.point(X).position
        assert np.allclose(pts[Y] - pts[X], w2[:, None] * d, atol=1e-9 * np.abs(w2[:, None] * d).max())


@pytest.mark.parametrize("name", ["pantograph", "roberval-balance"])
def test_over_closed_chains_plan_each_loop_closing_hinge_once(name):
    """An over-closed chain (the pantograph's parallelogram, Roberval's balance): the hinge that
    closes a loop belongs to two groups of the solution order; its two images j, j′ are drawn
    once (drawing them with both groups had raised "drawn twice"), and every acceleration of
    the plan is the engine's."""
    mech = linkwork.load(f"library:{name}")
    x0 = mech.driver_input_at_design(mech.drivers[0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the over-closed chain's warning
        sol = solve(mech, x0 + np.array([0.0, 0.3, -0.4]))
    con = acceleration_plan(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()


# ------------------------------------------------------------------ slides in moving planes
SLIDES = ["oscillating-crank-slotted-lever", "rotating-crank-slotted-lever", "rosenauer-shaping-machine",
          "whitworth-quick-return", "poeschl-quick-return-shaper"]


def _slide_sol(name):
    mech = linkwork.load(f"library:{name}")
    x0 = mech.driver_input_at_design(mech.drivers[0])
    return mech, solve(mech, x0 + np.array([0.05, 0.4, 1.1, 2.0, -1.0]))


@pytest.mark.parametrize("name", SLIDES)
def test_slide_pair_drawings_match_the_engine(name):
    """Papers 3 and 5 (M7 oscillating and M8 rotating crank-slotted lever, M9 the shaping
    machine): the parallelogram's coincident-point velocities and sliding velocity, the
    half-Coriolis point L (2·AL = j_γ), the double parallelogram's accelerations and sliding
    acceleration, all against the engine; the check lines (poles on a normal to the slide,
    ob ⟂ BP, oa′ ⟂ AP) and the perpendicular sides as vanishing cosines."""
    mech, sol = _slide_sol(name)
    con = slide_pairs(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    kinds = {k.split("_")[0] for k in con.results}
    assert {"vrel", "cor", "arel", "check"} <= kinds
    assert sum(k.startswith("check_") for k in con.results) >= 5
    # both figures are parallelograms: opposite sides equal
    for key in [k for k in con.elements if k.endswith((".v.parallelogram", ".a.basic", ".a.second"))]:
        v = [p.xy for p in con.elements[key].obj.vertices]
        side = np.linalg.norm(v[1] - v[0], axis=1).max() + np.linalg.norm(v[2] - v[1], axis=1).max()
        assert np.allclose(v[1] - v[0], v[2] - v[3], atol=1e-9 * side), key


def test_slotted_lever_parallelograms_are_rectangles():
    """Paper 3 Ex. 1 / paper 5 Ex. I: the slot passes through the lever's pivot B, so A and B lie
    on a line parallel to the slide: all three figures are rectangles (special case I)."""
    mech, sol = _slide_sol("oscillating-crank-slotted-lever")
    con = slide_pairs(mech, sol)
    con.check()
    for key in [k for k in con.elements if k.endswith((".v.parallelogram", ".a.basic", ".a.second"))]:
        v = [p.xy for p in con.elements[key].obj.vertices]
        d1, d2 = v[1] - v[0], v[3] - v[0]
        cos = np.sum(d1 * d2, axis=1) / (np.linalg.norm(d1, axis=1) * np.linalg.norm(d2, axis=1))
        assert np.all(abs(cos) <= 1e-9), key


def test_slide_pairs_needs_a_slide_between_moving_links():
    with pytest.raises(linkwork.LinkworkError, match="no sliding pair between two moving links"):
        slide_pairs(linkwork.load("library:slider-crank-centric"), [0.3])


# ------------------------------------------------------------------ the inscribed triangle
@pytest.mark.parametrize("name", ["closed-8-link", "closed-8-link-straight"])
def test_inscribed_perpendicular_similar_triangle(name):
    """Paper 4, Ex. III and V (digest 000 §2.8): the ends of the accelerations of A, B, C lie on
    the locus lines and form a triangle with sides perpendicular to ABC's, found from a trial
    triangle by the homothety from Q (the trial corner, Q and the true corner in line); with A, B,
    C on one line the trial corner divides the opposite side (paper 5, Ex. III). The accelerations
    read off are the engine's (`check`), and each vertex minus its plan point is too."""
    mech = load(name)
    sol = positions(mech)
    con = acceleration_plan(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    el = con.elements
    res = {p: el[f"a.tri.abc.{p}.laid"].obj for p in ("A", "B", "C")}
    for p, arrow in res.items():
        a = sol.point(p).acceleration
        assert np.allclose(arrow.vector, a, atol=1e-9 * np.linalg.norm(a, axis=1).max())
    # sides perpendicular to the link's sides
    P = {p: sol.point(p).position for p in ("A", "B", "C")}
    for X, Y in (("A", "B"), ("B", "C"), ("C", "A")):
        side = res[Y].head.xy - res[X].head.xy
        d = P[Y] - P[X]
        assert np.all(abs(np.sum(side * d, axis=1)) <= 1e-9 * np.linalg.norm(side, axis=1).max()
                      * np.linalg.norm(d, axis=1))
    # the homothety: Q, a trial corner and its true corner in line (for the corner on the ray)
    Q = el["a.tri.Q"].obj.xy
    trial = {k.split(".")[-1][0]: el[k].obj.xy for k in el if k.startswith("a.tri.trial.")}
    hits = 0
    for p, t in trial.items():
        u, v = t - Q, res[p].head.xy - Q
        if np.all(abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) <= 1e-9 * np.linalg.norm(u, axis=1)
                  * np.linalg.norm(v, axis=1)):
            hits += 1
    assert hits == 3  # every corner: the whole trial triangle is homothetic from Q


# ------------------------------------------------------------------ Thales semicircles
@pytest.mark.parametrize("name", ["library:crank-rocker", "library:holst-mechanism",
                                  "library:rolling-lever-valve-gear", "closed-8-link"])
def test_thales_semicircle_gives_the_relative_normal_accelerations(name):
    """Digest 000 §2.6: XE² = XN·XY in the right triangle over the semicircle, so the arc of
    radius |u| (the rotated relative velocity) about X cuts off XN = u²/XY: the relative
    normal acceleration ω²·XY (engine ω) at the scale k_v². Every side of every link."""
    mech = load(name)
    sol = positions(mech, 0.1)
    con = relative_normals(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    sides = sum(1 if len(set(mech.link(ln).points)) == 2 else len(set(mech.link(ln).points))
                for ln in mech.moving_links if len(set(mech.link(ln).points)) >= 2)
    assert len([k for k in con.results if k.startswith("an_")]) >= min(sides, 3)


# ------------------------------------------------------------------ runtime coincidences
TRIAD = {"ABC": "ABC", "AK": "AK", "BL": "BL", "CM": "CM"}


def _triad_geometry(pts):
    return {k: np.array([v], float) for k, v in pts.items()}


def test_planner_avoids_lines_parallel_in_the_drawing():
    """The triad with v_K, v_L, v_M given (paper 2, Ex. II): the graph alone takes the auxiliary
    point on KA and LB. Drawn with KA ∥ LB, the planner takes the lines that do meet."""
    chain = Chain.free(TRIAD, given=("K", "L", "M"))
    first = plan_velocities(chain)
    lines = {frozenset(ln.points) for ln in first.aux[0].lines}
    assert lines == {frozenset("AK"), frozenset("BL")}
    geo = _triad_geometry({"K": (0, 0), "A": (0, 1), "L": (2, 0), "B": (2, 1.2), "M": (5, 0), "C": (3.5, 2)})
    s = plan_velocities(chain, geo)
    assert s.direct and not s.coincidences
    for a in s.aux:
        pair = [frozenset(ln.points) for ln in a.lines]
        assert {frozenset("AK"), frozenset("BL")} != set(pair)


def test_planner_names_a_coincidence_it_cannot_avoid():
    chain = Chain.free(TRIAD, given=("K", "L", "M"))
    # all three arms parallel: every pair of lines is parallel (the triad is at a dead centre)
    geo = _triad_geometry({"K": (0, 0), "A": (0, 1), "L": (2, 0), "B": (2, 1.2), "M": (5, 0), "C": (5, 2)})
    s = plan_velocities(chain, geo)
    assert s.coincidences and "no other lines" in s.coincidences[0]


@pytest.mark.parametrize("name", ["rolling-lever-valve-gear", "stephenson-link-motion"])
@pytest.mark.parametrize("build", [velocity_plan, rotated_velocities, acceleration_plan],
                         ids=["plan", "rotated", "acceleration"])
def test_drawing_position_coincidences_are_chosen_around(name, build):
    """At their drawing positions the rolling lever's rod AD is parallel to the common normal
    n–n (the auxiliary point AD ∩ n–n at infinity), and the Stephenson link motion has Q, E, K in
    line. The planner, given the drawing, takes the paper-8 pole (the normal to the slide at B
    ∩ n–n) and a division on a known line instead: nothing degenerates."""
    mech = linkwork.load(f"library:{name}")
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = solve(mech, x0 + np.array([0.0, 1e-6, 0.3]))
    con = build(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    if name == "rolling-lever-valve-gear" and build is velocity_plan:
        # the graph's first choice, AD ∩ n–n, is at infinity here: another pair is taken
        steps = " ".join(st.text for st in con.steps)
        assert "= AD \u2229 the common normal of E" not in steps
        assert "Q = AD \u2229 the normal to guide at B" in steps or "the normal to guide at B \u2229" in steps


# ------------------------------------------------------------------ paper 8
def test_rolling_lever_construction_of_paper_8():
    """Paper 8 (M18): the lever's pole on the normal to the slide at B and on n–n; W by
    Euler–Savary from the centres of curvature and the auxiliary point D; the inflection circle
    through B, P, W and the inflection pole W₀ opposite P (the curvature layer's W₀ = P + a_P/ω²);
    V_p = |v_W₀| (the pole-change velocity); j_p = ω·V_p (the pole acceleration); the check
    end(j_p) on the line through b parallel to the slide; j_d and the valve's j_b (engine)."""
    mech = linkwork.load("library:rolling-lever-valve-gear")
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = solve(mech, x0 + np.array([0.3, 1.0, 2.0, -0.7]))
    con = rolling_lever(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    assert {"P", "W0", "Vp", "jp", "check_jp", "a_D", "a_B", "arel_valve"} <= set(con.results)
    # W lies on the inflection circle: the circle with diameter PW₀ (from the curvature layer)
    P = con.elements["rl.P"].obj.xy
    W = con.elements["rl.W"].obj.xy
    W0 = con.results["W0"].analytic
    from linkwork.constructions._common import inflection_pole
    W0 = inflection_pole(sol, "lever")
    assert np.allclose(np.sum((W - P) * (W - W0), axis=1), 0.0,
                       atol=1e-9 * np.linalg.norm(W0 - P, axis=1).max() ** 2)


def test_rolling_lever_says_why_at_its_drawing_position():
    """At its drawing position the rod AD is instantaneously translating (ω_rod = 0, engine), so
    the lever's pole lies on AD, and BD is perpendicular to the slide: the paper's lines for j_d
    and j_b are parallel there. Said, not invented."""
    mech = linkwork.load("library:rolling-lever-valve-gear")
    sol = solve(mech, [mech.driver_input_at_design(mech.drivers[0])])
    assert abs(sol.link("rod").omega[0]) <= 1e-12 * abs(sol.link("crank").omega[0])
    con = rolling_lever(mech, sol)
    assert con.degenerate[0]
    assert any("rod's line AD" in m or "BD is perpendicular to the slide" in m for m in con.messages(0))


def test_free_dreispann_with_va_vb_by_two_trials():
    """Paper 2, Ex. IV: the free Dreispann with v_A and v_B given is not directly constructible
    (CDE lies more than two joints from the given velocities: the rule's verdict stays named).
    The classical false position: a trial rate of AGH about A, the binary link AC left out, two
    trials, the check ac ⟂ AC. Every velocity against the engine (the linear solve of the given
    conditions)."""
    mech = load("free-dreispann-ab")
    s = plan_velocities(mech)
    assert not s.direct and "CDE" in s.unreached
    assert s.check is not None and s.scale_by is None
    assert "two trials" in s.verdict() and "given velocities" in s.verdict()
    for build in (velocity_plan, rotated_velocities):
        con = build(mech, None)
        con.check()
        assert con.max_error() <= 1e-9 and not con.degenerate.any()
        assert any(st.text.startswith("second trial") for st in con.steps)
