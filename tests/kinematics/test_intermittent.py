"""Geneva and star wheels (Pöschl §25) against closed forms, finite differences and the seed's
facts.

Expectations come from outside the solver:
- the Geneva wheel is the slotted crank while engaged (Pöschl §25a): its turn from
  mid-engagement is tan ψ = λ sin φ/(1 − λ cos φ), λ = r/D; velocities and accelerations are
  finite differences of that closed form, jerks finite differences of its derivative
  ψ′ = λ(cos φ − λ)/(1 − 2λ cos φ + λ²) (differentiated by hand);
- at mid-engagement the pin stands on the line of centres, r from M and D − r from C, so the
  wheel turns r/(D − r) times as fast as the driver (seed digest 002a, derived checks: n = 4
  gives 1/(√2 − 1) ≈ 2.414);
- shock-free design r = D·sin(π/n): the slot is tangent to the pin circle where the pin meets
  it, cos φₑ = λ, so ψ′ = 0 there; the driver is engaged for π − 2π/n (seed digest: 90° for
  n = 4), the wheel rests for the remaining (n + 2)/(2n) of the turn and moves (n − 2)/(2n) of
  it; at cos φ = λ, ψ″ = −λ sin φ/(1 − λ²) = ∓tan(π/n): the acceleration jumps by ω²·tan(π/n)
  at entry and exit;
- a larger pin radius meets the slot line (bearing π/n from C) where the pin circle cuts it
  (found here by root-finding on the closed form), with a jump of the wheel's velocity;
- the star wheel (§25b): steps of 2·asin(r/D) + (k − 1)·β·r/(D − r) for k pins at spacing β,
  speed rising from rest in the entry slot up to the pin gear's constant r/(D − r) at the slot's
  foot, falling to rest in the exit slot; pins on different pitch circles drive at different
  speeds; the pins' relative paths on the star wheel are epicycloids (the equidistants of the
  tooth flanks).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

import linkwork
from intermittent_mechanisms import D, geneva, tan_formula
from linkwork.errors import ModelError
from linkwork.kinematics.intermittent import engagement
from linkwork.model import GenevaPair, Mechanism, Revolute, StarWheelPair


def psi_rate(phi, lam):
    """dψ/dφ of the tan formula."""
    return lam * (np.cos(phi) - lam) / (1 - 2 * lam * np.cos(phi) + lam * lam)


def engaged_angles(n, count=41, margin=1e-3):
    half = np.pi / 2 - np.pi / n
    return np.linspace(-half + margin, half - margin, count)


@pytest.mark.parametrize("n", [3, 4, 6, 8])
def test_velocity_ratio_at_mid_engagement(n):
    mech = geneva(n)
    sol = linkwork.solve(mech, [0.0], velocities=[1.0])
    r = D * np.sin(np.pi / n)
    rep = sol.joint("G")
    assert rep["ratio"][0] == pytest.approx(-r / (D - r), rel=1e-12)
    assert sol.link("wheel").omega[0] == pytest.approx(-r / (D - r), rel=1e-12)
    assert rep["phase"][0] == 1 and rep["slot"][0] == 0  # engaged, in the first slot
    if n == 4:
        assert -rep["ratio"][0] == pytest.approx(1 / (np.sqrt(2) - 1), rel=1e-12)


@pytest.mark.parametrize("n", [4, 6])
def test_engaged_motion_is_the_tan_formula(n):
    mech = geneva(n)
    lam = np.sin(np.pi / n)
    phi = engaged_angles(n)
    sol = linkwork.solve(mech, phi, velocities=np.ones_like(phi), order=3)
    w = sol.link("wheel")
    theta = sol.pose_derivatives("wheel")[:, :, 2]
    np.testing.assert_allclose(theta[0], -tan_formula(phi, lam), rtol=0, atol=1e-13)
    h = 1e-5
    fd1 = (tan_formula(phi + h, lam) - tan_formula(phi - h, lam)) / (2 * h)
    np.testing.assert_allclose(w.omega, -fd1, rtol=0, atol=1e-8)
    h = 1e-4
    fd2 = (tan_formula(phi + h, lam) - 2 * tan_formula(phi, lam) + tan_formula(phi - h, lam)) / h**2
    np.testing.assert_allclose(w.alpha, -fd2, rtol=0, atol=1e-5)
    fd3 = (psi_rate(phi + h, lam) - 2 * psi_rate(phi, lam) + psi_rate(phi - h, lam)) / h**2
    np.testing.assert_allclose(w.jerk, -fd3, rtol=0, atol=1e-4 * np.abs(fd3).max())


def test_rates_scale_with_the_driver_speed_and_acceleration():
    """ω = θ′φ̇, α = θ″φ̇² + θ′φ̈: at φ̇ = 3, φ̈ = 2 against the unit-speed solve."""
    mech = geneva(4)
    phi = engaged_angles(4, 9)
    one = linkwork.solve(mech, phi, velocities=np.ones_like(phi), accelerations=np.zeros_like(phi))
    two = linkwork.solve(mech, phi, velocities=np.full_like(phi, 3.0),
                         accelerations=np.full_like(phi, 2.0))
    t1, t2 = one.link("wheel").omega, one.link("wheel").alpha
    np.testing.assert_allclose(two.link("wheel").omega, 3 * t1, rtol=0, atol=1e-13)
    np.testing.assert_allclose(two.link("wheel").alpha, 9 * t2 + 2 * t1, rtol=0, atol=1e-11)


@pytest.mark.parametrize("n", [4, 6])
def test_snap_is_the_derivative_of_the_jerk(n):
    mech = geneva(n)
    phi = engaged_angles(n, 11)
    h = 1e-5
    s = linkwork.solve(mech, phi, velocities=np.ones_like(phi), order=4)
    up = linkwork.solve(mech, phi + h, velocities=np.ones_like(phi), order=3).link("wheel").jerk
    dn = linkwork.solve(mech, phi - h, velocities=np.ones_like(phi), order=3).link("wheel").jerk
    snap = s.pose_derivatives("wheel")[4, :, 2]
    np.testing.assert_allclose(snap, (up - dn) / (2 * h), rtol=0, atol=1e-5 * np.abs(snap).max())


@pytest.mark.parametrize("n", [4, 6])
def test_shock_free_entry_and_exit(n):
    """Zero wheel velocity at entry and exit, on both sides, and at the samples on them."""
    mech = geneva(n)
    half = np.pi / 2 - np.pi / n
    phi = np.array([-half, -half + 1e-7, 0.3, half - 1e-7, half])
    sol = linkwork.solve(mech, phi, velocities=np.ones_like(phi))
    w = sol.link("wheel").omega
    assert abs(w[0]) < 1e-12 and abs(w[-1]) < 1e-12
    assert abs(w[1]) < 1e-6 and abs(w[3]) < 1e-6
    e = engagement(sol, "G")
    kinds = [ev.kind for ev in e.events]
    assert kinds == ["entry", "exit"]
    for ev in e.events:
        assert ev.omega == pytest.approx((0.0, 0.0), abs=1e-12)
        assert len(ev.samples) == 1
        np.testing.assert_allclose(ev.at_samples[0, :, 0], 0.0, atol=1e-12)


@pytest.mark.parametrize("n", [4, 6])
def test_acceleration_jump_at_entry_and_exit(n):
    """ω²·tan(π/n) from rest at entry, back to rest at exit (the driver at constant speed ω)."""
    mech = geneva(n)
    omega = mech.drivers[0].law.speed
    half = np.pi / 2 - np.pi / n
    phi = np.linspace(-np.pi, np.pi, 721)
    sol = linkwork.solve(mech, phi)
    (entry,), (exit_,) = ([ev for ev in engagement(sol, "G").events if ev.kind == k]
                          for k in ("entry", "exit"))
    jump = omega**2 * np.tan(np.pi / n)
    assert entry.angle == pytest.approx(-half, abs=1e-12)
    assert exit_.angle == pytest.approx(half, abs=1e-12)
    assert entry.alpha == pytest.approx((0.0, -jump), abs=1e-10)
    assert exit_.alpha == pytest.approx((jump, 0.0), abs=1e-10)
    assert entry.acceleration_jump == pytest.approx(-jump, abs=1e-10)
    # the same limit from one-sided finite differences of the closed form at entry
    lam, h = np.sin(np.pi / n), 1e-4
    f = [tan_formula(-half + k * h, lam) for k in range(4)]
    one_sided = (2 * f[0] - 5 * f[1] + 4 * f[2] - f[3]) / h**2
    assert entry.alpha[1] == pytest.approx(-omega**2 * one_sided, abs=1e-5 * jump)
    # the solver's acceleration just inside the engagement tends to it
    inside = linkwork.solve(mech, [-half + 1e-8]).link("wheel").alpha[0]
    assert inside == pytest.approx(-jump, rel=1e-6)


@pytest.mark.parametrize("n", [4, 6])
def test_dwell_and_engagement_fractions(n):
    """The driver is engaged for π − 2π/n of its turn: the wheel moves (n − 2)/(2n) of the time
    and rests (n + 2)/(2n); at rest its velocity and acceleration are exactly zero."""
    mech = geneva(n)
    phi = np.linspace(0.0, 2 * np.pi, 3600, endpoint=False) + 1e-4
    sol = linkwork.solve(mech, phi)
    e = engagement(sol, "G")
    assert e.dwell_fraction == pytest.approx((n + 2) / (2 * n), abs=1e-12)
    (eng,) = [iv for iv in e.intervals if iv[0] == "engaged"]
    assert eng[2] - eng[1] == pytest.approx(np.pi - 2 * np.pi / n, abs=1e-12)
    assert e.advance == pytest.approx(2 * np.pi / n, abs=1e-14)
    dwell = e.phase == "dwell"
    assert dwell.mean() == pytest.approx((n + 2) / (2 * n), abs=1.0 / phi.size)
    assert (~dwell).mean() == pytest.approx((n - 2) / (2 * n), abs=1.0 / phi.size)
    w = sol.link("wheel")
    assert (w.omega[dwell] == 0).all() and (w.alpha[dwell] == 0).all()
    assert (np.abs(w.omega[~dwell]) > 0).all()


@pytest.mark.parametrize("n", [4, 6])
def test_n_turns_of_the_driver_turn_the_wheel_once(n):
    """Each slot is used once in n turns, and the wheel then has made one full turn."""
    mech = geneva(n)
    phi = np.linspace(0.0, 2 * np.pi * n, 360 * n + 1)
    sol = linkwork.solve(mech, phi)
    theta = sol.pose_derivatives("wheel")[0, :, 2]
    assert theta[-1] - theta[0] == pytest.approx(-2 * np.pi, abs=1e-12)
    assert (np.diff(theta) <= 1e-15).all()  # it never turns back
    slots = sol.joint("G")["slot"]
    used = slots[slots >= 0]
    first = used[np.r_[True, np.diff(used) != 0]]
    assert sorted(first[:n]) == list(range(n))


def test_larger_pin_radius_enters_with_a_velocity_jump():
    """r > D·sin(π/n): the pin meets the slot line where the pin circle cuts it, bearing π/n
    from C, moving across it: the wheel jumps from rest to ψ′(φₑ)·ω."""
    n = 4
    lam = 1.15 * np.sin(np.pi / n)
    mech = geneva(n, lam * D)
    omega = mech.drivers[0].law.speed
    phi_e = brentq(lambda p: tan_formula(p, lam) + np.pi / n, -np.arccos(lam), 0.0, xtol=1e-15)
    h = 1e-6
    rate = (tan_formula(phi_e + h, lam) - tan_formula(phi_e - h, lam)) / (2 * h)
    assert rate > 0.1  # a real jump
    phi = np.array([phi_e - 1e-9, phi_e, phi_e + 1e-9, 0.0, -phi_e])
    sol = linkwork.solve(mech, phi)
    e = engagement(sol, "G")
    entry = next(ev for ev in e.events if ev.kind == "entry")
    assert entry.angle == pytest.approx(phi_e, abs=1e-12)
    assert entry.omega[0] == 0.0
    assert entry.omega[1] == pytest.approx(-rate * omega, rel=1e-8)
    assert entry.velocity_jump == pytest.approx(-rate * omega, rel=1e-8)
    w = sol.link("wheel").omega
    assert w[0] == 0.0
    assert w[2] == pytest.approx(-rate * omega, rel=1e-6)
    # the wheel still turns 2π/n per engagement, over a shorter driver angle than π − 2π/n
    assert e.advance == pytest.approx(2 * np.pi / n, abs=1e-12)
    (eng,) = [iv for iv in e.intervals if iv[0] == "engaged"]
    assert eng[2] - eng[1] == pytest.approx(-2 * phi_e, abs=1e-12)
    assert -2 * phi_e < np.pi - 2 * np.pi / n


def test_wheel_on_a_moving_carrier_moves_relative_to_it_as_on_the_frame():
    """The disc and the wheel pivoted on an arm that is itself driven: the wheel's motion
    relative to the arm is the fixed Geneva wheel's for the disc's motion relative to the arm."""
    n, r = 4, D * np.sin(np.pi / 4)
    O = np.array([-60.0, -40.0])
    mech = Mechanism.build(
        name="Geneva on an arm", points={"O": O, "M": [0, 0], "C": [D, 0], "B": [r, 0], "W": [D, 30]},
        links={"frame": ["O"], "arm": ["O", "M", "C"], "disc": ["M", "B"], "wheel": ["C", "W"]},
        joints=[Revolute("O", "O", ("frame", "arm")), Revolute("M", "M", ("arm", "disc")),
                Revolute("C", "C", ("arm", "wheel")), GenevaPair("G", ("disc", "wheel"), "B", n, "arm")],
        drivers=[{"joint": "O"}, {"joint": "M"}])
    fixed = geneva(n)
    rel = np.linspace(-1.2, 2.0, 33)
    arm = 0.3 + 0.5 * rel
    u0 = [mech.driver_input_at_design(d) for d in mech.drivers]
    inputs = np.column_stack([u0[0] + arm, u0[1] + rel])
    rates = np.column_stack([np.full_like(rel, 1.7), np.full_like(rel, 1.0)])
    accs = np.column_stack([np.full_like(rel, 0.4), np.full_like(rel, -0.2)])
    sol = linkwork.solve(mech, inputs, velocities=rates, accelerations=accs)
    ref = linkwork.solve(fixed, rel, velocities=np.ones_like(rel), accelerations=np.full_like(rel, -0.2))
    a = sol.joint("G")
    np.testing.assert_allclose(a["angle"], ref.pose_derivatives("wheel")[0, :, 2], atol=1e-12)
    np.testing.assert_allclose(a["omega"], ref.link("wheel").omega, atol=1e-11)
    np.testing.assert_allclose(a["alpha"], ref.link("wheel").alpha, atol=1e-9)
    np.testing.assert_array_equal(a["phase"], ref.joint("G")["phase"])


def test_reversed_driver_runs_the_same_motion_backwards():
    mech = geneva(6)
    phi = np.linspace(-np.pi, np.pi, 181)
    fwd = linkwork.solve(mech, phi, velocities=np.ones_like(phi))
    back = linkwork.solve(mech, phi[::-1], velocities=-np.ones_like(phi))
    np.testing.assert_allclose(back.link("wheel").angle[::-1], fwd.link("wheel").angle, atol=1e-14)
    np.testing.assert_allclose(back.link("wheel").omega[::-1], -fwd.link("wheel").omega, atol=1e-12)


# ---------------------------------------------------------------------------- errors
def _mech(joint, points=None):
    pts = {"M": [0, 0], "C": [D, 0], "B": [60, 0], "B2": [0, 60], "W": [D, 30]}
    pts.update(points or {})
    return Mechanism.build(
        name="bad", points=pts,
        links={"frame": ["M", "C"], "disc": ["M", "B", "B2"], "wheel": ["C", "W"]},
        joints=[Revolute("M", "M", ("frame", "disc")), Revolute("C", "C", ("frame", "wheel")), joint],
        drivers=[{"joint": "M"}])


@pytest.mark.parametrize("joint,points,message", [
    (GenevaPair("G", ("disc", "wheel"), "B", 4), {"B": [60, 0]}, r"geneva pair 'G'.*does not reach into the slots.*r ≥ D·sin\(π/4\)"),
    (GenevaPair("G", ("disc", "wheel"), "B", 2), None, "geneva pair 'G': a Geneva wheel needs at least 3 slots"),
    (GenevaPair("G", ("disc", "wheel"), "W", 4), None, "the pin 'W' must be a point of the driver 'disc'"),
    (GenevaPair("G", ("disc", "wheel"), "B", 4), {"B": [120, 0]}, "between the pivot and the centre distance"),
    (GenevaPair("G", ("disc", "wheel"), "B", 4, "disc"), None, "carrier 'disc' cannot be the driver"),
    (StarWheelPair("S", ("disc", "wheel"), (("B", "B2"),)), {"B2": [0, 50]}, "different pitch circles"),
    (StarWheelPair("S", ("disc", "wheel"), (("B",), ("B2",))), None, "overlap"),
    (StarWheelPair("S", ("disc", "wheel"), (("B",),)), None, "does not divide the full turn"),
])
def test_errors_name_the_pair(joint, points, message):
    with pytest.raises(ModelError, match=message):
        _mech(joint, points)


def test_unequal_pin_spacing_is_refused():
    pts = {"P1": [50, 0], "P2": [50 * np.cos(0.3), 50 * np.sin(0.3)], "P3": [50 * np.cos(0.5), 50 * np.sin(0.5)]}
    with pytest.raises(ModelError, match="star-wheel pair 'S': the pins P1, P2, P3 are not equally spaced"):
        Mechanism.build(
            name="bad", points={"M": [0, 0], "C": [D, 0], "W": [D, 30], **pts},
            links={"frame": ["M", "C"], "disc": ["M", *pts], "wheel": ["C", "W"]},
            joints=[Revolute("M", "M", ("frame", "disc")), Revolute("C", "C", ("frame", "wheel")),
                    StarWheelPair("S", ("disc", "wheel"), (("P1", "P2", "P3"),))],
            drivers=[{"joint": "M"}])


# ---------------------------------------------------------------------------- the star wheel
@pytest.fixture(scope="module")
def star():
    mech = linkwork.load("library:star-wheel")
    return mech, linkwork.whole_motion(mech, step=np.radians(0.25))


def _groups(mech):
    """Per group, from the drawing: pitch radius r and pin spacing β."""
    M = mech.points["M"]
    out = []
    for group in mech.joint("index").groups:
        xy = np.array([mech.points[p] - M for p in group])
        ang = np.arctan2(xy[:, 1], xy[:, 0])
        out.append((float(np.hypot(*xy[0])), float(np.abs(np.angle(np.exp(1j * (ang[1] - ang[0]))))), len(group)))
    return out


def test_star_wheel_steps_are_unequal_and_follow_the_pin_groups(star):
    mech, sol = star
    Dm = float(np.hypot(*(mech.points["C"] - mech.points["M"])))
    steps = [2 * np.arcsin(r / Dm) + (k - 1) * beta * r / (Dm - r) for r, beta, k in _groups(mech)]
    assert abs(steps[0] - steps[1]) > np.radians(10)  # Pöschl: steps need not be equal
    theta = sol.pose_derivatives("star")[0, :, 2]
    rest = sol.link("star").omega == 0
    # the wheel's angle on its rests: two index angles per turn, the steps apart
    levels = np.unique(np.round(theta[rest], 9))
    moved = -np.diff(levels[::-1])
    assert sorted(moved) == pytest.approx(sorted(steps), abs=1e-9)
    assert theta[-1] - theta[0] == pytest.approx(-sum(steps), abs=1e-12)


def test_star_wheel_speed_rises_stays_and_falls(star):
    """Entry: from rest up to the pin gear's speed r/(D − r) at the slot's foot; gear: constant;
    exit: down to rest. Pins on different pitch circles drive at different speeds."""
    mech, sol = star
    Dm = float(np.hypot(*(mech.points["C"] - mech.points["M"])))
    omega = mech.drivers[0].law.speed
    e = engagement(sol, "index")
    w = sol.link("star").omega
    phase = e.phase
    groups = _groups(mech)
    gear_speeds = []
    for g, (r, _, _) in enumerate(groups):
        slot = sol.joint("index")["slot"]
        in_g = np.isin(slot, [g, g + 2])  # two groups, four entries on the wheel
        gear = in_g & (phase == "gear")
        np.testing.assert_allclose(w[gear], -omega * r / (Dm - r), rtol=1e-12)
        gear_speeds.append(r / (Dm - r))
        for name, sign in (("entry", 1), ("exit", -1)):
            idx = np.flatnonzero(in_g & (phase == name))
            speed = -w[idx]
            assert (sign * np.diff(speed) > 0).all(), name
    assert gear_speeds[0] != pytest.approx(gear_speeds[1])
    for ev in e.events:
        if ev.kind == "transfer":  # the speed at the slot's foot is the pin gear's
            assert ev.omega[0] == pytest.approx(ev.omega[1], rel=1e-12)
            assert ev.alpha[0] == pytest.approx(ev.alpha[1], abs=1e-9)
            assert ev.jerk[0] != pytest.approx(ev.jerk[1])  # the jerk jumps there
        else:  # shock-free entry and exit slots
            assert ev.omega == pytest.approx((0.0, 0.0), abs=1e-12)
            assert max(abs(a) for a in ev.alpha) > 1.0


def test_star_wheel_pins_run_on_epicycloids_in_the_gear_phase(star):
    """Relative to the star wheel, a pin centre of the driver's pitch circle (radius r) rolling
    on the star's (radius ρ = D − r) traces the epicycloid (ρ + r)e^{it} − r e^{i(ρ+r)t/r},
    its cusp where the pin stands on the line of centres (Pöschl: the equidistants of the tooth
    flanks are the pins' relative paths)."""
    mech, sol = star
    Dm = float(np.hypot(*(mech.points["C"] - mech.points["M"])))
    rep = sol.joint("index")
    e = engagement(sol, "index")
    C = mech.points["C"]
    for g, (group, (r, _, _)) in enumerate(zip(mech.joint("index").groups, _groups(mech))):
        rho = Dm - r
        gear = (e.phase == "gear") & (rep["slot"] == g)
        lead = group[0]
        start = next(ev for ev in e.events if ev.kind == "transfer" and ev.slot == g)
        # the lead pin's cusp: where it stands on the line of centres at the transfer
        at = linkwork.solve(mech, [start.input])
        cusp = at.local("star", at.point(lead).position)[0] - C
        base = np.arctan2(cusp[1], cusp[0])
        assert np.hypot(*cusp) == pytest.approx(rho, rel=1e-12)
        p = sol.local("star", sol.point(lead).position)[gear] - C
        p = p @ np.array([[np.cos(base), -np.sin(base)], [np.sin(base), np.cos(base)]])  # cusp on +x
        z = p[:, 0] + 1j * p[:, 1]
        # |f(t)|² = (ρ + r)² + r² − 2r(ρ + r)·cos(ρt/r) gives the rolling angle t up to its
        # sign; the polar angle must then be the epicycloid's too
        c = ((rho + r) ** 2 + r * r - np.abs(z) ** 2) / (2 * r * (rho + r))
        t = r / rho * np.arccos(np.clip(c, -1, 1))
        err = []
        for sign in (1, -1):
            f = (rho + r) * np.exp(1j * sign * t) - r * np.exp(1j * (rho + r) * sign * t / r)
            err.append(np.abs(np.angle(f / z)))
        assert min(np.max(e_) for e_ in err) < 1e-9
        assert np.all(t[1:-1] > 1e-3)  # away from the cusp: a real test of the angle
        assert gear.sum() > 10


# ---------------------------------------------------------------------------- two code paths
@pytest.mark.parametrize("name", ["geneva-4", "geneva-6", "star-wheel"])
def test_closed_form_rates_equal_the_phase_equations_on_jets(name, monkeypatch):
    """The solver's closed-form rates (the transmission composed with the driver's jet) against
    the linear solve on the jets of each sample's phase equation (`derivatives_generic`), up to
    the snap, with the same condition numbers."""
    from linkwork.kinematics import groups

    mech = linkwork.load(f"library:{name}")
    u = mech.driver_input_at_design(mech.drivers[0]) + np.linspace(0.0, 2 * np.pi, 721)[:-1] + 1e-3
    fast = linkwork.solve(mech, u, velocities=np.full_like(u, 1.3), accelerations=np.full_like(u, 0.7),
                          jerks=np.full_like(u, -0.4), order=4)
    original = groups.GroupSolver.derivatives

    def on_jets(self, state, ok):
        if self.kind == "intermittent":
            return groups.derivatives_generic(state, self.group, ok)
        return original(self, state, ok)

    monkeypatch.setattr(groups.GroupSolver, "derivatives", on_jets)
    slow = linkwork.solve(mech, u, velocities=np.full_like(u, 1.3), accelerations=np.full_like(u, 0.7),
                          jerks=np.full_like(u, -0.4), order=4)
    wheel = mech.joints[-1].links[1]
    a, b = fast.pose_derivatives(wheel), slow.pose_derivatives(wheel)
    for k in range(5):
        scale = np.abs(b[k]).max() or 1.0
        np.testing.assert_allclose(a[k], b[k], rtol=0, atol=1e-10 * scale, err_msg=f"order {k}")
    np.testing.assert_allclose(fast.condition, slow.condition, rtol=1e-9)


@pytest.mark.parametrize("n,pin_over_a,engaged_deg", [(3, np.sqrt(3), 60.0), (4, 1.0, 90.0),
                                                      (6, 1 / np.sqrt(3), 120.0)])
def test_poeschls_design_relation(n, pin_over_a, engaged_deg):
    """Pöschl §25a: wheel radius a and centre distance D_n = a/cos(π/n) (D₃ = 2a, D₄ = a√2);
    the seed digest's derived checks: crank radius a·tan(π/n) (a√3 for n = 3, a for n = 4),
    engagement 60° and 90°. The pin enters and leaves the wheel on its rim, |CB| = a."""
    a = 40.0
    Dn = a / np.cos(np.pi / n)
    if n in (3, 4):
        assert Dn == pytest.approx({3: 2 * a, 4: a * np.sqrt(2)}[n])
    mech = geneva(n, a * pin_over_a, centre=Dn)  # the shock-free pin: r = D·sin(π/n) = a·tan(π/n)
    phi = np.radians(np.arange(-180.0, 180.0, 0.5))
    sol = linkwork.solve(mech, phi)
    e = engagement(sol, "G")
    (eng,) = [iv for iv in e.intervals if iv[0] == "engaged"]
    assert np.degrees(eng[2] - eng[1]) == pytest.approx(engaged_deg, abs=1e-9)
    for ev in e.events:
        B = linkwork.solve(mech, [ev.input]).point("B").position[0]
        assert np.hypot(*(B - [Dn, 0.0])) == pytest.approx(a, rel=1e-12)
        assert ev.omega == pytest.approx((0.0, 0.0), abs=1e-12)


@pytest.mark.parametrize("at", [0.0, np.pi, 0.5])
def test_mobility_counts_the_pair_in_every_phase(at):
    """Drawn engaged (φ = 0, 0.5) or locked (φ = π): the Jacobian's rank leaves one freedom, as
    Kutzbach's count with h = 1 says: F = 3·(3 − 1) − 2·2 − 1 = 1."""
    from linkwork.structure.mobility import counts, mobility

    mech = geneva(4, at=at)
    c = counts(mech)
    assert (c.n, c.g, c.h) == (3, 2, 1) and c.mobility == 1
    m = mobility(mech)
    assert m.real_mobility == 1 and not m.redundant and m.count_mobility == 1
