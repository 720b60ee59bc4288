"""Hypothesis properties of linkwork.geometry: incidence identities, extremal properties,
exact rational results, and batch results equal to per-item scalar results."""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from linkwork.geometry import (
    Arc, Circle, Line, Point, collinear, foot_of_perpendicular, harmonic_conjugate, intersect,
    orientation, polar, reflect,
)

# numerical code must stay silent: NaN/inf are produced on purpose, never by accident
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

# per-test settings (a global profile would leak into other packages' tests)
props = settings(max_examples=150, deadline=None)

coord = st.floats(-100, 100, allow_nan=False, allow_infinity=False)
xy = st.tuples(coord, coord)
small_int = st.integers(-1000, 1000)


def P(t):
    return Point.at(*t)


def far_apart(*pts, d=1e-3):
    return all(np.hypot(p[0] - q[0], p[1] - q[1]) > d for i, p in enumerate(pts) for q in pts[i + 1:])


def cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


def sine(l1, l2):
    n1, n2 = l1.normal.xy, l2.normal.xy
    return abs(n1[0] * n2[1] - n1[1] * n2[0])


@props
@given(xy, xy, xy, xy)
def test_intersection_lies_on_both_lines(a, b, c, d):
    assume(far_apart(a, b) and far_apart(c, d))
    l1, l2 = Line.through(P(a), P(b)), Line.through(P(c), P(d))
    assume(sine(l1, l2) > 1e-3)
    x = intersect(l1, l2)
    assert x.is_finite and l1.contains(x, 1e-8) and l2.contains(x, 1e-8)


@props
@given(small_int, small_int, small_int, small_int, small_int, small_int)
def test_integer_lines_intersect_exactly(a1, b1, c1, a2, b2, c2):
    det = a1 * b2 - a2 * b1
    assume(det != 0 and (a1, b1) != (0, 0) and (a2, b2) != (0, 0))
    x = intersect(Line.from_abc(a1, b1, c1), Line.from_abc(a2, b2, c2))
    # Cramer's rule in exact rationals, then one correct rounding
    assert x.xy[0] == float(Fraction(b1 * c2 - b2 * c1, det))
    assert x.xy[1] == float(Fraction(c1 * a2 - c2 * a1, det))


@props
@given(xy, xy, xy)
def test_parallel_lines_meet_at_their_common_direction(a, b, c):
    assume(far_apart(a, b))
    line = Line.through(P(a), P(b))
    par = Line.parallel(through=P(c), to=line)
    assume(not par.equals(line, 1e-6))
    x = intersect(line, par)
    assert x.coords[2] == 0 and x.equals(Point.at_infinity(np.subtract(b, a)))


@props
@given(xy, xy, st.fractions(-5, 5, max_denominator=16))
def test_harmonic_conjugate_cross_ratio(a, b, t):
    assume(far_apart(a, b, d=1e-2) and t not in (0, 1) and abs(t - Fraction(1, 2)) > Fraction(1, 64))
    A, B = np.array(a), np.array(b)
    D = harmonic_conjugate(P(a), P(b), Point.from_xy(A + float(t) * (B - A)))
    s = np.dot(D.xy - A, B - A) / np.dot(B - A, B - A)  # parameter of D on A + s (B - A)
    t = float(t)
    assert np.isclose(t * (s - 1) / ((t - 1) * s), -1.0, rtol=1e-6)


@props
@given(xy, xy, xy, st.floats(-1e3, 1e3))
def test_foot_of_perpendicular_minimises_distance(a, b, p, t):
    assume(far_apart(a, b))
    line = Line.through(P(a), P(b))
    f = foot_of_perpendicular(P(p), line)
    assert line.contains(f, 1e-9)
    other = f + line.direction * t
    # rounding of coordinates of size `scale` allows an absolute slack of a few ulps
    scale = max(1.0, *map(abs, (*a, *b, *p)))
    assert P(p).distance(other) >= P(p).distance(f) * (1 - 1e-12) - 1e-12 * scale
    assert abs((P(p) - f).dot(line.direction)) <= 1e-9 * max(1.0, P(p).distance(f))


@props
@given(xy, xy, xy)
def test_circle_through_three_points_passes_through_them(a, b, c):
    A, B, C = map(np.array, (a, b, c))
    assume(far_apart(a, b, c, d=1e-2))
    assume(abs(cross(B - A, C - A)) > 1e-2 * max(np.ptp([A, B, C], axis=0)) ** 2)
    circle = Circle.through(P(a), P(b), P(c))
    assert not circle.is_line
    for q in (a, b, c):
        assert circle.contains(P(q), 1e-8)


@props
@given(xy, st.floats(0.1, 50), xy, st.floats(0.1, 50))
def test_circle_circle_points_and_validity(c1, r1, c2, r2):
    d = np.hypot(c1[0] - c2[0], c1[1] - c2[1])
    lo, hi = abs(r1 - r2), r1 + r2
    assume(min(abs(d - lo), abs(d - hi)) > 1e-6 * hi)
    k1, k2 = Circle.at(P(c1), r1), Circle.at(P(c2), r2)
    res = intersect(k1, k2)
    assert bool(res.valid) == (lo < d < hi)
    if res.valid:
        for x in (res.plus, res.minus):
            assert k1.contains(x, 1e-7) and k2.contains(x, 1e-7)
        assert orientation(P(c1), P(c2), res.plus) >= 0 >= orientation(P(c1), P(c2), res.minus)


@props
@given(xy, st.floats(0.1, 50), xy, xy)
def test_circle_line_points_and_validity(c, r, a, b):
    assume(far_apart(a, b, d=1e-2))
    circle, line = Circle.at(P(c), r), Line.through(P(a), P(b))
    dist = abs(line.signed_distance(P(c)))
    assume(abs(dist - r) > 1e-6 * r)
    res = intersect(circle, line)
    assert bool(res.valid) == (dist < r)
    if res.valid:
        for x in (res.plus, res.minus):
            assert circle.contains(x, 1e-7) and line.contains(x, 1e-7)
        assert (res.plus - res.minus).dot(line.direction) >= 0  # plus is farther along the line


@props
@given(xy, xy, xy)
def test_reflection_is_an_isometric_involution(a, b, p):
    assume(far_apart(a, b))
    line = Line.through(P(a), P(b))
    q = reflect(P(p), line)
    assert reflect(q, line).equals(P(p), 1e-9)
    assert np.isclose(line.signed_distance(q), -line.signed_distance(P(p)), atol=1e-9 * 100)


# |t| is kept away from rounding level: a + t d must be a representable, distinct point
@props
@given(xy, xy, st.floats(-10, 10).filter(lambda t: t == 0 or abs(t) > 1e-3), st.tuples(coord, coord))
def test_line_through_a_direction_and_collinearity(a, b, t, d):
    assume(np.hypot(*d) > 1e-3)
    line = Line.through(P(a), Point.at_infinity(d))
    assert line.contains(P(a)) and line.contains(Point.at_infinity(d))
    on = Point.from_xy(np.array(a) + t * np.array(d))
    assert collinear(P(a), on, Point.at_infinity(d))
    assert orientation(P(a), P(b), on) == -orientation(P(b), P(a), on)


@props
@given(xy, st.floats(0.5, 50), xy, xy)
def test_pole_polar_reciprocity(c, r, p, q):
    # La Hire: Q lies on the polar of P  <=>  P lies on the polar of Q; test with Q projected onto polar(P)
    circle = Circle.at(P(c), r)
    assume(far_apart(p, c, d=1e-1))
    qq = polar(P(p), circle).project(P(q))
    assume(far_apart(tuple(qq.xy), c, d=1e-1))
    assert polar(qq, circle).contains(P(p), 1e-7)


@props
@given(xy, xy, xy)
def test_tangent_circle_touches_line_and_passes_through_point(a, b, p):
    assume(far_apart(a, b))
    line = Line.through(P(a), P(b))
    assume(abs(line.signed_distance(P(p))) > 1e-2)
    k = Circle.tangent_to(line, at=P(a), through=P(p))
    assert k.contains(P(p), 1e-8) and k.contains(P(a), 1e-8)
    # tangency: the radius to the contact point is perpendicular to the line
    assert abs((k.centre - P(a)).dot(line.direction)) <= 1e-8 * max(1.0, float(k.radius))


@props
@given(xy, xy, xy)
def test_arc_through_three_points(a, m, b):
    A, M, B = map(np.array, (a, m, b))
    assume(far_apart(a, m, b, d=1e-1) and abs(cross(M - A, B - A)) > 1e-1 * max(np.ptp([A, M, B], axis=0)) ** 2)
    arc = Arc.through(P(a), P(m), P(b))
    assert arc.start_point.equals(P(a), 1e-8) and arc.end_point.equals(P(b), 1e-8)
    ts = np.linspace(0, 1, 2001)
    assert np.min(np.hypot(*(arc.point_at(ts).xy - M).T)) < 1e-2 * float(arc.length)  # m lies on the arc


def same(x, y):
    np.testing.assert_array_equal(x, y)  # exact, NaN == NaN


@props
@given(st.lists(st.tuples(xy, xy, xy, xy, st.floats(0, 60), st.floats(0, 60)), min_size=1, max_size=8))
def test_batch_equals_scalar(items):
    items = [it for it in items if far_apart(it[0], it[1]) and far_apart(it[2], it[3])]
    assume(items)
    a, b, c, d, r1, r2 = (np.array(v) for v in zip(*items))
    l1, l2 = Line.through(Point.from_xy(a), Point.from_xy(b)), Line.through(Point.from_xy(c), Point.from_xy(d))
    k1, k2 = Circle.at(Point.from_xy(a), r1), Circle.at(Point.from_xy(c), r2)
    batch = {
        "meet": intersect(l1, l2, coincident="nan").coords,
        "circle-line": np.stack([*(p.coords for p in intersect(k1, l2)[:2])], -2),
        "circle-circle": np.stack([*(p.coords for p in intersect(k1, k2)[:2])], -2),
        "cc-valid": intersect(k1, k2).valid,
        "foot": foot_of_perpendicular(Point.from_xy(c), l1).coords,
        "reflect": reflect(Point.from_xy(d), l1).coords,
        "circumcircle": Circle.through(Point.from_xy(a), Point.from_xy(b), Point.from_xy(c)).centre.coords
        if all(far_apart(*it[:3]) for it in items) else None,
    }
    for i in range(len(items)):
        p = [Point.from_xy(v[i]) for v in (a, b, c, d)]
        L1, L2 = Line.through(p[0], p[1]), Line.through(p[2], p[3])
        K1, K2 = Circle.at(p[0], r1[i]), Circle.at(p[2], r2[i])
        same(batch["meet"][i], intersect(L1, L2, coincident="nan").coords)
        same(batch["circle-line"][i], np.stack([q.coords for q in intersect(K1, L2)[:2]]))
        same(batch["circle-circle"][i], np.stack([q.coords for q in intersect(K1, K2)[:2]]))
        same(batch["cc-valid"][i], intersect(K1, K2).valid)
        same(batch["foot"][i], foot_of_perpendicular(p[2], L1).coords)
        same(batch["reflect"][i], reflect(p[3], L1).coords)
        if batch["circumcircle"] is not None:
            same(batch["circumcircle"][i], Circle.through(p[0], p[1], p[2]).centre.coords)
