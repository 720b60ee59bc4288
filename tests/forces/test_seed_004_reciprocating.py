"""Seed 004 (steam-engine text, §174–§176): the inertia forces of the reciprocating masses
("Beschleunigungsdrücke") of the centric slider-crank.

Expectations: the seed's dead-centre accelerations 4·r·π²·n²·(1 ± r/l) (n in rev/s), its table of
the crank angle of maximum piston velocity (zero inertia force) for rod ratios l/r = 2 … 10,
the cubic in sin²α that it states for that angle, and the exact piston acceleration derived by
hand, −r·ω²·[cos φ + (λ·cos 2φ + λ³·sin⁴φ)/(1 − λ²·sin²φ)^{3/2}], λ = r/l, of which the usual
series' first two harmonics are the approximation."""

import numpy as np
import pytest
from scipy.optimize import brentq

import linkwork
from linkwork.errors import ModelError
from linkwork.forces.reciprocating import reciprocating_inertia
from mechanism_texts import slider_crank_text

# seed 004, §176: rod ratio n = l/r -> crank angle of maximum piston velocity (degrees, minutes)
TABLE = {2: (67, 42), 3: (73, 11), 4: (76, 43), 5: (79, 7), 6: (80, 48), 7: (82, 2), 8: (82, 59),
         9: (83, 44), 10: (84, 20)}


def slider_crank(ratio: float, r: float = 100.0, rpm: float = 300.0):
    """Centric slider-crank, crank r (mm) drawn at 60°, rod ratio l/r."""
    l = ratio * r
    A = (r * np.cos(np.pi / 3), r * np.sin(np.pi / 3))
    B = (A[0] + np.sqrt(l**2 - A[1] ** 2), 0.0)
    return linkwork.load_text(slider_crank_text(name=f"l/r = {ratio}", A=A, B=B, speed=f"{rpm} rpm"))


@pytest.mark.parametrize("ratio", [3.5, 4.0, 5.0])
def test_dead_centres(ratio):
    mech = slider_crank(ratio, r=150.0, rpm=240.0)
    sol = linkwork.solve(mech, [0.0, np.pi])
    m = 12.0
    rec = reciprocating_inertia(sol, m)
    n, r = 4.0, 0.150
    a = 4 * r * np.pi**2 * n**2 * np.array([1 + 1 / ratio, 1 - 1 / ratio])
    # the piston accelerates towards the crank at the outer dead centre, away at the inner one:
    # its inertia force points the other way
    np.testing.assert_allclose(rec.exact, m * a * [1, -1], rtol=1e-12)
    np.testing.assert_allclose(np.cos(rec.angle), [1.0, -1.0], atol=1e-12)
    # the series is exact at the dead centres
    np.testing.assert_allclose(rec.error, 0.0, atol=1e-12 * m * a[0])


@pytest.mark.parametrize("ratio", [2.5, 4.0, 6.0])
def test_exact_force_and_harmonics(ratio):
    mech = slider_crank(ratio)
    phi = np.radians(np.arange(0.0, 360.0, 7.5))
    sol = linkwork.solve(mech, phi)
    m, w, r, lam = 3.0, 300 * 2 * np.pi / 60, 0.1, 1 / ratio
    rec = reciprocating_inertia(sol, m)
    np.testing.assert_allclose(np.cos(rec.angle), np.cos(phi), atol=1e-12)
    s, c = np.sin(phi), np.cos(phi)
    acc = -r * w**2 * (c + (lam * np.cos(2 * phi) + lam**3 * s**4) / (1 - lam**2 * s**2) ** 1.5)
    F0 = m * r * w**2
    np.testing.assert_allclose(rec.exact, -m * acc, rtol=0, atol=1e-12 * F0)
    np.testing.assert_allclose(rec.first, F0 * c, rtol=0, atol=1e-14 * F0)
    np.testing.assert_allclose(rec.second, F0 * lam * np.cos(2 * phi), rtol=0, atol=1e-14 * F0)
    # the error of two harmonics is of third order in λ (the next terms are λ³/4·(cos 2φ + cos 4φ)…)
    err = np.abs(rec.error).max() / F0
    assert 0.1 * lam**3 < err < 0.6 * lam**3


def _zero_of_force(ratio: float) -> float:
    mech = slider_crank(ratio)
    f = lambda a: reciprocating_inertia(linkwork.solve(mech, [a]), 1.0).exact[0]
    return brentq(f, np.radians(45), np.radians(89.9), xtol=1e-14)


@pytest.mark.parametrize("ratio", sorted(TABLE))
def test_crank_angle_of_maximum_piston_velocity(ratio):
    alpha = _zero_of_force(ratio)
    # the seed's cubic: sin⁶α − n²·sin⁴α − n⁴·sin²α + n⁴ = 0 (its root in (0, 1))
    n = float(ratio)
    roots = np.roots([1.0, -n**2, -n**4, n**4])
    x = next(z.real for z in roots if abs(z.imag) < 1e-12 and 0 < z.real < 1)
    assert alpha == pytest.approx(np.arcsin(np.sqrt(x)), abs=1e-9)
    # the printed table, in whole minutes: the digest finds it within about one minute of the
    # exact angle (n = 6 prints 80° 48′ for 80° 46.97′)
    deg, minutes = TABLE[ratio]
    assert np.degrees(alpha) * 60 == pytest.approx(deg * 60 + minutes, abs=1.1)


def test_offset_slider_crank_is_refused():
    sol = linkwork.solve(linkwork.load("library:slider-crank-offset"), [0.3])
    with pytest.raises(ModelError, match="offset"):
        reciprocating_inertia(sol, 1.0)
