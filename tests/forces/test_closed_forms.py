"""Kinetostatics against closed forms derived by hand, and identities checked by a second
method: the rotating crank's bearing force m·ω²·ρ, the static slider-crank's torque by virtual
work and its guide force from the rod as a two-force member, the piston's inertia force at the
dead centres, the shaking force as the resultant of the inertia forces, and the driver torque
of free motion from the reduced inertia (Lagrange), whose derivative is checked by finite
differences."""

import numpy as np
import pytest

import linkwork
from linkwork.forces import kinetostatics
from linkwork.forces.reduced import flywheel, reduced_inertia
from linkwork.model import PolynomialLaw
from linkwork.model.inertia import Couple, Dynamics, Loads, MassProperties, PointForce

CRANK = """
name = "crank"
units = { length = "m" }
[points]
O = [0, 0]
A = [1, 0]
[links]
frame = ["O"]
crank = ["O", "A"]
[joints]
O = { type = "revolute", links = ["frame", "crank"] }
[driver]
joint = "O"
"""


def random_masses(mech, rng, scale=1.0):
    out = {}
    for ln in mech.moving_links:
        xy = np.array([mech.points[p] for p in mech.link(ln).points])
        c = xy.mean(axis=0) + rng.uniform(-0.3, 0.3, 2) * mech.length_scale
        out[ln] = MassProperties(rng.uniform(0.5, 3.0) * scale, c, rng.uniform(0.01, 0.1) * scale)
    return out


@pytest.mark.parametrize("alpha", [0.0, 7.5])
def test_rotating_crank_bearing_force(alpha):
    # centre of mass at ρ = |(0.3, 0.4)| = 0.5 m from the pivot; ω = 12 rad/s
    mech = linkwork.load_text(CRANK)
    m, I, w = 2.0, 0.05, 12.0
    S = np.array([0.3, 0.4])
    dyn = Dynamics.build(mech, {"crank": MassProperties(m, S, I)})
    q = np.linspace(0, 2 * np.pi, 13)
    fa = kinetostatics(dyn, linkwork.solve(mech, q, velocities=w, accelerations=alpha))
    phi = q + np.arctan2(S[1], S[0])  # the direction of the centre of mass
    e = np.c_[np.cos(phi), np.sin(phi)]
    rho = 0.5
    # the frame holds the crank's centre of mass on its circle: m·(−ω²ρ e + αρ e⊥)
    want = m * (-w**2 * rho * e + alpha * rho * np.c_[-e[:, 1], e[:, 0]])
    np.testing.assert_allclose(fa.reactions["O"].force, want, atol=1e-12 * m * w**2)
    np.testing.assert_allclose(fa.reactions["O"].magnitude, m * rho * np.hypot(w**2, alpha), rtol=1e-12)
    np.testing.assert_allclose(fa.effort, (I + m * rho**2) * alpha, atol=1e-12 * m * w**2)
    # what the crank does to the frame: the inertia force (a rotating unbalance)
    np.testing.assert_allclose(fa.frame_force, fa.shaking_force, atol=1e-12 * m * w**2)
    np.testing.assert_allclose(fa.frame_force, -want, atol=1e-12 * m * w**2)


def test_gravity_on_crank_static():
    # a horizontal crank holding its weight: torque m·g·x_S, bearing force m·g upward
    mech = linkwork.load_text(CRANK)
    dyn = Dynamics.build(mech, {"crank": MassProperties(3.0, np.array([0.4, 0.0]), 0.1)},
                         Loads(gravity=np.array([0.0, -9.81])))
    q = np.radians([0.0, 60.0, 180.0])
    fa = kinetostatics(dyn, linkwork.solve(mech, q), inertia=False)
    np.testing.assert_allclose(fa.effort, 3.0 * 9.81 * 0.4 * np.cos(q), atol=1e-12)
    np.testing.assert_allclose(fa.reactions["O"].force, np.tile([0.0, 3.0 * 9.81], (3, 1)), atol=1e-12)


def test_static_slider_crank_torque_by_virtual_work():
    # r = 50 mm, l = 200 mm; a gas force P on the block along x; T·δφ + P·δs = 0
    mech = linkwork.load("library:slider-crank-centric")
    P = -1000.0
    dyn = Dynamics.build(mech, loads=Loads(forces=(PointForce("block", mech.points["B"], [P, 0.0]),)))
    phi = np.radians(np.arange(5.0, 360.0, 10.0))
    sol = linkwork.solve(mech, phi)
    fa = kinetostatics(dyn, sol, inertia=False)
    # points of application in the drawing's unit (mm)
    np.testing.assert_allclose(fa.reactions["B"].point, sol.point("B").position, rtol=1e-15)
    r, l = 0.05, 0.2
    root = np.sqrt(l**2 - (r * np.sin(phi)) ** 2)
    ds = -r * np.sin(phi) - r**2 * np.sin(phi) * np.cos(phi) / root
    np.testing.assert_allclose(fa.effort, -P * ds, rtol=1e-12, atol=1e-12 * abs(P) * r)
    # the rod is a two-force member: the block's normal force is P·tan β (β the rod's angle)
    ey, ex = -r * np.sin(phi) / l, root / l
    np.testing.assert_allclose(fa.reactions["guide"].components["normal"], P * ey / ex, rtol=1e-12,
                               atol=1e-12 * abs(P))
    np.testing.assert_allclose(fa.reactions["guide"].couple, 0.0, atol=1e-12 * abs(P) * r)
    # the rod pushes the block with the rod force along the rod (force of rod on block at B)
    Rb = fa.reactions["B"].force
    np.testing.assert_allclose(Rb[:, 0], -P, rtol=1e-12)


def test_piston_inertia_force_at_dead_centres():
    # seed 004: at the dead centres the piston accelerates by v²/r ± v²/l, v = 2rπn
    mech = linkwork.load("library:slider-crank-centric")  # 120 rpm
    m_block = 1.7
    dyn = Dynamics.build(mech, {"crank": MassProperties(0, mech.points["O"], 0),
                                "rod": MassProperties(0, mech.points["A"], 0),
                                "block": MassProperties(m_block, mech.points["B"], 0)})
    fa = kinetostatics(dyn, linkwork.solve(mech, [0.0, np.pi]))
    n, r, l = 2.0, 0.05, 0.2
    v = 2 * r * np.pi * n
    a = np.array([v**2 / r + v**2 / l, v**2 / r - v**2 / l])
    # the rod drives the block: force of the rod on the block = m·a (towards the crank at the
    # outer dead centre, away from it at the inner one)
    np.testing.assert_allclose(fa.reactions["B"].force[:, 0], m_block * a * [-1, 1], rtol=1e-12)
    np.testing.assert_allclose(fa.shaking_force[:, 0], m_block * a * [1, -1], rtol=1e-12)


def _crank_rocker(rng):
    mech = linkwork.load("library:crank-rocker")
    return mech, Dynamics.build(mech, random_masses(mech, rng))


def test_free_motion_torque_from_reduced_inertia():
    rng = np.random.default_rng(4)
    mech, dyn = _crank_rocker(rng)
    q = np.linspace(0, 2 * np.pi, 37)
    w, al = 5.0, -3.0
    fa = kinetostatics(dyn, linkwork.solve(mech, q, velocities=w, accelerations=al))
    red = reduced_inertia(dyn, q)
    T = red.inertia * al + 0.5 * red.derivative * w**2
    np.testing.assert_allclose(fa.effort, T, rtol=1e-10, atol=1e-12 * np.abs(T).max())
    np.testing.assert_allclose(fa.kinetic_energy, 0.5 * red.inertia * w**2, rtol=1e-12)
    # J′ by central differences of J
    h = 1e-5
    fd = (reduced_inertia(dyn, q + h).inertia - reduced_inertia(dyn, q - h).inertia) / (2 * h)
    np.testing.assert_allclose(red.derivative, fd, rtol=0, atol=1e-7 * np.abs(red.inertia).max())


def test_kinetic_energy_rate_by_finite_differences():
    rng = np.random.default_rng(5)
    mech, _ = _crank_rocker(rng)
    d = mech.drivers[0]
    law = PolynomialLaw((mech.driver_input_at_design(d), 2.0, 3.0, -0.5), 2.0)
    from dataclasses import replace
    mech = linkwork.Mechanism.build(name="accelerating crank-rocker", points=mech.points,
                                    links={ln.name: list(ln.points) for ln in mech.links},
                                    joints=list(mech.joints), drivers=[replace(d, law=law)],
                                    length_unit=mech.length_unit)
    dyn = Dynamics.build(mech, random_masses(mech, rng))
    t = np.linspace(0.1, 1.9, 19)
    h = 1e-5
    fa = kinetostatics(dyn, linkwork.solve(mech, times=t))
    e = [kinetostatics(dyn, linkwork.solve(mech, times=t + s)).kinetic_energy for s in (h, -h)]
    np.testing.assert_allclose(fa.kinetic_energy_rate, (e[0] - e[1]) / (2 * h), rtol=1e-6)
    assert np.abs(fa.power_residual / fa.power_scale).max() < 1e-12


def test_shaking_force_and_moment_are_the_frame_loads_without_external_loads():
    rng = np.random.default_rng(6)
    mech, dyn = _crank_rocker(rng)
    fa = kinetostatics(dyn, linkwork.solve(mech, np.linspace(0, 2 * np.pi, 25), accelerations=2.0))
    scale = np.abs(fa.shaking_force).max()
    np.testing.assert_allclose(fa.frame_force, fa.shaking_force, atol=1e-11 * scale)
    np.testing.assert_allclose(fa.frame_moment, fa.shaking_moment, atol=1e-11 * scale * 0.05)


def test_static_without_loads_has_no_forces():
    mech = linkwork.load("library:crank-rocker")
    fa = kinetostatics(Dynamics.build(mech), linkwork.solve(mech, [0.3, 1.0]), inertia=False)
    assert np.all(fa.effort == 0)
    assert all(np.all(r.force == 0) for r in fa.reactions.values())


def test_couple_on_output_by_virtual_work():
    # a couple M on the rocker: T = −M·ω_rocker/ω_crank, from the kinematics alone
    mech = linkwork.load("library:crank-rocker")
    dyn = Dynamics.build(mech, loads=Loads(couples=(Couple("rocker", 25.0),)))
    q = np.linspace(0, 2 * np.pi, 19)
    sol = linkwork.solve(mech, q, velocities=1.0)
    fa = kinetostatics(dyn, sol, inertia=False)
    np.testing.assert_allclose(fa.effort, -25.0 * sol.link("rocker").omega, rtol=1e-11, atol=1e-11)


def test_flywheel_from_sinusoidal_torque():
    # T = T0 + A·sin 2φ: ∫(T − T0) dφ = A(1 − cos 2φ)/2 swings by A; J = A / (δ ω²)
    phi = np.linspace(0, 2 * np.pi, 20001)
    fw = flywheel(phi, 3.0 + 40.0 * np.sin(2 * phi), mean_speed=10.0, fluctuation=0.02)
    assert fw.mean_effort == pytest.approx(3.0, abs=1e-9)
    assert fw.energy_fluctuation == pytest.approx(40.0, rel=1e-6)
    assert fw.inertia == pytest.approx(40.0 / (0.02 * 100.0), rel=1e-6)
