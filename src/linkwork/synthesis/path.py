"""Path generation (*Bahnerzeugung*): a four-bar whose coupler point passes through prescribed
points, by optimisation.

Unknowns: the fixed pivots A₀, B₀, the crank a, coupler b and rocker c, the coupler point's
place (p, q) in the coupler's frame (from A, x along AB) and the crank angle θ_j at each point
— or, with prescribed timing (*mit Zuordnung*), one start angle θ₀ and θ_j = θ₀ + Δ_j. For each
point the rocker pin B_j is the meet of the circles about A_j = A₀ + a e^{iθ_j} (radius b) and
about B₀ (radius c) on one assembly σ = ±1, the coupler point C_j = A_j + (p + iq)(B_j − A_j)/b.

Objective: Σ |C_j − T_j|² (`scipy.optimize.least_squares`, trust region with bounds a, b, c ≥
1e-3 of the targets' size); constraint: the chain must assemble at every point with a margin,
kept as a penalty residual 10³·max(0, 10⁻⁴ − h_j²) (lengths in the targets' size) where h_j² is
the squared half-chord of the two circles. Several deterministic starts on both assemblies; the best is kept (the search stops
at the first that meets every target to rounding). Nine unknowns and one angle per point: exact
through up to nine points (five with timing), least squares beyond. The result is turned into a
`linkages.Linkage` (the coupler's poses at the points as positions), so it is checked and
written like any other synthesized linkage.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .burmester import Dyad
from .linkages import Linkage
from .positions import Positions, SynthesisError

__all__ = ["PathGenerator", "path_generator"]

MARGIN = 1e-4  # h² the chain must keep at every target (in the targets' size squared)
PENALTY = 1e3  # weight of the assembly constraint's residual


def _meet(c1: np.ndarray, r1: float, c2: np.ndarray, r2: float, sigma: float):
    """The pin of a dyad: the meet of the circles about c1 (radius r1) and c2 (radius r2), each
    (N, 2), on the side sigma = ±1 of c1→c2, and the squared half-chord h² (< 0: no meet; the
    pin is then the foot of the chord, for the penalty to pull from)."""
    v = c2 - c1
    d2 = np.sum(v * v, axis=1)
    d = np.sqrt(d2)
    along = (r1 * r1 - r2 * r2 + d2) / (2 * d)
    h2 = r1 * r1 - along**2
    u = v / d[:, None]
    n = np.column_stack([-u[:, 1], u[:, 0]])
    return c1 + along[:, None] * u + sigma * np.sqrt(np.maximum(h2, 0.0))[:, None] * n, h2


def _coupler_points(x: np.ndarray, theta: np.ndarray, sigma: float):
    """Pins and coupler points at crank angles theta for the parameters x (see the module)."""
    A0, B0 = x[0:2], x[2:4]
    a, b, c, p, q = x[4:9]
    A = A0 + a * np.column_stack([np.cos(theta), np.sin(theta)])
    B, h2 = _meet(A, b, np.broadcast_to(B0, A.shape), c, sigma)
    e = (B - A) / b
    C = A + p * e + q * np.column_stack([-e[:, 1], e[:, 0]])
    return A, B, C, h2


def _targets(targets, timing):
    """The targets (N, 2), the timing relative to the first (None: free), their size and
    middle, and the targets on the unit scale (the search works there); errors name the
    mistake."""
    T = np.asarray(targets, dtype=float)
    if T.ndim != 2 or T.shape[1] != 2 or T.shape[0] < 3:
        raise InputError(f"give at least three target points as an (N, 2) array, got shape {T.shape}")
    if not np.isfinite(T).all():
        raise InputError("the target points must be finite")
    N = T.shape[0]
    dt = None
    if timing is not None:
        dt = np.asarray(timing, dtype=float).ravel()
        if dt.shape != (N,) or not np.isfinite(dt).all():
            raise InputError(f"timing: give {N} crank angles (radians), one per target")
        dt = dt - dt[0]
    size = float(np.ptp(T, axis=0).max())
    if size <= 0:
        raise SynthesisError("the target points coincide")
    centre = T.mean(axis=0)
    return T, dt, size, centre, (T - centre) / size


@dataclass(frozen=True)
class PathGenerator:
    """The best four-bar found: its parameters, crank angles, the largest distance of its
    coupler point from the targets, and the `Linkage` (checked, written)."""

    linkage: Linkage
    targets: np.ndarray
    angles: np.ndarray
    error: float  # largest |C_j − T_j|
    parameters: np.ndarray
    assembly: int


def path_generator(targets, *, timing=None, starts: int = 24, seed: int = 0,
                   name: str = "Path generator") -> PathGenerator:
    """A four-bar whose coupler point passes through `targets` ((N, 2), N ≥ 3), in their order;
    `timing`: the crank angle of each target relative to the first (radians, N values, the first
    0) to prescribe the timing, else the angles are free."""
    from scipy.optimize import least_squares

    T, dt, size, centre, Tn = _targets(targets, timing)
    N = T.shape[0]

    def angles(z):
        return z[9] + dt if timing is not None else z[9:]

    def residual(z, sigma):
        A, B, C, h2 = _coupler_points(z, angles(z), sigma)
        return np.concatenate([(C - Tn).ravel(), PENALTY * np.maximum(0.0, MARGIN - h2)])

    lo = np.full(9 + (1 if timing is not None else N), -np.inf)
    lo[4:7] = 1e-3
    rng = np.random.default_rng(seed)
    best = None
    around = np.unwrap(np.arctan2(*(Tn - Tn.mean(axis=0)).T[::-1]))
    for k in range(starts):
        sigma = 1.0 if k % 2 == 0 else -1.0
        A0 = rng.uniform(-1.5, 1.5, 2)
        B0 = rng.uniform(-1.5, 1.5, 2)
        a = rng.uniform(0.1, 0.6)
        b, c = rng.uniform(0.5, 2.0, 2)
        p, q = rng.uniform(-1.0, 1.0, 2)
        z0 = [*A0, *B0, a, b, c, p, q]
        if timing is not None:
            z0.append(rng.uniform(-np.pi, np.pi))
        else:
            turn = rng.choice([-1.0, 1.0])
            z0.extend(rng.uniform(-np.pi, np.pi) + turn * (around - around[0]))
        try:
            res = least_squares(residual, np.array(z0), args=(sigma,), bounds=(lo, np.inf),
                                xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=300)
        except ValueError:
            continue
        cost = float(np.max(np.abs(res.fun))) if res.fun.size else 0.0
        if np.isfinite(cost) and (best is None or cost < best[0]):
            best = (cost, res.x, sigma)
        if best is not None and best[0] <= 1e-13:
            break  # through every target to rounding: no start can do better
    if best is None:
        raise SynthesisError("no start converged to a four-bar")
    _, z, sigma = best
    A, B, C, h2 = _coupler_points(z, angles(z), sigma)
    if (h2 < 0).any():
        raise SynthesisError("the best four-bar found does not assemble at every target: try more starts")
    A, B, C = (v * size + centre for v in (A, B, C))
    A0, B0 = z[0:2] * size + centre, z[2:4] * size + centre
    e = B - A
    pos = Positions(np.arctan2(e[:, 1], e[:, 0]), C)  # the coupler's poses: origin at the tracer
    from ..geometry import Point
    lk = Linkage(Dyad(Point.from_xy(A0), Point.from_xy(A[0]), pos), Dyad(Point.from_xy(B0), Point.from_xy(B[0]), pos),
                 name)
    err = float(np.max(np.hypot(*(C - T).T)))
    params = np.concatenate([A0, B0, z[4:7] * size, z[7:9] * size])
    return PathGenerator(lk, T, angles(z), err, params, int(sigma))
