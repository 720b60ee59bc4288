"""Running a sweep: every design of a grid or a random sample solved over its motion (the whole
motion, or given inputs), its metrics computed; designs are spread in chunks over worker
processes here or over the workers of an existing Dask cluster (`scheduler`), and finished
chunks are kept in a side file so that an interrupted sweep resumes.

Workers receive the mechanism file's text, not its path, so that a cluster's machines need
only linkwork installed (profiles read from CSV files must be beside the file on them too).
"""

from __future__ import annotations

import json
import math
import os
from contextlib import nullcontext
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Callable

import numpy as np

from ..errors import InputError, LinkworkError
from ..io.files import load, load_text, resolve
from ..kinematics import kernels, solve, whole_motion
from ..kinematics.designs import solve_designs, whole_motions
from ..kinematics.export import with_unit
from ..kinematics.warmup import loaded_compiled_loops
from ..model import Mechanism
from . import designs as D
from .metrics import Metric, evaluate, evaluate_designs, parse_metric


#: designs per process from which a sweep loads the kinematics' compiled loops first: about a
#: second (CPU) of loading against some 60 ms a four-bar design saves (2 ms instead of 60)
COMPILED_FROM = 40
#: least designs per chunk on a Dask cluster (unless the sweep has fewer): a chunk is one batch
#: (`run_designs`), and a task's own cost (some milliseconds) wants several designs
DASK_CHUNK = 16


@dataclass
class SweepPlan:
    """What to sweep: the mechanism (a path or library:NAME, so that workers load it
    themselves), its parameters and designs (rows), the metrics, and the inputs (None: the
    whole motion of each design)."""

    spec: str
    params: list[D.Parameter]
    designs: np.ndarray
    metrics: list[Metric]
    inputs: np.ndarray | None = None
    mechanism: Mechanism | None = field(default=None, repr=False)
    text: str = field(default="", repr=False)
    base_dir: str | None = None

    @property
    def columns(self) -> list[str]:
        return [p.name for p in self.params] + [m.name for m in self.metrics] + ["ok", "status"]

    def units(self) -> dict[str, str]:
        u = self.mechanism.length_unit
        return {**{p.name: u for p in self.params}, **{m.name: m.unit_in(u) for m in self.metrics},
                "ok": "fraction of samples"}


def plan(spec: str, vary: list[str], metrics: list[str], *, samples: int | None = None,
         seed: int = 0, inputs: np.ndarray | None = None) -> SweepPlan:
    """Parse a sweep's arguments: `vary` as NAME=START:STOP:STEP (a grid of every combination)
    or, with `samples`, NAME=LOW:HIGH (a uniform random sample of that many designs)."""
    import tomllib
    mech = load(spec)
    named = tomllib.loads(resolve(spec)[1]).get("parameters", {})
    if not vary:
        raise InputError("give at least one --vary NAME=… (a point coordinate P.x, P.y or a distance A-B)")
    if not metrics:
        raise InputError("give at least one --metric (see `linkwork sweep --help`)")
    if samples is None:
        axes = [D.grid_values(v) for v in vary]
        params = [D.parameter(mech, n, named) for n, _ in axes]
        rows = D.grid([vals for _, vals in axes])
    else:
        ranges = [D.random_range(v) for v in vary]
        params = [D.parameter(mech, n, named) for n, *_ in ranges]
        rows = D.random_designs([r[1] for r in ranges], [r[2] for r in ranges], samples, seed)
    names = [p.name for p in params]
    if len(set(names)) != len(names):
        raise InputError(f"--vary names a parameter twice: {', '.join(n for n in names if names.count(n) > 1)}")
    if len(rows) > 10_000_000:
        raise InputError(f"the sweep has {len(rows)} designs; at most 10 000 000")
    if len(mech.drivers) != 1 and inputs is not None:
        raise InputError("--inputs takes one driver's values; this mechanism has several drivers")
    base = None if spec.startswith("library:") else str(Path(spec).resolve().parent)
    return SweepPlan(spec, params, rows, [parse_metric(mech, m) for m in metrics], inputs, mech,
                     resolve(spec)[1], base)


@lru_cache(maxsize=4)
def _load(spec: str, text: str, base_dir: str | None) -> Mechanism:
    return load_text(text, source=spec, base_dir=None if base_dir is None else Path(base_dir))


def run_designs(spec: str, params: list[D.Parameter], rows: np.ndarray, metrics: list[Metric],
                inputs: np.ndarray | None, text: str = "", base_dir: str | None = None,
                compiled: bool = False, batch: bool = True) -> list[list]:
    """Rows of [metric values…, ok fraction, status] for the designs `rows` (one process) of
    the mechanism `text` (read from `spec` if empty): all designs solved in one batch
    (`kinematics.designs`: their whole motions, or `inputs`) and their metrics reduced over
    arrays of designs × samples; `batch=False` solves and reduces them one by one (the same
    rows, to rounding: the reference the tests and bench/bench_sweep.py hold the batch to).
    `compiled`: this process solves enough designs to load the compiled loops first
    (`warmup.compile_kernels`, once per process); else the loops run interpreted."""
    with loaded_compiled_loops() if compiled else kernels.compiled_loops(False):
        rows_of = _rows if batch else _rows_one_by_one
        return rows_of(spec, params, rows, metrics, inputs, text, base_dir, compiled)


def _failed(metrics: list[Metric], exc: LinkworkError) -> list:
    """The row of a design that cannot be built or solved: marked, not fatal."""
    return ([math.nan if m.kind != "grashof" else "" for m in metrics]
            + [0.0, f"error: {str(exc).splitlines()[0]}"])


def _finished(sol, values: list) -> list:
    ok = float(np.mean(sol.status == 0)) if len(sol) else 0.0
    return values + [ok, "ok" if ok > 0 else "unreachable"]


def _rows(spec, params, rows, metrics, inputs, text, base_dir, compiled) -> list[list]:
    """`run_designs` in one batch: every design built, solved by one `whole_motions` (or
    `solve_designs`) call and reduced by `evaluate_designs`; a design that cannot be built or
    solved gets its error in its row, the others go on."""
    import warnings
    base = _load(spec, text, base_dir) if text else load(spec)
    out: list = [None] * len(rows)
    built: list[tuple[int, Mechanism]] = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an over-closed design warns once per solve
        for k, values in enumerate(rows):
            try:
                built.append((k, D.apply(base, params, values)))
            except LinkworkError as exc:
                out[k] = _failed(metrics, exc)
        mechs = [m for _, m in built]
        sols = (whole_motions(mechs, compiled=compiled, isolate=True) if inputs is None else
                solve_designs(mechs, inputs, compiled=compiled, isolate=True))
    solved = []
    for (k, m), sol in zip(built, sols):
        if isinstance(sol, LinkworkError):
            out[k] = _failed(metrics, sol)
        else:
            solved.append((k, m, sol))
    values = evaluate_designs([m for _, m, _ in solved], [s for *_, s in solved], metrics)
    for (k, _, sol), v in zip(solved, values):
        out[k] = _finished(sol, v)
    return out


def _rows_one_by_one(spec, params, rows, metrics, inputs, text, base_dir, compiled) -> list[list]:
    """`run_designs` design by design (`whole_motion` or `solve`, then `evaluate`)."""
    import warnings
    base = _load(spec, text, base_dir) if text else load(spec)
    out = []
    for values in rows:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # an over-closed design warns once per solve
                mech = D.apply(base, params, values)
                sol = whole_motion(mech, order=2) if inputs is None else solve(mech, inputs, order=2)
            out.append(_finished(sol, evaluate(mech, sol, metrics)))
        except LinkworkError as exc:  # a design that cannot be built or solved is marked, not fatal
            out.append(_failed(metrics, exc))
    return out


def _chunks(n: int, size: int) -> list[range]:
    return [range(i, min(i + size, n)) for i in range(0, n, size)]


def execute(p: SweepPlan, *, workers: int | None = None, chunk: int | None = None,
            resume: Path | None = None, progress: Callable[[int, int], None] | None = None,
            scheduler=None, batch: bool = True) -> list[list]:
    """Every design's row (parameters, metrics, ok, status), in design order. `workers`
    processes (default: all cores; 1 runs here), or the workers of the Dask cluster whose
    scheduler is at `scheduler` (an address such as tcp://host:8786, or a `distributed.Client`);
    `resume` is a side file of finished chunks (JSON Lines), read first and appended to, so
    that a sweep cut off resumes where it stopped. Each chunk of designs is solved in one batch
    (`run_designs`; `batch=False`: design by design)."""
    n = len(p.designs)
    workers = max(1, workers or os.cpu_count() or 1)
    if scheduler is not None and chunk is None:
        # some 64 chunks (for any number of workers), but a batch of at least DASK_CHUNK
        chunk = max(1, min(200, max(DASK_CHUNK, math.ceil(n / 64))))
    chunk = chunk or max(1, min(200, math.ceil(n / (4 * workers))))
    parts = _chunks(n, chunk)
    done: dict[int, list] = {}
    key = {"spec": p.spec, "params": [q.name for q in p.params], "metrics": [m.name for m in p.metrics],
           "designs": n, "chunk": chunk}
    if resume is not None and resume.exists():
        lines = resume.read_text(encoding="utf-8").splitlines()
        head = json.loads(lines[0]) if lines else None
        if head != key:
            raise InputError(f"the resume file {resume} belongs to another sweep (remove it to start afresh)")
        for ln in lines[1:]:
            try:
                rec = json.loads(ln)
            except json.JSONDecodeError:  # a line cut off by the interruption
                continue
            done[rec["chunk"]] = rec["rows"]
    elif resume is not None:
        resume.write_text(json.dumps(key) + "\n", encoding="utf-8")
    todo = [i for i in range(len(parts)) if i not in done]
    finished = sum(len(parts[i]) for i in done)
    if progress:
        progress(finished, n)

    def record(i: int, rows: list[list]) -> None:
        nonlocal finished
        done[i] = rows
        if resume is not None:
            with open(resume, "a", encoding="utf-8") as fh:
                fh.write(json.dumps({"chunk": i, "rows": rows}, allow_nan=True) + "\n")
        finished += len(parts[i])
        if progress:
            progress(finished, n)

    def compiled_for(processes: int) -> bool:
        """Enough designs per process to pay for loading the compiled loops (once per process:
        a cluster's worker keeps them for its next chunks; local processes are forked from
        this one after it loaded them, where processes start by fork), or inputs enough per
        design for the compiled loops on their own?"""
        return (n - finished) / processes >= COMPILED_FROM or \
            (p.inputs is not None and len(p.inputs) > kernels.INTERPRETED_UP_TO)

    args = lambda i, compiled: (p.spec, p.params, p.designs[parts[i].start:parts[i].stop], p.metrics,
                                p.inputs, p.text, p.base_dir, compiled, batch)
    if scheduler is not None:
        _on_cluster(scheduler, todo, compiled_for, args, record)
    else:
        processes = 1 if workers == 1 or len(todo) <= 1 else min(workers, len(todo))
        compiled = compiled_for(processes)
        with loaded_compiled_loops() if compiled else nullcontext():
            if processes == 1:
                for i in todo:
                    record(i, run_designs(*args(i, compiled)))
            else:
                with ProcessPoolExecutor(max_workers=processes) as pool:
                    futures = {pool.submit(run_designs, *args(i, compiled)): i for i in todo}
                    for f in as_completed(futures):
                        record(futures[f], f.result())
    rows = []
    for i, r in enumerate(parts):
        for k, vals in zip(r, done[i]):
            rows.append([float(v) for v in p.designs[k]] + list(vals))
    return rows


def _on_cluster(scheduler, todo: list[int], compiled_for, args, record) -> None:
    """Run the chunks `todo` on a Dask cluster (dask.distributed), recording each as it ends;
    the compiled loops if its workers have designs enough each (`compiled_for`)."""
    try:
        from distributed import Client, as_completed as finished
    except ImportError:  # pragma: no cover - distributed is a dependency
        raise InputError("--scheduler needs dask.distributed (pip install distributed)") from None
    own = not hasattr(scheduler, "submit")
    if own:
        try:
            client = Client(scheduler, timeout="5s", set_as_default=False)
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(f"cannot reach the Dask scheduler at {scheduler}: {exc}") from None
    else:
        client = scheduler
    try:
        compiled = compiled_for(max(1, len(client.scheduler_info().get("workers", {}))))
        futures = {client.submit(run_designs, *args(i, compiled), pure=False): i for i in todo}
        for f in finished(list(futures), loop=client.loop):
            record(futures[f], f.result())
    finally:
        if own:
            client.close()


def to_frame(p: SweepPlan, rows: list[list]):
    """The results as a pandas DataFrame (units in `DataFrame.attrs['units']`)."""
    import pandas as pd
    df = pd.DataFrame(rows, columns=p.columns)
    df.attrs["units"] = p.units()
    return df


def write(p: SweepPlan, rows: list[list], path: str | Path) -> None:
    """CSV (units in the header: `name [unit]`) or Parquet (units in the schema's metadata,
    key b"linkwork.units"), chosen by the suffix; written whole or not at all."""
    from ..outputs import output_path
    path = Path(path)
    df = to_frame(p, rows)
    units = p.units()
    suffix = path.suffix.lower()
    if suffix == ".csv":
        df = df.rename(columns={c: with_unit(c, units.get(c, "")) for c in df.columns})
        with output_path(path) as tmp:
            df.to_csv(tmp, index=False)
    elif suffix in (".parquet", ".pq"):
        import pyarrow as pa
        import pyarrow.parquet as pq
        table = pa.Table.from_pandas(df, preserve_index=False)
        meta = dict(table.schema.metadata or {})
        meta[b"linkwork.units"] = json.dumps(units).encode()
        meta[b"linkwork.mechanism"] = p.spec.encode()
        with output_path(path) as tmp:
            pq.write_table(table.replace_schema_metadata(meta), tmp)
    else:
        raise InputError(f"-o {path}: write .csv or .parquet")
