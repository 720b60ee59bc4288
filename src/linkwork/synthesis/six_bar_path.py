"""Path generation with six-bars (*Bahnerzeugung mit Sechsgliedern*): a point of a Watt or
Stephenson six-bar through prescribed points, by optimisation from several starts.

Both are a four-bar A₀ABB₀ (crank a, coupler b, rocker c, coupler point D = A + (p + iq)·e_AB)
and a dyad X–Z–Y (lengths g = XZ, h = ZY) whose tracing point P = X + (u + iv)·e_XZ rides on
its first link:

* `watt` (Watt I, the library's `watt-i-six-bar`: the ternary crank and coupler joined at A):
  X = A₀ + (m + in)·e_A₀A on the crank, Y = D on the coupler;
* `stephenson` (Stephenson III, the library's `stephenson-iii-six-bar`): X = D on the coupler,
  Y = O₆ a new frame pivot.

Unknowns: A₀, B₀, a, b, c, p, q, X's or Y's place (m, n or O₆), g, h, u, v (fifteen) and the
crank angle θ_j of each target (or, with prescribed timing, one start angle θ₀ and θ_j = θ₀ +
Δ_j). Each dyad is closed on one assembly σ = ±1 (B from A and B₀ as in `path`, Z from X and
Y alike). Objective: Σ |P_j − T_j|² (`scipy.optimize.least_squares`, trust region with bounds
a, b, c, g, h ≥ 1e-3 of the targets' size); constraints: both loops must assemble at every
target with a margin, each a penalty residual 10³·max(0, 10⁻⁴ − h_j²) as in `path`. Deterministic starts
(`_starts`: random six-bars over the four assembly pairs, each moved by the similarity that fits
its tracer best onto the targets, the best fits first); the best result is kept (the search stops at the first that meets
every target to rounding). Exact through up to fifteen points (fourteen with timing: the
unknowns outnumber the conditions below that), least squares beyond.

The result is written as a mechanism file drawn at the first target and solved by the engine at
the crank angles found: `engine_error` is the largest distance of the engine's tracer from the
targets, the number a caller should trust.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ._file import mechanism_file
from .path import MARGIN, PENALTY, _coupler_points, _meet, _targets
from .positions import SynthesisError

__all__ = ["SixBarPath", "six_bar_path_generator", "KINDS"]

KINDS = ("watt", "stephenson")
UNKNOWNS = 15


def _perp(v: np.ndarray) -> np.ndarray:
    return np.column_stack([-v[:, 1], v[:, 0]])


def _six_bar_points(x: np.ndarray, theta: np.ndarray, s1: float, s2: float, kind: str):
    """Every joint and the tracer at crank angles theta (see the module), and both loops' h²."""
    A, B, D, h2 = _coupler_points(x[:9], theta, s1)
    A0 = x[0:2]
    if kind == "stephenson":
        X, Y = D, np.broadcast_to(x[9:11], D.shape)
    else:
        e = (A - A0) / x[4]
        X, Y = A0 + x[9] * e + x[10] * _perp(e), D
    g, h = x[11], x[12]
    Z, h2b = _meet(X, g, Y, h, s2)
    f = (Z - X) / g
    P = X + x[13] * f + x[14] * _perp(f)
    return {"A": A, "B": B, "D": D, "X": X, "Y": Y, "Z": Z, "P": P}, h2, h2b


@dataclass(frozen=True)
class SixBarPath:
    """The best six-bar found: its file (drawn at the first target), the crank angles at the
    targets, the largest distance from them in the optimiser's model (`error`) and by the
    engine solving the file (`engine_error`), the parameters (module) and assemblies."""

    kind: str
    text: str
    targets: np.ndarray
    angles: np.ndarray
    error: float
    engine_error: float
    parameters: np.ndarray
    assembly: tuple[int, int]

    def mechanism(self):
        from ..io import load_text

        return load_text(self.text, source=f"{self.kind} six-bar path generator")


def six_bar_path_generator(targets, kind: str = "stephenson", *, timing=None, starts: int = 12,
                           seed: int = 0, name: str | None = None, length_unit: str = "mm") -> SixBarPath:
    """A Watt (`kind="watt"`) or Stephenson (`"stephenson"`) six-bar whose tracing point P
    passes through `targets` ((N, 2), N ≥ 3) in their order; `timing`: the crank angle of each
    target relative to the first (radians, N values) to prescribe the timing, else free."""
    from scipy.optimize import least_squares

    if kind not in KINDS:
        raise InputError(f"six-bar kind '{kind}': choose one of {', '.join(KINDS)}")
    if starts < 1:
        raise InputError(f"starts {starts}: give at least 1")
    T, dt, size, centre, Tn = _targets(targets, timing)
    N = T.shape[0]

    def angles(z):
        return z[UNKNOWNS] + dt if dt is not None else z[UNKNOWNS:]

    def residual(z, s1, s2):
        pts, h2, h2b = _six_bar_points(z, angles(z), s1, s2, kind)
        return np.concatenate([(pts["P"] - Tn).ravel(), PENALTY * np.maximum(0.0, MARGIN - h2),
                               PENALTY * np.maximum(0.0, MARGIN - h2b)])

    lo = np.full(UNKNOWNS + (1 if dt is not None else N), -np.inf)
    lo[[4, 5, 6, 11, 12]] = 1e-3
    best = None
    for z0, s1, s2 in _starts(Tn, dt, kind, starts, seed):
        try:
            res = least_squares(residual, z0, args=(s1, s2), bounds=(lo, np.inf),
                                xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=600)
        except ValueError:
            continue
        cost = float(np.max(np.abs(res.fun)))
        if np.isfinite(cost) and (best is None or cost < best[0]):
            best = (cost, res.x, s1, s2)
        if best is not None and best[0] <= 1e-13:
            break  # through every target to rounding: no start can do better
    if best is None:
        raise SynthesisError("no start converged to a six-bar")
    _, z, s1, s2 = best
    th = angles(z)
    pts, h2, h2b = _six_bar_points(z, th, s1, s2, kind)
    if (h2 < 0).any() or (h2b < 0).any():
        raise SynthesisError("the best six-bar found does not assemble at every target: try more starts")
    world = {k: v * size + centre for k, v in pts.items()}
    params = z[:UNKNOWNS].copy()
    params[:4] = params[:4] * size + np.tile(centre, 2)
    params[4:UNKNOWNS] *= size
    if kind == "stephenson":
        params[9:11] += centre
    err = float(np.max(np.hypot(*(world["P"] - T).T)))
    text = _file(kind, world, params, th, name or f"{kind.capitalize()} six-bar path generator", length_unit)
    return SixBarPath(kind, text, T, th, err, _engine_error(text, th, T), params, (int(s1), int(s2)))


def _starts(Tn: np.ndarray, dt, kind: str, starts: int, seed: int):
    """Starting points, best first: random six-bars (on the unit scale) whose tracer, at crank
    angles spread like the targets (or at the prescribed timing), assembles at every target,
    each moved by the similarity (*Ähnlichkeitsabbildung*) that best fits its points onto the
    targets (closed form: T ≈ s·P + t in complex numbers); the `starts` best fits are tried."""
    rng = np.random.default_rng(seed)
    N = len(Tn)
    around = np.unwrap(np.arctan2(*(Tn - Tn.mean(axis=0)).T[::-1]))
    steps = around - around[0] if dt is None else dt
    Tc = Tn[:, 0] + 1j * Tn[:, 1]
    found = []
    for k in range(40 * starts):
        s1, s2 = (1.0, -1.0)[k % 2], (1.0, -1.0)[(k // 2) % 2]
        z = np.concatenate([rng.uniform(-1.0, 1.0, 4), [rng.uniform(0.1, 0.6)], rng.uniform(0.5, 2.0, 2),
                            rng.uniform(-1.0, 1.0, 2),
                            rng.uniform(-1.5, 1.5, 2) if kind == "stephenson" else rng.uniform(-1.0, 1.0, 2),
                            rng.uniform(0.5, 2.0, 2), rng.uniform(-1.0, 1.0, 2)])
        th = rng.uniform(-np.pi, np.pi) + (rng.choice([-1.0, 1.0]) * steps if dt is None else steps)
        pts, h2, h2b = _six_bar_points(z, th, s1, s2, kind)
        if (h2 < MARGIN).any() or (h2b < MARGIN).any():
            continue
        Pc = pts["P"][:, 0] + 1j * pts["P"][:, 1]
        dP, dT = Pc - Pc.mean(), Tc - Tc.mean()
        a = np.vdot(dP, dT) / np.vdot(dP, dP).real
        b = Tc.mean() - a * Pc.mean()
        fit = float(np.sum(np.abs(a * Pc + b - Tc) ** 2))
        # the six-bar moved by T = a·P + b: frame points mapped, lengths scaled, angles turned
        m = abs(a)
        w = z.copy()
        for i in ((0, 1), (2, 3)) + (((9, 10),) if kind == "stephenson" else ()):
            c = a * (z[i[0]] + 1j * z[i[1]]) + b
            w[list(i)] = c.real, c.imag
        w[[4, 5, 6, 7, 8, 11, 12, 13, 14]] *= m
        if kind == "watt":
            w[[9, 10]] *= m
        th = th + np.angle(a)
        found.append((fit, np.concatenate([w, th[:1] if dt is not None else th]), s1, s2))
    found.sort(key=lambda f: f[0])
    for fit, z0, s1, s2 in found[:starts]:
        yield z0, s1, s2


def _file(kind: str, w: dict, params: np.ndarray, th: np.ndarray, name: str, unit: str) -> str:
    """The six-bar drawn at the first target (names as in the library's six-bars)."""
    at = {k: v[0] for k, v in w.items()}
    A0, B0 = params[0:2], params[2:4]
    if kind == "stephenson":
        pts = {"A0": A0, "A": at["A"], "B": at["B"], "B0": B0, "E": at["X"], "F": at["Z"], "O6": params[9:11],
               "P": at["P"]}
        links = {"frame": ["A0", "B0", "O6"], "crank": ["A0", "A"], "coupler": ["A", "B", "E"],
                 "rocker": ["B", "B0"], "link_ef": ["E", "F", "P"], "output": ["F", "O6"]}
        joints = {"E": ("revolute", ("coupler", "link_ef"), ""), "F": ("revolute", ("link_ef", "output"), ""),
                  "O6": ("revolute", ("output", "frame"), "")}
        what = "Stephenson III (the coupler point E joined to the frame pivot O6 by the dyad E-F-O6)"
    else:
        pts = {"A0": A0, "A": at["A"], "C": at["X"], "B": at["B"], "D": at["Y"], "B0": B0, "E": at["Z"],
               "P": at["P"]}
        links = {"frame": ["A0", "B0"], "crank": ["A0", "A", "C"], "coupler": ["A", "B", "D"],
                 "rocker": ["B", "B0"], "link_ce": ["C", "E", "P"], "link_de": ["D", "E"]}
        joints = {"C": ("revolute", ("crank", "link_ce"), ""), "D": ("revolute", ("coupler", "link_de"), ""),
                  "E": ("revolute", ("link_ce", "link_de"), "")}
        what = "Watt I (the ternary crank and coupler joined by the dyad C-E-D)"
    joints = {"A0": ("revolute", ("frame", "crank"), ""), "A": ("revolute", ("crank", "coupler"), ""),
              "B": ("revolute", ("coupler", "rocker"), ""), "B0": ("revolute", ("rocker", "frame"), ""), **joints}
    desc = (f"A {what} six-bar whose point P passes through {len(th)} prescribed points, drawn at the "
            "first; crank angles at the points: " + ", ".join(f"{math.degrees(a):.9g}°" for a in th)
            + ". Written by linkwork's synthesis.")
    return mechanism_file(name=name, description=desc, length_unit=unit, points=pts, links=links, joints=joints,
                          driver="A0", speed="1 rad/s")


def _engine_error(text: str, th: np.ndarray, T: np.ndarray) -> float:
    from ..io import load_text
    from ..kinematics import solve

    mech = load_text(text, source="six-bar path generator")
    sol = solve(mech, th, order=1)
    d = np.hypot(*(sol.point("P").position - T).T)
    return float(np.max(d)) if np.isfinite(d).all() else math.inf
