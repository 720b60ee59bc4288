"""The long fuzz run of issue 10: ten thousand cases or more through the harness of tests/fuzz.

    .venv/bin/python tools/fuzz.py --cases 10000 --workers 2 [--seed 1] [--report fuzz.json]

Each case is a mutated library file (load + solve + structure) or, for --cli-share of them, a
random command line. The figures printed at the end: cases, results, user errors, and crashes,
hangs and wrong `ok` samples by cause, with one example each. Every case is reproducible from
the seed and its number (`--only N`).
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import random
import sys
import time
from collections import Counter, defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "fuzz"))

from rich.console import Console  # noqa: E402
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn  # noqa: E402
from rich.table import Table  # noqa: E402

_STATE: dict = {}


def _init(seed: int, cli_share: float, timeout: float) -> None:
    import warnings

    import fuzz_harness as h

    warnings.simplefilter("ignore")  # RuntimeWarnings of NumPy on absurd inputs are not findings
    texts = h.library_texts()
    _STATE.update(h=h, texts=texts, names=sorted(texts), seed=seed, cli_share=cli_share, timeout=timeout)
    h.warm_up()  # numba's compilation is not a hang of the first case


def _case(i: int) -> tuple[int, str, str, str, str]:
    h, names = _STATE["h"], _STATE["names"]
    rng = random.Random(_STATE["seed"] * 1_000_003 + i)
    if rng.random() < _STATE["cli_share"]:
        args = h.cli_args(rng, names)
        out = h.run_cli_case(args, seconds=_STATE["timeout"] * 3)
        case = "cli: linkwork " + " ".join(repr(a) if " " in a or not a else a for a in args)
    else:
        name = rng.choice(names)
        data, muts = h.mutate(_STATE["texts"][name], rng)
        out = h.run_file_case(data, rng, seconds=_STATE["timeout"])
        case = f"file: library:{name} with " + "; ".join(muts)
    return i, out.kind, out.cause, out.detail, case


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", type=int, default=10_000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cli-share", type=float, default=0.1, help="the share of command-line cases")
    ap.add_argument("--timeout", type=float, default=10.0, help="seconds per file case (command lines: 3×)")
    ap.add_argument("--only", type=int, default=None, help="run this one case and print it")
    ap.add_argument("--report", type=Path, default=None, help="write every finding as JSON here")
    a = ap.parse_args()
    con = Console()
    if a.only is not None:
        _init(a.seed, a.cli_share, a.timeout)
        con.print(_case(a.only), markup=False)
        return 0
    kinds: Counter = Counter()
    causes: dict[str, Counter] = defaultdict(Counter)
    examples: dict[tuple[str, str], tuple[int, str, str]] = {}
    findings = []
    t0 = time.monotonic()
    # findings also stream to REPORT.jsonl as they come, so that a long run cut short keeps them
    stream = open(a.report.with_suffix(".jsonl"), "w") if a.report else None
    ctx = mp.get_context("fork")
    with ctx.Pool(a.workers, initializer=_init, initargs=(a.seed, a.cli_share, a.timeout)) as pool, \
            Progress(TextColumn("fuzz"), BarColumn(), MofNCompleteColumn(), TextColumn("{task.fields[found]}"),
                     TimeElapsedColumn(), TimeRemainingColumn(), console=con) as bar:
        task = bar.add_task("fuzz", total=a.cases, found="")
        for i, kind, cause, detail, case in pool.imap_unordered(_case, range(a.cases), chunksize=4):
            kinds[kind] += 1
            causes[kind][cause] += 1
            if kind not in ("result", "user-error"):
                examples.setdefault((kind, cause), (i, case, detail))
                findings.append({"case": i, "kind": kind, "cause": cause, "detail": detail, "input": case})
                if stream:
                    stream.write(json.dumps(findings[-1]) + "\n")
                    stream.flush()
            bad = sum(v for k, v in kinds.items() if k not in ("result", "user-error"))
            bar.update(task, advance=1, found=f"{bad} findings")
            done = sum(kinds.values())
            if stream and done % 100 == 0:  # the figures so far, for a run cut short
                stream.write(json.dumps({"done": done, "outcomes": dict(kinds),
                                         "seconds": round(time.monotonic() - t0)}) + "\n")
                stream.flush()
    elapsed = time.monotonic() - t0
    if stream:
        stream.close()
    t = Table(title=f"linkwork fuzz: {a.cases} cases, seed {a.seed}, {elapsed:.0f} s on {a.workers} workers")
    t.add_column("outcome")
    t.add_column("cases", justify="right")
    t.add_column("causes")
    for kind in ("result", "user-error", "crash", "hang", "wrong-ok"):
        top = ", ".join(f"{c} ×{n}" for c, n in causes[kind].most_common(8)) if kind != "user-error" else \
            ", ".join(f"{c} ×{n}" for c, n in causes[kind].most_common(6))
        t.add_row(kind, str(kinds[kind]), top)
    con.print(t, markup=False)
    for (kind, cause), (i, case, detail) in sorted(examples.items()):
        con.print(f"[{kind}] {cause} — case {i}: {case}\n    {detail}", markup=False, highlight=False)
    if a.report:
        a.report.write_text(json.dumps({"cases": a.cases, "seed": a.seed, "seconds": elapsed,
                                        "outcomes": dict(kinds), "causes": {k: dict(v) for k, v in causes.items()},
                                        "findings": findings}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
