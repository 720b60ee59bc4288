"""The plans of a group driven from inside: the ellipsograph (elliptic trammel), whose rod is
turned against the block at A. The rod's ω is the input's rate, so v_BA = ω·AB is a known side
of the velocity triangle o–a–b with a on guide a and b on guide b (and likewise a_BA for the
accelerations).

Independent values: the trammel in closed form — B − A = l(cos θ, sin θ) with A on the x-axis
and B on the y-axis gives A = (−l cos θ, 0), B = (0, l sin θ), so v_A = (l ω sin θ, 0),
v_B = (0, l ω cos θ) and, at the constant input speed, a_A = (l ω² cos θ, 0),
a_B = (0, −l ω² sin θ); besides, ``Construction.check`` compares every value with the engine.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.constructions import acceleration_plan, rotated_velocities, velocity_plan
from linkwork.errors import InputError

L = 50.0
OMEGA = np.pi  # 30 rpm


def trammel():
    mech = linkwork.load("library:ellipsograph")
    theta = mech.driver_input_at_design(mech.drivers[0]) + np.linspace(0.0, 2 * np.pi, 49)[:-1]
    return mech, theta


@pytest.mark.parametrize("build", [velocity_plan, rotated_velocities, acceleration_plan],
                         ids=["plan", "rotated", "acceleration"])
def test_ellipsograph_plans_match_the_closed_form_and_the_engine(build):
    mech, theta = trammel()
    con = build(mech, theta)
    con.check()
    s, c = np.sin(theta), np.cos(theta)
    z = np.zeros_like(theta)
    ok = ~con.degenerate
    # guides along the rod (θ = 0, π/2, …) are dead centres of the blocks: none here but noted
    v_a = con.results["v_A"].constructed
    v_b = con.results["v_B"].constructed
    assert np.allclose(v_a[ok], np.stack([L * OMEGA * s, z], 1)[ok], rtol=0, atol=1e-9 * L * OMEGA)
    assert np.allclose(v_b[ok], np.stack([z, L * OMEGA * c], 1)[ok], rtol=0, atol=1e-9 * L * OMEGA)
    assert np.allclose(con.results["omega_rod"].constructed, OMEGA, rtol=1e-12)
    if build is acceleration_plan:
        w2 = L * OMEGA**2
        assert np.allclose(con.results["a_A"].constructed, np.stack([w2 * c, z], 1), rtol=0, atol=1e-9 * w2)
        assert np.allclose(con.results["a_B"].constructed, np.stack([z, -w2 * s], 1), rtol=0, atol=1e-9 * w2)
        assert np.allclose(con.results["alpha_rod"].constructed, 0.0, atol=1e-9 * OMEGA**2)
        assert "cor_guide_a" in con.results and "cor_guide_b" in con.results


def test_step_texts_name_the_driver_the_rod_and_the_guides():
    mech, theta = trammel()
    v = [s.text for s in velocity_plan(mech, theta[:1]).steps]
    step = next(t for t in v if "Double slider" in t)
    for w in ("hinge A", "rod rod", "block_a", "guide_a", "guide_b", "v_BA", "perpendicular to AB",
              "parallel to guide_a", "they meet in a", "b = a + v_BA"):
        assert w in step, w
    a = [s.text for s in acceleration_plan(mech, theta[:1]).steps]
    step = next(t for t in a if "double slider" in t)
    for w in ("a_BA", "Coriolis", "guide_a", "guide_b", "b' = a' + a_BA"):
        assert w in step, w
    r = [s.text for s in rotated_velocities(mech, theta[:1]).steps]
    assert any("perpendicular to guide_a" in t and "parallel to AB" in t for t in r)


def test_driven_at_the_other_hinge(tmp_path):
    """The same trammel turned against block B: the rod's rate is the input's again."""
    from importlib.resources import files
    text = (files("linkwork.library") / "ellipsograph.toml").read_text()
    text = text.replace('joint = "A"\nreference = "B"', 'joint = "B"\nreference = "A"')
    text = text.replace('links = ["rod", "block_b"]', 'links = ["block_b", "rod"]')
    path = tmp_path / "trammel-b.toml"
    path.write_text(text)
    mech = linkwork.load(path)
    assert mech.drivers[0].joint == "B" and mech.drivers[0].base == "block_b"
    assert mech.drivers[0].driven == "rod"
    x0 = mech.driver_input_at_design(mech.drivers[0])
    con = acceleration_plan(mech, x0 + np.linspace(0.1, 6.0, 11))
    con.check()
    assert any("hinge B" in s.text for s in con.steps)


def test_other_groups_driven_from_inside_are_refused_by_name(tmp_path):
    """A four-bar turned at the coupler–rocker hinge: no double slider, refused naming the
    driver and why."""
    from importlib.resources import files
    text = (files("linkwork.library") / "crank-rocker.toml").read_text()
    text = text.replace('[driver]\njoint = "O2"', '[driver]\njoint = "B"\nreference = "O4"')
    path = tmp_path / "inner.toml"
    path.write_text(text)
    mech = linkwork.load(path)
    x0 = mech.driver_input_at_design(mech.drivers[0])
    for build in (velocity_plan, acceleration_plan):
        with pytest.raises(InputError, match=r"driver B \(inside the group, between moving links\)"):
            build(mech, np.array([x0]))


def test_two_points_on_the_trammel_keeps_its_digits():
    """The rod's inflection and Bresse circles from A and P over a whole turn (the plans above
    give the vectors). The input turns uniformly, so γ = 0 at every position: the compass copy
    of the zero angle must not lose half the digits (it did, 2e-8, before the chord's height
    was computed without cancellation)."""
    from linkwork.constructions import inflection_from_two_points
    mech, theta = trammel()
    con = inflection_from_two_points(mech, theta)
    con.check()
    assert con.max_error() <= 1e-12
