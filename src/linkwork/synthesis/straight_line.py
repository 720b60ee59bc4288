"""Straight-line guidance (*Geradführung*, Pöschl ch. X, Rosenauer ch. VI): linkages whose tracing
point runs (nearly or exactly) on a straight line, designed from requirements, and the
straightness of any point path.

* `straightness`, `path_straightness`: the deviation of a path from a straight line in
  Chebyshev's sense, half the width of the narrowest strip that holds the path (the best line
  runs down its middle; the least-squares line of the sweeps' `straightness` metric is never
  better), over the whole path or over a stroke around an input.
* `ball_point_linkage`: the four-bar at an input with a tracing point at the coupler's Ball
  point (`instant.third_order.ball_point`), where the inflection circle meets the cubic of
  stationary curvature: curvature and its first derivative vanish, the path is straight to the
  third order (four-point contact with its tangent).
* `watt_linkage` (*Wattscher Lenker*, Pöschl §65b eq. 103, Rosenauer §37): equal arms r on
  opposite sides, coupler c, in the middle position a right-angled Z (r² + (c/2)² = (O₁O₂/2)²),
  the coupler's midpoint Q as tracer. Its path is odd about the middle and the y³ term vanishes:
  x = y⁵/(4cr³) + …, so over a stroke s = 2h the deviation is ≈ 4t⁵·h⁵/(4cr³) with t the root
  of 4t⁵ + 5t⁴ = 1 (the best line tilts to equalise the error). From two of arm, coupler and
  deviation the third is found with the engine's path.
* `chebyshev_linkage` (*Tschebyschewscher Lenker*, Rosenauer §36): the crossed four-bar whose
  coupler midpoint passes at one height through the middle position and both stroke ends,
  where a rocker stands at right angles to the frame in line with the coupler: the frame is the
  stroke, and the two conditions give the rockers and the coupler (Chebyshev's 4 : 5 : 2).
* `evans_linkage` (*Evans-Lenker*, Rosenauer §§32–34): the ellipsograph's slider A replaced by
  a long arm E–A, the ellipse of C on AB by the circle through C's positions at the start, the
  middle and the end; three forms by where C lies (between A and B, beyond B, beyond A).
* `hart_straight_line` (Pöschl §66c): Hart's exact straight line from any four-bar O₁ABO₂:
  E = O₁O₂ ∩ AB; F the second meeting point of the circles EAO₁ and EBO₂; C, D where the
  circles' tangents at F cut the cranks; Q, the mirror image of F in the perpendicular bisector
  of CD (CQ = DF, DQ = CF; the isosceles-trapezoid branch), moves exactly on a line ⟂ O₁O₂.

Every design returns a mechanism file (the engine reads it back) and the straightness of its
tracer over the stroke, measured on the engine's path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..model import Mechanism
from ._file import mechanism_file
from ._four_bar import _base, _four_bar_at, _fresh
from .positions import SynthesisError

__all__ = ["Straightness", "StraightLineLinkage", "ball_point_linkage", "chebyshev_linkage",
           "evans_linkage", "hart_straight_line", "path_straightness", "straightness", "watt_deviation_estimate",
           "watt_linkage"]


# ---------------------------------------------------------------------------- the metric
@dataclass(frozen=True)
class Straightness:
    """A path against its best straight line (Chebyshev's sense): `deviation` = half the width
    of the narrowest strip holding the path, the line down its middle through `point` along
    `direction`; `stroke` the path's extent along the line; `inputs` the input range measured
    (a path from a mechanism), else None."""

    deviation: float
    stroke: float
    point: np.ndarray
    direction: np.ndarray
    inputs: tuple[float, float] | None = None

    @property
    def relative(self) -> float:
        """The deviation per unit stroke."""
        return self.deviation / self.stroke if self.stroke > 0 else math.nan

    def as_dict(self) -> dict:
        return {"deviation": self.deviation, "stroke": self.stroke, "relative": self.relative,
                "line_point": self.point.tolist(), "line_direction": self.direction.tolist(),
                **({"inputs": list(self.inputs)} if self.inputs is not None else {})}


def straightness(xy) -> Straightness:
    """The straightness of the points `xy` (N, 2), N ≥ 2 (NaN rows, unreachable samples, are
    left out): the narrowest strip holding them, found among the directions of the convex
    hull's edges (the narrowest strip of a point set has a hull edge on one side)."""
    P = np.asarray(xy, dtype=float)
    if P.ndim != 2 or P.shape[1] != 2:
        raise InputError(f"straightness: give the path as (N, 2) points, got shape {P.shape}")
    P = P[np.isfinite(P).all(axis=1)]
    if len(P) < 2:
        raise InputError("straightness: the path needs at least two finite points")
    c = P.mean(axis=0)
    Q = P - c
    axis = np.linalg.svd(Q, full_matrices=False)[2][0]
    size = float(np.ptp(Q @ axis))
    if size == 0:
        raise InputError("straightness: the path's points coincide")
    normal = np.array([-axis[1], axis[0]])
    candidates = [axis]
    if np.ptp(Q @ normal) > 1e-14 * size and len(P) > 2:
        from scipy.spatial import ConvexHull, QhullError

        try:
            H = Q[ConvexHull(Q).vertices]
        except QhullError:  # collinear to rounding: the main axis is the line
            H = None
        if H is not None:
            E = np.roll(H, -1, axis=0) - H
            keep = np.hypot(*E.T) > 0
            candidates = list(E[keep] / np.hypot(*E[keep].T)[:, None])
            Q = H[keep]  # edge i runs from Q[i]
    D = np.asarray(candidates)
    if len(D) > 1:  # rotating calipers: the vertex farthest from each hull edge, vectorised
        theta = np.unwrap(np.arctan2(D[:, 1], D[:, 0]))
        ext = np.concatenate([theta, theta + 2 * np.pi])
        j = np.searchsorted(ext, theta + np.pi) % len(D)
        cand = (j[:, None] + np.arange(-2, 3)[None, :]) % len(D)
        rel = Q[cand] - Q[:, None, :]
        widths = np.abs(D[:, None, 0] * rel[..., 1] - D[:, None, 1] * rel[..., 0]).max(axis=1)
        d = D[int(np.argmin(widths))]
    else:
        d = D[0]
    n = np.array([-d[1], d[0]])
    if d @ axis < 0:
        d, n = -d, -n
    proj = Q @ n
    mid = 0.5 * (proj.max() + proj.min())
    width = float(np.ptp(proj))
    along = (P - c) @ d
    return Straightness(0.5 * width, float(np.ptp(along)), c + mid * n, d)


def path_straightness(mech: Mechanism, point: str, *, at: float | None = None,
                      stroke: float | None = None, samples: int = 2001) -> Straightness:
    """The straightness of the engine's path of `point` (a point name) of the one-driver
    mechanism `mech`: over its whole motion (`stroke` None), or over the part of the path
    around input `at` (default the design input) that runs ±stroke/2 along the path's tangent
    at `at` (found by bisection on the engine's positions), sampled at `samples` inputs."""
    from ..kinematics import Status, solve, whole_motion

    if point not in mech.points:
        raise InputError(f"mechanism '{mech.name}' has no point '{point}'")
    if len(mech.drivers) != 1:
        raise InputError("path_straightness takes a mechanism with one driver")
    if samples < 3:
        raise InputError(f"samples {samples}: give at least 3")
    if stroke is None:
        sol = whole_motion(mech, step=2 * math.pi / samples)
        return straightness(sol.point(point).position)
    if not (stroke > 0 and math.isfinite(stroke)):
        raise InputError(f"stroke {stroke}: give a positive length")
    d = mech.drivers[0]
    u0 = mech.driver_input_at_design(d) if at is None else float(at)
    s0 = solve(mech, [u0], order=1)
    if s0.status[0] == Status.UNREACHABLE:
        raise SynthesisError(f"mechanism '{mech.name}' cannot be assembled at input {u0:g}")
    X0, v = s0.point(point).position[0].copy(), s0.point(point).velocity[0].copy()
    if np.hypot(*v) == 0:
        raise SynthesisError(f"point '{point}' stands still at input {u0:g}: its path has no tangent there")
    t = v / np.hypot(*v) * (1.0 if (d.law.speed if hasattr(d.law, "speed") else 1.0) >= 0 else -1.0)
    revolute = mech.joint(d.joint).kind == "revolute"
    h = math.radians(0.25) if revolute else stroke / 400
    K = 1440 if revolute else 4000
    ks = np.arange(1, K + 1)

    def along(u):
        s = solve(mech, np.atleast_1d(u), order=1)
        X = s.point(point).position
        out = (X - X0) @ t
        return np.where(s.status == Status.UNREACHABLE, np.nan, out)

    ends = []
    for sign, want in ((-1.0, -0.5 * stroke), (1.0, 0.5 * stroke)):
        lo = hi = None
        flo = 0.0 - want
        start = 0
        while start < K:  # march out in blocks until the path has run `want` along t
            u = u0 + sign * h * np.arange(start + 1, min(start + 96, K) + 1)
            f = along(u) - want
            cross = np.nonzero(np.sign(f) != np.sign(flo))[0]
            bad = np.nonzero(~np.isfinite(f))[0]
            prev = u0 + sign * h * start
            if len(bad) and (not len(cross) or bad[0] <= cross[0]):
                # the input's limit comes first: the stroke may still end just short of it
                good, gone = (u[bad[0] - 1] if bad[0] else prev), u[bad[0]]
                for _ in range(60):
                    mid = 0.5 * (good + gone)
                    fm = float(along(mid)[0]) - want
                    if not np.isfinite(fm):
                        gone = mid
                    elif np.sign(fm) != np.sign(flo):
                        lo, hi = good, mid
                        break
                    else:
                        good = mid
                break
            if len(cross):
                i = cross[0]
                lo, hi = (u[i - 1] if i else prev), u[i]
                break
            flo, start = f[-1], start + 96
        if lo is None:
            raise SynthesisError(f"point '{point}' does not run {abs(want):g} along its tangent "
                                 f"{'before' if sign < 0 else 'after'} input {u0:g}: the stroke is "
                                 "too long for this path")
        for _ in range(8):  # bracket shrinks 32-fold a round, the samples solved at once
            grid = np.linspace(lo, hi, 33)
            f = along(grid) - want
            flip = np.nonzero(np.sign(f[1:]) != np.sign(f[0]))[0]
            i = int(flip[0]) if len(flip) else 31
            lo, hi = grid[i], grid[i + 1]
        ends.append(0.5 * (lo + hi))
    u = np.linspace(ends[0], ends[1], samples)
    sol = solve(mech, u, order=1)
    got = straightness(sol.point(point).position)
    return Straightness(got.deviation, got.stroke, got.point, got.direction, (ends[0], ends[1]))


# ---------------------------------------------------------------------------- designs
@dataclass(frozen=True)
class StraightLineLinkage:
    """A straight-line linkage: its mechanism file `text`, the tracing point's name, the
    lengths that define it, and the tracer's straightness over the stroke (engine)."""

    kind: str
    text: str
    tracer: str
    lengths: dict
    straightness: Straightness | None
    points: dict  # the drawn (design) position's points

    def mechanism(self) -> Mechanism:
        from ..io import load_text

        return load_text(self.text, source=self.kind)


def _four_bar_text(name, description, unit, pts, frame, arm_a, coupler, arm_b, driver, speed):
    """A four-bar file: `pts` in order; `arm_a` = (fixed, moving) etc.; the coupler's points."""
    links = {"frame": list(frame), "arm_a": list(arm_a), "coupler": list(coupler), "arm_b": list(arm_b)}
    joints = {arm_a[0]: ("revolute", ("frame", "arm_a"), ""), arm_a[1]: ("revolute", ("arm_a", "coupler"), ""),
              arm_b[1]: ("revolute", ("coupler", "arm_b"), ""), arm_b[0]: ("revolute", ("arm_b", "frame"), "")}
    return mechanism_file(name=name, description=description, length_unit=unit, points=pts, links=links,
                          joints=joints, driver=driver, speed=speed)


def _positive(value, what: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what}: give a number, got {value!r}") from None
    if not (v > 0 and math.isfinite(v)):
        raise InputError(f"{what} {value}: give a positive length")
    return v


def _finish(kind, text, tracer, lengths, pts, stroke, at=None) -> StraightLineLinkage:
    from ..io import load_text

    mech = load_text(text, source=kind)
    st = path_straightness(mech, tracer, at=at, stroke=stroke) if stroke is not None else None
    return StraightLineLinkage(kind, text, tracer, lengths, st, pts)


def ball_point_linkage(mech: Mechanism, at: float, *, stroke: float | None = None,
                       name: str | None = None) -> StraightLineLinkage:
    """The four-bar `mech` with a tracing point 'U' at its coupler's Ball point at input `at`
    (radians): the file (drawn at `at`) and, with `stroke`, the straightness over it."""
    from ..instant.third_order import ball_point

    fb = _four_bar_at(mech, at, 3)
    U = ball_point(fb.solution, fb.coupler).xy[0]
    if not np.isfinite(U).all():
        raise SynthesisError("the coupler has no single Ball point at this input (it translates, or "
                             "the whole inflection circle has stationary curvature): choose another input")
    pts, links, joints = _base(fb)
    u = _fresh("U", pts)
    pts[u] = U
    links[fb.coupler].append(u)
    from .second_order import _speed

    desc = (f"'{mech.name}' with the tracing point {u} at the coupler's Ball point at input "
            f"{math.degrees(at):.6g}° (inflection circle ∩ cubic of stationary curvature): its path is "
            "straight to the third order there. Written by linkwork's synthesis.")
    text = mechanism_file(name=name or f"{mech.name}, Ball point", description=desc, length_unit=fb.unit,
                          points=pts, links=links, joints=joints, driver=mech.drivers[0].joint,
                          speed=_speed(mech))
    return _finish("Ball-point linkage", text, u, {}, pts, stroke, at)


def _watt_text(arm: float, coupler: float, unit: str, name: str) -> tuple[str, dict]:
    r, c = arm, coupler
    pts = {"Ca": [-r, c / 2], "A": [0.0, c / 2], "Q": [0.0, 0.0], "B": [0.0, -c / 2], "Cb": [r, -c / 2]}
    desc = (f"Watt's straight-line linkage (Pöschl §65b, Rosenauer §37): arms {r:.9g}, coupler {c:.9g}, "
            "drawn in the middle position (arms parallel, at right angles to the coupler, r² + (c/2)² = "
            "(CaCb/2)²); the coupler's midpoint Q runs straight. Written by linkwork's synthesis.")
    return _four_bar_text(name, desc, unit, pts, ("Ca", "Cb"), ("Ca", "A"), ("A", "Q", "B"), ("Cb", "B"),
                          "Ca", "10 rpm"), pts


def watt_deviation_estimate(stroke: float, arm: float, coupler: float) -> float:
    """The leading term of Watt's deviation over `stroke` (module docstring): 4t⁵h⁵/(4cr³)."""
    t = _watt_t()
    h = stroke / 2
    return 4 * t**5 * h**5 / (4 * coupler * arm**3)


def _watt_t() -> float:
    from scipy.optimize import brentq

    return brentq(lambda t: 4 * t**5 + 5 * t**4 - 1, 0.0, 1.0, xtol=1e-15)


def watt_linkage(stroke: float, *, deviation: float | None = None, arm: float | None = None,
                 coupler: float | None = None, frame: float | None = None, unit: str = "mm",
                 name: str = "Watt's straight-line linkage") -> StraightLineLinkage:
    """Watt's linkage for a straight `stroke` of the coupler's midpoint: give two of `arm`,
    `coupler`, `deviation` (the largest deviation allowed over the stroke) and `frame` (the
    overall size: the distance of the fixed pivots, frame² = 4·arm² + coupler², Pöschl eq. 103;
    not with deviation); the rest is found, the deviation's partner (it falls as either length
    grows) with the engine's path."""
    from scipy.optimize import brentq

    s = _positive(stroke, "stroke")
    given = [k for k, v in (("arm", arm), ("coupler", coupler), ("deviation", deviation), ("frame", frame))
             if v is not None]
    if len(given) != 2 or set(given) == {"deviation", "frame"}:
        raise InputError("Watt's linkage: give two of arm, coupler, deviation and frame, not deviation "
                         f"with frame (got {', '.join(given) or 'none'})")
    r = None if arm is None else _positive(arm, "arm")
    c = None if coupler is None else _positive(coupler, "coupler")
    if frame is not None:
        f = _positive(frame, "frame")
        if (r is not None and 2 * r >= f) or (c is not None and c >= f):
            raise InputError(f"frame {f:g}: the fixed pivots must be farther apart than 2·arm and the "
                             "coupler (frame² = 4·arm² + coupler²)")
        if r is None:
            r = math.sqrt(f * f - c * c) / 2
        else:
            c = math.sqrt(f * f - 4 * r * r)
    if deviation is not None:
        dev = _positive(deviation, "deviation")

        def measured(x):
            rr, cc = (x, c) if r is None else (r, x)
            text, _ = _watt_text(rr, cc, unit, name)
            from ..io import load_text
            try:
                return path_straightness(load_text(text, source="Watt"), "Q", stroke=s).deviation
            except SynthesisError:
                return 1e300  # too short to run the stroke: worse than any requirement

        # the leading term solved for the unknown: a start inside the bracket
        if r is None:
            x0 = (4 * _watt_t()**5 * (s / 2)**5 / (4 * c * dev)) ** (1 / 3)
        else:
            x0 = 4 * _watt_t()**5 * (s / 2)**5 / (4 * r**3 * dev)
        lo, hi = x0 / 2, x0 * 2
        for _ in range(60):
            if measured(lo) > dev:
                break
            lo /= 2
        for _ in range(60):
            if measured(hi) <= dev:
                break
            hi *= 2
        x = brentq(lambda z: math.log(measured(z) / dev), lo, hi, xtol=1e-10 * hi, rtol=1e-12)
        x *= 1 + 1e-9  # just inside the requirement
        if r is None:
            r = x
        else:
            c = x
    text, pts = _watt_text(r, c, unit, name)
    return _finish("Watt's linkage", text, "Q", {"arm": r, "coupler": c, "frame": math.hypot(2 * r, c)},
                   pts, s)


def chebyshev_linkage(stroke: float | None = None, *, deviation: float | None = None, unit: str = "mm",
                      name: str = "Chebyshev's straight-line linkage") -> StraightLineLinkage:
    """Chebyshev's straight-line linkage for a straight `stroke` of the coupler's midpoint M (or,
    with `deviation`, the longest stroke that keeps within it).
    Frame d = stroke (M's ends lie above the fixed pivots); the rockers c and coupler b follow
    from Chebyshev's two conditions: (i) at a stroke end a rocker stands at right angles to the
    frame with the coupler in line with it, d² + (c − b)² = c²; (ii) M is there at the height it
    has in the symmetric middle position, c − b/2 = √(c² − ((d + b)/2)²)."""
    from scipy.optimize import fsolve

    if (stroke is None) == (deviation is None):
        raise InputError("Chebyshev's linkage: give the stroke or the deviation allowed over it (its "
                         "proportions are fixed, so its deviation grows with its size)")
    if deviation is not None:
        # the deviation per stroke of the proportions, measured by the engine on one of unit size
        per = chebyshev_linkage(1.0, unit=unit).straightness.relative
        d = _positive(deviation, "deviation") / per
        return chebyshev_linkage(d, unit=unit, name=name)
    d = _positive(stroke, "stroke")

    def conditions(z):
        c, b = z
        return [d**2 + (c - b) ** 2 - c**2, (c - b / 2) ** 2 - (c**2 - ((d + b) / 2) ** 2)]

    (c, b), info, ok, msg = fsolve(conditions, [1.5 * d, 0.4 * d], full_output=True, xtol=1e-14)
    if ok != 1 or not (c > 0 and b > 0):
        raise SynthesisError(f"Chebyshev's conditions have no solution from the start used: {msg}")
    h = math.sqrt(c**2 - ((d + b) / 2) ** 2)
    pts = {"O2": [0.0, 0.0], "O4": [d, 0.0], "A": [(d + b) / 2, h], "M": [d / 2, h], "B": [(d - b) / 2, h]}
    desc = (f"Chebyshev's straight-line linkage (Rosenauer §36): crossed four-bar, frame {d:.9g}, rockers "
            f"{c:.9g}, coupler {b:.9g}, drawn in the symmetric middle position; the coupler's midpoint M "
            "runs straight over the frame's length. Written by linkwork's synthesis.")
    text = _four_bar_text(name, desc, unit, pts, ("O2", "O4"), ("O2", "A"), ("A", "M", "B"), ("O4", "B"),
                          "O2", "10 rpm")
    # the stroke ends where the driving rocker reaches its limit (coupler and the other rocker in
    # line): measured to just short of it, where the path still has samples on both sides
    return _finish("Chebyshev's linkage", text, "M", {"frame": d, "rocker": c, "coupler": b}, pts,
                   d * (1 - 1e-6))


def evans_linkage(stroke: float, *, angle: float = math.radians(45.0), fraction: float = 0.7,
                  lever: float | None = None, deviation: float | None = None, unit: str = "mm",
                  name: str = "Evans straight-line linkage") -> StraightLineLinkage:
    """Evans's linkage (Rosenauer §§32–34) for a straight `stroke` of B along the vertical
    through O: the ellipsograph bar AB = stroke / (2 sin angle) swinging ±`angle` (≤ 45° as the
    seed advises, at most 80° here) about the horizontal, C = A + fraction·(B − A) (between A and
    B: first form; beyond B, > 1: second; beyond A, < 0: third), D on line AO equidistant from C
    at the start and C′ in the middle, E on the perpendicular bisector of A's two places at
    `lever` (default 4·AB) below line AO. Drawn in the middle position (B at O), driven at D.
    With `deviation` instead of `lever`: the shortest lever that keeps the deviation over the
    stroke within it (the deviation falls as the lever grows, towards the floor of the circle
    arc standing in for the ellipse; a deviation below that floor is refused)."""
    s = _positive(stroke, "stroke")
    if deviation is not None:
        if lever is not None:
            raise InputError("Evans's linkage: give the lever or the deviation allowed, not both")
        from scipy.optimize import brentq

        dev = _positive(deviation, "deviation")
        L = s / (2 * math.sin(float(angle)))

        def excess(x):  # log of the measured deviation over the allowed one, lever = L·e^x
            got = evans_linkage(s, angle=angle, fraction=fraction, lever=L * math.exp(x), unit=unit)
            return math.log(got.straightness.deviation / dev)

        lo, hi = math.log(0.25), math.log(1e4)
        if excess(hi) > 0:
            raise SynthesisError(f"deviation {dev:g}: even a lever of 10⁴·AB leaves more (the circle arc "
                                 "about D stands in for the ellipse); allow more, or change the fraction or "
                                 "the swing")
        if excess(lo) <= 0:
            return evans_linkage(s, angle=angle, fraction=fraction, lever=L * math.exp(lo), unit=unit, name=name)
        x = brentq(excess, lo, hi, xtol=1e-10)
        return evans_linkage(s, angle=angle, fraction=fraction, lever=L * math.exp(x) * (1 + 1e-9), unit=unit,
                             name=name)
    a = float(angle)
    if not (0 < a <= math.radians(80)):
        raise InputError(f"angle {math.degrees(a):g}°: give the bar's swing in (0°, 80°]")
    k = float(fraction)
    if not math.isfinite(k) or abs(k - 0.5) < 1e-9 or k == 0 or k == 1:
        raise InputError(f"fraction {k:g}: C must not be A, B or AB's midpoint (whose ellipse is a "
                         "circle about O, the exact elliptic linkage)")
    L = s / (2 * math.sin(a))
    e = 4 * L if lever is None else _positive(lever, "lever")
    A_start, B_start = np.array([-L * math.cos(a), 0.0]), np.array([0.0, L * math.sin(a)])
    A_mid = np.array([-L, 0.0])
    C_start = A_start + k * (B_start - A_start)
    C_mid = A_mid + k * (np.zeros(2) - A_mid)
    # D on the x-axis with |D − C_start| = |D − C_mid|
    xD = (C_start @ C_start - C_mid @ C_mid) / (2 * (C_start[0] - C_mid[0]))
    E = np.array([0.5 * (A_start[0] + A_mid[0]), -e])
    form = "first" if 0 < k < 1 else ("second" if k > 1 else "third")
    pts = {"E": E.tolist(), "A": A_mid.tolist(), "C": C_mid.tolist(), "B": [0.0, 0.0], "D": [xD, 0.0]}
    desc = (f"Evans straight-line linkage, {form} form (Rosenauer §§32–34): bar AB = {L:.9g} swinging "
            f"±{math.degrees(a):.6g}°, C at {k:g}·AB from A, arm EA = {math.hypot(*(A_mid - E)):.9g}, rocker "
            f"DC = {math.hypot(*(C_mid - [xD, 0.0])):.9g}; drawn in the middle position, B runs straight "
            "along the vertical through O. Written by linkwork's synthesis.")
    text = _four_bar_text(name, desc, unit, pts, ("E", "D"), ("E", "A"), ("A", "C", "B"), ("D", "C"),
                          "D", "10 rpm")
    lengths = {"bar": L, "fraction": k, "arm": float(np.hypot(*(A_mid - E))),
               "rocker": float(np.hypot(*(C_mid - [xD, 0.0])))}
    return _finish(f"Evans linkage ({form} form)", text, "B", lengths, pts, s * (1 - 1e-9))


def _circle(p, q, r):
    """Centre of the circle through three points (None when collinear)."""
    (ax, ay), (bx, by), (cx, cy) = p, q, r
    dd = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    if abs(dd) <= 1e-12 * max(np.ptp([ax, bx, cx]), np.ptp([ay, by, cy])) ** 2:
        return None
    a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    return np.array([(a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / dd,
                     (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / dd])


def _meet(p, u, q, w):
    """Intersection of the lines p + s·u and q + t·w (None when parallel)."""
    den = u[0] * w[1] - u[1] * w[0]
    if abs(den) <= 1e-12 * np.hypot(*u) * np.hypot(*w):
        return None
    s = ((q - p)[0] * w[1] - (q - p)[1] * w[0]) / den
    return p + s * u


def hart_straight_line(mech: Mechanism, at: float | None = None, *,
                       name: str | None = None) -> StraightLineLinkage:
    """Hart's exact straight line (Pöschl §66c) from the four-bar `mech`, constructed at input
    `at` (radians, default the design input): the six-bar file (drawn at `at`) with the tracer
    Q, and Q's straightness over the whole motion (engine)."""
    from .second_order import _speed

    if len(mech.drivers) != 1:
        raise InputError(f"mechanism '{mech.name}': give a four-bar of revolute pairs with one driver")
    u0 = mech.driver_input_at_design(mech.drivers[0]) if at is None else float(at)
    fb = _four_bar_at(mech, u0, 1)
    O1, A, B, O2 = fb.A0, fb.A, fb.B, fb.B0
    scale = max(np.hypot(*(O2 - O1)), np.hypot(*(B - A)))
    E = _meet(O1, O2 - O1, A, B - A)
    if E is None:
        raise SynthesisError("the coupler is parallel to the frame at this input: E = O1O2 ∩ AB is at "
                             "infinity; choose another input")
    ca, cb = _circle(E, A, O1), _circle(E, B, O2)
    if ca is None or cb is None:
        raise SynthesisError("E coincides with a pivot (a circle EAO1 or EBO2 degenerates); choose another input")
    # F: the second meeting point, E mirrored in the line of centres
    w = cb - ca
    F = ca + ((E - ca) @ w) / (w @ w) * w * 2 - (E - ca)
    if np.hypot(*(F - E)) <= 1e-9 * scale:
        raise SynthesisError("the circles EAO1 and EBO2 touch at E (no second point F); choose another input")
    ta, tb = np.array([-(F - ca)[1], (F - ca)[0]]), np.array([-(F - cb)[1], (F - cb)[0]])
    C = _meet(F, ta, O1, A - O1)
    D = _meet(F, tb, O2, B - O2)
    if C is None or D is None:
        raise SynthesisError("a tangent at F is parallel to its crank; choose another input")
    m, n = 0.5 * (C + D), D - C
    if np.hypot(*n) <= 1e-9 * scale:
        raise SynthesisError("C and D coincide; choose another input")
    nn = n / np.hypot(*n)
    Q = F - 2 * ((F - m) @ nn) * nn  # mirror in the perpendicular bisector of CD
    pts, links, joints = _base(fb)
    c, d, q = _fresh("C", pts), _fresh("D", pts), _fresh("Q", pts)
    pts[c], pts[d], pts[q] = C, D, Q
    links[fb.crank].append(c)
    links[fb.rocker].append(d)
    lc, ld = _fresh("link_cq", links), _fresh("link_dq", links)
    links[lc], links[ld] = [c, q], [d, q]
    joints[_fresh(c, joints)] = ("revolute", (fb.crank, lc), f'point = "{c}"')
    joints[_fresh(d, joints)] = ("revolute", (fb.rocker, ld), f'point = "{d}"')
    joints[_fresh(q, joints)] = ("revolute", (lc, ld), f'point = "{q}"')
    desc = (f"Hart's exact straight line (Pöschl §66c) from '{mech.name}' at input {math.degrees(u0):.6g}°: "
            f"C and D on the cranks where the tangents at F = {F[0]:.9g}, {F[1]:.9g} to the circles EAO1 and "
            f"EBO2 cut them, {q} with {c}{q} = DF and {d}{q} = CF runs on a line at right angles to the frame. "
            "Written by linkwork's synthesis.")
    text = mechanism_file(name=name or f"{mech.name}, Hart's straight line", description=desc,
                          length_unit=fb.unit, points=pts, links=links, joints=joints,
                          driver=mech.drivers[0].joint, speed=_speed(mech))
    from ..io import load_text

    six = load_text(text, source="Hart's straight line")
    st = path_straightness(six, q)
    lengths = {"CQ": float(np.hypot(*(Q - C))), "DQ": float(np.hypot(*(Q - D))),
               "F": F.tolist(), "C_fraction": float(np.hypot(*(C - O1)) / np.hypot(*(A - O1))),
               "D_fraction": float(np.hypot(*(D - O2)) / np.hypot(*(B - O2)))}
    return StraightLineLinkage("Hart's straight line", text, q, lengths, st, pts)
