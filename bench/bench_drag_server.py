"""The workbench server's side of a drag frame, without the drawing: `Sources.load` (the moved
mechanism built) and `web.app.solve_request` (its solve carrying the previous frame's march
over), as `/api/drawing` runs them, timed per frame and optionally profiled.

A point is moved in small steps round a circle (bench_workbench.py's cases), each step a
request naming the source and the moved point; the loops compiled, as `linkwork serve` runs
them. Times are CPU ms of this thread (`time.thread_time`), median and p95 over the frames
(the first few, which fill the caches, left out).

    uv run python bench/bench_drag_server.py
    uv run python bench/bench_drag_server.py --frames 60 --profile heusinger-valve-gear
"""

from __future__ import annotations

import argparse
import cProfile
import math
import pstats
import time

import numpy as np

from linkwork.kinematics import whole_motion
from linkwork.kinematics.continuation import carried
from linkwork.kinematics.warmup import loaded_compiled_loops
from linkwork.web import models as m
from linkwork.web.app import solve_request
from linkwork.web.sources import Sources

#: (library name, the point dragged, the radius of its circle (mm), the input's place as a
#: fraction of the whole motion's samples), as bench_workbench.py drags them; and the
#: Proell–Schwabe valve gear's rolling pair (its Newton group on jets) three quarters on
CASES = [("crank-rocker", "C", 0.6, 0.0), ("heusinger-valve-gear", "P45", 4.0, 0.0),
         ("heusinger-valve-gear", "P45", 4.0, 0.25), ("proell-schwabe-valve-gear", "P12", 0.1, 0.75)]
WARMUP = 4


def drag(name: str, point: str, radius: float, place: float, frames: int,
         profile: cProfile.Profile | None = None, timed_from=None) -> tuple[np.ndarray, np.ndarray, list]:
    """CPU ms of each frame's load and solve, and how each frame's march began (`timed_from`:
    called before the first timed frame)."""
    sources = Sources(None)
    base = sources.load(library=name).mechanism
    at = None
    if place:
        motion = whole_motion(base)
        at = motion.inputs[int(round(place * (len(motion) - 1)))].tolist()
    x0 = base.points[point]
    load_ms, solve_ms, marches = [], [], []
    # the bench's drag: a 24th of the circle per frame
    for k, a in enumerate(np.linspace(0, 2 * math.pi * (frames + WARMUP) / 24, frames + WARMUP)):
        xy = (float(x0[0] + radius * math.cos(a)), float(x0[1] + radius * math.sin(a)))
        req = m.DrawingRequest.model_validate(
            {"source": {"library": name, "points": {point: xy}}, "motion": False,
             **({} if at is None else {"at": [at]})})
        timed = k >= WARMUP
        if k == WARMUP and timed_from is not None:
            timed_from()
        if timed and profile is not None:
            profile.enable()
        t0 = time.thread_time()
        src = req.source
        loaded = sources.load(library=src.library, points=src.points)
        t1 = time.thread_time()
        solve_request(loaded.mechanism, req, previous=loaded.previous)
        t2 = time.thread_time()
        if timed and profile is not None:
            profile.disable()
        if timed:
            load_ms.append((t1 - t0) * 1e3)
            solve_ms.append((t2 - t1) * 1e3)
            marches.append(carried(loaded.mechanism))
    return np.array(load_ms), np.array(solve_ms), marches


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--frames", type=int, default=40)
    ap.add_argument("--profile", metavar="NAME", help="profile the frames of this library "
                    "mechanism's cases (cProfile, cumulative)")
    ap.add_argument("--top", type=int, default=40)
    args = ap.parse_args()
    with loaded_compiled_loops():
        for name, point, radius, place in CASES:
            prof = cProfile.Profile() if args.profile == name else None
            load_ms, solve_ms, marches = drag(name, point, radius, place, args.frames, prof)
            fresh = sum(1 for c in marches if c is not None and c.reason is not None)
            print(f"{name:22s} {point:4s} place {place:4.2f}: load {np.median(load_ms):6.2f} / "
                  f"{np.percentile(load_ms, 95):6.2f} ms, solve {np.median(solve_ms):6.2f} / "
                  f"{np.percentile(solve_ms, 95):6.2f} ms (median / p95 CPU)"
                  + (f"; {fresh} frames marched afresh" if fresh else ""))
            if prof is not None:
                pstats.Stats(prof).sort_stats("cumulative").print_stats(args.top)


if __name__ == "__main__":
    main()
