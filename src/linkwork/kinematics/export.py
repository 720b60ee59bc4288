"""Solution exports: the JSON document of `analyze`, and a wide table (CSV, Parquet) whose
columns carry their units (`column_units`: in a CSV header as `name [unit]`, in Parquet's
metadata under `linkwork.units`, as the sweeps write theirs)."""

from __future__ import annotations

import math

import numpy as np

from ..kinematics.solution import Solution, Status
from ..model import Prismatic

#: the unit of each field of a pair's report (`Solution.joint`), "L" standing for the file's
#: length unit; fields without a unit (codes, a profile's own parameter) are not listed
JOINT_FIELD_UNITS = {
    **dict.fromkeys(("angle", "angle_1", "angle_2", "driver_angle", "arc_angle",
                     "pressure_angle"), "rad"),
    **dict.fromkeys(("omega", "omega_1", "omega_2", "arc_rate", "roller_spin"), "rad/s"),
    "alpha": "rad/s^2",
    **dict.fromkeys(("slide", "point", "point_on_profile", "point_on_follower"), "L"),
    **dict.fromkeys(("velocity", "sliding_velocity", "profile_speed", "follower_speed"), "L/s"),
    **dict.fromkeys(("acceleration", "coriolis", "sliding_acceleration"), "L/s^2"),
    "curvature": "1/L",
    **dict.fromkeys(("normal", "ratio"), "1"),
}
#: the fields of a pair's report that have no unit: the phase and slot codes of intermittent
#: pairs, and the contact parameters u, v (each profile's own: an angle, a length, …)
UNITLESS_JOINT_FIELDS = ("phase", "slot", "u", "v")


def _num(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def _vec(a: np.ndarray) -> list:
    return [_num(v) for v in a]


def _joint_fields(sol: Solution) -> dict[str, dict[str, np.ndarray]]:
    return {j.name: sol.joint(j.name) for j in sol.mechanism.joints}


def to_document(sol: Solution) -> dict:
    mech = sol.mechanism
    return {
        "mechanism": mech.name,
        "units": {"length": mech.length_unit, "angle": "rad", "time": "s"},
        "drivers": [d.joint for d in mech.drivers],
        "samples": list(iter_samples(sol)),
    }


def iter_samples(sol: Solution):
    """The samples of `to_document`, one dict at a time (so that a long solution can be written
    as it is read: JSON Lines, a streamed JSON document)."""
    mech = sol.mechanism
    points = {p: sol.point(p) for p in mech.points}
    links = {ln: sol.link(ln) for ln in mech.link_names}
    joints = _joint_fields(sol)
    single = sol.inputs.shape[1] == 1
    for n in range(len(sol)):
        s = {
            "input": _num(sol.inputs[n, 0]) if single else _vec(sol.inputs[n]),
            "status": str(Status(int(sol.status[n]))),
            "condition": _num(sol.condition[n]),
            "error": _num(sol.errors[n]),
        }
        if sol.time is not None:
            s["time"] = _num(sol.time[n])
        s["points"] = {p: {"position": _vec(m.position[n]), "velocity": _vec(m.velocity[n]),
                           "acceleration": _vec(m.acceleration[n]) if m.acceleration is not None else None}
                       for p, m in points.items()}
        s["links"] = {ln: {"angle": _num(m.angle[n]), "omega": _num(m.omega[n]),
                           "alpha": _num(m.alpha[n]) if m.alpha is not None else None}
                      for ln, m in links.items() if ln != mech.frame}
        s["joints"] = {jn: {k: (_vec(v[n]) if v.ndim == 2 else _num(v[n])) for k, v in f.items()}
                       for jn, f in joints.items()}
        yield s


def _table(sol: Solution) -> list[tuple[str, np.ndarray, str]]:
    """The wide table as (column, values, unit) in order, the unit with "L" for the length
    unit ("" for codes without one)."""
    mech = sol.mechanism
    out: list[tuple[str, np.ndarray, str]] = []
    for i, d in enumerate(mech.drivers):
        unit = "L" if isinstance(mech.joint(d.joint), Prismatic) else "rad"
        out.append(("input" if len(mech.drivers) == 1 else f"input.{d.joint}", sol.inputs[:, i], unit))
    if sol.time is not None:
        out.append(("time", sol.time, "s"))
    out.append(("status", np.array([str(Status(int(s))) for s in sol.status]), ""))
    out.append(("condition", sol.condition, "1"))
    out.append(("error", sol.errors, "1"))  # relative (`precision`)
    for p in mech.points:
        m = sol.point(p)
        for name, arr, unit in (("x", m.position, "L"), ("vx", m.velocity, "L/s"),
                                ("ax", m.acceleration, "L/s^2")):
            if arr is not None:
                out.append((f"{p}.{name}", arr[:, 0], unit))
                out.append((f"{p}.{name.replace('x', 'y')}", arr[:, 1], unit))
    for ln in mech.moving_links:
        m = sol.link(ln)
        out.append((f"{ln}.angle", m.angle, "rad"))
        out.append((f"{ln}.omega", m.omega, "rad/s"))
        if m.alpha is not None:
            out.append((f"{ln}.alpha", m.alpha, "rad/s^2"))
    for jn, f in _joint_fields(sol).items():
        for k, v in f.items():
            unit = JOINT_FIELD_UNITS.get(k, "")
            if v.ndim == 1:
                out.append((f"{jn}.{k}", v, unit))
            else:
                out.append((f"{jn}.{k}.x", v[:, 0], unit))
                out.append((f"{jn}.{k}.y", v[:, 1], unit))
    return out


def _units(table: list, length_unit: str) -> dict[str, str]:
    return {name: unit.replace("L", length_unit) for name, _, unit in table}


def columns(sol: Solution) -> dict[str, np.ndarray]:
    """The wide table of a solution as named columns, one row per sample: inputs (and time),
    status, condition, error bound, every point's x, y and rates, every moving link's angle,
    ω, α, and every pair's fields."""
    return {name: v for name, v, _ in _table(sol)}


def column_units(sol: Solution) -> dict[str, str]:
    """The unit of each column of `columns` ("" for codes without one): the file's length
    unit, radians and seconds, written as pint reads them (`mm/s^2`)."""
    return _units(_table(sol), sol.mechanism.length_unit)


def with_unit(name: str, unit: str) -> str:
    """A column's header with its unit: `name [unit]` (the name alone where there is none)."""
    return f"{name} [{unit}]" if unit else name


def write_parquet(sol: Solution, path) -> None:
    """The wide table as Parquet, all or nothing, with the units of its columns (`column_units`)
    as JSON in the schema's metadata, key b"linkwork.units", and the mechanism's name under
    b"linkwork.mechanism"."""
    import json

    import pyarrow as pa
    import pyarrow.parquet as pq

    from ..outputs import output_path
    cols = _table(sol)
    table = pa.table({name: v for name, v, _ in cols})
    meta = {b"linkwork.units": json.dumps(_units(cols, sol.mechanism.length_unit)).encode(),
            b"linkwork.mechanism": sol.mechanism.name.encode()}
    with output_path(path) as tmp:
        pq.write_table(table.replace_schema_metadata(meta), tmp)


def to_dataframe(sol: Solution):
    """`columns` as a pandas DataFrame (units in `DataFrame.attrs['units']`)."""
    import pandas as pd

    cols = _table(sol)
    df = pd.DataFrame({name: v for name, v, _ in cols})
    df.attrs["units"] = _units(cols, sol.mechanism.length_unit)
    return df


def csv_lines(sol: Solution, header: bool = True, piece: int = 4096, units: bool = False):
    """The wide table as CSV text in pieces of `piece` rows (the format of pandas' `to_csv`:
    shortest round-trip numbers, NaN as an empty field), without pandas; `units`: each header
    with its unit, `name [unit]` (`column_units`)."""
    import csv
    import io

    table = _table(sol)
    cols = {name: v for name, v, _ in table}
    text = [np.where(np.isnan(v), "", v.astype(str)) if v.dtype.kind == "f" else v.astype(str)
            for v in cols.values()]
    buf = io.StringIO()
    out = csv.writer(buf, lineterminator="\n")
    if header:
        out.writerow([with_unit(c, u) for c, u in _units(table, sol.mechanism.length_unit).items()]
                     if units else cols)
    for lo in range(0, len(sol), piece):
        out.writerows(zip(*(t[lo:lo + piece] for t in text)))
        yield buf.getvalue()
        buf.seek(0)
        buf.truncate()
    if header and len(sol) == 0:
        yield buf.getvalue()
