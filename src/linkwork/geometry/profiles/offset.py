"""Offset curves (*Äquidistante*, *Parallelkurve*): the pitch curve of a cam for a roller of
radius ρ is the profile's offset by +ρ, and the profile is the pitch curve's offset by −ρ.

o(u) = c(u) + d·n(u) with n = (y′, −x′)/|c′| the unit normal to the right of the direction of
travel, so d > 0 lies outside a counter-clockwise closed profile. Then o′ = (1 + dκ)·c′: the
offset is regular where 1 + dκ > 0, reverses where 1 + dκ < 0, and has a cusp (the roller cuts
the profile: undercut, *Unterschneidung*) where 1 + dκ changes sign.

The derivatives of n to any order come from the Taylor series of c′(u + h): |c′|² is a product
of series, its power −½ follows Miller's recurrence (`taylor.power`), so every derivative of the
offset is exact from the base curve's derivatives.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np

from . import taylor
from .base import BaseProfile, Profile, ProfileError, curvature, derivatives_at


class OffsetProfile(BaseProfile):
    """The offset of `base` by the signed `distance` (positive to the right of the direction of
    travel: outward for a counter-clockwise closed profile). Same parameter, domain and breaks as
    the base; at a break, `side` is passed to the base."""

    def __init__(self, base: Profile, distance: float) -> None:
        if not np.isfinite(distance):
            raise ProfileError(f"an offset distance must be finite, got {distance}")
        self.base = base
        self.distance = float(distance)
        self.closed = bool(base.closed)
        self.domain = tuple(float(x) for x in base.domain)

    @property
    def breaks(self) -> np.ndarray:
        return np.asarray(self.base.breaks, dtype=float)

    @cached_property
    def cusps(self) -> np.ndarray:
        """Parameters where the offset has a cusp (1 + dκ changes sign), see `offset_cusps`."""
        return offset_cusps(self.base, self.distance)

    def _quadrature_edges(self) -> np.ndarray:
        # the speed |1 + dκ|·|c′| has a kink at each cusp: start a piece there
        base = self.base._quadrature_edges() if isinstance(self.base, BaseProfile) else super()._quadrature_edges()
        return np.union1d(base, self.cusps)

    def _eval(self, u: np.ndarray, order: int, side: int) -> np.ndarray:
        d = derivatives_at(self.base, u, order + 1, side)
        t = taylor.from_derivatives(d[1:])  # series of c′(u + h)
        w = taylor.power(taylor.mul(t[..., 0], t[..., 0]) + taylor.mul(t[..., 1], t[..., 1]), -0.5)
        normal = taylor.to_derivatives(np.stack([taylor.mul(t[..., 1], w), taylor.mul(-t[..., 0], w)], -1))
        return d[: order + 1] + self.distance * normal


def offset_cusps(profile: Profile, distance: float, samples: int = 2048) -> np.ndarray:
    """Parameters where the offset of `profile` by `distance` has a cusp: where 1 + d·κ(u) changes
    sign, between samples (refined by bisection to full precision, all intervals at once) or at a
    break (a jump of curvature across −1/d). Sorted; empty for a regular offset. A double root
    (1 + dκ touching zero without changing sign) is not reported; an offset with 1 + dκ < 0
    everywhere (a circle offset inward by more than its radius) has no cusp but runs backwards."""
    a, b = (float(x) for x in profile.domain)
    if not (np.isfinite(a) and np.isfinite(b)):
        # only the straight line has an infinite domain here, and it has no curvature
        return np.empty(0)

    def g(u, side=1):
        return 1.0 + distance * curvature(profile, u, side)

    return sign_changes(g, (a, b), profile.breaks, closed=profile.closed, samples=samples)


def sign_changes(g, domain: tuple[float, float], breaks=(), *, closed: bool = False,
                 samples: int = 2048) -> np.ndarray:
    """Where the function g(u, side) of a profile's parameter changes sign on `domain`: between
    samples (refined by bisection to full precision, all intervals at once), at a break (g on
    the piece ending there, side=−1, and on the piece starting there, side=+1, of opposite
    signs) or exactly at a sample. Sorted; a closed profile's end is its start."""
    a, b = domain
    brk = np.asarray(breaks, dtype=float)
    brk = brk[(brk >= a) & (brk <= b)]
    grid = np.union1d(np.linspace(a, b, samples + 1), brk)
    after, before = g(grid[:-1]), g(grid[1:], -1)  # each interval from its start to its end
    roots = []
    if brk.size:
        roots.append(brk[np.sign(g(brk, -1)) * np.sign(g(brk)) < 0])
    lo, hi = grid[:-1], grid[1:]
    change = np.sign(after) * np.sign(before) < 0
    lo, hi, g_lo = lo[change], hi[change], after[change]
    for _ in range(200):
        mid = (lo + hi) / 2
        gm = g(mid)
        left = np.sign(gm) == np.sign(g_lo)
        lo, g_lo = np.where(left, mid, lo), np.where(left, gm, g_lo)
        hi = np.where(left, hi, mid)
        if np.all((hi - lo) <= 4 * np.spacing(np.maximum(np.abs(lo), np.abs(hi)))):
            break
    roots.append((lo + hi) / 2)
    zero = grid[g(grid) == 0.0]
    out = np.unique(np.concatenate(roots + [zero]))
    if closed:
        out = np.unique(np.where(out >= b, a, out))
    return out
