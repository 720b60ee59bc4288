"""Properties of random profiles (Hypothesis): circles and ellipses against their closed forms,
finite differences and the three-point circle; closed quintic splines through random star-shaped
points pass through them and are C⁴ at the seam; offsets of random ellipses obey o′ = (1 + dκ)c′."""

from __future__ import annotations

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from linkwork.geometry.profiles import CircleProfile, EllipseProfile, OffsetProfile, SplineProfile, curvature
from profile_checks import assert_derivatives_match_differences, distance_at, three_point_curvature

props = settings(max_examples=30, deadline=None)
coord = st.floats(-100, 100)
param = st.floats(-20, 20)


@props
@given(cx=coord, cy=coord, r=st.floats(0.1, 100), u=param, px=coord, py=coord)
def test_random_circle(cx, cy, r, u, px, py):
    c = CircleProfile((cx, cy), r)
    uu = np.array([u])
    np.testing.assert_allclose(curvature(c, uu), 1 / r, rtol=1e-12)
    np.testing.assert_allclose(three_point_curvature(c, uu, 1e-3), 1 / r, rtol=1e-5)
    d = c.derivatives(uu, 4)
    np.testing.assert_allclose(np.hypot(*(d[0, 0] - [cx, cy])), r, rtol=1e-12)
    np.testing.assert_allclose(d[4], d[0] - [cx, cy], atol=1e-12 * (r + 1))  # c⁗ = c − C
    assume(np.hypot(px - cx, py - cy) > 1e-3)
    foot = c.derivatives(c.nearest(np.array([px, py])), 0)[0]
    np.testing.assert_allclose(np.hypot(*(foot - [px, py])), abs(np.hypot(px - cx, py - cy) - r), atol=1e-9 * (r + 100))


@props
@given(a=st.floats(0.5, 20), ratio=st.floats(0.1, 1.0), angle=st.floats(-4, 4), u=param)
def test_random_ellipse(a, ratio, angle, u):
    b = a * ratio
    e = EllipseProfile((1.0, -2.0), (a, b), angle)
    uu = np.array([u, u + 0.3])
    kappa = a * b / (a**2 * np.sin(uu) ** 2 + b**2 * np.cos(uu) ** 2) ** 1.5
    np.testing.assert_allclose(curvature(e, uu), kappa, rtol=1e-11)
    np.testing.assert_allclose(three_point_curvature(e, uu, 1e-4), kappa, rtol=1e-4)
    assert_derivatives_match_differences(e, uu, 4, h=1e-3, rtol=1e-6)
    np.testing.assert_allclose(e.arc_length(uu + 2 * np.pi), e.arc_length(uu) + e.length, rtol=1e-12)
    # the point lies on the ellipse: in its own axes (x/a)² + (y/b)² = 1
    p = e.derivatives(uu, 0)[0] - [1.0, -2.0]
    x = p[:, 0] * np.cos(angle) + p[:, 1] * np.sin(angle)
    y = -p[:, 0] * np.sin(angle) + p[:, 1] * np.cos(angle)
    np.testing.assert_allclose((x / a) ** 2 + (y / b) ** 2, 1.0, rtol=1e-12)


@st.composite
def star_points(draw):
    n = draw(st.integers(6, 12))
    gaps = np.array(draw(st.lists(st.floats(0.5, 1.5), min_size=n, max_size=n)))
    ang = np.cumsum(gaps) * 2 * np.pi / np.sum(gaps)
    rad = np.array(draw(st.lists(st.floats(5, 15), min_size=n, max_size=n)))
    return np.column_stack([rad * np.cos(ang), rad * np.sin(ang)])


@settings(max_examples=20, deadline=None)
@given(pts=star_points(), degree=st.sampled_from([3, 5]))
def test_random_closed_spline(pts, degree):
    s = SplineProfile(pts, closed=True, degree=degree)
    knots = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(np.vstack([pts, pts[:1]]), axis=0), axis=1))])
    np.testing.assert_allclose(s.knots, knots, rtol=1e-14)
    np.testing.assert_allclose(s.derivatives(knots, 0)[0], np.vstack([pts, pts[:1]]), atol=1e-10)
    # the seam from both sides, derivatives 0 … degree − 1
    L, delta = knots[-1], 1e-7
    below, above = s.derivatives(np.array([L - delta]), degree - 1), s.derivatives(np.array([delta]), degree - 1)
    fine = s.derivatives(np.linspace(0, L, 2001), degree)
    for k in range(degree):
        bound = 3 * 2 * delta * np.max(np.abs(fine[k + 1])) + 1e-9
        assert np.max(np.abs(below[k] - above[k])) <= bound, k
    # each given point is a point of the profile: its nearest point is itself
    np.testing.assert_allclose(distance_at(s, s.nearest(pts), pts), 0, atol=1e-8)


@props
@given(a=st.floats(1, 10), ratio=st.floats(0.2, 1.0), frac=st.floats(-0.9, 3.0), u=param)
def test_random_ellipse_offset(a, ratio, frac, u):
    b = a * ratio
    d = frac * b**2 / a  # inward no further than the smallest radius of curvature
    e = EllipseProfile((0.0, 0.0), (a, b))
    o = OffsetProfile(e, d)
    uu = np.array([u])
    kappa = a * b / (a**2 * np.sin(uu) ** 2 + b**2 * np.cos(uu) ** 2) ** 1.5
    np.testing.assert_allclose(o.derivatives(uu, 1)[1], (1 + d * kappa)[:, None] * e.derivatives(uu, 1)[1],
                               atol=1e-11 * a)
    np.testing.assert_allclose(curvature(o, uu), kappa / (1 + d * kappa), rtol=1e-10)
    assert o.cusps.size == 0
