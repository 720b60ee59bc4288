"""`linkwork forces`: kinetostatics on the command line — driving torque or force, the
reaction of every pair, frame and shaking loads, with the power-balance check; a plot of the
driving torque and the pair forces over the motion.

The work is `linkwork.forces.kinetostatics`; the mass data and loads come from the file's
[masses] and [loads] sections (`linkwork.io.load_dynamics`).
"""

from __future__ import annotations

import io
import json
from enum import Enum
from pathlib import Path
from typing import Optional

import numpy as np
import typer
from rich.console import Console
from rich.table import Table

from ..errors import InputError
from ..forces import ForceAnalysis, kinetostatics
from ..forces.export import CONVENTION, columns, to_csv_text, to_document
from ..forces.reduced import flywheel, reduced_inertia
from ..io import load_dynamics
from ..kinematics import solve, whole_motion
from ..model import Prismatic
from .common import output_format, user_errors, write_output
from .inputs import input_speeds, input_values, show_input


class Format(str, Enum):
    table = "table"
    json = "json"
    csv = "csv"


def _effort_unit(mech, d) -> str:
    return "N" if isinstance(mech.joint(d.joint), Prismatic) else "N·m"


def _table(fa: ForceAnalysis) -> str:
    mech = fa.dynamics.mechanism
    sol = fa.solution
    out = Console(record=True, width=180, file=io.StringIO(), markup=False)
    kind = "kinetostatics" if fa.inertia else "statics (inertia off)"
    if len(fa) <= 4:
        for n in range(len(fa)):
            inp = ", ".join(f"{d.joint} {show_input(mech, d, v)}" for d, v in zip(mech.drivers, sol.inputs[n]))
            t = Table(title=f"{mech.name} — {kind} — input {inp}")
            for c in ("pair", "links (first on second)", "Fx [N]", "Fy [N]", "|F| [N]", "couple [N·m]"):
                t.add_column(c, justify="right")
            for name, r in fa.reactions.items():
                t.add_row(name, f"{r.links[0]} → {r.links[1]}", *(f"{v:.6g}" for v in (
                    r.force[n, 0], r.force[n, 1], r.magnitude[n], r.couple[n])))
            out.print(t)
            t = Table()
            t.add_column("quantity")
            t.add_column("value", justify="right")
            for d in mech.drivers:
                t.add_row(f"driver {d.joint} effort [{_effort_unit(mech, d)}]", f"{fa.efforts[d.joint][n]:.6g}")
                t.add_row(f"  by virtual work", f"{fa.virtual_work[d.joint][n]:.6g}")
            t.add_row("force on the frame [N]", f"({fa.frame_force[n, 0]:.6g}, {fa.frame_force[n, 1]:.6g})")
            t.add_row("moment on the frame about its origin [N·m]", f"{fa.frame_moment[n]:.6g}")
            if fa.shaking_force is not None:
                t.add_row("shaking force [N]", f"({fa.shaking_force[n, 0]:.6g}, {fa.shaking_force[n, 1]:.6g})")
                t.add_row("shaking moment [N·m]", f"{fa.shaking_moment[n]:.6g}")
            t.add_row("power balance residual (relative)",
                      f"{abs(fa.power_residual[n]) / fa.power_scale[n]:.2g}" if fa.power_scale[n] else "0")
            out.print(t)
    else:
        t = Table(title=f"{mech.name} — {kind}: {len(fa)} samples (forces in N)")
        for d in mech.drivers:
            t.add_column("input" if len(mech.drivers) == 1 else f"input {d.joint}", justify="right")
        for d in mech.drivers:
            t.add_column(f"{d.joint} [{_effort_unit(mech, d)}]", justify="right")
        for name in fa.reactions:
            t.add_column(f"|{name}|", justify="right")
        for n in range(len(fa)):
            row = [show_input(mech, d, v) for d, v in zip(mech.drivers, sol.inputs[n])]
            row += [f"{fa.efforts[d.joint][n]:.5g}" for d in mech.drivers]
            row += [f"{r.magnitude[n]:.5g}" for r in fa.reactions.values()]
            t.add_row(*row)
        out.print(t)
    out.print(f"sign convention: {CONVENTION}")
    ok = fa.solved
    if not ok.any():
        out.print(f"samples solved: 0 of {len(fa)} (unreachable, or at a dead centre of the force "
                  "transmission)")
    else:
        scale = np.where(fa.power_scale[ok] > 0, fa.power_scale[ok], 1.0)
        worst = float(np.max(np.abs(fa.power_residual[ok]) / scale))
        out.print(f"samples solved: {int(ok.sum())} of {len(fa)}; worst power-balance residual "
                  f"(relative): {worst:.2g}")
    return out.export_text()


def plot(fa: ForceAnalysis, path: str | Path) -> Path:
    """The driving effort and the magnitude of every pair's reaction over the motion."""
    from ..drawing.plots import _plt, save
    plt = _plt()
    mech = fa.dynamics.mechanism
    d = mech.drivers[0]
    x = fa.solution.inputs[:, 0]
    prismatic = isinstance(mech.joint(d.joint), Prismatic)
    x, label = (x, f"input {d.joint} [{mech.length_unit}]") if prismatic else \
        (np.degrees(x), f"input {d.joint} [°]")
    fig, (a1, a2) = plt.subplots(2, 1, sharex=True, figsize=(8, 7))
    for dd in mech.drivers:
        a1.plot(x, fa.efforts[dd.joint], label=f"{dd.joint} [{_effort_unit(mech, dd)}]")
    a1.set_ylabel("driving torque / force")
    a1.legend()
    a1.grid(True, alpha=0.3)
    for name, r in fa.reactions.items():
        a2.plot(x, r.magnitude, label=name)
    a2.set_ylabel("pair reaction |F| [N]")
    a2.set_xlabel(label)
    a2.legend(ncol=4, fontsize="small")
    a2.grid(True, alpha=0.3)
    fig.suptitle(f"{mech.name}: {'kinetostatics' if fa.inertia else 'statics'}")
    return save(fig, path)


def _flywheel(fa: ForceAnalysis, fluctuation: float) -> dict:
    """The flywheel for the driving torque over the whole motion, which must be one turn."""
    mech = fa.dynamics.mechanism
    d = mech.drivers[0]
    q = fa.solution.inputs[:, 0]
    w = fa.solution.pose_derivatives(d.driven)[1, :, 2]
    if isinstance(mech.joint(d.joint), Prismatic) or not np.isclose(abs(q[-1] - q[0]), 2 * np.pi):
        raise InputError("--flywheel: the driver does not turn fully (a flywheel evens out a crank's turn)")
    sign = 1.0 if q[-1] > q[0] else -1.0
    fw = flywheel(sign * q, sign * fa.effort, mean_speed=float(np.mean(np.abs(w))), fluctuation=fluctuation)
    return {"fluctuation": fluctuation, "mean_speed": float(np.mean(np.abs(w))),
            "mean_torque": sign * fw.mean_effort, "energy_fluctuation": fw.energy_fluctuation,
            "inertia": fw.inertia}


def register(app: typer.Typer) -> None:
    """Add `forces` to the `linkwork` application."""

    @app.command("forces")
    def forces_cmd(
        mechanism: str = typer.Argument(..., help="a mechanism file with its mass data and loads, or library:NAME"),
        at: Optional[list[str]] = typer.Option(None, "--at", help="input values as for `analyze --at`"),
        sweep: Optional[list[str]] = typer.Option(None, "--sweep", help="START:STOP:STEP as for `analyze --sweep`"),
        speed: Optional[list[str]] = typer.Option(None, "--speed", help="driver speed, e.g. '120 rpm' (overrides the file)"),
        static: bool = typer.Option(False, "--static", help="static equilibrium: inertia forces off (gravity and loads stay)"),
        fmt: Optional[Format] = typer.Option(None, "--format", help="table, json or csv (default: from the -o suffix, else table)"),
        output: Optional[str] = typer.Option(None, "-o", "--output", help="write to this file (.csv, .json or a table)"),
        plot_file: Optional[str] = typer.Option(None, "--plot", help="also draw the driving torque and the pair forces over the motion (.png, .pdf, .svg)"),
        fluctuation: Optional[float] = typer.Option(None, "--flywheel", help="size a flywheel for this coefficient of speed fluctuation δ (e.g. 0.02) from the driving torque over one crank turn (whole motion only)"),
    ) -> None:
        """Kinetostatics: the driving torque or force and every pair's reaction, with the
        frame's and shaking loads and the power-balance check. Without --at or --sweep, the
        whole motion."""
        with user_errors():
            dyn = load_dynamics(mechanism)
            mech = dyn.mechanism
            if mech.given:
                raise InputError(f"mechanism '{mech.name}' is driven by given point velocities: it has "
                                 "no driver whose effort the kinetostatics could balance the loads with")
            chosen = Format(output_format(fmt and fmt.value, output, ("table", "json", "csv"), "table"))
            w = input_speeds(mech, speed)
            asked = input_values(mech, at, sweep)
            if asked is None:
                if len(mech.drivers) != 1:
                    raise InputError("a mechanism with several drivers needs --at or --sweep")
                sol = whole_motion(mech, speed=None if w is None else float(w[0]))
            else:
                kind, values = asked
                if kind == "time":
                    if w is not None:
                        raise InputError("--speed sets the speed at input values; at times each "
                                         "driver's law gives it")
                    sol = solve(mech, times=values)
                else:
                    sol = solve(mech, values, velocities=None if w is None else
                                np.broadcast_to(w, values.shape).copy())
            if fluctuation is not None and asked is not None:
                raise InputError("--flywheel needs the whole motion (one crank turn): drop --at and --sweep")
            fa = kinetostatics(dyn, sol, inertia=not static)
            extra, extra_units, summary = {}, {}, {}
            if len(mech.drivers) == 1 and all(ln in dyn.masses for ln in mech.moving_links):
                red = reduced_inertia(dyn, sol.inputs[:, 0])
                extra = {"reduced_inertia": red.inertia, "reduced_inertia_derivative": red.derivative}
                # per radian of a crank, per metre of a slide (`forces.reduced`)
                J = "kg" if isinstance(mech.joint(mech.drivers[0].joint), Prismatic) else "kg*m^2"
                extra_units = {"reduced_inertia": J,
                               "reduced_inertia_derivative": J + ("/m" if J == "kg" else "")}
            if fluctuation is not None:
                summary["flywheel"] = _flywheel(fa, fluctuation)
            if chosen is Format.json:
                text = json.dumps(to_document(fa, extra, summary), indent=1) + "\n"
            elif chosen is Format.csv:
                text = to_csv_text(fa, extra, extra_units)
            else:
                text = _table(fa) + "".join(
                    f"flywheel for δ = {fw['fluctuation']:g} at {fw['mean_speed']:.6g} rad/s: mean torque "
                    f"{fw['mean_torque']:.6g} N·m, energy fluctuation {fw['energy_fluctuation']:.6g} J, "
                    f"moment of inertia {fw['inertia']:.6g} kg·m²\n" for fw in summary.values())
            write_output(text, output)
            if plot_file:
                plot(fa, plot_file)


__all__ = ["columns", "plot", "register"]
