"""The Newton-solved groups' speed: whole motions of the valve gears and a drag's per-frame solve.

Two configurations run alternately in this one process, so that their ratio holds on a shared
machine: *jets* — every group's residuals, Jacobian and first rates evaluated on jets
(`groups.PAIR_TABLES = False`, as before the pair tables) — and *tables* (the default). Times
are CPU time of this process (`time.process_time`), the median of `--repeats`.

- whole motion: `linkwork.whole_motion` of a freshly loaded mechanism (no march kept from an
  earlier solve), the load not timed;
- drag: the server's solve of a drag frame: a point moved round a small circle, each frame a
  new mechanism solved at one input carrying the previous frame's march over
  (`solve(mech, at, previous=…)`), as `web.app.solve_at` does; the loops compiled, as the
  server runs them (`--interpreted`: as a command line runs a few samples).

    uv run python bench/bench_newton.py
    uv run python bench/bench_newton.py --repeats 7 --frames 60
"""

from __future__ import annotations

import argparse
import math
import subprocess
import time
from contextlib import contextmanager

import numpy as np

import linkwork
from linkwork.kinematics import groups, kernels
from linkwork.web.sources import moved

MOTIONS = ["heusinger-valve-gear", "heusinger-hinge-chain", "proell-schwabe-valve-gear"]
#: (library name, the point dragged, the radius of its circle (mm), the input's place as a
#: fraction of the whole motion's samples)
DRAGS = [("heusinger-valve-gear", "P45", 4.0, 0.0), ("heusinger-valve-gear", "P45", 4.0, 0.25),
         ("heusinger-hinge-chain", "P67", 4.0, 0.25)]


@contextmanager
def configuration(name: str):
    saved = groups.PAIR_TABLES
    groups.PAIR_TABLES = name != "jets"
    try:
        yield
    finally:
        groups.PAIR_TABLES = saved


CONFIGS = ["jets", "tables"]


def whole_motion_time(name: str) -> float:
    mech = linkwork.load(f"library:{name}")
    t = time.process_time()
    linkwork.whole_motion(mech)
    return time.process_time() - t


def drag_times(name: str, point: str, radius: float, place: float, frames: int) -> np.ndarray:
    """CPU ms of each frame's solve (the first few, which fill the caches, left out)."""
    base = linkwork.load(f"library:{name}")
    motion = linkwork.whole_motion(base)
    u = motion.inputs[int(round(place * (len(motion) - 1)))]
    at = u[None, :]
    x0 = base.points[point]
    out, previous = [], base
    linkwork.solve(base, at)
    for k in range(frames + 4):
        a = 2 * math.pi * k / (frames + 4)
        mech = moved(base, {point: (x0[0] + radius * math.cos(a), x0[1] + radius * math.sin(a))})
        t = time.process_time()
        linkwork.solve(mech, at, previous=previous)
        if k >= 4:
            out.append((time.process_time() - t) * 1e3)
        previous = mech
    return np.array(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--frames", type=int, default=40, help="drag frames per repeat")
    ap.add_argument("--interpreted", action="store_true",
                    help="the loops interpreted (as a command line's few samples)")
    args = ap.parse_args()
    print("uptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    loops = kernels.compiled_loops(not args.interpreted)
    with loops:
        if not args.interpreted:
            linkwork.whole_motion(linkwork.load("library:crank-rocker"))  # numba loaded first
        print("\nwhole motion, CPU s (median of %d):" % args.repeats)
        print(f"{'mechanism':28} " + " ".join(f"{c:>8}" for c in CONFIGS) + "   ratio")
        for name in MOTIONS:
            t = {c: [] for c in CONFIGS}
            for _ in range(args.repeats):
                for c in CONFIGS:
                    with configuration(c):
                        t[c].append(whole_motion_time(name))
            med = {c: float(np.median(v)) for c, v in t.items()}
            print(f"{name:28} " + " ".join(f"{med[c]:8.3f}" for c in CONFIGS)
                  + f"   {med[CONFIGS[0]] / med[CONFIGS[-1]]:5.2f}×")
        print("\ndrag: one frame's solve with previous=, CPU ms (median and p95 over "
              f"{args.repeats} × {args.frames} frames):")
        print(f"{'mechanism':28} {'at':>5} " + " ".join(f"{c + ' p50':>11} {'p95':>6}" for c in CONFIGS)
              + "   ratio")
        for name, point, radius, place in DRAGS:
            t = {c: [] for c in CONFIGS}
            for _ in range(args.repeats):
                for c in CONFIGS:
                    with configuration(c):
                        t[c].append(drag_times(name, point, radius, place, args.frames))
            t = {c: np.concatenate(v) for c, v in t.items()}
            p50 = {c: float(np.median(v)) for c, v in t.items()}
            print(f"{name:28} {place:5.2f} " + " ".join(
                f"{p50[c]:11.1f} {np.percentile(t[c], 95):6.1f}" for c in CONFIGS)
                + f"   {p50[CONFIGS[0]] / p50[CONFIGS[-1]]:5.2f}×")
    print("\nuptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


if __name__ == "__main__":
    main()
