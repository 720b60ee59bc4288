"""Truncated Taylor series against series known in closed form: the binomial series of (1 + x)^p,
products of polynomials, and e^{i(a₀ + a₁h)} = e^{ia₀} Σ (i a₁ h)^k/k!."""

from __future__ import annotations

from math import factorial

import numpy as np

from linkwork.geometry.profiles import taylor


def test_derivatives_round_trip_and_exp():
    # e^{2u} at u = 0.3: derivatives 2^k e^{0.6}, coefficients 2^k e^{0.6}/k!
    d = np.array([2.0**k * np.exp(0.6) for k in range(7)])
    a = taylor.from_derivatives(d)
    np.testing.assert_allclose(a, [2.0**k * np.exp(0.6) / factorial(k) for k in range(7)], rtol=1e-15)
    np.testing.assert_allclose(taylor.to_derivatives(a), d, rtol=1e-15)


def test_product_truncated_at_the_shorter_order():
    a = np.array([1.0, 2.0, 3.0])            # 1 + 2h + 3h²
    b = np.array([4.0, 5.0, 6.0, 7.0])       # 4 + 5h + 6h² + 7h³
    # (1 + 2h + 3h²)(4 + 5h + 6h²…) = 4 + 13h + 28h² + …
    np.testing.assert_allclose(taylor.mul(a, b), [4.0, 13.0, 28.0])
    batch = taylor.mul(np.stack([a, 2 * a], -1), np.stack([b[:3], b[:3]], -1))
    np.testing.assert_allclose(batch, [[4, 8], [13, 26], [28, 56]])


def binom(p, k):
    """The generalised binomial coefficient p(p − 1)…(p − k + 1)/k!."""
    return float(np.prod([p - j for j in range(k)])) / factorial(k)


def test_power_is_the_binomial_series():
    c, x1 = 2.5, 0.7  # (c + x1 h)^p = c^p Σ binom(p, k) (x1 h / c)^k
    a = np.zeros(8)
    a[0], a[1] = c, x1
    for p in (-0.5, 1.5, -3.0, 2.0):
        expect = [c**p * binom(p, k) * (x1 / c) ** k for k in range(8)]
        np.testing.assert_allclose(taylor.power(a, p), expect, rtol=1e-13, atol=1e-300)
    # a general series: the square of the square root gives back the series
    s = np.array([4.0, -1.0, 0.5, 2.0, -0.3])
    r = taylor.power(s, 0.5)
    np.testing.assert_allclose(taylor.mul(r, r), s, rtol=1e-14, atol=1e-14)


def test_expi_of_a_linear_angle():
    a = np.zeros(7)
    a[0], a[1] = 0.4, 1.3
    expect = [np.exp(0.4j) * (1.3j) ** k / factorial(k) for k in range(7)]
    np.testing.assert_allclose(taylor.expi(a), expect, rtol=1e-14)
    # a quadratic angle: e^{i(θ + h²)} = e^{iθ}(1 + i h² − h⁴/2 − i h⁶/6 …)
    q = np.zeros(7)
    q[0], q[2] = 0.4, 1.0
    expect = np.exp(0.4j) * np.array([1, 0, 1j, 0, -0.5, 0, -1j / 6])
    np.testing.assert_allclose(taylor.expi(q), expect, atol=1e-15)
