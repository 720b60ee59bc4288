"""The mechanism file format, as pydantic models: the single source of its JSON schema.

Files written in the documented shape must keep loading; new keys may be added. Unknown keys
are errors (a typo must not be ignored silently).
"""

from __future__ import annotations

from typing import Annotated, Literal, Union

from pydantic import (BaseModel, ConfigDict, Discriminator, Field, Strict, Tag, field_validator,
                      model_validator)

from .profiles import ProfileSpec
from .values import Number, PositiveNumber

Coordinates = Annotated[list[Number], Field(min_length=2, max_length=2)]
# an axis is a direction vector [x, y] or an angle (degrees unless a unit is written)
Axis = Union[Coordinates, Number, str]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class Units(_Strict):
    length: str = "mm"
    angle: Literal["deg", "degree", "rad", "radian"] = "deg"


class RevoluteSpec(_Strict):
    type: Literal["revolute"]
    links: Annotated[list[str], Field(min_length=2, max_length=2)]
    point: str | None = Field(None, description="hinge point; defaults to the joint's name")


class PrismaticSpec(_Strict):
    type: Literal["prismatic"]
    links: Annotated[list[str], Field(min_length=2, max_length=2)]
    axis: Axis = Field(description="guide direction, fixed in the first link")
    point: str | None = None


class SlotSpec(_Strict):
    type: Literal["slot"]
    links: Annotated[list[str], Field(min_length=2, max_length=2)]
    axis: Axis = Field(description="slot direction, fixed in the first link; the pin belongs to the second")
    point: str | None = None


class CircularSlotSpec(_Strict):
    type: Literal["circular-slot"]
    links: Annotated[list[str], Field(min_length=2, max_length=2)]
    center: str = Field(description="centre of the arc, a point of the first (slotted) link")
    point: str | None = None


class GearSpec(_Strict):
    type: Literal["gear"]
    links: Annotated[list[str], Field(min_length=2, max_length=2)]
    carrier: str = "frame"
    radii: Annotated[list[PositiveNumber], Field(min_length=1, max_length=2)]
    kind: Literal["external", "internal", "rack"] = "external"
    point: str | None = None


class CamSpec(_Strict):
    type: Literal["cam"]
    links: Annotated[list[str], Field(min_length=2, max_length=2)] = Field(
        description="the link carrying the profile, then the follower")
    profile: str = Field(description="the profile (a [profiles] name) carried by the first link")
    follower: Literal["roller", "knife", "flat", "profile"] = Field(
        description="the follower's element: a roller (circle of `radius` about `point`), a knife "
                    "edge at `point`, a flat face through `point` along `axis`, or the profile `mate`")
    point: str | None = Field(None, description="roller centre, knife tip or a point of the flat "
                                                "face, carried by the follower; defaults to the joint's name")
    radius: PositiveNumber | None = Field(None, description="roller radius")
    axis: Axis | None = Field(None, description="direction of the flat face, fixed in the follower")
    mate: str | None = Field(None, description="the follower's profile (follower = \"profile\")")


class RollingSpec(_Strict):
    type: Literal["rolling"]
    links: Annotated[list[str], Field(min_length=2, max_length=2)]
    profiles: Annotated[list[str], Field(min_length=2, max_length=2)] = Field(
        description="the profile of each link; they touch in the drawing and roll without slip")
    carrier: str | None = Field(None, description="the link carrying both wheels' axles "
                                "(non-circular gears; found when both links are hinged to one link)")


class GenevaSpec(_Strict):
    type: Literal["geneva"]
    links: Annotated[list[str], Field(min_length=2, max_length=2)] = Field(
        description="the driver carrying the pin, then the slotted wheel (Malteserkreuz)")
    pin: str | None = Field(None, description="the pin (Triebstock), a point of the driver; "
                                              "defaults to the joint's name")
    slots: Annotated[int, Strict()] = Field(ge=3, le=360, description="number of radial slots of the wheel (3 to 360); the "
                                         "pin radius r and the centre distance D come from the "
                                         "drawing, r = D·sin(180°/slots) for shock-free entry")
    carrier: str = Field("frame", description="the link both are pivoted on")


class StarWheelSpec(_Strict):
    type: Literal["star-wheel"]
    links: Annotated[list[str], Field(min_length=2, max_length=2)] = Field(
        description="the driver carrying the pins, then the star wheel (Sternrad)")
    groups: Annotated[list[Annotated[list[str], Field(min_length=1)]], Field(min_length=1)] = Field(
        description="the pins (points of the driver) of each indexing group, equally spaced on "
                    "one pitch circle per group")
    entry: Annotated[list[Union[Number, str]], Field(min_length=1)] | None = Field(
        None, description="per group, the angle of its entry and exit slots from the line of "
                          "centres where the pin meets them (file's angle unit unless written); "
                          "default asin(r/D), shock-free")
    carrier: str = Field("frame", description="the link both are pivoted on")


JointSpec = Annotated[
    Union[RevoluteSpec, PrismaticSpec, SlotSpec, CircularSlotSpec, GearSpec, CamSpec, RollingSpec,
          GenevaSpec, StarWheelSpec],
    Field(discriminator="type"),
]


class PolynomialLawSpec(_Strict):
    type: Literal["polynomial"]
    coefficients: list[Number] = Field(min_length=1, description="input(t) = sum c_k t^k, in degrees (or the length unit) and seconds")
    duration: PositiveNumber = 1.0


class TableLawSpec(_Strict):
    type: Literal["table"]
    time: list[Number] = Field(min_length=4)
    value: list[Number] = Field(min_length=4)


class DriverSpec(_Strict):
    joint: str
    reference: str | None = None
    speed: Number | str | None = Field(
        None, description="constant speed: '60 rpm', '2 rad/s', '100 mm/s'; a bare number is rad/s (or length unit/s)")
    law: Annotated[Union[PolynomialLawSpec, TableLawSpec], Field(discriminator="type")] | None = None

    @model_validator(mode="after")
    def _speed_or_law(self) -> "DriverSpec":
        if self.speed is not None and self.law is not None:
            raise ValueError("give either `speed` (a constant speed) or `law` (a motion law), "
                             "not both")
        return self


class GivenSpec(_Strict):
    """A given point velocity or velocity direction (`model.given`): the inputs of a free or
    open chain without a driver (Rosenauer 1937, paper 2)."""

    point: str = Field(description="the point whose motion is given")
    link: str | None = Field(None, description="the link the point is taken in (default: the link "
                                               "that reports the point)")
    velocity: Coordinates | None = Field(None, description="[vx, vy] in the length unit per second")
    acceleration: Coordinates | None = Field(None, description="[ax, ay] in the length unit per "
                                             "second squared (with `velocity`; for accelerations)")
    direction: Axis | None = Field(None, description="the line the point's velocity lies on: a "
                                   "direction [x, y] or an angle (the file's angle unit unless written)")
    curvature: Number | None = Field(None, description="curvature of the point's path (with "
                                     "`direction`; 1/length unit, positive bending to the left of "
                                     "the direction, 0 on a straight guide; for accelerations)")

    @model_validator(mode="after")
    def _one_kind(self) -> "GivenSpec":
        if (self.velocity is None) == (self.direction is None):
            raise ValueError("give either `velocity` (the point's velocity) or `direction` (the "
                             "line its velocity lies on)")
        if self.acceleration is not None and self.velocity is None:
            raise ValueError("`acceleration` goes with `velocity`; with `direction` give the "
                             "path's `curvature`")
        if self.curvature is not None and self.direction is None:
            raise ValueError("`curvature` goes with `direction`")
        return self


# ---------------------------------------------------------------- mass data and loads (forces)
#: a quantity: a bare number in the key's SI unit, or a string with its unit ("0.5 kg", "2 N/mm")
Quantity = Union[Number, str]
#: a point of the drawing by name, or design coordinates [x, y] in the length unit
PointRef = Union[str, Coordinates]


class LinkMassSpec(_Strict):
    mass: Quantity = Field(description="mass of the link; a bare number is kg")
    center: PointRef = Field(description="centre of mass: a named point or design coordinates [x, y]")
    inertia: Quantity = Field(0.0, description="moment of inertia about the centre of mass; a bare "
                                               "number is kg*m^2")


class LoadTableSpec(_Strict):
    of: Literal["input", "time"] = Field(description="tabulated against the first driver's input "
                                         "(the file's angle unit, or the length unit) or time (s)")
    at: list[Number] = Field(min_length=2, description="increasing abscissae")
    values: list[Union[Number, Coordinates]] = Field(min_length=2, description="one value per abscissa "
                                                     "(a number for a torque, [x, y] for a force)")
    periodic: Annotated[bool, Strict()] = Field(False, description="wrap the abscissa over the table's span")

    @model_validator(mode="after")
    def _shape(self) -> "LoadTableSpec":
        if len(self.at) != len(self.values):
            raise ValueError(f"the table has {len(self.at)} abscissae but {len(self.values)} values")
        if any(b <= a for a, b in zip(self.at, self.at[1:])):
            raise ValueError("the abscissae `at` must increase")
        return self


def _table_or_value(v) -> str:
    # tags the key-path cleaner drops (`files._clean`), so errors name the key itself
    return "table" if isinstance(v, dict) else "list[value]"


ForceValue = Annotated[Union[Annotated[LoadTableSpec, Tag("table")], Annotated[Coordinates, Tag("list[value]")]],
                       Discriminator(_table_or_value)]
TorqueValue = Annotated[Union[Annotated[LoadTableSpec, Tag("table")], Annotated[Quantity, Tag("list[value]")]],
                        Discriminator(_table_or_value)]


class ForceSpec(_Strict):
    link: str
    point: PointRef = Field(description="point of application (a material point of the link)")
    force: ForceValue = Field(description="[Fx, Fy] in N, or a table")
    axes: Literal["frame", "link"] = Field("frame", description="components fixed in the frame "
                                           "or turning with the link")


class TorqueSpec(_Strict):
    link: str
    torque: TorqueValue = Field(description="counter-clockwise; a bare number is N*m")


class SpringSpec(_Strict):
    links: Annotated[list[str], Field(min_length=2, max_length=2)]
    points: Annotated[list[PointRef], Field(min_length=2, max_length=2)] = Field(
        description="the spring's ends, on the first and on the second link")
    stiffness: Quantity = Field(0.0, description="a bare number is N/m")
    free_length: Quantity | None = Field(None, description="default: the length in the drawing; a "
                                                           "bare number is in the length unit")
    preload: Quantity = Field(0.0, description="tension added (N)")
    damping: Quantity = Field(0.0, description="viscous damping along the spring; a bare number is N*s/m")


class TorsionSpringSpec(_Strict):
    joint: str = Field(description="a revolute pair")
    stiffness: Quantity = Field(0.0, description="a bare number is N*m/rad")
    free_angle: Quantity = Field(0.0, description="relative angle at rest, from the drawing (file's angle unit)")
    damping: Quantity = Field(0.0, description="rotary damping; a bare number is N*m*s/rad")


class FrictionSpec(_Strict):
    joint: str = Field(description="a revolute, prismatic, slot, circular-slot or cam pair")
    coefficient: PositiveNumber = Field(description="Coulomb friction coefficient")
    radius: Quantity = Field(0.0, description="journal radius of a revolute pair (friction torque "
                                              "coefficient*radius*|R|); a bare number is in the length unit")


class LoadsSpec(_Strict):
    gravity: Union[Coordinates, Annotated[bool, Strict()]] = Field(
        False, description="acceleration of gravity [gx, gy] in m/s^2, or true for 9.80665 m/s^2 along -y")
    forces: list[ForceSpec] = Field(default_factory=list)
    torques: list[TorqueSpec] = Field(default_factory=list)
    springs: list[SpringSpec] = Field(default_factory=list, description="linear springs and dampers")
    torsion_springs: list[TorsionSpringSpec] = Field(default_factory=list)
    friction: list[FrictionSpec] = Field(default_factory=list, description="Coulomb friction in pairs "
                                         "(zero where a pair does not move; an option of the force analysis)")


class MechanismFile(_Strict):
    name: str
    description: str = ""
    category: str = Field("", description="the library's group for this mechanism (four-bars, "
                          "slider mechanisms, valve gears, straight-line linkages, governors, ...)")
    units: Units = Units()
    parameters: dict[str, str] = Field(
        default_factory=dict, description="named design parameters for sweeps: NAME = \"P.x\", "
        "\"P.y\" (a point's coordinate), \"A-B\" (the distance from A to B, B moving along it) or "
        "\"A-B.angle\" (the direction of B from A in degrees, B turning about A)")
    frame: str = "frame"
    points: dict[str, Coordinates]
    profiles: dict[str, ProfileSpec] = Field(
        default_factory=dict, description="curves carried by links, for higher pairs (cam, rolling)")
    links: dict[str, list[str]]
    joints: dict[str, JointSpec]
    driver: DriverSpec | None = None
    drivers: list[DriverSpec] | None = None
    given: list[GivenSpec] | None = Field(
        None, description="given point velocities or velocity directions ([[given]]) at the drawn "
        "position, instead of a driver: a free chain (no frame link needed) or an open chain")
    masses: dict[str, LinkMassSpec] = Field(
        default_factory=dict, description="mass data per moving link (needed for forces only)")
    loads: LoadsSpec | None = Field(None, description="loads for force analysis")

    @field_validator("points")
    @classmethod
    def _some_points(cls, v: dict) -> dict:
        if not v:
            raise ValueError("a mechanism needs at least one point")
        return v
