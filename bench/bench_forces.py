"""linkwork's kinetostatics over 100 000 samples: a four-bar (`library:crank-rocker`) and a
six-bar (`library:pmks-stephenson-iii`), both with the mass data of their library files.

Times `linkwork.forces.kinetostatics` on a solved motion (the solve is timed separately), with
and without the virtual-work check (a second kinematic solve), best of `--repeats`, and prints
samples per second and the worst power-balance residual. Side by side on the four-bar: kinepy's
dynamics (PyPI `kinepy`, bench group; `System.solve_dynamics`, which takes the accelerations
from second differences of the positions over the samples, evenly spaced in time). Its
reactions and driving torque are compared with linkwork's before anything is timed (kinepy
reports the opposite member of each action-reaction pair: the force of links[1] on links[0],
and the torque the driven link exerts back); then kinematics + forces are timed in both.

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


def kinepy_four_bar(dyn, n: int):
    """The crank-rocker in kinepy (SI units; every solid's local frame is the world frame at the
    design position, so its angle is the rotation from there, as in linkwork), with the mass
    data of the library file, and a function solving kinematics + dynamics for one crank turn
    in one second over `n` samples (60 rpm, the file's speed)."""
    import contextlib
    import io

    import kinepy as kp

    kp.units.set_unit_system(kp.units.SI)
    mech, m = dyn.mechanism, dyn.metres_per_unit
    P = {p: m * np.asarray(mech.points[p], float) for p in ("O2", "A", "B", "O4")}
    s = kp.System()
    for ln in ("crank", "coupler", "rocker"):
        mp = dyn.masses[ln]
        s.add_solid(ln, mp.mass, mp.inertia, tuple(m * np.asarray(mp.center, float)))
    joints = {"O2": s.add_revolute(0, "crank", P["O2"], P["O2"]),
              "A": s.add_revolute("crank", "coupler", P["A"], P["A"]),
              "B": s.add_revolute("coupler", "rocker", P["B"], P["B"]),
              "O4": s.add_revolute("rocker", 0, P["O4"], P["O4"])}
    with contextlib.redirect_stdout(io.StringIO()):  # kinepy prints its compilation
        s.pilot(joints["O2"])
        s.compile()
        s.change_signs([-1])  # the assembly branch of the drawing
    theta = 2 * np.pi * np.arange(n) / n

    def run():
        s.solve_dynamics(theta[None, :].copy(), t=1.0)
    return joints, theta, run


def kinepy_difference(dyn, n: int) -> tuple[np.ndarray, object]:
    """Per interior sample, the largest difference between kinepy's and linkwork's reactions
    and driving torque over `n` samples, relative to each quantity's largest magnitude; and
    kinepy's run function."""
    joints, theta, run = kinepy_four_bar(dyn, n)
    mech = dyn.mechanism
    q = mech.driver_input_at_design(mech.drivers[0]) + theta
    run()
    fa = kinetostatics(dyn, linkwork.solve(mech, q), virtual_work=False)
    inner = slice(1, -1)  # kinepy's central differences leave the end samples NaN
    pairs = [(fa.reactions[name].force[inner], -np.asarray(j.force).T[inner]) for name, j in joints.items()]
    pairs.append((fa.effort[inner, None], -np.asarray(joints["O2"].torque)[inner, None]))
    d = np.max([np.max(np.abs(a - b), axis=1) / np.max(np.abs(a)) for a, b in pairs], axis=0)
    return d, run


def compare_kinepy(dyn, n: int, repeats: int) -> None:
    try:
        import kinepy  # noqa: F401
    except ImportError:
        print("  kinepy not installed (uv sync --group bench): skipped")
        return
    # kinepy differentiates positions twice numerically: truncation ~(ω·dt)²/12 falls and
    # round-off ~ε/(ω·dt)² grows with the samples; at 1000 samples both are below 1e-5, so the
    # results are compared there (to 1e-4), and at `n` the spread is only reported
    d_check, _ = kinepy_difference(dyn, 1000)
    if not np.max(d_check) < 1e-4:
        raise SystemExit(f"kinepy and linkwork disagree: worst relative difference "
                         f"{np.max(d_check):.1e} at 1000 samples")
    d, run = kinepy_difference(dyn, n)
    mech = dyn.mechanism
    q = mech.driver_input_at_design(mech.drivers[0]) + 2 * np.pi * np.arange(n) / n

    def ours_run():
        kinetostatics(dyn, linkwork.solve(mech, q), virtual_work=False)
    t_ours, t_kp = best(ours_run, repeats), best(run, repeats)
    print(f"  vs kinepy: at 1000 samples worst relative difference {np.max(d_check):.1e}; at {n}: "
          f"median {np.median(d):.1e}, 99th percentile {np.percentile(d, 99):.1e}, worst "
          f"{np.max(d):.1e} at sample {int(np.argmax(d)) + 1}")
    print(f"  kinematics + forces over {n} samples: linkwork {n / t_ours:,.0f}/s, kinepy "
          f"{n / t_kp:,.0f}/s; kinepy takes {t_kp / t_ours:.2f}× linkwork's time")


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
        if name == "crank-rocker":
            compare_kinepy(dyn, n, args.repeats)


if __name__ == "__main__":
    main()
