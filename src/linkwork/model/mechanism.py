"""`Mechanism`: the immutable description of a planar mechanism in its design position.

The design position defines everything (as a draftsman expects): each named point has its
drawing coordinates, every link carries a set of points, and lengths, angles, slot radii and
the assembly branch all follow from that drawing. Each link's own coordinate system coincides
with the frame's at the design position, so a point's design coordinates are also its
coordinates in its link.

Pairs (German *Elementenpaare*, Latvian *kinēmatiskie pāri*):
`Revolute` (hinge, *Drehpaar*), `Prismatic` (block on a guide, *Schubpaar*), `Slot` (pin in a
straight slot, turning and sliding), `CircularSlot` (pin in a curved slot, *Kulisse*),
`Gear` (pitch circles rolling, *Zahnräderpaar*); the higher pairs `CamContact` and
`RollingContact` (`higher_pairs`) keep profiles (`geometry.profiles`) in contact; the
intermittent pairs `GenevaPair` and `StarWheelPair` (`intermittent`) change with the phase.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from types import MappingProxyType
from typing import Mapping, Union

import numpy as np

from ..errors import ModelError
from ..geometry.profiles import Profile
from .higher_pairs import CamContact, RollingContact, validate_higher_pair, with_pivot_carrier
from .given import normalized
from .intermittent import GenevaPair, StarWheelPair, validate_intermittent
from .laws import ConstantSpeed, MotionLaw, PolynomialLaw, TabulatedLaw

_TOL = 1e-9


def _ro(a) -> np.ndarray:
    arr = np.array(a, dtype=float)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class Link:
    """A rigid plane (*Glied*, *loceklis*) carrying named points."""

    name: str
    points: tuple[str, ...]


@dataclass(frozen=True)
class Revolute:
    """Hinge at `point`, shared by both links."""

    name: str
    point: str
    links: tuple[str, str]
    kind = "revolute"


@dataclass(frozen=True)
class Prismatic:
    """Block `links[1]` slides along the line through `point` with direction `axis`, fixed in
    `links[0]`, without turning relative to it (slider on the frame, block in a Kulisse)."""

    name: str
    point: str
    links: tuple[str, str]
    axis: np.ndarray
    kind = "prismatic"


@dataclass(frozen=True)
class Slot:
    """Pin `point` of `links[1]` slides along the straight line through it with direction `axis`,
    fixed in `links[0]`, and may turn (pin in slot; the die block folded into one pair)."""

    name: str
    point: str
    links: tuple[str, str]
    axis: np.ndarray
    kind = "slot"


@dataclass(frozen=True)
class CircularSlot:
    """Point `point` of `links[1]` is guided on the circular arc about `center` (a point of
    `links[0]`) through its design position: curved Kulisse, as in Stephenson's and
    Heusinger's valve gears."""

    name: str
    point: str
    links: tuple[str, str]
    center: str
    kind = "circular-slot"

    def radius(self, mech: "Mechanism") -> float:
        return float(np.hypot(*(mech.points[self.point] - mech.points[self.center])))


@dataclass(frozen=True)
class Gear:
    """Pitch circles of `links[0]` and `links[1]` roll without slip; both wheels are pivoted on
    `carrier`. `kind` is 'external', 'internal' or 'rack' (then `links[1]` is the rack, which
    must slide on the carrier by a prismatic pair, and only the pinion radius is used)."""

    name: str
    links: tuple[str, str]
    carrier: str
    radii: tuple[float, float]
    gear_kind: str = "external"
    point: str | None = None
    kind = "gear"


Joint = Union[Revolute, Prismatic, Slot, CircularSlot, Gear, CamContact, RollingContact, GenevaPair,
              StarWheelPair]


@dataclass(frozen=True)
class Driver:
    """A pair with prescribed motion.

    Revolute driver: input = angle (radians, counter-clockwise from the base link's x-axis, i.e.
    the frame's x-axis for a driver on the frame) of the line from the hinge to the `reference`
    point of the driven link. Prismatic driver: displacement along the axis from the design
    position (so its design value is 0).
    """

    joint: str
    driven: str
    base: str
    reference: str | None
    law: MotionLaw = field(default_factory=ConstantSpeed)


@dataclass(frozen=True, eq=False)
class Mechanism:
    """A validated, immutable planar mechanism. Build it with `Mechanism.build` or load a file
    with `linkwork.load`."""

    name: str
    length_unit: str
    points: Mapping[str, np.ndarray]
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    drivers: tuple[Driver, ...]
    frame: str
    description: str = ""
    profiles: Mapping[str, Profile] = field(default_factory=lambda: MappingProxyType({}))
    #: given point velocities or directions (`given`): the inputs of a chain without drivers
    given: tuple = ()

    # ------------------------------------------------------------------ construction
    @classmethod
    def build(cls, *, name: str, points: Mapping[str, object], links: Mapping[str, list[str]],
              joints: list[Joint], drivers: list[dict] | list[Driver], frame: str = "frame",
              length_unit: str = "mm", description: str = "",
              profiles: Mapping[str, Profile] | None = None, given=()) -> "Mechanism":
        pts = {k: _ro(v) for k, v in points.items()}
        for k, v in pts.items():
            if v.shape != (2,) or not np.isfinite(v).all():
                raise ModelError(f"point '{k}': give two finite coordinates [x, y], got "
                                 f"{np.asarray(points[k]).tolist()}")
        link_objs = tuple(Link(n, tuple(p)) for n, p in links.items())
        joint_objs = tuple(joints)
        # non-circular gears on two axles of one link: the rolling pair's carrier (h = 1)
        joint_objs = tuple(with_pivot_carrier(j, joint_objs) if isinstance(j, RollingContact) else j
                           for j in joint_objs)
        mech_drivers = tuple(d if isinstance(d, Driver) else _make_driver(d, joint_objs, frame, link_objs)
                             for d in drivers)
        mech = cls(name=name, length_unit=length_unit, points=MappingProxyType(pts),
                   links=link_objs, joints=joint_objs, drivers=mech_drivers, frame=frame,
                   description=description, profiles=MappingProxyType(dict(profiles or {})))
        mech._validate()
        if given:
            object.__setattr__(mech, "given", normalized(mech, given))
        return mech

    # ------------------------------------------------------------------ lookups
    @cached_property
    def link_names(self) -> tuple[str, ...]:
        return tuple(link.name for link in self.links)

    @cached_property
    def link_index(self) -> Mapping[str, int]:
        return MappingProxyType({n: i for i, n in enumerate(self.link_names)})

    @cached_property
    def joint_index(self) -> Mapping[str, Joint]:
        return MappingProxyType({j.name: j for j in self.joints})

    def link(self, name: str) -> Link:
        try:
            return self.links[self.link_index[name]]
        except KeyError:
            raise ModelError(f"mechanism '{self.name}' has no link '{name}'") from None

    def joint(self, name: str) -> Joint:
        try:
            return self.joint_index[name]
        except KeyError:
            raise ModelError(f"mechanism '{self.name}' has no joint '{name}'") from None

    @cached_property
    def point_owner(self) -> Mapping[str, str]:
        """For every point, the link whose motion reports it: the first link listing it,
        preferring a moving link over the frame (a slider's point moves with the slider) except
        at the frame's own hinges, which stand still whatever the link on them does (also where
        its rates are undefined, at a singular position)."""
        hinges = {j.point for j in self.joints if isinstance(j, Revolute) and self.frame in j.links}
        owner: dict[str, str] = {}
        for link in self.links:
            for p in link.points:
                if p not in owner or (owner[p] == self.frame and p not in hinges):
                    owner[p] = link.name
        return MappingProxyType(owner)

    @cached_property
    def moving_links(self) -> tuple[str, ...]:
        return tuple(n for n in self.link_names if n != self.frame)

    @cached_property
    def length_scale(self) -> float:
        """Characteristic length: the diagonal of the design drawing's bounding box."""
        xy = np.array(list(self.points.values()))
        span = np.ptp(xy, axis=0) if len(xy) > 1 else np.zeros(2)
        return float(np.hypot(*span)) or 1.0

    def wheel_centre(self, gear: Gear, wheel: str) -> str:
        """The hinge point by which `wheel` is pivoted on the gear's carrier."""
        for j in self.joints:
            if isinstance(j, Revolute) and set(j.links) == {wheel, gear.carrier}:
                return j.point
        raise ModelError(f"gear '{gear.name}': wheel '{wheel}' has no revolute pair with its "
                         f"carrier '{gear.carrier}'")

    def rack_guide(self, gear: Gear) -> Prismatic:
        for j in self.joints:
            if isinstance(j, Prismatic) and set(j.links) == {gear.links[1], gear.carrier}:
                return j
        raise ModelError(f"gear '{gear.name}': rack '{gear.links[1]}' has no prismatic pair "
                         f"with the carrier '{gear.carrier}'")

    def driver_input_at_design(self, driver: Driver) -> float:
        joint = self.joint(driver.joint)
        if isinstance(joint, Prismatic):
            return 0.0
        d = self.points[driver.reference] - self.points[joint.point]
        return float(np.arctan2(d[1], d[0]))

    # ------------------------------------------------------------------ validation
    def _validate(self) -> None:
        names = set(self.link_names)
        if len(names) != len(self.links):
            raise ModelError("two links have the same name")
        if self.frame not in names:
            raise ModelError(f"there is no frame link '{self.frame}' (name the fixed link "
                             f"'{self.frame}' or set frame = \"...\")")
        for link in self.links:
            if not link.points and link.name != self.frame:
                raise ModelError(f"link '{link.name}' carries no points")
            for p in link.points:
                if p not in self.points:
                    raise ModelError(f"link '{link.name}' lists point '{p}', which is not in [points]")
            if len(link.points) >= 2:
                xy = np.array([self.points[p] for p in link.points])
                spread = float(np.ptp(xy, axis=0).max())
                if spread <= _TOL * self.length_scale:
                    raise ModelError(
                        f"link '{link.name}': all its points coincide, so its angle is undefined"
                        if spread == 0 else
                        f"link '{link.name}': its points lie within {spread:.3g} of each other, "
                        f"which is no length next to the drawing's size {self.length_scale:.3g} "
                        "(check the coordinates: a point far away shrinks every link)")
        self._validate_pair_spans()
        seen: set[str] = set()
        for j in self.joints:
            if j.name in seen:
                raise ModelError(f"two joints are named '{j.name}'")
            seen.add(j.name)
            for ln in j.links:
                if ln not in names:
                    raise ModelError(f"joint '{j.name}' names link '{ln}', which is not in [links]")
            if j.links[0] == j.links[1]:
                raise ModelError(f"joint '{j.name}' joins link '{j.links[0]}' to itself")
            self._validate_joint(j)
        for d in self.drivers:
            self._validate_driver(d)

    def _validate_pair_spans(self) -> None:
        """A moving link hinged at two or more points and held by nothing else must not have them
        all in one place: it would be a link of zero length (its angle undefined, every dyad
        through it unreachable). Coaxial hinges on a wheel that a gear, a guide or a higher pair
        turns are fine."""
        hinges: dict[str, set[str]] = {}
        turned_otherwise: set[str] = set()  # links whose angle another pair sets (gear, guide, cam)
        for j in self.joints:
            if isinstance(j, Revolute) and j.point in self.points:
                for ln in j.links:
                    hinges.setdefault(ln, set()).add(j.point)
            elif not isinstance(j, Revolute):
                turned_otherwise.update(j.links)
        for ln, pts in hinges.items():
            if ln == self.frame or len(pts) < 2 or ln in turned_otherwise:
                continue
            xy = np.array([self.points[p] for p in sorted(pts)])
            if np.ptp(xy, axis=0).max() <= _TOL * self.length_scale:
                names = ", ".join(f"'{p}'" for p in sorted(pts))
                raise ModelError(f"link '{ln}': its hinges {names} are at one place, so it has "
                                 "zero length between them; draw them apart (or join the pairs at "
                                 "one point)")

    def _has(self, link: str, point: str) -> bool:
        return point in self.link(link).points

    def _validate_joint(self, j: Joint) -> None:
        if isinstance(j, (CamContact, RollingContact)):
            validate_higher_pair(self, j)
            return
        if isinstance(j, (GenevaPair, StarWheelPair)):
            validate_intermittent(self, j)
            return
        if isinstance(j, Gear):
            if j.carrier not in self.link_index:
                raise ModelError(f"gear '{j.name}': carrier '{j.carrier}' is not a link")
            c1 = self.points[self.wheel_centre(j, j.links[0])]
            if j.gear_kind == "rack":
                guide = self.rack_guide(j)
                n = np.array([-guide.axis[1], guide.axis[0]])
                if not j.radii[0] > 0:
                    raise ModelError(f"gear '{j.name}': the pinion radius must be positive")
                # the rack's pitch line lies at distance r from the pinion centre
                if j.point is not None:
                    off = abs(float(np.dot(self.points[j.point] - c1, n)))
                    if abs(off - j.radii[0]) > 1e-6 * max(1.0, j.radii[0]):
                        raise ModelError(f"gear '{j.name}': pitch point is {off:g} from the pinion "
                                         f"centre, but the pinion radius is {j.radii[0]:g}")
                return
            c2 = self.points[self.wheel_centre(j, j.links[1])]
            dist = float(np.hypot(*(c2 - c1)))
            r1, r2 = j.radii
            if not (r1 > 0 and r2 > 0 and np.isfinite(r1) and np.isfinite(r2)):
                raise ModelError(f"gear '{j.name}': pitch radii must be positive, got {r1:g}, {r2:g}")
            want = r1 + r2 if j.gear_kind == "external" else abs(r1 - r2)
            if abs(dist - want) > 1e-6 * max(1.0, want):
                raise ModelError(
                    f"gear '{j.name}': the wheel centres are {dist:g} apart, but {j.gear_kind} "
                    f"pitch circles of radii {r1:g} and {r2:g} need {want:g}")
            return
        if j.point not in self.points:
            raise ModelError(f"joint '{j.name}': point '{j.point}' is not in [points]")
        if isinstance(j, (Prismatic, Slot)):
            axis = np.asarray(j.axis, dtype=float)
            if axis.shape != (2,) or not np.isfinite(axis).all() or not np.hypot(*axis) > 0:
                raise ModelError(f"{j.kind} joint '{j.name}': the axis must be a finite, non-zero "
                                 f"direction, got {axis.tolist()}")
        a, b = j.links
        if isinstance(j, Revolute):
            for ln in (a, b):
                if not self._has(ln, j.point) and ln != self.frame:
                    raise ModelError(f"revolute joint '{j.name}': link '{ln}' does not carry "
                                     f"point '{j.point}' (list it under [links])")
        elif isinstance(j, (Prismatic, Slot)):
            if not self._has(b, j.point):
                raise ModelError(f"{j.kind} joint '{j.name}': the sliding link '{b}' does not "
                                 f"carry point '{j.point}'")
        elif isinstance(j, CircularSlot):
            if not self._has(b, j.point):
                raise ModelError(f"circular-slot joint '{j.name}': link '{b}' does not carry "
                                 f"point '{j.point}'")
            if j.center not in self.points or (not self._has(a, j.center) and a != self.frame):
                raise ModelError(f"circular-slot joint '{j.name}': the centre '{j.center}' must "
                                 f"be a point of the slotted link '{a}'")
            if j.radius(self) <= _TOL * self.length_scale:
                raise ModelError(f"circular-slot joint '{j.name}': point and centre coincide "
                                 "(zero slot radius)")

    def _validate_driver(self, d: Driver) -> None:
        j = self.joint(d.joint)
        law = d.law
        numbers = {ConstantSpeed: lambda: (law.speed, law.start),
                   PolynomialLaw: lambda: (*law.coefficients, law.span),
                   TabulatedLaw: lambda: (*law.times, *law.values)}.get(type(law), lambda: ())()
        if not np.isfinite(np.asarray(numbers, dtype=float)).all():
            raise ModelError(f"driver '{d.joint}': its motion law has a number that is not finite")
        if isinstance(law, PolynomialLaw) and (not law.coefficients or not law.span > 0):
            raise ModelError(f"driver '{d.joint}': a polynomial law needs at least one "
                             "coefficient and a positive duration")
        if isinstance(law, TabulatedLaw) and (len(law.times) != len(law.values) or len(law.times) < 2
                                              or np.any(np.diff(law.times) <= 0)):
            raise ModelError(f"driver '{d.joint}': a law table needs as many values as times, "
                             "at least two, at increasing times")
        if not isinstance(j, (Revolute, Prismatic)):
            raise ModelError(f"driver joint '{d.joint}' is a {j.kind} pair; only revolute and "
                             "prismatic pairs can be drivers")
        if isinstance(j, Revolute):
            ref = d.reference
            if ref is None or ref not in self.link(d.driven).points and d.driven != self.frame:
                raise ModelError(f"driver '{d.joint}': reference point '{ref}' is not a point of "
                                 f"the driven link '{d.driven}'")
            if np.hypot(*(self.points[ref] - self.points[j.point])) <= _TOL * self.length_scale:
                raise ModelError(f"driver '{d.joint}': reference point '{ref}' coincides with "
                                 "the hinge, so the input angle is undefined")


def _make_driver(spec: dict, joints: tuple[Joint, ...], frame: str,
                 links: tuple[Link, ...]) -> Driver:
    """Fill in the driven and base links and the default reference point of a driver."""
    byname = {j.name: j for j in joints}
    jname = spec["joint"]
    if jname not in byname:
        raise ModelError(f"driver joint '{jname}' is not in [joints]")
    j = byname[jname]
    if not isinstance(j, (Revolute, Prismatic)):
        raise ModelError(f"driver joint '{jname}' is a {j.kind} pair; only revolute and "
                         "prismatic pairs can be drivers")
    a, b = j.links
    driven, base = (a, b) if b == frame else (b, a)
    if isinstance(j, Prismatic):
        driven, base = b, a
    ref = spec.get("reference")
    if ref is None and isinstance(j, Revolute):
        pts = next((link.points for link in links if link.name == driven), None)
        if pts is None:
            raise ModelError(f"driver '{jname}': the driven link '{driven}' is not in [links]")
        others = [p for p in pts if p != j.point]
        if not others:
            raise ModelError(f"driver '{jname}': the driven link '{driven}' has no point besides "
                             "the hinge to measure its angle by; add one or set reference")
        ref = others[0]
    return Driver(joint=jname, driven=driven, base=base, reference=ref,
                  law=spec.get("law") or ConstantSpeed())
