"""Straight lines in homogeneous coordinates, including the line at infinity.

Owns :class:`Line` and the low-level :func:`meet` (cross product of two lines) shared by
:func:`linkwork.geometry.intersect` and the circle code.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ._base import Batch, batch_shape, core_array, cross2, dot, frozen, norm, pow2_normalise, where_
from .errors import GeometryError
from .point import Point, Vector, finite_xy


@dataclass(frozen=True, eq=False)
class Line(Batch):
    """The line(s) ``a x + b y + c w = 0``: ``coords = (a, b, c)`` of shape ``(..., 3)``.

    Oriented: ``direction = (b, -a)``, ``normal = (a, b)`` points to its left, and the signed
    distance is positive on the left. ``a = b = 0`` is only the line at infinity (``c != 0``).
    Stored rescaled by an exact power of two so that ``max(|a|, |b|)`` lies in [0.5, 1).
    """

    coords: np.ndarray

    def __post_init__(self) -> None:
        c = core_array(self.coords, 3, "Line coefficients")
        a, b, k = np.moveaxis(c, -1, 0)
        at_inf = (a == 0) & (b == 0)
        if (at_inf & (k == 0)).any():
            raise GeometryError("(0, 0, 0) is not a line: a = b = 0 is only allowed for the line at infinity (c != 0)")
        c = pow2_normalise(c, np.where(at_inf, abs(k), np.maximum(abs(a), abs(b))))
        c[np.isnan(c).any(axis=-1)] = np.nan
        object.__setattr__(self, "coords", frozen(c))

    @classmethod
    def from_abc(cls, a: Any, b: Any, c: Any) -> Line:
        return cls(np.stack(np.broadcast_arrays(*(np.asarray(v, float) for v in (a, b, c))), axis=-1))

    @classmethod
    def through(cls, p: Point, q: Point) -> Line:
        """The line from ``p`` to ``q``; either may be at infinity (a direction), both: the line at infinity."""
        batch_shape(p.shape, q.shape, what="Line.through")
        c = np.cross(p.coords, q.coords)
        same = (c == 0).all(axis=-1)
        if same.any():
            raise GeometryError(f"Line.through: the two points coincide{where_(same)}")
        return cls(c)

    @classmethod
    def perpendicular(cls, *, through: Point, to: Line) -> Line:
        """The line through ``through`` perpendicular to ``to``, directed along ``to.normal``."""
        return cls.through(through, Point.at_infinity(to._normal_xy("Line.perpendicular")))

    @classmethod
    def parallel(cls, *, through: Point, to: Line) -> Line:
        """The line through ``through`` parallel to ``to``, with the same orientation."""
        return cls.through(through, to.point_at_infinity)

    @classmethod
    def at_infinity(cls) -> Line:
        return cls(np.array([0.0, 0.0, 1.0]))

    @property
    def shape(self) -> tuple[int, ...]:
        return self.coords.shape[:-1]

    @property
    def is_at_infinity(self) -> bool | np.ndarray:
        return (self.coords[..., 0] == 0) & (self.coords[..., 1] == 0)

    def _normal_xy(self, what: str) -> np.ndarray:
        if self.is_at_infinity.any():
            raise GeometryError(f"{what}: the line at infinity{where_(self.is_at_infinity)} has no normal")
        return self.coords[..., :2]

    @property
    def normal(self) -> Vector:
        """Unit normal ``(a, b) / |(a, b)|`` (left of the direction); NaN for the line at infinity."""
        n = self.coords[..., :2]
        with np.errstate(invalid="ignore"):
            return Vector(n / norm(n)[..., None])

    @property
    def direction(self) -> Vector:
        """Unit direction ``(b, -a) / |(a, b)|``; NaN for the line at infinity."""
        return self.normal.rotated90(-1)

    @property
    def point_at_infinity(self) -> Point:
        return Point.at_infinity(self._normal_xy("Line.point_at_infinity") @ np.array([[0.0, -1.0], [1.0, 0.0]]))

    def signed_distance(self, p: Point) -> np.ndarray:
        """Distance of finite ``p`` from the line, positive on the left (normal side)."""
        n = self.coords[..., :2]
        with np.errstate(invalid="ignore", divide="ignore"):
            return (dot(n, finite_xy(p, "Line.signed_distance")) + self.coords[..., 2]) / norm(n)

    def project(self, p: Point) -> Point:
        """Foot of the perpendicular from finite ``p``: the point of the line nearest to ``p``."""
        return Point.from_xy(finite_xy(p, "Line.project") - self.signed_distance(p)[..., None] * self.normal.xy)

    def contains(self, p: Point, tol: float = 1e-9) -> np.ndarray:
        """Incidence: finite p within ``tol * max(1, |p|)``; p at infinity with direction along the line."""
        batch_shape(self.shape, p.shape, what="Line.contains")
        inc = abs(dot(self.coords, p.coords))
        with np.errstate(invalid="ignore", divide="ignore"):
            near = inc / norm(self.coords[..., :2]) <= tol * np.maximum(1.0, norm(p.coords[..., :2]))
        along = inc <= tol * norm(self.coords) * norm(p.coords[..., :2])
        return np.where(p.is_finite, near, p.is_infinite & along)

    def equals(self, other: Line, tol: float = 1e-9) -> np.ndarray:
        """Same point set (orientation ignored): parallel normals and equal offsets within tolerance."""
        batch_shape(self.shape, other.shape, what="Line.equals")
        n1, n2 = self.coords[..., :2], other.coords[..., :2]
        l1, l2 = norm(n1), norm(n2)
        with np.errstate(invalid="ignore", divide="ignore"):
            s = np.sign(dot(n1, n2))
            o1, o2 = self.coords[..., 2] / l1, s * other.coords[..., 2] / l2
            same = (abs(cross2(n1, n2)) <= tol * l1 * l2) & (abs(o1 - o2) <= tol * np.maximum(1, np.maximum(abs(o1), abs(o2))))
        return same | (self.is_at_infinity & other.is_at_infinity)


def meet(l1: Line, l2: Line, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Homogeneous intersection ``l1 x l2`` and the mask of coincident pairs.

    The lines are already power-of-two normalised, so ``|a1 b2 - a2 b1| / (|n1| |n2|)`` is the sine
    of their angle; below ``tol`` the pair counts as parallel and ``w`` is set to exactly 0.
    """
    batch_shape(l1.shape, l2.shape, what="intersect")
    x = np.cross(l1.coords, l2.coords)
    parallel = abs(x[..., 2]) <= tol * norm(l1.coords[..., :2]) * norm(l2.coords[..., :2])
    x[..., 2] = np.where(parallel, 0.0, x[..., 2])
    coincident = parallel & (norm(x[..., :2]) <= tol * norm(l1.coords) * norm(l2.coords))
    return x, coincident
