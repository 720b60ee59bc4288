"""The `linkwork poles` and `linkwork curvature` commands: the command-line face of
`linkwork.instant` (option parsing, Rich tables, JSON documents). All kinematics is done by the
library functions; points at infinity are written with their direction, never as numbers."""

from __future__ import annotations

import json
import math
from enum import Enum
from typing import Optional

import numpy as np
import typer
from rich.console import Console
from rich.table import Table

from ..errors import InputError
from ..geometry import Circle, Point
from ..instant import (agreement, centrodes, curvature_centre, inflection_circle, instant,
                       kennedy_poles, pole_line_count, pole_lines, pole_schedule, poles,
                       return_circle, bresse_circle)
from ..kinematics import Solution, Status, solve
from ..model import Mechanism
from .common import load_mechanism, user_errors, write_output
from .inputs import input_values


class Format(str, Enum):
    table = "table"
    json = "json"


# ---------------------------------------------------------------------------- helpers
def _num(x) -> float | None:
    x = float(x) + 0.0  # no negative zeros in the output
    return x if math.isfinite(x) else None


def _point_doc(p: Point, n: int) -> dict | None:
    h = np.asarray(p.coords[n])
    if not np.isfinite(h).all():
        return None
    if h[2] == 0:
        d = h[:2] / np.hypot(*h[:2])
        return {"at_infinity": True, "direction": [_num(d[0]), _num(d[1])]}
    return {"x": _num(h[0]), "y": _num(h[1])}


def _point_text(p: Point, n: int) -> str:
    doc = _point_doc(p, n)
    if doc is None:
        return "undefined"
    if doc.get("at_infinity"):
        dx, dy = doc["direction"]
        return f"at infinity, direction {math.degrees(math.atan2(dy, dx)) % 180:.3f}°"
    return f"({doc['x'] + 0.0:.6g}, {doc['y'] + 0.0:.6g})"


def _circle_doc(c: Circle, n: int) -> dict | None:
    r = float(c.radius[n])
    if math.isnan(r):
        return None
    if math.isinf(r):
        a, nrm = c.anchor.xy[n], c.normal.xy[n]
        return {"line": True, "through": {"x": _num(a[0]), "y": _num(a[1])},
                "direction": [_num(-nrm[1]), _num(nrm[0])]}
    return {"centre": _point_doc(c.centre, n), "radius": _num(r)}


def _circle_text(c: Circle, n: int) -> str:
    doc = _circle_doc(c, n)
    if doc is None:
        return "undefined"
    if doc.get("line"):
        t, d = doc["through"], doc["direction"]
        return (f"straight line through ({t['x']:.6g}, {t['y']:.6g}), "
                f"direction {math.degrees(math.atan2(d[1], d[0])) % 180:.3f}°")
    cen = doc["centre"]
    return f"centre ({cen['x']:.6g}, {cen['y']:.6g}), radius {doc['radius']:.6g}"


def _solve(mech: Mechanism, at: Optional[list[str]], order: int) -> Solution:
    asked = input_values(mech, at, None)
    if asked is None:
        return solve(mech, order=order)
    kind, values = asked
    return solve(mech, times=values, order=order) if kind == "time" else solve(mech, values, order=order)


def _input_text(mech: Mechanism, sol: Solution, n: int) -> str:
    if sol.time is not None:
        return f"t = {sol.time[n]:.6g} s"
    def one(d, v) -> str:
        prismatic = mech.joint(d.joint).kind == "prismatic"
        return f"{v:.6g} {mech.length_unit}" if prismatic else f"{math.degrees(v):.6g}°"

    if len(mech.drivers) == 1:
        return one(mech.drivers[0], sol.inputs[n, 0])
    return ", ".join(f"{d.joint} {one(d, v)}" for d, v in zip(mech.drivers, sol.inputs[n]))


def _input_doc(sol: Solution, n: int):
    if sol.time is not None:
        return {"time": _num(sol.time[n])}
    return {"input": [_num(v) for v in sol.inputs[n]]}


def _render(tables: list) -> str:
    con = Console(record=True, width=150, file=open("/dev/null", "w"), markup=False)
    for t in tables:
        con.print(t)
    return con.export_text()


# ---------------------------------------------------------------------------- poles
def _poles_command(mechanism: str, at: Optional[list[str]], schedule: bool, fmt: Format,
                   output: Optional[str]) -> None:
    with user_errors():
        mech = load_mechanism(mechanism)
        sol = _solve(mech, at, 1)
        P = poles(sol)
        sch = pole_schedule(mech)
        K = kennedy_poles(sol, sch)
        agree = agreement(P, K, mech.length_scale)
        lines = pole_lines(P, mech.length_scale)
        n = len(mech.links)
        if fmt is Format.json:
            doc = {
                "mechanism": mech.name,
                "links": {str(i + 1): ln for i, ln in enumerate(P.links)},
                "pole_count": len(P), "pole_line_count": pole_line_count(n),
                "unreachable_by_three_pole_theorem": [P.label(*p) for p in sch.unreachable],
                "samples": [],
            }
            if schedule:
                doc["schedule"] = sch.lines()
            for k in range(len(sol)):
                rows = []
                for pair in P:
                    rows.append({"label": P.label(*pair), "links": list(pair),
                                 "pole": _point_doc(P[pair], k),
                                 "three_pole_theorem": _point_doc(K[pair], k),
                                 "discrepancy": _num(agree[pair][k])})
                res = [pl.residual[k] for pl in lines]
                doc["samples"].append({**_input_doc(sol, k), "status": str(Status(int(sol.status[k]))),
                                       "poles": rows,
                                       "pole_lines_max_residual": _num(np.nanmax(res)) if res else None})
            write_output(json.dumps(doc, indent=1) + "\n", output)
            return
        tables = []
        for k in range(len(sol)):
            t = Table(title=f"{mech.name}: poles at {_input_text(mech, sol, k)} "
                            f"({Status(int(sol.status[k]))})", caption=P.legend())
            for col in ("pole", "links", "from velocities", "three-pole theorem", "agree"):
                t.add_column(col)
            for pair in P:
                d = agree[pair][k]
                t.add_row(P.label(*pair), " / ".join(pair), _point_text(P[pair], k),
                          _point_text(K[pair], k), "—" if not np.isfinite(d) else f"{d:.1e}")
            tables.append(t)
        text = _render(tables)
        nl = pole_line_count(n)
        text += (f"{len(P)} poles = n(n−1)/2 with n = {n}; {nl} pole line{'s' if nl != 1 else ''} "
                 f"= n(n−1)(n−2)/6\n")
        if schedule:
            text += "\nThree-pole theorem (Aronhold–Kennedy) schedule:\n  " + "\n  ".join(sch.lines()) + "\n"
        write_output(text, output)


# ---------------------------------------------------------------------------- curvature
def _design_point(mech: Mechanism, text: str):
    if text in mech.points:
        return text
    parts = text.replace(";", ",").split(",")
    if len(parts) == 2:
        try:
            return np.array([float(parts[0]), float(parts[1])])
        except ValueError:
            pass
    raise InputError(f"--point '{text}': give a point name of '{mech.name}' "
                     f"({', '.join(mech.points)}) or design coordinates x,y")


def _curvature_command(mechanism: str, link: str, relative_to: Optional[str], points: list[str],
                       at: Optional[list[str]], fmt: Format, output: Optional[str]) -> None:
    with user_errors():
        mech = load_mechanism(mechanism)
        sol = _solve(mech, at, 3)
        ins = instant(sol, link, relative_to)
        circles = {"inflection_circle": inflection_circle(sol, link, relative_to),
                   "return_circle": return_circle(sol, link, relative_to),
                   "bresse_circle": bresse_circle(sol, link, relative_to)}
        cen = centrodes(sol, link, relative_to)
        asked = [(p, _design_point(mech, p)) for p in points]
        paths = [(p, curvature_centre(sol, link, s, relative_to)) for p, s in asked]
        rel = ins.relative_to
        u = ins.pole_velocity.xy
        b = ins.pole_acceleration.xy
        if fmt is Format.json:
            doc = {"mechanism": mech.name, "link": link, "relative_to": rel,
                   "unit": mech.length_unit, "samples": []}
            for k in range(len(sol)):
                s = {**_input_doc(sol, k), "status": str(Status(int(sol.status[k]))),
                     "omega": _num(ins.omega[k]), "alpha": _num(ins.alpha[k]),
                     "pole": _point_doc(ins.pole, k),
                     "pole_velocity": [_num(u[k, 0]), _num(u[k, 1])],
                     "pole_velocity_magnitude": _num(np.hypot(*u[k])),
                     "pole_acceleration": [_num(b[k, 0]), _num(b[k, 1])],
                     "pole_tangent": [_num(x) for x in ins.pole_tangent.xy[k]],
                     "pole_normal": [_num(x) for x in ins.pole_normal.xy[k]],
                     "inflection_pole": _point_doc(ins.inflection_pole, k),
                     "diameter": _num(ins.diameter[k]),
                     "diameter_is_infinite": bool(np.isinf(ins.diameter[k])),
                     "tangential_pole": _point_doc(ins.tangential_pole, k),
                     "acceleration_pole": _point_doc(ins.acceleration_pole, k),
                     **{name: _circle_doc(c, k) for name, c in circles.items()},
                     "fixed_centrode_radius": _num(cen.fixed_radius[k]),
                     "moving_centrode_radius": _num(cen.moving_radius[k]),
                     "curvature_centres": {
                         name: {"position": _point_doc(Point.from_xy(pc.position), k),
                                "centre": _point_doc(pc.centre, k),
                                "radius": _num(pc.radius[k])} for name, pc in paths}}
                doc["samples"].append(s)
            write_output(json.dumps(doc, indent=1) + "\n", output)
            return
        tables = []
        for k in range(len(sol)):
            t = Table(title=f"{mech.name}: {link} relative to {rel} at {_input_text(mech, sol, k)} "
                            f"({Status(int(sol.status[k]))})")
            t.add_column("quantity")
            t.add_column("value")
            rad = lambda r: "∞ (straight)" if np.isinf(r) else ("undefined" if np.isnan(r) else f"{r:.6g}")
            rows = [
                ("ω, ω̇", f"{ins.omega[k]:.6g} rad/s, {ins.alpha[k]:.6g} rad/s²"),
                ("pole P", _point_text(ins.pole, k)),
                ("pole velocity u", f"({u[k, 0]:.6g}, {u[k, 1]:.6g}), |u| = {np.hypot(*u[k]):.6g}"),
                ("acceleration of the point at P", f"({b[k, 0]:.6g}, {b[k, 1]:.6g})"),
                ("inflection pole W", _point_text(ins.inflection_pole, k)),
                ("D = u/ω", rad(ins.diameter[k])),
                ("inflection circle", _circle_text(circles["inflection_circle"], k)),
                ("return circle", _circle_text(circles["return_circle"], k)),
                ("Bresse circle", _circle_text(circles["bresse_circle"], k)),
                ("tangential pole H", _point_text(ins.tangential_pole, k)),
                ("acceleration pole Γ", _point_text(ins.acceleration_pole, k)),
                ("R′ (fixed centrode)", rad(cen.fixed_radius[k])),
                ("R (moving centrode)", rad(cen.moving_radius[k])),
            ]
            for name, pc in paths:
                rows.append((f"curvature centre of {name}",
                             f"{_point_text(pc.centre, k)}, radius {rad(pc.radius[k])}"))
            for r in rows:
                t.add_row(*r)
            tables.append(t)
        write_output(_render(tables), output)


# ---------------------------------------------------------------------------- registration
def register(app: typer.Typer) -> None:
    """Add `poles` and `curvature` to the `linkwork` application."""

    @app.command("poles")
    def poles_cmd(
        mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
        at: Optional[list[str]] = typer.Option(None, "--at", help="input values V[,V…] (degrees, the file's length unit, or a time like 0.5s); several drivers: NAME=V[,V…] per driver, as for analyze; default: the design position"),
        schedule: bool = typer.Option(False, "--schedule", help="also print the three-pole theorem schedule (P13 = P12P23 ∩ P14P34 …)"),
        fmt: Format = typer.Option(Format.table, "--format", help="table or json"),
        output: Optional[str] = typer.Option(None, "-o", "--output", help="write to this file instead of stdout"),
    ) -> None:
        """All n(n−1)/2 relative poles, from the velocities and by the three-pole theorem."""
        _poles_command(mechanism, at, schedule, fmt, output)

    @app.command("curvature")
    def curvature_cmd(
        mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
        link: str = typer.Option(..., "--link", help="the moving link"),
        relative_to: Optional[str] = typer.Option(None, "--relative-to", help="the reference link (default: the frame)"),
        point: Optional[list[str]] = typer.Option(None, "--point", help="a point name or design coordinates x,y whose path curvature centre to report (repeatable)"),
        at: Optional[list[str]] = typer.Option(None, "--at", help="input values V[,V…]; several drivers: NAME=V[,V…] per driver, as for analyze; default: the design position"),
        fmt: Format = typer.Option(Format.table, "--format", help="table or json"),
        output: Optional[str] = typer.Option(None, "-o", "--output", help="write to this file instead of stdout"),
    ) -> None:
        """Curvature theory of a link's motion: pole, inflection, return and Bresse circles, Γ,
        pole velocity, centrode radii and the curvature centres of chosen points."""
        _curvature_command(mechanism, link, relative_to, point or [], at, fmt, output)
