"""Long outputs of `analyze`: their size estimated before anything is solved or written, and the
samples solved and written chunk by chunk under one progress bar (so that a million samples
take memory for one chunk, not for the whole text). Each chunk goes on from where the one
before left the path of the inputs (`solve(..., resume=)`: the branches and the continuation
of several drivers), so the chunks give what one solve of all samples gives.

Formats: `csv` (one row per sample, each header with its unit: `B.vx [mm/s]`), `jsonl` (JSON Lines: one sample object per line, the
file's length unit, radians and seconds), `json` (one document; its samples are written one
per line as they are solved) and `table` (for reading: refused above `MAX_TABLE_ROWS`).
"""

from __future__ import annotations

import json
import shutil
from contextlib import nullcontext
from pathlib import Path
from typing import Iterator

import numpy as np
from rich.console import Console
from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

from ..errors import OutputError
from ..kinematics import Solution, solve
from ..kinematics.export import csv_lines, iter_samples

#: samples solved at a time (and then written before the next chunk is solved)
CHUNK = 50_000
#: rows written per piece of CSV or JSON text
PIECE = 5_000
#: above this many samples a progress bar is shown (on stderr)
PROGRESS_SAMPLES = 50_000
#: the largest output written without --force (bytes)
MAX_OUTPUT_BYTES = 1_000_000_000
#: the longest table drawn without --force (rows): a table is for reading
MAX_TABLE_ROWS = 10_000


def _human(n: float) -> str:
    for unit in ("bytes", "kB", "MB", "GB", "TB"):
        if n < 1000 or unit == "TB":
            return f"{n:.0f} {unit}" if unit == "bytes" else f"{n:.3g} {unit}"
        n /= 1000
    return f"{n:.3g} TB"  # pragma: no cover


def _lines(sol: Solution, sep: str, first: bool) -> Iterator[str]:
    """Samples as compact JSON, one per line; `sep` before each but the very first."""
    lines: list[str] = []
    for s in iter_samples(sol):
        lines.append(("" if first else sep) + json.dumps(s))
        first = False
        if len(lines) == PIECE:
            yield "\n".join(lines) + "\n"
            lines = []
    if lines:
        yield "\n".join(lines) + "\n"


def render(sol: Solution, fmt: str, first: bool = True) -> Iterator[str]:
    """The text of `sol` in `fmt` (csv, jsonl, json) in pieces; `first`: whether this is the
    first chunk of the output (CSV header, JSON document head)."""
    if fmt == "csv":
        yield from csv_lines(sol, first, PIECE, units=True)
    elif fmt == "jsonl":
        yield from _lines(sol, "", True)
    else:
        yield from _lines(sol, ",", first)


def json_head(sol: Solution) -> str:
    mech = sol.mechanism
    head = {"mechanism": mech.name, "units": {"length": mech.length_unit, "angle": "rad", "time": "s"},
            "drivers": [d.joint for d in mech.drivers]}
    return json.dumps(head)[:-1] + ', "samples": [\n'


JSON_TAIL = "]}\n"


def estimate_bytes(mech, fmt: str, n: int) -> int:
    """The size of `n` samples in `fmt` (csv, jsonl, json), from one sample at the design
    position (NaN samples write shorter, so this is an upper estimate for them)."""
    one = solve(mech)
    body = "".join(render(one, fmt, first=False)).encode()
    head = "".join(render(one, fmt, first=True)).encode()
    return len(head) - len(body) + len(body) * n + (len(json_head(one)) + len(JSON_TAIL) if fmt == "json" else 0)


def check_size(mech, fmt: str, n: int, output: str | None, force: bool) -> None:
    """Refuse (unless `force`) an output that would be larger than MAX_OUTPUT_BYTES, a table
    longer than MAX_TABLE_ROWS, or a file larger than the free space of its disk."""
    if force:
        return
    if fmt == "table" and n > MAX_TABLE_ROWS:
        raise OutputError(f"a table of {n} samples is too long to read (at most {MAX_TABLE_ROWS} "
                          "rows): write --format csv or jsonl, fewer samples, or give --force")
    if fmt == "table":
        return
    size = estimate_bytes(mech, fmt, n)
    if size > MAX_OUTPUT_BYTES:
        raise OutputError(f"the output would be about {_human(size)} ({n} samples of about "
                          f"{_human(size / max(n, 1))}), more than {_human(MAX_OUTPUT_BYTES)}: ask "
                          "for fewer samples (a larger step), write --format csv (the smallest), "
                          "or give --force")
    if output:
        folder = Path(output).parent
        try:
            free = shutil.disk_usage(folder if folder.is_dir() else ".").free
        except OSError:
            return
        if size > free:
            raise OutputError(f"cannot write '{output}': it would take about {_human(size)}, and "
                              f"its disk has {_human(free)} free (give --force to try anyway)")


def progress(n: int):
    """A Rich progress bar on stderr over solving and writing `n` samples (twice n steps), or
    a context doing nothing for short runs."""
    if n < PROGRESS_SAMPLES:
        return nullcontext(None)
    return Progress(TextColumn("{task.description}"), BarColumn(), TextColumn("{task.percentage:>3.0f}%"),
                    TimeRemainingColumn(), console=Console(stderr=True), transient=True,
                    redirect_stdout=False, redirect_stderr=False)  # stdout is the output


def stream(mech, kind: str, values: np.ndarray, speeds: np.ndarray | None, fmt: str,
           bar: Progress | None) -> Iterator[str]:
    """Solve `values` (times (N,) or inputs (N, drivers)) chunk by chunk and yield the text in
    `fmt` (csv, jsonl, json); `bar` advances by one per sample solved and one per sample
    written."""
    n = len(values)
    task = bar.add_task("solving and writing", total=2 * n) if bar is not None else None

    def one(v: np.ndarray, resume) -> Solution:
        if kind == "time":
            return solve(mech, times=v, resume=resume)
        vel = None if speeds is None else np.broadcast_to(speeds, v.shape).copy()
        return solve(mech, v, velocities=vel, resume=resume)

    end = None  # each chunk goes on where the one before left the path (several drivers)
    for i in range(0, n, CHUNK):
        sol = one(values[i:i + CHUNK], end)
        end = sol.path_end
        if bar is not None:
            bar.advance(task, len(sol))
        if i == 0 and fmt == "json":
            yield json_head(sol)
        for piece in render(sol, fmt, first=i == 0):
            yield piece
        if bar is not None:
            bar.advance(task, len(sol))
    if fmt == "json":
        yield JSON_TAIL


def whole(sol: Solution, fmt: str) -> Iterator[str]:
    """The text of a solution computed in one piece (the whole motion)."""
    if fmt == "json":
        yield json_head(sol)
    yield from render(sol, fmt)
    if fmt == "json":
        yield JSON_TAIL
