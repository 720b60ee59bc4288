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
the jump of acceleration is reported, never smoothed.

`Profile` is the protocol every profile implements; `CircleProfile` is the simplest one (an
eccentric disc, a roller seen as a profile, a pitch circle).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from .errors import GeometryError


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


def curvature(profile: Profile, u: np.ndarray) -> np.ndarray:
    """Signed curvature κ = (c′ × c″)/|c′|³ at u (positive where the profile turns left, i.e.
    counter-clockwise with increasing u)."""
    d = profile.derivatives(np.asarray(u, dtype=float), 2)
    c1, c2 = d[1], d[2]
    speed = np.hypot(c1[..., 0], c1[..., 1])
    return (c1[..., 0] * c2[..., 1] - c1[..., 1] * c2[..., 0]) / speed**3


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

    def derivatives(self, u: np.ndarray, order: int) -> np.ndarray:
        u = np.asarray(u, dtype=float)
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
        return self.radius * (np.asarray(u, dtype=float) - self.domain[0])

    def nearest(self, p: np.ndarray) -> np.ndarray:
        p = np.asarray(p, dtype=float)
        return np.arctan2(p[..., 1] - self.center[1], p[..., 0] - self.center[0])
