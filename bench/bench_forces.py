"""linkwork's kinetostatics over 100 000 samples: a four-bar (`library:crank-rocker`) and a
six-bar (`library:pmks-stephenson-iii`), both with the mass data of their library files.

Times `linkwork.forces.kinetostatics` on a solved motion (the solve is timed separately), with
and without the virtual-work check (a second kinematic solve), best of `--repeats`, and prints
samples per second and the worst power-balance residual. No peer library is compared here:
kinepy's dynamics was not set up in this environment (see bench/README.md).

    uv run python bench/bench_forces.py [--samples 100000] [--repeats 3]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import linkwork
from linkwork.forces import kinetostatics
from linkwork.io import load_dynamics


def best(f, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--samples", type=int, default=100_000)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    for name in ("crank-rocker", "pmks-stephenson-iii"):
        dyn = load_dynamics(f"library:{name}")
        mech = dyn.mechanism
        q0 = mech.driver_input_at_design(mech.drivers[0])
        # the six-bar's input rocks: stay inside its limits
        q = q0 + (np.linspace(-0.3, 0.3, args.samples) if name.startswith("pmks")
                  else np.linspace(0, 2 * np.pi, args.samples))
        kinetostatics(dyn, linkwork.solve(mech, q[:100]))  # warm-up (numba, caches)
        sol = linkwork.solve(mech, q)
        t_solve = best(lambda: linkwork.solve(mech, q), args.repeats)
        t_plain = best(lambda: kinetostatics(dyn, sol, virtual_work=False), args.repeats)
        t_full = best(lambda: kinetostatics(dyn, sol), args.repeats)
        fa = kinetostatics(dyn, sol)
        worst = float(np.max(np.abs(fa.power_residual) / fa.power_scale))
        n = args.samples
        print(f"{name}: {n} samples; solve {n / t_solve:,.0f}/s; kinetostatics {n / t_plain:,.0f}/s "
              f"(with the virtual-work check {n / t_full:,.0f}/s); worst power residual {worst:.1e}")


if __name__ == "__main__":
    main()
