"""linkwork on Geneva wheels: the library's 4- and 6-slot wheels over 100 000 driver angles.

Neither pylinkage 1.3 nor `mechanism` 1.1 has an intermittent drive, so there is no peer to run
side by side. What the benchmark sets linkwork against instead is the closed form itself,
written here in NumPy (the bare formula, no mechanism around it, the least any program can do
per angle) and the accuracy of linkwork's wheel angle, angular velocity and acceleration
against it.

The closed form (Pöschl §25a, the slotted crank of §24): with the driver's angle φ from the
line of centres towards the wheel and λ = r/D, while the pin is in a slot the wheel has turned
ψ = atan2(λ sin φ, 1 − λ cos φ) against the driver's sense from mid-engagement, with
ψ′ = λ(cos φ − λ)/N and ψ″ = −λ(1 − λ²) sin φ/N², N = 1 − 2λ cos φ + λ²; engaged for
|φ| < π/2 − π/n (shock-free wheel: r = D sin π/n), locked at ∓π/n between, 2π/n per turn.

    uv run --group bench python bench/bench_intermittent.py [--samples 100000] [--repeats 3]
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time

import numpy as np
from rich.console import Console
from rich.table import Table

import linkwork

WHEELS = {"geneva-4": 4, "geneva-6": 6}
OMEGA = 2 * math.pi  # the library's driver: 60 rpm


def closed_form(phi: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Wheel angle (from the drawing at mid-engagement), ω and α at driver angles φ (from the
    drawing) turning at the constant speed OMEGA."""
    lam = math.sin(math.pi / n)
    k = np.round(phi / (2 * np.pi))
    p = phi - 2 * np.pi * k  # within one turn of mid-engagement
    engaged = np.abs(p) < np.pi / 2 - np.pi / n
    c, s = np.cos(p), np.sin(p)
    N = 1 - 2 * lam * c + lam * lam
    psi = np.where(engaged, np.arctan2(lam * s, 1 - lam * c), np.sign(p) * np.pi / n)
    d1 = np.where(engaged, lam * (c - lam) / N, 0.0)
    d2 = np.where(engaged, -lam * (1 - lam * lam) * s / (N * N), 0.0)
    return -psi - k * 2 * np.pi / n, -d1 * OMEGA, -d2 * OMEGA**2


def timed(fn) -> float:
    """CPU seconds of this process for fn() (the wall clock also counts waiting for a CPU on a
    machine shared with other jobs)."""
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=100_000, help="driver angles per run")
    ap.add_argument("--repeats", type=int, default=3, help="timed repeats (the best is kept)")
    args = ap.parse_args(argv)
    n = args.samples
    # two driver turns, half a step off the entries and exits (where the acceleration jumps)
    step = 4 * np.pi / n
    phi = -2 * np.pi + step * (np.arange(n) + 0.5)
    console = Console(width=120)
    load = os.getloadavg()[0]
    table = Table(title=f"Geneva wheels, {n:,} driver angles over two turns (best of {args.repeats})")
    for col in ("wheel", "linkwork (angle, ω, α)", "closed form in NumPy", "linkwork / closed form",
                "angle error (rad)", "ω error (rad/s)", "α error (rad/s²)", "status ok"):
        table.add_column(col, justify="left" if col == "wheel" else "right")
    for name, slots in WHEELS.items():
        mech = linkwork.load(f"library:{name}")

        def run():  # the pair's report: the wheel's turn from the drawing, its ω and α
            r = linkwork.solve(mech, phi).joint("pin")
            return r["angle"], r["omega"], r["alpha"]

        run()  # warm-up (compiled kernels, the plan)
        got = run()
        want = closed_form(phi, slots)
        errs = [float(np.abs(g - w).max()) for g, w in zip(got, want)]
        ok = float((linkwork.solve(mech, phi).status == 0).mean())
        best = dict(lw=math.inf, cf=math.inf)
        for _ in range(args.repeats):
            best["lw"] = min(best["lw"], timed(run))
            best["cf"] = min(best["cf"], timed(lambda: closed_form(phi, slots)))
        table.add_row(name, f"{n / best['lw'] / 1e3:.0f} k/s", f"{n / best['cf'] / 1e3:.0f} k/s",
                      f"{best['cf'] / best['lw']:.2f}", *(f"{e:.1e}" for e in errs), f"{ok:.0%}")
    console.print(table)
    load = max(load, os.getloadavg()[0])
    console.print(f"numpy {np.__version__}, python {sys.version.split()[0]}, {os.cpu_count()} CPUs, "
                  f"load average up to {load:.1f} while running")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
