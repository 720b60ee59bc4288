"""The closed-form profiles (circle, ellipse, involute, spirals, line, r(φ), c(u)) against their
closed forms written out here, finite differences of the next lower derivative, the circle through
three close points, SciPy's quadrature of the speed and a dense search for the nearest point."""

from __future__ import annotations

import numpy as np
import pytest

from linkwork.geometry.errors import GeometryError
from linkwork.geometry.profiles import (
    ArchimedeanSpiral,
    CircleProfile,
    EllipseProfile,
    InvoluteProfile,
    LineProfile,
    LogarithmicSpiral,
    ParametricProfile,
    PolarProfile,
    Profile,
    ProfileError,
    curvature,
    curvature_jumps,
    derivatives_at,
)
from profile_checks import (
    assert_derivatives_match_differences,
    brute_nearest_distance,
    distance_at,
    quad_length,
    three_point_curvature,
)

ORDER = 6  # closed forms exist to any order: check beyond the engine's usual 4


def xy(z):
    return np.stack([np.real(z), np.imag(z)], -1)


# -- the closed forms, written with complex numbers -------------------------------------------

def circle_closed(center, R, u, k):
    """c = C + R e^{iu}: c⁽ᵏ⁾ = R iᵏ e^{iu} (k ≥ 1)."""
    return xy(R * 1j**k * np.exp(1j * u) + (complex(*center) if k == 0 else 0))


def ellipse_closed(center, a, b, angle, u, k):
    """c = C + e^{iθ}(a cos u + i b sin u); d^k cos u = Re(iᵏ e^{iu}), d^k sin u = Im(iᵏ e^{iu})."""
    w = 1j**k * np.exp(1j * u)
    return xy(np.exp(1j * angle) * (a * w.real + 1j * b * w.imag) + (complex(*center) if k == 0 else 0))


def involute_ccw_closed(center, r, alpha0, t, k):
    """c = C + r e^{iα₀}(cos t + t sin t, sin t − t cos t), with (Leibniz)
    dᵏ[t sin t] = t sin(t + kπ/2) + k sin(t + (k−1)π/2), dᵏ[t cos t] likewise with cos."""
    q = k * np.pi / 2
    x = np.cos(t + q) + t * np.sin(t + q) + k * np.sin(t + q - np.pi / 2)
    y = np.sin(t + q) - t * np.cos(t + q) - k * np.cos(t + q - np.pi / 2)
    return xy(np.exp(1j * alpha0) * r * (x + 1j * y) + (complex(*center) if k == 0 else 0))


def archimedes_closed(center, r0, rate, phi0, phi, k):
    """c = C + r e^{iφ}, r = r₀ + m(φ − φ₀): c⁽ᵏ⁾ = r iᵏ e^{iφ} + k m i^{k−1} e^{iφ}."""
    r = r0 + rate * (phi - phi0)
    z = r * 1j**k * np.exp(1j * phi) + k * rate * 1j ** (k - 1) * np.exp(1j * phi)
    return xy(z + (complex(*center) if k == 0 else 0))


def log_spiral_closed(center, r0, b, phi0, phi, k):
    """c = C + r₀ e^{(b + i)(φ − φ₀)} e^{iφ₀}: c⁽ᵏ⁾ = (b + i)ᵏ r e^{iφ}."""
    z = (b + 1j) ** k * r0 * np.exp(b * (phi - phi0)) * np.exp(1j * phi)
    return xy(z + (complex(*center) if k == 0 else 0))


def assert_closed_form(profile, u, closed_form, max_order=ORDER, rtol=1e-12):
    d = profile.derivatives(u, max_order)
    assert d.shape == (max_order + 1,) + np.shape(u) + (2,)
    for k in range(max_order + 1):
        expect = closed_form(u, k)
        np.testing.assert_allclose(d[k], expect, rtol=0, atol=rtol * max(1.0, np.max(np.abs(expect))),
                                   err_msg=f"order {k}")


# -- circle ------------------------------------------------------------------------------------

CIRCLE = CircleProfile((3.0, -2.0), 7.5)


def test_circle_derivatives_closed_form_and_differences():
    u = np.linspace(-7.0, 13.0, 41)
    assert_closed_form(CIRCLE, u, lambda x, k: circle_closed((3.0, -2.0), 7.5, x, k))
    assert_derivatives_match_differences(CIRCLE, u, ORDER, h=1e-3)
    assert isinstance(CIRCLE, Profile)


def test_circle_curvature_length_nearest():
    u = np.linspace(0, 2 * np.pi, 13)
    np.testing.assert_allclose(curvature(CIRCLE, u), 1 / 7.5, rtol=1e-13)
    np.testing.assert_allclose(three_point_curvature(CIRCLE, u, 1e-3), 1 / 7.5, rtol=1e-6)
    np.testing.assert_allclose(CIRCLE.arc_length(np.array([1.0, 2 * np.pi])), [7.5, 15 * np.pi], rtol=1e-14)
    np.testing.assert_allclose(quad_length(CIRCLE, 0, 2.5), 7.5 * 2.5, rtol=1e-12)
    p = np.array([[10.0, 5.0], [-4.0, -2.0], [3.0, 1.0]])  # the nearest point lies on the ray from C
    np.testing.assert_allclose(CIRCLE.nearest(p), [np.pi / 4, np.pi, np.pi / 2], atol=1e-14)
    unit = CircleProfile((0.0, 0.0), 1.0)
    np.testing.assert_allclose(unit.nearest(np.array([[1.0, 1.0]])), [np.pi / 4])
    # non-finite input is marked, not answered: NaN (and no warning)
    assert np.all(np.isnan(unit.nearest(np.array([[np.nan, 0.0], [np.inf, 0.0]]))))
    assert np.all(np.isnan(unit.derivatives(np.array([np.inf, -np.inf, np.nan]), 2)))
    assert np.all(np.isnan(unit.arc_length(np.array([np.inf, np.nan]))))
    with pytest.raises(GeometryError, match=r"shape \(\.\.\., 2\)"):
        unit.nearest(np.zeros(3))


@pytest.mark.parametrize("center,radius", [((0, 0), 0.0), ((0, 0), -1.0), ((0, 0), np.inf), ((np.nan, 0), 1.0)])
def test_circle_refuses_bad_data(center, radius):
    with pytest.raises(GeometryError, match="circle profile needs"):
        CircleProfile(center, radius)


@pytest.mark.parametrize("order", [-1, 1.5, True, "2"])
def test_order_must_be_a_non_negative_integer(order):
    for profile in (CIRCLE, EllipseProfile((0, 0), (2, 1))):
        with pytest.raises(GeometryError, match="derivative order must be a non-negative integer"):
            profile.derivatives(np.array([0.1]), order)


@pytest.mark.parametrize("side", [0, 2, True, "left"])
def test_side_must_be_plus_or_minus_one(side):
    for profile in (CIRCLE, EllipseProfile((0, 0), (2, 1))):
        with pytest.raises(GeometryError, match="side must be"):
            profile.derivatives(np.array([0.1]), 1, side=side)


def test_numpy_integer_order_and_shapes():
    u = np.zeros((3, 4))
    assert CIRCLE.derivatives(u, np.int64(2)).shape == (3, 3, 4, 2)
    assert EllipseProfile((0, 0), (2, 1)).derivatives(u, 0).shape == (1, 3, 4, 2)
    assert EllipseProfile((0, 0), (2, 1)).derivatives(0.5, 3).shape == (4, 2)


# -- ellipse -----------------------------------------------------------------------------------

A, B, TH = 5.0, 2.0, 0.7
ELLIPSE = EllipseProfile((1.0, 2.0), (A, B), TH)


def ellipse_kappa(u, a=A, b=B):
    return a * b / (a**2 * np.sin(u) ** 2 + b**2 * np.cos(u) ** 2) ** 1.5


def test_ellipse_derivatives_closed_form_and_differences():
    u = np.linspace(-3.0, 9.0, 37)
    assert_closed_form(ELLIPSE, u, lambda x, k: ellipse_closed((1.0, 2.0), A, B, TH, x, k))
    assert_derivatives_match_differences(ELLIPSE, u, ORDER, h=1e-3)


def test_ellipse_curvature_closed_form_and_osculating_circle():
    u = np.linspace(0, 2 * np.pi, 50)
    np.testing.assert_allclose(curvature(ELLIPSE, u), ellipse_kappa(u), rtol=1e-12)
    np.testing.assert_allclose(three_point_curvature(ELLIPSE, u, 1e-3), ellipse_kappa(u), rtol=1e-5)
    # the extremes: a/b² at the vertices of the major axis, b/a² at those of the minor axis
    np.testing.assert_allclose(curvature(ELLIPSE, np.array([0.0, np.pi / 2])), [A / B**2, B / A**2], rtol=1e-13)


def test_ellipse_length_against_quadrature():
    u = np.array([0.3, 1.7, 4.0, 2 * np.pi])
    expect = [quad_length(ELLIPSE, 0.0, x) for x in u]
    np.testing.assert_allclose(ELLIPSE.arc_length(u), expect, rtol=1e-12)
    np.testing.assert_allclose(ELLIPSE.length, expect[-1], rtol=1e-12)
    # whole turns add whole lengths; negative parameters count backwards
    np.testing.assert_allclose(ELLIPSE.arc_length(u + 4 * np.pi), np.array(expect) + 2 * ELLIPSE.length, rtol=1e-12)
    np.testing.assert_allclose(ELLIPSE.arc_length(np.array([-0.5])), [-quad_length(ELLIPSE, 2 * np.pi - 0.5, 2 * np.pi)],
                               rtol=1e-12)


def test_ellipse_periodicity_and_seam():
    u = np.linspace(0, 2 * np.pi, 17)
    d = ELLIPSE.derivatives(u, 4)
    for turns in (-3, -1, 1, 5):
        np.testing.assert_allclose(ELLIPSE.derivatives(u + turns * 2 * np.pi, 4), d, rtol=0, atol=1e-11)
    # the seam: u = 2π is u = 0, and just below it the curve comes back to the start
    np.testing.assert_allclose(ELLIPSE.derivatives(np.array([2 * np.pi]), 4), ELLIPSE.derivatives(np.array([0.0]), 4),
                               atol=1e-12)
    below = ELLIPSE.derivatives(np.array([2 * np.pi - 1e-9]), 4)
    np.testing.assert_allclose(below, ELLIPSE.derivatives(np.array([0.0]), 4), atol=1e-7 * A)
    assert np.all(np.isnan(ELLIPSE.derivatives(np.array([np.nan, np.inf]), 2)))
    assert np.all(np.isnan(ELLIPSE.arc_length(np.array([np.nan]))))


def test_ellipse_nearest_against_dense_search():
    rng = np.random.default_rng(4)
    p = rng.uniform(-8, 8, size=(40, 2)) + [1.0, 2.0]
    u = ELLIPSE.nearest(p)
    assert np.all((u >= 0) & (u < 2 * np.pi))
    brute = np.array([brute_nearest_distance(ELLIPSE, q, 0, 2 * np.pi) for q in p])
    np.testing.assert_allclose(distance_at(ELLIPSE, u, p), brute, atol=1e-9)
    # a point on the curve is found at its own parameter
    u0 = np.array([0.0, 1.0, 3.0, 6.0])
    np.testing.assert_allclose(ELLIPSE.nearest(ELLIPSE.derivatives(u0, 0)[0]), u0, atol=1e-9)
    out = ELLIPSE.nearest(np.array([[np.nan, 0.0], [1.0, 2.5], [np.inf, 1.0]]))
    assert np.isnan(out[0]) and np.isfinite(out[1]) and np.isnan(out[2])
    with pytest.raises(GeometryError, match=r"shape \(\.\.\., 2\)"):
        ELLIPSE.nearest(np.zeros((3, 3)))


@pytest.mark.parametrize("args,message", [
    (((0, 0), (0, 1)), "semi-axis a"), (((0, 0), (1, -1)), "semi-axis b"), (((0, np.nan), (1, 1)), "centre"),
    (((0, 0, 0), (1, 1)), "centre"), (((0, 0), (1, 1), np.inf), "angle"),
])
def test_ellipse_refuses_bad_data(args, message):
    with pytest.raises(ProfileError, match=message):
        EllipseProfile(*args)


# -- involute ----------------------------------------------------------------------------------

R_BASE, ALPHA0 = 4.0, 0.3
INVOLUTE = InvoluteProfile((1.0, -1.0), R_BASE, ALPHA0, roll=(0.0, 3.0))


def test_involute_derivatives_closed_form_and_differences():
    t = np.linspace(0.0, 3.0, 31)
    assert_closed_form(INVOLUTE, t, lambda x, k: involute_ccw_closed((1.0, -1.0), R_BASE, ALPHA0, x, k))
    assert_derivatives_match_differences(INVOLUTE, t[1:-1], ORDER, h=1e-3)


def test_involute_clockwise_is_the_mirror_image():
    """Unwinding clockwise from α₀ is the counter-clockwise involute from −α₀ mirrored in the x-axis."""
    cw = InvoluteProfile((0.0, 0.0), R_BASE, ALPHA0, roll=(0.5, 2.5), sense=-1)
    t = np.linspace(0.5, 2.5, 21)
    mirror = np.array([1.0, -1.0])
    assert_closed_form(cw, t, lambda x, k: involute_ccw_closed((0.0, 0.0), R_BASE, -ALPHA0, x, k) * mirror)
    np.testing.assert_allclose(curvature(cw, t), -1 / (R_BASE * t), rtol=1e-12)


def test_involute_string_property():
    """The string unwound from the base circle: the tangent from c(t) to the circle touches it at
    the angle α₀ + t, is r·t long and is normal to the involute."""
    t = np.linspace(0.1, 3.0, 12)
    d = INVOLUTE.derivatives(t, 1)
    touch = np.array([1.0, -1.0]) + R_BASE * np.stack([np.cos(ALPHA0 + t), np.sin(ALPHA0 + t)], -1)
    string = d[0] - touch
    np.testing.assert_allclose(np.linalg.norm(string, axis=-1), R_BASE * t, rtol=1e-13)
    np.testing.assert_allclose(np.sum(string * d[1], axis=-1), 0, atol=1e-12)


def test_involute_curvature_and_length():
    t = np.linspace(0.2, 3.0, 15)
    np.testing.assert_allclose(curvature(INVOLUTE, t), 1 / (R_BASE * t), rtol=1e-12)
    np.testing.assert_allclose(three_point_curvature(INVOLUTE, t[:-1], 1e-4), 1 / (R_BASE * t[:-1]), rtol=1e-5)
    np.testing.assert_allclose(INVOLUTE.arc_length(t), R_BASE * t**2 / 2, rtol=1e-14)
    np.testing.assert_allclose([quad_length(INVOLUTE, 0, x) for x in t], R_BASE * t**2 / 2, rtol=1e-11)
    later = InvoluteProfile((0, 0), R_BASE, 0.0, roll=(1.0, 2.0))
    np.testing.assert_allclose(later.arc_length(np.array([1.5])), R_BASE * (1.5**2 - 1) / 2, rtol=1e-14)
    np.testing.assert_allclose(later.length, R_BASE * (4 - 1) / 2, rtol=1e-12)  # the quadrature of BaseProfile


def test_involute_is_open():
    t = np.array([-0.1, 3.1, np.nan, 0.0, 3.0])
    d = INVOLUTE.derivatives(t, 3)
    assert np.all(np.isnan(d[:, :3])) and np.all(np.isfinite(d[:, 3:]))
    assert np.all(np.isnan(INVOLUTE.arc_length(t[:3])))
    assert not INVOLUTE.closed and INVOLUTE.domain == (0.0, 3.0)


def test_involute_nearest_stays_in_domain():
    rng = np.random.default_rng(7)
    p = rng.uniform(-15, 15, size=(30, 2))
    u = INVOLUTE.nearest(p)
    assert np.all((u >= 0) & (u <= 3.0))
    brute = np.array([brute_nearest_distance(INVOLUTE, q, 0, 3.0) for q in p])
    np.testing.assert_allclose(distance_at(INVOLUTE, u, p), brute, atol=1e-9)


@pytest.mark.parametrize("kw,message", [
    (dict(base_radius=0), "base radius"), (dict(roll=(-1, 2)), "start at 0 or later"),
    (dict(roll=(2, 1)), "two finite increasing"), (dict(roll=(0, np.inf)), "two finite increasing"),
    (dict(sense=0), "sense is"), (dict(start_angle=np.nan), "start angle"), (dict(center=(0, np.inf)), "centre"),
])
def test_involute_refuses_bad_data(kw, message):
    args = dict(center=(0, 0), base_radius=1.0) | kw
    with pytest.raises(ProfileError, match=message):
        InvoluteProfile(**args)


# -- spirals -----------------------------------------------------------------------------------

@pytest.mark.parametrize("pitch", [6.0, -3.0])
def test_archimedean_spiral(pitch):
    r0, phi0, phi1 = 5.0, 0.5, 0.5 + 2.5 * np.pi
    s = ArchimedeanSpiral((2.0, 1.0), r0, pitch, (phi0, phi1))
    m = pitch / (2 * np.pi)
    phi = np.linspace(phi0, phi1, 29)
    assert_closed_form(s, phi, lambda x, k: archimedes_closed((2.0, 1.0), r0, m, phi0, x, k))
    assert_derivatives_match_differences(s, phi[1:-1], ORDER, h=1e-3)
    r = r0 + m * (phi - phi0)
    # polar curvature (r² + 2r′² − r r″)/(r² + r′²)^{3/2} with r′ = m, r″ = 0
    kappa = (r**2 + 2 * m**2) / (r**2 + m**2) ** 1.5
    np.testing.assert_allclose(curvature(s, phi), kappa, rtol=1e-12)
    np.testing.assert_allclose(three_point_curvature(s, phi[1:-1], 1e-4), kappa[1:-1], rtol=1e-5)

    def F(rho):  # ∫ √(ρ² + m²) dρ / m
        q = np.sqrt(rho**2 + m**2)
        return (rho * q + m**2 * np.log(rho + q)) / (2 * m)
    np.testing.assert_allclose(s.arc_length(phi), F(r) - F(r0), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(s.arc_length(phi[7:8]), quad_length(s, phi0, phi[7]), rtol=1e-12)
    assert np.all(np.isnan(s.derivatives(np.array([phi0 - 1e-9, phi1 + 1e-9]), 2)))


def test_archimedean_spiral_refuses_a_radius_through_zero():
    with pytest.raises(ProfileError, match="radius must stay positive"):
        ArchimedeanSpiral((0, 0), 5.0, -10.0, (0.0, 2 * np.pi))  # runs to 5 − 10 = −5
    with pytest.raises(ProfileError, match="finite start radius and pitch"):
        ArchimedeanSpiral((0, 0), 5.0, np.inf, (0.0, 1.0))
    with pytest.raises(ProfileError, match="two finite increasing"):
        ArchimedeanSpiral((0, 0), 5.0, 1.0, (1.0, 1.0))


@pytest.mark.parametrize("pitch_angle", [0.3, -0.2, 0.0])
def test_logarithmic_spiral(pitch_angle):
    r0, phi0, phi1 = 3.0, -0.4, 4.0
    s = LogarithmicSpiral((0.5, 0.5), r0, pitch_angle, (phi0, phi1))
    b = np.tan(pitch_angle)
    phi = np.linspace(phi0, phi1, 23)
    assert_closed_form(s, phi, lambda x, k: log_spiral_closed((0.5, 0.5), r0, b, phi0, x, k))
    assert_derivatives_match_differences(s, phi[1:-1], ORDER, h=1e-3)
    r = r0 * np.exp(b * (phi - phi0))
    np.testing.assert_allclose(curvature(s, phi), 1 / (r * np.sqrt(1 + b**2)), rtol=1e-12)
    np.testing.assert_allclose(three_point_curvature(s, phi[1:-1], 1e-4), 1 / (r[1:-1] * np.sqrt(1 + b**2)), rtol=1e-5)
    # s = √(1 + b²)(r − r₀)/b, the circle's r₀(φ − φ₀) when b = 0
    expect = np.sqrt(1 + b**2) * (r - r0) / b if b else r0 * (phi - phi0)
    np.testing.assert_allclose(s.arc_length(phi), expect, rtol=1e-12, atol=1e-13)
    # the constant angle between the tangent and the circle about the centre
    d = s.derivatives(phi, 1)
    radial = d[0] - [0.5, 0.5]
    cosang = np.sum(radial * d[1], axis=-1) / np.linalg.norm(radial, axis=-1) / np.linalg.norm(d[1], axis=-1)
    np.testing.assert_allclose(np.arcsin(cosang), pitch_angle, atol=1e-12)


@pytest.mark.parametrize("kw,message", [
    (dict(start_radius=0.0), "start radius"), (dict(pitch_angle=np.pi / 2), "between -90° and 90°"),
    (dict(pitch_angle=np.nan), "between -90° and 90°"), (dict(angles=(1.0, 0.0)), "two finite increasing"),
])
def test_logarithmic_spiral_refuses_bad_data(kw, message):
    args = dict(center=(0, 0), start_radius=1.0, pitch_angle=0.1, angles=(0.0, 1.0)) | kw
    with pytest.raises(ProfileError, match=message):
        LogarithmicSpiral(**args)


# -- line --------------------------------------------------------------------------------------

def test_line():
    line = LineProfile((1.0, 2.0), (3.0, 4.0))
    e = np.array([0.6, 0.8])
    u = np.array([-1e6, -2.5, 0.0, 7.0])
    d = line.derivatives(u, 5)
    np.testing.assert_allclose(d[0], [1.0, 2.0] + u[:, None] * e, rtol=1e-15)
    np.testing.assert_allclose(d[1], np.broadcast_to(e, (4, 2)), rtol=1e-15)
    assert np.all(d[2:] == 0)
    assert_derivatives_match_differences(line, u[1:], 5, h=1e-2)
    np.testing.assert_array_equal(curvature(line, u), 0.0)
    np.testing.assert_allclose(line.arc_length(u), u)
    assert np.isnan(line.arc_length(np.array([np.inf]))[0]) and line.length == np.inf
    p = np.array([[5.0, 0.0], [1.0, 2.0], [-4.0, 3.0]])
    np.testing.assert_allclose(line.nearest(p), (p - [1.0, 2.0]) @ e, rtol=1e-15)
    assert np.all(np.isnan(line.derivatives(np.array([np.nan, np.inf]), 1)))
    with pytest.raises(ProfileError, match="zero vector"):
        LineProfile((0, 0), (0, 0))
    with pytest.raises(ProfileError, match="direction"):
        LineProfile((0, 0), (np.nan, 1))
    with pytest.raises(ProfileError, match=r"shape \(\.\.\., 2\)"):
        line.nearest(np.zeros(3))


# -- r(φ) and c(u) given by code -----------------------------------------------------------------

def test_polar_profile_of_a_circle_through_the_pole():
    """r = 2R cos φ on (−π/2, π/2) is the circle about (R, 0) of radius R traversed twice as fast:
    c = R(1 + cos 2φ, sin 2φ), so c⁽ⁿ⁾ = R 2ⁿ e^{i(2φ + nπ/2)} (n ≥ 1) and κ = 1/R."""
    R = 3.0

    def radius(phi, order):
        return np.stack([2 * R * np.cos(phi + j * np.pi / 2) for j in range(order + 1)])

    p = PolarProfile(radius, domain=(-np.pi / 2, np.pi / 2), closed=False)
    phi = np.linspace(-1.5, 1.5, 31)
    assert_closed_form(p, phi, lambda x, k: xy((R if k == 0 else 0) + R * 2.0**k * 1j**k * np.exp(2j * x)))
    assert_derivatives_match_differences(p, phi, ORDER, h=1e-3)
    np.testing.assert_allclose(curvature(p, phi), 1 / R, rtol=1e-12)
    np.testing.assert_allclose(p.arc_length(phi), 2 * R * (phi + np.pi / 2), rtol=1e-12)


def test_polar_profile_closed_and_sided():
    """A closed r(φ) = 4 + cos 3φ; a radius function with a kink at a break answers each side."""
    def radius(phi, order):
        return np.stack([(4.0 if j == 0 else 0.0) + 3.0**j * np.cos(3 * phi + j * np.pi / 2) for j in range(order + 1)])

    p = PolarProfile(radius, center=(1.0, 1.0))
    phi = np.linspace(0, 2 * np.pi, 25)
    assert_derivatives_match_differences(p, phi, 5, h=1e-3)
    np.testing.assert_allclose(p.derivatives(phi + 2 * np.pi, 4), p.derivatives(phi, 4), atol=1e-11)
    np.testing.assert_allclose(p.arc_length(np.array([2 * np.pi])), quad_length(p, 0, 2 * np.pi), rtol=1e-12)

    def kinked(phi, order, side=1):  # r = 5 + |φ − 1|: slope −1 before φ = 1, +1 after
        out = np.zeros((order + 1,) + phi.shape)
        out[0] = 5 + np.abs(phi - 1)
        if order:
            out[1] = np.where(phi > 1, 1.0, np.where(phi < 1, -1.0, float(side)))
        return out

    q = PolarProfile(kinked, domain=(0.0, 2.0), closed=False, breaks=[1.0], sided=True)
    np.testing.assert_array_equal(q.breaks, [1.0])
    plus, minus = q.derivatives(np.array([1.0]), 1, side=1)[1, 0], q.derivatives(np.array([1.0]), 1, side=-1)[1, 0]
    # c′ = r′ e^{iφ} + r i e^{iφ} at φ = 1 with r = 5, r′ = ±1
    e = np.array([np.cos(1.0), np.sin(1.0)])
    n = np.array([-np.sin(1.0), np.cos(1.0)])
    np.testing.assert_allclose(plus, e + 5 * n, rtol=1e-14)
    np.testing.assert_allclose(minus, -e + 5 * n, rtol=1e-14)
    np.testing.assert_allclose(derivatives_at(q, np.array([1.0]), 1, -1)[1, 0], minus)


def test_polar_profile_refuses_bad_functions():
    with pytest.raises(ProfileError, match="callable radius"):
        PolarProfile(3.0)
    bad = PolarProfile(lambda phi, order: np.ones(phi.shape))
    with pytest.raises(ProfileError, match="must return shape"):
        bad.derivatives(np.array([0.1, 0.2]), 1)


def test_parametric_profile_of_an_ellipse():
    """c(u) given by code: the wrapping, the breaks and the arc length come from BaseProfile."""
    fn = lambda u, order: np.stack([ellipse_closed((0, 0), 3.0, 1.0, 0.0, u, k) for k in range(order + 1)])  # noqa: E731
    p = ParametricProfile(fn, (0.0, 2 * np.pi), closed=True, breaks=[2.0, 1.0], pieces=16)
    np.testing.assert_array_equal(p.breaks, [1.0, 2.0])
    u = np.array([-1.0, 0.5, 7.0])
    assert_closed_form(p, u, lambda x, k: ellipse_closed((0, 0), 3.0, 1.0, 0.0, x, k), max_order=4)
    np.testing.assert_allclose(p.length, quad_length(p, 0, 2 * np.pi), rtol=1e-12)
    np.testing.assert_allclose(curvature(p, u), ellipse_kappa(u, 3.0, 1.0), rtol=1e-12)
    ju, before, after = curvature_jumps(p)  # a smooth curve given breaks: both sides agree
    np.testing.assert_allclose(before, after)
    open_p = ParametricProfile(fn, (0.0, 1.0))
    assert np.all(np.isnan(open_p.derivatives(np.array([1.5]), 2)))
    with pytest.raises(ProfileError, match="callable fn"):
        ParametricProfile(None, (0, 1))
    with pytest.raises(ProfileError, match="must return shape"):
        ParametricProfile(lambda u, order: np.zeros((order + 1, 2)), (0, 1)).derivatives(np.array([0.5, 0.6]), 1)


def test_profile_from_outside_the_package_gets_side_only_when_asked():
    class Plain:  # a profile that knows nothing of sides
        closed, domain, breaks = True, (0.0, 2 * np.pi), np.empty(0)

        def derivatives(self, u, order):
            return CIRCLE.derivatives(u, order)

    u = np.array([0.3])
    np.testing.assert_allclose(curvature(Plain(), u), 1 / 7.5)
    np.testing.assert_allclose(derivatives_at(Plain(), u, 3), CIRCLE.derivatives(u, 3))
