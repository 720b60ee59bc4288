"""Metrics of one design over its motion: one number (or a class name) per design.

`evaluate` reduces one design's solution; `evaluate_designs` a chunk of designs at once, each
metric over arrays of (designs, samples) (the designs' samples padded to the longest), with the
same values to rounding.

Each metric is named on the command line as `KIND[:ARGUMENT]` (see `METRICS`) or, for any
quantity of the JSON output, `POINT.QUANTITY:REDUCTION` / `LINK.QUANTITY:REDUCTION` with the
quantities x, y, vx, vy, ax, ay, speed, acceleration of a point and angle, omega, alpha of a
link, reduced by min, max, range or rms. Only samples with status ok enter a metric; a design
without any has NaN. Angles are in degrees, lengths in the file's unit, time in seconds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, LinkworkError
from ..kinematics import Solution, Status
from ..model import Mechanism, Revolute

#: metric kinds, their argument and unit ("L" = the file's length unit)
METRICS = {
    "grashof": ("", "", "Grashof class and type of the mechanism's (first) four-link loop"),
    "transmission-min": ("JOINT", "deg", "least transmission angle at a hinge over the motion"),
    "transmission-max": ("JOINT", "deg", "largest transmission angle at a hinge over the motion"),
    "input-range": ("", "deg", "range of the (first) driver's input: 360 for a crank, a rocker's swing"),
    "stroke": ("POINT", "L", "extent of a point's path along its main direction"),
    "time-ratio": ("POINT", "", "input taken by a point's longer stroke over its shorter one "
                               "(a crank turning once, the point reversing twice)"),
    "straightness": ("POINT", "L", "largest distance of a point's path from its best straight line"),
    "circularity": ("POINT", "L", "largest distance of a point's path from its best circle"),
    "max-speed": ("POINT", "L/s", "largest speed of a point"),
    "max-acceleration": ("POINT", "L/s^2", "largest acceleration of a point"),
}
POINT_QUANTITIES = {"x": "L", "y": "L", "vx": "L/s", "vy": "L/s", "ax": "L/s^2", "ay": "L/s^2",
                    "speed": "L/s", "acceleration": "L/s^2"}
LINK_QUANTITIES = {"angle": "deg", "omega": "deg/s", "alpha": "deg/s^2"}
REDUCTIONS = ("min", "max", "range", "rms")


@dataclass(frozen=True)
class Metric:
    """A parsed metric: its column name, kind, argument and unit template."""

    name: str
    kind: str
    arg: str = ""
    quantity: str = ""
    reduction: str = ""
    unit: str = ""

    def unit_in(self, length_unit: str) -> str:
        return self.unit.replace("L", length_unit)


def parse_metric(mech: Mechanism, text: str) -> Metric:
    """The metric `text` for `mech`, or an `InputError` naming the mistake."""
    text = text.strip()
    kind, _, arg = text.partition(":")
    if kind in METRICS:
        need, unit, _ = METRICS[kind]
        if need and not arg:
            raise InputError(f"--metric {text}: '{kind}' needs a {need.lower()}: {kind}:{need}")
        if not need and arg:
            raise InputError(f"--metric {text}: '{kind}' takes no argument")
        if need == "POINT" and arg not in mech.points:
            raise InputError(f"--metric {text}: there is no point '{arg}' (points: {', '.join(sorted(mech.points))})")
        if need == "JOINT":
            j = next((j for j in mech.joints if j.name == arg), None)
            if not isinstance(j, Revolute):
                raise InputError(f"--metric {text}: '{arg}' is not a revolute joint of the mechanism")
            _arms(mech, j)
        return Metric(text, kind, arg, unit=unit)
    obj, dot, qty = kind.rpartition(".")
    if dot and arg in REDUCTIONS:
        if obj in mech.points and qty in POINT_QUANTITIES:
            return Metric(text, "point", obj, qty, arg, POINT_QUANTITIES[qty])
        if obj in mech.link_names and qty in LINK_QUANTITIES:
            return Metric(text, "link", obj, qty, arg, LINK_QUANTITIES[qty])
    raise InputError(f"--metric {text}: unknown metric; use one of {', '.join(METRICS)} (with :POINT or "
                     f":JOINT where needed), or POINT.{{{','.join(POINT_QUANTITIES)}}}:REDUCTION or "
                     f"LINK.{{{','.join(LINK_QUANTITIES)}}}:REDUCTION with REDUCTION one of "
                     f"{', '.join(REDUCTIONS)}")


def _arms(mech: Mechanism, j: Revolute) -> tuple[str, str]:
    """For the hinge `j` between links L1 and L2, a point of each link on another hinge of it:
    the transmission angle is the angle at `j` between the lines to them."""
    out = []
    for link in j.links:
        other = next((k.point for k in mech.joints if isinstance(k, Revolute) and k is not j
                      and link in k.links and k.point != j.point), None)
        if other is None:
            raise InputError(f"--metric transmission:{j.name}: link '{link}' has no other hinge, "
                             "so the transmission angle there is undefined")
        out.append(other)
    return out[0], out[1]


def _reduce(v: np.ndarray, how: str) -> float:
    v = v[np.isfinite(v)]
    if v.size == 0:
        return math.nan
    return float({"min": np.min, "max": np.max, "range": np.ptp,
                  "rms": lambda a: np.sqrt(np.mean(a * a))}[how](v))


def _main_axis(xy: np.ndarray) -> np.ndarray:
    c = xy - xy.mean(axis=0)
    return np.linalg.svd(c, full_matrices=False)[2][0]


def _straightness(xy: np.ndarray) -> float:
    """Largest distance from the total-least-squares line (the path's main axis)."""
    c = xy - xy.mean(axis=0)
    n = np.linalg.svd(c, full_matrices=False)[2][1]
    return float(np.abs(c @ n).max())


def _circularity(xy: np.ndarray) -> float:
    """Largest radial distance from the least-squares circle (Kåsa's linear fit)."""
    x, y = xy.T
    A = np.c_[2 * x, 2 * y, np.ones_like(x)]
    (cx, cy, k), *_ = np.linalg.lstsq(A, x * x + y * y, rcond=None)
    R = math.sqrt(max(k + cx * cx + cy * cy, 0.0))
    return float(np.abs(np.hypot(x - cx, y - cy) - R).max())


def _time_ratio(u: np.ndarray, s_dot: np.ndarray) -> float:
    """Longer over shorter input interval between the two reversals (sign changes of the
    velocity along the main axis, interpolated linearly) of one full turn; NaN otherwise."""
    sgn = np.sign(s_dot)
    k = np.flatnonzero(sgn[:-1] * sgn[1:] < 0)
    if len(k) != 2 or abs(u[-1] - u[0]) < 2 * math.pi - 1e-6:
        return math.nan
    t = u[k] + (u[k + 1] - u[k]) * s_dot[k] / (s_dot[k] - s_dot[k + 1])
    a = abs(t[1] - t[0])
    b = 2 * math.pi - a
    return max(a, b) / min(a, b)


def evaluate(mech: Mechanism, sol: Solution, metrics: list[Metric]) -> list:
    """The value of every metric for one solved design (NaN where it is undefined)."""
    ok = sol.status == Status.OK
    out = []
    for m in metrics:
        try:
            out.append(_value(mech, sol, ok, m))
        except LinkworkError:
            out.append(math.nan if m.kind != "grashof" else "")
    return out


def _value(mech: Mechanism, sol: Solution, ok: np.ndarray, m: Metric):
    if m.kind == "grashof":
        return _grashof(mech)
    if m.kind == "input-range":
        return math.degrees(float(np.ptp(sol.inputs[:, 0]))) if len(sol) else math.nan
    if not ok.any():
        return math.nan
    if m.kind in ("transmission-min", "transmission-max"):
        j = mech.joint(m.arg)
        p, q = _arms(mech, j)
        J, P, Q = (sol.point(x).position[ok] for x in (j.point, p, q))
        a, b = P - J, Q - J
        mu = np.degrees(np.arctan2(np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), (a * b).sum(1)))
        return float(mu.min() if m.kind == "transmission-min" else mu.max())
    if m.kind in ("point", "link"):
        return _reduce(_quantity(sol, m)[ok], m.reduction)
    pm = sol.point(m.arg)
    xy = pm.position[ok]
    if m.kind == "stroke":
        return float(np.ptp(xy @ _main_axis(xy))) if len(xy) > 1 else 0.0
    if m.kind == "straightness":
        return _straightness(xy) if len(xy) > 2 else math.nan
    if m.kind == "circularity":
        return _circularity(xy) if len(xy) > 3 else math.nan
    if m.kind == "max-speed":
        return float(np.hypot(*pm.velocity[ok].T).max())
    if m.kind == "max-acceleration":
        return float(np.hypot(*pm.acceleration[ok].T).max())
    if m.kind == "time-ratio":
        if not ok.all():
            return math.nan
        return _time_ratio(np.unwrap(sol.inputs[:, 0]), pm.velocity @ _main_axis(pm.position))
    raise AssertionError(m.kind)


def _grashof(mech: Mechanism, cycles: list | None = None) -> str:
    """Grashof class and type of the first four-link loop ("" if none); `cycles`: the
    structure's loops (`grashof.loop_cycles`), if known."""
    from ..structure.grashof import loops
    try:
        rep = next(iter(loops(mech, cycles)), None)
    except LinkworkError:
        return ""
    return "" if rep is None else " ".join(x for x in (rep.grashof, rep.type) if x)


def _quantity(sol: Solution, m: Metric) -> np.ndarray:
    if m.kind == "link":
        lm = sol.link(m.arg)
        v = {"angle": lm.angle, "omega": lm.omega, "alpha": lm.alpha}[m.quantity]
        return np.degrees(v)
    pm = sol.point(m.arg)
    return {"x": pm.position[:, 0], "y": pm.position[:, 1], "vx": pm.velocity[:, 0],
            "vy": pm.velocity[:, 1], "ax": pm.acceleration[:, 0], "ay": pm.acceleration[:, 1],
            "speed": np.hypot(*pm.velocity.T), "acceleration": np.hypot(*pm.acceleration.T)}[m.quantity]


# ------------------------------------------------------------------ many designs at once
def _padded(parts: list[np.ndarray], N: int, fill=np.nan) -> np.ndarray:
    """(designs, N, …) from per-design arrays of at most N samples, padded with `fill`."""
    out = np.full((len(parts), N) + parts[0].shape[1:], fill, dtype=np.result_type(parts[0], fill))
    for d, a in enumerate(parts):
        out[d, :len(a)] = a
    return out


def _masked(v: np.ndarray, mask: np.ndarray, how: str) -> np.ndarray:
    """`how` (min, max, range, rms) of each row of v (designs, samples) over `mask`; NaN for a
    row without any."""
    n = mask.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        if how == "rms":
            r = np.sqrt(np.where(mask, v * v, 0.0).sum(axis=1) / n)
        else:
            lo, hi = np.where(mask, v, np.inf).min(axis=1), np.where(mask, v, -np.inf).max(axis=1)
            r = {"min": lo, "max": hi, "range": hi - lo}[how]
    return np.where(n > 0, r, np.nan)


def _axes(xy: np.ndarray, mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per design, its path's samples `xy` (designs, samples, 2) over `mask` centred on their
    mean (zero elsewhere), and the right singular vectors (designs, 2, 2) of those: the path's
    main axis first (`_main_axis` of each design)."""
    n = np.maximum(mask.sum(axis=1), 1)[:, None]
    mean = np.where(mask[..., None], xy, 0.0).sum(axis=1) / n
    c = np.where(mask[..., None], xy - mean[:, None], 0.0)
    return c, np.linalg.svd(c, full_matrices=False)[2]


def _time_ratios(u: np.ndarray, s_dot: np.ndarray, n: np.ndarray) -> np.ndarray:
    """`_time_ratio` of every design (rows of u, s_dot; n samples each, NaN beyond)."""
    sgn = np.sign(s_dot)
    cross = sgn[:, :-1] * sgn[:, 1:] < 0
    last = u[np.arange(len(u)), np.maximum(n - 1, 0)]
    good = (cross.sum(axis=1) == 2) & ~(np.abs(last - u[:, 0]) < 2 * math.pi - 1e-6)
    out = np.full(len(u), np.nan)
    if not good.any():
        return out
    rows, k = np.nonzero(cross[good])
    k = k.reshape(-1, 2)
    uu, ss = u[good], s_dot[good]
    r = np.arange(len(uu))[:, None]
    t = uu[r, k] + (uu[r, k + 1] - uu[r, k]) * ss[r, k] / (ss[r, k] - ss[r, k + 1])
    a = np.abs(t[:, 1] - t[:, 0])
    b = 2 * math.pi - a
    out[good] = np.maximum(a, b) / np.minimum(a, b)
    return out


def evaluate_designs(mechs: list[Mechanism], sols: list[Solution], metrics: list[Metric]) -> list[list]:
    """`evaluate` of each design (mechs[d] solved as sols[d]): its row of metric values. Each
    metric is reduced over arrays of (designs, samples); the Grashof class and the
    circularity's circle fit are taken design by design."""
    D = len(sols)
    if D == 0:
        return []
    n = np.array([len(s) for s in sols])
    N = max(int(n.max()), 1)
    ok = _padded([s.status == Status.OK for s in sols], N, False)
    count = ok.sum(axis=1)
    cache: dict = {}

    def point(name: str, what: str) -> np.ndarray:
        if (name, what) not in cache:
            cache[name, what] = _padded([getattr(s.point(name), what) for s in sols], N)
        return cache[name, what]

    cols = []
    for m in metrics:
        try:
            cols.append(_column(mechs, sols, ok, count, n, N, point, m))
        except LinkworkError:  # as `evaluate`: design by design, NaN where it fails
            cols.append([evaluate(mech, s, [m])[0] for mech, s in zip(mechs, sols)])
    return [list(r) for r in zip(*cols)]


def _column(mechs, sols, ok, count, n, N, point, m: Metric) -> list:
    """One metric of every design (see `evaluate_designs`)."""
    if m.kind == "grashof":  # the loops of the structure found once, classified per design
        from ..structure.grashof import loop_cycles
        cycles = loop_cycles(mechs[0])
        return [_grashof(mech, cycles) for mech in mechs]
    if m.kind == "input-range":
        return [math.degrees(float(np.ptp(s.inputs[:, 0]))) if len(s) else math.nan for s in sols]
    none = count == 0
    if m.kind in ("transmission-min", "transmission-max"):
        j = mechs[0].joint(m.arg)
        p, q = _arms(mechs[0], j)
        J, P, Q = (point(x, "position") for x in (j.point, p, q))
        a, b = P - J, Q - J
        mu = np.degrees(np.arctan2(np.abs(a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]),
                                   (a * b).sum(-1)))
        v = _masked(mu, ok, "min" if m.kind == "transmission-min" else "max")
    elif m.kind in ("point", "link"):
        q = _padded([_quantity(s, m) for s in sols], N)
        v = _masked(q, ok & np.isfinite(q), m.reduction)
    elif m.kind == "stroke":
        xy = point(m.arg, "position")
        _, vh = _axes(xy, ok)
        s = (xy * vh[:, None, 0]).sum(-1)
        v = np.where(count > 1, _masked(s, ok, "range"), 0.0)
    elif m.kind == "straightness":
        c, vh = _axes(point(m.arg, "position"), ok)
        v = np.where(count > 2, _masked(np.abs((c * vh[:, None, 1]).sum(-1)), ok, "max"), np.nan)
    elif m.kind == "circularity":
        xy = point(m.arg, "position")
        v = np.array([_circularity(xy[d][ok[d]]) if count[d] > 3 else math.nan
                      for d in range(len(sols))])
    elif m.kind in ("max-speed", "max-acceleration"):
        w = point(m.arg, "velocity" if m.kind == "max-speed" else "acceleration")
        v = _masked(np.hypot(w[..., 0], w[..., 1]), ok, "max")
    elif m.kind == "time-ratio":
        full = count == n  # every sample ok
        xy, vel = point(m.arg, "position"), point(m.arg, "velocity")
        _, vh = _axes(xy, ok)
        u = _padded([np.unwrap(s.inputs[:, 0]) for s in sols], N)
        v = np.where(full, _time_ratios(u, (vel * vh[:, None, 0]).sum(-1), n), np.nan)
    else:
        raise AssertionError(m.kind)
    return [math.nan if e else float(x) for e, x in zip(none, v)]
