"""Input values as the user writes them on the command line (--at, --sweep, --speed): angles
in degrees, lengths in the file's unit or times, one value per driver or NAME=V per driver;
and an input value shown back the same way."""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..model import ConstantSpeed, Driver, Mechanism
from ..units import parse_quantity, unit_dimension


def _is_prismatic(mech: Mechanism, driver: Driver | None = None) -> bool:
    d = mech.drivers[0] if driver is None else driver
    return mech.joint(d.joint).kind == "prismatic"


def driver_names(mech: Mechanism) -> str:
    return ", ".join(d.joint for d in mech.drivers)


def show_input(mech: Mechanism, driver: Driver, value: float) -> str:
    """One input value as the user writes it: degrees, or the file's length unit."""
    if _is_prismatic(mech, driver):
        return f"{value:.4g} {mech.length_unit}"
    return f"{np.degrees(value):.3f}°"


def input_value(mech: Mechanism, text: str, driver: Driver | None = None,
                what: str = "input value", part: str = "") -> tuple[str, float]:
    """('input', value in rad or length unit) or ('time', seconds) for one value written by
    the user: degrees for a revolute driver and the file's unit for a prismatic one, unless a
    unit is written (`1.2rad`, `0.5 s`). `driver` defaults to the only (first) driver; when it
    is given, messages name it; `what` names the option in messages (--at, --sweep O2) and
    `part` the value's place in it (STEP)."""
    text = text.strip()
    the = "the driver" if driver is None else f"driver {driver.joint}"
    if not text:
        raise InputError("empty input value" if driver is None else f"empty value for driver {driver.joint}")
    kind = f"{what} {part}".strip()
    dim = unit_dimension(text, kind)
    if dim == "time":
        return "time", parse_quantity(text, default_unit="s", kind=kind)
    if _is_prismatic(mech, driver):
        if dim not in (None, "length"):
            raise InputError(f"{what}: '{text}': {the} is prismatic, give a length (default "
                             f"{mech.length_unit})")
        return "input", parse_quantity(text, default_unit=mech.length_unit, kind=kind)
    if dim not in (None, "angle"):
        raise InputError(f"{what}: '{text}': {the} is revolute, give an angle (degrees by default)")
    return "input", float(np.radians(parse_quantity(text, default_unit="deg", kind=kind)))


MAX_SAMPLES = 10_000_000


def _range(mech: Mechanism, text: str, label: str, driver: Driver | None) -> tuple[str, np.ndarray]:
    """START:STOP:STEP -> (kind, samples); `label` starts every message (--sweep, --sweep O2)."""
    parts = text.split(":")
    if len(parts) != 3:
        raise InputError(f"{label} '{text}': write START:STOP:STEP")
    parsed = [input_value(mech, p, driver, label, part)
              for p, part in zip(parts, ("START", "STOP", "STEP"))]
    kinds = {k for k, _ in parsed}
    if len(kinds) > 1:
        raise InputError(f"{label} mixes times and input values")
    (a, b, h) = (v for _, v in parsed)
    if h == 0:
        raise InputError(f"{label}: the step must not be zero")
    if (b - a) * h < 0:
        raise InputError(f"{label}: the step goes away from STOP")
    n = int(np.floor((b - a) / h + 1e-9)) + 1
    if n > MAX_SAMPLES:
        raise InputError(f"{label} asks for {n} samples; at most 10 000 000")
    return kinds.pop(), a + h * np.arange(n)


def _texts(option: str | list[str] | tuple[str, ...] | None) -> list[str]:
    if option is None:
        return []
    return [option] if isinstance(option, str) else list(option)


def _items(texts: list[str]) -> list[tuple[str | None, str]]:
    """(driver name or None, value text) for every comma-separated item of the option's
    occurrences. `NAME=V` names the driver; the items after it without a name continue the
    same driver's list (`O2=0,30,60` is three values of O2), up to the next `NAME=`."""
    out: list[tuple[str | None, str]] = []
    for text in texts:
        name = None
        for item in text.split(","):
            if "=" in item:
                name, item = (s.strip() for s in item.split("=", 1))
            out.append((name, item.strip()))
    return out


def _driver(mech: Mechanism, name: str, label: str) -> Driver:
    for d in mech.drivers:
        if d.joint == name:
            return d
    if not name:
        raise InputError(f"{label}: a value has '=' but no driver name before it; "
                         f"the drivers are {driver_names(mech)}")
    if name in mech.joint_index:
        raise InputError(f"{label} {name}: joint '{name}' is not a driver; the drivers are "
                         f"{driver_names(mech)}")
    raise InputError(f"{label} {name}: mechanism '{mech.name}' has no driver '{name}'; the "
                     f"drivers are {driver_names(mech)}")


def input_values(mech: Mechanism, at: str | list[str] | None,
                 sweep: str | list[str] | None) -> tuple[str, np.ndarray] | None:
    """The samples asked for with --at and --sweep (None: neither was given, the whole motion).

    Returns ('time', t of shape (N,)) or ('input', values of shape (N, drivers)), in seconds,
    radians and the file's length unit.

    One driver: --at V[,V…] or --sweep START:STOP:STEP. Several drivers: every driver named,
    --at NAME=V[,V…] and/or --sweep NAME=START:STOP:STEP, once per driver (in one option, comma-
    separated, or repeated). The drivers move in lock-step: sample k takes every driver's k-th
    value; a driver with a single value is held at it. Times (--at 0.5s, --sweep 0s:2s:0.1s)
    are written without a name and drive every driver through its law.
    """
    at_texts, sweep_texts = _texts(at), _texts(sweep)
    if not at_texts and not sweep_texts:
        return None
    at_items, sweep_items = _items(at_texts), _items(sweep_texts)
    names = {n for n, _ in at_items + sweep_items}
    if None in names and len(names) > 1:
        named = sorted(n for n in names if n is not None)
        raise InputError(f"name the driver of every value or of none: values for "
                         f"{', '.join(named)} are given together with values without a name")
    if None in names:
        return _unnamed(mech, at_texts, at_items, sweep_texts)
    return _named(mech, at_items, sweep_items)


def _unnamed(mech: Mechanism, at_texts: list[str], at_items: list, sweep_texts: list[str]
             ) -> tuple[str, np.ndarray]:
    if at_texts and sweep_texts:
        raise InputError("give either --at or --sweep, not both (with several drivers, named "
                         "ones combine: --sweep O2=0:360:10 --at O5=45 holds O5 while O2 turns)")
    if len(mech.drivers) != 1:
        # only times drive several drivers without names: check before reading the values
        # with the first driver's unit
        option = "--at" if at_texts else "--sweep"
        texts = [v for _, v in at_items] if at_texts else sweep_texts[0].split(":")
        if any(t.strip() and unit_dimension(t) != "time" for t in texts):
            raise InputError(
                f"mechanism '{mech.name}' has {len(mech.drivers)} drivers ({driver_names(mech)}): "
                f"name the driver of each value, e.g. --at {mech.drivers[0].joint}=30 "
                f"--at {mech.drivers[1].joint}=10 or --sweep {mech.drivers[0].joint}=0:360:10 "
                f"--sweep {mech.drivers[1].joint}=0:360:10, or give times ({option} 0.5s)")
    if at_texts:
        parsed = [input_value(mech, v, what="--at") for _, v in at_items]
        kinds = {k for k, _ in parsed}
        if len(kinds) > 1:
            raise InputError("--at mixes times and input values")
        kind, values = kinds.pop(), np.array([v for _, v in parsed])
    else:
        if len(sweep_texts) > 1:
            raise InputError("--sweep is given more than once; a one-driver mechanism takes one "
                             "START:STOP:STEP (name the drivers of a mechanism with several)")
        kind, values = _range(mech, sweep_texts[0], "--sweep", None)
    return kind, values if kind == "time" else values[:, None]


def _named(mech: Mechanism, at_items: list, sweep_items: list) -> tuple[str, np.ndarray]:
    columns: dict[str, np.ndarray] = {}
    origin: dict[str, str] = {}
    for option, items in (("--at", at_items), ("--sweep", sweep_items)):
        grouped: dict[str, list[str]] = {}
        for name, text in items:
            grouped.setdefault(name, []).append(text)
        for name, texts in grouped.items():
            d = _driver(mech, name, option)
            label = f"{option} {name}"
            if name in origin:
                raise InputError(f"{label}: driver {name} is given twice ({origin[name]} and "
                                 f"{option}); give each driver's values once")
            if option == "--sweep" and len(texts) != 1:
                raise InputError(f"{label}: one START:STOP:STEP per driver, got "
                                 f"{', '.join(texts)}")
            try:
                if option == "--at":
                    parsed = [input_value(mech, t, d, label) for t in texts]
                    kind = "time" if any(k == "time" for k, _ in parsed) else "input"
                    vals = np.array([v for _, v in parsed])
                else:
                    kind, vals = _range(mech, texts[0], label, d)
            except InputError as exc:
                msg = str(exc)
                raise InputError(msg if msg.startswith(label) else f"{label}: {msg}") from None
            if kind == "time":
                raise InputError(f"{label}: a time drives every driver at once through its law; "
                                 f"write it without a driver name ({option} 0.5s)")
            columns[name], origin[name] = vals, option
    missing = [d.joint for d in mech.drivers if d.joint not in columns]
    if missing:
        which = ", ".join(missing)
        raise InputError(
            f"no value for driver{'s' if len(missing) > 1 else ''} {which}: every driver needs "
            f"its values, e.g. --at {missing[0]}=V[,V…] or --sweep {missing[0]}=START:STOP:STEP")
    counts = {name: len(v) for name, v in columns.items()}
    n = max(counts.values())
    if any(c not in (1, n) for c in counts.values()):
        listed = ", ".join(f"{name} has {c}" for name, c in counts.items())
        raise InputError(f"the drivers move in lock-step and need the same number of values: "
                         f"{listed} (a driver with one value is held at it)")
    return "input", np.column_stack([np.broadcast_to(columns[d.joint], (n,)) for d in mech.drivers])


def input_speeds(mech: Mechanism, speed: str | list[str] | None) -> np.ndarray | None:
    """Input speeds per driver (shape (drivers,)) from --speed, or None when not given.

    One driver: --speed Q (rad/s or the length unit per second unless a unit is written).
    Several drivers: --speed NAME=Q per driver, in one option (comma-separated) or repeated;
    a driver not named keeps its file's constant speed (0 under another law)."""
    texts = _texts(speed)
    if not texts:
        return None

    def one(d: Driver, text: str) -> float:
        unit = f"{mech.length_unit}/s" if _is_prismatic(mech, d) else "rad/s"
        return parse_quantity(text, default_unit=unit, kind="speed" if len(mech.drivers) == 1
                              else f"speed of driver {d.joint}")

    items = _items(texts)
    names = [n for n, _ in items]
    if all(n is None for n in names):
        if len(items) != 1:
            raise InputError("--speed takes one speed; name the drivers of a mechanism with "
                             "several (--speed O2=120rpm --speed O5=60rpm)")
        if len(mech.drivers) != 1:
            raise InputError(f"mechanism '{mech.name}' has {len(mech.drivers)} drivers "
                             f"({driver_names(mech)}): name the driver of each speed, e.g. "
                             f"--speed {mech.drivers[0].joint}={texts[0].strip()}")
        return np.array([one(mech.drivers[0], items[0][1])])
    if None in names:
        raise InputError("--speed: name the driver of every speed or of none")
    w = np.array([d.law.speed if isinstance(d.law, ConstantSpeed) else 0.0 for d in mech.drivers])
    seen: set[str] = set()
    for name, text in items:
        d = _driver(mech, name, "--speed")
        if name in seen:
            raise InputError(f"--speed {name}: driver {name} is given twice; give one speed")
        seen.add(name)
        w[[x.joint for x in mech.drivers].index(name)] = one(d, text)
    return w
