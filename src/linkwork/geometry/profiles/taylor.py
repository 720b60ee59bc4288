"""Truncated Taylor series in one variable, batch-first: the arithmetic behind exact derivatives
of composed curves (the unit normal of an offset curve).

A series is an array whose axis 0 holds the coefficients a_k = f⁽ᵏ⁾(u)/k!, k = 0…K, of
f(u + h) = Σ a_k h^k; the other axes are samples. Products and powers are truncated at the
shorter operand's order, so every coefficient they return is exact.
"""

from __future__ import annotations

from math import factorial

import numpy as np


def from_derivatives(d: np.ndarray) -> np.ndarray:
    """Taylor coefficients f⁽ᵏ⁾/k! from stacked derivatives f, f′, f″, … (axis 0)."""
    scale = np.array([1.0 / factorial(k) for k in range(d.shape[0])])
    return d * scale.reshape((-1,) + (1,) * (d.ndim - 1))


def to_derivatives(a: np.ndarray) -> np.ndarray:
    """Stacked derivatives f⁽ᵏ⁾ = k!·a_k from Taylor coefficients (axis 0)."""
    scale = np.array([float(factorial(k)) for k in range(a.shape[0])])
    return a * scale.reshape((-1,) + (1,) * (a.ndim - 1))


def mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The product series (Cauchy product), truncated at the shorter order."""
    n = min(a.shape[0], b.shape[0])
    out = np.zeros((n,) + np.broadcast_shapes(a.shape[1:], b.shape[1:]), dtype=np.result_type(a, b, float))
    for k in range(n):
        for j in range(k + 1):
            out[k] += a[j] * b[k - j]
    return out


def power(a: np.ndarray, p: float) -> np.ndarray:
    """The series of a^p for a real exponent p (a₀ > 0 wherever p is not a whole number).

    From f = a^p, a·f′ = p·a′·f (J. C. P. Miller's recurrence):
    f_k = 1/(k a₀) Σ_{j=1..k} ((p + 1) j − k) a_j f_{k−j}.
    """
    out = np.zeros_like(a, dtype=float)
    out[0] = a[0] ** p
    for k in range(1, a.shape[0]):
        acc = np.zeros_like(out[0])
        for j in range(1, k + 1):
            acc += ((p + 1) * j - k) * a[j] * out[k - j]
        out[k] = acc / (k * a[0])
    return out


def expi(a: np.ndarray) -> np.ndarray:
    """The series of e^{i·a} (complex) for a real series a: from f′ = i·a′·f,
    f_k = (i/k) Σ_{j=1..k} j a_j f_{k−j} (the unit vector turned by a curve's angle)."""
    out = np.zeros(a.shape, dtype=complex)
    out[0] = np.exp(1j * a[0])
    for k in range(1, a.shape[0]):
        acc = np.zeros_like(out[0])
        for j in range(1, k + 1):
            acc += j * a[j] * out[k - j]
        out[k] = 1j * acc / k
    return out
