"""Hand-computed checks of Circle, Arc and circle intersections (linkwork.geometry)."""

import numpy as np
import pytest

from linkwork.geometry import Arc, Circle, GeometryError, Line, Point, Vector, intersect

# numerical code must stay silent: NaN/inf are produced on purpose, never by accident
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

O = Point.at(0, 0)


def test_circle_at_and_validation():
    c = Circle.at(Point.at(1, 2), 3)
    assert c.centre.equals(Point.at(1, 2)) and c.radius == 3 and not c.is_line
    assert c.contains(Point.at(4, 2)) and c.contains(Point.at(1, -1)) and not c.contains(O)
    assert c.signed_distance(Point.at(1, 7)) == pytest.approx(2.0)
    assert c.curvature == pytest.approx(1 / 3)
    with pytest.raises(GeometryError, match=">= 0"):
        Circle.at(O, -1)
    with pytest.raises(GeometryError, match="from_line"):
        Circle.at(O, np.inf)
    with pytest.raises(GeometryError, match="infinity"):
        Circle.at(Point.at_infinity([1, 0]), 1)
    with pytest.raises(GeometryError, match="do not agree"):
        Circle.at(Point.at([0, 1], [0, 0]), [1, 2, 3])
    with pytest.raises(GeometryError, match="non-zero"):
        Circle(O, Vector.of(0, 0), 1.0)


def test_circle_with_centre_and_through_three_points():
    assert Circle.with_centre(Point.at(1, 1), Point.at(4, 5)).radius == 5
    c = Circle.through(Point.at(0, 0), Point.at(2, 0), Point.at(0, 2))
    assert c.centre.equals(Point.at(1, 1)) and c.radius == pytest.approx(np.sqrt(2))
    with pytest.raises(GeometryError, match="coincide"):
        Circle.through(O, O, Point.at(1, 0))


def test_degenerate_circle_is_a_line():
    c = Circle.through(Point.at(0, 1), Point.at(2, 1), Point.at(5, 1))  # collinear: y = 1
    assert c.is_line and c.radius == np.inf and c.curvature == 0
    assert c.tangent_line.equals(Line.from_abc(0, 1, -1))
    assert c.centre.is_infinite and c.centre.equals(Point.at_infinity([0, 1]))
    assert c.contains(Point.at(-3, 1)) and not c.contains(Point.at(0, 0))
    f = Circle.from_line(Line.from_abc(1, 0, -2))  # x = 2
    assert f.is_line and f.anchor.equals(Point.at(2, 0))
    with pytest.raises(GeometryError, match="line at infinity"):
        Circle.from_line(Line.at_infinity())


def test_circle_tangent_to_line_at_point_through_point():
    c = Circle.tangent_to(Line.from_abc(0, 1, 0), at=Point.at(0, 0), through=Point.at(0, 2))
    assert c.centre.equals(Point.at(0, 1)) and c.radius == 1
    c = Circle.tangent_to(Line.from_abc(0, 1, 0), at=Point.at(1, 0), through=Point.at(3, -2))
    assert c.centre.equals(Point.at(1, -2)) and c.radius == 2  # centre on the far side of the normal
    flat = Circle.tangent_to(Line.from_abc(0, 1, 0), at=O, through=Point.at(4, 0))
    assert flat.is_line and flat.tangent_line.equals(Line.from_abc(0, 1, 0))
    with pytest.raises(GeometryError, match="tangency"):
        Circle.tangent_to(Line.from_abc(0, 1, 0), at=O, through=O)


def test_circle_line_intersection_and_branches():
    res = intersect(Circle.at(O, 5), Line.from_abc(0, 1, -3))  # y = 3, directed +x
    assert res.valid and res.plus.equals(Point.at(4, 3)) and res.minus.equals(Point.at(-4, 3))
    res = intersect(Line.from_abc(0, -1, 3), Circle.at(O, 5))  # same line directed -x: branches swap
    assert res.plus.equals(Point.at(-4, 3))
    tangent = intersect(Circle.at(O, 5), Line.from_abc(0, 1, -5))
    assert tangent.valid and tangent.plus.equals(Point.at(0, 5)) and tangent.minus.equals(Point.at(0, 5))
    miss = intersect(Circle.at(O, 5), Line.from_abc(0, 1, -6))
    assert not miss.valid and np.isnan(miss.plus.coords).all() and np.isnan(miss.minus.coords).all()
    assert not intersect(Circle.at(O, 5), Line.at_infinity()).valid


def test_circle_circle_intersection_and_branches():
    res = intersect(Circle.at(O, 5), Circle.at(Point.at(6, 0), 5))
    assert res.valid and res.plus.equals(Point.at(3, 4)) and res.minus.equals(Point.at(3, -4))
    swapped = intersect(Circle.at(Point.at(6, 0), 5), Circle.at(O, 5))  # left of c1->c2 is now -y
    assert swapped.plus.equals(Point.at(3, -4))
    assert res.select(-1).equals(Point.at(3, -4))
    outer = intersect(Circle.at(O, 1), Circle.at(Point.at(2, 0), 1))
    assert outer.valid and outer.plus.equals(Point.at(1, 0)) and outer.minus.equals(Point.at(1, 0))
    inner = intersect(Circle.at(O, 3), Circle.at(Point.at(1, 0), 2))
    assert inner.valid and inner.plus.equals(Point.at(3, 0)) and inner.minus.equals(Point.at(3, 0))
    for c2 in (Circle.at(Point.at(5, 0), 1), Circle.at(Point.at(0.5, 0), 1), Circle.at(O, 1)):
        miss = intersect(Circle.at(O, 2), c2)  # apart, nested, concentric
        assert not miss.valid and np.isnan(miss.plus.coords).all()


def test_intersections_batch_never_raise_and_select_per_item():
    c1 = Circle.at(Point.at([0, 0, 0], [0, 0, 0]), [5, 1, 2])
    c2 = Circle.at(Point.at([6, 2, 10], [0, 0, 0]), [5, 1, 1])
    res = intersect(c1, c2)
    np.testing.assert_array_equal(res.valid, [True, True, False])
    np.testing.assert_array_equal(res.select([1, -1, 1]).xy[:2], [[3, 4], [1, 0]])
    assert np.isnan(res.plus.xy[2]).all()


def test_degenerate_circle_intersections():
    flat = Circle.from_line(Line.from_abc(1, 0, -3))  # x = 3, normal +x
    res = intersect(flat, Line.from_abc(0, 1, -2))
    assert res.valid and res.plus.equals(Point.at(3, 2)) and res.minus.equals(Point.at(3, 2))
    assert not intersect(flat, Line.from_abc(1, 0, -5)).valid  # parallel: only at infinity
    assert not intersect(flat, Line.from_abc(1, 0, -3)).valid  # coincident: no exception
    # the line x = 3 meets the circle |X| = 5 at (3, +-4); its centre lies at infinity along +x,
    # so from the first centre to the second the direction is -x and "left" is -y
    res = intersect(flat, Circle.at(O, 5))
    assert res.plus.equals(Point.at(3, -4)) and res.minus.equals(Point.at(3, 4))
    res = intersect(Circle.at(O, 5), flat)  # direction +x, left is +y
    assert res.plus.equals(Point.at(3, 4)) and res.minus.equals(Point.at(3, -4))
    both = intersect(flat, Circle.from_line(Line.from_abc(0, 1, 1)))
    assert both.valid and both.plus.equals(Point.at(3, -1))
    # one batch mixing a proper circle (centre (4, 0), radius 3) and the line x = 3
    mixed = intersect(Circle(Point.at([1, 3], [0, 0]), Vector.of(1, 0), [3, np.inf]), Circle.at(O, 5))
    assert mixed.valid.all()
    assert mixed.plus.equals(Point.at([4, 3], [-3, -4])).all() and mixed.minus.equals(Point.at([4, 3], [3, 4])).all()


def test_arc():
    arc = Arc.through(Point.at(1, 0), Point.at(0, 1), Point.at(-1, 0))  # upper half, counter-clockwise
    assert arc.sweep == pytest.approx(np.pi) and arc.length == pytest.approx(np.pi)
    assert arc.start_point.equals(Point.at(1, 0)) and arc.end_point.equals(Point.at(-1, 0))
    assert arc.point_at(0.5).equals(Point.at(0, 1))
    lower = Arc.through(Point.at(1, 0), Point.at(0, -1), Point.at(-1, 0))
    assert lower.sweep == pytest.approx(-np.pi)
    pts = Arc.through(Point.at([1, 2], [0, 0]), Point.at([0, 0], [1, 2]), Point.at([-1, -2], [0, 0])).sample(5)
    assert pts.shape == (2, 5) and pts[1, 2].equals(Point.at(0, 2))
    with pytest.raises(GeometryError, match="collinear"):
        Arc.through(O, Point.at(1, 0), Point.at(2, 0))
    with pytest.raises(GeometryError, match="sweep"):
        Arc(Circle.at(O, 1), 0.0, 7.0)
