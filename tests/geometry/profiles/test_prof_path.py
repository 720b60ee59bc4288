"""Paths of lines and circular arcs: segment lengths from elementary geometry, derivatives against
the arc's and the line's closed forms and finite differences, joins and curvature jumps, the two
sides of a join, arcs by centre or by radius in either sense, and the refusals of bad input."""

from __future__ import annotations

import numpy as np
import pytest

from linkwork.geometry.profiles import ArcTo, LineTo, PathProfile, ProfileError, curvature, curvature_jumps
from profile_checks import (
    assert_derivatives_match_differences,
    brute_nearest_distance,
    distance_at,
    quad_length,
    three_point_curvature,
)

R, L = 2.0, 5.0


def stadium() -> PathProfile:
    """Counter-clockwise: bottom line (0,0)→(L,0), right half-circle about (L,R), top line back,
    left half-circle about (0,R) to the start."""
    return PathProfile((0.0, 0.0), [LineTo((L, 0.0)), ArcTo((L, 2 * R), center=(L, R)),
                                    LineTo((0.0, 2 * R)), ArcTo((0.0, 0.0), center=(0.0, R))], closed=True)


def test_stadium_lengths_and_joins():
    p = stadium()
    assert p.closed and p.domain == (0.0, pytest.approx(2 * L + 2 * np.pi * R, rel=1e-15))
    np.testing.assert_allclose(p.segment_starts, [0, L, L + np.pi * R, 2 * L + np.pi * R], rtol=1e-15)
    j = p.joins()
    # the joins in parameter order, the seam (u = 0: the left arc ends, the bottom line starts) last
    np.testing.assert_allclose(j.u, [L, L + np.pi * R, 2 * L + np.pi * R, 0.0], rtol=1e-15)
    np.testing.assert_allclose(j.kappa_before, [0, 1 / R, 0, 1 / R], rtol=1e-15)
    np.testing.assert_allclose(j.kappa_after, [1 / R, 0, 1 / R, 0], rtol=1e-15)
    np.testing.assert_allclose(j.turn, 0, atol=1e-15)  # tangent joins
    u, before, after = curvature_jumps(p)
    np.testing.assert_allclose(u, np.sort(j.u))
    order = np.argsort(j.u)
    np.testing.assert_allclose(before, j.kappa_before[order], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(after, j.kappa_after[order], rtol=1e-12, atol=1e-15)
    assert p.length == p.domain[1]


def test_stadium_derivatives():
    p = stadium()
    # inside each segment: the closed forms (line: p₀ + s t; arc: C + R e^{i(θ₀ + s/R)})
    s = np.linspace(0.1, L - 0.1, 7)
    d = p.derivatives(s, 4)
    np.testing.assert_allclose(d[0], np.stack([s, 0 * s], -1), atol=1e-15)
    np.testing.assert_allclose(d[1], np.broadcast_to([1.0, 0.0], d[1].shape))
    assert np.all(d[2:] == 0)
    s = L + np.linspace(0.1, np.pi * R - 0.1, 9)
    ang = -np.pi / 2 + (s - L) / R
    d = p.derivatives(s, 5)
    for k in range(6):
        z = R * (1j / R) ** k * np.exp(1j * ang) + (complex(L, R) if k == 0 else 0)
        np.testing.assert_allclose(d[k], np.stack([z.real, z.imag], -1), atol=1e-13, err_msg=f"order {k}")
    # finite differences away from the joins, unit speed, and the three-point curvature
    u = np.concatenate([np.linspace(0.2, L - 0.2, 5), L + np.linspace(0.2, np.pi * R - 0.2, 5),
                        2 * L + np.pi * R + np.linspace(0.2, np.pi * R - 0.2, 5)])
    assert_derivatives_match_differences(p, u, 5, h=1e-3)
    np.testing.assert_allclose(np.linalg.norm(p.derivatives(u, 1)[1], axis=-1), 1.0, rtol=1e-14)
    np.testing.assert_allclose(three_point_curvature(p, u, 1e-3), curvature(p, u), rtol=1e-6, atol=1e-9)


def test_side_at_a_join():
    p = stadium()
    u = np.array([L])  # line ends, right arc starts: (L, 0), tangent (1, 0)
    plus, minus = p.derivatives(u, 2, side=1), p.derivatives(u, 2, side=-1)
    np.testing.assert_allclose(plus[:2], minus[:2], atol=1e-15)
    np.testing.assert_allclose(plus[2, 0], [0.0, 1 / R], atol=1e-15)  # centripetal, towards (L, R)
    np.testing.assert_allclose(minus[2, 0], [0.0, 0.0], atol=1e-15)
    # at the seam, side −1 is the end of the last segment (the left arc arriving at (0, 0))
    seam_minus = p.derivatives(np.array([0.0, p.length]), 2, side=-1)
    np.testing.assert_allclose(seam_minus[0], [[0, 0], [0, 0]], atol=1e-13)
    np.testing.assert_allclose(seam_minus[2], [[0, 1 / R], [0, 1 / R]], atol=1e-13)
    np.testing.assert_allclose(p.derivatives(np.array([0.0]), 2, side=1)[2], [[0, 0]], atol=1e-15)
    np.testing.assert_allclose(curvature(p, np.array([0.0, L]), side=-1), [1 / R, 0], atol=1e-15)
    np.testing.assert_array_equal(p.segment_index(np.array([0.0, L, p.length]), side=-1), [3, 0, 3])
    np.testing.assert_array_equal(p.segment_index(np.array([0.0, L, p.length]), side=1), [0, 1, 0])


def test_periodicity_length_and_nearest():
    p = stadium()
    u = np.random.default_rng(2).uniform(0, p.length, 23)  # almost surely no join
    for turns in (-2, 1, 3):
        np.testing.assert_allclose(p.derivatives(u + turns * p.length, 3), p.derivatives(u, 3), atol=1e-12)
    np.testing.assert_allclose(p.arc_length(u + 2 * p.length), u + 2 * p.length, rtol=1e-14)
    np.testing.assert_allclose(quad_length(p, 0, p.length, points=p.breaks), p.length, rtol=1e-12)
    rng = np.random.default_rng(11)
    q = rng.uniform([-4, -3], [L + 4, 2 * R + 3], size=(60, 2))
    un = p.nearest(q)
    assert np.all((un >= 0) & (un < p.length))
    brute = np.array([brute_nearest_distance(p, x, 0, p.length) for x in q])
    np.testing.assert_allclose(distance_at(p, un, q), brute, atol=1e-9)
    assert np.isnan(p.nearest(np.array([np.nan, 1.0])))


def test_open_path_outside_its_domain_and_ends():
    p = PathProfile((0, 0), [LineTo((3, 0)), ArcTo((3, 2), center=(3, 1))])
    assert not p.closed and p.domain == (0.0, pytest.approx(3 + np.pi))
    j = p.joins()
    np.testing.assert_allclose([j.u[0], j.kappa_before[0], j.kappa_after[0]], [3, 0, 1.0])
    assert len(j.u) == 1
    d = p.derivatives(np.array([-1e-9, p.length + 1e-9, np.nan]), 2)
    assert np.all(np.isnan(d))
    assert np.all(np.isnan(p.arc_length(np.array([-0.5, 10.0]))))
    # at the ends only one segment exists: both sides give it
    for side in (1, -1):
        np.testing.assert_allclose(p.derivatives(np.array([0.0, p.length]), 2, side=side)[0], [[0, 0], [3, 2]], atol=1e-14)
    # nearest: clamped to the ends of an open path
    np.testing.assert_allclose(p.nearest(np.array([[-5.0, -1.0], [0.0, 5.0]])), [0.0, p.length], atol=1e-12)


@pytest.mark.parametrize("sense,large,center,length,kappa", [
    ("ccw", False, (0, 0), np.pi / 2, 1), (1, True, (1, 1), 3 * np.pi / 2, 1),
    ("cw", False, (1, 1), np.pi / 2, -1), (-1, True, (0, 0), 3 * np.pi / 2, -1),
])
def test_arc_by_radius(sense, large, center, length, kappa):
    """From (1, 0) to (0, 1) with radius 1: the circles about (0, 0) and (1, 1) pass through both;
    counter-clockwise the one about (0, 0) gives the quarter, about (1, 1) three quarters; clockwise
    the other way round."""
    p = PathProfile((1.0, 0.0), [ArcTo((0.0, 1.0), radius=1.0, sense=sense, large=large)])
    np.testing.assert_allclose(p.length, length, rtol=1e-14)
    np.testing.assert_allclose(curvature(p, np.linspace(0, length, 5)), kappa, rtol=1e-13)
    mid = p.derivatives(np.array([length / 2]), 0)[0, 0]
    np.testing.assert_allclose(np.hypot(*(mid - center)), 1.0, rtol=1e-13)
    np.testing.assert_allclose(p.derivatives(np.array([length]), 0)[0, 0], [0, 1], atol=1e-14)
    # the same arc about its centre
    q = PathProfile((1.0, 0.0), [ArcTo((0.0, 1.0), center=center, sense=sense)])
    u = np.linspace(0, length, 9)
    np.testing.assert_allclose(q.derivatives(u, 3), p.derivatives(u, 3), atol=1e-13)


def test_full_circle_about_a_centre_and_half_circle_by_radius():
    p = PathProfile((3.0, 0.0), [ArcTo((3.0, 0.0), center=(1.0, 0.0), sense="cw")], closed=True)
    np.testing.assert_allclose(p.length, 4 * np.pi, rtol=1e-14)
    np.testing.assert_allclose(curvature(p, np.array([0.0, 3.0])), -0.5, rtol=1e-14)
    assert p.breaks.size == 0  # one smooth circle: its seam is no break
    half = PathProfile((2.0, 0.0), [ArcTo((-2.0, 0.0), radius=2.0)])
    np.testing.assert_allclose(half.length, 2 * np.pi, rtol=1e-12)
    np.testing.assert_allclose(half.derivatives(np.array([np.pi]), 0)[0, 0], [0, 2], atol=1e-7)


def test_square_corners_and_smooth_refusal():
    pts = [(1, 0), (1, 1), (0, 1), (0, 0)]
    sq = PathProfile((0, 0), [LineTo(p) for p in pts], closed=True)
    j = sq.joins()
    np.testing.assert_allclose(j.turn, np.pi / 2, rtol=1e-14)
    np.testing.assert_allclose(sq.breaks, [0, 1, 2, 3], atol=1e-15)  # corners break even at κ = 0
    np.testing.assert_allclose(sq.derivatives(np.array([1.0]), 1, side=-1)[1], [[1, 0]])
    np.testing.assert_allclose(sq.derivatives(np.array([1.0]), 1, side=1)[1], [[0, 1]])
    with pytest.raises(ProfileError, match=r"segment 1 starts with a corner of 90° against segment 0") as e:
        PathProfile((0, 0), [LineTo(p) for p in pts], closed=True, smooth=True)
    assert e.value.index == 1
    # a tangent path is accepted as smooth; a clockwise corner has a negative turn
    PathProfile((0, 0), [LineTo((L, 0)), ArcTo((L, 2 * R), center=(L, R))], smooth=True)
    zig = PathProfile((0, 0), [LineTo((1, 0)), LineTo((2, -1))])
    np.testing.assert_allclose(zig.joins().turn, [-np.pi / 4])
    with pytest.raises(ProfileError, match="corner of -45°"):
        PathProfile((0, 0), [LineTo((1, 0)), LineTo((2, -1))], smooth=True)
    # the seam of a closed path is a join too: segment 0 starts with the corner
    # (a teardrop: line, half circle about (1, 1), then an arc of radius 5/4 about (1, 3/4) back
    # to the start, tangent at (1, 2) but arriving along (0.6, −0.8): a corner of atan2(0.8, 0.6))
    drop = [LineTo((1, 0)), ArcTo((1, 2), center=(1, 1)), ArcTo((0, 0), center=(1, 0.75))]
    np.testing.assert_allclose(PathProfile((0, 0), drop, closed=True).joins().turn, [0, 0, np.arctan2(0.8, 0.6)],
                               atol=1e-14)
    with pytest.raises(ProfileError, match=r"segment 0 starts with a corner of 53.130\d*° against segment 2") as e:
        PathProfile((0, 0), drop, closed=True, smooth=True)
    assert e.value.index == 0


def test_tangent_arc_to_arc_join_with_same_curvature_is_no_break():
    # two quarter arcs of one circle: a join without a jump
    p = PathProfile((1, 0), [ArcTo((0, 1), center=(0, 0)), ArcTo((-1, 0), center=(0, 0))])
    assert p.breaks.size == 0 and len(p.joins().u) == 1
    # an S-curve: the curvature changes sign at a tangent join
    s = PathProfile((0, 0), [ArcTo((2, 0), radius=1.0, sense="cw"), ArcTo((4, 0), radius=1.0, sense="ccw")])
    u, before, after = curvature_jumps(s)
    np.testing.assert_allclose([u[0], before[0], after[0]], [np.pi, -1, 1], rtol=1e-14)
    np.testing.assert_allclose(s.joins().turn, [0.0], atol=1e-14)


@pytest.mark.parametrize("start,segments,closed,message,index", [
    ((0, np.nan), [LineTo((1, 0))], False, "finite start point", None),
    ((0, 0, 0), [LineTo((1, 0))], False, "finite start point", None),
    ((0, 0), [], False, "at least one segment", None),
    ((0, 0), [LineTo((1, 0)), LineTo((np.inf, 0))], False, "segment 1: the end point must be a finite", 1),
    ((0, 0), [LineTo((1, 0)), LineTo((1, 0))], False, "segment 1: a line of zero length", 1),
    ((0, 0), ["up"], False, "segment 0: not a LineTo or ArcTo but str", 0),
    ((0, 0), [ArcTo((1, 1))], False, "either its centre or its radius", 0),
    ((0, 0), [ArcTo((1, 1), center=(1, 0), radius=1)], False, "either its centre or its radius", 0),
    ((0, 0), [ArcTo((2, 0), center=(1, 0), large=True)], False, "'large' applies to an arc given by its radius", 0),
    ((0, 0), [ArcTo((2, 0), center=(1, np.nan))], False, "the centre must be a finite", 0),
    ((0, 0), [ArcTo((2, 0), center=(0, 0))], False, "starts at its centre", 0),
    ((0, 0), [ArcTo((3, 0), center=(1, 0))], False, "not on one circle", 0),
    ((0, 0), [ArcTo((1, 0), radius=0.0)], False, "radius must be positive", 0),
    ((0, 0), [ArcTo((1, 0), radius=-1.0)], False, "radius must be positive", 0),
    ((0, 0), [LineTo((1, 0)), ArcTo((1, 0), radius=1.0)], False, "segment 1: an arc given by its radius needs distinct", 1),
    ((0, 0), [ArcTo((3, 0), radius=1.0)], False, "chord 3 is longer than the diameter 2", 0),
    ((0, 0), [ArcTo((2, 0), radius=1.0, sense="up")], False, "sense must be 'ccw' or 'cw'", 0),
    ((0, 0), [ArcTo((2, 0), radius=1.0, sense=True)], False, "sense must be 'ccw' or 'cw'", 0),
    ((0, 0), [LineTo((1, 0)), LineTo((1, 1))], True, r"closed path must end at its start \[0.0, 0.0\]", 1),
])
def test_bad_paths_are_refused(start, segments, closed, message, index):
    with pytest.raises(ProfileError, match=message) as e:
        PathProfile(start, segments, closed=closed)
    assert e.value.index == index


def test_end_points_met_to_the_tolerance_of_the_figure():
    # an end point a hair off the circle (1e-12 of the figure) is accepted, 1e-6 is not
    PathProfile((100.0, 0.0), [ArcTo((0.0, 100.0 + 1e-10), center=(0.0, 0.0))])
    with pytest.raises(ProfileError, match="not on one circle"):
        PathProfile((100.0, 0.0), [ArcTo((0.0, 100.0 + 1e-4), center=(0.0, 0.0))])
