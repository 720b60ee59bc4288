"""Hand-computed checks of Point, Vector, Line and their validation (linkwork.geometry)."""

import dataclasses

import numpy as np
import pytest

from linkwork.geometry import GeometryError, Line, Point, Vector, intersect

# numerical code must stay silent: NaN/inf are produced on purpose, never by accident
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")


def test_point_canonical_and_equality_up_to_scale():
    p = Point(np.array([2.0, 4.0, 2.0]))
    assert np.array_equal(p.coords, [1.0, 2.0, 1.0])
    assert p.equals(Point.at(1, 2)) and p.is_finite and not p.is_infinite
    inf = Point.at_infinity([3.0, 4.0])
    assert inf.is_infinite and not inf.is_finite
    assert np.isnan(inf.xy).all()
    np.testing.assert_allclose(inf.direction.xy, [0.6, 0.8])
    assert inf.equals(Point.at_infinity([-6.0, -8.0]))  # direction sense is irrelevant
    assert not inf.equals(Point.at(3, 4)) and not Point.at(3, 4).equals(inf)
    assert np.isnan(Point.at(1, 2).direction.xy).all()


def test_point_rejects_invalid_input():
    for bad in ([0, 0, 0], [np.inf, 0, 1], [1.0, 2.0]):
        with pytest.raises(GeometryError):
            Point(np.array(bad, float))
    with pytest.raises(GeometryError, match="at_infinity"):
        Point.at(np.inf, 0)
    with pytest.raises(GeometryError):
        Point.at_infinity([0, 0])


def test_point_overflowing_quotient_is_at_infinity():
    p = Point(np.array([1.0, 1.0, 1e-320]))
    assert p.is_infinite and p.equals(Point.at_infinity([1, 1]))


def test_immutable():
    p = Point.at([1, 2], [3, 4])
    with pytest.raises(ValueError):
        p.coords[0, 0] = 5
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.coords = np.zeros((2, 3))
    source = np.array([1.0, 1.0, 1.0])
    q = Point(source)
    source[0] = 9  # the object holds a private copy
    assert q.coords[0] == 1


def test_batch_protocol_and_shape_agreement():
    p = Point.at([0, 1, 2], [0, 0, 0])
    assert p.shape == (3,) and len(p) == 3
    assert p[1].equals(Point.at(1, 0)) and p[1].shape == ()
    assert p[np.array([True, False, True])].shape == (2,)
    with pytest.raises(TypeError):
        len(Point.at(0, 0))
    with pytest.raises(GeometryError, match="do not agree"):
        Line.through(Point.at([0, 1], [0, 0]), Point.at([0, 1, 2], [1, 1, 1]))


def test_distance_and_arithmetic():
    p, q = Point.at(1, 1), Point.at(4, 5)
    assert p.distance(q) == 5.0
    v = q - p
    assert isinstance(v, Vector) and np.array_equal(v.xy, [3, 4])
    assert (p + v).equals(q) and (q - v).equals(p)
    with pytest.raises(GeometryError, match="infinity"):
        p.distance(Point.at_infinity([1, 0]))


def test_vector():
    v = Vector.of(3.0, 4.0)
    assert v.norm == 5.0
    assert np.array_equal(v.rotated90().xy, [-4, 3])
    assert np.array_equal(v.rotated90(-1).xy, [4, -3])
    assert v.angle == pytest.approx(np.arctan2(4, 3))
    np.testing.assert_allclose(v.rotated(np.pi / 2).xy, [-4, 3], atol=1e-15)
    np.testing.assert_allclose(Vector.from_angle(np.pi / 2, 2).xy, [0, 2], atol=1e-15)
    assert v.dot(Vector.of(1, 0)) == 3 and v.cross(Vector.of(1, 0)) == -4
    assert np.array_equal((2 * v - v / 2 + -v).xy, [1.5, 2.0])
    with pytest.raises(GeometryError):
        Vector.of(0, 0).unit()
    with pytest.raises(GeometryError):
        v.rotated90(2)


def test_line_validation_and_at_infinity():
    with pytest.raises(GeometryError, match="line at infinity"):
        Line.from_abc(0, 0, 0)
    l_inf = Line.at_infinity()
    assert l_inf.is_at_infinity
    assert l_inf.contains(Point.at_infinity([1, 2])) and not l_inf.contains(Point.at(0, 0))
    with pytest.raises(GeometryError, match="no normal"):
        Line.perpendicular(through=Point.at(0, 0), to=l_inf)


def test_line_through_orientation_and_metrics():
    line = Line.through(Point.at(0, 0), Point.at(2, 0))  # the x-axis, directed +x
    np.testing.assert_array_equal(line.direction.xy, [1, 0])
    np.testing.assert_array_equal(line.normal.xy, [0, 1])
    assert line.signed_distance(Point.at(5, 3)) == 3.0
    assert line.signed_distance(Point.at(5, -3)) == -3.0
    assert line.project(Point.at(5, 3)).equals(Point.at(5, 0))
    assert line.point_at_infinity.equals(Point.at_infinity([1, 0]))
    with pytest.raises(GeometryError, match="coincide"):
        Line.through(Point.at(1, 1), Point.at(1, 1))


def test_line_through_a_point_at_infinity():
    line = Line.through(Point.at(1, 1), Point.at_infinity([1, 0]))  # y = 1
    assert line.equals(Line.from_abc(0, 1, -1))
    assert line.contains(Point.at(-7, 1)) and not line.contains(Point.at(0, 0))
    assert Line.through(Point.at_infinity([1, 0]), Point.at_infinity([0, 1])).is_at_infinity


def test_perpendicular_and_parallel():
    base = Line.from_abc(1, -1, 0)  # y = x
    perp = Line.perpendicular(through=Point.at(2, 0), to=base)
    assert perp.equals(Line.from_abc(1, 1, -2))
    par = Line.parallel(through=Point.at(0, 1), to=base)
    assert par.equals(Line.from_abc(1, -1, 1))
    np.testing.assert_allclose(par.direction.xy, base.direction.xy)


def test_line_equals_ignores_scale_and_sense():
    assert Line.from_abc(1, 2, 3).equals(Line.from_abc(-2, -4, -6))
    assert not Line.from_abc(1, 2, 3).equals(Line.from_abc(1, 2, 3.1))
    # far from the origin an offset of 1 still counts
    assert not Line.from_abc(1, 0, -1e6).equals(Line.from_abc(1, 0, -1e6 - 1))


def test_intersect_lines_exact():
    x = intersect(Line.from_abc(1, 1, -2), Line.from_abc(1, -1, 0))
    assert np.array_equal(x.coords, [1, 1, 1])
    x = intersect(Line.through(Point.at(0, 0), Point.at(3, 1)), Line.from_abc(1, 0, -1))  # x = 1
    assert np.array_equal(x.xy, [1, 1 / 3])


def test_intersect_parallel_lines_is_the_exact_point_at_infinity():
    x = intersect(Line.from_abc(1, -2, 0), Line.from_abc(2, -4, 7))
    assert x.is_infinite and x.coords[2] == 0
    assert x.equals(Point.at_infinity([2, 1]))
    assert intersect(Line.at_infinity(), Line.from_abc(0, 1, -5)).equals(Point.at_infinity([1, 0]))


def test_intersect_coincident_lines():
    with pytest.raises(GeometryError, match="coincide"):
        intersect(Line.from_abc(1, 2, 3), Line.from_abc(2, 4, 6))
    batch = Line.from_abc([1, 1], [2, 0], [3, 0])
    with pytest.raises(GeometryError, match=r"batch index \[0\]"):
        intersect(batch, Line.from_abc(2, 4, 6))
    x = intersect(batch, Line.from_abc(2, 4, 6), coincident="nan")
    assert np.isnan(x.coords[0]).all() and x[1].equals(Point.at(0, -1.5))


def test_intersect_nearly_parallel_lines():
    eps = 2.0**-30  # slope; the lines y = 0 and y = 1 + eps x meet at x = -1/eps exactly
    x = intersect(Line.from_abc(0, 1, 0), Line.through(Point.at(0, 1), Point.at(1, 1 + eps)))
    assert x.is_finite and x.xy[0] == -(2.0**30) and x.xy[1] == 0
    # below the parallel tolerance the pair is honestly treated as parallel, not as 1e12
    y = intersect(Line.from_abc(0, 1, 0), Line.from_abc(1e-14, 1, -1))
    assert y.is_infinite and y.equals(Point.at_infinity([1, 0]))
    z = intersect(Line.from_abc(0, 1, 0), Line.from_abc(1e-14, 1, -1), tol=0)
    np.testing.assert_allclose(z.xy, [1e14, 0])


def test_intersect_huge_and_tiny_coefficients_do_not_overflow():
    x = intersect(Line.from_abc(1e200, 1e200, -2e200), Line.from_abc(1e-200, -1e-200, 0))
    assert np.array_equal(x.xy, [1, 1])
    y = intersect(Line.from_abc(3e300, 0, -3e300), Line.from_abc(0, 5e300, -1e301))
    assert np.array_equal(y.xy, [1, 2])
