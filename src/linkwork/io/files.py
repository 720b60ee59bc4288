"""Mechanism files: TOML text -> validated `Mechanism`, with errors that name key and line.

`resolve` turns a user's mechanism argument (a path or `library:NAME`) into text;
`load_text` validates it against `schema.MechanismFile` and builds the model.
"""

from __future__ import annotations

import difflib
import json
import re
import tomllib
from importlib import resources
from pathlib import Path

import numpy as np
from pydantic import ValidationError

from ..errors import InputError, MechanismFileError, ModelError, UnknownMechanismError
from ..model import (CamContact, CircularSlot, ConstantSpeed, Gear, Mechanism, PolynomialLaw,
                     Prismatic, Revolute, RollingContact, Slot, TabulatedLaw)
from ..units import check_length_unit, parse_quantity
from . import schema
from .profiles import build_profile

LIBRARY_PREFIX = "library:"


def library_names() -> list[str]:
    root = resources.files("linkwork") / "library"
    return sorted(p.name[:-5] for p in root.iterdir() if p.name.endswith(".toml"))


def resolve(spec: str | Path) -> tuple[str, str]:
    """(source label, TOML text) of a mechanism given as a path or as `library:NAME`."""
    spec = str(spec)
    if spec.startswith(LIBRARY_PREFIX):
        name = spec[len(LIBRARY_PREFIX):]
        if name not in library_names():
            close = [n for n in library_names() if name.lower() in n or n in name.lower()]
            hint = f"; did you mean {', '.join(close)}?" if close else "; `linkwork library` lists them"
            raise UnknownMechanismError(f"the library has no mechanism '{name}'{hint}")
        return spec, (resources.files("linkwork") / "library" / f"{name}.toml").read_text()
    path = Path(spec)
    if not path.is_file():
        raise UnknownMechanismError(
            f"no mechanism file '{spec}' (give a path, or library:NAME for a shipped mechanism)")
    return spec, path.read_text(encoding="utf-8")


def load(spec: str | Path) -> Mechanism:
    """Load a mechanism from a file path or `library:NAME` (profiles read from CSV files are
    looked up beside the mechanism file)."""
    source, text = resolve(spec)
    base = None if str(spec).startswith(LIBRARY_PREFIX) else Path(spec).resolve().parent
    return load_text(text, source=source, base_dir=base)


def _line_of(text: str, loc: tuple) -> int | None:
    """Best-effort line number (1-based) of the key path `loc` in TOML `text`."""
    lines = text.splitlines()
    start, found = 0, None
    keys = [str(k) for k in loc if not isinstance(k, int)]
    for depth, key in enumerate(keys):
        pat = re.compile(
            rf'^\s*(\[\s*([\w."-]*\.)?"?{re.escape(key)}"?\s*\]|"?{re.escape(key)}"?\s*=)'
            rf'|[{{,]\s*"?{re.escape(key)}"?\s*=')
        for i in range(start, len(lines)):
            if pat.search(lines[i]):
                found, start = i + 1, i
                break
        else:
            break
    return found


def load_text(text: str, *, source: str = "<text>", base_dir: Path | None = None) -> Mechanism:
    """Validate mechanism-file `text` and build the `Mechanism`; `base_dir` is where profile
    CSV files are read from (the working directory if None)."""
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise MechanismFileError(f"not valid TOML: {exc}", source=source,
                                 line=int(m.group(1)) if m else None) from None
    try:
        spec = schema.MechanismFile.model_validate(raw)
    except ValidationError as exc:
        raise _file_error(exc, text, source) from None
    try:
        return _build(spec, text, source, base_dir)
    except (ModelError, InputError) as exc:
        raise MechanismFileError(str(exc), source=source) from None


_TAGS = {"revolute", "prismatic", "slot", "circular-slot", "gear", "cam", "rolling", "polynomial",
         "table", "float", "int", "str", "circle", "ellipse", "path", "spline", "points", "line",
         "involute", "archimedean-spiral", "logarithmic-spiral", "cam-design"}


_SEGMENT_TAGS = {"line", "arc", "rise", "dwell", "return"}


def _clean(loc: tuple) -> tuple:
    """A pydantic error location without the union/discriminator tags it inserts."""
    loc = tuple(k for k in loc if not str(k).startswith(("function-", "union[", "list[")))
    # a discriminated union inserts its tag right after the entry's name (joints.K.cam.radius);
    # strip that one only: a top-level section or a field may share a tag's name ("points"),
    # and so may the name a user gives a joint or a profile (profiles.cam)
    first = 2 if loc and loc[0] in ("joints", "profiles") else 1
    for i, k in enumerate(loc):
        if i >= first and k in _TAGS:
            loc = loc[:i] + loc[i + 1:]
            break
    # a profile segment's kind follows its index (profiles.P.segments.0.rise.law)
    return tuple(k for i, k in enumerate(loc)
                 if not (i >= 2 and loc[i - 2] == "segments" and isinstance(loc[i - 1], int) and k in _SEGMENT_TAGS))


def _file_error(exc: ValidationError, text: str, source: str) -> MechanismFileError:
    """One message for the most telling error: a misspelt key before the key it misses."""
    errors = exc.errors()
    extra = [e for e in errors if e["type"] == "extra_forbidden"]
    err = extra[0] if extra else errors[0]
    clean = _clean(tuple(err["loc"]))
    key = ".".join(str(k) for k in clean)
    msg = err["msg"]
    if err["type"] == "extra_forbidden":
        missing = [str(_clean(tuple(e["loc"]))[-1]) for e in errors
                   if e["type"] == "missing" and _clean(tuple(e["loc"]))[:-1] == clean[:-1]]
        close = difflib.get_close_matches(str(clean[-1]), missing, n=1)
        msg = "unknown key" + (f" (did you mean '{close[0]}'?)" if close else " (check its spelling)")
    elif err["type"] == "missing":
        msg = "required key is missing"
    return MechanismFileError(msg, source=source, key=key, line=_line_of(text, clean))


def _axis(value, angle_unit: str, where: str) -> np.ndarray:
    """Unit direction from a vector [x, y] or an angle (file's angle unit unless written)."""
    if isinstance(value, list):
        v = np.array(value, dtype=float)
    else:
        ang = _angle_in_rad(value, angle_unit, f"joint '{where}' axis angle")
        v = np.array([np.cos(ang), np.sin(ang)])
    n = float(np.hypot(*v))
    if n == 0.0:
        raise ModelError(f"joint '{where}': the axis is the zero vector")
    return v / n


def _angle_in_rad(value, angle_unit: str, kind: str) -> float:
    if isinstance(value, str):
        return parse_quantity(value, default_unit="rad", kind=kind) if any(c.isalpha() for c in value) \
            else _angle_in_rad(float(value), angle_unit, kind)
    return float(value) if angle_unit.startswith("rad") else float(np.radians(value))


def _build(spec: schema.MechanismFile, text: str, source: str, base_dir: Path | None = None) -> Mechanism:
    unit = check_length_unit(spec.units.length)
    profiles = {name: build_profile(name, p, base_dir, angle_unit=spec.units.angle, source=source)
                for name, p in spec.profiles.items()}
    joints = []
    for name, j in spec.joints.items():
        point = j.point or name
        links = tuple(j.links)
        if isinstance(j, schema.RevoluteSpec):
            joints.append(Revolute(name, point, links))
        elif isinstance(j, schema.PrismaticSpec):
            joints.append(Prismatic(name, point, links, _axis(j.axis, spec.units.angle, name)))
        elif isinstance(j, schema.SlotSpec):
            joints.append(Slot(name, point, links, _axis(j.axis, spec.units.angle, name)))
        elif isinstance(j, schema.CircularSlotSpec):
            joints.append(CircularSlot(name, point, links, j.center))
        elif isinstance(j, schema.CamSpec):
            at = j.point or (name if name in spec.points and j.follower != "profile" else None)
            axis = None if j.axis is None else _axis(j.axis, spec.units.angle, name)
            joints.append(CamContact(name, links, j.profile, j.follower, point=at,
                                     radius=float(j.radius or 0.0), axis=axis, mate=j.mate))
        elif isinstance(j, schema.RollingSpec):
            joints.append(RollingContact(name, links, tuple(j.profiles)))
        elif isinstance(j, schema.GearSpec):
            radii = tuple(float(r) for r in j.radii)
            if j.kind != "rack" and len(radii) != 2:
                raise ModelError(f"gear '{name}': give two pitch radii")
            joints.append(Gear(name, links, j.carrier, radii if len(radii) == 2 else (radii[0], np.inf),
                               j.kind, j.point if j.point else (name if name in spec.points else None)))
    driver_specs = list(spec.drivers or []) + ([spec.driver] if spec.driver else [])
    if not driver_specs:
        raise MechanismFileError("no [driver] given: name the joint that drives the mechanism",
                                 source=source, key="driver")
    drivers = []
    joint_kinds = {j.name: j for j in joints}
    for d in driver_specs:
        jk = joint_kinds.get(d.joint)
        prismatic = isinstance(jk, Prismatic)
        if d.law is not None:
            scale = 1.0 if prismatic else (1.0 if spec.units.angle.startswith("rad") else np.pi / 180)
            if isinstance(d.law, schema.PolynomialLawSpec):
                law = PolynomialLaw(tuple(scale * c for c in d.law.coefficients), float(d.law.duration))
            else:
                if len(d.law.time) != len(d.law.value):
                    raise ModelError(f"driver '{d.joint}': law table has {len(d.law.time)} times "
                                     f"but {len(d.law.value)} values")
                if np.any(np.diff(d.law.time) <= 0):
                    raise ModelError(f"driver '{d.joint}': law table times must increase")
                law = TabulatedLaw(tuple(map(float, d.law.time)), tuple(scale * v for v in d.law.value))
        else:
            speed = 1.0 if d.speed is None else parse_quantity(
                d.speed, default_unit=f"{unit}/s" if prismatic else "rad/s", kind=f"driver '{d.joint}' speed")
            law = ConstantSpeed(speed=speed)
        drivers.append({"joint": d.joint, "reference": d.reference, "law": law})
    return Mechanism.build(name=spec.name, points=spec.points, links=spec.links, joints=joints,
                           drivers=drivers, frame=spec.frame, length_unit=unit,
                           description=spec.description, profiles=profiles)


def dump_schema() -> str:
    """The published JSON schema of mechanism files."""
    return json.dumps(schema.MechanismFile.model_json_schema(), indent=2)
