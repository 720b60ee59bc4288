"""Solution exports: the JSON document of `analyze`, and a wide pandas table (CSV, Parquet)."""

from __future__ import annotations

import math

import numpy as np

from ..kinematics.solution import Solution, Status


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


def columns(sol: Solution) -> dict[str, np.ndarray]:
    """The wide table of a solution as named columns, one row per sample: inputs (and time),
    status, condition, error bound, every point's x, y and rates, every moving link's angle,
    ω, α, and every pair's fields."""
    mech = sol.mechanism
    cols: dict[str, np.ndarray] = {}
    for i, d in enumerate(mech.drivers):
        cols["input" if len(mech.drivers) == 1 else f"input.{d.joint}"] = sol.inputs[:, i]
    if sol.time is not None:
        cols["time"] = sol.time
    cols["status"] = np.array([str(Status(int(s))) for s in sol.status])
    cols["condition"] = sol.condition
    cols["error"] = sol.errors
    for p in mech.points:
        m = sol.point(p)
        for name, arr in (("x", m.position), ("vx", m.velocity), ("ax", m.acceleration)):
            if arr is not None:
                cols[f"{p}.{name}"] = arr[:, 0]
                cols[f"{p}.{name.replace('x', 'y')}"] = arr[:, 1]
    for ln in mech.moving_links:
        m = sol.link(ln)
        cols[f"{ln}.angle"], cols[f"{ln}.omega"] = m.angle, m.omega
        if m.alpha is not None:
            cols[f"{ln}.alpha"] = m.alpha
    for jn, f in _joint_fields(sol).items():
        for k, v in f.items():
            if v.ndim == 1:
                cols[f"{jn}.{k}"] = v
            else:
                cols[f"{jn}.{k}.x"], cols[f"{jn}.{k}.y"] = v[:, 0], v[:, 1]
    return cols


def to_dataframe(sol: Solution):
    """`columns` as a pandas DataFrame."""
    import pandas as pd

    return pd.DataFrame(columns(sol))


def csv_lines(sol: Solution, header: bool = True, piece: int = 4096):
    """The wide table as CSV text in pieces of `piece` rows (the format of pandas' `to_csv`:
    shortest round-trip numbers, NaN as an empty field), without pandas."""
    import csv
    import io

    cols = columns(sol)
    text = [np.where(np.isnan(v), "", v.astype(str)) if v.dtype.kind == "f" else v.astype(str)
            for v in cols.values()]
    buf = io.StringIO()
    out = csv.writer(buf, lineterminator="\n")
    if header:
        out.writerow(cols)
    for lo in range(0, len(sol), piece):
        out.writerows(zip(*(t[lo:lo + piece] for t in text)))
        yield buf.getvalue()
        buf.seek(0)
        buf.truncate()
    if header and len(sol) == 0:
        yield buf.getvalue()
