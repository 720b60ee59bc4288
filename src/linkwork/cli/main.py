"""`linkwork` commands of the core engine (analyze, library, schema) and the registry of the
other layers' command modules: every module `linkwork.cli.*_cmd` with a `register(app)` adds
its commands, so a layer brings its own commands without editing this file."""

from __future__ import annotations

import importlib
import json
import pkgutil
from enum import Enum
from typing import Optional

import numpy as np
import typer
from rich.console import Console
from rich.markup import escape
from rich.progress import Progress
from rich.table import Table

from ..io.files import library_names, resolve
from ..io.schema import MechanismFile
from ..kinematics import Solution, Status, solve, whole_motion
from ..units import parse_quantity
from .common import input_values, load_mechanism, user_errors, write_output

app = typer.Typer(add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
                  help="Kinematics of planar mechanisms: exact solutions, poles and curvature, "
                       "structure, and the classical constructions.")
console = Console()

CHUNK = 50_000  # samples per solve call when a progress bar is shown


class Format(str, Enum):
    table = "table"
    json = "json"
    csv = "csv"


def _solve_with_progress(mech, kind: str, values: np.ndarray, speed: float | None) -> Solution:
    """Solve in chunks under a Rich progress bar when there are many samples."""
    def one(v):
        if kind == "time":
            return solve(mech, times=v)
        vel = None if speed is None else np.full(v.shape, speed)
        return solve(mech, v, velocities=vel)

    if values.size <= CHUNK:
        return one(values)
    parts = []
    with Progress(console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task("solving", total=values.size)
        for i in range(0, values.size, CHUNK):
            parts.append(one(values[i:i + CHUNK]))
            bar.advance(task, min(CHUNK, values.size - i))
    return _concat(parts)


def _concat(parts: list[Solution]) -> Solution:
    first = parts[0]
    from math import factorial
    D = np.concatenate([p._D for p in parts], axis=1)
    coeff = D / np.array([factorial(k) for k in range(D.shape[0])])[:, None, None, None]
    time = None if first.time is None else np.concatenate([p.time for p in parts])
    return Solution(first.mechanism, np.concatenate([p.inputs for p in parts]), time, coeff,
                    np.concatenate([p.status for p in parts]),
                    np.concatenate([p.condition for p in parts]))


def _table(sol: Solution) -> str:
    mech = sol.mechanism
    out = Console(record=True, width=160, file=open("/dev/null", "w"))
    unit = mech.length_unit
    prismatic = mech.joint(mech.drivers[0].joint).kind == "prismatic"
    show = (lambda v: f"{v:.4g} {unit}") if prismatic else (lambda v: f"{np.degrees(v):.3f}°")
    if len(sol) <= 4:
        for n in range(len(sol)):
            inp = ", ".join(show(v) for v in sol.inputs[n])
            t = Table(title=f"{mech.name} — input {inp} — {Status(int(sol.status[n]))}, "
                            f"condition {sol.condition[n]:.3g}")
            for c in ("point", f"x [{unit}]", "y", f"vx [{unit}/s]", "vy", f"ax [{unit}/s²]", "ay"):
                t.add_column(escape(c), justify="right")
            for p in mech.points:
                m = sol.point(p)
                t.add_row(p, *(f"{v:.6g}" for v in (*m.position[n], *m.velocity[n], *m.acceleration[n])))
            out.print(t)
            t = Table()
            for c in ("link", "angle [°]", "ω [rad/s]", "α [rad/s²]"):
                t.add_column(escape(c), justify="right")
            for ln in mech.moving_links:
                m = sol.link(ln)
                t.add_row(ln, f"{np.degrees(m.angle[n]):.4f}", f"{m.omega[n]:.6g}", f"{m.alpha[n]:.6g}")
            out.print(t)
    else:
        t = Table(title=f"{mech.name}: {len(sol)} samples (ω in rad/s, α in rad/s²)")
        t.add_column("input", justify="right")
        t.add_column("status")
        for ln in mech.moving_links:
            t.add_column(f"ω {ln}", justify="right")
            t.add_column(f"α {ln}", justify="right")
        links = {ln: sol.link(ln) for ln in mech.moving_links}
        for n in range(len(sol)):
            row = [show(sol.inputs[n, 0]), str(Status(int(sol.status[n])))]
            for m in links.values():
                row += [f"{m.omega[n]:.5g}", f"{m.alpha[n]:.5g}"]
            t.add_row(*row)
        out.print(t)
    return out.export_text()


@app.command()
def analyze(
    mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
    at: Optional[str] = typer.Option(None, "--at", help="input values V[,V…]: degrees (revolute) or the file's length unit (prismatic) unless a unit is written, e.g. 1.2rad or 0.5s"),
    sweep: Optional[str] = typer.Option(None, "--sweep", help="START:STOP:STEP in the same units"),
    speed: Optional[str] = typer.Option(None, "--speed", help="driver speed, e.g. '120 rpm' (overrides the file)"),
    fmt: Format = typer.Option(Format.table, "--format", help="table, json or csv"),
    output: Optional[str] = typer.Option(None, "-o", "--output", help="write to this file instead of stdout"),
) -> None:
    """Positions, velocities and accelerations of every point, link and pair.

    Without --at or --sweep, the whole motion: one turn of a crank, or back and forth between
    the limit positions of a rocker or slider.
    """
    with user_errors():
        mech = load_mechanism(mechanism)
        w = None
        if speed is not None:
            prism = mech.joint(mech.drivers[0].joint).kind == "prismatic"
            w = parse_quantity(speed, default_unit=f"{mech.length_unit}/s" if prism else "rad/s",
                               kind="speed")
        asked = input_values(mech, at, sweep)
        sol = whole_motion(mech, speed=w) if asked is None else _solve_with_progress(mech, *asked, w)
        if fmt is Format.json:
            text = json.dumps(sol.to_document(), indent=1) + "\n"
        elif fmt is Format.csv:
            text = sol.to_pandas().to_csv(index=False)
        else:
            text = _table(sol)
        write_output(text, output)


@app.command()
def library(name: Optional[str] = typer.Argument(None, help="print this mechanism's file")) -> None:
    """List the shipped mechanisms, or print one of them (load it as library:NAME)."""
    with user_errors():
        if name:
            write_output(resolve(f"library:{name}")[1], None)
            return
        t = Table(title="linkwork library (use as library:NAME)")
        t.add_column("name")
        t.add_column("mechanism")
        import tomllib
        for n in library_names():
            doc = tomllib.loads(resolve(f"library:{n}")[1])
            t.add_row(n, doc.get("name", ""))
        console.print(t)


@app.command()
def schema() -> None:
    """Print the JSON schema of mechanism files."""
    write_output(json.dumps(MechanismFile.model_json_schema(), indent=2) + "\n", None)


def _register_layers() -> None:
    from .. import cli as pkg
    for mod in pkgutil.iter_modules(pkg.__path__):
        if mod.name.endswith("_cmd"):
            importlib.import_module(f"{pkg.__name__}.{mod.name}").register(app)


_register_layers()
