"""Profiles: the curves that higher pairs keep in contact (cam discs, flanks, tracks, centrodes).

A profile (German *Profil*, *Kurvenscheibe* for a cam disc; Latvian *profils*) is a regular plane
curve c(u), u in `domain`, given in the design coordinates of the link that carries it (which are
its link coordinates, as for points). The kinematics needs its derivatives with respect to the
parameter to any order, for many parameters at once: `derivatives(u, order)` returns the stacked
c(u), c′(u), …, c⁽ᵒʳᵈᵉʳ⁾(u), shape (order + 1, *u.shape, 2). The parameter need not be the arc
length; `arc_length(u)` gives the arc length from the start of the domain, which rolling pairs
need. A closed profile is periodic in u with period `domain[1] - domain[0]`; an open one is
defined on its domain only (samples outside it are NaN).

`breaks` lists the parameters where the curvature jumps (the joins of a profile made of lines
and circular arcs, as the books draw cams): there the kinematics is exact on either side, and
the jump of acceleration is reported, never smoothed. Every profile of this package takes a
keyword `side` in `derivatives`: at a break, `side=+1` (the default) evaluates the piece that
starts there, `side=-1` the piece that ends there; elsewhere both agree.

`Profile` is the protocol every profile implements; `CircleProfile` is the simplest one (an
eccentric disc, a roller seen as a profile, a pitch circle). `BaseProfile` holds what the other
profiles share: periodic wrapping, arc length by Gauss–Legendre quadrature, the nearest point.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from operator import index as _as_index
from typing import Protocol, runtime_checkable

import numpy as np

from ..errors import GeometryError


class ProfileError(GeometryError):
    """A profile that cannot be built from its data; `index` is the segment or point the
    message names (None when the error concerns the whole profile)."""

    def __init__(self, message: str, index: int | None = None) -> None:
        super().__init__(message)
        self.index = index


@runtime_checkable
class Profile(Protocol):
    """A regular plane curve with derivatives of any order, batch-first."""

    closed: bool
    domain: tuple[float, float]

    @property
    def breaks(self) -> np.ndarray:
        """Parameters where the curvature jumps (sorted; empty for a smooth profile)."""

    def derivatives(self, u: np.ndarray, order: int) -> np.ndarray:
        """(order + 1, *u.shape, 2): c(u), c′(u), …; NaN outside the domain of an open profile."""

    def arc_length(self, u: np.ndarray) -> np.ndarray:
        """Arc length from domain[0] to u (for a closed profile, u taken modulo the period and
        whole turns added)."""

    def nearest(self, p: np.ndarray) -> np.ndarray:
        """Parameter of the point of the profile nearest to each p (..., 2): a starting value for
        the contact of a follower element."""


def check_order(order: int) -> int:
    """The derivative order as a non-negative int (GeometryError otherwise)."""
    if isinstance(order, bool):
        raise GeometryError(f"derivative order must be a non-negative integer, got {order!r}")
    try:
        k = _as_index(order)
    except TypeError:
        raise GeometryError(f"derivative order must be a non-negative integer, got {order!r}") from None
    if k < 0:
        raise GeometryError(f"derivative order must be a non-negative integer, got {order!r}")
    return k


def check_side(side: int) -> int:
    if side not in (1, -1) or isinstance(side, bool):
        raise GeometryError(f"side must be +1 (the piece starting at u) or -1 (the piece ending at u), got {side!r}")
    return int(side)


def derivatives_at(profile: Profile, u: np.ndarray, order: int, side: int = 1) -> np.ndarray:
    """`profile.derivatives(u, order)` on the given side of a break (see the module docstring);
    a profile outside this package is asked for `side` only when it is -1."""
    if check_side(side) == 1:
        return profile.derivatives(u, order)
    return profile.derivatives(u, order, side=side)


def curvature(profile: Profile, u: np.ndarray, side: int = 1) -> np.ndarray:
    """Signed curvature κ = (c′ × c″)/|c′|³ at u (positive where the profile turns left, i.e.
    counter-clockwise with increasing u); at a break, on the given `side`."""
    d = derivatives_at(profile, np.asarray(u, dtype=float), 2, side)
    c1, c2 = d[1], d[2]
    speed = np.hypot(c1[..., 0], c1[..., 1])
    return (c1[..., 0] * c2[..., 1] - c1[..., 1] * c2[..., 0]) / speed**3


def curvature_jumps(profile: Profile) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(u, κ before, κ after) at every break of the profile: the curvature on the piece that
    ends there and on the piece that starts there (Krümmungssprung; the follower's acceleration
    jumps with it)."""
    u = np.asarray(profile.breaks, dtype=float)
    return u, curvature(profile, u, side=-1), curvature(profile, u, side=1)


@dataclass(frozen=True)
class CircleProfile:
    """The circle about `center` with `radius`, counter-clockwise, u = angle from the x-axis
    (radians): an eccentric disc, a roller, a pitch circle."""

    center: tuple[float, float]
    radius: float
    closed: bool = True
    domain: tuple[float, float] = (0.0, 2 * np.pi)

    def __post_init__(self) -> None:
        if not (np.isfinite(self.radius) and self.radius > 0):
            raise GeometryError(f"a circle profile needs a positive finite radius, got {self.radius}")
        if not np.all(np.isfinite(self.center)):
            raise GeometryError("a circle profile needs a finite centre")

    @property
    def breaks(self) -> np.ndarray:
        return np.empty(0)

    def derivatives(self, u: np.ndarray, order: int, side: int = 1) -> np.ndarray:
        order, _ = check_order(order), check_side(side)
        u = np.asarray(u, dtype=float)
        with np.errstate(invalid="ignore"):  # ±∞ gives NaN, as for every closed profile
            c, s = np.cos(u), np.sin(u)
        out = np.empty((order + 1,) + u.shape + (2,))
        # d^k/du^k (cos u, sin u) cycles through (c, s), (−s, c), (−c, −s), (s, −c)
        cycle = ((c, s), (-s, c), (-c, -s), (s, -c))
        for k in range(order + 1):
            x, y = cycle[k % 4]
            out[k, ..., 0] = self.radius * x
            out[k, ..., 1] = self.radius * y
        out[0, ..., 0] += self.center[0]
        out[0, ..., 1] += self.center[1]
        return out

    def arc_length(self, u: np.ndarray) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        return np.where(np.isfinite(u), self.radius * (u - self.domain[0]), np.nan)

    def nearest(self, p: np.ndarray) -> np.ndarray:
        p = np.asarray(p, dtype=float)
        if p.shape[-1:] != (2,):
            raise GeometryError(f"nearest needs points of shape (..., 2), got {p.shape}")
        u = np.arctan2(p[..., 1] - self.center[1], p[..., 0] - self.center[0])
        return np.where(np.all(np.isfinite(p), axis=-1), u, np.nan)


# Gauss–Legendre rule of the arc-length quadrature: exact for polynomials of degree 47, so on a
# piece where the speed is smooth its error is far below 1e-13 of the piece's length.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(24)


class BaseProfile:
    """What the profiles of this package share. A subclass sets `closed` and `domain` and
    implements `_eval(u, order, side)` for parameters u inside the domain (already wrapped into
    [domain[0], domain[1]) for a closed profile); it may override `breaks`, `_pieces` (how many
    equal parts of the domain the arc-length table and the nearest-point search start from) and
    `_quadrature_edges()`."""

    closed: bool
    domain: tuple[float, float]
    _pieces: int = 64

    @property
    def breaks(self) -> np.ndarray:
        return np.empty(0)

    @property
    def period(self) -> float:
        """domain[1] - domain[0] (the period of a closed profile)."""
        return self.domain[1] - self.domain[0]

    def _eval(self, u: np.ndarray, order: int, side: int) -> np.ndarray:  # pragma: no cover
        raise NotImplementedError

    def _wrap(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(u inside the domain, whole turns taken off, mask of samples inside the domain)."""
        a, b = self.domain
        if self.closed:
            with np.errstate(invalid="ignore"):  # ±∞ wraps to NaN, then marked outside
                turns = np.floor((u - a) / self.period)
                r = u - turns * self.period
            over, under = r >= b, r < a  # rounding at the seam
            r = np.where(over, r - self.period, np.where(under, r + self.period, r))
            turns = turns + over - under
            inside = np.isfinite(u)
        else:
            turns = np.zeros_like(u)
            inside = (u >= a) & (u <= b) & np.isfinite(u)  # ±∞ is no parameter, even of a line
            r = u
        return np.where(inside, r, a if np.isfinite(a) else 0.0), turns, inside

    def derivatives(self, u: np.ndarray, order: int, side: int = 1) -> np.ndarray:
        """(order + 1, *u.shape, 2): c(u), c′(u), …; NaN outside the domain of an open profile;
        at a break, the piece that starts there (side=+1) or ends there (side=-1)."""
        order, side = check_order(order), check_side(side)
        u = np.asarray(u, dtype=float)
        r, _, inside = self._wrap(u)
        out = self._eval(r, order, side)
        if not inside.all():
            out[:, ~inside] = np.nan
        return out

    # -- arc length ----------------------------------------------------------------------------

    def _quadrature_edges(self) -> np.ndarray:
        """Parameters splitting the domain into pieces on which the speed |c′| is smooth."""
        a, b = self.domain
        inner = np.asarray(self.breaks, dtype=float)
        return np.union1d(np.linspace(a, b, self._pieces + 1), inner[(inner > a) & (inner < b)])

    def _gauss(self, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        """∫ |c′| du from lo to hi by the Gauss–Legendre rule (lo, hi inside one smooth piece)."""
        half, mid = (hi - lo) / 2, (hi + lo) / 2
        x = mid + half * _GL_X.reshape((-1,) + (1,) * np.ndim(mid))
        c1 = self.derivatives(x, 1)[1]
        return half * np.tensordot(_GL_W, np.hypot(c1[..., 0], c1[..., 1]), axes=1)

    @cached_property
    def _arc_table(self) -> tuple[np.ndarray, np.ndarray]:
        edges = self._quadrature_edges()
        return edges, np.concatenate([[0.0], np.cumsum(self._gauss(edges[:-1], edges[1:]))])

    @property
    def length(self) -> float:
        """Length of the whole profile (one turn of a closed one)."""
        return float(self._arc_table[1][-1])

    def arc_length(self, u: np.ndarray) -> np.ndarray:
        """Arc length from domain[0] to u (a closed profile adds whole turns; an open one gives NaN
        outside its domain): a cumulative table over the smooth pieces plus a Gauss–Legendre
        quadrature from the piece's start to each u."""
        u = np.asarray(u, dtype=float)
        edges, cum = self._arc_table
        r, turns, inside = self._wrap(u)
        i = np.clip(np.searchsorted(edges, r, side="right") - 1, 0, len(edges) - 2)
        s = cum[i] + self._gauss(edges[i], r) + turns * cum[-1]
        return np.where(inside, s, np.nan)

    # -- nearest point -------------------------------------------------------------------------

    @cached_property
    def _coarse(self) -> tuple[np.ndarray, np.ndarray, float]:
        """Parameters and points of the coarse search, and the largest parameter step."""
        edges = self._quadrature_edges()
        fine = np.linspace(0.0, 1.0, 9)[:-1]
        grid = (edges[:-1, None] + np.diff(edges)[:, None] * fine).ravel()
        if not self.closed:
            grid = np.append(grid, edges[-1])
        return grid, self.derivatives(grid, 0)[0], float(np.max(np.diff(edges))) / 8

    def nearest(self, p: np.ndarray) -> np.ndarray:
        """Parameter of the point of the profile nearest to each p (..., 2): the nearest of a
        coarse sample, refined by Newton's method on (c(u) − p)·c′(u) = 0 (steps no longer than the
        sample spacing, kept inside an open profile's domain); NaN for non-finite p."""
        p = np.asarray(p, dtype=float)
        if p.shape[-1:] != (2,):
            raise GeometryError(f"nearest needs points of shape (..., 2), got {p.shape}")
        q = p.reshape(-1, 2)
        grid, pts, step = self._coarse
        u0 = np.empty(len(q))
        chunk = max(1, 2_000_000 // len(grid))  # bounds the (points × samples) distance table
        for lo in range(0, len(q), chunk):
            c = q[lo:lo + chunk]
            d2 = (c[:, None, 0] - pts[None, :, 0]) ** 2 + (c[:, None, 1] - pts[None, :, 1]) ** 2
            u0[lo:lo + chunk] = grid[np.argmin(np.where(np.isnan(d2), np.inf, d2), axis=1)]
        u = _newton_nearest(self, u0, q, step)
        u = np.where(np.all(np.isfinite(q), axis=1), u, np.nan)
        return u.reshape(p.shape[:-1])


def _distance2(profile: BaseProfile, u: np.ndarray, q: np.ndarray) -> np.ndarray:
    r = profile.derivatives(u, 0)[0] - q
    return r[:, 0] ** 2 + r[:, 1] ** 2


def _newton_nearest(profile: BaseProfile, u0: np.ndarray, q: np.ndarray, step: float) -> np.ndarray:
    """Newton's method on f(u) = (c(u) − p)·c′(u), f′ = |c′|² + (c − p)·c″, from u0; the result is
    kept only where it is at least as near as the start."""
    a, b = profile.domain
    u = u0.copy()
    tol = 1e-15 * max(1.0, abs(a) if np.isfinite(a) else 1.0, abs(b) if np.isfinite(b) else 1.0)
    for _ in range(50):
        d = profile.derivatives(u, 2)
        r = d[0] - q
        f = np.sum(r * d[1], axis=-1)
        fp = np.sum(d[1] * d[1], axis=-1) + np.sum(r * d[2], axis=-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            du = np.where(fp > 0, -f / fp, 0.0)
        du = np.nan_to_num(np.clip(du, -step, step))
        new = u + du if profile.closed else np.clip(u + du, a, b)
        done = np.max(np.abs(new - u), initial=0.0) <= tol
        u = new
        if done:
            break
    better = _distance2(profile, u, q) <= _distance2(profile, u0, q)
    u = np.where(better, u, u0)
    return profile._wrap(u)[0] if profile.closed else u
