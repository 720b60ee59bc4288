"""Cam motion laws and programs against their closed forms written out by hand, the peak factors
of the literature, Pöschl's parabolic law (§19, eq. 55) and his rest-to-rest check (§22d:
∫ b dr = 0 over a lift), and finite differences for the higher derivatives."""

from __future__ import annotations

import numpy as np
import pytest

from cam_laws_by_hand import BY_HAND, program_by_hand
from linkwork.errors import LinkworkError
from linkwork.model.motion_programs import LAWS, CamDesignError, MotionProgram, Segment, law

X = np.concatenate([np.random.default_rng(7).random(500), [0.0, 0.125, 0.375, 0.5, 0.625, 0.875, 1.0]])


@pytest.mark.parametrize("name", LAWS)
def test_law_equals_its_closed_form(name):
    want = BY_HAND[name](X)
    got = law(name).derivatives(X, 3)
    for k in range(4):
        np.testing.assert_allclose(got[k], want[k], rtol=0, atol=1e-11 * max(1.0, np.abs(want[k]).max()))


@pytest.mark.parametrize("name", LAWS)
def test_higher_derivatives_are_differences_of_lower(name):
    """Orders 1 to 5, each against the central difference of the order below (inside pieces)."""
    x = np.linspace(0.01, 0.99, 97)
    x = x[np.min(np.abs(x[:, None] - np.array([0.125, 0.375, 0.5, 0.625, 0.875])[None, :]), axis=1) > 2e-3]
    h = 1e-5
    L = law(name)
    d, up, dn = L.derivatives(x, 5), L.derivatives(x + h, 5), L.derivatives(x - h, 5)
    for k in range(1, 6):
        fd = (up[k - 1] - dn[k - 1]) / (2 * h)
        scale = max(1.0, np.abs(d[k]).max())
        np.testing.assert_allclose(d[k], fd, rtol=0, atol=1e-6 * scale * (4 * np.pi) ** 2)


# (Cv, Ca, Cj) from the literature (Rothbart, Cam Design Handbook; Norton, Cam Design and
# Manufacturing Handbook), as printed: 4 to 5 digits
PEAKS = {
    "harmonic": (np.pi / 2, np.pi**2 / 2, None),
    "cycloidal": (2.0, 2 * np.pi, 4 * np.pi**2),
    "3-4-5": (1.875, 5.7735, 60.0),
    "4-5-6-7": (2.1875, 7.5132, 52.5),
    "modified-trapezoid": (2.0, 4.888, 61.43),
    "modified-sine": (1.76, 5.528, 69.47),
    "parabolic": (2.0, 4.0, 0.0),
    "uniform": (1.0, 0.0, 0.0),
}


@pytest.mark.parametrize("name", LAWS)
def test_peak_factors(name):
    got = law(name).peaks
    for g, w in zip(got, PEAKS[name]):
        if w is not None:
            assert g == pytest.approx(w, rel=5e-4, abs=1e-12)


@pytest.mark.parametrize("name", LAWS)
def test_rest_to_rest_and_poeschl_area_check(name):
    """S(0) = 0, S(1) = 1; every law but the uniform one starts and ends at rest, and over
    the lift ∫ a ds = [v²/2] = 0: the positive and negative areas of the acceleration–lift
    diagram are equal (Pöschl §22d)."""
    L = law(name)
    ends = L.derivatives(np.array([0.0, 1.0]), 2)
    np.testing.assert_allclose(ends[0], [0.0, 1.0], atol=1e-15)
    if name != "uniform":
        np.testing.assert_allclose(ends[1], 0.0, atol=1e-14)
    area = 0.0
    edges = np.concatenate([[0.0], L.breaks, [1.0]])
    for a, b in zip(edges[:-1], edges[1:]):  # piece by piece: a jumps at the joins
        x = np.linspace(a, b, 20001)
        d = np.concatenate([L.derivatives(x[:1], 2, 1), L.derivatives(x[1:-1], 2),
                            L.derivatives(x[-1:], 2, -1)], axis=1)
        area += np.trapezoid(d[2] * d[1], x)  # ∫ a ds with ds = S′ dx
    assert abs(area) < 1e-7


def test_end_conditions_of_the_smooth_laws():
    ends = np.array([0.0, 1.0])
    for name in ("cycloidal", "3-4-5", "4-5-6-7", "modified-trapezoid", "modified-sine"):
        np.testing.assert_allclose(law(name).derivatives(ends, 2)[2], 0.0, atol=1e-12)
    np.testing.assert_allclose(law("4-5-6-7").derivatives(ends, 3)[3], 0.0, atol=1e-12)
    np.testing.assert_allclose(law("harmonic").derivatives(ends, 2)[2], [np.pi**2 / 2, -np.pi**2 / 2])


def test_poeschl_parabolic_law_eq_55():
    """Pöschl §19 c): on the second half of the constant-acceleration law the velocity follows
    v = V√(1 − y/h) of the half's lift y (h = 1/2, V = 2 here, the drive's speed v_s = 1), and
    the lift is y = h[1 − (V x/(2 v_s h) − 1)²] (the digest's corrected eq. 55); the equation
    as printed, y = h[1 − (V x/(v_s h) − 1)²], does not hold."""
    xs = np.linspace(0.0, 0.5, 101)  # cam angle from the half's start
    d = law("parabolic").derivatives(0.5 + xs, 1)
    y, v = d[0] - 0.5, d[1]
    h, V = 0.5, 2.0
    np.testing.assert_allclose(v, V * np.sqrt(np.clip(1 - y / h, 0, None)), atol=1e-12)
    np.testing.assert_allclose(y, h * (1 - (V * xs / (2 * h) - 1) ** 2), atol=1e-14)
    printed = h * (1 - (V * xs / h - 1) ** 2)
    assert np.max(np.abs(printed - y)) > 0.1


SEGMENTS = [("rise", 120.0, 20.0, "cycloidal"), ("dwell", 60.0, 0, None),
            ("return", 90.0, 20.0, "harmonic"), ("rise", 30.0, 5.0, "uniform"),
            ("return", 60.0, 5.0, "parabolic")]


def _program(segments=SEGMENTS):
    return MotionProgram([Segment(k, np.radians(e), lift, lw) for k, e, lift, lw in segments])


def test_program_equals_its_segments_by_hand():
    prog = _program()
    phi = np.radians(np.arange(0.05, 360.0, 0.37))
    want = program_by_hand(SEGMENTS, phi)
    got = prog.derivatives(phi, 3)
    for k in range(4):
        np.testing.assert_allclose(got[k], want[k], rtol=0, atol=1e-10 * np.abs(want[k]).max())
    # periodic, and sided at the joins
    np.testing.assert_allclose(prog.derivatives(phi + 2 * np.pi, 3), got, atol=1e-9)
    at = np.radians([120.0, 270.0])
    np.testing.assert_allclose(prog.derivatives(at, 1, side=-1)[1], [0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(prog.derivatives(at, 1, side=1)[1], [0.0, 5.0 / np.radians(30.0)], atol=1e-12)


def test_joins_report_the_jumps():
    """Velocity, acceleration and jerk jumps at the joins, from the laws' end values by hand:
    cycloidal against a dwell: jerk 4π²L/β³; harmonic from a dwell: acceleration (π²/2)L/β²;
    uniform after a harmonic return: velocity L/β; parabolic in its middle: acceleration
    −8L/β² (from +4 to −4)."""
    joins = {round(np.degrees(j.angle), 6): j for j in _program().joins()}
    b1, b2, b3, b4 = (np.radians(a) for a in (120.0, 90.0, 30.0, 60.0))
    j0 = joins[0.0]
    # the parabolic return ends at rest with s″ = 4L/β², the cycloidal rise starts with s″ = 0
    # and jerk 4π²L/β³
    assert j0.first_jump == 2 and j0.jumps[0] == 0.0
    assert j0.jumps[1] == pytest.approx(-4 * 5.0 / b4**2)
    assert j0.jumps[2] == pytest.approx(4 * np.pi**2 * 20.0 / b1**3)
    j120 = joins[120.0]
    assert j120.jumps[:2] == (0.0, 0.0)
    assert j120.jumps[2] == pytest.approx(-4 * np.pi**2 * 20.0 / b1**3)
    j180 = joins[180.0]
    assert j180.first_jump == 2 and j180.jumps[1] == pytest.approx(-np.pi**2 / 2 * 20.0 / b2**2)
    j270 = joins[270.0]
    assert j270.jumps[0] == pytest.approx(5.0 / b3)
    mid = joins[330.0]
    assert mid.jumps[0] == 0.0 and mid.jumps[1] == pytest.approx(8 * 5.0 / b4**2)


def test_lift_is_measured_from_its_lowest_point():
    prog = _program([("return", 180.0, 10.0, "cycloidal"), ("rise", 180.0, 10.0, "3-4-5")])
    s = prog.derivatives(np.radians(np.arange(0.0, 360.0, 1.0)), 0)[0]
    assert s.min() == pytest.approx(0.0, abs=1e-12) and s[0] == pytest.approx(10.0)


@pytest.mark.parametrize("segments,message", [
    ([("rise", 120.0, 20.0, "cycloidal"), ("return", 120.0, 20.0, "cycloidal")], "cover 240°"),
    ([("rise", 180.0, 20.0, "cycloidal"), ("return", 180.0, 15.0, "cycloidal")], "end the turn where it starts"),
    ([("rise", 180.0, 20.0, "cycloid-ish"), ("return", 180.0, 20.0, "cycloidal")], "segment 1 .*unknown motion law 'cycloid-ish'"),
    ([("rise", 180.0, -2.0, "cycloidal"), ("return", 180.0, 20.0, "cycloidal")], "segment 1 .*lift must be positive"),
    ([("rise", 360.0, 20.0, "cycloidal"), ("dwell", 0.0, 0, None)], "segment 2 .*must be positive"),
    ([("lift", 360.0, 20.0, "cycloidal")], "kind must be one of"),
])
def test_bad_programs_are_named(segments, message):
    with pytest.raises(CamDesignError, match=message):
        _program(segments)
    assert issubclass(CamDesignError, LinkworkError)
