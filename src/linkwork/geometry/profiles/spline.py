"""Splines through given points: a cam or a track drawn from a table of points.

The interpolating spline is SciPy's `make_interp_spline` in both coordinates over one parameter,
the cumulative chord length (the distance from point to point, so the parameter is close to the
arc length and the speed |c′| stays near 1). A closed profile uses periodic end conditions, so
the seam is as smooth as every other knot; an open one SciPy's not-a-knot conditions.

The default degree is 5 (quintic): the position is C⁴, so the curvature is C³ and the follower's
acceleration and jerk, which contain the curvature and its first derivative, vary smoothly; only
the fifth derivative jumps at the knots (the engine's order 6 sees that as a crackle, not as a
jump of acceleration). Degree 3 (cubic, C², curvature only C⁰ with kinks, jerk jumping at every
knot) is available where a book's table was drawn that way.
"""

from __future__ import annotations

import numpy as np

from .base import BaseProfile, ProfileError


class SplineProfile(BaseProfile):
    """The interpolating spline of `degree` 5 (default) or 3 through `points` (n, 2), `closed`
    (periodic) or open; u = cumulative chord length from the first point, domain (0, total chord
    length, including the closing chord of a closed spline). A closed spline's points may repeat
    the first point at the end (it is dropped)."""

    def __init__(self, points, closed: bool = False, degree: int = 5) -> None:
        if degree not in (3, 5) or isinstance(degree, bool):
            raise ProfileError(f"a spline profile has degree 3 or 5, got {degree!r}")
        try:
            pts = np.array(points, dtype=float)
        except (TypeError, ValueError):
            raise ProfileError("spline points must be a list of [x, y] numbers") from None
        if pts.ndim != 2 or pts.shape[1] != 2:
            raise ProfileError(f"spline points must be a list of [x, y] pairs, got shape {pts.shape}")
        bad = np.flatnonzero(~np.all(np.isfinite(pts), axis=1))
        if bad.size:
            raise ProfileError(f"point {bad[0]}: not a finite [x, y] ({pts[bad[0]].tolist()})", int(bad[0]))
        if closed and len(pts) > 1 and np.array_equal(pts[0], pts[-1]):
            pts = pts[:-1]
        chords = np.hypot(*np.diff(pts, axis=0).T)
        scale = max(1.0, float(np.max(np.abs(pts), initial=0.0)))
        dup = np.flatnonzero(chords <= 1e-12 * scale)
        if dup.size:
            raise ProfileError(f"point {dup[0] + 1}: repeats point {dup[0]} ({pts[dup[0]].tolist()})",
                               int(dup[0] + 1))
        need = 3 if closed else degree + 1
        if len(pts) < need:
            raise ProfileError(f"a{' closed' if closed else 'n open'} spline of degree {degree} needs at "
                               f"least {need} distinct points, got {len(pts)}")
        if closed:
            closing = float(np.hypot(*(pts[0] - pts[-1])))
            if closing <= 1e-12 * scale:  # the first point given twice more at the end
                raise ProfileError(f"point {len(pts) - 1}: repeats point 0 ({pts[0].tolist()}); a closed "
                                   "spline may repeat its first point once at the end", len(pts) - 1)
            chords = np.append(chords, closing)
            pts = np.vstack([pts, pts[:1]])
        u = np.concatenate([[0.0], np.cumsum(chords)])
        self.points = pts[:-1] if closed else pts
        self.knots = u  # the parameters of the given points
        self.closed = bool(closed)
        self.degree = degree
        self.domain = (0.0, float(u[-1]))
        from scipy.interpolate import make_interp_spline  # SciPy loads when first needed
        spline = make_interp_spline(u, pts, k=degree, bc_type="periodic" if closed else None)
        self._splines = [spline] + [spline.derivative(k) for k in range(1, degree + 1)]
        t = spline.t
        self._pieces_edges = np.unique(t[(t >= u[0]) & (t <= u[-1])])

    def _quadrature_edges(self) -> np.ndarray:
        # each polynomial piece in four: the speed is the root of a polynomial, smooth on each;
        # the points too, for an open spline's end pieces span several of them (not-a-knot) and
        # its speed may dip there (2e-10 of the length lost without them)
        e = np.union1d(self._pieces_edges, self.knots)
        return np.union1d(e, (e[:-1, None] + np.diff(e)[:, None] * np.array([0.25, 0.5, 0.75])).ravel())

    def _eval(self, u: np.ndarray, order: int, side: int) -> np.ndarray:
        out = np.zeros((order + 1,) + u.shape + (2,))
        for k in range(min(order, self.degree) + 1):
            out[k] = self._splines[k](u)
        return out
