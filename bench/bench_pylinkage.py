"""linkwork vs pylinkage (and a hand-written C loop), side by side in one process.

Solves a four-bar (the library's crank-rocker with its coupler point), Jansen's linkage, a Watt
and a Stephenson six-bar and an offset slider-crank for N input angles (one full crank turn)
with both libraries: positions, velocities and accelerations of every joint point. pylinkage
runs its numba-compiled `Linkage.step_fast_with_kinematics`; linkwork runs `linkwork.solve` and
then reads every point's motion with `Solution.point` (both inside the timed region). The
four-bar is also run as a closed-form C loop (`fourbar_loop.c`, compiled here by gcc -O2 into
a temporary folder and called through ctypes): the yardstick of what one core can do.

Before timing, all results are compared point by point; the table reports the largest
differences (position in mm, velocity in mm/s, acceleration in mm/s²), scaled by the
mechanism's size L and the crank speed ω where noted.

    uv run --group bench python bench/bench_pylinkage.py [--samples 100000] [--repeats 15]
        [--only four-bar jansen watt stephenson slider-crank]
"""

from __future__ import annotations

import argparse
import ctypes
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
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
    points: list[str]              # pylinkage's component names, in its order
    build_pylinkage: Callable[[float], tuple]  # angle step -> (linkage, crank)
    theta0: float                  # crank angle at the design position
    #: linkwork's points read in the timed region (default: `points`); the points both have
    #: are compared
    lw_points: list[str] | None = None

    @property
    def read(self) -> list[str]:
        return self.points if self.lw_points is None else self.lw_points

    @property
    def shared(self) -> list[str]:
        return [p for p in self.points if p in self.read]


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


def _pl_rrr(P, a1, a2, pa1, pa2, name):
    return pl.RRRDyad(a1, a2, distance1=_d(P[pa1], P[name]), distance2=_d(P[pa2], P[name]),
                      x=P[name][0], y=P[name][1], name=name)


def _pl_fixed(P, a1, a2, pa1, pa2, name):
    """A point fixed in the link through pa1 and pa2 (at its distance from pa1, at its angle
    from the line pa1 -> pa2)."""
    return pl.FixedDyad(a1, a2, distance=_d(P[pa1], P[name]),
                        angle=_ang(P[pa1], P[name]) - _ang(P[pa1], P[pa2]), name=name)


def _pl_crank(P, centre, tip, step):
    anchor = pl.Ground(*P[centre], name=centre)
    crank = pl.Crank(anchor=anchor, radius=_d(P[centre], P[tip]), angular_velocity=step,
                     initial_angle=_ang(P[centre], P[tip]), name=tip)
    return anchor, crank


def _library(name: str) -> tuple[linkwork.Mechanism, dict[str, np.ndarray]]:
    mech = linkwork.load(f"library:{name}")
    return mech, {k: np.asarray(v) for k, v in mech.points.items()}


def watt_case() -> Case:
    """Watt I six-bar: the crank-rocker with a ternary crank O2AC and a ternary coupler ABD,
    and the dyad C-E-D joining them."""
    mech, P = _library("watt-i-six-bar")

    def build(step: float):
        O2, crank = _pl_crank(P, "O2", "A", step)
        O4 = pl.Ground(*P["O4"], name="O4")
        C = _pl_fixed(P, O2, crank.output, "O2", "A", "C")
        B = _pl_rrr(P, crank.output, O4, "A", "O4", "B")
        D = _pl_fixed(P, crank.output, B, "A", "B", "D")
        E = _pl_rrr(P, C, D, "C", "D", "E")
        link = pl.Linkage([O2, O4, crank, C, B, D, E], name="watt")
        link.set_input_velocity(crank, OMEGA, ALPHA)
        return link, crank

    return Case("Watt six-bar (Watt I)", mech, ["O2", "O4", "A", "C", "B", "D", "E"], build,
                _ang(P["O2"], P["A"]))


def stephenson_case() -> Case:
    """Stephenson III six-bar: the crank-rocker's coupler point E drives the dyad E-F-O6."""
    mech, P = _library("stephenson-iii-six-bar")

    def build(step: float):
        O2, crank = _pl_crank(P, "O2", "A", step)
        O4 = pl.Ground(*P["O4"], name="O4")
        O6 = pl.Ground(*P["O6"], name="O6")
        B = _pl_rrr(P, crank.output, O4, "A", "O4", "B")
        E = _pl_fixed(P, crank.output, B, "A", "B", "E")
        F = _pl_rrr(P, E, O6, "E", "O6", "F")
        link = pl.Linkage([O2, O4, O6, crank, B, E, F], name="stephenson")
        link.set_input_velocity(crank, OMEGA, ALPHA)
        return link, crank

    return Case("Stephenson six-bar (III)", mech, ["O2", "O4", "O6", "A", "B", "E", "F"], build,
                _ang(P["O2"], P["A"]))


def slider_crank_case() -> Case:
    """The offset slider-crank: crank O-A, rod A-B, block B-P on the frame's guide y = 20.
    pylinkage's `RRPDyad` slides B on the line through two ground points of the guide (B's
    and P's design places); linkwork reads its four points O, A, B, P (the block's P too)."""
    mech, P = _library("slider-crank-offset")

    def build(step: float):
        O, crank = _pl_crank(P, "O", "A", step)
        g1 = pl.Ground(*P["B"], name="guide1")
        g2 = pl.Ground(*P["P"], name="guide2")
        B = pl.RRPDyad(crank.output, g1, g2, distance=_d(P["A"], P["B"]), x=P["B"][0],
                       y=P["B"][1], name="B")
        link = pl.Linkage([O, g1, g2, crank, B], name="slider-crank")
        link.set_input_velocity(crank, OMEGA, ALPHA)
        return link, crank

    return Case("slider-crank (offset)", mech, ["O", "guide1", "guide2", "A", "B"], build,
                _ang(P["O"], P["A"]), lw_points=["O", "A", "B", "P"])


# ---------------------------------------------------------------------------- the C loop
C_SOURCE = Path(__file__).with_name("fourbar_loop.c")


def c_four_bar(case: Case):
    """The four-bar of `case` (crank-rocker with coupler point C) as a hand-written C loop,
    compiled here with gcc -O2 into a temporary folder: a function (angles, ω) -> (n, 5, 3, 2)
    positions, velocities and accelerations of O2, O4, A, B, C; None without a C compiler."""
    cc = shutil.which("gcc") or shutil.which("cc")
    if cc is None:
        return None
    P = {k: np.asarray(v, dtype=float) for k, v in case.mech.points.items()}
    with tempfile.TemporaryDirectory(prefix="linkwork-bench-") as tmp:
        lib_path = Path(tmp) / "fourbar_loop.so"
        subprocess.run([cc, "-O2", "-shared", "-fPIC", "-o", str(lib_path), str(C_SOURCE), "-lm"],
                       check=True)
        lib = ctypes.CDLL(str(lib_path))  # stays loaded after the folder is removed
    fn = lib.fourbar
    dp = ctypes.POINTER(ctypes.c_double)
    fn.argtypes = [ctypes.c_long, dp, dp, dp, dp, dp]
    fn.restype = None
    A, B, C = P["A"], P["B"], P["C"]
    r3 = _d(A, B)
    t = (B - A) / r3
    d, e = P["O4"] - A, B - A
    side = math.copysign(1.0, d[0] * e[1] - d[1] * e[0])  # B left of A -> O4: +1
    params = np.array([*P["O2"], *P["O4"], _d(P["O2"], A), r3, _d(P["O4"], B),
                       float(t @ (C - A)), float(t[0] * (C - A)[1] - t[1] * (C - A)[0]), side])

    alphas: dict[int, np.ndarray] = {}

    def run(angles: np.ndarray, omega: np.ndarray) -> np.ndarray:
        n = angles.shape[0]
        alpha = alphas.setdefault(n, np.full(n, ALPHA))
        out = np.empty((n, 5, 3, 2))  # a fresh result, as the libraries return
        fn(n, angles.ctypes.data_as(dp), omega.ctypes.data_as(dp), alpha.ctypes.data_as(dp),
           params.ctypes.data_as(dp), out.ctypes.data_as(dp))
        return out

    return run


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


def _max_diff(a: tuple, b: tuple) -> dict:
    return dict(pos=float(np.abs(a[0] - b[0]).max()), vel=float(np.abs(a[1] - b[1]).max()),
                acc=float(np.abs(a[2] - b[2]).max()),
                finite=all(np.isfinite(x).all() for x in (*a, *b)))


def compare(case: Case, n: int, c_loop=None) -> dict:
    """Both libraries (and the C loop, if given) on the same n inputs; the largest
    differences from linkwork over the points they share."""
    step = 2 * math.pi / n
    link, crank = case.build_pylinkage(step)
    pp, pv, pa = run_pylinkage(link, n)
    # pylinkage advances its crank by the step from atan2 of the previous crank position, so
    # its angles drift from θ0 + k·step by rounding; linkwork is given the angles pylinkage
    # actually reached, so that both solve exactly the same inputs
    ia = case.points.index(crank.name)
    rel = pp[:, ia] - pp[:, 0]  # the crank's anchor is the first ground point in every case
    angles = case.theta0 + np.unwrap(np.arctan2(rel[:, 1], rel[:, 0]) - case.theta0)
    nominal = case.theta0 + step * np.arange(1, n + 1)
    omega = np.full(n, OMEGA)
    lw = stacked(run_linkwork(case.mech, case.shared, angles, omega))
    pick = [case.points.index(p) for p in case.shared]
    out = dict(pl=_max_diff(lw, (pp[:, pick], pv[:, pick], pa[:, pick])),
               L=case.mech.length_scale, drift=float(np.abs(angles - nominal).max()))
    if c_loop is not None:  # the C loop's points are the four-bar's O2, O4, A, B, C
        c = c_loop(angles, omega)
        lw_c = stacked(run_linkwork(case.mech, ["O2", "O4", "A", "B", "C"], angles, omega))
        out["c"] = _max_diff(lw_c, (c[:, :, 0], c[:, :, 1], c[:, :, 2]))
    return out


def _timed(fn) -> tuple[float, float]:
    """Wall-clock and CPU time of one call (the CPU time of this process is the steadier of
    the two where other processes share the CPUs)."""
    t0, c0 = time.perf_counter(), time.process_time()
    fn()
    return time.perf_counter() - t0, time.process_time() - c0


def bench(case: Case, n: int, repeats: int, c_loop=None) -> dict:
    """Best wall-clock and CPU times of both libraries (and the C loop), run alternately so that
    all see the same machine load, and a breakdown of linkwork's time."""
    step = 2 * math.pi / n
    link, _ = case.build_pylinkage(step)
    run_pylinkage(link, 1000)  # numba: compile (or load from its cache) and warm up
    angles = case.theta0 + step * np.arange(1, n + 1)
    omega = np.full(n, OMEGA)
    run_linkwork(case.mech, case.read, angles, omega)  # warm up (plan cache, allocator)
    sol = linkwork.solve(case.mech, angles, velocities=omega)
    runs = dict(pl=lambda: run_pylinkage(link, n),
                lw=lambda: run_linkwork(case.mech, case.read, angles, omega))
    if c_loop is not None:
        c_loop(angles, omega)
        runs["c"] = lambda: c_loop(angles, omega)
    best = {k: (math.inf, math.inf) for k in (*runs, "solve", "read")}

    def keep(key, t):
        best[key] = tuple(min(a, b) for a, b in zip(best[key], t))

    for _ in range(repeats):
        for key, fn in runs.items():
            keep(key, _timed(fn))
    for _ in range(repeats):
        keep("solve", _timed(lambda: linkwork.solve(case.mech, angles, velocities=omega)))
        keep("read", _timed(lambda: [sol.point(p) for p in case.read]))
    return best


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=100_000, help="input angles per run")
    ap.add_argument("--repeats", type=int, default=15, help="timed repeats (the best is kept)")
    ap.add_argument("--only", nargs="*", default=None,
                    help="cases to run (four-bar, jansen, watt, stephenson, slider-crank)")
    args = ap.parse_args(argv)
    n = args.samples
    console = Console(width=120)
    makers = {"four-bar": four_bar_case, "jansen": jansen_case, "watt": watt_case,
              "stephenson": stephenson_case, "slider-crank": slider_crank_case}
    cases = [makers[k]() for k in (args.only or makers)]
    load = os.getloadavg()[0]

    acc_table = Table(title=f"Agreement on {n:,} inputs: max |linkwork − other| over the points "
                            "both give and all samples")
    for col in ("mechanism", "other", "points", "position [mm]", "velocity [mm/s]",
                "acceleration [mm/s²]", "relative (÷ L, Lω, Lω²)"):
        acc_table.add_column(col, justify="left" if col in ("mechanism", "other") else "right")
    speed_table = Table(title=f"Input positions solved per second ({n:,} inputs; positions, "
                              f"velocities, accelerations of every point; best of {args.repeats})")
    for col in ("mechanism", "pylinkage", "linkwork", "linkwork / pylinkage",
                "… by CPU time", "C loop", "C / linkwork", "… by CPU time"):
        speed_table.add_column(col, justify="left" if col == "mechanism" else "right")
    parts_table = Table(title="Where linkwork's time goes (best of each, wall-clock ms)")
    for col in ("mechanism", "points", "solve()", "sol.point() × points", "pylinkage", "C loop"):
        parts_table.add_column(col, justify="left" if col == "mechanism" else "right")

    def agreement(name, other, npts, c):
        rel = max(c["pos"] / L, c["vel"] / (L * OMEGA), c["acc"] / (L * OMEGA ** 2))
        acc_table.add_row(name, other, str(npts), f"{c['pos']:.1e}", f"{c['vel']:.1e}",
                          f"{c['acc']:.1e}", f"{rel:.1e}")
        if not c["finite"]:
            console.print(f"[red]{name}: some samples did not assemble ({other} or linkwork)")

    drift = 0.0
    for case in cases:
        c_loop = c_four_bar(case) if case.name.startswith("four-bar") else None
        c = compare(case, n, c_loop)
        drift = max(drift, c["drift"])
        L = c["L"]
        agreement(case.name, "pylinkage", len(case.shared), c["pl"])
        if "c" in c:
            agreement(case.name, "C loop", 5, c["c"])
        b = bench(case, n, args.repeats, c_loop)
        (w_pl, c_pl), (w_lw, c_lw) = b["pl"], b["lw"]
        row = [case.name, f"{n / w_pl / 1e6:.2f} M/s", f"{n / w_lw / 1e6:.2f} M/s",
               f"{w_pl / w_lw:.2f}×", f"{c_pl / c_lw:.2f}×"]
        if "c" in b:
            w_c, c_c = b["c"]
            row += [f"{n / w_c / 1e6:.2f} M/s", f"{w_lw / w_c:.2f}×", f"{c_lw / c_c:.2f}×"]
        else:
            row += ["", "", ""]
        speed_table.add_row(*row)
        parts_table.add_row(case.name, str(len(case.read)), f"{1e3 * b['solve'][0]:.1f}",
                            f"{1e3 * b['read'][0]:.1f}", f"{1e3 * w_pl:.1f}",
                            f"{1e3 * b['c'][0]:.1f}" if "c" in b else "")
        load = max(load, os.getloadavg()[0])
    console.print(acc_table)
    console.print(f"L = the drawing's diagonal, ω = {OMEGA:.4f} rad/s. pylinkage's crank angle "
                  f"drifts by rounding as it steps (here by up to {drift:.1e} rad from θ0 + k·2π/n), "
                  "so linkwork and the C loop are given the angles pylinkage reached.")
    console.print(speed_table)
    console.print("C / linkwork: how many times longer linkwork takes than the C loop.")
    console.print(parts_table)
    load = max(load, os.getloadavg()[0])
    console.print(f"numpy {np.__version__}, pylinkage {pl.__version__}, "
                  f"numba {__import__('numba').__version__}, python {sys.version.split()[0]}, "
                  f"{os.cpu_count()} CPUs, load average up to {load:.1f} while running")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
