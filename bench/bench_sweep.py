"""Designs per second of a four-bar design sweep (`linkwork.sweeps`): one core, all cores
(local processes), and a local Dask cluster of 1 … N worker processes.

    uv run python bench/bench_sweep.py                 # 200 designs of library:crank-rocker
    uv run python bench/bench_sweep.py --designs 2000 --no-dask

Each design is the crank-rocker with O4.x and the crank length varied on a grid, solved over its
whole motion (one crank turn, 361 samples) and reduced to four metrics (Grashof class, least and
largest transmission angle, time ratio). Timing: `time.perf_counter` around `sweeps.execute`,
best of `--repeats`, after one warm-up run (imports and the compiled kernels).
"""

from __future__ import annotations

import argparse
import math
import os
import time

from linkwork import sweeps

METRICS = ["grashof", "transmission-min:B", "transmission-max:B", "time-ratio:B"]


def plan(n: int):
    side = max(2, int(math.isqrt(n)))
    step_x, step_a = 10.0 / (side - 1), 4.0 / (side - 1)
    return sweeps.plan("library:crank-rocker", [f"O4.x=35:45:{step_x}", f"O2-A=8:12:{step_a}"], METRICS)


def best(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--designs", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--no-dask", action="store_true", help="skip the Dask cluster runs")
    args = ap.parse_args()
    p = plan(args.designs)
    n, cores = len(p.designs), os.cpu_count() or 1
    sweeps.execute(p, workers=1)  # warm-up
    print(f"{n} designs of library:crank-rocker, {len(METRICS)} metrics, {cores} cores")
    for label, workers in (("1 core", 1), (f"{cores} processes", cores)):
        t = best(lambda: sweeps.execute(p, workers=workers), args.repeats)
        print(f"  local, {label:>12}: {n / t:8.1f} designs/s")
    if args.no_dask:
        return
    from distributed import LocalCluster
    for k in range(1, cores + 1):
        with LocalCluster(n_workers=k, threads_per_worker=1, processes=True, dashboard_address=None) as c:
            sweeps.execute(p, scheduler=c.scheduler_address)  # warm-up of the workers
            t = best(lambda: sweeps.execute(p, scheduler=c.scheduler_address), args.repeats)
            print(f"  Dask LocalCluster, {k} worker{'s' if k > 1 else ' '}: {n / t:8.1f} designs/s")


if __name__ == "__main__":
    main()
