"""Closed-form profiles: the ellipse, the involute of a circle, spirals, the straight line, and
curves given by code (r(φ) with its derivatives, or c(u) with its derivatives).

Each derivative is written out in closed form for any order, so nothing is differenced.
"""

from __future__ import annotations

from math import comb
from typing import Callable

import numpy as np

from .base import BaseProfile, ProfileError


def _finite_point(value, what: str) -> np.ndarray:
    v = np.asarray(value, dtype=float)
    if v.shape != (2,) or not np.all(np.isfinite(v)):
        raise ProfileError(f"{what} must be a finite [x, y], got {np.asarray(value).tolist()}")
    return v


def _positive(value, what: str) -> float:
    v = float(value)
    if not (np.isfinite(v) and v > 0):
        raise ProfileError(f"{what} must be positive and finite, got {value}")
    return v


def _interval(value, what: str) -> tuple[float, float]:
    lo, hi = (float(x) for x in value)
    if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo):
        raise ProfileError(f"{what} must be two finite increasing values, got {list(value)}")
    return lo, hi


def _quarter_turns(theta: np.ndarray, order: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """(cos, sin) of θ + kπ/2 for k = 0 … order: the k-th derivatives of the unit vector e^{iθ}
    with respect to θ (one cos and one sin, then quarter turns by swapping and signs)."""
    c, s = np.cos(theta), np.sin(theta)
    turns = ((c, s), (-s, c), (-c, -s), (s, -c))
    return [turns[k % 4] for k in range(order + 1)]


class EllipseProfile(BaseProfile):
    """The ellipse about `center` with semi-axes (a, b), the a-axis turned by `angle` (radians)
    from the x-axis, counter-clockwise; u = the eccentric anomaly: c = C + R(angle)(a cos u, b sin u)."""

    def __init__(self, center, semi_axes, angle: float = 0.0) -> None:
        self.center = _finite_point(center, "an ellipse's centre")
        a, b = semi_axes
        self.semi_axes = (_positive(a, "an ellipse's semi-axis a"), _positive(b, "an ellipse's semi-axis b"))
        if not np.isfinite(angle):
            raise ProfileError(f"an ellipse's angle must be finite, got {angle}")
        self.angle = float(angle)
        self.closed = True
        self.domain = (0.0, 2 * np.pi)

    def _eval(self, u: np.ndarray, order: int, side: int) -> np.ndarray:
        a, b = self.semi_axes
        ca, sa = np.cos(self.angle), np.sin(self.angle)
        out = np.empty((order + 1,) + u.shape + (2,))
        for k, (ex, ey) in enumerate(_quarter_turns(u, order)):
            x, y = a * ex, b * ey
            out[k, ..., 0] = ca * x - sa * y
            out[k, ..., 1] = sa * x + ca * y
        out[0] += self.center
        return out


class InvoluteProfile(BaseProfile):
    """The involute of the base circle (`center`, `base_radius`) that leaves it at the angle
    `start_angle` (radians), unwinding counter-clockwise (`sense` +1) or clockwise (-1); u = the
    roll angle t ≥ 0 (*Wälzwinkel*), domain `roll`: c = C + r e^{iα}(1 − iσt), α = start_angle + σt.
    Its arc length from t = 0 is r t²/2 and its radius of curvature r t (zero at t = 0, the cusp)."""

    def __init__(self, center, base_radius: float, start_angle: float = 0.0,
                 roll: tuple[float, float] = (0.0, 2 * np.pi), sense: int = 1) -> None:
        self.center = _finite_point(center, "an involute's base-circle centre")
        self.base_radius = _positive(base_radius, "an involute's base radius")
        if not np.isfinite(start_angle):
            raise ProfileError(f"an involute's start angle must be finite, got {start_angle}")
        self.start_angle = float(start_angle)
        self.domain = _interval(roll, "an involute's roll angles")
        if self.domain[0] < 0:
            raise ProfileError(f"an involute's roll angles start at 0 or later, got {list(roll)}")
        if sense not in (1, -1):
            raise ProfileError(f"an involute's sense is +1 or -1, got {sense!r}")
        self.sense = int(sense)
        self.closed = False

    def _eval(self, u: np.ndarray, order: int, side: int) -> np.ndarray:
        s, r = self.sense, self.base_radius
        e = np.exp(1j * (self.start_angle + s * u))
        out = np.empty((order + 1,) + u.shape + (2,))
        for k in range(order + 1):
            # d^k/dt^k [e^{iα}(1 − iσt)] = (iσ)^k e^{iα}(1 − k − iσt)
            z = r * (1j * s) ** k * e * (1 - k - 1j * s * u)
            out[k, ..., 0], out[k, ..., 1] = z.real, z.imag
        out[0] += self.center
        return out

    def arc_length(self, u: np.ndarray) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        inside = (u >= self.domain[0]) & (u <= self.domain[1])
        return np.where(inside, self.base_radius * (u**2 - self.domain[0] ** 2) / 2, np.nan)


class PolarProfile(BaseProfile):
    """c(φ) = C + r(φ)(cos φ, sin φ) from a radius function with its derivatives:
    `radius(phi, order)` returns r, r′, …, r⁽ᵒʳᵈᵉʳ⁾ stacked, shape (order + 1, *phi.shape) (the cam
    synthesis gives r(φ) of a motion law so). u = φ; a closed profile needs a periodic r.
    c⁽ⁿ⁾ = Σ_j C(n, j) r⁽ʲ⁾ e^{i(φ + (n − j)π/2)} (Leibniz). `breaks` are passed through; a radius
    function that jumps there may take a keyword `side` (set `sided=True`)."""

    def __init__(self, radius: Callable[..., np.ndarray], center=(0.0, 0.0),
                 domain: tuple[float, float] = (0.0, 2 * np.pi), closed: bool = True,
                 breaks=(), sided: bool = False) -> None:
        if not callable(radius):
            raise ProfileError("a polar profile needs a callable radius(phi, order)")
        self.radius = radius
        self.center = _finite_point(center, "a polar profile's centre")
        self.domain = _interval(domain, "a polar profile's domain")
        self.closed = bool(closed)
        self._breaks = np.sort(np.asarray(breaks, dtype=float))
        self._sided = sided

    @property
    def breaks(self) -> np.ndarray:
        return self._breaks

    def _eval(self, u: np.ndarray, order: int, side: int) -> np.ndarray:
        r = np.asarray(self.radius(u, order, side=side) if self._sided else self.radius(u, order), dtype=float)
        if r.shape != (order + 1,) + u.shape:
            raise ProfileError(f"radius(phi, {order}) must return shape {(order + 1,) + u.shape}, got {r.shape}")
        out = np.empty((order + 1,) + u.shape + (2,))
        c, s = np.cos(u), np.sin(u)
        for n in range(order + 1):
            # c⁽ⁿ⁾ = e^{iφ}·Σ_j C(n, j) r⁽ʲ⁾ i^{n−j}: the sum's real and imaginary parts, then
            # one turn by φ
            parts = [None, None]  # (real, imaginary)
            for j in range(n + 1):
                w = comb(n, j)
                term = r[j] if w == 1 else w * r[j]
                k = (n - j) % 4
                cur = parts[k % 2]
                if k < 2:
                    parts[k % 2] = term if cur is None else cur + term
                else:
                    parts[k % 2] = -term if cur is None else cur - term
            re, im = parts
            if im is None:
                out[n, ..., 0] = re * c
                out[n, ..., 1] = re * s
            elif re is None:
                out[n, ..., 0] = -im * s
                out[n, ..., 1] = im * c
            else:
                out[n, ..., 0] = re * c - im * s
                out[n, ..., 1] = re * s + im * c
        out[0] += self.center
        return out


class ArchimedeanSpiral(PolarProfile):
    """r = start_radius + pitch·(φ − φ₀)/2π about `center` for φ in `angles` = (φ₀, φ₁) (radians):
    the radius grows by `pitch` per turn (negative: shrinks); r must stay positive."""

    def __init__(self, center, start_radius: float, pitch: float, angles: tuple[float, float]) -> None:
        phi0, phi1 = _interval(angles, "a spiral's angles")
        r0, rate = float(start_radius), float(pitch) / (2 * np.pi)
        if not (np.isfinite(r0) and np.isfinite(rate)):
            raise ProfileError("an Archimedean spiral needs a finite start radius and pitch")
        if min(r0, r0 + rate * (phi1 - phi0)) <= 0:
            raise ProfileError(f"an Archimedean spiral's radius must stay positive over its angles "
                               f"(it runs from {r0} to {r0 + rate * (phi1 - phi0)})")
        self.start_radius, self.pitch = r0, float(pitch)

        def radius(phi, order):
            out = np.zeros((order + 1,) + phi.shape)
            out[0] = r0 + rate * (phi - phi0)
            if order >= 1:
                out[1] = rate
            return out

        super().__init__(radius, center, (phi0, phi1), closed=False)


class LogarithmicSpiral(PolarProfile):
    """r = start_radius·e^{b(φ − φ₀)}, b = tan(pitch_angle) (the angle between the tangent and the
    circle about the centre, constant along the curve), for φ in `angles` (radians)."""

    def __init__(self, center, start_radius: float, pitch_angle: float, angles: tuple[float, float]) -> None:
        phi0, phi1 = _interval(angles, "a spiral's angles")
        r0 = _positive(start_radius, "a logarithmic spiral's start radius")
        if not (np.isfinite(pitch_angle) and abs(pitch_angle) < np.pi / 2):
            raise ProfileError(f"a logarithmic spiral's pitch angle must lie strictly between -90° and 90°, "
                               f"got {np.degrees(pitch_angle)}°")
        b = float(np.tan(pitch_angle))
        self.start_radius, self.pitch_angle = r0, float(pitch_angle)

        def radius(phi, order):
            e = r0 * np.exp(b * (phi - phi0))
            return np.stack([b**j * e for j in range(order + 1)])

        super().__init__(radius, center, (phi0, phi1), closed=False)


class LineProfile(BaseProfile):
    """The whole straight line through `point` along `direction` (a flat face, a straight track);
    u = signed distance from `point` along the unit direction, domain (−∞, ∞). Having no start,
    its `arc_length(u)` is measured from `point`: it is u."""

    def __init__(self, point, direction) -> None:
        self.point = _finite_point(point, "a line's point")
        d = _finite_point(direction, "a line's direction")
        n = float(np.hypot(*d))
        if n == 0:
            raise ProfileError("a line's direction is the zero vector")
        self.direction = d / n
        self.closed = False
        self.domain = (-np.inf, np.inf)

    def _eval(self, u: np.ndarray, order: int, side: int) -> np.ndarray:
        out = np.zeros((order + 1,) + u.shape + (2,))
        out[0] = self.point + u[..., None] * self.direction
        if order >= 1:
            out[1] = self.direction
        return out

    @property
    def length(self) -> float:
        return np.inf

    def arc_length(self, u: np.ndarray) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        return np.where(np.isfinite(u), u, np.nan)

    def nearest(self, p: np.ndarray) -> np.ndarray:
        p = np.asarray(p, dtype=float)
        if p.shape[-1:] != (2,):
            raise ProfileError(f"nearest needs points of shape (..., 2), got {p.shape}")
        return np.sum((p - self.point) * self.direction, axis=-1)


class ParametricProfile(BaseProfile):
    """A profile given by code: `fn(u, order)` returns c, c′, …, c⁽ᵒʳᵈᵉʳ⁾ stacked, shape
    (order + 1, *u.shape, 2), for u inside `domain` (wrapped there first when `closed`). The cam
    synthesis builds its pitch curves and profiles so. `breaks` are passed through; a function
    that jumps there takes a keyword `side` (set `sided=True`). `pieces`: how many equal parts
    of the domain the arc-length table and the nearest-point search start from (raise it for a
    curve that winds much)."""

    def __init__(self, fn: Callable[..., np.ndarray], domain: tuple[float, float], closed: bool = False,
                 breaks=(), sided: bool = False, pieces: int = 64) -> None:
        if not callable(fn):
            raise ProfileError("a parametric profile needs a callable fn(u, order)")
        self.fn = fn
        self.domain = _interval(domain, "a parametric profile's domain")
        self.closed = bool(closed)
        self._breaks = np.sort(np.asarray(breaks, dtype=float))
        self._sided = sided
        self._pieces = int(pieces)

    @property
    def breaks(self) -> np.ndarray:
        return self._breaks

    def _eval(self, u: np.ndarray, order: int, side: int) -> np.ndarray:
        out = np.array(self.fn(u, order, side=side) if self._sided else self.fn(u, order), dtype=float)
        if out.shape != (order + 1,) + u.shape + (2,):
            raise ProfileError(f"fn(u, {order}) must return shape {(order + 1,) + u.shape + (2,)}, got {out.shape}")
        return out
