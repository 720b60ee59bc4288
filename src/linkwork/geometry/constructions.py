"""Classical helper constructions on points, lines and circles.

Owns: midpoint, perpendicular bisector, foot of perpendicular, harmonic conjugate, reflection,
collinearity and orientation tests, and the polar of a point. (The circle through a point
tangent to a line at another point is :meth:`Circle.tangent_to`.) Projective constructions
(harmonic conjugate, reflection, collinearity, orientation, polar) accept points at infinity;
metric ones (midpoint, bisector, foot) need finite points.
"""

from __future__ import annotations

import numpy as np

from ._base import batch_shape, dot, norm, where_
from .circle import Circle
from .errors import GeometryError
from .line import Line
from .point import Point, finite_xy


def midpoint(p: Point, q: Point) -> Point:
    return Point.from_xy((finite_xy(p, "midpoint") + finite_xy(q, "midpoint")) / 2)


def perpendicular_bisector(p: Point, q: Point) -> Line:
    """Locus of points equidistant from ``p`` and ``q``; its normal points from ``p`` to ``q``."""
    P, Q = finite_xy(p, "perpendicular_bisector"), finite_xy(q, "perpendicular_bisector")
    n = Q - P
    same = (n == 0).all(-1)
    if same.any():
        raise GeometryError(f"perpendicular_bisector: the points coincide{where_(same)}")
    return Line(np.concatenate([n, -dot(n, P + Q)[..., None] / 2], axis=-1))


def foot_of_perpendicular(p: Point, line: Line) -> Point:
    """The point of ``line`` nearest to finite ``p``."""
    return line.project(p)


def reflect(p: Point, line: Line) -> Point:
    """Mirror image of ``p`` (finite or at infinity) in ``line``: ``P - 2 (l.P) / (a^2 + b^2) (a, b, 0)``."""
    if np.any(line.is_at_infinity):
        raise GeometryError("reflect: cannot reflect in the line at infinity")
    n = np.concatenate([line.coords[..., :2], np.zeros(line.shape + (1,))], axis=-1)
    k = 2 * dot(line.coords, p.coords) / dot(n, n)
    return Point(p.coords - k[..., None] * n)


def _det(p: Point, q: Point, r: Point) -> np.ndarray:
    """Similarity-invariant determinant of three homogeneous points.

    Finite points are centred on their centroid and scaled by their spread, directions of points
    at infinity are made unit, so ``|det|`` is dimensionless (~ area / size**2 for finite points).
    """
    batch_shape(p.shape, q.shape, r.shape, what="collinear/orientation")
    pts = np.stack(np.broadcast_arrays(p.coords, q.coords, r.coords), axis=-2)
    fin = pts[..., 2:] == 1
    xy = pts[..., :2]
    centroid = np.where(fin, xy, 0).sum(-2) / np.maximum(fin.sum(-2), 1)
    xy = np.where(fin, xy - centroid[..., None, :], xy)
    spread = np.max(np.where(fin, norm(xy)[..., None], 0), axis=-2)
    xy = xy / np.where(fin, np.where(spread > 0, spread, 1)[..., None, :], norm(xy)[..., None])
    with np.errstate(divide="ignore", invalid="ignore"):  # LAPACK warns on exactly singular input
        return np.linalg.det(np.concatenate([xy, pts[..., 2:]], axis=-1))


def collinear(p: Point, q: Point, r: Point, tol: float = 1e-9) -> np.ndarray:
    """Whether three points (any of them possibly at infinity) lie on one line; NaN gives False."""
    return abs(_det(p, q, r)) <= tol


def orientation(p: Point, q: Point, r: Point, tol: float = 1e-9) -> np.ndarray:
    """+1.0 if ``p, q, r`` turn counter-clockwise, -1.0 clockwise, 0.0 collinear, NaN undefined.

    With ``r`` at infinity this is the side of ``p -> q`` its direction points to.
    """
    d = _det(p, q, r)
    return np.where(abs(d) <= tol, 0.0, np.sign(d))


def harmonic_conjugate(a: Point, b: Point, c: Point, tol: float = 1e-9) -> Point:
    """The point D with cross-ratio (A, B; C, D) = -1 on the line AB (any point may be at infinity).

    Writing C = alpha A + beta B in homogeneous coordinates gives D = alpha A - beta B; the
    conjugate of the midpoint is the point at infinity and vice versa.
    """
    ab = np.cross(a.coords, b.coords)
    if (ab == 0).all(-1).any():
        raise GeometryError("harmonic_conjugate: A and B coincide")
    if not collinear(a, b, c, tol).all():
        raise GeometryError("harmonic_conjugate: C is not on the line AB")
    n2 = dot(ab, ab)
    alpha = dot(np.cross(c.coords, b.coords), ab) / n2
    beta = dot(np.cross(a.coords, c.coords), ab) / n2
    return Point(alpha[..., None] * a.coords - beta[..., None] * b.coords)


def polar(p: Point, circle: Circle) -> Line:
    """Polar line of ``p`` w.r.t. a proper circle: ``(P - C) . (X - C) = r^2`` in homogeneous form.

    The polar of the centre is the line at infinity; of a point at infinity, the perpendicular diameter.
    """
    if np.any(circle.is_line):
        raise GeometryError("polar: needs a proper circle (finite radius)")
    C, r = circle.centre.xy, circle.radius
    w = p.coords[..., 2]
    n = p.coords[..., :2] - w[..., None] * C
    return Line(np.concatenate([n, (-dot(n, C) - w * r**2)[..., None]], axis=-1))
