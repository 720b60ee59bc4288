"""Interpolating splines: through their points at the cumulative chord lengths, C⁴ (quintic) or
C² (cubic) at every knot and at the seam of a closed one (the next derivative jumps), a straight
line through collinear points, a circle approximated closely, and the refusals of bad points."""

from __future__ import annotations

import numpy as np
import pytest

from linkwork.geometry.profiles import ProfileError, SplineProfile, curvature
from profile_checks import (
    assert_derivatives_match_differences,
    brute_nearest_distance,
    distance_at,
    quad_length,
    three_point_curvature,
)

# a star-shaped, unevenly spaced closed outline
ANG = np.array([0.0, 0.7, 1.2, 2.1, 2.9, 3.5, 4.4, 5.0, 5.8])
RAD = np.array([10.0, 12.0, 9.0, 11.0, 8.0, 10.5, 9.5, 12.5, 11.0])
STAR = np.column_stack([RAD * np.cos(ANG), RAD * np.sin(ANG)])


def chord_knots(pts, closed):
    p = np.vstack([pts, pts[:1]]) if closed else pts
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])


def one_sided_jumps(s, x, order, delta):
    """|c⁽ᵏ⁾(x + δ) − c⁽ᵏ⁾(x − δ)| for k = 0 … order, each knot x."""
    d_plus, d_minus = s.derivatives(x + delta, order), s.derivatives(x - delta, order)
    return np.linalg.norm(d_plus - d_minus, axis=-1)  # (order + 1, n)


@pytest.mark.parametrize("closed", [True, False])
@pytest.mark.parametrize("degree", [5, 3])
def test_through_the_points_at_chord_lengths(closed, degree):
    s = SplineProfile(STAR, closed=closed, degree=degree)
    knots = chord_knots(STAR, closed)
    np.testing.assert_allclose(s.knots, knots, rtol=1e-15)
    assert s.domain == (0.0, pytest.approx(knots[-1], rel=1e-15)) and s.closed == closed
    np.testing.assert_allclose(s.derivatives(knots[: len(STAR)], 0)[0], STAR, atol=1e-11)
    # arc length against quadrature; at least the polygon's length (a chord is the shortest way)
    np.testing.assert_allclose(s.length, quad_length(s, 0, s.domain[1], points=knots), rtol=1e-10)
    assert s.length >= knots[-1]
    np.testing.assert_allclose(s.arc_length(knots[3:4]), quad_length(s, 0, knots[3], points=knots), rtol=1e-10)


@pytest.mark.parametrize("degree", [5, 3])
def test_continuity_at_knots_and_seam(degree):
    """Derivatives 0 … degree − 1 agree from both sides of every knot, the seam included (the
    difference over 2δ is bounded by the next derivative); the degree-th derivative jumps."""
    s = SplineProfile(STAR, closed=True, degree=degree)
    L = s.domain[1]
    knots = s.knots  # the last one is the seam, u = L ≡ 0
    delta = 1e-7
    jumps = one_sided_jumps(s, knots, degree, delta)
    bound = [3 * 2 * delta * np.max(np.linalg.norm(s.derivatives(np.linspace(0, L, 4001), k + 1)[k + 1], axis=-1))
             + 1e-9 * np.max(np.abs(STAR)) for k in range(degree)]
    for k in range(degree):
        assert np.all(jumps[k] <= bound[k]), f"derivative {k} jumps at a knot: {jumps[k]} > {bound[k]}"
    assert np.max(jumps[degree]) > 1e3 * bound[degree - 1]  # the test sees a jump where there is one
    # the seam seen through the wrapping: u slightly below L continues to u = 0
    for k, (a, b) in enumerate(zip(s.derivatives(np.array([L - delta]), degree - 1),
                                   s.derivatives(np.array([delta]), degree - 1))):
        assert np.linalg.norm(a - b) <= bound[k]
    np.testing.assert_allclose(s.derivatives(np.array([L, 2 * L + 1.0]), 4), s.derivatives(np.array([0.0, 1.0]), 4),
                               atol=1e-9)


def test_open_spline_and_derivatives_inside_pieces():
    s = SplineProfile(STAR, closed=False)
    k = s.knots
    mid = (k[:-1] + k[1:]) / 2
    assert_derivatives_match_differences(s, mid, 5, h=1e-3, rtol=1e-6)
    assert np.all(s.derivatives(mid, 7)[6:] == 0)  # a quintic's sixth derivative vanishes
    d = s.derivatives(np.array([-1e-9, k[-1] + 1e-9, np.nan]), 3)
    assert np.all(np.isnan(d))
    np.testing.assert_allclose(three_point_curvature(s, mid, 1e-4), curvature(s, mid), rtol=1e-5)
    np.testing.assert_array_equal(s.breaks, [])


def test_collinear_points_give_the_line_itself():
    """Chord length is arc length on a line, so the spline through unevenly spaced collinear points
    is p₀ + u·e exactly: unit speed, no curvature."""
    t = np.array([0.0, 0.3, 1.1, 1.5, 2.9, 3.0, 4.2])
    e = np.array([0.6, -0.8])
    s = SplineProfile(np.array([1.0, 2.0]) + t[:, None] * e)
    u = np.linspace(0, 4.2, 29)
    d = s.derivatives(u, 3)
    np.testing.assert_allclose(d[0], [1.0, 2.0] + u[:, None] * e, atol=1e-12)
    np.testing.assert_allclose(d[1], np.broadcast_to(e, d[1].shape), atol=1e-11)
    np.testing.assert_allclose(d[2:], 0, atol=1e-9)
    np.testing.assert_allclose(s.length, 4.2, rtol=1e-12)


@pytest.mark.parametrize("degree,rtol", [(5, 2e-6), (3, 1e-3)])
def test_circle_through_many_points(degree, rtol):
    R, n = 10.0, 72
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    s = SplineProfile(np.column_stack([R * np.cos(t), R * np.sin(t)]), closed=True, degree=degree)
    u = np.linspace(0, s.domain[1], 1001)
    pos = s.derivatives(u, 0)[0]
    np.testing.assert_allclose(np.linalg.norm(pos, axis=-1), R, rtol=rtol)
    np.testing.assert_allclose(curvature(s, u), 1 / R, rtol=200 * rtol)
    np.testing.assert_allclose(s.length, 2 * np.pi * R, rtol=rtol)
    # the nearest point of a point outside is on its ray
    p = np.array([[30.0, 40.0], [-3.0, 0.5]])
    foot = s.derivatives(s.nearest(p), 0)[0]
    np.testing.assert_allclose(foot / np.linalg.norm(foot, axis=-1, keepdims=True),
                               p / np.linalg.norm(p, axis=-1, keepdims=True), atol=10 * rtol)


def test_nearest_against_dense_search():
    s = SplineProfile(STAR, closed=True)
    rng = np.random.default_rng(3)
    p = rng.uniform(-15, 15, size=(30, 2))
    u = s.nearest(p)
    brute = np.array([brute_nearest_distance(s, q, 0, s.domain[1], samples=40001) for q in p])
    np.testing.assert_allclose(distance_at(s, u, p), brute, atol=1e-9)


def test_closed_spline_may_repeat_its_first_point_and_needs_three():
    a = SplineProfile(STAR, closed=True)
    b = SplineProfile(np.vstack([STAR, STAR[:1]]), closed=True)
    np.testing.assert_array_equal(a.knots, b.knots)
    np.testing.assert_array_equal(b.points, STAR)
    tri = SplineProfile([[0, 0], [4, 0], [0, 3]], closed=True)
    np.testing.assert_allclose(tri.domain[1], 12.0)
    np.testing.assert_allclose(tri.derivatives(np.array([0.0, 4.0, 9.0]), 0)[0], [[0, 0], [4, 0], [0, 3]], atol=1e-12)
    jumps = one_sided_jumps(tri, np.array([0.0, 4.0, 9.0]), 4, 1e-7)
    assert np.all(jumps <= 1e-4)


@pytest.mark.parametrize("points,kw,message,index", [
    (STAR, dict(degree=4), "degree 3 or 5, got 4", None),
    (STAR, dict(degree=True), "degree 3 or 5, got True", None),
    ([[0, 0], [1, "a"]], {}, "list of \\[x, y\\] numbers", None),
    ([[0, 0], [1, 1, 2]], {}, "list of \\[x, y\\]", None),
    (np.zeros((4, 3)), {}, "pairs, got shape \\(4, 3\\)", None),
    ([[0, 0], [1, 0], [np.nan, 1], [2, 2], [3, 0], [4, 1]], {}, "point 2: not a finite", 2),
    ([[0, 0], [1, 0], [2, 1], [2, 1], [3, 0], [4, 1]], {}, "point 3: repeats point 2", 3),
    (STAR[:5], {}, "an open spline of degree 5 needs at least 6 distinct points, got 5", None),
    (STAR[:3], dict(degree=3), "needs at least 4 distinct points, got 3", None),
    (STAR[:2], dict(closed=True), "a closed spline of degree 5 needs at least 3", None),
    (np.vstack([STAR, STAR[:1], STAR[:1]]), dict(closed=True), "point 9: repeats point 0", 9),
])
def test_bad_points_are_refused(points, kw, message, index):
    with pytest.raises(ProfileError, match=message) as e:
        SplineProfile(points, **kw)
    assert e.value.index == index
