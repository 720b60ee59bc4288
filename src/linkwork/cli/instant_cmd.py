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
from rich.table import Table

from ..errors import InputError
from ..geometry import Circle, Point
from ..instant.export import (circle_doc as _circle_doc, curvature_document, curvature_report,
                              point_doc as _point_doc, poles_document)
from ..instant import (agreement, kennedy_poles, pole_line_count, pole_schedule,
                       poles)
from ..kinematics import Solution, Status, solve, solve_at
from ..model import Mechanism
from .common import load_mechanism, output_format, recording_console, user_errors, write_output
from .inputs import input_values


class Format(str, Enum):
    table = "table"
    json = "json"


# ---------------------------------------------------------------------------- helpers
def _point_text(p: Point, n: int) -> str:
    doc = _point_doc(p, n)
    if doc is None:
        return "undefined"
    if doc.get("at_infinity"):
        dx, dy = doc["direction"]
        return f"at infinity, direction {math.degrees(math.atan2(dy, dx)) % 180:.3f}°"
    return f"({doc['x'] + 0.0:.6g}, {doc['y'] + 0.0:.6g})"


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
    if mech.given:  # driven by given point velocities: at its drawn position only
        return solve_at(mech, at or None, order=order, asked="--at")
    asked = input_values(mech, at, None)
    if asked is None:
        return solve(mech, order=order)
    kind, values = asked
    return solve(mech, times=values, order=order) if kind == "time" else solve(mech, values, order=order)


def _input_text(mech: Mechanism, sol: Solution, n: int) -> str:
    if sol.time is not None:
        return f"t = {sol.time[n]:.6g} s"
    if mech.given:
        return "the drawn position (given point velocities)"
    def one(d, v) -> str:
        prismatic = mech.joint(d.joint).kind == "prismatic"
        return f"{v:.6g} {mech.length_unit}" if prismatic else f"{math.degrees(v):.6g}°"

    if len(mech.drivers) == 1:
        return one(mech.drivers[0], sol.inputs[n, 0])
    return ", ".join(f"{d.joint} {one(d, v)}" for d, v in zip(mech.drivers, sol.inputs[n]))


def _render(tables: list) -> str:
    con = recording_console(150, markup=False)
    for t in tables:
        con.print(t)
    return con.export_text()


# ---------------------------------------------------------------------------- poles
def _poles_command(mechanism: str, at: Optional[list[str]], schedule: bool, fmt: Format | None,
                   output: Optional[str]) -> None:
    with user_errors():
        fmt = Format(output_format(fmt and fmt.value, output, ("table", "json"), "table"))
        mech = load_mechanism(mechanism)
        sol = _solve(mech, at, 1)
        if fmt is Format.json:
            write_output(json.dumps(poles_document(sol, schedule), indent=1) + "\n", output)
            return
        P = poles(sol)
        sch = pole_schedule(mech)
        K = kennedy_poles(sol, sch)
        agree = agreement(P, K, mech.length_scale)
        n = len(mech.links)
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
                       at: Optional[list[str]], fmt: Format | None, output: Optional[str]) -> None:
    with user_errors():
        fmt = Format(output_format(fmt and fmt.value, output, ("table", "json"), "table"))
        mech = load_mechanism(mechanism)
        sol = _solve(mech, at, 3)
        asked = [(p, _design_point(mech, p)) for p in points]
        if fmt is Format.json:
            write_output(json.dumps(curvature_document(sol, link, relative_to, asked), indent=1) + "\n", output)
            return
        rep = curvature_report(sol, link, relative_to, asked)
        ins, circles, cen, paths = rep.instant, rep.circles, rep.centrodes, rep.paths
        rel = ins.relative_to
        u = ins.pole_velocity.xy
        b = ins.pole_acceleration.xy
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
        fmt: Optional[Format] = typer.Option(None, "--format", help="table or json (default: from the suffix of -o, else table)"),
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
        fmt: Optional[Format] = typer.Option(None, "--format", help="table or json (default: from the suffix of -o, else table)"),
        output: Optional[str] = typer.Option(None, "-o", "--output", help="write to this file instead of stdout"),
    ) -> None:
        """Curvature theory of a link's motion: pole, inflection, return and Bresse circles, Γ,
        pole velocity, centrode radii and the curvature centres of chosen points."""
        _curvature_command(mechanism, link, relative_to, point or [], at, fmt, output)
