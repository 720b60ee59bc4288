"""Profile definitions in mechanism files: the `[profiles.NAME]` tables of higher pairs.

A profile is the curve a cam disc, a follower face, a track or a rolling wheel carries. It is
written in the design coordinates of its link (the same coordinates and length unit as the
file's points). Angles are in the file's angle unit (`[units] angle`, degrees by default).
Every number must be finite; a misspelt key is an error, as everywhere in mechanism files.

    [profiles.disc]          # a circle (an eccentric disc, a roller, a pitch circle)
    type = "circle"
    center = [10, 0]
    radius = 40

    [profiles.egg]           # an ellipse; `angle` turns the first semi-axis from the x-axis
    type = "ellipse"
    center = [0, 0]
    semi_axes = [40, 25]
    angle = 0                # optional, default 0

    [profiles.cam]           # lines and circular arcs from a start point (the books' cams)
    type = "path"
    start = [40, 0]
    closed = true            # optional, default false; a closed path must end at its start
    smooth = false           # optional: true refuses a corner between segments
    segments = [
        { arc_to = [0, 40], center = [0, 0] },              # about a centre (sense "ccw" by default)
        { line_to = [-30, 10] },
        { arc_to = [40, 0], radius = 40, sense = "ccw" },   # by radius: the shorter arc ...
        # { arc_to = [..], radius = 40, large = true }      # ... or the longer one
    ]

    [profiles.track]         # an interpolating spline through points
    type = "spline"
    points = [[0, 0], [10, 5], [20, 0], [10, -5]]
    closed = true            # optional, default false (periodic when closed)
    degree = 5               # optional: 5 (quintic, default: curvature C³) or 3 (cubic)

    [profiles.csvcam]        # the same, with the points read from a CSV file
    type = "points"
    file = "cam.csv"         # beside the mechanism file
    closed = true
    degree = 5

    [profiles.face]          # a whole straight line (a flat follower face, a straight track)
    type = "line"
    point = [0, 0]
    direction = [1, 0]

    [profiles.inv]           # the involute of a circle
    type = "involute"
    center = [0, 0]
    base_radius = 20
    start_angle = 0          # where it leaves the base circle
    roll = [0, 360]          # optional: the roll angles it spans (from 0 or later)
    sense = "ccw"            # optional: the way it unwinds

    [profiles.spiral]        # r = start_radius + pitch·(φ − φ₀)/turn over angles [φ₀, φ₁]
    type = "archimedean-spiral"
    center = [0, 0]
    start_radius = 20
    pitch = 10               # radial growth per turn
    angles = [0, 360]

    [profiles.log]           # r = start_radius·exp((φ − φ₀)·tan(pitch_angle))
    type = "logarithmic-spiral"
    center = [0, 0]
    start_radius = 20
    pitch_angle = 10
    angles = [0, 360]

    [profiles.cam]           # a disc cam designed from a motion program (see below)
    type = "cam-design"
    follower = "roller"      # roller, knife or flat
    base_radius = 40         # the base circle (smallest radius of the profile)
    roller_radius = 10       # a roller's radius
    offset = 0               # optional: translating follower's line, right of the cam centre
    segments = [             # one turn of cam angle, in order from the drawing's position
        { rise = 20, over = 120, law = "cycloidal" },
        { dwell = 60 },
        { return = 20, over = 120, law = "3-4-5" },
        { dwell = 60 },
    ]

A `cam-design` table describes the cam by the follower motion it must produce: `segments` rise,
dwell and return over cam angles that fill one turn, each `law` one of uniform, harmonic,
cycloidal, 3-4-5, 4-5-6-7, modified-trapezoid, modified-sine, parabolic
(`linkwork.model.motion_programs`). The cam turns counter-clockwise about `center` (default
[0, 0]). `motion = "translating"` (default): the follower moves along the direction `direction`
(an angle, default 90° straight up) on a line `offset` to the right of the cam centre, and the
lifts are lengths. `motion = "oscillating"`: a lever pivoted at `pivot` carries the roller or
knife at `arm` from it, or a flat face at `face_offset` from it; `side` ("left", default, or
"right") puts the follower on that side of the line from the cam centre to the pivot, and the
lifts are angles. The profile's parameter is the cam angle: the contact of a roller or knife
designed so sits at u = φ. `linkwork cam design` writes such files with the follower drawn in
place.

Parameters (what the engine reports positions on a profile by): the arc length from the start
for a path, the chord length from point to point for a spline, the angle for a circle, the
eccentric anomaly for an ellipse, the roll angle for an involute, the polar angle for spirals,
the distance from `point` for a line; radians whatever the file's angle unit.

The CSV of a `points` profile has one point per line, `x, y` (commas or blanks between), `#`
starts a comment, blank lines are skipped, and one header line (such as `x,y`) may come first.
A relative `file` is read from the mechanism file's folder. It must stay inside that folder (no
absolute paths, no `..` out of it): a mechanism file with its profiles is then a folder that can be
moved, shared and put in the library as a whole, and a file never reads beyond its own folder.

`build_profile(name, table, base_dir)` turns one table (as parsed by `tomllib`) into a profile of
`linkwork.geometry.profiles`; `ProfileSpec` is the pydantic model of a table and
`profile_file_schema()` its JSON schema.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Annotated, Any, Literal, Union

import numpy as np
from pydantic import BaseModel, ConfigDict, Discriminator, Field, Strict, Tag, TypeAdapter, ValidationError

from ..errors import MechanismFileError
from ..model.disc_cams import DiscCam
from ..model.motion_programs import LAWS, CamDesignError, MotionProgram, Segment
from ..geometry.errors import GeometryError
from ..units import MAX_MAGNITUDE
from ..geometry.profiles import (
    ArchimedeanSpiral,
    ArcTo,
    CircleProfile,
    EllipseProfile,
    InvoluteProfile,
    LineProfile,
    LineTo,
    LogarithmicSpiral,
    PathProfile,
    Profile,
    ProfileError,
    SplineProfile,
)
from .values import Number, PositiveNumber

Finite = Number
Positive = PositiveNumber
Point = Annotated[list[Finite], Field(min_length=2, max_length=2, description="[x, y]")]
Pair = Annotated[list[Finite], Field(min_length=2, max_length=2)]
Sense = Literal["ccw", "cw"]


class _Table(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class LineSegmentSpec(_Table):
    line_to: Point = Field(description="end point of a straight segment")


class ArcSegmentSpec(_Table):
    arc_to: Point = Field(description="end point of a circular arc")
    center: Point | None = Field(None, description="centre of the arc (or give its radius)")
    radius: Positive | None = Field(None, description="radius of the arc (or give its centre)")
    sense: Sense = "ccw"
    large: Annotated[bool, Strict()] = Field(False, description="with a radius: the longer of the two arcs")


def _segment_kind(value: Any) -> str | None:
    if isinstance(value, dict):
        return "line" if "line_to" in value else "arc" if "arc_to" in value else None
    return "line" if hasattr(value, "line_to") else "arc" if hasattr(value, "arc_to") else None


SegmentSpec = Annotated[
    Union[Annotated[LineSegmentSpec, Tag("line")], Annotated[ArcSegmentSpec, Tag("arc")]],
    Discriminator(_segment_kind, custom_error_type="segment",
                  custom_error_message="a segment is { line_to = [x, y] } or { arc_to = [x, y], center = .. | radius = .. }"),
]


class CircleSpec(_Table):
    type: Literal["circle"]
    center: Point
    radius: Positive


class EllipseSpec(_Table):
    type: Literal["ellipse"]
    center: Point
    semi_axes: Annotated[list[Positive], Field(min_length=2, max_length=2)]
    angle: Finite = Field(0.0, description="turn of the first semi-axis from the x-axis")


class PathSpec(_Table):
    type: Literal["path"]
    start: Point
    segments: Annotated[list[SegmentSpec], Field(min_length=1)]
    closed: Annotated[bool, Strict()] = False
    smooth: Annotated[bool, Strict()] = Field(False, description="refuse corners between segments")


class SplineSpec(_Table):
    type: Literal["spline"]
    points: Annotated[list[Point], Field(min_length=3)]
    closed: Annotated[bool, Strict()] = False
    degree: Literal[3, 5] = 5


class PointsSpec(_Table):
    type: Literal["points"]
    file: str = Field(description="CSV of x, y per line, relative to the mechanism file's folder")
    closed: Annotated[bool, Strict()] = False
    degree: Literal[3, 5] = 5


class LineSpec(_Table):
    type: Literal["line"]
    point: Point
    direction: Point


class InvoluteSpec(_Table):
    type: Literal["involute"]
    center: Point
    base_radius: Positive
    start_angle: Finite = 0.0
    roll: Pair | None = Field(None, description="roll angles spanned (default: one turn from 0)")
    sense: Sense = "ccw"


class ArchimedeanSpiralSpec(_Table):
    type: Literal["archimedean-spiral"]
    center: Point
    start_radius: Positive
    pitch: Finite = Field(description="radial growth per turn")
    angles: Pair


class LogarithmicSpiralSpec(_Table):
    type: Literal["logarithmic-spiral"]
    center: Point
    start_radius: Positive
    pitch_angle: Finite = Field(description="angle between the tangent and the circle about the centre")
    angles: Pair


LawName = Literal[LAWS]  # type: ignore[valid-type]


class RiseSpec(_Table):
    rise: Positive = Field(description="lift: a length (translating) or an angle (oscillating)")
    over: Positive = Field(description="cam angle of the rise")
    law: LawName


class DwellSpec(_Table):
    dwell: Positive = Field(description="cam angle of the dwell")


class ReturnSpec(_Table):
    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)
    return_: Positive = Field(alias="return", description="fall back by this lift")
    over: Positive = Field(description="cam angle of the return")
    law: LawName


def _cam_segment_kind(value: Any) -> str | None:
    if isinstance(value, dict):
        keys = [k for k in ("rise", "dwell", "return") if k in value]
        return keys[0] if len(keys) == 1 else None
    return ("rise" if hasattr(value, "rise") else "dwell" if hasattr(value, "dwell")
            else "return" if hasattr(value, "return_") else None)


CamSegmentSpec = Annotated[
    Union[Annotated[RiseSpec, Tag("rise")], Annotated[DwellSpec, Tag("dwell")],
          Annotated[ReturnSpec, Tag("return")]],
    Discriminator(_cam_segment_kind, custom_error_type="segment",
                  custom_error_message="a cam segment is { rise = L, over = A, law = .. }, { dwell = A } "
                                       "or { return = L, over = A, law = .. }"),
]


class CamDesignSpec(_Table):
    type: Literal["cam-design"]
    follower: Literal["roller", "knife", "flat"]
    base_radius: Positive = Field(description="radius of the base circle, the profile's smallest")
    segments: Annotated[list[CamSegmentSpec], Field(min_length=1)] = Field(
        description="rise, dwell and return segments over one turn of cam angle, in order")
    roller_radius: Positive | None = Field(None, description="the roller's radius (follower = roller)")
    motion: Literal["translating", "oscillating"] = "translating"
    center: Point = Field([0.0, 0.0], description="the cam's centre of rotation")
    offset: Finite = Field(0.0, description="translating: the line of motion's distance to the right of the cam centre")
    direction: Finite | None = Field(None, description="translating: the angle of the line of motion (default: 90°, straight up)")
    pivot: Point | None = Field(None, description="oscillating: the lever's fixed pivot")
    arm: Positive | None = Field(None, description="oscillating: pivot to roller centre or knife tip")
    face_offset: Finite = Field(0.0, description="oscillating flat face: its distance from the pivot")
    side: Literal["left", "right"] = Field("left", description="oscillating: the follower's side of the line from the cam centre to the pivot")


ProfileSpec = Annotated[
    Union[CircleSpec, EllipseSpec, PathSpec, SplineSpec, PointsSpec, LineSpec, InvoluteSpec,
          ArchimedeanSpiralSpec, LogarithmicSpiralSpec, CamDesignSpec],
    Field(discriminator="type"),
]
_ADAPTER: TypeAdapter = TypeAdapter(ProfileSpec)
_TYPES = {"circle", "ellipse", "path", "spline", "points", "line", "involute", "archimedean-spiral",
          "logarithmic-spiral", "cam-design"}


def profile_file_schema() -> dict:
    """JSON schema of one `[profiles.NAME]` table."""
    return _ADAPTER.json_schema()


def _key(name: str, loc: tuple = ()) -> str:
    """The dotted key of a pydantic error location, without the tags of the unions (the profile's
    type first, a segment's kind after its index)."""
    key = f"profiles.{name}"
    for i, part in enumerate(loc):
        if (i == 0 and part in _TYPES) or (i >= 2 and loc[i - 2] == "segments" and part in ("line", "arc", "rise", "dwell", "return")):
            continue
        key += f"[{part}]" if isinstance(part, int) else f".{part}"
    return key


def _given_type(err: dict) -> Any:
    return err["input"].get("type") if isinstance(err.get("input"), dict) else None


def _validation_error(exc: ValidationError, name: str, source: str | None) -> MechanismFileError:
    errors = exc.errors(include_url=False)
    extra = [e for e in errors if e["type"] == "extra_forbidden"]
    err = extra[0] if extra else errors[0]
    kinds = ", ".join(sorted(_TYPES))
    msg = {"extra_forbidden": "unknown key (check its spelling)",
           "missing": "required key is missing",
           "union_tag_not_found": f"a profile needs a 'type': one of {kinds}",
           "union_tag_invalid": f"unknown profile type {_given_type(err)!r} (one of {kinds})"}.get(
               err["type"], err["msg"].removeprefix("Value error, "))
    return MechanismFileError(msg, source=source, key=_key(name, tuple(err["loc"])))


def parse_profile_spec(name: str, table: dict, source: str | None = None):
    """Validate one profile table (a dict from tomllib) into its pydantic model."""
    if not isinstance(table, dict):
        raise MechanismFileError("a profile is a table with a 'type'", source=source, key=_key(name))
    try:
        return _ADAPTER.validate_python(table)
    except ValidationError as exc:
        raise _validation_error(exc, name, source) from None


def build_profile(name: str, spec: dict, base_dir: Path | None = None, *, angle_unit: str = "deg",
                  source: str | None = None) -> Profile:
    """The profile a `[profiles.NAME]` table describes. `base_dir` is the mechanism file's folder
    (CSV files are read from there; None: the working directory); `angle_unit` the file's
    `[units] angle`; `source` names the mechanism file in messages. Every error is a
    MechanismFileError naming the profile's key."""
    model = spec if isinstance(spec, BaseModel) else parse_profile_spec(name, spec, source)
    if angle_unit.startswith("deg"):
        rad = float(np.pi / 180)
    elif angle_unit.startswith("rad"):
        rad = 1.0
    else:
        raise MechanismFileError(f"unknown angle unit {angle_unit!r} (deg or rad)", source=source, key="units.angle")
    try:
        return _build(name, model, base_dir, rad, source)
    except (ProfileError, CamDesignError) as exc:
        sub = {PathSpec: "segments", SplineSpec: "points", CamDesignSpec: "segments"}.get(type(model))
        key = _key(name) + (f".{sub}[{exc.index}]" if sub and exc.index is not None else "")
        if getattr(exc, "key", None):
            key = _key(name) + "." + exc.key
        raise MechanismFileError(str(exc), source=source, key=key) from None
    except GeometryError as exc:
        raise MechanismFileError(str(exc), source=source, key=_key(name)) from None


def _build(name: str, m, base_dir: Path | None, rad: float, source: str | None) -> Profile:
    if isinstance(m, CircleSpec):
        return CircleProfile(tuple(m.center), m.radius)
    if isinstance(m, EllipseSpec):
        return EllipseProfile(m.center, m.semi_axes, m.angle * rad)
    if isinstance(m, PathSpec):
        segments = [LineTo(tuple(s.line_to)) if isinstance(s, LineSegmentSpec) else
                    ArcTo(tuple(s.arc_to), center=None if s.center is None else tuple(s.center),
                          radius=s.radius, sense=s.sense, large=s.large) for s in m.segments]
        return PathProfile(m.start, segments, closed=m.closed, smooth=m.smooth)
    if isinstance(m, SplineSpec):
        return SplineProfile(m.points, closed=m.closed, degree=m.degree)
    if isinstance(m, PointsSpec):
        path = _csv_path(name, m.file, base_dir, source)
        points, lines = read_points_csv(path, key=_key(name, ("file",)))
        try:
            return SplineProfile(points, closed=m.closed, degree=m.degree)
        except ProfileError as exc:
            line = lines[exc.index] if exc.index is not None and exc.index < len(lines) else None
            raise MechanismFileError(str(exc), source=str(path), key=_key(name, ("file",)), line=line) from None
    if isinstance(m, LineSpec):
        return LineProfile(m.point, m.direction)
    if isinstance(m, InvoluteSpec):
        roll = (0.0, 2 * np.pi) if m.roll is None else (m.roll[0] * rad, m.roll[1] * rad)
        return InvoluteProfile(m.center, m.base_radius, m.start_angle * rad, roll,
                               1 if m.sense == "ccw" else -1)
    if isinstance(m, ArchimedeanSpiralSpec):
        return ArchimedeanSpiral(m.center, m.start_radius, m.pitch, (m.angles[0] * rad, m.angles[1] * rad))
    if isinstance(m, LogarithmicSpiralSpec):
        return LogarithmicSpiral(m.center, m.start_radius, m.pitch_angle * rad,
                                 (m.angles[0] * rad, m.angles[1] * rad))
    if isinstance(m, CamDesignSpec):
        return cam_from_spec(m, rad).profile
    raise MechanismFileError(f"unknown profile type {type(m).__name__}", source=source, key=_key(name))  # pragma: no cover


def cam_from_spec(m: CamDesignSpec, rad: float) -> DiscCam:
    """The `DiscCam` a `cam-design` table describes (`rad`: radians per the file's angle unit)."""
    lift_unit = rad if m.motion == "oscillating" else 1.0
    segments = [Segment("rise", s.over * rad, s.rise * lift_unit, s.law) if isinstance(s, RiseSpec) else
                Segment("return", s.over * rad, s.return_ * lift_unit, s.law) if isinstance(s, ReturnSpec) else
                Segment("dwell", s.dwell * rad) for s in m.segments]
    for key, value in (("roller_radius", m.roller_radius if m.follower == "roller" else 0.0),
                       ("pivot", m.pivot if m.motion == "oscillating" else 0.0),
                       ("arm", m.arm if m.motion == "oscillating" and m.follower != "flat" else 0.0)):
        if value is None:
            need = {"roller_radius": "a roller needs `roller_radius`",
                    "pivot": "an oscillating follower needs `pivot`, the lever's fixed pivot",
                    "arm": "an oscillating roller or knife needs `arm`, its distance from the pivot"}[key]
            raise CamDesignError(need, key=key)
    return DiscCam(MotionProgram(segments), m.follower, m.base_radius,
                   roller_radius=m.roller_radius or 0.0, motion=m.motion, offset=m.offset,
                   direction=np.pi / 2 if m.direction is None else m.direction * rad, pivot=None if m.pivot is None else tuple(m.pivot),
                   arm=m.arm, face_offset=m.face_offset, side=m.side, center=tuple(m.center))


def _csv_path(name: str, file: str, base_dir: Path | None, source: str | None) -> Path:
    key = _key(name, ("file",))
    base = (Path(base_dir) if base_dir is not None else Path.cwd()).resolve()
    rel = Path(file)
    if not file.strip() or rel.is_absolute() or rel.drive:
        raise MechanismFileError(f"give the CSV as a path relative to the mechanism file's folder, not {file!r}",
                                 source=source, key=key)
    path = (base / rel).resolve()
    if not path.is_relative_to(base):
        raise MechanismFileError(f"the CSV {file!r} lies outside the mechanism file's folder {base}",
                                 source=source, key=key)
    if not path.is_file():
        raise MechanismFileError(f"no such CSV file: {path}", source=source, key=key)
    return path


_SPLIT = re.compile(r"[,\s;]+")


def read_points_csv(path: Path, *, key: str | None = None) -> tuple[np.ndarray, list[int]]:
    """Points (n, 2) from a CSV of `x, y` lines (`#` comments, blank lines, one optional header
    line before the first point) and the line number of each point. Errors name the file and line."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise MechanismFileError(f"cannot read the CSV: {exc}", source=str(path), key=key) from None
    points, lines = [], []
    header_allowed = True
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        fields = [f for f in _SPLIT.split(line) if f]
        try:
            values = [float(f) for f in fields]
        except ValueError:
            if header_allowed:
                header_allowed = False
                continue
            raise MechanismFileError(f"not a point 'x, y': {line!r}", source=str(path), key=key, line=number) from None
        header_allowed = False
        if len(values) != 2:
            raise MechanismFileError(f"a point has two coordinates x, y; this line has {len(values)}",
                                     source=str(path), key=key, line=number)
        if not all(np.isfinite(values)) or max(map(abs, values)) > MAX_MAGNITUDE:
            raise MechanismFileError(f"coordinates must be finite numbers of at most "
                                     f"{MAX_MAGNITUDE:g} in size: {line!r}",
                                     source=str(path), key=key, line=number)
        points.append(values)
        lines.append(number)
    if not points:
        raise MechanismFileError("the CSV holds no points", source=str(path), key=key)
    return np.array(points, dtype=float), lines
