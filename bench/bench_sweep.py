"""Designs per second of a four-bar design sweep (`linkwork.sweeps`): one core, all cores
(local processes), and a local Dask cluster of 1 … N worker processes; each before (every
design solved and reduced on its own: `execute(batch=False)`) and after (each chunk of designs
in one batch: `kinematics.designs.whole_motions`, `metrics.evaluate_designs`), in the same run.

    uv run python bench/bench_sweep.py                 # 200 designs of library:crank-rocker
    uv run python bench/bench_sweep.py --designs 2000 --no-dask
    uv run python bench/bench_sweep.py --mixed         # cranks 8 … 35: rockers past Grashof's limit

Each design is the crank-rocker with O4.x and the crank length varied on a grid, solved over its
whole motion (one crank turn, 361 samples; with --mixed, many designs are non-Grashof rockers,
each with its own limit positions) and reduced to four metrics (Grashof class, least and largest
transmission angle, time ratio). Timing: `time.perf_counter` around `sweeps.execute`, best of
`--repeats`, after one warm-up run (imports and the compiled kernels); CPU: the CPU time of that
best run — this process and its finished children (local processes), or the workers
(`Client.run(time.process_time)`, Dask) — since on a shared machine wall time says little.
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import time

from linkwork import sweeps

METRICS = ["grashof", "transmission-min:B", "transmission-max:B", "time-ratio:B"]


def plan(n: int, mixed: bool = False):
    side = max(2, int(math.isqrt(n)))
    hi = 35.0 if mixed else 12.0
    step_x, step_a = 10.0 / (side - 1), (hi - 8.0) / (side - 1)
    return sweeps.plan("library:crank-rocker", [f"O4.x=35:45:{step_x}", f"O2-A=8:{hi}:{step_a}"],
                       METRICS)


def _own_cpu() -> float:
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def best(fn, repeats: int, cpu=_own_cpu) -> tuple[float, float]:
    """(wall, CPU) seconds of the fastest of `repeats` runs."""
    runs = []
    for _ in range(repeats):
        c, t = cpu(), time.perf_counter()
        fn()
        runs.append((time.perf_counter() - t, cpu() - c))
    return min(runs)


def line(label: str, n: int, before: tuple, after: tuple) -> None:
    (wb, cb), (wa, ca) = before, after
    print(f"  {label:<26} before {n / wb:7.1f} designs/s ({1e3 * cb / n:5.2f} ms CPU/design)"
          f"   after {n / wa:7.1f} designs/s ({1e3 * ca / n:5.2f} ms CPU/design)"
          f"   {wb / wa:4.1f}x wall, {cb / ca:4.1f}x CPU")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--designs", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--mixed", action="store_true", help="cranks up to 35: rockers too")
    ap.add_argument("--no-dask", action="store_true", help="skip the Dask cluster runs")
    args = ap.parse_args()
    p = plan(args.designs, args.mixed)
    n, cores = len(p.designs), os.cpu_count() or 1
    for batch in (False, True):
        sweeps.execute(p, workers=1, batch=batch)  # warm-up
    load = os.getloadavg()
    print(f"{n} designs of library:crank-rocker{' (mixed)' if args.mixed else ''}, "
          f"{len(METRICS)} metrics, {cores} cores, load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    for label, workers in (("local, 1 core", 1), (f"local, {cores} processes", cores)):
        before, after = (best(lambda: sweeps.execute(p, workers=workers, batch=b), args.repeats)
                         for b in (False, True))
        line(label, n, before, after)
    if args.no_dask:
        return
    from distributed import Client, LocalCluster
    for k in range(1, cores + 1):
        with LocalCluster(n_workers=k, threads_per_worker=1, processes=True,
                          dashboard_address=None) as c, Client(c, set_as_default=False) as client:

            def workers_cpu() -> float:
                return time.process_time() + sum(client.run(time.process_time).values())
            res = []
            for b in (False, True):
                sweeps.execute(p, scheduler=client, batch=b)  # warm-up of the workers
                res.append(best(lambda: sweeps.execute(p, scheduler=client, batch=b),
                                args.repeats, workers_cpu))
            line(f"Dask LocalCluster, {k} worker{'s' if k > 1 else ''}", n, *res)
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
