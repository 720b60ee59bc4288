"""Rosenauer's velocity constructions of chains driven by given point velocities (1937, paper 2,
Examples I–V; digest 000 §4.2–4.6), on the library's files.

Each construction is checked against the engine to 1e-9 (`Construction.check`), and the
constructed velocities, with no use of the engine, against identities the papers rest on: the
projection theorem along every link and across a joint (Rosenauer's extension, digest 000 §2.4),
the given data, and the relative poles read off the drawn images against the poles the
Aronhold–Kennedy theorem reaches from the hinges. Then each example's stated property: its
auxiliary points, and the constructibility verdicts (§13.10).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from linkwork.constructions import acceleration_plan, rotated_velocities, velocity_plan
from linkwork.kinematics.point_inputs import solve_given
from linkwork.model import GivenDirection, GivenVelocity, Mechanism, hinge_chain
from linkwork.topology.constructibility import Chain, plan_velocities, wittenbauer_rule

EXAMPLES = ["rosenauer-free-watt-chain", "rosenauer-free-triad", "rosenauer-free-serial-chain",
            "rosenauer-free-dreispann", "rosenauer-free-heusinger-chain"]


def load(name: str) -> Mechanism:
    return linkwork.load(f"library:{name}")


def with_given(mech: Mechanism, given) -> Mechanism:
    return Mechanism.build(name=mech.name, points=dict(mech.points),
                           links={ln.name: list(ln.points) for ln in mech.links},
                           joints=list(mech.joints), drivers=[], frame=mech.frame, given=given)


def cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def constructed_field(mech, con):
    """Per link, the velocity field (a point P, v(P), ω) read off two constructed velocities of
    its points (a hinge's velocity is common to its links): v(X) = v(P) + ω·J(X − P)."""
    out = {}
    for ln in mech.moving_links:
        vel = {p: np.asarray(con.results[f"v_{p}"].constructed)[0]
               for p in dict.fromkeys(mech.link(ln).points) if f"v_{p}" in con.results}
        (P, vp), (R, vr) = list(vel.items())[:2]
        d = mech.points[R] - mech.points[P]
        w = cross(d, vr - vp) / (d @ d)
        out[ln] = (mech.points[P], vp, w)
    return out


def at(field, X):
    P, vp, w = field
    d = X - P
    return vp + w * np.array([-d[1], d[0]])


@pytest.mark.parametrize("name", EXAMPLES)
@pytest.mark.parametrize("build", [velocity_plan, rotated_velocities], ids=["plan", "rotated"])
def test_construction_matches_the_engine(name, build):
    mech = load(name)
    con = build(mech, None)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()
    for a in plan_velocities(mech).aux:  # every auxiliary point was compared as a point of its link
        assert f"v_{a.name}@{a.link}" in con.results


@pytest.mark.parametrize("name", EXAMPLES)
def test_constructed_velocities_obey_the_projection_theorem_and_the_given_data(name):
    mech = load(name)
    con = velocity_plan(mech, solve_given(mech))
    field = constructed_field(mech, con)
    vmax = max(np.abs(f[1]).max() for f in field.values())
    for ln, f in field.items():
        pts = list(dict.fromkeys(mech.link(ln).points))
        for i, X in enumerate(pts):
            for Y in pts[i + 1:]:
                d = mech.points[Y] - mech.points[X]
                assert abs((at(f, mech.points[Y]) - at(f, mech.points[X])) @ d) <= 1e-9 * vmax * np.hypot(*d)
    for g in mech.given:
        v = at(field[g.link], mech.points[g.point])
        if g.kind == "velocity":
            assert np.allclose(v, g.velocity, atol=1e-12 * vmax)
        else:
            assert abs(cross(g.direction, v)) <= 1e-12 * vmax


@pytest.mark.parametrize("name", EXAMPLES)
def test_relative_poles_of_the_drawn_plan_are_the_three_pole_theorems(name):
    """The pole of links a and b where their constructed fields agree, against every pole the
    Aronhold–Kennedy theorem reaches from the hinges (`instant.kennedy_poles`)."""
    from linkwork.instant.poles import kennedy_poles

    mech = load(name)
    sol = solve_given(mech)
    field = constructed_field(mech, velocity_plan(mech, sol))
    kp = kennedy_poles(sol)
    checked = 0
    for (a, b) in kp:
        if mech.frame in (a, b):
            continue  # a free chain has no hinge on the frame: those poles are not reached
        h = np.asarray(kp[a, b].coords)[0]
        if not np.isfinite(h).all() or abs(h[2]) < 1e-12:
            continue
        K = h[:2] / h[2]
        (Pa, va, wa), (Pb, vb, wb) = field[a], field[b]
        # where v_a(X) = v_b(X): (va − vb) + J((wa − wb)·X − wa·Pa + wb·Pb) = 0, J⁻¹ = −J
        dv, s = va - vb, wa * Pa - wb * Pb
        X = (s + np.array([-dv[1], dv[0]])) / (wa - wb)
        assert np.hypot(*(X - K)) <= 1e-8 * mech.length_scale, (a, b)
        checked += 1
    assert checked >= len(mech.joints)


def meet(P, p, q, r, t) -> np.ndarray:
    """Where the lines pq and rt of the drawing P meet."""
    M = np.column_stack([P[q] - P[p], P[r] - P[t]])
    u = np.linalg.solve(M, P[r] - P[p])
    return P[p] + u[0] * (P[q] - P[p])


def L(*pairs: str) -> frozenset:
    return frozenset(frozenset(p) for p in pairs)


def aux_lines(script) -> set:
    return {frozenset(frozenset(ln.points) for ln in a.lines) for a in script.aux}


def test_example_1_watt_chain_auxiliary_points_and_projections_across_joints():
    """Q = AC ∩ BG taken in CDG: v_Q projects on AC as v_A does (across C) and on BG as v_B
    (across G); R = AE ∩ BF in DEF likewise. Wittenbauer's rule fails for this chain."""
    mech = load("rosenauer-free-watt-chain")
    s = plan_velocities(mech)
    assert s.direct and aux_lines(s) == {L("AC", "BG"), L("AE", "BF")}
    assert not wittenbauer_rule(Chain.from_mechanism(mech)).holds
    con = velocity_plan(mech, None)
    P = mech.points
    for a in s.aux:
        vq = np.asarray(con.results[f"v_{a.name}@{a.link}"].constructed)[0]
        for line in a.lines:
            X, Y = line.points
            given = X if X in ("A", "B") else Y
            e = P[Y] - P[X]
            v_given = next(g.velocity for g in mech.given if g.point == given)
            assert vq @ e == pytest.approx(v_given @ e, abs=1e-9 * np.abs(v_given).max() * np.hypot(*e))


def test_example_2_triad_both_of_rosenauers_auxiliary_points():
    """D = AK ∩ BL and E = AK ∩ CM as points of ABC: each has the projections of the given ends'
    velocities on its two lines (the triad's plan without similar point rows)."""
    mech = load("rosenauer-free-triad")
    s = plan_velocities(mech)
    assert s.direct and L("KA", "LB") in aux_lines(s) and {a.link for a in s.aux} == {"ABC"}
    field = constructed_field(mech, velocity_plan(mech, None))["ABC"]
    P = mech.points
    v = {g.point: g.velocity for g in mech.given}

    for (k, a), (m, b) in ((("K", "A"), ("L", "B")), (("K", "A"), ("M", "C"))):
        X = meet(P, k, a, m, b)
        vx = at(field, X)
        for end, hinge in ((k, a), (m, b)):
            e = P[hinge] - P[end]
            assert vx @ e == pytest.approx(v[end] @ e, rel=1e-9)


def test_example_3_serial_chain_pole_of_ebf_on_the_normal_at_b():
    """The pole of EBF lies on the normal to B's direction (so does R = that normal ∩ AE, whose
    velocity is along B's direction), and a, e, r lie on one line perpendicular to AE."""
    mech = load("rosenauer-free-serial-chain")
    s = plan_velocities(mech)
    kinds = {(a.link, frozenset(ln.kind for ln in a.lines)) for a in s.aux}
    assert kinds == {("EBF", frozenset({"direction", "join"})), ("CGF", frozenset({"direction", "join"}))}
    con = velocity_plan(mech, None)
    field = constructed_field(mech, con)
    dB = next(g.direction for g in mech.given if g.point == "B")
    nB = np.array([-dB[1], dB[0]])
    Pe, ve, w = field["EBF"][0], field["EBF"][1], field["EBF"][2]
    pole = Pe + np.array([-ve[1], ve[0]]) / w  # where the field of EBF vanishes
    B = mech.points["B"]
    assert abs(cross(pole - B, nB)) <= 1e-9 * mech.length_scale
    aux = next(a for a in s.aux if a.link == "EBF")
    vr = np.asarray(con.results[f"v_{aux.name}@EBF"].constructed)[0]
    assert abs(cross(vr, dB)) <= 1e-9 * np.abs(vr).max()
    e = mech.points["E"] - mech.points["A"]
    va = next(g.velocity for g in mech.given if g.point == "A")
    vE = np.asarray(con.results["v_E"].constructed)[0]
    for x in (vE, vr):
        assert (x - va) @ e == pytest.approx(0.0, abs=1e-9 * np.abs(va).max() * np.hypot(*e))


def test_example_4_dreispann_papers_q_and_r_and_the_verdicts():
    """With v_A and v_F direct; Rosenauer's Q = FK ∩ DB and R = HJ ∩ DB taken in JKB have the
    projections of v_F on FK, v_D on DB and v_H on HJ. With v_A and v_B Rosenauer's rule fails
    for CDE, and `linkwork plan` says so without drawing."""
    mech = load("rosenauer-free-dreispann")
    assert plan_velocities(mech).direct
    con = velocity_plan(mech, None)
    field = constructed_field(mech, con)
    P = mech.points
    vel = {p: np.asarray(con.results[f"v_{p}"].constructed)[0] for p in ("F", "D", "H")}

    for (a, b), (c, d) in ((("F", "K"), ("D", "B")), (("H", "J"), ("D", "B"))):
        X = meet(P, a, b, c, d)
        vx = at(field["JKB"], X)
        for p, q in ((a, b), (c, d)):
            e = P[q] - P[p]
            assert vx @ e == pytest.approx(vel[p] @ e, rel=1e-9)
    ab = with_given(mech, [GivenVelocity("A", [30.0, 10.0]), GivenVelocity("B", [-10.0, 40.0])])
    s = plan_velocities(ab)
    assert not s.direct and "CDE" in s.unreached
    assert solve_given(ab).status[0] == 0  # the engine solves it all the same


@pytest.mark.parametrize("pair", [("A", "O3"), ("I", "O1"), ("B", "O2"), ("C", "O1")])
def test_example_5_free_heusinger_chain_with_each_pair_the_paper_names(pair):
    mech = load("rosenauer-free-heusinger-chain")
    given = [GivenVelocity(pair[0], [30.0, -20.0]), GivenVelocity(pair[1], [10.0, 25.0], link="XII")]
    m2 = with_given(mech, given)
    assert plan_velocities(m2).direct
    con = velocity_plan(m2, None)
    con.check()
    assert con.max_error() <= 1e-9 and not con.degenerate.any()


def test_example_5_auxiliary_points_are_the_papers():
    s = plan_velocities(load("rosenauer-free-heusinger-chain"))
    assert aux_lines(s) == {L(("H", "G"), ("O5", "K")), L(("D", "E"), ("O4", "L"))}
    assert {a.link for a in s.aux} == {"gkf", "fel"}


RANDOM = {
    "Ex I": ({"CDG": "CDG", "DEF": "DEF", "AC": "AC", "AE": "AE", "BG": "BG", "BF": "BF"}, "AB", ""),
    "Ex II": ({"ABC": "ABC", "AK": "AK", "BL": "BL", "CM": "CM"}, "KLM", ""),
    "Ex III": ({"AE": "AE", "EBF": "EBF", "CGF": "CGF", "GD": "GD"}, "AD", "BC"),
    "Ex IV": ({"AGH": "AGH", "EFG": "EFG", "CDE": "CDE", "JKB": "JKB", "AC": "AC", "HJ": "HJ",
               "FK": "FK", "DB": "DB"}, "AF", ""),
}


@pytest.mark.parametrize("example", list(RANDOM))
@pytest.mark.parametrize("seed", [11, 12, 13])
def test_scripts_at_random_positions_match_the_engine(example, seed):
    """The examples' chains drawn anew at random and given random data: every image the script
    constructs (auxiliary points included) is the engine's velocity to 1e-9."""
    links, velocities, directions = RANDOM[example]
    rng = np.random.default_rng(seed)
    pos = {p: rng.uniform(-100, 100, 2) for p in sorted({p for v in links.values() for p in v})}
    given = [GivenVelocity(p, rng.uniform(-50, 50, 2)) for p in velocities]
    given += [GivenDirection(p, rng.normal(size=2)) for p in directions]
    mech = hinge_chain(example, pos, links, given)
    for build in (velocity_plan, rotated_velocities):
        con = build(mech, None)
        con.check()
        assert con.max_error() <= 1e-9 and not con.degenerate.any()


def test_a_batch_of_given_velocity_sets_is_constructed_sample_by_sample():
    mech = load("rosenauer-free-watt-chain")
    rng = np.random.default_rng(2)
    sol = solve_given(mech, [GivenVelocity("A", rng.uniform(-40, 40, (5, 2))),
                             GivenVelocity("B", rng.uniform(-40, 40, (5, 2)))])
    for build in (velocity_plan, rotated_velocities):
        con = build(mech, sol)
        con.check()
        assert con.max_error() <= 1e-9 and len(con.degenerate) == 5


def test_acceleration_plan_without_given_accelerations_is_refused_with_its_reason():
    """The Watt chain's file gives velocities only (the acceleration plans of given chains are
    in test_given_accelerations.py)."""
    with pytest.raises(linkwork.LinkworkError, match="needs the acceleration of A, the acceleration of B"):
        acceleration_plan(load("rosenauer-free-watt-chain"), None)


# ------------------------------------------------------------------ the commands
def test_plan_command_explains_and_checks_a_free_chain():
    res = CliRunner().invoke(app, ["plan", "library:rosenauer-free-watt-chain", "--explain"])
    assert res.exit_code == 0, res.output
    assert "given: a = o + v_A" in res.output
    assert "Q = AC \u2229 BG" in res.output or "Q = BG \u2229 AC" in res.output
    assert "largest relative error against the engine" in res.output
    res = CliRunner().invoke(app, ["plan", "library:rosenauer-free-serial-chain", "--format", "json"])
    doc = json.loads(res.output)
    assert doc["rosenauer"]["direct"] and doc["construction"]["max_relative_error"] <= 1e-9


def test_plan_command_refuses_at_and_draws_a_chain_by_two_trials(tmp_path):
    res = CliRunner().invoke(app, ["plan", "library:rosenauer-free-triad", "--at", "30"])
    assert res.exit_code != 0 and "takes no --at" in res.output
    text = linkwork.io.files.resolve("library:rosenauer-free-dreispann")[1]
    f = tmp_path / "dreispann-ab.toml"
    f.write_text(text.replace('point = "F"\nvelocity = [-10, 40]', 'point = "B"\nvelocity = [-10, 40]'))
    res = CliRunner().invoke(app, ["plan", str(f), "--explain"])
    assert res.exit_code == 0, res.output
    # Rosenauer's rule does not reach it (v_A, v_B); similar point rows (two trials) do, and
    # the drawn velocities are checked against the engine
    assert "not directly constructible" in res.output and "second trial" in res.output
    err = float(res.output.rsplit("largest relative error against the engine:", 1)[1].split()[0])
    assert err <= 1e-9


def test_plan_command_names_a_missing_condition(tmp_path):
    text = linkwork.io.files.resolve("library:rosenauer-free-watt-chain")[1]
    f = tmp_path / "watt-a.toml"
    f.write_text(text.replace('[[given]]\npoint = "B"\nvelocity = [10, -35]\n', ""))
    res = CliRunner().invoke(app, ["plan", str(f)])
    assert res.exit_code != 0 and "under-determined: 2 more conditions needed" in res.output


def test_draw_command_draws_the_plan_of_a_free_chain(tmp_path):
    out = tmp_path / "plan.svg"
    res = CliRunner().invoke(app, ["draw", "library:rosenauer-free-heusinger-chain", "--construction",
                                   "velocity-plan", "--show", "mechanism,velocities,poles", "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert out.read_text().lstrip().startswith("<")
    res = CliRunner().invoke(app, ["draw", "library:rosenauer-free-serial-chain", "--construction",
                                   "rotated-velocities", "--steps", "-o", str(tmp_path / "r.svg")])
    assert res.exit_code == 0, res.output
    res = CliRunner().invoke(app, ["draw", "library:rosenauer-free-watt-chain", "--show", "accelerations",
                                   "-o", str(tmp_path / "a.svg")])
    assert res.exit_code != 0 and "accelerations are not solved" in res.output


def test_poles_and_structure_commands_take_the_given_data():
    res = CliRunner().invoke(app, ["poles", "library:rosenauer-free-triad"])
    assert res.exit_code == 0, res.output
    assert "poles at the drawn position" in res.output
    assert "(70, -5)" in res.output  # P13 = ABC / BL: the hinge B, from velocities and by the theorem
    res = CliRunner().invoke(app, ["poles", "library:rosenauer-free-triad", "--at", "10"])
    assert res.exit_code != 0 and "takes no --at" in res.output
    res = CliRunner().invoke(app, ["structure", "library:rosenauer-free-watt-chain", "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    assert doc["real_mobility"] == 4 and doc["inputs_needed"] == 0


def test_five_bar_plan_from_its_coupler_point_velocity():
    """A mechanism with drivers solved from a point's velocity instead (its two cranks' rates
    unknown): the plan starts from c and reaches a and b by dyad steps to the frame pivots."""
    mech = load("five-bar")
    driven = linkwork.solve(mech, times=[0.0])
    sol = solve_given(mech, [GivenVelocity("C", driven.point("C").velocity[0])])
    con = velocity_plan(mech, sol)
    con.check()
    assert con.max_error() <= 1e-9
    assert con.steps[1].text.startswith("given: c = o + v_C")


def test_analyze_command_at_the_drawn_position():
    res = CliRunner().invoke(app, ["analyze", "library:rosenauer-free-triad", "--format", "json"])
    assert res.exit_code == 0, res.output
    (sample,) = json.loads(res.output)["samples"]
    assert sample["points"]["K"]["velocity"] == pytest.approx([30.0, -10.0])
    assert sample["points"]["K"]["acceleration"] == pytest.approx([5.0, 20.0])
    res = CliRunner().invoke(app, ["analyze", "library:rosenauer-free-watt-chain"])
    assert res.exit_code == 0 and "given point velocities" in res.output
    res = CliRunner().invoke(app, ["analyze", "library:rosenauer-free-watt-chain", "--at", "3"])
    assert res.exit_code != 0 and "takes no --at" in res.output


@pytest.mark.parametrize("command", [["forces"], ["animate", "-o", "x.html"]])
def test_commands_of_a_whole_motion_or_a_driver_refuse_with_the_reason(command, tmp_path):
    args = [command[0], "library:rosenauer-free-triad"] + [str(tmp_path / a) if a.endswith(".html") else a
                                                          for a in command[1:]]
    res = CliRunner().invoke(app, args)
    assert res.exit_code != 0 and "given point velocities" in res.output
    assert "Traceback" not in res.output
