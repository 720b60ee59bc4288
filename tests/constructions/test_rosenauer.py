"""Rosenauer's direct velocity constructions (1937, papers 1, 2, 7; digest 000 §3, §4, §9).

The constructibility verdicts are the seeds' own (digest 000 §13.10: which chains with which
given data the papers construct directly, and the Dreispann with V_a, V_b that they do not); the
auxiliary points are the ones the papers name. Every drawn velocity, auxiliary points included,
is compared with the engine's (an independent method: the solver's linear solves on the
constraint Jacobian), to 1e-9 relative.
"""

from __future__ import annotations

import json
from pathlib import Path

import os

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from linkwork.constructions import acceleration_plan, rotated_velocities, velocity_plan
from linkwork.kinematics import Status, solve
from linkwork.topology.constructibility import Chain, plan_velocities, wittenbauer_rule

DATA = Path(__file__).parent / "data"

# the free chains of paper 2, topology as the digest rebuilds it from the construction steps
WATT = {"CDG": "CDG", "DEF": "DEF", "AC": "AC", "AE": "AE", "BG": "BG", "BF": "BF"}
TRIAD = {"ABC": "ABC", "AK": "AK", "BL": "BL", "CM": "CM"}
SERIAL = {"AE": "AE", "EBF": "EBF", "CGF": "CGF", "GD": "GD"}
DREISPANN = {"AGH": "AGH", "EFG": "EFG", "CDE": "CDE", "JKB": "JKB", "AC": "AC", "HJ": "HJ",
             "FK": "FK", "DB": "DB"}
HEUSINGER = {"XII": ("1", "2", "3", "4", "5"), "1AB": ("1", "A", "B"), "BC": "BC",
             "2CD": ("2", "C", "D"), "AI": "AI", "3IH": ("3", "I", "H"), "HG": "HG",
             "5K": ("5", "K"), "DE": "DE", "4L": ("4", "L"), "GKF": "GKF", "FEL": "FEL"}


def aux_lines(script) -> set[frozenset[frozenset[str]]]:
    """The auxiliary points as sets of their two lines (each a set of two point names)."""
    return {frozenset(frozenset(ln.points) for ln in a.lines) for a in script.aux}


def meet_text(target: str, a: str, b: str) -> tuple[str, str]:
    """The script's sentence for target = a ∩ b, in either order of the two lines."""
    return (f"{target} = {a} \u2229 {b}", f"{target} = {b} \u2229 {a}")


def has_meet(s, target: str, a: str, b: str) -> bool:
    texts = [st.text for st in s.steps] if not isinstance(s, str) else [s]
    return any(t in x for t in meet_text(target, a, b) for x in texts)


def L(*pairs: str) -> frozenset:
    return frozenset(frozenset(p) for p in pairs)


# ------------------------------------------------------------------ the seeds' verdicts
def test_watt_chain_with_va_vb_is_direct_with_q_and_r():
    """Paper 2, Example I: Q = AC ∩ BG in CDG, R = AE ∩ BF in DEF, then d from q and r.
    Wittenbauer's rule fails (A to B crosses two joints), as Wittenbauer himself found."""
    chain = Chain.free(WATT, given=("A", "B"))
    s = plan_velocities(chain)
    assert s.direct
    assert aux_lines(s) == {L("AC", "BG"), L("AE", "BF")}
    assert {a.link for a in s.aux} == {"CDG", "DEF"}
    assert has_meet(s, "d", "(q \u27c2 QD)", "(r \u27c2 RD)")
    assert not wittenbauer_rule(chain).holds


def test_triad_with_three_given_ends_is_direct():
    """Paper 2, Example II: the triad ABC with AK, BL, CM and v_K, v_L, v_M given: direct
    with auxiliary points where the binary links' lines meet (at most two)."""
    s = plan_velocities(Chain.free(TRIAD, given=("K", "L", "M")))
    assert s.direct and 1 <= len(s.aux) <= 2
    assert all(a.link == "ABC" for a in s.aux)
    # the first is where two binary links' lines meet (Rosenauer's D = AK ∩ BL)
    assert L("KA", "LB") in aux_lines(s)


def test_serial_chain_with_two_velocities_and_two_directions_is_direct():
    """Paper 2, Example III: v_A, v_D and the directions of B and C: the normals at B and C
    meet AE and DG in the auxiliary points (R in EBF, Q in CGF), then f from both."""
    s = plan_velocities(Chain.free(SERIAL, given=("A", "D"), directions=("B", "C")))
    assert s.direct
    got = {(a.link, frozenset((a.lines[0].kind, a.lines[1].kind))) for a in s.aux}
    assert got == {("EBF", frozenset(("direction", "join"))), ("CGF", frozenset(("direction", "join")))}
    assert {frozenset(ln.points) for a in s.aux for ln in a.lines if ln.kind == "join"} == \
        {frozenset("AE"), frozenset("DG")}


@pytest.mark.parametrize("given,direct", [(("A", "B"), False), (("A", "F"), True), (("A", "E"), True)])
def test_dreispann_verdicts(given, direct):
    """Paper 2, Example IV: with V_a and V_b the Dreispann is not directly constructible (for
    CDE one way crosses two joints, the other four); with V_a and V_f (or V_e) it is."""
    s = plan_velocities(Chain.free(DREISPANN, given=given))
    assert s.direct is direct
    if not direct:
        assert "similar point rows" in s.verdict()
        assert "CDE" in s.unreached


def test_dreispann_with_va_vf_follows_the_papers_order():
    s = plan_velocities(Chain.free(DREISPANN, given=("A", "F")))
    texts = [st.text for st in s.steps]
    # g = (f + ⟂FG) ∩ (a + ⟂AG), then h, e, c, d by dyad steps, as in the paper
    assert has_meet(texts[2], "g", "(a \u27c2 AG)", "(f \u27c2 FG)")
    assert [st.point for st in s.steps[2:7]] == ["G", "H", "E", "C", "D"]
    assert [a.link for a in s.aux] == ["JKB"]


@pytest.mark.parametrize("fixed,driver,pivot,ref", [("AC", "AGH", "A", "G"), ("AC", "CDE", "C", "E")])
def test_dreispann_fixed_on_ac_is_direct(fixed, driver, pivot, ref):
    """Paper 2, Example IV: 'just as easy: link AC fixed, with AGH or CDE driving'."""
    s = plan_velocities(Chain.free(DREISPANN, known=(fixed,), drivers=((driver, pivot, ref),)))
    assert s.direct


def test_heusinger_chain_with_va_has_the_papers_q_and_r():
    """Paper 2, Example V: b, c, d, i, h by dyads; Q = HG ∩ 5K in GKF and R = DE ∩ 4L in FEL;
    f = (q ⟂ QF) ∩ (r ⟂ RF)."""
    chain = Chain.free(HEUSINGER, known=("XII",), drivers=(("1AB", "1", "A"),))
    s = plan_velocities(chain)
    assert s.direct
    assert aux_lines(s) == {L("HG", "5K"), L("DE", "4L")}
    assert {a.link for a in s.aux} == {"GKF", "FEL"}
    assert [st.point for st in s.steps[1:6]] == ["B", "C", "D", "I", "H"]
    assert has_meet(s, "f", "(q \u27c2 QF)", "(r \u27c2 RF)")


@pytest.mark.parametrize("given", [("A", "3"), ("I", "1"), ("B", "2"), ("C", "1")])
def test_free_heusinger_chain_with_two_point_velocities_is_direct(given):
    """Paper 2, Example V: the free chain with any of these pairs of point velocities given."""
    assert plan_velocities(Chain.free(HEUSINGER, given=given)).direct


@pytest.mark.parametrize("name,links", [("alt-8-link", ("link_4", "link_5")),
                                        ("alt-10-link", ("link_4", "link_5"))])
def test_alt_chains_need_two_auxiliary_points(name, links):
    """Paper 7: Alt's 8- and 10-link chains without four-bar loops, link 1 driving: direct with
    just two auxiliary points, Q = (2) ∩ (3) in link 4 and R = (6) ∩ (7) in link 5."""
    s = plan_velocities(linkwork.load(DATA / f"{name}.toml"))
    assert s.direct and len(s.aux) == 2
    assert tuple(a.link for a in s.aux) == links
    assert aux_lines(s) == {L(("A", "D"), ("O1", "E")), L(("B", "G"), ("O2", "H"))}
    assert not wittenbauer_rule(Chain.from_mechanism(linkwork.load(DATA / f"{name}.toml"))).holds


def test_roemer_needs_one_auxiliary_point_on_ka_and_mc():
    """Paper 1, Construction II: D = KA ∩ MC, a point of the coupler ABC (here named Q)."""
    s = plan_velocities(linkwork.load("library:roemer-mechanism"))
    assert s.direct
    assert aux_lines(s) == {L("KA", "MC")}
    assert s.aux[0].link == "coupler"


def test_wittenbauer_rule_holds_for_a_four_bar():
    chain = Chain.from_mechanism(linkwork.load("library:crank-rocker"))
    assert wittenbauer_rule(chain).holds
    assert plan_velocities(chain).direct and not plan_velocities(chain).aux


def test_unknown_pairs_leave_the_question_open():
    s = plan_velocities(linkwork.load("library:geneva-4"))
    assert not s.direct and "not decided" in s.verdict()


# ------------------------------------------------------------------ the drawn constructions
MECHANISMS = ["library:roemer-mechanism", "alt-8-link", "alt-10-link", "heusinger-12-link",
              "dreispann-8-link", "closed-8-link"]


def load(name: str):
    return linkwork.load(name if name.startswith("library:") else DATA / f"{name}.toml")


def positions(mech):
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = solve(mech, x0 + np.linspace(-0.15, 0.15, 9))
    ok = np.asarray(sol.status) == Status.OK
    assert ok.sum() >= 5
    return solve(mech, np.asarray(sol.inputs).reshape(len(sol), -1)[ok, 0])


@pytest.mark.parametrize("name", MECHANISMS)
@pytest.mark.parametrize("build", [velocity_plan, rotated_velocities], ids=["plan", "rotated"])
def test_direct_construction_matches_the_engine(name, build):
    mech = load(name)
    sol = positions(mech)
    con = build(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9
    assert not con.degenerate.any()
    # every auxiliary point's velocity was compared too (as a point of its link)
    script = plan_velocities(mech)
    for a in script.aux:
        assert any(k.startswith(f"v_{a.name}@") for k in con.results), a.name


@pytest.mark.parametrize("name", MECHANISMS + ["library:crank-driven-wedge",
                                              "library:whitworth-quick-return"])
def test_relative_normal_acceleration_plan_matches_the_engine(name):
    """Paper 4: the same script drawn through the ends of the accelerations laid off at the
    plan of relative normal accelerations, transferred across each pair (the hinges' several
    images, the Coriolis term of a sliding pair, the gears' pitch-point normal accelerations)."""
    mech = load(name)
    sol = positions(mech)
    con = acceleration_plan(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9
    assert not con.degenerate.any()
    # a triad group is drawn by the inscribed triangle (paper 4), which needs no auxiliary point
    triangle = {k.split(".")[2] for k in con.elements if k.startswith("a.tri.") and k.count(".") >= 4}
    for a in plan_velocities(mech).aux:
        assert a.link in triangle or any(k.startswith(f"a_{a.name}@") for k in con.results), a.name


def test_heusinger_auxiliary_point_lies_on_both_lines_and_has_the_links_velocity():
    """Q = HG ∩ O5K taken as a point of GKF: its velocity projects on HG as h does and on O5K
    as the fixed pivot O5 does (zero) — the projection theorem across the joints G and K."""
    mech = load("heusinger-12-link")
    sol = positions(mech)
    con = velocity_plan(mech, sol)
    q = con.results["v_Q@gkf"].constructed
    pos = {p: sol.point(p).position for p in ("H", "G", "O5", "K")}
    e1 = pos["G"] - pos["H"]
    e2 = pos["K"] - pos["O5"]
    vh = sol.point("H").velocity
    scale = np.linalg.norm(vh, axis=1)
    assert np.allclose(np.sum(q * e1, 1) / np.linalg.norm(e1, axis=1), np.sum(vh * e1, 1) / np.linalg.norm(e1, axis=1),
                       atol=1e-9 * scale.max())
    assert np.allclose(np.sum(q * e2, 1), 0.0, atol=1e-9 * scale.max() * np.linalg.norm(e2, axis=1).max())


def test_sliding_and_gear_groups_through_the_direct_construction():
    for name in ("crank-driven-wedge", "whitworth-quick-return"):
        mech = linkwork.load(f"library:{name}")
        x0 = mech.driver_input_at_design(mech.drivers[0])
        velocity_plan(mech, [x0 + 0.05]).check()


# ------------------------------------------------------------------ the commands
def test_plan_command_prints_the_script_and_checks_it():
    res = CliRunner().invoke(app, ["plan", str(DATA / "heusinger-12-link.toml"), "--at", "130",
                                   "--explain"])
    assert res.exit_code == 0, res.output
    assert "Q = O_5K \u2229 HG" in res.output or "Q = HG \u2229 O_5K" in res.output
    assert has_meet(res.output, "f", "(q \u27c2 QF)", "(r \u27c2 RF)")
    assert "largest relative error against the engine" in res.output


def test_plan_command_refuses_a_position_that_does_not_assemble():
    res = CliRunner().invoke(app, ["plan", str(DATA / "heusinger-12-link.toml"), "--at", "62"])
    assert res.exit_code != 0
    assert "cannot be assembled" in res.output


def test_plan_command_json_and_structure_report():
    res = CliRunner().invoke(app, ["plan", "library:roemer-mechanism", "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    assert doc["rosenauer"]["direct"] is True
    assert doc["wittenbauer"]["holds"] is False
    res = CliRunner().invoke(app, ["structure", "library:roemer-mechanism", "--format", "json"])
    assert res.exit_code == 0, res.output
    assert json.loads(res.output)["velocity_construction"]["rosenauer"]["auxiliary_points"][0]["link"] == "coupler"


# ------------------------------------------------------------------ false position
def test_binary_driver_needs_false_position():
    """Paper 7, remark: with a binary link (3) driving Alt's chain the plan is not direct; a trial
    rate of link 1 makes it direct, and the plan is then rescaled (one trial: the velocities are
    proportional to the input, so the rows of trial images pass through o)."""
    mech = load("alt-8-link-binary-driver")
    s = plan_velocities(mech)
    assert not s.direct and s.complete
    assert s.trial[0] == "link_1" and s.scale_by[0] == "link_3"
    assert "false position" in s.verdict()
    assert s.steps[-1].kind == "scale"


@pytest.mark.parametrize("build", [velocity_plan, rotated_velocities], ids=["plan", "rotated"])
def test_false_position_plan_matches_the_engine(build):
    mech = load("alt-8-link-binary-driver")
    sol = positions(mech)
    con = build(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    assert {"v_Q@link_4", "v_R@link_5"} <= set(con.results)


def test_acceleration_plan_after_false_position_matches_the_engine():
    """The plan of relative normal accelerations continues from a false-position velocity plan:
    with every ω known the accelerations are affine in the trial crank's α*, so two trials and
    the given driver's acceleration fix every row (test_accplans has the details)."""
    mech = load("alt-8-link-binary-driver")
    con = acceleration_plan(mech, positions(mech))
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()


# ------------------------------------------------------------------ cam contacts
@pytest.mark.parametrize("name", ["rolling-lever-valve-gear", "radial-roller-cam", "flat-faced-cam",
                                  "oscillating-roller-cam", "sulzer-valve-gear", "elliptical-gears",
                                  "proell-schwabe-valve-gear"])
@pytest.mark.parametrize("build", [velocity_plan, rotated_velocities], ids=["plan", "rotated"])
def test_cam_contact_velocities_through_the_common_normal(name, build):
    """A cam contact: both links' velocities project equally on the common normal n–n at the
    contact (Rosenauer 1937 paper 8: the rolling lever's pole on n–n), a line condition like a
    sliding pair's; a rolling contact: the point of contact is the relative pole, a hinge."""
    mech = linkwork.load(f"library:{name}")
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = solve(mech, x0 + np.array([0.05, 0.4, 1.1]))
    con = build(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9
    assert plan_velocities(mech).direct


def test_elliptical_gears_at_their_drawing_where_a_centre_is_in_line_with_the_mesh():
    """At the design position the wheel's centre M2 lies on the line of its axle O2 and the
    point of contact (the far vertex): the two lines through o and the contact's image are
    parallel there, so M2's image divides theirs (it is in line at every position drawn), and
    the planner's choice does not depend on Python's hash seed (the same steps under three)."""
    mech = linkwork.load("library:elliptical-gears")
    x0 = mech.driver_input_at_design(mech.drivers[0])
    con = velocity_plan(mech, solve(mech, np.array([x0])))
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    import subprocess
    import sys
    texts = []
    for seed in ("1", "2", "3"):
        code = ("import linkwork, numpy as np; from linkwork.constructions import construct; "
                "m = linkwork.load('library:elliptical-gears'); "
                "print(construct('velocity-plan', m, "
                "np.array([m.driver_input_at_design(m.drivers[0])])).describe())")
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             env={**os.environ, "PYTHONHASHSEED": seed})
        assert out.returncode == 0, out.stderr
        texts.append(out.stdout)
    assert texts[0] == texts[1] == texts[2]


def test_roemer_coupler_pole_lies_on_the_normal_to_the_slide_at_b():
    """Paper 1, Construction I, step 3: the pole P of the coupler ABC lies on BN, the line through B
    perpendicular to the slide of BL. The pole is read off the drawn images of Q and B (where the
    coupler's velocity vanishes) and compared with the line BN and with the engine's pole."""
    from linkwork.constructions._common import perp, pole

    mech = linkwork.load("library:roemer-mechanism")
    sol = positions(mech)
    con = velocity_plan(mech, sol)
    vq, vb = con.results["v_Q@coupler"].constructed, con.results["v_B"].constructed
    Q = np.array([e for e in con.elements.values() if e.label == "Q" and e.space == "mechanism"][0].obj.xy)
    B = sol.point("B").position
    # ω from the two images: v_B − v_Q = ω J (B − Q)
    d = B - Q
    w = np.sum((vb - vq) * perp(d), axis=1) / np.sum(d * d, axis=1)
    P = B + perp(vb) / w[:, None]
    slide = np.array([0.0, 1.0])  # the guide of BL (frame, not turning)
    assert np.allclose((P - B) @ slide, 0.0, atol=1e-9 * mech.length_scale)
    assert np.allclose(P, pole(sol, "coupler"), atol=1e-9 * mech.length_scale)


# ------------------------------------------------------------------ the free chains of paper 2
def _reference_velocities(chain, pos, given, directions, omega):
    """The velocity state of a free chain from its given data by linear algebra (the second,
    independent method): per link (v_x, v_y at its first point, ω), hinges equal, given point
    velocities, given directions (v × d = 0), known links at rest, drivers at their rate."""
    links = list(chain.links)
    col = {ln: 3 * i for i, ln in enumerate(links)}
    rows, rhs = [], []

    def field(ln, p):
        """Rows giving v_ln(p) (2 × 3n)."""
        M = np.zeros((2, 3 * len(links)))
        P0 = pos[chain.links[ln][0]]
        d = pos[p] - P0
        c = col[ln]
        M[:, c:c + 2] = np.eye(2)
        M[:, c + 2] = [-d[1], d[0]]
        return M

    for p, a, b in chain.hinges:
        rows.append(field(a, p) - field(b, p)); rhs.append(np.zeros(2))
    for p in given:
        for ln, pts in chain.links.items():
            if p in pts:
                rows.append(field(ln, p)); rhs.append(given[p])
    for p, d in directions.items():
        for ln, pts in chain.links.items():
            if p in pts:
                F = field(ln, p)
                rows.append((d[0] * F[1] - d[1] * F[0])[None]); rhs.append(np.zeros(1))
    for ln in chain.known:
        M = np.zeros((3, 3 * len(links))); M[:, col[ln]:col[ln] + 3] = np.eye(3)
        rows.append(M); rhs.append(np.zeros(3))
    for ln, pivot, ref in chain.drivers:
        rows.append(field(ln, pivot)); rhs.append(np.zeros(2))
        M = np.zeros((1, 3 * len(links))); M[0, col[ln] + 2] = 1
        rows.append(M); rhs.append(np.array([omega]))
    A, y = np.vstack(rows), np.concatenate(rhs)
    x, *_ = np.linalg.lstsq(A, y, rcond=None)
    assert np.linalg.matrix_rank(A) == 3 * len(links)
    assert np.allclose(A @ x, y, atol=1e-9)
    return lambda ln, P: x[col[ln]:col[ln] + 2] + x[col[ln] + 2] * np.array(
        [-(P - pos[chain.links[ln][0]])[1], (P - pos[chain.links[ln][0]])[0]])


def _run_script(script, chain, pos, given, directions, omega):
    """Carry out the script numerically, as a ruler would: each image where its two plan lines
    meet (plan lines through an image, perpendicular to a mechanism line)."""
    pos = dict(pos)
    img: dict = {}
    root, fixed = {}, set()
    for k, others in script.shared.items():
        root[k] = min((k,) + tuple(others))
        if any(ln in chain.known for ln, _ in (k,) + tuple(others)):
            fixed.add(k)

    def get(key):
        r = root.get(key, key)
        if key[0] == "o" or key[0] in chain.known or key in fixed:
            return np.zeros(2)  # the pole o: the known (fixed) link's points
        return img[r]

    def put(key, v):
        img[root.get(key, key)] = v

    def line_dir(line):
        if line.kind == "join":
            p, q = line.points
            return pos[q] - pos[p]
        d = directions[line.points[0]]
        return np.array([-d[1], d[0]])  # the normal to the given direction

    def where(aux):
        (l1, l2) = aux.lines
        p1, d1 = pos[l1.points[0]], line_dir(l1)
        p2, d2 = pos[l2.points[0]], line_dir(l2)
        t = np.linalg.solve(np.column_stack([d1, -d2]), p2 - p1)
        return p1 + t[0] * d1

    for st in script.steps:
        if st.aux is not None:
            pos[st.point] = where(st.aux)
        if st.kind == "given":
            v = given[st.point]
        elif st.kind == "driver":
            ln, pivot, ref = chain.drivers[0]
            d = pos[ref] - pos[pivot]
            v = omega * np.array([-d[1], d[0]])
        elif st.kind == "meet":
            (a, b) = st.lines
            da, db = (line_dir(pl.line) for pl in (a, b))
            # the image x with (x − anchor) ⟂ the mechanism line: x·d = anchor·d
            v = np.linalg.solve(np.vstack([da, db]), [get(a.anchor) @ da, get(b.anchor) @ db])
        elif st.kind == "divide":
            X, Y = (pos[n] for n in st.base)
            t = (pos[st.point] - X) @ (Y - X) / ((Y - X) @ (Y - X))
            x, y = (get((st.link, n)) for n in st.base)
            v = x + t * (y - x)
        else:
            raise AssertionError(st.kind)
        put((st.link, st.point), v)
    return pos, get


FREE_EXAMPLES = {
    "Ex I, Watt chain, v_A v_B": (WATT, ("A", "B"), (), (), ()),
    "Ex II, triad, v_K v_L v_M": (TRIAD, ("K", "L", "M"), (), (), ()),
    "Ex III, serial chain, v_A v_D, directions B C": (SERIAL, ("A", "D"), ("B", "C"), (), ()),
    "Ex IV, Dreispann, v_A v_F": (DREISPANN, ("A", "F"), (), (), ()),
    "Ex IV, Dreispann, v_A v_E": (DREISPANN, ("A", "E"), (), (), ()),
    "Ex IV, Dreispann on AC, AGH driving": (DREISPANN, (), (), ("AC",), (("AGH", "A", "G"),)),
    "Ex V, Heusinger, 1AB driving": (HEUSINGER, (), (), ("XII",), (("1AB", "1", "A"),)),
    "Ex V, free Heusinger, v_A v_3": (HEUSINGER, ("A", "3"), (), (), ()),
    "Ex V, free Heusinger, v_I v_1": (HEUSINGER, ("I", "1"), (), (), ()),
    "Ex V, free Heusinger, v_B v_2": (HEUSINGER, ("B", "2"), (), (), ()),
    "Ex V, free Heusinger, v_C v_1": (HEUSINGER, ("C", "1"), (), (), ()),
}


@pytest.mark.parametrize("example", list(FREE_EXAMPLES))
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_papers_free_chain_scripts_give_the_velocities(example, seed):
    """Each example of paper 2 at random positions and given data: every image the script
    constructs (auxiliary points included) equals the velocity from the linear solve."""
    links, given, dirs, known, drivers = FREE_EXAMPLES[example]
    chain = Chain.free(links, given=given, directions=dirs, known=known, drivers=drivers)
    rng = np.random.default_rng(seed)
    names = sorted({p for pts in chain.links.values() for p in pts})
    pos = {p: rng.uniform(-100, 100, 2) for p in names}
    gv = {p: rng.uniform(-50, 50, 2) for p in given}
    dv = {p: (lambda a: np.array([np.cos(a), np.sin(a)]))(rng.uniform(0, np.pi)) for p in dirs}
    script = plan_velocities(chain)
    assert script.direct
    pos, image = _run_script(script, chain, pos, gv, dv, 2.0)
    ref = _reference_velocities(chain, pos, gv, dv, 2.0)
    scale = max(np.linalg.norm(ref(ln, pos[p])) for ln, pts in chain.links.items() for p in pts)
    for (ln, p) in script.labels:
        if ln in chain.known or ln == "o":
            continue
        assert np.linalg.norm(image((ln, p)) - ref(ln, pos[p])) <= 1e-9 * scale, (ln, p)


# ------------------------------------------------------------------ curved slots, the library's valve gears
@pytest.mark.parametrize("name", ["stephenson-link-motion", "heusinger-valve-gear", "heusinger-hinge-chain"])
@pytest.mark.parametrize("build", [velocity_plan, rotated_velocities, acceleration_plan],
                         ids=["plan", "rotated", "acceleration"])
def test_valve_gears_of_the_library(name, build):
    """A pin in a curved slot (the die in the Kulisse): the relative velocity is tangent to the arc,
    so both links project equally on its radius; for accelerations the relative normal v²/r
    towards the arc's centre and the Coriolis term are transferred. The library's Heusinger gear
    has two drivers (crank and reversing arm): sampled in time."""
    mech = linkwork.load(f"library:{name}")
    if len(mech.drivers) > 1:
        sol = solve(mech, times=np.array([0.05, 0.2, 0.4, 0.7]))
    else:
        # away from the drawn position: the Stephenson gear is drawn where Q, E and K fall on one
        # line (the step k = (q ⟂ QK) ∩ (e ⟂ EK) degenerates there, and says so)
        sol = solve(mech, mech.driver_input_at_design(mech.drivers[0]) + np.array([0.3, 0.9, 2.0, 4.0]))
    assert (np.asarray(sol.status) == Status.OK).all()
    con = build(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    assert plan_velocities(mech).direct


@pytest.mark.parametrize("name", ["roberval-balance", "conchoidograph", "heusinger-valve-gear"])
@pytest.mark.parametrize("kind", ["velocity-plan", "rotated-velocities"])
def test_a_mechanism_at_rest_checks_its_plan(name, kind):
    """At rest (the drivers' rates given as zero): the constructed images must be zero too
    (the check no longer divides zero by a zero scale)."""
    import warnings

    from linkwork.constructions import construct
    from linkwork.errors import LinkworkWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LinkworkWarning)  # Roberval is over-closed
        mech = linkwork.load(f"library:{name}")
        rest = np.zeros(len(mech.drivers))
        sol = linkwork.solve(mech, velocities=rest, accelerations=rest)
    assert np.all(sol.link(mech.moving_links[0]).omega == 0)
    con = construct(kind, mech, sol)
    con.check()
    assert con.max_error() == 0.0
