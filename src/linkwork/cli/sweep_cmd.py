"""`linkwork sweep`: a design sweep on the command line (the work is `linkwork.sweeps`).

Designs come from a grid (`--vary NAME=START:STOP:STEP`, every combination) or a random sample
(`--samples N --vary NAME=LOW:HIGH`); each is solved over its whole motion (or `--inputs`) on all
cores (or on a Dask cluster, `--scheduler`), reduced to the `--metric`s, and written to CSV or Parquet (`-o`, by the suffix, units in
the header or the metadata) or shown as a table. With `-o`, finished designs are kept in
FILE.resume.jsonl until the file is written, so that running the same command again after an
interruption goes on where it stopped.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Optional

import numpy as np
import typer
from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn
from rich.table import Table

from ..errors import InputError
from .common import user_errors


def _inputs(text: str | None, mech) -> np.ndarray | None:
    if text is None:
        return None
    try:
        start, stop, step = (float(x) for x in text.split(":"))
    except ValueError:
        raise InputError(f"--inputs {text}: write START:STOP:STEP (degrees, or the length unit "
                         "for a prismatic driver)") from None
    if step == 0 or (stop - start) * step < 0:
        raise InputError(f"--inputs {text}: the step does not lead from START to STOP")
    v = start + step * np.arange(int(math.floor((stop - start) / step + 1e-9)) + 1)
    prismatic = mech.joint(mech.drivers[0].joint).kind == "prismatic"
    return v if prismatic else np.radians(v)


def register(app: typer.Typer) -> None:
    """Add `sweep` to the `linkwork` application."""

    @app.command("sweep")
    def sweep_cmd(
        mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
        vary: list[str] = typer.Option(..., "--vary", help="NAME=START:STOP:STEP (grid) or, with --samples, "
                                       "NAME=LOW:HIGH; NAME is a point coordinate P.x, P.y or a distance A-B "
                                       "(B moves along the line from A)"),
        metric: list[str] = typer.Option(..., "--metric", help="grashof, transmission-min:JOINT, "
                                         "transmission-max:JOINT, input-range, stroke:P, time-ratio:P, "
                                         "straightness:P, circularity:P, max-speed:P, max-acceleration:P, or "
                                         "P.{x,y,vx,vy,ax,ay,speed,acceleration}:{min,max,range,rms}, "
                                         "LINK.{angle,omega,alpha}:{min,max,range,rms}"),
        samples: Optional[int] = typer.Option(None, "--samples", help="a random sample of N designs instead of a grid"),
        seed: int = typer.Option(0, "--seed", help="seed of the random sample"),
        inputs: Optional[str] = typer.Option(None, "--inputs", help="START:STOP:STEP of the driver instead of the "
                                             "whole motion (degrees or the length unit)"),
        workers: Optional[int] = typer.Option(None, "--workers", help="processes (default: all cores)"),
        scheduler: Optional[str] = typer.Option(None, "--scheduler", help="address of an existing Dask "
                                                "cluster's scheduler (tcp://HOST:8786) to run the designs on"),
        output: Optional[str] = typer.Option(None, "-o", "--output", help="FILE.csv or FILE.parquet"),
    ) -> None:
        """Vary a mechanism's dimensions and tabulate metrics of each design's motion."""
        with user_errors():
            from .. import sweeps
            from ..io.files import load
            if output and Path(output).suffix.lower() not in (".csv", ".parquet", ".pq"):
                raise InputError(f"-o {output}: write .csv or .parquet")
            if workers is not None and workers < 1:
                raise InputError(f"--workers {workers}: give at least 1")
            mech = load(mechanism)
            plan = sweeps.plan(mechanism, vary, metric, samples=samples, seed=seed,
                               inputs=_inputs(inputs, mech))
            resume = Path(output).with_name(Path(output).name + ".resume.jsonl") if output else None
            with Progress(TextColumn("sweep"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                          console=Console(stderr=True), transient=True) as bar:
                task = bar.add_task("designs", total=len(plan.designs))
                rows = sweeps.execute(plan, workers=workers, resume=resume, scheduler=scheduler,
                                      progress=lambda done, n: bar.update(task, completed=done))
            if output:
                sweeps.write(plan, rows, output)
                resume.unlink(missing_ok=True)
                typer.echo(f"wrote {output}: {len(rows)} designs", err=True)
                return
            units = plan.units()
            t = Table(title=f"{mech.name}: {len(rows)} designs")
            for c in plan.columns:
                t.add_column(escape(f"{c} [{units[c]}]" if units.get(c) else c), justify="right")
            for r in rows:
                t.add_row(*(f"{v:.6g}" if isinstance(v, float) else escape(str(v)) for v in r))
            Console().print(t)
