"""Helpers shared by the command modules: loading a mechanism, reading input values, and
turning user mistakes into one clear message with a non-zero exit status."""

from __future__ import annotations

import sys
from contextlib import contextmanager
from typing import Iterator

import numpy as np
import typer
from rich.console import Console

from ..errors import InputError, LinkworkError
from ..io import load
from ..model import Mechanism
from ..units import parse_quantity, unit_dimension

err_console = Console(stderr=True)


@contextmanager
def user_errors() -> Iterator[None]:
    """Print a `LinkworkError` as one line on stderr and exit with status 2."""
    try:
        yield
    except LinkworkError as exc:
        err_console.print(f"[bold red]error:[/] {exc}", highlight=False, soft_wrap=True)
        raise typer.Exit(2) from None


def load_mechanism(spec: str) -> Mechanism:
    return load(spec)


def _is_prismatic(mech: Mechanism) -> bool:
    return mech.joint(mech.drivers[0].joint).kind == "prismatic"


def input_value(mech: Mechanism, text: str) -> tuple[str, float]:
    """('input', value in rad or length unit) or ('time', seconds) for one value written by
    the user: degrees for a revolute driver and the file's unit for a prismatic one, unless a
    unit is written (`1.2rad`, `0.5 s`)."""
    text = text.strip()
    if not text:
        raise InputError("empty input value")
    dim = unit_dimension(text)
    if dim == "time":
        return "time", parse_quantity(text, default_unit="s", kind="time")
    if _is_prismatic(mech):
        if dim not in (None, "length"):
            raise InputError(f"'{text}': the driver is prismatic, give a length")
        return "input", parse_quantity(text, default_unit=mech.length_unit, kind="input displacement")
    if dim not in (None, "angle"):
        raise InputError(f"'{text}': the driver is revolute, give an angle (degrees by default)")
    return "input", float(np.radians(parse_quantity(text, default_unit="deg", kind="input angle")))


def input_values(mech: Mechanism, at: str | None, sweep: str | None) -> tuple[str, np.ndarray] | None:
    """The samples asked for with --at V[,V…] or --sweep START:STOP:STEP (None: whole motion)."""
    if at is not None and sweep is not None:
        raise InputError("give either --at or --sweep, not both")
    if len(mech.drivers) != 1 and (at or sweep):
        raise InputError(f"mechanism '{mech.name}' has {len(mech.drivers)} drivers; --at and "
                         "--sweep take times (e.g. --at 0.5s) for it")
    if at is not None:
        parsed = [input_value(mech, v) for v in at.split(",")]
        kinds = {k for k, _ in parsed}
        if len(kinds) > 1:
            raise InputError("--at mixes times and input values")
        return kinds.pop(), np.array([v for _, v in parsed])
    if sweep is not None:
        parts = sweep.split(":")
        if len(parts) != 3:
            raise InputError(f"--sweep '{sweep}': write START:STOP:STEP")
        parsed = [input_value(mech, p) for p in parts]
        kinds = {k for k, _ in parsed}
        if len(kinds) > 1:
            raise InputError("--sweep mixes times and input values")
        (a, b, h) = (v for _, v in parsed)
        if h == 0 or not np.isfinite(h):
            raise InputError("--sweep: the step must not be zero")
        if (b - a) * h < 0:
            raise InputError("--sweep: the step goes away from STOP")
        n = int(np.floor((b - a) / h + 1e-9)) + 1
        if n > 10_000_000:
            raise InputError(f"--sweep asks for {n} samples; at most 10 000 000")
        return kinds.pop(), a + h * np.arange(n)
    return None


def write_output(text: str, output: str | None) -> None:
    if output:
        with open(output, "w", encoding="utf-8") as fh:
            fh.write(text)
    else:
        sys.stdout.write(text)
