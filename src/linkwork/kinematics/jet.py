"""Truncated Taylor series in time ("jets") over NumPy arrays.

A jet holds c[k] = f⁽ᵏ⁾(t)/k! for k = 0..K, for a whole batch of samples (c has shape
(K+1, *batch)). Evaluating a constraint with jets gives its time derivatives exactly, to any
order, without writing them by hand: this is how the generic group solver gets the
acceleration (and jerk) right-hand sides of the constraint equations.
"""

from __future__ import annotations

from math import factorial

import numpy as np


class Jet:
    __slots__ = ("c",)

    def __init__(self, c: np.ndarray) -> None:
        self.c = c

    @property
    def order(self) -> int:
        return self.c.shape[0] - 1

    @classmethod
    def from_derivatives(cls, d: np.ndarray) -> "Jet":
        """From stacked derivatives f, f', f'', … (first axis)."""
        scale = np.array([1.0 / factorial(k) for k in range(d.shape[0])])
        return cls(d * scale.reshape((-1,) + (1,) * (d.ndim - 1)))

    def derivative(self, k: int) -> np.ndarray:
        return self.c[k] * factorial(k)

    @classmethod
    def constant(cls, value, order: int, like: np.ndarray | None = None) -> "Jet":
        v = np.asarray(value, dtype=float)
        if like is not None:
            v = np.broadcast_to(v, like.shape)
        c = np.zeros((order + 1,) + v.shape)
        c[0] = v
        return cls(c)

    def _lift(self, other) -> "Jet":
        if isinstance(other, Jet):
            return other
        v = np.asarray(other, dtype=float)
        c = np.zeros((self.order + 1,) + (1,) * (self.c.ndim - 1 - v.ndim) + v.shape)
        c[0] = v
        return Jet(c)

    def __add__(self, other):
        o = self._lift(other)
        return Jet(self.c + o.c)

    __radd__ = __add__

    def __sub__(self, other):
        o = self._lift(other)
        return Jet(self.c - o.c)

    def __rsub__(self, other):
        return self._lift(other) - self

    def __neg__(self):
        return Jet(-self.c)

    def __mul__(self, other):
        if not isinstance(other, Jet):
            return Jet(self.c * np.asarray(other, dtype=float))
        K = self.order
        # the wider of the two dtypes: jets in extended precision stay extended (`precision`)
        out = np.empty(np.broadcast_shapes(self.c.shape, other.c.shape),
                       dtype=np.result_type(self.c, other.c))
        for k in range(K + 1):  # Cauchy product, K is 1..3
            out[k] = sum(self.c[i] * other.c[k - i] for i in range(k + 1))
        return Jet(out)

    __rmul__ = __mul__

    def cos_sin(self) -> tuple["Jet", "Jet"]:
        """(cos f, sin f) by the recurrence of their coupled ODE."""
        K = self.order
        c = np.empty_like(self.c)
        s = np.empty_like(self.c)
        c[0] = np.cos(self.c[0])
        s[0] = np.sin(self.c[0])
        for k in range(1, K + 1):
            # (cos f)' = -sin f · f',  (sin f)' = cos f · f'
            acc_c = sum(j * self.c[j] * s[k - j] for j in range(1, k + 1))
            acc_s = sum(j * self.c[j] * c[k - j] for j in range(1, k + 1))
            c[k] = -acc_c / k
            s[k] = acc_s / k
        return Jet(c), Jet(s)

    def reciprocal(self) -> "Jet":
        """1/f, by the recurrence of f·g = 1 (f must not vanish)."""
        K = self.order
        g = np.empty_like(self.c)
        g[0] = 1.0 / self.c[0]
        for k in range(1, K + 1):
            g[k] = -sum(self.c[i] * g[k - i] for i in range(1, k + 1)) * g[0]
        return Jet(g)

    def sqrt(self) -> "Jet":
        """√f, by the recurrence of g·g = f (f must be positive)."""
        K = self.order
        g = np.empty_like(self.c)
        g[0] = np.sqrt(self.c[0])
        for k in range(1, K + 1):
            g[k] = (self.c[k] - sum(g[i] * g[k - i] for i in range(1, k))) / (2 * g[0])
        return Jet(g)

    def compose(self, derivatives: np.ndarray) -> "Jet":
        """F(f) for a function F whose derivatives at f's value are given: derivatives[m] =
        F⁽ᵐ⁾(f₀) for m = 0 … order, with any trailing shape (e.g. (…, 2) for a plane curve).
        Taylor's formula in δ = f − f₀, whose powers start at δᵐ (so m ≤ order suffices)."""
        K = self.order
        extra = derivatives.ndim - self.c.ndim  # trailing axes of F beyond the batch
        delta = Jet(self.c.copy())
        delta.c[0] = 0.0
        lift = (slice(None),) + (...,) + (None,) * extra
        out = np.zeros(np.broadcast_shapes(self.c.shape + (1,) * extra,
                                           (K + 1,) + derivatives.shape[1:]))
        out[0] = derivatives[0]
        power = Jet(np.ones_like(self.c[:1]).repeat(K + 1, axis=0))
        power.c[1:] = 0.0
        for m in range(1, K + 1):
            power = power * delta
            out += power.c[lift] * (derivatives[m] / factorial(m))
        return Jet(out)
