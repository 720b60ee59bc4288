"""The acceleration plans of chains driven by given point velocities (Rosenauer 1937, paper 4,
Ex. III: the free triad from the given accelerations of K, L, M; paper 2's free chains), drawn at
their drawn position: the velocity script of the chain performed on the plan of relative normal
accelerations, by false position with two trials where the velocities needed it (the
Dreispann), with a given direction's line through the end of its normal component κ·v².

Every constructed acceleration (points, Rosenauer's auxiliary points, every link's α) is
compared by ``Construction.check`` with the engine's solve from the given data
(`kinematics.point_inputs.solve_given`: linear solves on the pairs' equations and their jets,
an independent route); batches of several velocity sets are drawn sample by sample.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import linkwork
from linkwork.constructions import acceleration_plan, construct
from linkwork.errors import InputError
from linkwork.kinematics.point_inputs import solve_given

CHAINS = ["rosenauer-free-triad", "rosenauer-free-watt-chain", "rosenauer-free-serial-chain",
          "rosenauer-free-dreispann", "rosenauer-free-heusinger-chain"]


def with_accelerations(mech, n=None, seed=0):
    """The file's given data with an acceleration for every given velocity that has none (and
    the file's own where it has them); ``n``: a batch of n sets, velocities and accelerations
    varied about the file's."""
    rng = np.random.default_rng(seed)
    out = []
    for g in mech.given:
        if g.kind == "velocity":
            a = g.acceleration if g.acceleration is not None else rng.uniform(-20, 20, 2)
            if n is not None:
                g = replace(g, velocity=g.velocity + rng.uniform(-5, 5, (n, 2)),
                            acceleration=a + rng.uniform(-5, 5, (n, 2)))
            else:
                g = replace(g, acceleration=a)
        elif g.curvature is None:
            g = replace(g, curvature=0.0)
        out.append(g)
    return out


@pytest.mark.parametrize("name", CHAINS)
@pytest.mark.parametrize("n", [None, 4])
def test_given_chain_acceleration_plans_match_the_engine(name, n):
    mech = linkwork.load(f"library:{name}")
    sol = solve_given(mech, with_accelerations(mech, n))
    con = acceleration_plan(mech, sol)
    assert not con.degenerate.any(), con.messages()
    con.check()
    for ln in mech.moving_links:
        assert f"alpha_{ln}" in con.results
    for g in mech.given:
        assert f"a_{g.point}" in con.results


def test_the_free_triad_draws_from_its_file():
    """The triad's file gives the accelerations of K, L, M (paper 4, Ex. III): drawn as it
    stands, and each given acceleration is laid off at its point of the plan."""
    mech = linkwork.load("library:rosenauer-free-triad")
    con = construct("acceleration-plan", mech, None)
    con.check()
    texts = [s.text for s in con.steps]
    for p in "KLM":
        assert any(f"given: the acceleration a_{p}, laid off at {p.lower()}" in t for t in texts)
    # paper 4, Ex. III: locus lines through the ends of j_K, j_L, j_M perpendicular to KA, LB,
    # MC, and the triangle A₁B₁C₁ inscribed with its sides perpendicular to ABC's
    assert any(t.startswith("Locus lines (paper 4)") and "perpendiculars to KA, LB, MC: α–α, β–β, γ–γ" in t
               for t in texts)
    assert any(t.startswith("Inscribed triangle") for t in texts)
    for p in "ABC":
        assert f"a_{p}" in con.results


def test_a_given_direction_uses_the_paths_curvature():
    mech = linkwork.load("library:rosenauer-free-serial-chain")
    con = acceleration_plan(mech, solve_given(mech, with_accelerations(mech)))
    con.check()
    texts = " ".join(s.text for s in con.steps)
    assert "the line ∥ v_B runs through the end of the normal component κ·v_B²" in texts
    assert "the line ∥ v_C runs through the end of the normal component κ·v_C²" in texts
    # the file's curvature of C's path (0.01/mm) is what the engine solved with: a different κ
    # moves the constructed accelerations with the engine's
    bent = [replace(g, curvature=0.03) if g.point == "C" else g for g in with_accelerations(mech)]
    acceleration_plan(mech, solve_given(mech, bent)).check()


def test_two_trials_on_accelerations_for_the_dreispann():
    """The Dreispann from v_A, v_B (paper 2: Rosenauer's rule fails, two trials): the
    accelerations follow the same false position, two trial α* and the check's ratio."""
    mech = linkwork.load(Path(__file__).parent / "data" / "free-dreispann-ab.toml")
    con = acceleration_plan(mech, solve_given(mech, with_accelerations(mech)))
    con.check()
    texts = [s.text for s in con.steps]
    assert any(t.startswith("first trial (accelerations)") for t in texts)
    assert any(t.startswith("second trial (accelerations)") for t in texts)


@pytest.mark.parametrize("name, missing", [
    ("rosenauer-free-watt-chain", "the acceleration of A, the acceleration of B"),
    ("rosenauer-free-dreispann", "the acceleration of A, the acceleration of F"),
    ("rosenauer-free-serial-chain", "the acceleration of A, the acceleration of D"),
])
def test_missing_accelerations_are_named(name, missing):
    mech = linkwork.load(f"library:{name}")
    with pytest.raises(InputError, match=f"needs {missing}"):
        acceleration_plan(mech, None)


def test_a_missing_curvature_is_named():
    mech = linkwork.load("library:rosenauer-free-serial-chain")
    given = [replace(g, curvature=None) if g.point == "B" else g for g in with_accelerations(mech)]
    sol = solve_given(mech, [g for g in with_accelerations(mech)])
    # the solve itself needs the curvature for accelerations; a velocity solve is refused by name
    with pytest.raises(InputError, match="the curvature of the path of B"):
        acceleration_plan(mech, replace_given(sol, given))


def replace_given(sol, given):
    sol.given = tuple(given)
    return sol


def test_a_velocity_solve_is_refused_for_the_accelerations():
    mech = linkwork.load("library:rosenauer-free-triad")
    with pytest.raises(InputError, match="solved to velocities only"):
        acceleration_plan(mech, solve_given(mech, order=1))
