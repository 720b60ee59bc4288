"""Generalised circles (a straight line is a circle of infinite radius) and circular arcs.

Owns :class:`Circle` and :class:`Arc`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ._base import Batch, batch_shape, cross2, dot, frozen, norm, rot90, where_
from .errors import GeometryError
from .line import Line
from .point import Point, Vector, finite_xy


@dataclass(frozen=True, eq=False)
class Circle(Batch):
    """Generalised circle(s), stored as ``(anchor, normal, radius)``:

    * ``anchor``: a finite point on the circle,
    * ``normal``: unit normal at ``anchor``, pointing towards the centre,
    * ``radius``: ``>= 0``; ``inf`` makes the item the straight line through ``anchor``
      perpendicular to ``normal`` (its centre is the point at infinity along ``normal``).

    This osculating form is how Euler-Savary data arrive (path point, normal, radius of
    curvature), degrades continuously to the line of a translating motion's inflection
    "circle", lets one batch mix circles and lines, and never computes ``x**2 + y**2 - r**2``
    (whose cancellation ruins small circles far from the origin). The line at infinity is not
    representable. Build proper circles with :meth:`at` (centre, radius).
    """

    anchor: Point
    normal: Vector
    radius: np.ndarray

    def __post_init__(self) -> None:
        r = np.array(self.radius, dtype=float)
        shape = batch_shape(self.anchor.shape, self.normal.shape, r.shape, what="Circle")
        if (r < 0).any():
            raise GeometryError(f"Circle radius must be >= 0 (inf for a straight line){where_(r < 0)}")
        if self.anchor.is_infinite.any():
            raise GeometryError("Circle anchor must be a finite point")
        n = self.normal.xy
        if (norm(n) == 0).any():
            raise GeometryError("Circle normal must be a non-zero vector")
        object.__setattr__(self, "anchor", Point(np.broadcast_to(self.anchor.coords, shape + (3,))))
        object.__setattr__(self, "normal", Vector(np.broadcast_to(n / norm(n)[..., None], shape + (2,))))
        object.__setattr__(self, "radius", frozen(np.broadcast_to(r, shape)))

    @classmethod
    def at(cls, centre: Point, radius: Any) -> Circle:
        """Proper circle(s) with finite ``centre`` and finite ``radius >= 0``."""
        r = np.asarray(radius, float)
        batch_shape(centre.shape, r.shape, what="Circle.at")
        if np.isinf(r).any():
            raise GeometryError("Circle.at needs a finite radius; use Circle.from_line for a straight line")
        c = finite_xy(centre, "Circle.at")
        return cls(Point.from_xy(c - np.stack([r, np.zeros_like(r)], axis=-1)), Vector.of(1.0, 0.0), r)

    @classmethod
    def with_centre(cls, centre: Point, through: Point) -> Circle:
        """Circle(s) about ``centre`` passing through ``through``."""
        return cls.at(centre, centre.distance(through))

    @classmethod
    def from_line(cls, line: Line) -> Circle:
        """The degenerate circle (radius inf) equal to ``line``; the anchor is the foot from the origin."""
        if np.any(line.is_at_infinity):
            raise GeometryError("the line at infinity cannot be represented as a Circle")
        return cls(line.project(Point.at(0.0, 0.0)), line.normal, np.full(line.shape, np.inf))

    @classmethod
    def through(cls, p: Point, q: Point, r: Point, tol: float = 1e-12) -> Circle:
        """Circle through three finite points; collinear points give their line (radius inf).

        Collinear means twice the triangle area <= ``tol`` * (longest side)**2.
        """
        P, Q, R = (finite_xy(x, "Circle.through") for x in (p, q, r))
        b, c = Q - P, R - P
        sides = np.stack([norm(b), norm(c), norm(c - b)], axis=-1)
        if (sides == 0).any():
            raise GeometryError(f"Circle.through: two of the points coincide{where_((sides == 0).any(-1))}; the circle is undetermined")
        d = 2 * cross2(b, c)
        longest = sides.max(axis=-1)
        flat = abs(d) <= tol * longest**2
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            u = (dot(c, c)[..., None] * rot90(b) - dot(b, b)[..., None] * rot90(c)) / d[..., None]
        u = np.where(flat[..., None], 0.0, u)  # centre offset; meaningless (maybe overflowing) when flat
        # for a line the normal is perpendicular to the longest side (the best-conditioned one)
        k = np.argmax(sides, axis=-1)[..., None]
        n = np.where(flat[..., None], rot90(np.where(k == 0, b, np.where(k == 1, c, c - b))), u)
        return cls(Point.from_xy(P), Vector(n), np.where(flat, np.inf, norm(u)))

    @classmethod
    def tangent_to(cls, line: Line, at: Point, through: Point, tol: float = 1e-12) -> Circle:
        """The circle tangent to ``line`` at ``at`` (projected onto the line) passing through ``through``.

        If ``through`` lies on the line (sine of its angle below ``tol``) the result is the line itself.
        """
        T = finite_xy(line.project(at), "Circle.tangent_to")
        n = line.normal.xy
        v = finite_xy(through, "Circle.tangent_to") - T
        vv, vn = dot(v, v), dot(v, n)
        if (vv == 0).any():
            raise GeometryError(f"Circle.tangent_to: `through` is the point of tangency{where_(vv == 0)}")
        flat = abs(vn) <= tol * np.sqrt(vv)
        with np.errstate(divide="ignore"):
            t = np.where(flat, np.inf, vv / (2 * vn))  # signed distance from T to the centre along n
        return cls(Point.from_xy(T), Vector(np.where((t < 0)[..., None], -n, n)), abs(t))

    @property
    def shape(self) -> tuple[int, ...]:
        return self.radius.shape

    @property
    def is_line(self) -> np.ndarray:
        return np.isinf(self.radius)

    @property
    def curvature(self) -> np.ndarray:
        """``1 / radius`` (0 for lines, inf for point circles)."""
        with np.errstate(divide="ignore"):
            return 1.0 / self.radius

    @property
    def centre(self) -> Point:
        """Centre; the point at infinity along ``normal`` for lines."""
        r = np.where(self.is_line, 0.0, self.radius)[..., None]
        fin = np.concatenate([self.anchor.coords[..., :2] + r * self.normal.xy, np.ones(self.shape + (1,))], axis=-1)
        inf = np.concatenate([self.normal.xy, np.zeros(self.shape + (1,))], axis=-1)
        return Point(np.where(self.is_line[..., None], inf, fin))

    @property
    def tangent_line(self) -> Line:
        """Tangent at ``anchor``; for a degenerate circle this is the circle itself."""
        return Line.through(self.anchor, Point.at_infinity(rot90(self.normal.xy)))

    def signed_distance(self, p: Point) -> np.ndarray:
        """Distance from the curve, positive outside (for a line: on the side away from ``normal``)."""
        X = finite_xy(p, "Circle.signed_distance")
        r = np.where(self.is_line, 0.0, self.radius)
        proper = norm(X - self.centre.coords[..., :2]) - r
        return np.where(self.is_line, -dot(X - self.anchor.xy, self.normal.xy), proper)

    def contains(self, p: Point, tol: float = 1e-9) -> np.ndarray:
        """Whether finite ``p`` lies on the curve within ``tol * max(1, radius, |p|)``."""
        scale = np.maximum(np.maximum(1.0, np.where(self.is_line, 0.0, self.radius)), norm(p.xy))
        return abs(self.signed_distance(p)) <= tol * scale


@dataclass(frozen=True, eq=False)
class Arc(Batch):
    """Circular arc(s) of a proper ``circle``: from polar angle ``start`` (radians, about the
    centre) through the signed ``sweep`` (``> 0`` counter-clockwise, ``|sweep| <= 2 pi``)."""

    circle: Circle
    start: np.ndarray
    sweep: np.ndarray

    def __post_init__(self) -> None:
        start, sweep = np.asarray(self.start, float), np.asarray(self.sweep, float)
        shape = batch_shape(self.circle.shape, start.shape, sweep.shape, what="Arc")
        if self.circle.is_line.any():
            raise GeometryError("an Arc needs a proper circle (finite radius)")
        if not (np.isfinite(start).all() and np.isfinite(sweep).all()) or (abs(sweep) > 2 * np.pi * (1 + 1e-12)).any():
            raise GeometryError("Arc start and sweep must be finite with |sweep| <= 2*pi")
        c = self.circle
        circle = Circle(Point(np.broadcast_to(c.anchor.coords, shape + (3,))), c.normal, np.broadcast_to(c.radius, shape))
        object.__setattr__(self, "circle", circle)
        object.__setattr__(self, "start", frozen(np.broadcast_to(start, shape)))
        object.__setattr__(self, "sweep", frozen(np.broadcast_to(sweep, shape)))

    @classmethod
    def through(cls, p: Point, m: Point, q: Point) -> Arc:
        """The arc from ``p`` via ``m`` to ``q`` (three finite, non-collinear points)."""
        circle = Circle.through(p, m, q)
        if circle.is_line.any():
            raise GeometryError(f"Arc.through: the points are collinear{where_(circle.is_line)}")
        C = circle.centre.xy
        a = [np.arctan2(v[..., 1], v[..., 0]) for v in (x.xy - C for x in (p, m, q))]
        ccw, mid = np.mod(a[2] - a[0], 2 * np.pi), np.mod(a[1] - a[0], 2 * np.pi)
        return cls(circle, a[0], np.where(mid < ccw, ccw, ccw - 2 * np.pi))

    @property
    def shape(self) -> tuple[int, ...]:
        return self.start.shape

    @property
    def length(self) -> np.ndarray:
        return self.circle.radius * abs(self.sweep)

    def point_at(self, t: Any) -> Point:
        """Point at fraction ``t`` of the sweep (0: start, 1: end); ``t`` broadcasts after the batch axes."""
        t = np.asarray(t, float)
        extra = (None,) * t.ndim
        angle = self.start[(..., *extra)] + t * self.sweep[(..., *extra)]
        C, r = self.circle.centre.xy[(..., *extra, slice(None))], self.circle.radius[(..., *extra)]
        return Point.at(C[..., 0] + r * np.cos(angle), C[..., 1] + r * np.sin(angle))

    @property
    def start_point(self) -> Point:
        return self.point_at(0.0)

    @property
    def end_point(self) -> Point:
        return self.point_at(1.0)

    def sample(self, n: int) -> Point:
        """``n`` evenly spaced points, batch shape ``shape + (n,)`` (for drawing)."""
        return self.point_at(np.linspace(0.0, 1.0, n))
