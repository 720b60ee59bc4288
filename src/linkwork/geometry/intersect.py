"""Intersections of lines and generalised circles.

Owns :func:`intersect` and its two-point result :class:`IntersectionPair`.

Conventions (all batch-first, no Python loop over samples):

* line x line -> :class:`Point`. Parallel lines meet exactly at their common point at infinity
  (``w = 0``); "parallel" means the sine of their angle is <= ``tol``. Coincident lines raise
  :class:`GeometryError` (``coincident="raise"``, default) or give NaN items (``coincident="nan"``).
* circle x line, circle x circle -> :class:`IntersectionPair` ``(plus, minus, valid)``. Missing
  intersections are NaN points with ``valid == False``, never an exception; tangency (within
  ``tol``, relative) gives a double point ``plus == minus``. A degenerate circle (a line) meets a
  line or a circle like a line; where the result would only be a point at infinity it is invalid.
"""

from __future__ import annotations

from typing import Any, Literal, NamedTuple

import numpy as np

from ._base import batch_shape, dot, norm, rot90, where_
from .circle import Circle
from .errors import GeometryError
from .line import Line, meet
from .point import Point


class IntersectionPair(NamedTuple):
    """Both intersection points and the mask of items where they exist.

    Branches: circle x line: ``plus`` is the point farther along ``line.direction``;
    circle x circle: ``plus`` lies to the left of the directed line from the first centre to the
    second (for a degenerate circle its centre is the point at infinity along its ``normal``).
    """

    plus: Point
    minus: Point
    valid: np.ndarray

    def select(self, branch: Any) -> Point:
        """``plus`` where ``branch > 0``, else ``minus``; ``branch`` is a scalar or per-item array."""
        b = np.asarray(branch)[..., None] > 0
        return Point(np.where(b, self.plus.coords, self.minus.coords))


def intersect(first: Line | Circle, second: Line | Circle, *, tol: float = 1e-12,
              coincident: Literal["raise", "nan"] = "raise") -> Point | IntersectionPair:
    """Intersect two lines (-> Point) or a circle with a line or a circle (-> IntersectionPair)."""
    match first, second:
        case Line(), Line():
            return _lines(first, second, tol, coincident)
        case Circle(), Line():
            return _circle_line(first, second, tol)
        case Line(), Circle():
            return _circle_line(second, first, tol)
        case Circle(), Circle():
            return _circles(first, second, tol)
    raise TypeError(f"cannot intersect {type(first).__name__} with {type(second).__name__}")


def _lines(l1: Line, l2: Line, tol: float, coincident: str) -> Point:
    x, same = meet(l1, l2, tol)
    if same.any() and coincident == "raise":
        raise GeometryError(f"intersect: the lines coincide{where_(same)}; their intersection is the whole line")
    x[same] = np.nan
    return Point(x)


def _pair(plus: np.ndarray, minus: np.ndarray, valid: np.ndarray) -> IntersectionPair:
    """Assemble homogeneous coordinates, blanking invalid items to NaN."""
    plus, minus = (np.where(valid[..., None], v, np.nan) for v in (plus, minus))
    valid = np.array(valid, dtype=bool)
    valid.flags.writeable = False
    return IntersectionPair(Point(plus), Point(minus), valid)


def _circle_line(circle: Circle, line: Line, tol: float) -> IntersectionPair:
    shape = batch_shape(circle.shape, line.shape, what="intersect")
    # proper circles: foot F of the centre, half-chord h from (r - |s|)(r + |s|), no cancellation
    flat = circle.is_line
    r = np.where(flat, 1.0, circle.radius)
    C = Point(np.where(flat[..., None], [0.0, 0.0, 1.0], circle.centre.coords))
    s = line.signed_distance(C)
    F = C.xy - s[..., None] * line.normal.xy
    h2 = (r - abs(s)) * (r + abs(s))
    touch = (h2 < 0) & np.isfinite(s) & (abs(s) - r <= tol * np.maximum(r, abs(s)))
    h = np.sqrt(np.where(touch, 0.0, np.maximum(h2, 0.0)))[..., None] * line.direction.xy
    one = np.ones(shape + (1,))
    plus, minus = np.concatenate([F + h, one], -1), np.concatenate([F - h, one], -1)
    # degenerate circles: a single point, finite unless the two lines are parallel
    x, same = meet(circle.tangent_line, line, tol)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where(~same[..., None] & (x[..., 2:] != 0), x / x[..., 2:], np.nan)
    valid = np.where(flat, np.isfinite(x).all(-1), (h2 >= 0) | touch)
    return _pair(np.where(flat[..., None], x, plus), np.where(flat[..., None], x, minus), valid)


def _circles(c1: Circle, c2: Circle, tol: float) -> IntersectionPair:
    shape = batch_shape(c1.shape, c2.shape, what="intersect")
    l1, l2 = np.broadcast_to(c1.is_line, shape), np.broadcast_to(c2.is_line, shape)
    r1, r2 = (np.where(l, 1.0, c.radius) for l, c in ((l1, c1), (l2, c2)))
    D = np.where((l1 | l2)[..., None], [1.0, 0.0], c2.centre.coords[..., :2] - c1.centre.coords[..., :2])
    d = norm(D)
    u = D / np.where(d > 0, d, 1.0)[..., None]
    # factored discriminant: (r1+r2-d) >= 0 (not apart) and (d-|r1-r2|) >= 0 (not nested)
    apart, nested, big = r1 + r2 - d, d - abs(r1 - r2), r1 + r2 + d
    apart, nested = (np.where((x < 0) & (x >= -tol * big), 0.0, x) for x in (apart, nested))
    valid = (apart >= 0) & (nested >= 0) & (d > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        a = (d + (r1 - r2) * (r1 + r2) / d) / 2
        h = np.sqrt(np.maximum(big * apart * nested * (d + abs(r1 - r2)), 0.0)) / (2 * d)
        M = c1.centre.coords[..., :2] + a[..., None] * u
    one = np.ones(shape + (1,))
    plus = np.concatenate([M + h[..., None] * rot90(u), one], -1)
    minus = np.concatenate([M - h[..., None] * rot90(u), one], -1)
    # a line among the pair: intersect the other one with it, then order by the same left-hand rule
    if (l1 | l2).any():
        A = _circle_line(c2, c1.tangent_line, tol)
        B = _circle_line(c1, c2.tangent_line, tol)
        lp, lm, lv = (np.where(l1[..., None], a_, b_) for a_, b_ in
                      ((A.plus.coords, B.plus.coords), (A.minus.coords, B.minus.coords), (A.valid[..., None], B.valid[..., None])))
        u = np.where(l1[..., None], -c1.normal.xy, c2.normal.xy)
        swap = (dot(rot90(u), lp[..., :2] - lm[..., :2]) < 0)[..., None]
        lp, lm = np.where(swap, lm, lp), np.where(swap, lp, lm)
        either = (l1 | l2)[..., None]
        plus, minus = np.where(either, lp, plus), np.where(either, lm, minus)
        valid = np.where(l1 | l2, lv[..., 0], valid)
    return _pair(plus, minus, valid)
