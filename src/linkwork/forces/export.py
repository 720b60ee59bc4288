"""A `ForceAnalysis` as named columns (one value per sample) and as the JSON document of
`linkwork forces --format json`. NaN (samples not solved) becomes null in JSON, empty in CSV."""

from __future__ import annotations

import math

import numpy as np

from ..model import Prismatic
from .kinetostatics import ForceAnalysis

CONVENTION = ("a pair's reaction is the force (and, for a prismatic pair, the couple) that the "
              "pair's first link exerts on its second; a driver's effort is the torque or force "
              "that its base link exerts on the driven link; counter-clockwise positive; SI "
              "units (N, N*m, W, J), points in the mechanism's length unit")


def columns(fa: ForceAnalysis, extra: dict[str, np.ndarray] | None = None) -> dict[str, np.ndarray]:
    """'input', 'status', '<driver>.torque' or '.force', '<pair>.fx', '.fy', '.couple' (prismatic),
    '.<component>', '.magnitude', frame and shaking loads, kinetic energy, the checks."""
    sol, mech = fa.solution, fa.dynamics.mechanism
    out: dict[str, np.ndarray] = {}
    if sol.time is not None:
        out["time"] = sol.time
    for i, d in enumerate(mech.drivers):
        out["input" if len(mech.drivers) == 1 else f"input.{d.joint}"] = sol.inputs[:, i]
    out["status"] = sol.status.astype(float)
    out["solved"] = fa.solved.astype(float)
    for d in mech.drivers:
        kind = "force" if isinstance(mech.joint(d.joint), Prismatic) else "torque"
        out[f"{d.joint}.{kind}"] = fa.efforts[d.joint]
        out[f"{d.joint}.{kind}_virtual_work"] = fa.virtual_work[d.joint]
    for name, r in fa.reactions.items():
        out[f"{name}.fx"], out[f"{name}.fy"] = r.force[:, 0], r.force[:, 1]
        if isinstance(mech.joint(name), Prismatic):
            out[f"{name}.couple"] = r.couple
        for comp, v in r.components.items():
            if comp not in ("x", "y", "couple"):
                out[f"{name}.{comp}"] = v
        out[f"{name}.magnitude"] = r.magnitude
    out["frame.fx"], out["frame.fy"] = fa.frame_force[:, 0], fa.frame_force[:, 1]
    out["frame.moment"] = fa.frame_moment
    if fa.shaking_force is not None:
        out["shaking.fx"], out["shaking.fy"] = fa.shaking_force[:, 0], fa.shaking_force[:, 1]
        out["shaking.moment"] = fa.shaking_moment
    if fa.kinetic_energy is not None:
        out["kinetic_energy"] = fa.kinetic_energy
    out["driver_power"] = fa.driver_power
    with np.errstate(invalid="ignore", divide="ignore"):
        out["power_residual_relative"] = np.abs(fa.power_residual) / fa.power_scale
    out["condition"] = fa.condition
    out.update(extra or {})
    return out


def _clean(v: float):
    return None if not math.isfinite(v) else v


def to_document(fa: ForceAnalysis, extra: dict[str, np.ndarray] | None = None,
                summary: dict | None = None) -> dict:
    """The JSON document: `columns` (see `columns`, with `extra` columns) and `summary` keys."""
    mech = fa.dynamics.mechanism
    cols = columns(fa, extra)
    return {"mechanism": mech.name, "length_unit": mech.length_unit,
            "inertia": fa.inertia, "sign_convention": CONVENTION,
            "samples": len(fa), **(summary or {}),
            "columns": {k: [_clean(float(x)) for x in v] for k, v in cols.items()}}


def column_units(fa: ForceAnalysis, extra_units: dict[str, str] | None = None) -> dict[str, str]:
    """The unit of each column of `columns` as pint reads it ("" for codes): SI for forces,
    couples, energy and power, the file's length unit for a prismatic input; `extra_units`
    for the caller's own columns."""
    sol, mech = fa.solution, fa.dynamics.mechanism
    out: dict[str, str] = {}
    if sol.time is not None:
        out["time"] = "s"
    for d in mech.drivers:
        slide = isinstance(mech.joint(d.joint), Prismatic)
        out["input" if len(mech.drivers) == 1 else f"input.{d.joint}"] = (
            mech.length_unit if slide else "rad")
        kind, unit = ("force", "N") if slide else ("torque", "N*m")
        out[f"{d.joint}.{kind}"] = out[f"{d.joint}.{kind}_virtual_work"] = unit
    out["status"] = out["solved"] = ""
    for name, r in fa.reactions.items():
        out[f"{name}.fx"] = out[f"{name}.fy"] = out[f"{name}.magnitude"] = "N"
        if isinstance(mech.joint(name), Prismatic):
            out[f"{name}.couple"] = "N*m"
        for comp in r.components:
            if comp not in ("x", "y", "couple"):
                # a hinge's friction is the moment of its friction circle; a slide's, a force
                revolute = comp == "friction" and mech.joint(name).kind == "revolute"
                out[f"{name}.{comp}"] = "N*m" if revolute else "N"
    for body in ("frame", "shaking"):
        out[f"{body}.fx"] = out[f"{body}.fy"] = "N"
        out[f"{body}.moment"] = "N*m"
    out.update(kinetic_energy="J", driver_power="W", power_residual_relative="1", condition="1")
    out.update(extra_units or {})
    return out


def to_csv_text(fa: ForceAnalysis, extra: dict[str, np.ndarray] | None = None,
                extra_units: dict[str, str] | None = None) -> str:
    """The columns as CSV, each header with its unit, `name [unit]` (as `linkwork analyze`)."""
    from ..kinematics.export import with_unit
    cols = columns(fa, extra)
    units = column_units(fa, extra_units)
    names = list(cols)
    lines = [",".join(with_unit(k, units.get(k, "")) for k in names)]
    data = np.column_stack([np.asarray(cols[k], dtype=float) for k in names])
    for row in data:
        lines.append(",".join("" if not math.isfinite(x) else repr(float(x)) for x in row))
    return "\n".join(lines) + "\n"
