"""Offset curves: o = c + d·n with n = (y′, −x′)/|c′| the right-hand normal (the sign convention of
the module's docstring), rebuilt here from c′ alone. Its distance to the base is |d|, its tangent
is parallel to the base's, its curvature κ/(1 + dκ) (so a circle's offset by d has radius R + d),
and its cusps lie where 1 + dκ changes sign: on an ellipse offset inward by more than b²/a at the
parameters solved here in closed form, on an involute at the roll angle −d/r."""

from __future__ import annotations

import numpy as np
import pytest

from linkwork.geometry.profiles import (
    ArcTo,
    CircleProfile,
    EllipseProfile,
    InvoluteProfile,
    LineProfile,
    LineTo,
    OffsetProfile,
    PathProfile,
    ProfileError,
    curvature,
    offset_cusps,
)
from profile_checks import (
    assert_derivatives_match_differences,
    brute_nearest_distance,
    quad_length,
    three_point_curvature,
)

A, B = 5.0, 2.0
ELLIPSE = EllipseProfile((1.0, -1.0), (A, B), 0.4)


def ellipse_kappa(u):
    return A * B / (A**2 * np.sin(u) ** 2 + B**2 * np.cos(u) ** 2) ** 1.5


def offset_position(base, u, d):
    c = base.derivatives(u, 1)
    n = np.stack([c[1][..., 1], -c[1][..., 0]], -1) / np.linalg.norm(c[1], axis=-1, keepdims=True)
    return c[0] + d * n


@pytest.mark.parametrize("d", [1.5, -1.5, -2.5])
def test_offset_of_a_circle_is_the_concentric_circle(d):
    base = CircleProfile((2.0, 3.0), 4.0)
    o = OffsetProfile(base, d)
    u = np.linspace(-1.0, 7.0, 17)
    dd = o.derivatives(u, 6)
    # c = C + R e^{iu}: the right-hand normal of a counter-clockwise circle points outwards
    for k in range(7):
        z = (4.0 + d) * 1j**k * np.exp(1j * u) + (complex(2.0, 3.0) if k == 0 else 0)
        np.testing.assert_allclose(dd[k], np.stack([z.real, z.imag], -1), atol=1e-12, err_msg=f"order {k}")
    np.testing.assert_allclose(curvature(o, u), 1 / (4.0 + d), rtol=1e-12)
    assert o.closed and o.domain == base.domain and o.breaks.size == 0
    np.testing.assert_allclose(o.length, 2 * np.pi * abs(4.0 + d), rtol=1e-12)


def test_offset_of_a_circle_inward_beyond_its_centre_runs_backwards_without_cusps():
    o = OffsetProfile(CircleProfile((0.0, 0.0), 1.0), -3.0)  # radius 1 − 3 = −2: the far side
    assert o.cusps.size == 0
    np.testing.assert_allclose(o.derivatives(np.array([0.0]), 0)[0], [[-2.0, 0.0]], atol=1e-14)
    # −2e^{iu} = 2e^{i(u + π)} still turns counter-clockwise: κ = +1/2 = κ/|1 + dκ|, not κ/(1 + dκ)
    np.testing.assert_allclose(curvature(o, np.array([0.3])), 0.5, rtol=1e-12)


@pytest.mark.parametrize("d", [0.8, -0.6, 3.0])
def test_offset_of_an_ellipse(d):
    o = OffsetProfile(ELLIPSE, d)
    u = np.linspace(0, 2 * np.pi, 37)
    np.testing.assert_allclose(o.derivatives(u, 0)[0], offset_position(ELLIPSE, u, d), atol=1e-13)
    assert_derivatives_match_differences(o, u, 5, h=1e-3, rtol=1e-6)
    # o′ = (1 + dκ) c′: parallel tangents, the speed scaled by 1 + dκ
    c1, o1 = ELLIPSE.derivatives(u, 1)[1], o.derivatives(u, 1)[1]
    kappa = ellipse_kappa(u)
    np.testing.assert_allclose(o1, (1 + d * kappa)[:, None] * c1, atol=1e-12)
    # curvature κ/(1 + dκ), checked also through three points of the offset itself
    np.testing.assert_allclose(curvature(o, u), kappa / (1 + d * kappa), rtol=1e-11)
    np.testing.assert_allclose(three_point_curvature(o, u, 1e-3), kappa / (1 + d * kappa), rtol=1e-5)
    # every point of the offset lies |d| from the ellipse (inward only while |d| < b²/a = 0.8)
    p = o.derivatives(u[::4], 0)[0]
    dist = [brute_nearest_distance(ELLIPSE, q, 0, 2 * np.pi) for q in p]
    np.testing.assert_allclose(dist, abs(d), rtol=1e-9)
    # the length: ∫|1 + dκ||c′| (outwards L + 2π d for any convex closed curve)
    if d > 0:
        np.testing.assert_allclose(o.length, ELLIPSE.length + 2 * np.pi * d, rtol=1e-12)
    np.testing.assert_allclose(o.arc_length(np.array([1.0])), quad_length(o, 0, 1.0), rtol=1e-11)
    assert o.cusps.size == 0


def test_cusps_of_an_ellipse_offset_inward():
    """1 + dκ = 0 with κ = ab/(a² sin²u + b² cos²u)^{3/2}: sin²u = ((ab|d|)^{2/3} − b²)/(a² − b²),
    four cusps u, π − u, π + u, 2π − u (for b²/a < |d| < a²/b)."""
    d = -1.5
    s2 = ((A * B * abs(d)) ** (2 / 3) - B**2) / (A**2 - B**2)
    u = np.arcsin(np.sqrt(s2))
    expect = np.array([u, np.pi - u, np.pi + u, 2 * np.pi - u])
    got = offset_cusps(ELLIPSE, d)
    np.testing.assert_allclose(got, expect, atol=1e-12)
    o = OffsetProfile(ELLIPSE, d)
    np.testing.assert_allclose(o.cusps, expect, atol=1e-12)
    # the offset's speed vanishes there; the length integrates |1 + dκ||c′| across the cusps
    np.testing.assert_allclose(np.linalg.norm(o.derivatives(expect, 1)[1], axis=-1), 0, atol=1e-9)
    speed = lambda x: abs(1 + d * ellipse_kappa(x)) * np.hypot(A * np.sin(x), B * np.cos(x))  # noqa: E731
    from scipy.integrate import quad
    pts = np.concatenate([[0.0], expect, [2 * np.pi]])
    total = sum(quad(speed, a, b, epsabs=1e-13, epsrel=1e-13)[0] for a, b in zip(pts[:-1], pts[1:]))
    np.testing.assert_allclose(o.length, total, rtol=1e-11)
    # no cusps within b²/a (0.8) or outward; an inward offset beyond a²/b (12.5) only runs backwards
    assert offset_cusps(ELLIPSE, -0.79).size == 0 and offset_cusps(ELLIPSE, 4.0).size == 0
    assert offset_cusps(ELLIPSE, -13.0).size == 0


def test_cusp_of_an_involute_offset():
    """κ = 1/(r t) for a counter-clockwise involute: 1 + d/(r t) = 0 at t = −d/r."""
    inv = InvoluteProfile((0.0, 0.0), 2.0, 0.0, roll=(0.1, 3.0))
    np.testing.assert_allclose(offset_cusps(inv, -3.0), [1.5], rtol=1e-13)
    assert offset_cusps(inv, 3.0).size == 0
    o = OffsetProfile(inv, -3.0)
    assert not o.closed and o.domain == inv.domain
    assert np.all(np.isnan(o.derivatives(np.array([0.05, 3.5]), 2)))
    t = np.array([0.5, 1.0, 2.0, 2.9])
    # o′ × o″ = (1 + dκ)² c′ × c″ and |o′|³ = |1 + dκ|³|c′|³: κ/|1 + dκ| on both sides of the cusp
    np.testing.assert_allclose(curvature(o, t), (1 / (2 * t)) / np.abs(1 - 3 / (2 * t)), rtol=1e-11)
    np.testing.assert_allclose(three_point_curvature(o, t, 1e-4), (1 / (2 * t)) / np.abs(1 - 3 / (2 * t)), rtol=1e-5)


def test_cusp_at_a_break_and_the_sides():
    """A quarter arc of radius 1 (κ = 1) then a line: offset by d = −2, 1 + dκ is −1 on the arc and
    1 on the line, so the sign changes at the join itself."""
    p = PathProfile((1.0, 0.0), [ArcTo((0.0, 1.0), center=(0.0, 0.0)), LineTo((-3.0, 1.0))])
    j = np.pi / 2
    np.testing.assert_allclose(offset_cusps(p, -2.0), [j], rtol=1e-14)
    np.testing.assert_allclose(offset_cusps(p, -0.5), [], atol=0)
    o = OffsetProfile(p, -0.5)
    np.testing.assert_allclose(o.breaks, p.breaks)
    # at the join: the arc's offset (radius 0.5) before, the line's offset after
    before, after = o.derivatives(np.array([j]), 2, side=-1), o.derivatives(np.array([j]), 2, side=1)
    np.testing.assert_allclose(before[0], after[0], atol=1e-15)
    np.testing.assert_allclose(before[0], [[0.0, 0.5]], atol=1e-15)
    np.testing.assert_allclose(before[1], [[-0.5, 0.0]], atol=1e-15)  # (1 + dκ) c′ = 0.5 (−1, 0)
    np.testing.assert_allclose(after[1], [[-1.0, 0.0]], atol=1e-15)
    np.testing.assert_allclose(before[2], [[0.0, -0.5]], atol=1e-15)
    np.testing.assert_allclose(after[2], [[0.0, 0.0]], atol=1e-15)
    np.testing.assert_allclose(o.length, 0.5 * np.pi / 2 + 3.0, rtol=1e-12)


def test_line_offset_and_bad_distance():
    line = LineProfile((0.0, 0.0), (1.0, 1.0))
    o = OffsetProfile(line, np.sqrt(2))  # right of the direction (1, 1)/√2: (1, −1)
    np.testing.assert_allclose(o.derivatives(np.array([0.0, 2.0]), 1)[0], [[1, -1], [1 + np.sqrt(2), -1 + np.sqrt(2)]],
                               atol=1e-14)
    assert offset_cusps(line, 5.0).size == 0
    for bad in (np.inf, np.nan):
        with pytest.raises(ProfileError, match="offset distance must be finite"):
            OffsetProfile(line, bad)


def test_offset_nearest_and_periodicity():
    o = OffsetProfile(ELLIPSE, 1.0)
    u = np.linspace(0, 2 * np.pi, 11)
    np.testing.assert_allclose(o.derivatives(u + 2 * np.pi, 4), o.derivatives(u, 4), atol=1e-10)
    pts = o.derivatives(u[:-1], 0)[0]
    np.testing.assert_allclose(o.nearest(pts), u[:-1], atol=1e-8)
