"""Mass data and loads of a mechanism (German *Massen* and *äußere Kräfte*), kept beside the
`Mechanism`, which stays the kinematic description and does not change.

`Dynamics` bundles a mechanism with its links' `MassProperties` and its `Loads`. Units are SI
for the dynamic quantities (kg, kg·m², N, N·m, N/m, N·s/m, m/s²); positions (centres of mass,
points of application, free lengths of springs) are in the mechanism's length unit, as in its
drawing, and `metres_per_unit` converts them. A point of a link is given by its design
coordinates, which are its coordinates in the link (`Mechanism`).

Loads are constant, or tabulated against the first driver's input (radians or the length unit)
or time (seconds), linearly interpolated (`LoadTable`), or any callable of (input, time) for
users of the Python interface.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Callable, Literal, Mapping, Union

import numpy as np

from ..errors import ModelError
from .mechanism import Mechanism, Revolute


def _vec(v, what: str) -> np.ndarray:
    arr = np.array(v, dtype=float)
    if arr.shape != (2,) or not np.isfinite(arr).all():
        raise ModelError(f"{what}: give two finite components [x, y], got {np.asarray(v).tolist()}")
    arr.setflags(write=False)
    return arr


def _finite(x, what: str, *, positive: bool = False, nonnegative: bool = False) -> float:
    x = float(x)
    if not np.isfinite(x) or (positive and not x > 0) or (nonnegative and not x >= 0):
        need = "a positive" if positive else "a non-negative" if nonnegative else "a finite"
        raise ModelError(f"{what}: expected {need} number, got {x:g}")
    return x


@dataclass(frozen=True)
class MassProperties:
    """Mass (kg), centre of mass (design coordinates, length unit) and moment of inertia about
    the centre of mass (kg·m², *Massenträgheitsmoment*) of one link."""

    mass: float
    center: np.ndarray
    inertia: float = 0.0


@dataclass(frozen=True)
class LoadTable:
    """Values tabulated against `of` ("input": the first driver's input; "time": seconds),
    linearly interpolated, held constant beyond the ends (`periodic`: wrapped over the table's
    span, as for a load over one crank turn). `values` has one row per abscissa."""

    of: Literal["input", "time"]
    abscissa: tuple[float, ...]
    values: tuple[tuple[float, ...], ...]
    periodic: bool = False

    def __call__(self, x: np.ndarray) -> np.ndarray:
        xs = np.asarray(self.abscissa)
        vals = np.asarray(self.values, dtype=float)
        x = np.asarray(x, dtype=float)
        if self.periodic:
            x = xs[0] + np.mod(x - xs[0], xs[-1] - xs[0])
        return np.stack([np.interp(x, xs, vals[:, k]) for k in range(vals.shape[1])], axis=-1)


#: a load's value: a constant, a table, or a callable f(input (N,), time (N,) or None) -> (N, k)
LoadValue = Union[float, np.ndarray, LoadTable, Callable]


@dataclass(frozen=True)
class PointForce:
    """A force (N) on `link` at the point with design coordinates `point`; `axes` "frame"
    (components fixed in the frame) or "link" (turning with the link)."""

    link: str
    point: np.ndarray
    force: LoadValue
    axes: Literal["frame", "link"] = "frame"
    name: str = ""


@dataclass(frozen=True)
class Couple:
    """A torque (N·m, counter-clockwise positive) on `link`."""

    link: str
    torque: LoadValue
    name: str = ""


@dataclass(frozen=True)
class LinearSpring:
    """A spring (and/or viscous damper) between `points` of `links` (design coordinates):
    tension = stiffness·(length − free_length) + preload + damping·(rate of length), in N;
    stiffness N/m, damping N·s/m, free length in the length unit (default: the design length,
    so the spring is relaxed in the drawing)."""

    links: tuple[str, str]
    points: tuple[np.ndarray, np.ndarray]
    stiffness: float = 0.0
    free_length: float | None = None
    preload: float = 0.0
    damping: float = 0.0
    name: str = ""


@dataclass(frozen=True)
class TorsionSpring:
    """A torsion spring (and/or rotary damper) in revolute pair `joint`: the torque on
    links[1] is −stiffness·(φ − free_angle) − damping·φ̇, with φ the relative angle of
    links[1] to links[0] from the design position (rad), stiffness N·m/rad, damping N·m·s/rad;
    links[0] receives the opposite torque."""

    joint: str
    stiffness: float = 0.0
    free_angle: float = 0.0
    damping: float = 0.0
    name: str = ""


@dataclass(frozen=True)
class PairFriction:
    """Coulomb friction in pair `joint` (an option of the force analysis): coefficient μ; in a
    revolute pair the friction torque μ·ρ·|R| with `radius` ρ of the journal (length unit),
    in a prismatic pair, slot, circular slot or cam contact the force μ·|N| along the relative
    sliding, opposing it. Where the pair does not move relative to itself the friction is
    taken as zero (sticking friction is statically indeterminate); a prismatic pair's couple
    (its edge pressures) adds no friction."""

    joint: str
    coefficient: float
    radius: float = 0.0


@dataclass(frozen=True)
class Loads:
    """The loads on a mechanism: gravity (m/s², acting at every centre of mass), point forces,
    couples, linear and torsion springs and dampers."""

    gravity: np.ndarray = field(default_factory=lambda: _vec([0.0, 0.0], "gravity"))
    forces: tuple[PointForce, ...] = ()
    couples: tuple[Couple, ...] = ()
    springs: tuple[LinearSpring, ...] = ()
    torsion_springs: tuple[TorsionSpring, ...] = ()
    friction: tuple[PairFriction, ...] = ()

    @property
    def has_gravity(self) -> bool:
        return bool(np.any(self.gravity != 0))


STANDARD_GRAVITY = 9.80665
#: pair kinds with a Coulomb friction model
FRICTION_PAIRS = ("revolute", "prismatic", "slot", "circular-slot", "cam")


@dataclass(frozen=True, eq=False)
class Dynamics:
    """A mechanism with the mass data of (some of) its moving links and its loads. Validated
    when built; the mass data are checked for completeness only when forces are computed
    (`require_masses`)."""

    mechanism: Mechanism
    masses: Mapping[str, MassProperties] = field(default_factory=lambda: MappingProxyType({}))
    loads: Loads = field(default_factory=Loads)
    metres_per_unit: float = 1e-3

    @classmethod
    def build(cls, mechanism: Mechanism, masses: Mapping[str, MassProperties] | None = None,
              loads: Loads | None = None, metres_per_unit: float | None = None) -> "Dynamics":
        if metres_per_unit is None:
            from ..units import parse_quantity
            metres_per_unit = parse_quantity(f"1 {mechanism.length_unit}", default_unit="m",
                                             kind="length unit")
        dyn = cls(mechanism, MappingProxyType(dict(masses or {})), loads or Loads(),
                  float(metres_per_unit))
        dyn._validate()
        return dyn

    def _validate(self) -> None:
        mech = self.mechanism
        for ln, mp in self.masses.items():
            if ln not in mech.link_index:
                raise ModelError(f"mass data for link '{ln}', which is not a link of "
                                 f"'{mech.name}'")
            _finite(mp.mass, f"link '{ln}' mass", nonnegative=True)
            _finite(mp.inertia, f"link '{ln}' moment of inertia", nonnegative=True)
            _vec(mp.center, f"link '{ln}' centre of mass")
        loads = self.loads
        _vec(loads.gravity, "gravity")
        for f in loads.forces:
            self._need_link(f.link, f"force '{f.name}'")
            _vec(f.point, f"force '{f.name}' point")
        for c in loads.couples:
            self._need_link(c.link, f"torque '{c.name}'")
        for s in loads.springs:
            for ln in s.links:
                self._need_link(ln, f"spring '{s.name}'")
            for p in s.points:
                _vec(p, f"spring '{s.name}' point")
            for what in ("stiffness", "preload", "damping"):
                _finite(getattr(s, what), f"spring '{s.name}' {what}")
            if s.free_length is not None:
                _finite(s.free_length, f"spring '{s.name}' free length", nonnegative=True)
            if np.hypot(*(np.asarray(s.points[1]) - s.points[0])) == 0 and s.free_length != 0:
                raise ModelError(f"spring '{s.name}': its two ends coincide in the drawing, so "
                                 "its direction is undefined there; draw them apart")
        for t in loads.torsion_springs:
            j = mech.joint(t.joint)
            if not isinstance(j, Revolute):
                raise ModelError(f"torsion spring '{t.name}': joint '{t.joint}' is a {j.kind} "
                                 "pair; a torsion spring sits in a revolute pair")
            for what in ("stiffness", "free_angle", "damping"):
                _finite(getattr(t, what), f"torsion spring '{t.name}' {what}")
        for fr in loads.friction:
            j = mech.joint(fr.joint)
            _finite(fr.coefficient, f"friction in '{fr.joint}' coefficient", nonnegative=True)
            _finite(fr.radius, f"friction in '{fr.joint}' journal radius", nonnegative=True)
            if j.kind not in FRICTION_PAIRS:
                raise ModelError(f"friction in '{fr.joint}': a {j.kind} pair has no friction "
                                 f"model (only {', '.join(FRICTION_PAIRS)})")
            if j.kind == "revolute" and not fr.radius > 0 and fr.coefficient > 0:
                raise ModelError(f"friction in revolute pair '{fr.joint}' needs the journal "
                                 "radius (the friction torque is μ·radius·|R|)")

    def _need_link(self, ln: str, what: str) -> None:
        if ln not in self.mechanism.link_index:
            raise ModelError(f"{what}: '{ln}' is not a link of '{self.mechanism.name}'")

    def require_masses(self, *, inertia: bool) -> None:
        """Every moving link needs mass data when inertia or gravity counts."""
        if not (inertia or self.loads.has_gravity):
            return
        missing = [ln for ln in self.mechanism.moving_links if ln not in self.masses]
        if missing:
            why = "inertia forces" if inertia else "gravity"
            raise ModelError(f"no mass data for link(s) {', '.join(repr(m) for m in missing)}: "
                             f"{why} need the mass, centre of mass and moment of inertia of "
                             "every moving link (give mass = 0 for a link without mass)")


__all__ = ["Couple", "Dynamics", "FRICTION_PAIRS", "PairFriction", "LinearSpring", "LoadTable", "LoadValue", "Loads",
           "MassProperties", "PointForce", "STANDARD_GRAVITY", "TorsionSpring"]
