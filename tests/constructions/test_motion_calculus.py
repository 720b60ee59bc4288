"""Pöschl's graphical calculus (ch. II §7, §10, §11): derived scales against the book's numbers,
and the constructions against the exact derivative and integrals of harmonic motion."""

import numpy as np
import pytest

from linkwork.constructions.motion_calculus import (derivative_scale, differentiate, integral_scale,
                                                    integrate, integrate_reciprocal, reciprocal_scale)
from linkwork.errors import InputError

PI = np.pi


def test_scales_of_example_1():
    # Pöschl §11, Example 1: a = 10 cm, ω = π/s, l_x = 2.5 cm/cm, l_b = 5π² cm/s² per cm
    assert integral_scale(1.0, 2.5, 5 * PI ** 2) == pytest.approx(12.5 * PI ** 2)  # l_{v²/2}
    assert integral_scale(2.0, 2.5, 0.1 / PI) == pytest.approx(0.5 / PI)  # l_t, H₂ = 2 cm
    assert reciprocal_scale(2.5, 2.5, 2 * PI) == pytest.approx(0.5 / PI)  # l_t, H′₂ = 2.5 cm


def test_scales_of_example_2():
    # Example 2: H₁ = 3 cm, l_x = 0.2 m/cm, l_b = 10 m/s² per cm → l_{v²/2} = 6; l_t = 0.04 s/cm
    assert integral_scale(3.0, 0.2, 10.0) == pytest.approx(6.0)
    assert integral_scale(4.0, 0.2, 0.05) == pytest.approx(0.04)
    assert reciprocal_scale(5.0, 0.2, 1.0) == pytest.approx(0.04)


def test_derivative_scale_is_eq_3():
    # l_v = l_x/(H₁ l_t); then l_b = l_v/(H₂ l_t) = l_x/(H₁H₂l_t²) (eq. 4)
    l_v = derivative_scale(2.5, 0.1, 2.0)
    assert l_v == pytest.approx(12.5)
    assert derivative_scale(l_v, 0.1, 4.0) == pytest.approx(2.5 / (2.0 * 4.0 * 0.1 ** 2))


def test_chords_of_harmonic_motion():
    # x = a sin ωt: the chord over [t, t+h] has slope aω cos(ω t_mid)·sin(ωh/2)/(ωh/2), exactly
    a, w = 10.0, PI
    t = np.linspace(0.0, 2.0, 41)
    d = differentiate(t, a * np.sin(w * t), l_t=0.1, l_x=2.5, H=2.0)
    h = t[1] - t[0]
    tm = (t[1:] + t[:-1]) / 2
    want = a * w * np.cos(w * tm) * np.sin(w * h / 2) / (w * h / 2)
    np.testing.assert_allclose(d.x, tm, rtol=1e-12)
    np.testing.assert_allclose(d.y, want, rtol=1e-10, atol=1e-10)
    # and drawn: V = H·tan α in cm
    np.testing.assert_allclose(d.Y, want / derivative_scale(2.5, 0.1, 2.0), rtol=1e-10, atol=1e-10)


def test_energy_integral_of_harmonic_motion():
    # b(x) = −ω²x from the left turning point: ∫b dx = v²/2 = ω²(a² − x²)/2, exact at the strip
    # boundaries (mean ordinates of a straight line are exact)
    a, w = 10.0, PI
    x = np.linspace(-a, a, 401)
    strips = np.linspace(-a, a, 9)
    z = integrate(x, -w * w * x, strips, l_x=2.5, l_y=5 * PI ** 2, H=1.0)
    want = w * w * (a * a - strips ** 2) / 2
    np.testing.assert_allclose(z.y, want, rtol=1e-12, atol=1e-9 * a * a * w * w)
    assert z.l_y == pytest.approx(12.5 * PI ** 2)


def test_time_from_the_velocity_line():
    # t = ∫dx/v with v = ω√(a² − x²): ωt = arcsin(x/a) − arcsin(x₀/a), strips away from the turning points
    a, w = 10.0, PI
    x = np.linspace(-9.0, 9.0, 3601)
    v = w * np.sqrt(a * a - x * x)
    strips = np.linspace(-9.0, 9.0, 13)
    t = integrate_reciprocal(x, v, strips, l_x=2.5, l_y=2 * PI, H=2.5, samples=32)
    want = (np.arcsin(strips / a) - np.arcsin(strips[0] / a)) / w
    np.testing.assert_allclose(t.y, want, rtol=2e-4, atol=1e-5)
    assert t.l_y == pytest.approx(0.5 / PI)


def test_bad_input_is_refused():
    x = np.linspace(-1, 1, 11)
    with pytest.raises(InputError, match="turning point"):
        integrate_reciprocal(x, x, [-1, 1], l_x=1, l_y=1, H=1)
    with pytest.raises(InputError, match="must be positive"):
        integrate(x, x, [-1, 1], l_x=1, l_y=1, H=0)
    with pytest.raises(InputError, match="increase"):
        differentiate(x[::-1], x, l_t=1, l_x=1, H=1)
    with pytest.raises(InputError, match="leave the given line"):
        integrate(x, x, [-2, 1], l_x=1, l_y=1, H=1)
