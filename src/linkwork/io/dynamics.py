"""Mass data and loads from a mechanism file's [masses] and [loads] sections -> `Dynamics`
(`model.inertia`), with errors that name the key and its line like the rest of `io`.

Bare numbers are in SI units (kg, kg·m², N, N·m, N/m, N·s/m, N·m/rad, m/s²), lengths and
coordinates in the file's length unit, angles in its angle unit; a string carries its own
unit ("0.5 kg", "1200 g*cm^2", "2 N/mm", "15 deg"). Whether every moving link has mass data is
checked only when forces are computed (`Dynamics.require_masses`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import InputError, MechanismFileError, ModelError
from ..model import Mechanism
from ..model.inertia import (STANDARD_GRAVITY, Couple, Dynamics, LinearSpring, Loads, LoadTable,
                             MassProperties, PairFriction, PointForce, TorsionSpring)
from ..units import parse_quantity
from . import schema
from .files import LIBRARY_PREFIX, _did_you_mean, _dotted, _line_of, parse, resolve


def load_dynamics(spec: str | Path) -> Dynamics:
    """The mechanism of a file path or `library:NAME` with its mass data and loads."""
    source, text = resolve(spec)
    base = None if str(spec).startswith(LIBRARY_PREFIX) else Path(spec).resolve().parent
    return dynamics_from_text(text, source=source, base_dir=base)


def dynamics_from_text(text: str, *, source: str = "<text>", base_dir: Path | None = None) -> Dynamics:
    mech, spec = parse(text, source=source, base_dir=base_dir)
    return build_dynamics(mech, spec, text, source)


def build_dynamics(mech: Mechanism, spec: schema.MechanismFile, text: str, source: str) -> Dynamics:
    def fail(loc: tuple, msg: str):
        raise MechanismFileError(msg, source=source, key=_dotted(loc), line=_line_of(text, loc))

    def quantity(loc: tuple, value, unit: str, what: str, nonnegative: bool = False) -> float:
        try:
            x = parse_quantity(value, default_unit=unit, kind=what)
        except InputError as exc:
            fail(loc, str(exc))
        if nonnegative and x < 0:
            fail(loc, f"{what} must not be negative, got {value!r}")
        return x

    metres = parse_quantity(f"1 {mech.length_unit}", default_unit="m", kind="length unit")
    length = f"{mech.length_unit}"
    deg = not spec.units.angle.startswith("rad")

    def point(loc: tuple, ref) -> np.ndarray:
        if isinstance(ref, str):
            if ref not in mech.points:
                fail(loc, f"point '{ref}', which is not in [points]{_did_you_mean(ref, mech.points)}")
            return np.array(mech.points[ref])
        return np.array(ref, dtype=float)

    def link(loc: tuple, name: str) -> str:
        if name not in mech.link_index:
            fail(loc, f"link '{name}', which is not in [links]{_did_you_mean(name, mech.link_index)}")
        return name

    def joint(loc: tuple, name: str) -> str:
        if name not in mech.joint_index:
            fail(loc, f"joint '{name}', which is not in [joints]{_did_you_mean(name, mech.joint_index)}")
        return name

    def table(t: schema.LoadTableSpec, k: int, loc: tuple) -> LoadTable:
        vals = []
        for i, v in enumerate(t.values):
            if (k == 1) != (not isinstance(v, list)):
                fail(loc + ("values", i), "a torque's table has numbers, a force's [x, y] pairs")
            vals.append(tuple(np.atleast_1d(np.asarray(v, dtype=float))))
        scale = np.pi / 180 if (t.of == "input" and deg and _revolute_input(mech)) else 1.0
        return LoadTable(t.of, tuple(scale * a for a in t.at), tuple(vals), t.periodic)

    masses = {}
    for ln, m in spec.masses.items():
        loc = ("masses", ln)
        link(loc, ln)
        if ln == mech.frame:
            fail(loc, f"'{ln}' is the frame: it does not move, its mass plays no part")
        masses[ln] = MassProperties(
            quantity(loc + ("mass",), m.mass, "kg", f"link '{ln}' mass", True),
            point(loc + ("center",), m.center),
            quantity(loc + ("inertia",), m.inertia, "kg*m^2", f"link '{ln}' moment of inertia", True))
    ls = spec.loads or schema.LoadsSpec()
    if ls.gravity is True:
        g = np.array([0.0, -STANDARD_GRAVITY])
    elif ls.gravity is False:
        g = np.zeros(2)
    else:
        g = np.array(ls.gravity, dtype=float)
    forces = []
    for i, f in enumerate(ls.forces):
        loc = ("loads", "forces", i)
        value = table(f.force, 2, loc + ("force",)) if isinstance(f.force, schema.LoadTableSpec) \
            else np.array(f.force, dtype=float)
        forces.append(PointForce(link(loc + ("link",), f.link), point(loc + ("point",), f.point),
                                 value, f.axes, name=f"loads.forces[{i}]"))
    couples = []
    for i, c in enumerate(ls.torques):
        loc = ("loads", "torques", i)
        value = table(c.torque, 1, loc + ("torque",)) if isinstance(c.torque, schema.LoadTableSpec) \
            else quantity(loc + ("torque",), c.torque, "N*m", f"torque {i}")
        couples.append(Couple(link(loc + ("link",), c.link), value, name=f"loads.torques[{i}]"))
    springs = []
    for i, s in enumerate(ls.springs):
        loc = ("loads", "springs", i)
        what = f"spring {i}"
        springs.append(LinearSpring(
            tuple(link(loc + ("links",), ln) for ln in s.links),
            tuple(point(loc + ("points",), p) for p in s.points),
            quantity(loc + ("stiffness",), s.stiffness, "N/m", f"{what} stiffness"),
            None if s.free_length is None else quantity(loc + ("free_length",), s.free_length,
                                                        length, f"{what} free length", True),
            quantity(loc + ("preload",), s.preload, "N", f"{what} preload"),
            quantity(loc + ("damping",), s.damping, "N*s/m", f"{what} damping"),
            name=f"loads.springs[{i}]"))
    torsion = []
    for i, t in enumerate(ls.torsion_springs):
        loc = ("loads", "torsion_springs", i)
        joint(loc + ("joint",), t.joint)
        free = t.free_angle
        free = quantity(loc + ("free_angle",), free, "rad", "free angle") if isinstance(free, str) \
            else (np.radians(free) if deg else float(free))
        torsion.append(TorsionSpring(
            t.joint, quantity(loc + ("stiffness",), t.stiffness, "N*m/rad", "torsion stiffness"),
            float(free), quantity(loc + ("damping",), t.damping, "N*m*s/rad", "rotary damping"),
            name=f"loads.torsion_springs[{i}]"))
    friction = []
    for i, fr in enumerate(ls.friction):
        loc = ("loads", "friction", i)
        joint(loc + ("joint",), fr.joint)
        friction.append(PairFriction(fr.joint, float(fr.coefficient), quantity(
            loc + ("radius",), fr.radius, length, "journal radius", True)))
    loads = Loads(gravity=g, forces=tuple(forces), couples=tuple(couples), springs=tuple(springs),
                  torsion_springs=tuple(torsion), friction=tuple(friction))
    try:
        return Dynamics.build(mech, masses, loads, metres_per_unit=metres)
    except ModelError as exc:
        raise MechanismFileError(str(exc), source=source,
                                 key="loads" if spec.loads else "masses",
                                 line=_line_of(text, ("loads",) if spec.loads else ("masses",))) from None


def _revolute_input(mech: Mechanism) -> bool:
    return bool(mech.drivers) and mech.joint(mech.drivers[0].joint).kind == "revolute"
