"""Hand-computed checks of the helper constructions (linkwork.geometry.constructions)."""

import numpy as np
import pytest

from linkwork.geometry import (
    Circle, GeometryError, Line, Point, collinear, foot_of_perpendicular, harmonic_conjugate,
    intersect, midpoint, orientation, perpendicular_bisector, polar, reflect,
)

# numerical code must stay silent: NaN/inf are produced on purpose, never by accident
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")


def test_midpoint_bisector_foot():
    assert midpoint(Point.at(0, 0), Point.at(2, 4)).equals(Point.at(1, 2))
    assert perpendicular_bisector(Point.at(0, 0), Point.at(2, 0)).equals(Line.from_abc(1, 0, -1))
    assert perpendicular_bisector(Point.at(1, 1), Point.at(3, 3)).equals(Line.from_abc(1, 1, -4))
    assert foot_of_perpendicular(Point.at(0, 2), Line.from_abc(1, -1, 0)).equals(Point.at(1, 1))
    with pytest.raises(GeometryError, match="coincide"):
        perpendicular_bisector(Point.at(1, 1), Point.at(1, 1))
    with pytest.raises(GeometryError, match="infinity"):
        midpoint(Point.at(0, 0), Point.at_infinity([1, 0]))


def test_reflect():
    assert reflect(Point.at(1, 2), Line.from_abc(1, -1, 0)).equals(Point.at(2, 1))
    assert reflect(Point.at(0, 0), Line.from_abc(1, 0, -1)).equals(Point.at(2, 0))
    assert reflect(Point.at_infinity([1, 0]), Line.from_abc(1, -1, 0)).equals(Point.at_infinity([0, 1]))
    with pytest.raises(GeometryError):
        reflect(Point.at(0, 0), Line.at_infinity())


def test_collinear_and_orientation():
    a, b = Point.at(0, 0), Point.at(1, 0)
    assert collinear(a, b, Point.at(5, 0)) and not collinear(a, b, Point.at(5, 1))
    assert collinear(a, b, Point.at_infinity([1, 0])) and not collinear(a, b, Point.at_infinity([1, 1]))
    assert collinear(a, a, Point.at(3, 7))
    assert orientation(a, b, Point.at(0, 1)) == 1 and orientation(a, b, Point.at(0, -1)) == -1
    assert orientation(a, b, Point.at(2, 0)) == 0
    assert orientation(a, b, Point.at_infinity([0, 1])) == 1
    # scale invariance: the same shape a million times smaller or larger
    for s in (1e-6, 1e6):
        assert orientation(Point.at(0, 0), Point.at(s, 0), Point.at(0, s)) == 1
        assert not collinear(Point.at(0, 0), Point.at(s, 0), Point.at(0, s * 1e-3))
    np.testing.assert_array_equal(
        collinear(Point.at([0, 0], [0, 0]), Point.at([1, 1], [0, 0]), Point.at([2, 2], [0, 1e-3])), [True, False])


def test_harmonic_conjugate():
    d = harmonic_conjugate(Point.at(0, 0), Point.at(3, 0), Point.at(1, 0))
    assert d.equals(Point.at(-3, 0))  # (0, 3; 1, -3): (1 - 0)(-3 - 3) / ((1 - 3)(-3 - 0)) = -1
    assert harmonic_conjugate(Point.at(0, 0), Point.at(2, 2), Point.at(1, 1)).equals(Point.at_infinity([1, 1]))
    assert harmonic_conjugate(Point.at(0, 0), Point.at(2, 2), Point.at_infinity([1, 1])).equals(Point.at(1, 1))
    with pytest.raises(GeometryError, match="not on the line"):
        harmonic_conjugate(Point.at(0, 0), Point.at(2, 0), Point.at(1, 1))


def test_polar():
    unit = Circle.at(Point.at(0, 0), 1)
    assert polar(Point.at(2, 0), unit).equals(Line.from_abc(1, 0, -0.5))
    assert polar(Point.at(0, 0), unit).is_at_infinity
    assert polar(Point.at_infinity([0, 1]), unit).equals(Line.from_abc(0, 1, 0))
    # the polar of an outside point passes through its two points of tangency
    P = Point.at(2, 0)
    touch = intersect(unit, polar(P, unit))
    for t in (touch.plus, touch.minus):
        assert abs((t - P).dot(t - Point.at(0, 0))) < 1e-12
    assert touch.plus.equals(Point.at(0.5, -np.sqrt(3) / 2))  # along the polar direction (0, -1)
    with pytest.raises(GeometryError):
        polar(P, Circle.from_line(Line.from_abc(1, 0, 0)))
