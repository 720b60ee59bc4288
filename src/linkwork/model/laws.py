"""Motion laws of drivers: the input value and its time derivatives as functions of time.

A law gives, for an array of times, the input value (radians or length unit) and its first three
derivatives (speed, acceleration, jerk), so that ω̇ ≠ 0 and higher-order curvature theory are
possible. Laws are immutable values.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


class MotionLaw:
    """Base of the driver laws. `derivatives(t)` returns shape (4, N): value, 1st, 2nd, 3rd."""

    #: whether the driver turns at a constant rate (input values can be sampled directly)
    constant: bool = False

    def derivatives(self, t: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def duration(self) -> float | None:
        return None


@dataclass(frozen=True)
class ConstantSpeed(MotionLaw):
    """Uniform motion: input = start + speed·t (the default law, Rosenauer's ω = const)."""

    speed: float = 1.0
    start: float = 0.0
    constant: bool = field(default=True, init=False)

    def derivatives(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        out = np.zeros((5,) + t.shape)
        out[0] = self.start + self.speed * t
        out[1] = self.speed
        return out


@dataclass(frozen=True)
class PolynomialLaw(MotionLaw):
    """input(t) = Σ c_k t^k over [0, duration]."""

    coefficients: tuple[float, ...]
    span: float = 1.0

    def derivatives(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        poly = np.polynomial.Polynomial(self.coefficients)
        return np.stack([poly.deriv(k)(t) if k else poly(t) for k in range(5)])

    @property
    def duration(self) -> float:
        return self.span


@dataclass(frozen=True)
class TabulatedLaw(MotionLaw):
    """A table of (time, value), interpolated by a C²-continuous cubic spline."""

    times: tuple[float, ...]
    values: tuple[float, ...]

    def derivatives(self, t: np.ndarray) -> np.ndarray:
        from scipy.interpolate import CubicSpline  # here: SciPy's import costs ~1 s of start-up

        spline = CubicSpline(np.asarray(self.times), np.asarray(self.values))
        t = np.asarray(t, dtype=float)
        return np.stack([spline(t, k) for k in range(5)])

    @property
    def duration(self) -> float:
        return self.times[-1] - self.times[0]
