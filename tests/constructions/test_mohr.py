"""Mohr's construction (Pöschl §47–48): b_B, b_AB^(n) = |Aα′| and the rod's angular acceleration
against the engine (linkwork.solve) at random and dense crank angles to 1e-9; the dead centres
against the closed form r ω² (1 ± r/l); the degenerate positions say why."""

import numpy as np
import pytest
from test_constructions import FOUR_BARS, RTOL, SLIDER_CRANKS, random_positions
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from linkwork.constructions import construct
from linkwork.constructions.construction import DegenerateConstruction


@pytest.mark.parametrize("mech_name", FOUR_BARS + SLIDER_CRANKS)
def test_mohr_matches_the_engine_at_random_positions(mech_name):
    mech, sol = random_positions(mech_name, n=60, seed=48)
    con = construct("mohr", mech, sol).check(RTOL)
    assert {"b_B", "b_ABn", "eps"} <= set(con.results)
    assert ("b_Bn" in con.results) == (mech_name in FOUR_BARS)
    assert con.max_error() <= RTOL
    assert con.degenerate.mean() < 0.1
    # the normal component of B about A is l ω² of the engine's rod, read as |Aα′|
    rod = con.results["b_ABn"]
    ok = ~con.degenerate
    np.testing.assert_allclose(rod.constructed[ok], rod.analytic[ok], rtol=1e-9)


@pytest.mark.parametrize("mech_name", ["slider-crank-centric", "slider-crank-offset",
                                       "pmks-teaching-slider-crank", "crank-rocker",
                                       "pmks-teaching-four-bar", "double-rocker", "antiparallelogram"])
def test_mohr_dense_sweep(mech_name):
    """Every 0.2° of the whole motion: right to 1e-9 wherever a result is given, a reason elsewhere,
    and only a handful of positions (poles far off the sheet, dead centres of the engine) left out."""
    mech = linkwork.load(f"library:{mech_name}")
    motion = linkwork.whole_motion(mech, step=np.radians(0.2))
    con = construct("mohr", mech, motion).check(RTOL)
    assert con.degenerate.sum() <= 8
    for i in np.flatnonzero(con.degenerate):
        assert con.messages(i)


def test_mohr_with_a_crank_that_accelerates():
    """b_A with a tangential component (ε₁ ≠ 0): the polygon still closes on the engine's b_B."""
    for name in ("slider-crank-offset", "crank-rocker"):
        mech = linkwork.load(f"library:{name}")
        phi = np.linspace(0.1, 6.1, 37)
        sol = linkwork.solve(mech, phi, velocities=np.full(37, 3.0), accelerations=np.full(37, -7.0))
        construct("mohr", mech, sol).check(RTOL)


def test_mohr_does_not_depend_on_the_scale():
    mech = linkwork.load("library:crank-rocker")
    phi = np.radians([20.0, 75.0, 230.0])
    a = construct("mohr", mech, phi).check(RTOL)
    b = construct("mohr", mech, phi, ka=0.37).check(RTOL)
    np.testing.assert_allclose(a.results["b_B"].constructed, b.results["b_B"].constructed, rtol=1e-12)


def test_mohr_dead_centres_closed_form():
    """Pöschl eqs. (100), (101): b_B0 = b_A(1 + r/l), b_B6 = b_A(1 − r/l) with b_A = r ω² (centric
    slider-crank, r = 50, l = 200, 120 rpm); the regular construction fails there (γ), Pöschl's
    dead-centre construction (OM = l, line OE) is used instead."""
    mech = linkwork.load("library:slider-crank-centric")
    con = construct("mohr", mech, np.radians([0.0, 180.0])).check(RTOL)
    assert not con.degenerate.any()
    assert any("dead centre" in m for m in con.messages())
    w, r, l = 120 * 2 * np.pi / 60, 50.0, 200.0
    bB = con.results["b_B"].constructed
    assert bB[0, 0] == pytest.approx(-r * w * w * (1 + r / l), rel=1e-12)
    assert bB[1, 0] == pytest.approx(r * w * w * (1 - r / l), rel=1e-12)
    np.testing.assert_allclose(bB[:, 1], 0.0, atol=1e-9 * r * w * w)
    # the line OE cuts both values off on the perpendiculars at B₀ and B₆
    np.testing.assert_allclose(con.results["b_B0"].constructed,
                               [r * w * w * (1 + r / l), r * w * w * (1 - r / l)], rtol=1e-12)
    # b_AB^(n) = l ω² with ω = (r/l) ω₁
    np.testing.assert_allclose(con.results["b_ABn"].constructed, r * r * w * w / l, rtol=1e-12)


def test_mohr_four_bar_reversal_point_uses_the_limiting_construction():
    """At the rocker's reversal points (O₁, A, B in line) Pöschl says the construction holds."""
    from scipy.optimize import brentq
    mech = linkwork.load("library:crank-rocker")

    def in_line(phi):
        s = linkwork.solve(mech, [phi])
        o, a, b = (s.point(p).position[0] for p in ("O2", "A", "B"))
        return (a - o)[0] * (b - o)[1] - (a - o)[1] * (b - o)[0]
    motion = linkwork.whole_motion(mech, step=np.radians(1.0))
    c = np.array([in_line(p) for p in motion.inputs[:, 0]])
    k = int(np.flatnonzero(np.sign(c[:-1]) != np.sign(c[1:]))[0])
    phi = brentq(in_line, motion.inputs[k, 0], motion.inputs[k + 1, 0], xtol=1e-15)
    con = construct("mohr", mech, [phi]).check(RTOL)
    assert not con.degenerate.any()
    assert any("reversal point" in m for m in con.messages())
    assert con.results["b_Bn"].constructed[0] == pytest.approx(0.0, abs=1e-6)


def test_mohr_near_a_dead_centre_is_one_clear_message():
    mech = linkwork.load("library:slider-crank-centric")
    con = construct("mohr", mech, [1e-8])
    assert con.degenerate[0]
    assert len(con.messages(0)) == 1
    with pytest.raises(DegenerateConstruction, match="in line .*grazing angle"):
        con.require(0)


def test_mohr_crank_parallel_to_rocker_is_one_clear_message():
    """Four-bar: the crank parallel to the rocker puts the coupler's pole Ω at infinity; the
    reversed line sequence at B collapses there."""
    mech = linkwork.load("library:crank-rocker")
    motion = linkwork.whole_motion(mech, step=np.radians(0.2))
    d = [motion.point(p).position for p in ("O2", "A", "B", "O4")]
    u, v = d[1] - d[0], d[2] - d[3]
    s = abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))
    i = int(np.argmin(s))
    con = construct("mohr", mech, motion.inputs[i:i + 1, 0])
    assert con.degenerate[0]
    assert len(con.messages(0)) == 1
    with pytest.raises(DegenerateConstruction, match="parallel to the rocker"):
        con.require(0)


def test_mohr_rejects_other_mechanisms():
    with pytest.raises(linkwork.LinkworkError, match="neither a slider-crank nor a four-bar"):
        construct("mohr", linkwork.load("library:whitworth-quick-return"), [0.3])


def test_mohr_is_drawn_by_the_cli(tmp_path):
    out = tmp_path / "mohr.svg"
    r = CliRunner().invoke(app, ["draw", "library:slider-crank-offset", "--at", "40",
                                 "--construction", "mohr", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert "Mohr" in r.output and "\u03b1\u2032" in r.output
    assert out.exists() and "<svg" in out.read_text()
