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
from pathlib import Path

import numpy as np
import pytest

import linkwork
from linkwork.constructions import acceleration_plan, rotated_velocities, slide_pairs, velocity_plan
from linkwork.kinematics import Status, solve
from linkwork.topology.constructibility import plan_velocities

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
    pts = {p: el[f"a.direct.abc.{p}.plan"].obj.xy for p in ("A", "B", "C")}
    for X, Y in (("A", "B"), ("B", "C"), ("C", "A")):
        d = sol.point(Y).position - sol.point(X).position
        assert np.allclose(pts[Y] - pts[X], w2[:, None] * d, atol=1e-9 * np.abs(w2[:, None] * d).max())


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
