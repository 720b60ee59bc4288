"""Pöschl's graphical calculus of point motion (ch. II, §7 and §10; seed 002, digest 002a):
graphical differentiation with a pole (*Polabstand* H) and graphical integration by strips with
mean ordinates (*Mittelordinaten*), including the integral of the reciprocal (time from a v–x
line), with the drawing scales of the books; the subnormal construction of the acceleration on
a v–s line; and of ch. III the plans (hodographs) of a point's velocity and acceleration, whose
tangents give the next derivative (§13), and the jerk along the path for the jerk diagram.

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
    #: integration by strips: each strip's mean ordinate of the given line, as drawn (cm)
    means: np.ndarray | None = None

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
    return Diagram(b / l_x, np.concatenate([[0.0], np.cumsum(dZ)]), l_x, l_z, Ym)


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
    Z, means = [0.0], []
    for lo, hi in zip(b[:-1], b[1:]):
        # samples at the middles of equal sub-strips, the harmonic mean of their ordinates
        xs = lo + (np.arange(samples) + 0.5) * (hi - lo) / samples
        ys = np.interp(xs, x, y)
        if np.any(ys == 0) or np.any(np.sign(ys) != np.sign(ys[0])):
            raise InputError(f"the ordinate vanishes between x = {lo:g} and {hi:g} (a turning point): "
                             "∫dx/y is infinite there; start the strips past it")
        Ym = 1.0 / np.mean(1.0 / ys) / l_y
        means.append(Ym)
        Z.append(Z[-1] + H * ((hi - lo) / l_x) / Ym)
    return Diagram(b / l_x, np.array(Z), l_x, l_z, np.array(means))


# ---------------------------------------------------------------------------- ch. III: plans
@dataclass(frozen=True)
class Plan:
    """A hodograph (Pöschl §13, *v-Plan* from the pole P, *b-Plan* from the pole Q): the tips of
    a point's velocity (or acceleration) vectors over the motion, all drawn from one pole at the
    scale ``scale`` (units of nature per cm). ``W`` are the tips as drawn (cm from the pole), ``t``
    the times. The tangent of the drawn curve at a tip is the direction of the next derivative
    (acceleration, or jerk for the b-plan): the derivative of a vector is the velocity of its tip
    along the plan."""

    W: np.ndarray
    t: np.ndarray
    scale: float

    @property
    def vectors(self) -> np.ndarray:
        """The vectors read back in nature (N, 2)."""
        return self.W * self.scale

    def tangent(self) -> np.ndarray:
        """The unit tangent of the drawn plan at every tip (:func:`curve_tangent`), pointing the
        way the tip moves; (N, 2), NaN at the two ends."""
        return curve_tangent(self.W)

    def rate(self) -> np.ndarray:
        """The velocity of the tip along the plan, read in nature (the derivative of the
        vectors, units per s): the slope at every inner tip of the parabola in t through the tip
        and its two neighbours; (N, 2), NaN at the ends."""
        t, V = self.t, self.vectors
        h0, h1 = (t[1:-1] - t[:-2])[:, None], (t[2:] - t[1:-1])[:, None]
        out = np.full(V.shape, np.nan)
        out[1:-1] = (-h1 / (h0 * (h0 + h1)) * V[:-2] + (h1 - h0) / (h0 * h1) * V[1:-1]
                     + h0 / (h1 * (h0 + h1)) * V[2:])
        return out


def curve_tangent(W: np.ndarray) -> np.ndarray:
    """The unit tangent of a drawn curve through the points ``W`` (N, 2) at every inner point, as
    the draughtsman draws it: perpendicular to the radius of the circle through the point and its
    two neighbours (the chord's direction where the three are in line), pointing along the
    curve's order; (N, 2), NaN at the two ends and where neighbours coincide."""
    W = np.asarray(W, float)
    a, b, c = W[:-2], W[1:-1], W[2:]
    ab, cb = a - b, c - b
    d = 2.0 * (ab[:, 0] * cb[:, 1] - ab[:, 1] * cb[:, 0])
    chord = c - a
    with np.errstate(divide="ignore", invalid="ignore"):
        na, nc = np.sum(ab * ab, 1), np.sum(cb * cb, 1)
        # the circumcentre relative to b; the tangent is its radius turned a right angle
        ux = (cb[:, 1] * na - ab[:, 1] * nc) / d
        uy = (ab[:, 0] * nc - cb[:, 0] * na) / d
        tan = np.stack([-uy, ux], 1)
        straight = ~np.isfinite(ux) | (np.abs(d) <= 1e-12 * np.sqrt(na * nc))
        tan[straight] = chord[straight]
        tan *= np.sign(np.sum(tan * chord, 1))[:, None]
        tan /= np.linalg.norm(tan, axis=1)[:, None]
    out = np.full(W.shape, np.nan)
    out[1:-1] = tan
    return out


def plan(t: np.ndarray, vectors: np.ndarray, *, scale: float) -> Plan:
    """The hodograph of ``vectors`` (N, 2) at the times ``t`` drawn at ``scale`` (units per cm).
    Samples that are not finite (unreachable positions) are refused: draw a plan per branch."""
    t = np.asarray(t, float)
    V = np.asarray(vectors, float)
    _positive(scale=scale)
    if V.ndim != 2 or V.shape[1] != 2 or t.shape != (len(V),) or len(t) < 3:
        raise InputError("a plan needs three vectors (N, 2) at least, one time for each")
    if not (np.all(np.isfinite(V)) and np.all(np.isfinite(t))):
        raise InputError("the plan's vectors or times are not all finite (an unreachable position?)")
    if np.any(np.diff(t) <= 0):
        raise InputError("the times of a plan must increase")
    return Plan(V / scale, t, float(scale))


def plan_scale(vectors: np.ndarray, size: float = 5.0) -> float:
    """A round scale (1, 2, 2.5 or 5 × 10ᵏ per cm) at which the longest vector is at most
    ``size`` cm, as the books choose them."""
    from .scales import nice_ceil
    return nice_ceil(float(np.nanmax(np.linalg.norm(np.asarray(vectors, float), axis=-1))) / size)


@dataclass(frozen=True)
class Subnormal:
    """The subnormal construction on a v–s line (Rosenauer §61 II; Pöschl §9, case II: b =
    v dv/ds): at the point A = (S, V) of the drawn line the tangent is drawn, then the normal;
    it cuts the s axis at N, and the subnormal FN from the foot F = (S, 0) of A's ordinate is
    V dV/dS, so the acceleration along the path is a = l_a·FN with l_a = l_v²/l_s. All points in
    cm of drawing."""

    A: np.ndarray
    F: np.ndarray
    N: np.ndarray
    tangent: np.ndarray
    l_s: float
    l_v: float

    @property
    def l_a(self) -> float:
        return self.l_v ** 2 / self.l_s

    @property
    def acceleration(self) -> float:
        """a = l_a·FN, signed: positive where N lies ahead of F (speed growing along s)."""
        return float(self.l_a * (self.N[0] - self.F[0]))


def subnormal(s: np.ndarray, v: np.ndarray, k: int, *, l_s: float, l_v: float) -> Subnormal:
    """The subnormal construction at the ``k``-th point of the v–s line (``s`` increasing)."""
    s, v = _line(s, v, "s", "v")
    _positive(l_s=l_s, l_v=l_v)
    if not 0 < k < len(s) - 1:
        raise InputError(f"the subnormal is drawn at an inner point of the v–s line, not at point {k}")
    W = np.stack([s / l_s, v / l_v], 1)
    tan = curve_tangent(W[k - 1:k + 2])[1]
    A = W[k]
    if abs(tan[0]) < 1e-12:
        raise InputError("the v–s line's tangent is vertical there (a turning point): no subnormal")
    N = np.array([A[0] + A[1] * tan[1] / tan[0], 0.0])
    return Subnormal(A, np.array([A[0], 0.0]), N, tan, float(l_s), float(l_v))


def path_jerk(velocity: np.ndarray, acceleration: np.ndarray, jerk: np.ndarray,
              direction: np.ndarray) -> np.ndarray:
    """The third derivative of the path coordinate, d³s/dt³ (the jerk diagram's ordinate): with
    the unit tangent e (``direction``, the positive sense of s) turning at ψ̇ = (v × a)/v²,
    d(a·e)/dt = j·e + a·ė, ė = ψ̇ e⊥. On a straight path it is the jerk along the line; on a
    circle at constant speed it is zero although the jerk vector is not."""
    v2 = np.sum(velocity * velocity, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        psi = (velocity[..., 0] * acceleration[..., 1] - velocity[..., 1] * acceleration[..., 0]) / v2
    psi = np.where(v2 > 0, psi, 0.0)
    e_perp = np.stack([-direction[..., 1], direction[..., 0]], axis=-1)
    return np.sum(jerk * direction, axis=-1) + psi * np.sum(acceleration * e_perp, axis=-1)


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
