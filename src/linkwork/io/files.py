"""Mechanism files: TOML text -> validated `Mechanism`, with errors that name key and line.

`resolve` turns a user's mechanism argument (a path or `library:NAME`) into text;
`load_text` validates it against `schema.MechanismFile` and builds the model.
"""

from __future__ import annotations

import difflib
import json
import re
import tomllib
from pathlib import Path

import numpy as np
from pydantic import ValidationError

from ..errors import InputError, MechanismFileError, ModelError, UnknownMechanismError
from ..model import (CamContact, CircularSlot, ConstantSpeed, Gear, GenevaPair, GivenDirection,
                     GivenVelocity, Mechanism,
                     PolynomialLaw, Prismatic, Revolute, RollingContact, Slot, StarWheelPair,
                     TabulatedLaw)
from ..units import check_length_unit, parse_quantity, unit_dimension
from . import schema
from .library import LIBRARY_PREFIX, library_names, library_text
from .profiles import build_profile, clean_profile_loc, profile_error_message

#: mechanism files are a few kilobytes; anything this large is not one
MAX_FILE_BYTES = 10_000_000


def resolve(spec: str | Path) -> tuple[str, str]:
    """(source label, TOML text) of a mechanism given as a path or as `library:NAME`."""
    spec = str(spec)
    if spec.startswith(LIBRARY_PREFIX):
        return spec, library_text(spec[len(LIBRARY_PREFIX):])
    path = Path(spec)
    if not path.is_file():
        raise UnknownMechanismError(
            f"no mechanism file '{spec}' (give a path, or library:NAME for a shipped mechanism)")
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise MechanismFileError(f"cannot read the file: {exc.strerror or exc}", source=spec) from None
    if len(data) > MAX_FILE_BYTES:
        raise MechanismFileError(f"the file has {len(data)} bytes; a mechanism file has at most "
                                 f"{MAX_FILE_BYTES}", source=spec)
    try:
        return spec, data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise MechanismFileError(f"not UTF-8 text: byte 0x{data[exc.start]:02x} cannot be read "
                                 "(save the file as UTF-8)", source=spec, line=line) from None


def load(spec: str | Path) -> Mechanism:
    """Load a mechanism from a file path or `library:NAME` (profiles read from CSV files are
    looked up beside the mechanism file)."""
    source, text = resolve(spec)
    base = None if str(spec).startswith(LIBRARY_PREFIX) else Path(spec).resolve().parent
    return load_text(text, source=source, base_dir=base)


def _line_of(text: str, loc: tuple) -> int | None:
    """Best-effort line number (1-based) of the key path `loc` in TOML `text`. An index after a
    key picks that entry of an array of tables (`[[drivers]]`)."""
    lines = text.splitlines()
    start, found = 0, None
    for depth, key in enumerate(loc):
        if isinstance(key, int):
            if depth == 0 or isinstance(loc[depth - 1], int):
                continue
            header = re.compile(rf'^\s*\[\[\s*"?{re.escape(str(loc[depth - 1]))}"?\s*\]\]')
            hits = [i for i, ln in enumerate(lines) if header.search(ln)]
            if key < len(hits):
                found, start = hits[key] + 1, hits[key]
            continue
        key = str(key)
        pat = re.compile(
            rf'^\s*(\[{{1,2}}\s*([\w."-]*\.)?"?{re.escape(key)}"?\s*[\].]|"?{re.escape(key)}"?\s*=)'
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
    return parse(text, source=source, base_dir=base_dir)[0]


def parse(text: str, *, source: str = "<text>", base_dir: Path | None = None
          ) -> tuple[Mechanism, schema.MechanismFile]:
    """`load_text`, also returning the validated file (for the sections that are not the
    mechanism's: [masses] and [loads], read by `io.dynamics`)."""
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise MechanismFileError(f"not valid TOML: {exc}", source=source,
                                 line=int(m.group(1)) if m else None) from None
    except ValueError as exc:  # an integer of more than 4300 digits
        raise MechanismFileError(f"not valid TOML: {exc}", source=source) from None
    try:
        spec = schema.MechanismFile.model_validate(raw)
    except ValidationError as exc:
        raise _file_error(exc, text, source) from None
    check_references(spec, text, source)
    try:
        return _build(spec, text, source, base_dir), spec
    except MechanismFileError as exc:
        if exc.line is None and exc.key and exc.source == source:  # a profile's key: find its line
            loc = tuple(int(k) if k.isdigit() else k for k in re.findall(r"[^.\[\]]+", exc.key))
            prefix = f"{source}, key '{exc.key}': "
            message = str(exc)[len(prefix):] if str(exc).startswith(prefix) else str(exc)
            raise MechanismFileError(message, source=source, key=exc.key,
                                     line=_line_of(text, loc)) from None
        raise
    except (ModelError, InputError) as exc:
        key = _key_of_message(str(exc), spec)
        raise MechanismFileError(str(exc), source=source, key=_dotted(key) if key else None,
                                 line=_line_of(text, key) if key else None) from None


_TAGS = {"revolute", "prismatic", "slot", "circular-slot", "gear", "cam", "rolling", "geneva",
         "star-wheel", "polynomial",
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


def _clean_key(loc: tuple) -> tuple:
    """`_clean`, and inside a `[profiles]` table without its own tags (`io.profiles`)."""
    if loc[:1] == ("profiles",) and len(loc) >= 2:
        rest = tuple(k for k in loc[2:] if not str(k).startswith(("function-", "union[", "list[")))
        return loc[:2] + clean_profile_loc(rest)
    return _clean(loc)


def _file_error(exc: ValidationError, text: str, source: str) -> MechanismFileError:
    """One message for the most telling error: a misspelt key before the key it misses."""
    errors = exc.errors()
    extra = [e for e in errors if e["type"] == "extra_forbidden"]
    err = extra[0] if extra else errors[0]
    clean = _clean_key(tuple(err["loc"]))
    key = _dotted(clean)
    msg = profile_error_message(err) if clean[:1] == ("profiles",) else err["msg"]
    if err["type"] == "extra_forbidden":
        missing = [str(_clean(tuple(e["loc"]))[-1]) for e in errors
                   if e["type"] == "missing" and _clean_key(tuple(e["loc"]))[:-1] == clean[:-1]]
        close = difflib.get_close_matches(str(clean[-1]), missing, n=1)
        msg = "unknown key" + (f" (did you mean '{close[0]}'?)" if close else " (check its spelling)")
    elif err["type"] == "missing":
        msg = "required key is missing"
    else:
        msg = msg.removeprefix("Value error, ")
    return MechanismFileError(msg, source=source, key=key, line=_line_of(text, clean))


def _dotted(loc: tuple) -> str:
    """A key path as written in messages: joints.O2.links, drivers[1].speed."""
    out = ""
    for k in loc:
        out += f"[{k}]" if isinstance(k, int) else (f".{k}" if out else str(k))
    return out


def _did_you_mean(name: str, known) -> str:
    close = difflib.get_close_matches(name, list(known), n=1, cutoff=0.5)
    if close:
        return f" (did you mean '{close[0]}'?)"
    known = sorted(known)
    return f" (defined: {', '.join(known[:12])}{', …' if len(known) > 12 else ''})" if known \
        else " (none is defined)"


def _driver_keys(spec: schema.MechanismFile) -> list[tuple[tuple, schema.DriverSpec]]:
    """(key path, spec) of every driver: [driver] and the entries of [[drivers]]."""
    keys = [(("drivers", i), d) for i, d in enumerate(spec.drivers or [])]
    return keys + ([(("driver",), spec.driver)] if spec.driver else [])


def check_references(spec: schema.MechanismFile, text: str, source: str) -> None:
    """Every name the file uses (points of links, links and points of joints, profiles of higher
    pairs, joints and reference points of drivers) resolved before the model is built, so that
    the first unknown name is reported with its key, its line and the nearest defined name."""

    def fail(loc: tuple, msg: str) -> None:
        raise MechanismFileError(msg, source=source, key=_dotted(loc), line=_line_of(text, loc))

    def need(loc: tuple, what: str, name: str, section: str, known) -> None:
        if name not in known:
            fail(loc, f"{what} '{name}', which is not in [{section}]{_did_you_mean(name, known)}")

    points, links, profiles = spec.points, spec.links, spec.profiles
    if spec.frame not in links and not spec.given:
        fail(("frame",) if "frame" in spec.model_fields_set else ("links",),
             f"there is no frame link '{spec.frame}' (name the fixed link '{spec.frame}' under "
             f"[links] or set frame = \"...\"){_did_you_mean(spec.frame, links) if links else ''}")
    carried = set()
    for ln, pts in links.items():
        for p in pts:
            need(("links", ln), f"link '{ln}' lists point", p, "points", points)
        carried.update(pts)
    for p in points:
        if p not in carried:
            fail(("points", p), f"point '{p}' is on no link (list it under [links], or remove it)")
    fixed_point = (schema.RevoluteSpec, schema.PrismaticSpec, schema.SlotSpec, schema.CircularSlotSpec)
    for jn, j in spec.joints.items():
        for ln in j.links:
            need(("joints", jn, "links"), f"joint '{jn}' names link", ln, "links", links)
        if isinstance(j, fixed_point) and j.point is None and jn not in points:
            fail(("joints", jn), f"joint '{jn}' has no `point` and there is no point named "
                                 f"'{jn}'{_did_you_mean(jn, points)}")
        for attr, section, known in (("point", "points", points), ("center", "points", points),
                                     ("carrier", "links", links), ("profile", "profiles", profiles),
                                     ("mate", "profiles", profiles)):
            name = getattr(j, attr, None)
            if isinstance(name, str):
                need(("joints", jn, attr), f"joint '{jn}' names {attr}", name, section, known)
        if isinstance(j, schema.RollingSpec):
            for name in j.profiles:
                need(("joints", jn, "profiles"), f"joint '{jn}' names profile", name, "profiles", profiles)
    for pn, expr in spec.parameters.items():
        m = re.fullmatch(r"(?P<a>[^\s=:-]+)-(?P<b>[^\s=:.-]+)(\.angle)?|(?P<p>[^\s.=:-][^\s=:]*?)\.[xy]",
                         expr.strip())
        if m is None:
            fail(("parameters", pn), f"parameter '{pn}' = '{expr}': write a point's coordinate (P.x, P.y), "
                                     "a distance (A-B) or a direction (A-B.angle)")
        for name in filter(None, (m.group("p"), m.group("a"), m.group("b"))):
            need(("parameters", pn), f"parameter '{pn}' names point", name, "points", points)
    driven: dict[str, tuple] = {}
    for loc, d in _driver_keys(spec):
        need(loc + ("joint",), "the driver names joint", d.joint, "joints", spec.joints)
        if d.joint in driven:
            fail(loc + ("joint",), f"joint '{d.joint}' has two drivers ({_dotted(driven[d.joint])} "
                                   f"and {_dotted(loc)}); give each joint one driver")
        driven[d.joint] = loc
        if d.reference is not None:
            need(loc + ("reference",), f"driver '{d.joint}' names reference point", d.reference,
                 "points", points)
    for i, g in enumerate(spec.given or []):
        need(("given", i, "point"), "the given data names point", g.point, "points", points)
        if g.link is not None:
            need(("given", i, "link"), f"given point '{g.point}' names link", g.link, "links", links)


_NAMED = re.compile(r"^(?P<words>[\w -]*?)\s*'(?P<name>[^']*)'(?P<rest>.*)", re.S)


def _key_of_message(message: str, spec: schema.MechanismFile) -> tuple | None:
    """The key path a model error is about, from the part its message names first: "link
    'NAME'", "joint 'NAME'" (also "revolute joint", "gear", "cam pair", "rolling pair" …),
    "driver 'NAME'" or "driver joint 'NAME'"; None if it names none of the file's parts."""
    if message.startswith("there is no frame link"):
        return ("frame",) if "frame" in spec.model_fields_set else ("links",)
    m = _NAMED.match(message)
    if m is None:
        return None
    words, name, rest = m.group("words").split(), m.group("name"), m.group("rest")
    if words[:2] == ["given", "point"]:
        hit = next((i for i, g in enumerate(spec.given or []) if g.point == name), None)
        return None if hit is None else ("given", hit)
    if words and words[0] == "driver":
        for loc, d in _driver_keys(spec):
            if d.joint == name:
                sub = next((k for k in ("speed", "law", "reference")
                            if rest.lstrip(" :").startswith(k)), None)
                return loc + ((sub,) if sub else ())
        return None
    if words == ["link"] and name in spec.links:
        return ("links", name)
    if name in spec.joints:
        return ("joints", name)
    if name in spec.links:
        return ("links", name)
    return None


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
    """An angle in radians: a number or a string in the file's angle unit, or a string with its
    own unit ('30 deg', '0.5 rad')."""
    if isinstance(value, str):
        if unit_dimension(value, kind) is not None:
            return parse_quantity(value, default_unit="rad", kind=kind)
        value = parse_quantity(value, default_unit="rad", kind=kind)
    return float(value) if angle_unit.startswith("rad") else float(np.radians(value))


def _build(spec: schema.MechanismFile, text: str, source: str, base_dir: Path | None = None) -> Mechanism:
    unit = check_length_unit(spec.units.length)
    profiles = {name: build_profile(name, p, base_dir, angle_unit=spec.units.angle, source=source)
                for name, p in spec.profiles.items()}
    joints = []
    for name, j in spec.joints.items():
        links = tuple(j.links)
        if isinstance(j, schema.GenevaSpec):
            joints.append(GenevaPair(name, links, j.pin or name, j.slots, j.carrier))
            continue
        if isinstance(j, schema.StarWheelSpec):
            entry = None if j.entry is None else tuple(
                _angle_in_rad(a, spec.units.angle, f"joint '{name}' entry angle") for a in j.entry)
            joints.append(StarWheelPair(name, links, tuple(tuple(g) for g in j.groups), j.carrier,
                                        entry))
            continue
        point = getattr(j, "point", None) or name  # a rolling pair has no point
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
            joints.append(RollingContact(name, links, tuple(j.profiles), j.carrier))
        elif isinstance(j, schema.GearSpec):
            radii = tuple(float(r) for r in j.radii)
            if j.kind != "rack" and len(radii) != 2:
                raise ModelError(f"gear '{name}': give two pitch radii")
            joints.append(Gear(name, links, j.carrier, radii if len(radii) == 2 else (radii[0], np.inf),
                               j.kind, j.point if j.point else (name if name in spec.points else None)))
    driver_specs = list(spec.drivers or []) + ([spec.driver] if spec.driver else [])
    if not driver_specs and not spec.given:
        raise MechanismFileError("no [driver] given: name the joint that drives the mechanism (or "
                                 "give point velocities under [[given]])", source=source, key="driver")
    if driver_specs and spec.given:
        raise MechanismFileError("a chain is driven by a [driver] or by [[given]] point velocities, "
                                 "not both", source=source, key="given", line=_line_of(text, ("given",)))
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
    links = dict(spec.links)
    if spec.given and spec.frame not in links:
        links[spec.frame] = []  # a free chain: the frame carries nothing and holds nothing
    return Mechanism.build(name=spec.name, points=spec.points, links=links, joints=joints,
                           drivers=drivers, frame=spec.frame, length_unit=unit,
                           description=spec.description, profiles=profiles,
                           given=_given(spec, text, source))


def _given(spec: schema.MechanismFile, text: str, source: str) -> tuple:
    """The [[given]] entries as `model.given` conditions (angles in the file's angle unit)."""
    out = []
    for i, g in enumerate(spec.given or []):
        if g.velocity is not None:
            out.append(GivenVelocity(g.point, np.array(g.velocity, float),
                                     None if g.acceleration is None else np.array(g.acceleration, float),
                                     g.link))
        else:
            if isinstance(g.direction, list):
                d = np.array(g.direction, float)  # the model refuses a zero vector, naming the point
            else:
                try:
                    ang = _angle_in_rad(g.direction, spec.units.angle, f"given point '{g.point}' direction")
                except InputError as exc:
                    raise MechanismFileError(str(exc), source=source, key=_dotted(("given", i, "direction")),
                                             line=_line_of(text, ("given", i, "direction"))) from None
                d = np.array([np.cos(ang), np.sin(ang)])
            out.append(GivenDirection(g.point, d, g.curvature, g.link))
    return tuple(out)


def dump_schema() -> str:
    """The published JSON schema of mechanism files."""
    return json.dumps(schema.MechanismFile.model_json_schema(), indent=2)
