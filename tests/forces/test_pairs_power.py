"""Every pair kind in the kinetostatics, checked by identities that do not use the reactions'
formulas: ideal pairs do no work, so driver power + power of all loads (inertia forces, gravity,
springs, dampers, forces in link axes, couples) is zero at every sample (power balance); and
the driver's effort equals the one from virtual work with the unit-speed velocities of a second
solve. Masses and loads are random."""

import zlib

import numpy as np
import pytest

import linkwork
from linkwork.errors import LinkworkWarning, ModelError
from linkwork.forces import kinetostatics
from linkwork.model.inertia import (Couple, Dynamics, LinearSpring, Loads, LoadTable, MassProperties,
                                    PointForce, TorsionSpring)
from mechanism_texts import (SCOTCH_YOKE, four_bar_from_lengths, four_bar_text, slider_crank_text,
                             two_crank_five_bar_text)

PLANETARY = """
name = "planet on a fixed sun"
[points]
S = [0, 0]
O = [30, 0]
K = [35, 4]
[links]
frame = ["S"]
arm = ["S", "O"]
planet = ["O", "K"]
[joints]
S = { type = "revolute", links = ["frame", "arm"] }
O = { type = "revolute", links = ["arm", "planet"] }
mesh = { type = "gear", links = ["frame", "planet"], carrier = "arm", radii = [20, 10] }
[driver]
joint = "S"
"""

CARDAN = PLANETARY.replace("[30, 0]", "[10, 0]").replace("[35, 4]", "[15, 3]").replace(
    'radii = [20, 10] }', 'radii = [20, 10], kind = "internal" }').replace("planet on a fixed sun", "Cardan")

GEAR_PAIR = """
name = "gear pair"
[points]
O1 = [0, 0]
O2 = [50, 0]
P = [5, 8]
Q = [58, 3]
[links]
frame = ["O1", "O2"]
pinion = ["O1", "P"]
wheel = ["O2", "Q"]
[joints]
O1 = { type = "revolute", links = ["frame", "pinion"] }
O2 = { type = "revolute", links = ["frame", "wheel"] }
mesh = { type = "gear", links = ["pinion", "wheel"], carrier = "frame", radii = [20, 30] }
[driver]
joint = "O1"
"""

RACK = """
name = "rack and pinion"
[points]
O = [0, 0]
K = [6, 4]
G = [0, -10]
R = [30, -14]
[links]
frame = ["O"]
pinion = ["O", "K"]
rack = ["G", "R"]
[joints]
O = { type = "revolute", links = ["frame", "pinion"] }
guide = { type = "prismatic", links = ["frame", "rack"], axis = [1, 0], point = "G" }
mesh = { type = "gear", links = ["pinion", "rack"], carrier = "frame", radii = [10], kind = "rack", point = "G" }
[driver]
joint = "O"
"""

TEXTS = {
    "scotch-yoke": SCOTCH_YOKE,
    "curved-slot": four_bar_text(curved_slot=True),
    "pin-in-slot": slider_crank_text(name="pin in slot", A=(30, 40), B=(150, 0), slot=True),
    "planetary": PLANETARY,
    "cardan": CARDAN,
    "gear-pair": GEAR_PAIR,
    "rack": RACK,
    "slider-driven": slider_crank_text(name="slider driven", A=(30, 40), B=(150, 0),
                                       driver="guide"),
}
LIBRARY = ["crank-rocker", "slider-crank-offset", "whitworth-quick-return",
           "oscillating-crank-slotted-lever", "rotating-crank-slotted-lever", "ellipsograph",
           "stephenson-iii-six-bar", "watt-i-six-bar", "jansen-linkage", "radial-roller-cam",
           "flat-faced-cam", "oscillating-roller-cam", "offset-roller-cam", "elliptical-gears",
           "proell-schwabe-valve-gear", "crank-driven-wedge", "sulzer-valve-gear"]


def _mechanism(name):
    return linkwork.load(f"library:{name}") if name in LIBRARY else linkwork.load_text(TEXTS[name])


def _random_dynamics(mech, rng):
    L = mech.length_scale
    masses = {}
    for ln in mech.moving_links:
        xy = np.array([mech.points[p] for p in mech.link(ln).points])
        masses[ln] = MassProperties(rng.uniform(0.5, 3.0), xy.mean(axis=0) + rng.uniform(-0.2, 0.2, 2) * L,
                                    rng.uniform(1e-4, 1e-3))
    moving = list(mech.moving_links)
    a, b = moving[0], moving[-1]
    pa = mech.points[mech.link(a).points[-1]]
    pb = mech.points[mech.link(b).points[0]] + np.array([0.1, 0.05]) * L
    hinge = next((j for j in mech.joints if j.kind == "revolute"), None)
    table = LoadTable("input", tuple(np.linspace(-10, 10, 7)), tuple(map(tuple, rng.uniform(-5, 5, (7, 2)))))
    loads = Loads(
        gravity=np.array([0.0, -9.81]),
        forces=(PointForce(b, pb, table, axes="link", name="tabled"),
                PointForce(a, pa, [3.0, -2.0], name="constant")),
        couples=(Couple(moving[len(moving) // 2], lambda q, t: 0.5 * np.sin(q), name="f(q)"),),
        springs=(LinearSpring((mech.frame, b), (pb + [0.3 * L, 0.2 * L], pb), stiffness=2000.0,
                              free_length=0.1 * L, damping=5.0, name="s"),),
        torsion_springs=() if hinge is None else (TorsionSpring(hinge.name, 0.7, 0.1, 0.02, name="t"),),
    )
    return Dynamics.build(mech, masses, loads)


@pytest.mark.parametrize("name", sorted(TEXTS) + LIBRARY)
def test_power_balance_and_virtual_work(name):
    rng = np.random.default_rng(zlib.crc32(name.encode()))
    mech = _mechanism(name)
    dyn = _random_dynamics(mech, rng)
    revolute = mech.joint(mech.drivers[0].joint).kind == "revolute"
    sol = linkwork.whole_motion(mech, step=np.radians(6) if revolute else None)
    if name == "crank-driven-wedge":  # over-closed: reactions indeterminate, the effort is not
        with pytest.warns(LinkworkWarning, match="over-closed"):
            fa = kinetostatics(dyn, sol)
    else:
        fa = kinetostatics(dyn, sol)
    ok = fa.solved
    assert ok.mean() > 0.8
    rel = np.abs(fa.power_residual[ok]) / fa.power_scale[ok]
    assert rel.max() < 1e-9
    jn = mech.drivers[0].joint
    T, Tv = fa.efforts[jn][ok], fa.virtual_work[jn][ok]
    assert np.abs(T - Tv).max() <= 1e-9 * np.abs(T).max()


def test_intermittent_pairs_are_refused():
    mech = linkwork.load("library:geneva-4")
    dyn = Dynamics.build(mech)
    with pytest.raises(ModelError, match="intermittent"):
        kinetostatics(dyn, linkwork.solve(mech, [0.1]), inertia=False)


def test_two_drivers_each_by_virtual_work():
    # a five-bar with two driven cranks: each driver's torque from its own unit-speed motion
    mech = linkwork.load_text(two_crank_five_bar_text())
    dyn = _random_dynamics(mech, np.random.default_rng(11))
    t = np.linspace(0.0, 0.35, 15)  # the cranks stay within reach of the dyad
    q0 = [mech.driver_input_at_design(d) for d in mech.drivers]
    inputs = np.column_stack([q0[0] + 2.0 * t, q0[1] - 1.0 * t])
    sol = linkwork.solve(mech, inputs, velocities=[2.0, -1.0], accelerations=[0.5, 0.3])
    fa = kinetostatics(dyn, sol)
    ok = fa.solved
    assert ok.all()
    assert np.max(np.abs(fa.power_residual) / fa.power_scale) < 1e-9
    for d in mech.drivers:
        T, Tv = fa.efforts[d.joint], fa.virtual_work[d.joint]
        assert np.abs(T - Tv).max() <= 1e-9 * np.abs(T).max(), d.joint


@pytest.mark.parametrize("seed", range(6))
def test_power_balance_on_random_four_bars(seed):
    # Grashof crank-rockers of random proportions (shortest link the crank), random masses and
    # loads, random crank speed and acceleration
    rng = np.random.default_rng(100 + seed)
    while True:
        a, b, c, d = rng.uniform(5, 10), rng.uniform(20, 60), rng.uniform(20, 60), rng.uniform(20, 60)
        if a + max(b, c, d) < b + c + d - max(b, c, d):  # Grashof: s + l < p + q, crank the shortest
            break
    mech = linkwork.load_text(four_bar_from_lengths(d, a, b, c, rng.uniform(0, 360)))
    dyn = _random_dynamics(mech, rng)
    q = np.linspace(0, 2 * np.pi, 73)
    fa = kinetostatics(dyn, linkwork.solve(mech, q, velocities=rng.uniform(-20, 20),
                                           accelerations=rng.uniform(-50, 50)))
    assert fa.solved.all()
    assert np.max(np.abs(fa.power_residual) / fa.power_scale) < 1e-9
    T = fa.effort
    assert np.abs(T - fa.virtual_work["O2"]).max() <= 1e-9 * np.abs(T).max()
