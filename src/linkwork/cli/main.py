"""`linkwork` commands of the core engine (analyze, library, schema) and the registry of the
other layers' command modules: every module `linkwork.cli.*_cmd` with a `register(app)` adds
its commands, so a layer brings its own commands without editing this file.

Why the imports sit inside the commands: a command pays only for the machinery it uses
(`linkwork library` needs neither NumPy nor the solver). Registering every command module
must therefore stay cheap: at module level a command module imports the standard library,
Typer, Rich and `cli.common` only (tests/cli/test_startup.py checks it)."""

from __future__ import annotations

import importlib
import pkgutil
from enum import Enum
from typing import TYPE_CHECKING, Optional

import typer
from rich.console import Console
from rich.table import Table

from .common import output_format, recording_console, user_errors, write_output

if TYPE_CHECKING:
    from ..kinematics import Solution

app = typer.Typer(add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
                  help="Kinematics of planar mechanisms: exact solutions, poles and curvature, "
                       "structure, and the classical constructions.")
console = Console()


class Format(str, Enum):
    table = "table"
    json = "json"
    jsonl = "jsonl"
    csv = "csv"


def _table(sol: Solution) -> str:
    import numpy as np

    from ..kinematics import Status
    from .inputs import show_input

    mech = sol.mechanism
    # markup off: names from the file ("[A]", "x [mm]") are text
    out = recording_console(160, markup=False)
    unit = mech.length_unit
    single = len(mech.drivers) == 1

    def inputs(n: int) -> str:
        if single:
            return show_input(mech, mech.drivers[0], sol.inputs[n, 0])
        return ", ".join(f"{d.joint} {show_input(mech, d, v)}" for d, v in zip(mech.drivers, sol.inputs[n]))

    none = np.full((len(sol), 2), np.nan)  # accelerations not solved (given point velocities only)
    if len(sol) <= 4:
        for n in range(len(sol)):
            inp = "the drawn position (given point velocities)" if mech.given else inputs(n)
            t = Table(title=f"{mech.name} — input {inp} — {Status(int(sol.status[n]))}, "
                            f"condition {sol.condition[n]:.3g}")
            for c in ("point", f"x [{unit}]", "y", f"vx [{unit}/s]", "vy", f"ax [{unit}/s²]", "ay"):
                t.add_column(c, justify="right")
            for p in mech.points:
                m = sol.point(p)
                acc = none if m.acceleration is None else m.acceleration
                t.add_row(p, *(f"{v:.6g}" for v in (*m.position[n], *m.velocity[n], *acc[n])))
            out.print(t)
            t = Table()
            for c in ("link", "angle [°]", "ω [rad/s]", "α [rad/s²]"):
                t.add_column(c, justify="right")
            for ln in mech.moving_links:
                m = sol.link(ln)
                t.add_row(ln, f"{np.degrees(m.angle[n]):.4f}", f"{m.omega[n]:.6g}",
                          "—" if m.alpha is None else f"{m.alpha[n]:.6g}")
            out.print(t)
    else:
        head = [("input" if single else f"input {d.joint}") for d in mech.drivers] + ["status"]
        for ln in mech.moving_links:
            head += [f"ω {ln}", f"α {ln}"]
        links = [sol.link(ln) for ln in mech.moving_links]
        rows = []
        for n in range(len(sol)):
            row = [show_input(mech, d, v) for d, v in zip(mech.drivers, sol.inputs[n])]
            row.append(str(Status(int(sol.status[n]))))
            for m in links:
                row += [f"{m.omega[n]:.5g}", f"{m.alpha[n]:.5g}"]
            rows.append(row)
        out.print(_columns(f"{mech.name}: {len(sol)} samples (ω in rad/s, α in rad/s²)", head, rows),
                  highlight=False, soft_wrap=True)
    _engagement_tables(out, sol)
    return out.export_text()


def _columns(title: str, head: list[str], rows: list[list[str]]) -> str:
    """A long table as plain right-aligned columns (one line per sample, never wrapped): Rich
    lays out a table cell by cell, some seconds for a whole motion of a six-bar."""
    from rich.cells import cell_len

    widths = [max(cell_len(r[c]) for r in (head, *rows)) for c in range(len(head))]

    def line(cells: list[str]) -> str:
        return "  ".join(" " * (w - cell_len(x)) + x for x, w in zip(cells, widths))

    top = line(head)
    return "\n".join([title, top, "─" * cell_len(top), *map(line, rows)])


def _engagement_tables(out: Console, sol: Solution) -> None:
    """Per Geneva or star-wheel pair: the phase boundaries the motion passes, with the wheel's
    one-sided velocities and accelerations (at the driver's constant speed)."""
    import numpy as np

    from ..kinematics.intermittent import engagement
    from ..model import is_intermittent

    for j in sol.mechanism.joints:
        if not is_intermittent(j):
            continue
        e = engagement(sol, j.name)
        t = Table(title=f"{j.kind} pair {j.name}: the wheel advances {np.degrees(e.advance):.4g}° "
                        f"per driver turn and rests {100 * e.dwell_fraction:.4g}% of it")
        for c in ("boundary", "input [°]", "phases", "slot", "ω left", "ω right", "α left", "α right"):
            t.add_column(c, justify="right")
        for ev in e.events:
            t.add_row(ev.kind, f"{np.degrees(ev.input):.4f}", f"{ev.before} → {ev.after}",
                      str(ev.slot), *(f"{v + 0.0:.6g}" for v in (*ev.omega, *ev.alpha)))
        out.print(t)


@app.command()
def analyze(
    mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
    at: Optional[list[str]] = typer.Option(None, "--at", help="input values V[,V…]: degrees (revolute) or the file's length unit (prismatic) unless a unit is written, e.g. 1.2rad, or times (0.5s). Several drivers: NAME=V[,V…] for each driver (repeat --at or separate by commas), e.g. --at O2=30,60 --at O5=10,20; the drivers move in lock-step, a driver with one value is held at it"),
    sweep: Optional[list[str]] = typer.Option(None, "--sweep", help="START:STOP:STEP in the same units. Several drivers: NAME=START:STOP:STEP per driver (repeat --sweep; may be combined with --at NAME=V to hold a driver), lock-step: equal numbers of samples"),
    speed: Optional[list[str]] = typer.Option(None, "--speed", help="driver speed, e.g. '120 rpm' (overrides the file). Several drivers: NAME=Q per driver; the others keep the file's"),
    fmt: Optional[Format] = typer.Option(None, "--format", help="table, json, jsonl (JSON Lines: one sample per line) or csv; default: from the suffix of -o (.csv, .json, .jsonl, .parquet), else table"),
    output: Optional[str] = typer.Option(None, "-o", "--output", help="write to this file instead of stdout (all or nothing: the file appears when complete); .parquet writes Parquet; CSV headers and Parquet's metadata carry the units"),
    force: bool = typer.Option(False, "--force", help="write outputs above the size limit (1 GB, or a table of 10 000 rows)"),
) -> None:
    """Positions, velocities and accelerations of every point, link and pair.

    Without --at or --sweep, the whole motion: one turn of a crank, or back and forth between
    the limit positions of a rocker or slider.
    """
    import numpy as np

    from ..errors import InputError
    from ..kinematics import solve, solve_at, whole_motion
    from . import streams
    from .common import load_mechanism
    from .inputs import input_speeds, input_values

    with user_errors():
        chosen = output_format(fmt and fmt.value, output, ("table", "json", "jsonl", "csv", "parquet"), "table")
        parquet = chosen == "parquet"
        fmt = Format.table if parquet else Format(chosen)
        mech = load_mechanism(mechanism)
        if mech.given:  # driven by given point velocities: its drawn position only
            sol = solve_at(mech, at or sweep or speed or None,
                           asked="--at, --sweep or --speed")
            if parquet:
                return sol.to_parquet(output)
            write_output(_table(sol) if fmt is Format.table else streams.whole(sol, fmt.value), output)
            return
        w = input_speeds(mech, speed)
        asked = input_values(mech, at, sweep)
        if w is not None and asked is not None and asked[0] == "time":
            raise InputError("--speed sets the input speed at input values; at times each "
                             "driver's law gives its speed (drop --speed or give input values)")
        if asked is None:
            if w is not None and len(mech.drivers) != 1:
                raise InputError("--speed with several drivers needs --at or --sweep: the whole "
                                 "motion follows the drivers' time laws")
            sol = whole_motion(mech, speed=None if w is None else float(w[0]))
            if parquet:
                return sol.to_parquet(output)
            streams.check_size(mech, fmt.value, len(sol), output, force)
            write_output(_table(sol) if fmt is Format.table else streams.whole(sol, fmt.value), output)
            return
        kind, values = asked
        if parquet:
            sol = solve(mech, times=values) if kind == "time" else solve(
                mech, values, velocities=None if w is None else np.broadcast_to(w, values.shape).copy())
            return sol.to_parquet(output)
        streams.check_size(mech, fmt.value, len(values), output, force)
        if fmt is Format.table:
            sol = solve(mech, times=values) if kind == "time" else solve(
                mech, values, velocities=None if w is None else np.broadcast_to(w, values.shape).copy())
            write_output(_table(sol), output)
            return
        with streams.progress(len(values)) as bar:
            write_output(streams.stream(mech, kind, values, w, fmt.value, bar), output)


@app.command()
def library(name: Optional[str] = typer.Argument(None, help="print this mechanism's file"),
            search: Optional[str] = typer.Option(None, "--search", "-s",
                                                 help="only mechanisms whose name or description contain these words"),
            category: Optional[str] = typer.Option(None, "--category", "-c",
                                                   help="only this group (four-bars, slider mechanisms, valve gears, "
                                                        "straight-line linkages, governors, cams, gears, ...)"),
            fmt: str = typer.Option("table", "--format", help="table or json")) -> None:
    """List the shipped mechanisms by group, search them, or print one (load it as library:NAME)."""
    import json

    from ..errors import InputError
    from ..io.library import library_entries, library_text, search_library

    with user_errors():
        if name:
            write_output(library_text(name), None)
            return
        if fmt not in ("table", "json"):
            raise InputError(f"--format must be table or json, not '{fmt}'")
        hits = search_library(search, category)
        if category and not hits and not search_library(None, category):
            groups = sorted({e["category"] for e in library_entries()})
            raise InputError(f"the library has no group '{category}' (groups: {', '.join(groups)})")
        if fmt == "json":
            write_output(json.dumps(hits, indent=2, ensure_ascii=False) + "\n", None)
            return
        if not hits:
            console.print(f"no library mechanism matches '{search}'" + (f" in '{category}'" if category else ""))
            raise typer.Exit(1)
        t = Table(title="linkwork library (use as library:NAME)")
        t.add_column("group")
        t.add_column("name")
        t.add_column("mechanism")
        last = None
        for e in hits:
            t.add_row(e["category"] if e["category"] != last else "", e["name"], e["title"],
                      end_section=False)
            last = e["category"]
        console.print(t)
        console.print(f"{len(hits)} mechanisms")


@app.command()
def schema() -> None:
    """Print the JSON schema of mechanism files."""
    import json

    from ..io.schema import MechanismFile

    write_output(json.dumps(MechanismFile.model_json_schema(), indent=2) + "\n", None)


#: the commands this module defines: they need no other command module loaded
CORE_COMMANDS = frozenset({"analyze", "library", "schema"})


def register_layers(target: typer.Typer) -> None:
    """Add the commands of every `linkwork.cli.*_cmd` module (each has `register(app)`)."""
    from .. import cli as pkg
    for mod in pkgutil.iter_modules(pkg.__path__):
        if mod.name.endswith("_cmd"):
            importlib.import_module(f"{pkg.__name__}.{mod.name}").register(target)
