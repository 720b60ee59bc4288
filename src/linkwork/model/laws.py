"""Motion laws of drivers: the input value and its time derivatives as functions of time.

A law gives, for an array of times, the input value (radians or length unit) and its first three
derivatives (speed, acceleration, jerk), so that ω̇ ≠ 0 and higher-order curvature theory are
possible. Laws are immutable values.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

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

    def time_of(self, values: np.ndarray) -> np.ndarray:
        """The time in [0, duration] at which the law takes each input value, NaN where it takes
        it at no time or (a law that goes back) at more than one; a law that stands still takes
        its value at every time: NaN too (`still` says so). Found on a table of the law over its
        span and polished by Newton's method, to rounding."""
        values = np.asarray(values, dtype=float)
        T = self.duration
        if not T:
            return np.full(values.shape, np.nan)
        grid = np.linspace(0.0, T, TIME_TABLE)
        table = self.derivatives(grid)[0]
        step = np.diff(table)
        if not (np.all(step > 0) or np.all(step < 0)):
            return np.full(values.shape, np.nan)
        order = slice(None) if step[0] > 0 else slice(None, None, -1)
        lo, hi = table[order][0], table[order][-1]
        tol = 1e-12 * max(abs(lo), abs(hi), hi - lo)
        t = np.interp(values, table[order], grid[order])
        for _ in range(4):
            d = self.derivatives(t)
            with np.errstate(divide="ignore", invalid="ignore"):
                t = np.clip(t - np.where(d[1] != 0, (d[0] - values) / d[1], 0.0), 0.0, T)
        inside = (values >= lo - tol) & (values <= hi + tol)
        return np.where(inside, t, np.nan)

    @cached_property
    def uniform_speed(self) -> float | None:
        """The law's speed if it is the same at every time of its span (a linear law, or one
        of one value: speed 0, a reversing arm set once), else None: at an input value its
        rates are then known without the time. (Once per law: every solve by input values
        asks, a drag's frames among them.)"""
        T = self.duration
        if not T:
            return None
        rates = self.derivatives(np.linspace(0.0, T, TIME_TABLE))[1:]
        v = rates[0]
        if np.all(rates[1:] == 0.0) and np.all(np.abs(v - v[0]) <= 1e-12 * np.abs(v[0])):
            return float(v[0])
        return None


#: the table a law is inverted on (`MotionLaw.time_of`): Newton's method polishes from it
TIME_TABLE = 1025


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
