"""linkwork vs pylinkage on a disc cam, side by side in one process.

One cam, one motion law: the cam's radius is pylinkage's `FunctionProfile` with the cycloidal
law (base radius 40 mm, lift 15 mm; rise over 0–90°, dwell to 180°, return to 270°, dwell), turning
at 60 rpm under a centric translating follower, first with a knife edge, then with a roller
(ρ = 10 mm). pylinkage runs `TranslatingCamFollower` in `Linkage.step` (its cam followers have no
compiled path and no velocities); linkwork solves the cam pair (`type = "cam"`) with the same
profile as a `PolarProfile`, positions, velocities and accelerations of the follower.

Accuracy against closed forms, derived here and not by either library:

- knife edge: the follower's height is the cam's radius under it, y = R(φ), so y′ = R′ω and
  y″ = R″ω² from the law's derivatives;
- roller: the roller centre sits where a circle of radius ρ, centred on the follower's line,
  last touches the cam: y = max over the profile points p(θ) of p·e + √(ρ² − (p × e)²) (e the
  line's direction in the cam), found per sample by a grid, a golden-section search and
  Newton's method; its velocity by the envelope theorem (the partial derivative at the touching point). pylinkage
  puts the roller centre at R(φ) + ρ, which is right only where the radius does not change.

    uv run --group bench python bench/bench_cams.py [--samples 100000] [--repeats 3]
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
from linkwork.geometry.profiles import PolarProfile
from linkwork.model import CamContact, Mechanism, Prismatic, Revolute
from linkwork.model.laws import ConstantSpeed

try:
    import mechanism.cams as mcams
    import pylinkage as pl
    from pylinkage.cam import CycloidalMotionLaw, FunctionProfile
except ImportError:  # pragma: no cover
    sys.exit("pylinkage or mechanism is not installed: run `uv sync --all-groups` or "
             "`uv run --group bench python bench/bench_cams.py`")
from importlib.metadata import version

from linkwork.model.motion_programs import MotionProgram, Segment

OMEGA = 2 * math.pi           # cam speed, rad/s (60 rpm)
BASE, LIFT, RHO = 40.0, 15.0, 10.0
RISE_END, DWELL_END, FALL_END = math.pi / 2, math.pi, 3 * math.pi / 2  # pylinkage's defaults


# ---------------------------------------------------------------------------- the law
def cam_radius(phi: np.ndarray, order: int) -> np.ndarray:
    """R(φ), R′, …, R⁽ᵒʳᵈᵉʳ⁾ of the cycloidal rise–dwell–return–dwell, from s(u) = u − sin(2πu)/2π
    (u the fraction of the rise) and its derivatives."""
    shape = np.shape(phi)
    phi = np.mod(np.atleast_1d(np.asarray(phi, dtype=float)), 2 * np.pi)
    out = np.zeros((order + 1,) + phi.shape)
    out[0] = BASE + LIFT * ((phi >= RISE_END) & (phi < DWELL_END))
    k = 2 * np.pi
    for lo, hi, sense in ((0.0, RISE_END, 1.0), (DWELL_END, FALL_END, -1.0)):
        m = (phi >= lo) & (phi < hi)
        span = hi - lo
        u = (phi[m] - lo) / span
        s = [u - np.sin(k * u) / k, 1 - np.cos(k * u)]
        s += [k ** (j - 1) * np.sin(k * u + (j - 2) * np.pi / 2) for j in range(2, order + 1)]
        out[0][m] = BASE + (0.0 if sense > 0 else LIFT) + sense * LIFT * s[0]
        for j in range(1, order + 1):
            out[j][m] = sense * LIFT * s[j] / span**j
    return out.reshape((order + 1,) + shape)


def profile_radius(theta: np.ndarray, order: int) -> np.ndarray:
    """The cam's polar radius r(θ) in its own drawing: the point at polar angle θ is under the
    follower (on the +y axis) at cam angle φ = π/2 − θ, where pylinkage reads R(φ)."""
    r = cam_radius(np.pi / 2 - np.asarray(theta), order)
    return r * np.array([(-1.0) ** j for j in range(order + 1)]).reshape((-1,) + (1,) * np.ndim(theta))


def linkwork_cam(follower: str) -> Mechanism:
    profile = PolarProfile(profile_radius,
                           breaks=np.mod(np.pi / 2 - np.array([0.0, RISE_END, DWELL_END, FALL_END]),
                                         2 * np.pi))
    y0 = BASE + (RHO if follower == "roller" else 0.0)
    return Mechanism.build(
        name=f"cycloidal cam, {follower}", length_unit="mm",
        points={"O": [0, 0], "Q": [BASE, 0], "C": [0, y0], "F": [0, y0 + 40]},
        links={"frame": ["O"], "cam": ["O", "Q"], "follower": ["C", "F"]},
        joints=[Revolute("O", "O", ("frame", "cam")),
                Prismatic("guide", "F", ("frame", "follower"), np.array([0.0, 1.0])),
                CamContact("K", ("cam", "follower"), "cam", follower, point="C",
                           radius=RHO if follower == "roller" else 0.0)],
        drivers=[{"joint": "O", "law": ConstantSpeed(speed=OMEGA)}], profiles={"cam": profile})


def pylinkage_cam(follower: str, step: float, start: float):
    O = pl.Ground(0.0, 0.0, name="O")
    G = pl.Ground(0.0, 0.0, name="G")
    crank = pl.Crank(anchor=O, radius=1.0, angular_velocity=step, initial_angle=start, name="A")
    profile = FunctionProfile(motion_law=CycloidalMotionLaw(), base_radius=BASE, total_lift=LIFT,
                              rise_start=0.0, rise_end=RISE_END, dwell_high_end=DWELL_END,
                              fall_end=FALL_END)
    f = pl.dyads.TranslatingCamFollower(cam_driver=crank, profile=profile, guide=G,
                                        guide_angle=math.pi / 2,
                                        roller_radius=RHO if follower == "roller" else 0.0, name="C")
    return pl.Linkage([O, G, crank, f], name="cam")


# ---------------------------------------------------------------------------- closed forms
def roller_closed_form(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Height y and dy/dφ (ω = 1) of the roller centre on the follower's line. In the cam's
    drawing the line points along α = π/2 − φ; a circle of radius ρ centred on it at height h
    passes through the profile point at polar angle θ when h = r cos δ + √(ρ² − r² sin²δ),
    δ = θ − α, and the roller rests at the largest such h."""
    alpha = np.pi / 2 - phi

    def h(theta, a):
        r = profile_radius(theta, 0)[0]
        d = theta - a
        rs = r * np.sin(d)
        return np.where(np.abs(rs) <= RHO, r * np.cos(d) + np.sqrt(np.maximum(RHO**2 - rs**2, 0.0)),
                        -np.inf)

    def dh_dtheta(theta, a):
        r, r1 = profile_radius(theta, 1)
        d = theta - a
        sn, cs = np.sin(d), np.cos(d)
        w = np.sqrt(RHO**2 - (r * sn) ** 2)
        return r1 * cs - r * sn - (r * r1 * sn * sn + r * r * sn * cs) / w

    span = math.asin(RHO / BASE) * 1.05
    grid = np.linspace(-span, span, 241)
    best = np.empty_like(phi)
    for lo in range(0, len(phi), 4096):  # a grid around the line, chunked to bound memory
        a = alpha[lo:lo + 4096, None]
        best[lo:lo + 4096] = a[:, 0] + grid[np.argmax(h(a + grid, a), axis=1)]
    # golden-section search on the bracket of the grid's best point
    g = (math.sqrt(5) - 1) / 2
    lo_, hi_ = best - (grid[1] - grid[0]), best + (grid[1] - grid[0])
    x1, x2 = hi_ - g * (hi_ - lo_), lo_ + g * (hi_ - lo_)
    f1, f2 = h(x1, alpha), h(x2, alpha)
    for _ in range(80):
        left = f1 > f2  # the maximum lies in [lo, x2]
        hi_, lo_ = np.where(left, x2, hi_), np.where(left, lo_, x1)
        xn = np.where(left, hi_ - g * (hi_ - lo_), lo_ + g * (hi_ - lo_))
        fn = h(xn, alpha)
        x1, f1, x2, f2 = (np.where(left, xn, x2), np.where(left, fn, f2),
                          np.where(left, x1, xn), np.where(left, f1, fn))
    theta = (lo_ + hi_) / 2
    # the search finds θ to √ε only (h is flat there); Newton's method on ∂h/∂θ = 0 (its
    # derivative by a central difference) gives the digits the velocity needs
    for _ in range(3):
        g0 = dh_dtheta(theta, alpha)
        eps = 1e-6
        theta = theta - g0 * 2 * eps / (dh_dtheta(theta + eps, alpha) - dh_dtheta(theta - eps, alpha))
    y = h(theta, alpha)
    # envelope theorem: dy/dφ = −∂h/∂α at the touching point
    r = profile_radius(theta, 0)[0]
    d = theta - alpha
    w = np.sqrt(RHO**2 - (r * np.sin(d)) ** 2)
    dy = -(r * np.sin(d) + r * r * np.sin(d) * np.cos(d) / w)
    return y, dy


# ---------------------------------------------------------------------------- runners
def run_pylinkage(link, n: int) -> np.ndarray:
    """Positions (n, components, 2) of every component over n steps."""
    return np.asarray(list(link.step(iterations=n)), dtype=float)


def run_linkwork(mech: Mechanism, angles: np.ndarray):
    """Position, velocity and acceleration of the follower (each (n, 2))."""
    return linkwork.solve(mech, angles).point("C")


def mechanism_law(n: int):
    """`mechanism`'s cam: the law's follower displacement, velocity, acceleration and jerk on
    its own grid of n cam angles from 0 (no profile, no follower: the law evaluated)."""
    cam = mcams.Cam(motion=[("rise", LIFT, 90), ("dwell", 90), ("fall", LIFT, 90), ("dwell", 90)],
                    degrees=True, omega=OMEGA, h=2 * np.pi / n)
    return cam, lambda: mcams.Cycloidal(cam.motion, cam.shifts, cam.intervals, cam.conditions,
                                         cam.thetas, omega=cam.omega)


def linkwork_law():
    """The same program in linkwork's cam design (`model.motion_programs`)."""
    q = np.pi / 2
    return MotionProgram([Segment("rise", q, LIFT, "cycloidal"), Segment("dwell", q),
                          Segment("return", q, LIFT, "cycloidal"), Segment("dwell", q)])


def timed(fn) -> float:
    """CPU seconds of this process for fn(): on a machine shared with other jobs the wall
    clock also counts the time spent waiting for a CPU, which moves the ratios by tens of
    per cent from run to run; both libraries run single-threaded here."""
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=100_000, help="cam angles per run")
    ap.add_argument("--repeats", type=int, default=3, help="timed repeats (the best is kept)")
    args = ap.parse_args(argv)
    n = args.samples
    step = 2 * math.pi / n
    start = step / 2  # half a step off the law's breaks, so no sample falls on one
    angles = start + step * np.arange(1, n + 1)
    console = Console(width=120)
    load = os.getloadavg()[0]
    acc = Table(title=f"Accuracy against the closed form, {n:,} cam angles (max |error|)")
    for col in ("follower", "library", "position [mm]", "velocity [mm/s]", "acceleration [mm/s²]"):
        acc.add_column(col, justify="left" if col in ("follower", "library") else "right")
    speed = Table(title=f"Cam angles solved per CPU second ({n:,} angles, best of {args.repeats})")
    for col in ("follower", "pylinkage (positions)", "linkwork (pos., vel., acc.)",
                "linkwork / pylinkage", "linkwork's first solve"):
        speed.add_column(col, justify="left" if col == "follower" else "right")

    for follower in ("knife", "roller"):
        mech = linkwork_cam(follower)
        link = pylinkage_cam(follower, step, start)
        # accuracy: pylinkage's crank angle drifts by rounding as it steps, so its result is
        # compared with the closed form at the angle it actually reached
        P = run_pylinkage(link, n)
        rel = P[:, 2] - P[:, 0]
        pl_phi = start + np.unwrap(np.arctan2(rel[:, 1], rel[:, 0]) - start)
        first = timed(lambda: run_linkwork(mech, angles))  # includes the continuation march
        C = run_linkwork(mech, angles)
        if follower == "knife":
            R = cam_radius(angles, 2)
            want = (R[0], OMEGA * R[1], OMEGA**2 * R[2])
            pl_want = cam_radius(pl_phi, 0)[0]
        else:
            y, dy = roller_closed_form(angles)
            want = (y, OMEGA * dy, None)
            pl_want = roller_closed_form(pl_phi)[0]
        lw_err = [float(np.abs(C.position[:, 1] - want[0]).max()),
                  float(np.abs(C.velocity[:, 1] - want[1]).max()),
                  float(np.abs(C.acceleration[:, 1] - want[2]).max()) if want[2] is not None else None]
        pl_err = float(np.abs(P[:, 3, 1] - pl_want).max())
        fmt = lambda v: "—" if v is None else f"{v:.1e}"  # noqa: E731
        acc.add_row(follower, "linkwork", *map(fmt, lw_err))
        acc.add_row(follower, "pylinkage", fmt(pl_err), "no velocities", "no accelerations")

        best = dict(pl=math.inf, lw=math.inf)
        for _ in range(args.repeats):
            link = pylinkage_cam(follower, step, start)
            best["pl"] = min(best["pl"], timed(lambda: run_pylinkage(link, n)))
            best["lw"] = min(best["lw"], timed(lambda: run_linkwork(mech, angles)))
        r_pl, r_lw = n / best["pl"], n / best["lw"]
        speed.add_row(follower, f"{r_pl / 1e3:.0f} k/s", f"{r_lw / 1e3:.0f} k/s", f"{r_lw / r_pl:.2f}×",
                      f"{first:.2f} s")
    console.print(acc)
    console.print("Closed forms: knife y = R(φ); roller y = max over the profile of the touching "
                  "circle's height (grid, golden section, Newton), y′ by the envelope theorem. "
                  "pylinkage puts the roller centre at R(φ) + ρ.")
    console.print(speed)

    # the law alone: `mechanism` evaluates a motion law's diagrams (it analyses no given cam
    # with a follower), so it is set beside linkwork's own evaluation of the law
    cam, m_run = mechanism_law(n)
    law = linkwork_law()
    th = cam.thetas
    M = m_run()
    R = cam_radius(th, 3)
    scale = (1.0, OMEGA, OMEGA**2, OMEGA**3)
    m_err = [float(np.abs(x - (R[k] - BASE if k == 0 else R[k] * scale[k])).max())
             for k, x in enumerate((M.S, M.V, M.A, M.J))]
    Lw = law.derivatives(th, 3)
    l_err = [float(np.abs(Lw[k] * scale[k] - (R[k] - BASE if k == 0 else R[k] * scale[k])).max())
             for k in range(4)]
    best = dict(m=math.inf, l=math.inf)
    for _ in range(args.repeats):
        best["m"] = min(best["m"], timed(m_run))
        best["l"] = min(best["l"], timed(lambda: law.derivatives(th, 3)))
    tab = Table(title=f"The law alone: s, v, a, j of the follower at {th.size:,} cam angles "
                      f"(best of {args.repeats}; max |error| against the closed form)")
    for col in ("library", "angles per second", "s (mm)", "v (mm/s)", "a (mm/s²)", "j (mm/s³)"):
        tab.add_column(col, justify="left" if col == "library" else "right")
    tab.add_row("mechanism (Cam, Cycloidal)", f"{th.size / best['m'] / 1e6:.2f} M/s",
                *(f"{e:.1e}" for e in m_err))
    tab.add_row("linkwork (MotionProgram)", f"{th.size / best['l'] / 1e6:.2f} M/s",
                *(f"{e:.1e}" for e in l_err))
    console.print(tab)
    console.print("mechanism evaluates the law given to it; it has no analysis of a given cam "
                  "profile under a follower, so it has no row in the tables above.")
    load = max(load, os.getloadavg()[0])
    console.print(f"numpy {np.__version__}, pylinkage {pl.__version__}, mechanism "
                  f"{version('mechanism')}, python {sys.version.split()[0]}, "
                  f"{os.cpu_count()} CPUs, load average up to {load:.1f} while running")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
