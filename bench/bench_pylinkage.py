"""linkwork vs pylinkage, side by side in one process.

Solves a four-bar (the library's crank-rocker with its coupler point) and Jansen's linkage for
N input angles (one full crank turn) with both libraries: positions, velocities and
accelerations of every joint point. pylinkage runs its numba-compiled
`Linkage.step_fast_with_kinematics`; linkwork runs `linkwork.solve` and then reads every
point's motion with `Solution.point` (both inside the timed region).

Before timing, both results are compared point by point; the table reports the largest
differences (position in mm, velocity in mm/s, acceleration in mm/s²), scaled by the
mechanism's size L and the crank speed ω where noted.

    uv run --group bench python bench/bench_pylinkage.py [--samples 100000] [--repeats 15]
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np
from rich.console import Console
from rich.table import Table

import linkwork

try:
    import pylinkage as pl
    from pylinkage.solver.simulation import simulate_with_kinematics  # noqa: F401  (numba kernel)
except ImportError:  # pragma: no cover
    sys.exit("pylinkage is not installed: run `uv sync --all-groups` or "
             "`uv run --group bench python bench/bench_pylinkage.py`")

OMEGA = 2 * math.pi  # crank speed, rad/s (60 rpm), the same in both libraries
ALPHA = 0.0          # crank angular acceleration


# ---------------------------------------------------------------------------- geometry
def _circles(P: np.ndarray, r1: float, Q: np.ndarray, r2: float, side: float) -> np.ndarray:
    """Intersection of circle(P, r1) and circle(Q, r2) on `side` (+1: left of P→Q)."""
    d = Q - P
    D = math.hypot(*d)
    a = (r1 * r1 - r2 * r2 + D * D) / (2 * D)
    h = math.sqrt(r1 * r1 - a * a)
    ex = d / D
    return P + a * ex + side * h * np.array([-ex[1], ex[0]])


def _fmt(p: np.ndarray) -> str:
    return f"[{float(p[0])!r}, {float(p[1])!r}]"


# Jansen's "holy numbers" (Theo Jansen, Strandbeest), in mm
JANSEN = dict(a=38.0, b=41.5, c=39.3, d=40.1, e=55.8, f=39.4, g=36.7, h=65.7, i=49.0, j=50.0,
              k=61.9, l=7.8, m=15.0)


def jansen_points(crank_angle: float = math.pi / 2) -> dict[str, np.ndarray]:
    """Design position of Jansen's leg: crank centre Z at the origin, frame pivot Y at (−a, −l),
    crank tip X at `crank_angle`; the leg points to the left, the foot F is at the bottom."""
    n = JANSEN
    Z = np.array([0.0, 0.0])
    Y = np.array([-n["a"], -n["l"]])
    X = Z + n["m"] * np.array([math.cos(crank_angle), math.sin(crank_angle)])
    C1 = _circles(X, n["j"], Y, n["b"], -1.0)  # top hinge (bars j and b)
    C2 = _circles(X, n["k"], Y, n["c"], +1.0)  # lower hinge (bars k and c)
    C3 = _circles(Y, n["d"], C1, n["e"], +1.0)  # outer corner of the triangle b-d-e
    C4 = _circles(C3, n["f"], C2, n["g"], -1.0)  # knee (bars f and g)
    F = _circles(C4, n["h"], C2, n["i"], -1.0)  # foot, corner of the triangle g-h-i
    pts = dict(Z=Z, Y=Y, X=X, C1=C1, C2=C2, C3=C3, C4=C4, F=F)
    # check the branch choices against the drawing: C3 left of Y, knee left of C2, foot lowest
    assert C3[0] < Y[0] and C4[0] < C2[0] and F[1] == min(p[1] for p in pts.values())
    return pts


def jansen_toml(points: dict[str, np.ndarray]) -> str:
    pts = "\n".join(f"{k} = {_fmt(v)}" for k, v in points.items())
    return f"""name = "Jansen's linkage (bench)"
description = "One leg of Theo Jansen's Strandbeest, from his numbers a..m."
units = {{ length = "mm" }}

[points]
{pts}

[links]
frame     = ["Z", "Y"]
crank     = ["Z", "X"]
bar_j     = ["X", "C1"]
bar_k     = ["X", "C2"]
bde       = ["Y", "C1", "C3"]
bar_c     = ["Y", "C2"]
bar_f     = ["C3", "C4"]
ghi       = ["C2", "C4", "F"]

[joints]
Z  = {{ type = "revolute", links = ["frame", "crank"] }}
Xj = {{ type = "revolute", point = "X", links = ["crank", "bar_j"] }}
Xk = {{ type = "revolute", point = "X", links = ["crank", "bar_k"] }}
C1 = {{ type = "revolute", links = ["bar_j", "bde"] }}
Yb = {{ type = "revolute", point = "Y", links = ["bde", "frame"] }}
Yc = {{ type = "revolute", point = "Y", links = ["bar_c", "frame"] }}
C2k = {{ type = "revolute", point = "C2", links = ["bar_k", "bar_c"] }}
C2g = {{ type = "revolute", point = "C2", links = ["bar_c", "ghi"] }}
C3 = {{ type = "revolute", links = ["bde", "bar_f"] }}
C4 = {{ type = "revolute", links = ["bar_f", "ghi"] }}

[driver]
joint = "Z"
reference = "X"
speed = "60 rpm"
"""


# ---------------------------------------------------------------------------- the cases
@dataclass
class Case:
    name: str
    mech: linkwork.Mechanism
    points: list[str]              # point names, in pylinkage's component order
    build_pylinkage: Callable[[float], tuple]  # angle step -> (linkage, crank)
    theta0: float                  # crank angle at the design position


def _d(P, Q) -> float:
    return float(math.hypot(*(np.asarray(Q) - np.asarray(P))))


def _ang(P, Q) -> float:
    return math.atan2(Q[1] - P[1], Q[0] - P[0])


def four_bar_case() -> Case:
    mech = linkwork.load("library:crank-rocker")
    P = {k: np.asarray(v) for k, v in mech.points.items()}
    theta0 = _ang(P["O2"], P["A"])

    def build(step: float):
        O2 = pl.Ground(*P["O2"], name="O2")
        O4 = pl.Ground(*P["O4"], name="O4")
        crank = pl.Crank(anchor=O2, radius=_d(P["O2"], P["A"]), angular_velocity=step,
                         initial_angle=theta0, name="A")
        B = pl.RRRDyad(crank.output, O4, distance1=_d(P["A"], P["B"]),
                       distance2=_d(P["O4"], P["B"]), x=P["B"][0], y=P["B"][1], name="B")
        C = pl.FixedDyad(crank.output, B, distance=_d(P["A"], P["C"]),
                         angle=_ang(P["A"], P["C"]) - _ang(P["A"], P["B"]), name="C")
        link = pl.Linkage([O2, O4, crank, B, C], name="crank-rocker")
        link.set_input_velocity(crank, OMEGA, ALPHA)
        return link, crank

    return Case("four-bar (crank-rocker)", mech, ["O2", "O4", "A", "B", "C"], build, theta0)


def jansen_case() -> Case:
    P = jansen_points()
    mech = linkwork.load_text(jansen_toml(P), source="<bench: jansen>")
    theta0 = _ang(P["Z"], P["X"])

    def build(step: float):
        Z = pl.Ground(*P["Z"], name="Z")
        Y = pl.Ground(*P["Y"], name="Y")
        crank = pl.Crank(anchor=Z, radius=_d(P["Z"], P["X"]), angular_velocity=step,
                         initial_angle=theta0, name="X")

        def rrr(a1, a2, pa1, pa2, name):
            return pl.RRRDyad(a1, a2, distance1=_d(P[pa1], P[name]), distance2=_d(P[pa2], P[name]),
                              x=P[name][0], y=P[name][1], name=name)

        def fixed(a1, a2, pa1, pa2, name):
            return pl.FixedDyad(a1, a2, distance=_d(P[pa1], P[name]),
                                angle=_ang(P[pa1], P[name]) - _ang(P[pa1], P[pa2]), name=name)

        C1 = rrr(crank.output, Y, "X", "Y", "C1")
        C2 = rrr(crank.output, Y, "X", "Y", "C2")
        C3 = fixed(Y, C1, "Y", "C1", "C3")
        C4 = rrr(C3, C2, "C3", "C2", "C4")
        F = fixed(C2, C4, "C2", "C4", "F")
        link = pl.Linkage([Z, Y, crank, C1, C2, C3, C4, F], name="jansen")
        link.set_input_velocity(crank, OMEGA, ALPHA)
        return link, crank

    return Case("Jansen's linkage", mech, ["Z", "Y", "X", "C1", "C2", "C3", "C4", "F"], build,
                theta0)


# ---------------------------------------------------------------------------- runners
def run_pylinkage(link, n: int):
    """(positions, velocities, accelerations), each (n, points, 2)."""
    return link.step_fast_with_kinematics(iterations=n, dt=1.0)


def run_linkwork(mech, names: list[str], angles: np.ndarray, omega: np.ndarray) -> list:
    """The same quantities from linkwork: solve, then read every point's position, velocity
    and acceleration (each an (n, 2) array, like pylinkage's arrays; nothing is copied)."""
    sol = linkwork.solve(mech, angles, velocities=omega)
    return [sol.point(name) for name in names]


def stacked(motions: list) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """linkwork's point motions in pylinkage's layout (n, points, 2)."""
    return tuple(np.stack([getattr(m, q) for m in motions], axis=1)
                 for q in ("position", "velocity", "acceleration"))


def compare(case: Case, n: int) -> dict:
    """Both libraries on the same n inputs; the largest differences."""
    step = 2 * math.pi / n
    link, crank = case.build_pylinkage(step)
    pp, pv, pa = run_pylinkage(link, n)
    # pylinkage advances its crank by the step from atan2 of the previous crank position, so
    # its angles drift from θ0 + k·step by rounding; linkwork is given the angles pylinkage
    # actually reached, so that both solve exactly the same inputs
    ia = case.points.index(crank.name)
    rel = pp[:, ia] - pp[:, 0]  # the crank's anchor is the first ground point in both cases
    angles = case.theta0 + np.unwrap(np.arctan2(rel[:, 1], rel[:, 0]) - case.theta0)
    nominal = case.theta0 + step * np.arange(1, n + 1)
    lp, lv, la = stacked(run_linkwork(case.mech, case.points, angles, np.full(n, OMEGA)))
    return dict(
        pos=float(np.abs(lp - pp).max()), vel=float(np.abs(lv - pv).max()),
        acc=float(np.abs(la - pa).max()), L=case.mech.length_scale,
        drift=float(np.abs(angles - nominal).max()),
        finite=all(np.isfinite(a).all() for a in (pp, pv, pa, lp, lv, la)),
    )


def bench(case: Case, n: int, repeats: int) -> dict:
    """Best wall-clock times (time.perf_counter) of both libraries, run alternately so that
    both see the same machine load, and a breakdown of linkwork's time."""
    step = 2 * math.pi / n
    link, _ = case.build_pylinkage(step)
    run_pylinkage(link, 1000)  # numba: compile (or load from its cache) and warm up
    angles = case.theta0 + step * np.arange(1, n + 1)
    omega = np.full(n, OMEGA)
    run_linkwork(case.mech, case.points, angles, omega)  # warm up (plan cache, allocator)
    sol = linkwork.solve(case.mech, angles, velocities=omega)

    def timed(fn) -> float:
        t0 = time.perf_counter()
        fn()
        return time.perf_counter() - t0

    best = dict(pl=math.inf, lw=math.inf, solve=math.inf, read=math.inf)
    for _ in range(repeats):
        best["pl"] = min(best["pl"], timed(lambda: run_pylinkage(link, n)))
        best["lw"] = min(best["lw"], timed(lambda: run_linkwork(case.mech, case.points, angles,
                                                                omega)))
    for _ in range(repeats):
        best["solve"] = min(best["solve"], timed(lambda: linkwork.solve(case.mech, angles,
                                                                        velocities=omega)))
        best["read"] = min(best["read"], timed(lambda: [sol.point(p) for p in case.points]))
    return best


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=100_000, help="input angles per run")
    ap.add_argument("--repeats", type=int, default=15, help="timed repeats (the best is kept)")
    args = ap.parse_args(argv)
    n = args.samples
    console = Console(width=112)
    cases = [four_bar_case(), jansen_case()]
    load = os.getloadavg()[0]

    acc_table = Table(title=f"Agreement on {n:,} inputs: max |linkwork − pylinkage| over all "
                            "points and samples")
    for col in ("mechanism", "points", "position [mm]", "velocity [mm/s]",
                "acceleration [mm/s²]", "relative (÷ L, Lω, Lω²)"):
        acc_table.add_column(col, justify="left" if col == "mechanism" else "right")
    speed_table = Table(title=f"Input positions solved per second ({n:,} inputs; positions, "
                              f"velocities, accelerations of every joint; best of {args.repeats})")
    for col in ("mechanism", "pylinkage", "linkwork", "linkwork / pylinkage"):
        speed_table.add_column(col, justify="left" if col == "mechanism" else "right")
    parts_table = Table(title="Where linkwork's time goes (best of each, ms)")
    for col in ("mechanism", "solve()", "sol.point() × points", "pylinkage"):
        parts_table.add_column(col, justify="left" if col == "mechanism" else "right")

    drift = 0.0
    for case in cases:
        c = compare(case, n)
        drift = max(drift, c["drift"])
        L = c["L"]
        rel = max(c["pos"] / L, c["vel"] / (L * OMEGA), c["acc"] / (L * OMEGA ** 2))
        acc_table.add_row(case.name, str(len(case.points)), f"{c['pos']:.1e}", f"{c['vel']:.1e}",
                          f"{c['acc']:.1e}", f"{rel:.1e}")
        if not c["finite"]:
            console.print(f"[red]{case.name}: some samples did not assemble")
        b = bench(case, n, args.repeats)
        r_pl, r_lw = n / b["pl"], n / b["lw"]
        speed_table.add_row(case.name, f"{r_pl / 1e6:.2f} M/s", f"{r_lw / 1e6:.2f} M/s",
                            f"{r_lw / r_pl:.2f}×")
        parts_table.add_row(case.name, f"{1e3 * b['solve']:.1f}", f"{1e3 * b['read']:.1f}",
                            f"{1e3 * b['pl']:.1f}")
    console.print(acc_table)
    console.print(f"L = the drawing's diagonal, ω = {OMEGA:.4f} rad/s. pylinkage's crank angle "
                  f"drifts by rounding as it steps (here by up to {drift:.1e} rad from θ0 + k·2π/n), "
                  "so linkwork is given the angles pylinkage reached.")
    console.print(speed_table)
    console.print(parts_table)
    load = max(load, os.getloadavg()[0])
    console.print(f"numpy {np.__version__}, pylinkage {pl.__version__}, "
                  f"numba {__import__('numba').__version__}, python {sys.version.split()[0]}, "
                  f"{os.cpu_count()} CPUs, load average up to {load:.1f} while running")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
