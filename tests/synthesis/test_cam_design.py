"""The design analyses of `linkwork.synthesis.cams` against second methods: the pressure angle of
a translating roller follower in closed form (written out by hand), the radius of curvature by
osculating circles through sampled profile points, cusps where the pitch curve's osculating
circle equals the roller, the smallest base circle by bisection on the largest pressure angle
(and checked on the engine's contact report)."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from cam_laws_by_hand import program_by_hand
from linkwork.model.disc_cams import DiscCam
from linkwork.model.motion_programs import CamDesignError, MotionProgram, Segment
from linkwork.synthesis import (analyse, cusps, follower_diagrams, mechanism_text, pressure_angle,
                                radius_of_curvature, smallest_base_radius, with_base_radius)

SEGS = [("rise", 100.0, 25.0, "cycloidal"), ("dwell", 50.0, 0.0, None),
        ("return", 150.0, 25.0, "modified-trapezoid"), ("dwell", 60.0, 0.0, None)]
PHI = np.radians(np.arange(0.21, 360.0, 0.5))


def program(segs=SEGS):
    return MotionProgram([Segment(k, np.radians(e), lift, lw) for k, e, lift, lw in segs])


def osculating_radius(points: np.ndarray) -> np.ndarray:
    """Signed radius of the circle through three consecutive points (prev, this, next) of a
    curve traced clockwise: positive where it bends clockwise (a convex part of a cam traced
    clockwise), negative where it bends the other way."""
    a, b, c = points
    ab, bc, ca = np.hypot(*(b - a).T), np.hypot(*(c - b).T), np.hypot(*(a - c).T)
    cross = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]
    return -ab * bc * ca / (2 * cross)


def sample_three(profile, phi, h=1e-4):
    return np.stack([profile.derivatives(phi + d, 0)[0] for d in (-h, 0.0, h)])


@pytest.mark.parametrize("offset", [0.0, 7.5, -4.0])
def test_pressure_angle_of_a_translating_roller_in_closed_form(offset):
    """tan α = (s′ − ε)/(√(R₀² − ε²) + s) (centric: s′/(R₀ + s)), s from the laws by hand."""
    Rb, rho = 35.0, 6.0
    cam = DiscCam(program(), "roller", Rb, roller_radius=rho, offset=offset)
    s, s1, _, _ = program_by_hand(SEGS, PHI)
    want = np.arctan((s1 - offset) / (np.sqrt((Rb + rho) ** 2 - offset**2) + s))
    np.testing.assert_allclose(pressure_angle(cam, PHI), want, atol=1e-12)


@pytest.mark.parametrize("kind", ["roller", "knife", "flat", "oscillating roller", "oscillating flat"])
def test_radius_of_curvature_by_osculating_circles(kind):
    kw = {"roller": dict(follower="roller", roller_radius=6.0),
          "knife": dict(follower="knife", offset=3.0),
          "flat": dict(follower="flat"),
          "oscillating roller": dict(follower="roller", roller_radius=6.0, motion="oscillating",
                                     pivot=(70.0, 30.0), arm=55.0),
          "oscillating flat": dict(follower="flat", motion="oscillating", pivot=(80.0, 0.0), face_offset=-3.0)}[kind]
    segs = SEGS if "oscillating" not in kind else [(k, e, np.radians(10.0) if lift else 0.0, lw) for k, e, lift, lw in SEGS]
    cam = DiscCam(program(segs), base_radius=35.0, **kw)
    R = radius_of_curvature(cam, PHI)
    Rs = osculating_radius(sample_three(cam.profile, PHI))
    # compared as curvatures: near an inflection the radius grows without bound
    np.testing.assert_allclose(1 / R, 1 / Rs, rtol=1e-5, atol=1e-8)
    if kind == "flat":
        s, _, s2, _ = program_by_hand(SEGS, PHI)
        np.testing.assert_allclose(R, 35.0 + s + s2, atol=1e-10)  # R_b + s + s″
    # on the base circle (dwell at lift 0) the profile is the base circle
    rest = (PHI > np.radians(300.5)) & (PHI < np.radians(359.5))
    np.testing.assert_allclose(R[rest], 35.0, atol=1e-9)


def test_roller_cusps_where_the_pitch_curve_bends_as_the_roller():
    """A steep rise on a small base circle and a big roller: the profile has cusps exactly where
    the pitch curve's osculating circle (from sampled points) has the roller's radius, and
    between them the profile runs backwards (undercut)."""
    segs = [("rise", 40.0, 30.0, "cycloidal"), ("dwell", 40.0, 0.0, None), ("return", 60.0, 30.0, "3-4-5"),
            ("dwell", 220.0, 0.0, None)]
    rho = 14.0
    cam = DiscCam(program(segs), "roller", 12.0, roller_radius=rho)
    cut = cusps(cam)
    assert cut.size >= 2 and cut.size % 2 == 0
    Rp = osculating_radius(sample_three(cam.pitch_curve, cut))
    np.testing.assert_allclose(Rp, rho, rtol=1e-5)
    rep = analyse(cam)
    assert rep.undercut.any()
    inside = rep.phi[rep.undercut]
    mid = inside[len(inside) // 2]
    # the profile runs against the pitch curve there
    t_pitch = cam.pitch_curve.derivatives(np.array([mid]), 1)[1][0]
    step = cam.profile.derivatives(np.array([mid + 1e-5]), 0)[0][0] - cam.profile.derivatives(np.array([mid]), 0)[0][0]
    assert step @ t_pitch < 0
    # a big enough base circle has none
    assert cusps(with_base_radius(cam, 60.0)).size == 0


def test_flat_face_cusps_where_its_radius_vanishes():
    """R = R_b + s + s″ by hand: the cusps are its zeros."""
    segs = [("rise", 60.0, 30.0, "harmonic"), ("return", 60.0, 30.0, "harmonic"), ("dwell", 240.0, 0.0, None)]
    cam = DiscCam(program(segs), "flat", 20.0)
    got = cusps(cam)
    phi = np.radians(np.linspace(0, 360, 360001))
    s, _, s2, _ = program_by_hand(segs, phi)
    R = 20.0 + s + s2
    sign_change = phi[:-1][np.sign(R[:-1]) * np.sign(R[1:]) < 0]
    # harmonic laws jump in acceleration at 0° and 60°: a sign change across a join counts too
    assert got.size == sign_change.size > 0
    np.testing.assert_allclose(got, sign_change, atol=np.radians(0.002))


def _max_alpha_by_hand(segs, Rp, eps, phi):
    s, s1, _, _ = program_by_hand(segs, phi)
    return np.max(np.abs(np.arctan((s1 - eps) / (np.sqrt(Rp**2 - eps**2) + s))))


@pytest.mark.parametrize("offset", [0.0, 8.0])
def test_smallest_base_radius_translating_roller(offset):
    """Closed form against bisection on the largest pressure angle (hand formula, 0.002°
    samples), then checked on the engine's contact report of the designed mechanism."""
    rho, amax = 5.0, np.radians(30.0)
    cam = DiscCam(program(), "roller", 50.0, roller_radius=rho, offset=offset)
    rb = smallest_base_radius(cam, max_pressure_angle=amax)
    phi = np.radians(np.arange(0.0, 360.0, 0.002))
    lo, hi = 1.0, 200.0
    for _ in range(60):
        mid = (lo + hi) / 2
        if _max_alpha_by_hand(SEGS, mid + rho, offset, phi) > amax:
            lo = mid
        else:
            hi = mid
    assert rb == pytest.approx(hi, rel=1e-6)
    designed = with_base_radius(cam, rb)
    sol = linkwork.solve(linkwork.load_text(mechanism_text(designed)), PHI)
    moving = np.abs(program_by_hand(SEGS, PHI)[1]) > 1e-6  # the engine's angle needs a velocity
    got = np.max(sol.joint("K")["pressure_angle"][moving])
    assert got == pytest.approx(amax, abs=1e-4) and got <= amax + 1e-9


def test_smallest_base_radius_oscillating_roller():
    """No closed form: the scan-and-Brent result is checked on the engine: its largest
    pressure angle is the limit there, and a base circle 0.5 % smaller exceeds it."""
    segs = [(k, e, np.radians(14.0) if lift else 0.0, lw) for k, e, lift, lw in SEGS]
    cam = DiscCam(program(segs), "roller", 40.0, roller_radius=6.0, motion="oscillating",
                  pivot=(90.0, 20.0), arm=70.0)
    amax = np.radians(35.0)
    rb = smallest_base_radius(cam, max_pressure_angle=amax)
    phi = np.radians(np.arange(0.13, 360.0, 0.25))
    moving = np.abs(program_by_hand(segs, phi)[1]) > 1e-6  # the engine's angle needs a velocity
    peaks = []
    for r in (rb, rb * 0.995):
        sol = linkwork.solve(linkwork.load_text(mechanism_text(with_base_radius(cam, r))), phi)
        peaks.append(np.max(sol.joint("K")["pressure_angle"][moving]))
    assert peaks[0] == pytest.approx(amax, abs=2e-4) and peaks[0] <= amax + 1e-9
    assert peaks[1] > amax


def test_smallest_base_radius_flat_face_by_curvature():
    """R_b ≥ ρ_min − min(s + s″), against bisection on the hand formula."""
    cam = DiscCam(program(), "flat", 10.0)
    rb = smallest_base_radius(cam, min_radius_of_curvature=3.0)
    phi = np.radians(np.arange(0.0, 360.0, 0.001))
    s, _, s2, _ = program_by_hand(SEGS, phi)
    lo, hi = 0.0, 500.0
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if np.min(mid + s + s2) < 3.0 else (lo, mid)
    assert rb == pytest.approx(hi, rel=1e-7)
    rep = analyse(with_base_radius(cam, rb))
    assert rep.min_radius_of_curvature == pytest.approx(3.0, rel=1e-4)
    assert cusps(with_base_radius(cam, rb)).size == 0


def test_diagrams_scale_with_the_cam_speed():
    cam = DiscCam(program(), "knife", 30.0)
    w = 2 * np.pi * 300 / 60  # 300 rpm
    d = follower_diagrams(cam, PHI, speed=w)
    s, s1, s2, s3 = program_by_hand(SEGS, PHI)
    for got, want in zip((d["s"], d["v"], d["a"], d["j"]), (s, w * s1, w**2 * s2, w**3 * s3)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 * np.abs(want).max())


@pytest.mark.parametrize("kw,message", [
    (dict(follower="roller", roller_radius=5.0, offset=46.0), "offset 46 must be smaller"),
    (dict(follower="roller"), "roller's radius must be positive"),
    (dict(follower="knife", motion="oscillating", pivot=(200.0, 0.0), arm=50.0), "cannot reach"),
    (dict(follower="knife", motion="oscillating", arm=50.0), "needs `pivot`"),
    (dict(follower="flat", motion="oscillating", pivot=(30.0, 0.0)), "cannot touch"),
    (dict(follower="wheel"), "follower must be one of"),
])
def test_bad_designs_are_named(kw, message):
    with pytest.raises(CamDesignError, match=message):
        DiscCam(program(), base_radius=40.0, **kw)


def test_flat_face_has_no_pressure_angle_to_limit():
    with pytest.raises(CamDesignError, match="limit the radius of curvature"):
        smallest_base_radius(DiscCam(program(), "flat", 40.0), max_pressure_angle=np.radians(30))


def test_smallest_base_radius_roller_without_undercut():
    """The smallest base circle whose profile keeps a radius of curvature of 2 on its convex
    parts: there the osculating circles through sampled profile points come down to 2, and on a
    base circle 1 % smaller below it."""
    segs = [("rise", 60.0, 25.0, "cycloidal"), ("dwell", 30.0, 0.0, None), ("return", 70.0, 25.0, "3-4-5"),
            ("dwell", 200.0, 0.0, None)]
    cam = DiscCam(program(segs), "roller", 40.0, roller_radius=10.0)
    rb = smallest_base_radius(cam, min_radius_of_curvature=2.0)
    phi = np.radians(np.arange(0.0, 360.0, 0.01))

    def smallest_convex(c):
        r = osculating_radius(sample_three(c.profile, phi, 1e-4))
        return r[(r > 0) & (r < 1e3)].min()

    assert smallest_convex(with_base_radius(cam, rb)) == pytest.approx(2.0, rel=1e-3)
    assert smallest_convex(with_base_radius(cam, 0.99 * rb)) < 2.0 - 1e-3
