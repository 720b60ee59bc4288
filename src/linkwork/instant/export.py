"""The JSON documents of the instantaneous kinematics (`linkwork poles` and `linkwork curvature
--format json`, the workbench's API): plain dicts of the file's length unit, radians and
seconds. Points at infinity are written with their direction, never as numbers; an undefined
value is null."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry import Circle, Point
from ..kinematics import Solution, Status
from .centrodes import Centrodes, centrodes
from .curvature import (Instant, PathCurvature, bresse_circle, curvature_centre,
                        inflection_circle, instant, return_circle)
from .poles import agreement, kennedy_poles, pole_line_count, pole_lines, pole_schedule, poles


def num(x) -> float | None:
    x = float(x) + 0.0  # no negative zeros in the output
    return x if math.isfinite(x) else None


def point_doc(p: Point, n: int) -> dict | None:
    """{"x", "y"}, {"at_infinity": true, "direction"} or None (undefined) for sample `n`."""
    h = np.asarray(p.coords[n])
    if not np.isfinite(h).all():
        return None
    if h[2] == 0:
        d = h[:2] / np.hypot(*h[:2])
        return {"at_infinity": True, "direction": [num(d[0]), num(d[1])]}
    return {"x": num(h[0]), "y": num(h[1])}


def circle_doc(c: Circle, n: int) -> dict | None:
    """{"centre", "radius"}, {"line": true, "through", "direction"} (a circle of infinite
    radius) or None for sample `n`."""
    r = float(c.radius[n])
    if math.isnan(r):
        return None
    if math.isinf(r):
        a, nrm = c.anchor.xy[n], c.normal.xy[n]
        return {"line": True, "through": {"x": num(a[0]), "y": num(a[1])},
                "direction": [num(-nrm[1]), num(nrm[0])]}
    return {"centre": point_doc(c.centre, n), "radius": num(r)}


def input_doc(sol: Solution, n: int) -> dict:
    if sol.time is not None:
        return {"time": num(sol.time[n])}
    return {"input": [num(v) for v in sol.inputs[n]]}


def poles_document(sol: Solution, schedule: bool = False) -> dict:
    """All relative poles of every sample, from the velocities and by the three-pole theorem,
    their discrepancy and the largest residual of the pole lines."""
    mech = sol.mechanism
    P = poles(sol)
    sch = pole_schedule(mech)
    K = kennedy_poles(sol, sch)
    agree = agreement(P, K, mech.length_scale)
    lines = pole_lines(P, mech.length_scale)
    doc = {
        "mechanism": mech.name,
        "links": {str(i + 1): ln for i, ln in enumerate(P.links)},
        "pole_count": len(P), "pole_line_count": pole_line_count(len(mech.links)),
        "unreachable_by_three_pole_theorem": [P.label(*p) for p in sch.unreachable],
        "samples": [],
    }
    if schedule:
        doc["schedule"] = sch.lines()
    for k in range(len(sol)):
        rows = [{"label": P.label(*pair), "links": list(pair), "pole": point_doc(P[pair], k),
                 "three_pole_theorem": point_doc(K[pair], k), "discrepancy": num(agree[pair][k])}
                for pair in P]
        res = [pl.residual[k] for pl in lines]
        doc["samples"].append({**input_doc(sol, k), "status": str(Status(int(sol.status[k]))),
                               "poles": rows,
                               "pole_lines_max_residual": num(np.nanmax(res)) if res else None})
    return doc


@dataclass(frozen=True)
class CurvatureReport:
    """What `linkwork curvature` reports: the instant, the three circles (by their JSON
    names), the centrodes and the path curvature of the asked points (label, result)."""

    instant: Instant
    circles: dict[str, Circle]
    centrodes: Centrodes
    paths: list[tuple[str, PathCurvature]]


def curvature_report(sol: Solution, link: str, relative_to: str | None = None,
                     points: list[tuple[str, str | np.ndarray]] = ()) -> CurvatureReport:
    """Curvature theory of `link`'s motion relative to `relative_to` (default the frame) at
    every sample of `sol` (solved to order 3), with the curvature centres of `points` ((label,
    point name or design coordinates) pairs)."""
    return CurvatureReport(
        instant(sol, link, relative_to),
        {"inflection_circle": inflection_circle(sol, link, relative_to),
         "return_circle": return_circle(sol, link, relative_to),
         "bresse_circle": bresse_circle(sol, link, relative_to)},
        centrodes(sol, link, relative_to),
        [(p, curvature_centre(sol, link, s, relative_to)) for p, s in points])


def curvature_document(sol: Solution, link: str, relative_to: str | None = None,
                       points: list[tuple[str, str | np.ndarray]] = ()) -> dict:
    """The `curvature_report` as JSON: pole, pole velocity and acceleration, inflection pole
    and circles, Γ, centrode radii and the curvature centres of `points`."""
    mech = sol.mechanism
    rep = curvature_report(sol, link, relative_to, points)
    ins, circles, cen, paths = rep.instant, rep.circles, rep.centrodes, rep.paths
    u = ins.pole_velocity.xy
    b = ins.pole_acceleration.xy
    doc = {"mechanism": mech.name, "link": link, "relative_to": ins.relative_to,
           "unit": mech.length_unit, "samples": []}
    for k in range(len(sol)):
        doc["samples"].append({
            **input_doc(sol, k), "status": str(Status(int(sol.status[k]))),
            "omega": num(ins.omega[k]), "alpha": num(ins.alpha[k]),
            "pole": point_doc(ins.pole, k),
            "pole_velocity": [num(u[k, 0]), num(u[k, 1])],
            "pole_velocity_magnitude": num(np.hypot(*u[k])),
            "pole_acceleration": [num(b[k, 0]), num(b[k, 1])],
            "pole_tangent": [num(x) for x in ins.pole_tangent.xy[k]],
            "pole_normal": [num(x) for x in ins.pole_normal.xy[k]],
            "inflection_pole": point_doc(ins.inflection_pole, k),
            "diameter": num(ins.diameter[k]),
            "diameter_is_infinite": bool(np.isinf(ins.diameter[k])),
            "tangential_pole": point_doc(ins.tangential_pole, k),
            "acceleration_pole": point_doc(ins.acceleration_pole, k),
            **{name: circle_doc(c, k) for name, c in circles.items()},
            "fixed_centrode_radius": num(cen.fixed_radius[k]),
            "moving_centrode_radius": num(cen.moving_radius[k]),
            "curvature_centres": {
                name: {"position": point_doc(Point.from_xy(pc.position), k),
                       "centre": point_doc(pc.centre, k),
                       "radius": num(pc.radius[k])} for name, pc in paths}})
    return doc
