"""Sliding pairs, Coriolis, driver laws, prismatic drivers, jerks and the generic group path,
each against finite differences of positions (an independent second method) or a closed form."""

import numpy as np
import pytest

import linkwork

SLOTTED_LEVER = """\
name = "oscillating crank-slotted lever, die block folded into a slot"
[points]
O2 = [0, 0]
A = [0, 10]
O4 = [0, -25]
T = [0, 20]
[links]
frame = ["O2", "O4"]
crank = ["O2", "A"]
lever = ["O4", "T"]
[joints]
O2 = { type = "revolute", links = ["frame", "crank"] }
O4 = { type = "revolute", links = ["frame", "lever"] }
A = { type = "slot", links = ["lever", "crank"], axis = [0, 1] }
[driver]
joint = "O2"
speed = "2 rad/s"
"""

H = 1e-5


def _fd(f, u, h=H):
    return (f(u + h) - f(u - h)) / (2 * h)


def test_slotted_lever_angle_closed_form():
    mech = linkwork.load_text(SLOTTED_LEVER)
    phi = np.radians(np.linspace(0, 350, 36))
    sol = linkwork.solve(mech, phi)
    # the lever points from O4 at A: its angle is atan2(A − O4)
    A = 10 * np.c_[np.cos(phi), np.sin(phi)]
    expected = np.arctan2(A[:, 1] + 25, A[:, 0])
    np.testing.assert_allclose(np.angle(np.exp(1j * (sol.link("lever").angle - expected))), 0, atol=1e-12)


def test_sliding_velocity_acceleration_and_coriolis_by_finite_differences():
    mech = linkwork.load_text(SLOTTED_LEVER)
    w = 2.0
    phi = np.radians(np.array([10.0, 75.0, 140.0, 260.0]))
    sol = linkwork.solve(mech, phi)
    slide = lambda u: linkwork.solve(mech, u).joint("A")["slide"]
    lever = lambda u: linkwork.solve(mech, u).link("lever").angle
    s_dot = _fd(slide, phi) * w
    s_ddot = (slide(phi + 1e-4) - 2 * slide(phi) + slide(phi - 1e-4)) / 1e-8 * w * w
    om_lever = _fd(lever, phi) * w
    j = sol.joint("A")
    np.testing.assert_allclose(j["sliding_velocity"], s_dot, rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(j["sliding_acceleration"], s_ddot, rtol=1e-5, atol=1e-4)
    # Coriolis acceleration 2 ω_lever × v_rel: magnitude 2|ω||ṡ|, normal to the slot
    np.testing.assert_allclose(np.hypot(*j["coriolis"].T), 2 * np.abs(om_lever * s_dot), rtol=1e-6)
    # the slot runs along the lever's reference line O4→T
    u = np.c_[np.cos(sol.link("lever").angle), np.sin(sol.link("lever").angle)]
    np.testing.assert_allclose((j["coriolis"] * u).sum(1), 0, atol=1e-9)


def test_jerk_equals_finite_difference_of_accelerations():
    mech = linkwork.load("library:crank-rocker")
    w = mech.drivers[0].law.speed
    phi = np.radians(np.array([20.0, 100.0, 250.0]))
    sol = linkwork.solve(mech, phi, order=3)
    acc = lambda u: linkwork.solve(mech, u).point("C").acceleration
    np.testing.assert_allclose(sol.point("C").jerk, _fd(acc, phi) * w,
                               rtol=1e-6, atol=1e-6 * np.abs(sol.point("C").jerk).max())
    alpha = lambda u: linkwork.solve(mech, u).link("rocker").alpha
    np.testing.assert_allclose(sol.link("rocker").jerk, _fd(alpha, phi) * w, rtol=1e-6, atol=1e-6)


def test_polynomial_driver_law_gives_angular_acceleration():
    text = linkwork.io.resolve("library:crank-rocker")[1].replace(
        'speed = "60 rpm"', 'law = { type = "polynomial", coefficients = [90, 30, 20], duration = 2 }')
    mech = linkwork.load_text(text)
    t = np.array([0.0, 0.5, 1.5])
    sol = linkwork.solve(mech, times=t)
    # θ(t) = 90° + 30°·t + 20°·t²: ω = 30° + 40°·t per second, α = 40°/s²
    np.testing.assert_allclose(sol.link("crank").omega, np.radians(30 + 40 * t))
    np.testing.assert_allclose(sol.link("crank").alpha, np.radians(40.0))
    pos = lambda tt: linkwork.solve(mech, times=tt).point("B").position
    vel = lambda tt: linkwork.solve(mech, times=tt).point("B").velocity
    np.testing.assert_allclose(sol.point("B").velocity, _fd(pos, t), rtol=1e-7, atol=1e-7)
    np.testing.assert_allclose(sol.point("B").acceleration, _fd(vel, t), rtol=1e-6, atol=1e-6)


def test_fourth_derivatives_equal_finite_differences_of_jerks():
    """`solve(..., order=4)` under a quartic law θ(t) = 90° + 30°t + 20°t² + 5°t³ + 2°t⁴
    (θ⁗ = 48°/s⁴): the crank's fourth derivative is the law's, the rocker's equals the central
    difference of its jerks in time."""
    text = linkwork.io.resolve("library:crank-rocker")[1].replace(
        'speed = "60 rpm"', 'law = { type = "polynomial", coefficients = [90, 30, 20, 5, 2], '
                            'duration = 2 }')
    mech = linkwork.load_text(text)
    t = np.array([0.1, 0.7, 1.6])
    sol = linkwork.solve(mech, times=t, order=4)
    np.testing.assert_allclose(sol.pose_derivatives("crank")[4, :, 2], np.radians(48.0))
    jerk = lambda tt: linkwork.solve(mech, times=tt, order=3).pose_derivatives("rocker")[3]
    snap = sol.pose_derivatives("rocker")[4]
    np.testing.assert_allclose(snap, _fd(jerk, t), rtol=1e-6, atol=1e-6 * np.abs(snap).max())
    assert sol.point("B").jerk is not None  # points keep their motion up to the jerk
    with pytest.raises(linkwork.errors.InputError, match="order must be"):
        linkwork.solve(mech, times=t, order=5)


INVERSE_SLIDER = """\
name = "slider-crank driven by its piston"
[points]
O = [0, 0]
A = [3, 4]
B = [15, 0]
[links]
frame = ["O"]
crank = ["O", "A"]
rod = ["A", "B"]
piston = ["B"]
[joints]
O = { type = "revolute", links = ["frame", "crank"] }
A = { type = "revolute", links = ["crank", "rod"] }
B = { type = "revolute", links = ["rod", "piston"] }
P = { type = "prismatic", point = "B", links = ["frame", "piston"], axis = [1, 0] }
[driver]
joint = "P"
speed = "1 mm/s"
"""


def test_prismatic_driver_crank_angle_closed_form():
    mech = linkwork.load_text(INVERSE_SLIDER)
    s = np.array([0.0, -2.0, 1.0])
    sol = linkwork.solve(mech, s)
    r, l = 5.0, np.hypot(12, 4)
    x = 15 + s
    # cosine law in triangle O A B: cos φ = (r² + x² − l²) / (2 r x), A above the line of stroke
    phi = np.arccos((r * r + x * x - l * l) / (2 * r * x))
    np.testing.assert_allclose(sol.link("crank").angle, phi, atol=1e-12)
    np.testing.assert_allclose(sol.point("B").velocity, np.c_[np.ones(3), np.zeros(3)], atol=1e-12)


def test_generic_newton_group_matches_closed_form_dyad(monkeypatch):
    """Force the RRR dyad through the generic path (Newton + Jacobian on jets): same answers."""
    from linkwork.kinematics import groups, solver
    mech = linkwork.load("library:pmks-stephenson-iii")
    phi = np.linspace(1.0, 2.3, 9)
    fast = linkwork.solve(mech, phi)
    monkeypatch.setattr(groups.GroupSolver, "__init__", lambda self, m, g, like=None: (
        setattr(self, "mech", m), setattr(self, "group", g),
        setattr(self, "kind", "driver" if g.drivers else "generic"), setattr(self, "parts", {}),
        setattr(self, "cam", None))[-1])
    solver.plan.cache_clear()
    try:
        slow = linkwork.solve(mech, phi)
    finally:
        solver.plan.cache_clear()
    for p in "CEF":
        for attr in ("position", "velocity", "acceleration"):
            np.testing.assert_allclose(getattr(slow.point(p), attr), getattr(fast.point(p), attr),
                                       rtol=1e-9, atol=1e-9)


def test_input_rates_must_match_the_inputs():
    mech = linkwork.load("library:crank-rocker")
    with pytest.raises(linkwork.errors.InputError, match="velocities: 3 samples for 2 inputs"):
        linkwork.solve(mech, [0.1, 0.2], velocities=[1.0, 2.0, 3.0])
    # one value serves every sample
    np.testing.assert_array_equal(linkwork.solve(mech, [0.1, 0.2], velocities=3.0).link("crank").omega,
                                  [3.0, 3.0])
