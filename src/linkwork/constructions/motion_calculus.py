"""Pöschl's graphical calculus of point motion (ch. II, §7 and §10; seed 002, digest 002a):
graphical differentiation with a pole (*Polabstand* H) and graphical integration by strips with
mean ordinates (*Mittelordinaten*), including the integral of the reciprocal (time from a v–x
line), with the drawing scales of the books.

Scales follow Pöschl's convention: a scale l_x is "l_x units of nature per cm of drawing", so a
quantity x is drawn as the length X = x / l_x, and every construction's derived scale comes from
similar triangles: l_v = l_x / (H₁ l_t) (eq. 3), l_z = H l_x l_y (eq. 24), the reciprocal
integral l_z₁ = l_x / (H′ l_y) (eq. 28). Drawing lengths are in the unit of H (cm in the book).

The constructions work on the drawing lengths, as the draughtsman does, and return them with
the values read back at the derived scale; each is checked in the tests against the exact
derivative or integral of a motion in closed form (harmonic motion, Pöschl's Example 1).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError


def derivative_scale(l_x: float, l_t: float, H: float) -> float:
    """l_v = l_x / (H l_t): the scale of the derivative drawn with pole distance H (eq. 3, 4)."""
    _positive(H=H, l_x=l_x, l_t=l_t)
    return l_x / (H * l_t)


def integral_scale(H: float, l_x: float, l_y: float) -> float:
    """l_z = H l_x l_y: the scale of the integral curve drawn with pole distance H (eq. 24)."""
    _positive(H=H, l_x=l_x, l_y=l_y)
    return H * l_x * l_y


def reciprocal_scale(H: float, l_x: float, l_y: float) -> float:
    """l_z₁ = l_x / (H′ l_y): the scale of ∫dx/y drawn with the perpendicular ray (eq. 28)."""
    _positive(H=H, l_x=l_x, l_y=l_y)
    return l_x / (H * l_y)


@dataclass(frozen=True)
class Diagram:
    """A constructed line of a motion diagram: abscissae and ordinates as drawn (``X``, ``Y``,
    drawing lengths) and read back in nature (``x``, ``y``) at the scales ``l_x``, ``l_y``."""

    X: np.ndarray
    Y: np.ndarray
    l_x: float
    l_y: float

    @property
    def x(self) -> np.ndarray:
        return self.X * self.l_x

    @property
    def y(self) -> np.ndarray:
        return self.Y * self.l_y


def differentiate(t: np.ndarray, x: np.ndarray, *, l_t: float, l_x: float, H: float) -> Diagram:
    """Graphical differentiation of an x–t line given by its points (chord method): through the
    pole at distance H left of the origin the parallel to each chord cuts the ordinate axis at
    V = H ΔX/ΔT, drawn at the chord's middle. Returns the v–t line at l_v = l_x/(H l_t)."""
    t, x = _line(t, x, "t", "x")
    l_v = derivative_scale(l_x, l_t, H)
    T, X = t / l_t, x / l_x
    V = H * np.diff(X) / np.diff(T)
    return Diagram((T[1:] + T[:-1]) / 2, V, l_t, l_v)


def integrate(x: np.ndarray, y: np.ndarray, strips: np.ndarray, *, l_x: float, l_y: float,
              H: float) -> Diagram:
    """Graphical integration by strips with mean ordinates (§10a): in each strip the mean ordinate
    Y_m (strip area / width, from the given line's points) is projected to the ordinate axis, the
    ray to the pole at distance H is drawn, and the integral line's chord parallel to it,
    ΔZ = Y_m ΔX / H (eq. 22). Returns the chord polygon at the strip boundaries, at l_z = H l_x l_y;
    ``x``, ``y``: the given line's points (finely), ``strips``: the strip boundaries."""
    x, y = _line(x, y, "x", "y")
    b = _strips(x, strips)
    l_z = integral_scale(H, l_x, l_y)
    area = np.array([_area(x, y, lo, hi) for lo, hi in zip(b[:-1], b[1:])])  # nature units
    Ym = area / np.diff(b) / l_y
    dZ = Ym * (np.diff(b) / l_x) / H
    return Diagram(b / l_x, np.concatenate([[0.0], np.cumsum(dZ)]), l_x, l_z)


def integrate_reciprocal(x: np.ndarray, y: np.ndarray, strips: np.ndarray, *, l_x: float,
                         l_y: float, H: float, samples: int = 16) -> Diagram:
    """∫dx/y by strips (§10c): the mean ordinate of a strip is the harmonic mean of ``samples``
    ordinates in it (Pöschl's footnote), the pole at H′ right of the origin and the perpendicular
    to its ray give ΔZ₁ = H′ ΔX / Y_m (eq. 26). Time from a v–x line: t = ∫dx/v. Returns the line
    at l_z₁ = l_x/(H′ l_y). The ordinates must not vanish in a strip (a turning point, where
    1/v is infinite): that is refused."""
    x, y = _line(x, y, "x", "y")
    b = _strips(x, strips)
    l_z = reciprocal_scale(H, l_x, l_y)
    Z = [0.0]
    for lo, hi in zip(b[:-1], b[1:]):
        # samples at the middles of equal sub-strips, the harmonic mean of their ordinates
        xs = lo + (np.arange(samples) + 0.5) * (hi - lo) / samples
        ys = np.interp(xs, x, y)
        if np.any(ys == 0) or np.any(np.sign(ys) != np.sign(ys[0])):
            raise InputError(f"the ordinate vanishes between x = {lo:g} and {hi:g} (a turning point): "
                             "∫dx/y is infinite there; start the strips past it")
        Ym = 1.0 / np.mean(1.0 / ys) / l_y
        Z.append(Z[-1] + H * ((hi - lo) / l_x) / Ym)
    return Diagram(b / l_x, np.array(Z), l_x, l_z)


def _area(x: np.ndarray, y: np.ndarray, lo: float, hi: float) -> float:
    """Area under the polygon through (x, y) between lo and hi (trapezoids, ends interpolated)."""
    inner = (x > lo) & (x < hi)
    xs = np.concatenate([[lo], x[inner], [hi]])
    ys = np.concatenate([[np.interp(lo, x, y)], y[inner], [np.interp(hi, x, y)]])
    return float(np.sum((ys[1:] + ys[:-1]) * np.diff(xs)) / 2)


def _line(a, b, na: str, nb: str) -> tuple[np.ndarray, np.ndarray]:
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.ndim != 1 or a.shape != b.shape or len(a) < 2:
        raise InputError(f"a line of the motion diagram needs {na} and {nb} of equal length (two points at least)")
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        raise InputError(f"the {na}–{nb} line has points that are not finite")
    if np.any(np.diff(a) <= 0):
        raise InputError(f"the abscissae {na} of the {na}–{nb} line must increase")
    return a, b


def _strips(x: np.ndarray, strips) -> np.ndarray:
    b = np.asarray(strips, float)
    if b.ndim != 1 or len(b) < 2 or np.any(np.diff(b) <= 0):
        raise InputError("the strip boundaries must be at least two increasing abscissae")
    if b[0] < x[0] or b[-1] > x[-1]:
        raise InputError(f"the strips ({b[0]:g} … {b[-1]:g}) leave the given line ({x[0]:g} … {x[-1]:g})")
    return b


def _positive(**values: float) -> None:
    for name, v in values.items():
        if not (np.isfinite(v) and v > 0):
            raise InputError(f"the drawing scale or pole distance {name} must be positive, got {v!r}")
