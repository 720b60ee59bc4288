"""Checks of profiles by means independent of the code under test: finite differences of the
next lower derivative, the circle through three close points for the curvature, SciPy's adaptive
quadrature of the speed for the arc length, and a dense search for the nearest point."""

from __future__ import annotations

import numpy as np
from scipy.integrate import quad
from scipy.optimize import minimize_scalar


def central_difference(profile, u, order, h, **kw):
    """d/du of the derivative of `order` - 1 by the five-point central stencil (error O(h⁴))."""
    f = lambda x: profile.derivatives(x, order - 1, **kw)[order - 1]  # noqa: E731
    return (-f(u + 2 * h) + 8 * f(u + h) - 8 * f(u - h) + f(u - 2 * h)) / (12 * h)


def assert_derivatives_match_differences(profile, u, max_order, h, rtol=1e-7, **kw):
    """Each derivative of order 1 … max_order equals the central difference of the one below,
    with h the step in the parameter (chosen for the curve's scale) and a tolerance relative to
    the largest value of that derivative over the samples."""
    u = np.asarray(u, dtype=float)
    d = profile.derivatives(u, max_order, **kw)
    for k in range(1, max_order + 1):
        fd = central_difference(profile, u, k, h, **kw)
        # the rounding of the stencil: a few ulps of the lower derivative divided by h
        rounding = 1e3 * np.finfo(float).eps * float(np.max(np.abs(d[k - 1]))) / h
        atol = rtol * float(np.max(np.abs(d[k]))) + rounding
        np.testing.assert_allclose(d[k], fd, rtol=0, atol=atol, err_msg=f"derivative of order {k}")


def three_point_curvature(profile, u, h):
    """Signed curvature of the circle through c(u − h), c(u), c(u + h) (Menger curvature):
    4·area / (product of the sides), positive when the three points turn left."""
    p = profile.derivatives(np.asarray(u, dtype=float) - h, 0)[0]
    q = profile.derivatives(np.asarray(u, dtype=float), 0)[0]
    r = profile.derivatives(np.asarray(u, dtype=float) + h, 0)[0]
    a, b = q - p, r - q
    cross = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    sides = np.linalg.norm(a, axis=-1) * np.linalg.norm(b, axis=-1) * np.linalg.norm(r - p, axis=-1)
    return 2 * cross / sides


def quad_length(profile, lo, hi, points=None):
    """∫ |c′| du from lo to hi by SciPy's adaptive quadrature (QUADPACK)."""
    def speed(x):
        c1 = profile.derivatives(np.array([x]), 1)[1][0]
        return float(np.hypot(*c1))
    pts = None if points is None else [p for p in points if lo < p < hi]
    value, _ = quad(speed, lo, hi, points=pts or None, limit=200, epsabs=1e-13, epsrel=1e-12)
    return value


def brute_nearest_distance(profile, p, lo, hi, samples=20001):
    """Distance from p to the profile over [lo, hi]: a dense sample, then a bounded scalar
    minimisation in the bracket around the best sample."""
    u = np.linspace(lo, hi, samples)
    pts = profile.derivatives(u, 0)[0]
    dist = np.hypot(pts[:, 0] - p[0], pts[:, 1] - p[1])
    i = int(np.argmin(dist))
    a, b = u[max(i - 1, 0)], u[min(i + 1, samples - 1)]

    def f(x):
        c = profile.derivatives(np.array([x]), 0)[0][0]
        return float(np.hypot(c[0] - p[0], c[1] - p[1]))
    res = minimize_scalar(f, bounds=(a, b), method="bounded", options={"xatol": 1e-13 * max(1.0, abs(hi - lo))})
    return min(res.fun, dist[i])


def distance_at(profile, u, p):
    c = profile.derivatives(np.asarray(u, dtype=float), 0)[0]
    return np.hypot(c[..., 0] - p[..., 0], c[..., 1] - p[..., 1])
