"""Points (homogeneous, possibly at infinity) and free vectors.

Owns :class:`Point`, :class:`Vector` and :func:`finite_xy`, the guard used by every metric
operation that needs a finite position.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ._base import Batch, batch_shape, core_array, cross2, dot, frozen, norm, pow2_normalise, rot90, where_
from .errors import GeometryError


@dataclass(frozen=True, eq=False)
class Point(Batch):
    """A point of the projective plane: homogeneous ``coords = (x, y, w)``, shape ``(..., 3)``.

    Stored canonically: finite points as ``(x/w, y/w, 1)``; points at infinity as ``(dx, dy, 0)``
    rescaled by an exact power of two (the sign of the direction is not significant). A quotient
    that overflows float range is, honestly, a point at infinity. NaN items mean "undefined"
    (e.g. a missing intersection) and are all-NaN. ``(0, 0, 0)`` and ±inf are rejected.
    """

    coords: np.ndarray

    def __post_init__(self) -> None:
        c = core_array(self.coords, 3, "Point coordinates")
        x, y, w = np.moveaxis(c, -1, 0)
        if ((x == 0) & (y == 0) & (w == 0)).any():
            raise GeometryError("(0, 0, 0) is not a point (a point at infinity needs a non-zero direction)")
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            fin = np.stack([x / w, y / w, np.ones_like(w)], axis=-1)
        at_inf = ~np.isfinite(fin).all(axis=-1)
        inf = pow2_normalise(np.stack([x, y, np.zeros_like(w)], axis=-1), np.maximum(abs(x), abs(y)))
        c = np.where(at_inf[..., None], inf, fin)
        c[np.isnan(c).any(axis=-1)] = np.nan
        object.__setattr__(self, "coords", frozen(c))

    @classmethod
    def at(cls, x: Any, y: Any) -> Point:
        """Finite point(s) at Cartesian ``(x, y)``."""
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        if np.isinf(x).any() or np.isinf(y).any():
            raise GeometryError("Point.at needs finite coordinates; use Point.at_infinity(direction)")
        return cls(np.stack([x, y, np.ones_like(x)], axis=-1))

    @classmethod
    def from_xy(cls, xy: Any) -> Point:
        """Finite point(s) from an array of shape ``(..., 2)``."""
        xy = core_array(xy, 2, "Point.from_xy argument")
        return cls.at(xy[..., 0], xy[..., 1])

    @classmethod
    def at_infinity(cls, direction: Vector | Any) -> Point:
        """The point(s) at infinity in ``direction`` (a :class:`Vector` or ``(..., 2)`` array)."""
        d = direction.xy if isinstance(direction, Vector) else core_array(direction, 2, "direction")
        return cls(np.concatenate([d, np.zeros(d.shape[:-1] + (1,))], axis=-1))

    @property
    def shape(self) -> tuple[int, ...]:
        return self.coords.shape[:-1]

    @property
    def is_finite(self) -> np.ndarray:
        return self.coords[..., 2] == 1  # canonical form; NaN compares False

    @property
    def is_infinite(self) -> np.ndarray:
        return self.coords[..., 2] == 0

    @property
    def xy(self) -> np.ndarray:
        """Cartesian coordinates ``(..., 2)``; NaN for points at infinity."""
        return np.where(self.is_finite[..., None], self.coords[..., :2], np.nan)

    @property
    def direction(self) -> Vector:
        """Unit direction of points at infinity; NaN for finite points."""
        d = self.coords[..., :2]
        with np.errstate(invalid="ignore"):
            return Vector(np.where(self.is_infinite[..., None], d / norm(d)[..., None], np.nan))

    def equals(self, other: Point, tol: float = 1e-9) -> np.ndarray:
        """Equality up to homogeneous scale.

        Finite points: distance <= ``tol * max(1, |p|, |q|)``; points at infinity: parallel
        directions (either sense). Finite and infinite points are never equal; NaN never equals.
        """
        batch_shape(self.shape, other.shape, what="Point.equals")
        p, q = self.coords[..., :2], other.coords[..., :2]
        scale = np.maximum(1.0, np.maximum(norm(p), norm(q)))
        finite = self.is_finite & other.is_finite & (norm(p - q) <= tol * scale)
        parallel = abs(cross2(p, q)) <= tol * norm(p) * norm(q)
        return finite | (self.is_infinite & other.is_infinite & parallel)

    def distance(self, other: Point) -> np.ndarray:
        """Euclidean distance between finite points."""
        return norm(finite_xy(self, "distance") - finite_xy(other, "distance"))

    def __sub__(self, other: Point | Vector) -> Any:
        """``p - q`` is the :class:`Vector` from q to p; ``p - v`` translates p."""
        if isinstance(other, Vector):
            return Point.from_xy(finite_xy(self, "translation") - other.xy)
        return Vector(finite_xy(self, "point difference") - finite_xy(other, "point difference"))

    def __add__(self, other: Vector) -> Point:
        if not isinstance(other, Vector):
            return NotImplemented
        return Point.from_xy(finite_xy(self, "translation") + other.xy)


def finite_xy(p: Point, what: str) -> np.ndarray:
    """``p.xy``, raising :class:`GeometryError` if any item is a point at infinity."""
    bad = p.is_infinite
    if bad.any():
        raise GeometryError(f"{what}: point at infinity{where_(bad)}; this needs finite points")
    return p.xy


@dataclass(frozen=True, eq=False)
class Vector(Batch):
    """A free vector ``xy`` of shape ``(..., 2)`` (velocities, directions, normals)."""

    xy: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "xy", frozen(core_array(self.xy, 2, "Vector components")))

    @classmethod
    def of(cls, x: Any, y: Any) -> Vector:
        return cls(np.stack(np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float)), axis=-1))

    @classmethod
    def from_angle(cls, angle: Any, length: Any = 1.0) -> Vector:
        """Vector of ``length`` at ``angle`` (radians, counter-clockwise from +x)."""
        angle, length = np.asarray(angle, float), np.asarray(length, float)
        return cls.of(length * np.cos(angle), length * np.sin(angle))

    @property
    def shape(self) -> tuple[int, ...]:
        return self.xy.shape[:-1]

    @property
    def norm(self) -> np.ndarray:
        return norm(self.xy)

    @property
    def angle(self) -> np.ndarray:
        """Polar angle in (-pi, pi]."""
        return np.arctan2(self.xy[..., 1], self.xy[..., 0])

    def unit(self) -> Vector:
        n = self.norm
        if (n == 0).any():
            raise GeometryError(f"the zero vector has no direction{where_(n == 0)}")
        return Vector(self.xy / n[..., None])

    def rotated90(self, sense: int = 1) -> Vector:
        """Quarter turn: ``sense=+1`` counter-clockwise ``(-y, x)``, ``-1`` clockwise.

        This is Rosenauer's rotated ("gedrehte") velocity used in velocity plans.
        """
        if sense not in (1, -1):
            raise GeometryError(f"sense must be +1 or -1, got {sense!r}")
        return Vector(sense * rot90(self.xy))

    def rotated(self, angle: Any) -> Vector:
        c, s = np.cos(angle), np.sin(angle)
        x, y = self.xy[..., 0], self.xy[..., 1]
        return Vector.of(c * x - s * y, s * x + c * y)

    def dot(self, other: Vector) -> np.ndarray:
        return dot(self.xy, other.xy)

    def cross(self, other: Vector) -> np.ndarray:
        """Scalar 2-D cross product ``self.x * other.y - self.y * other.x``."""
        return cross2(self.xy, other.xy)

    def __add__(self, other: Vector) -> Vector:
        return Vector(self.xy + other.xy) if isinstance(other, Vector) else NotImplemented

    def __sub__(self, other: Vector) -> Vector:
        return Vector(self.xy - other.xy) if isinstance(other, Vector) else NotImplemented

    def __neg__(self) -> Vector:
        return Vector(-self.xy)

    def __mul__(self, k: Any) -> Vector:
        return Vector(self.xy * np.asarray(k, float)[..., None])

    __rmul__ = __mul__

    def __truediv__(self, k: Any) -> Vector:
        return Vector(self.xy / np.asarray(k, float)[..., None])
