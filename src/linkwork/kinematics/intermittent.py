"""Intermittent pairs in the solver (Geneva and star wheels, `model.intermittent`).

Which equation holds is decided per sample by the driver's angle relative to the carrier, which
is known before the wheel's group is solved: every sample evaluates the equations of all phases
on jets and keeps its own phase's (`np.where` on masks, no loop over samples):

- pin on a slot (Geneva engaged, star-wheel entry and exit): the pin B lies on the slot's line
  through the wheel's centre C, (B − C) × e = 0 with e the slot's direction turning with the
  wheel; which slot follows from the turn and the group;
- pin gear (star wheel between entry and exit): the pitch circles roll,
  (D − r)·(θ_wheel − θ₀) + r·(δ − δ₀) = 0;
- locked (*Rast*, the locking arc holds the wheel): θ_wheel = its index angle.

So positions (closed form, `wheel_angle`), velocities, accelerations and jerks are exact in each
phase. At entry and exit the wheel's motion has one-sided limits that differ (a velocity jump
for a pin that meets its slot at an angle, an acceleration jump for the shock-free Geneva
wheel): a sample lying exactly on a phase boundary takes the phase that begins there, and
`engagement` reports both limits, from the closed-form transmission (`transmission`), never a
smoothed value.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..model import ConstantSpeed, Mechanism, Revolute
from ..model.intermittent import (DWELL, GEAR, PHASES, SLOT_PHASES, TWO_PI, IndexingSchedule,
                                  indexing_schedule, is_intermittent)
from .jet import Jet

__all__ = ["Engagement", "Event", "contact_normal", "engagement", "is_intermittent", "report",
           "residuals", "row_slope", "transmission", "wheel_angle"]


def schedule(mech: Mechanism, name: str) -> IndexingSchedule:
    return indexing_schedule(mech, mech.joint(name))


def _phase_data(sch: IndexingSchedule, delta: np.ndarray) -> dict[str, np.ndarray]:
    """Per sample (any shape): phase kind, pin index, pitch radius, the locked or starting
    wheel angle and driver rotation of a gear phase, and the slot's direction in the wheel's
    drawing coordinates (x, y)."""
    m, x, idx = sch.locate(delta)
    ph = sch.phases
    kind = np.array([p.kind for p in ph])[idx]
    radius = np.array([p.radius for p in ph])[idx]
    design_tau = sch.advance_at(np.zeros(1))[0]
    tau0 = np.array([p.tau0 for p in ph])[idx] + m * sch.advance - design_tau
    start = np.array([p.start for p in ph])[idx] + m * TWO_PI + sch.origin
    # the slot points from C to M when its pin stands on the line of centres
    centre = np.array([p.centre_tau for p in ph])[idx] + m * sch.advance - design_tau
    ang = sch.gamma + np.pi + centre
    pins = list(sch.pins)
    pin = np.array([pins.index(p.pin) if p.pin else -1 for p in ph])[idx]
    return dict(kind=kind, radius=radius, theta0=-tau0, delta0=start, sx=np.cos(ang),
                sy=np.sin(ang), pin=pin, m=m, idx=idx, x=x)


def _select(masks_and_jets: list[tuple[np.ndarray, Jet]], default: Jet) -> Jet:
    out = default.c
    for mask, jet in masks_and_jets:
        out = np.where(mask[None], jet.c, out)
    return Jet(out)


def residuals(mech: Mechanism, j, pose, point, rotate) -> list[Jet]:
    """The pair's one equation (length units) on the jets `pose(link)` gives, per sample the
    one of its phase."""
    sch = schedule(mech, j.name)
    driver, wheel = j.links
    th_c, th_d, th_w = pose(j.carrier)[2], pose(driver)[2], pose(wheel)[2]
    delta = th_d - th_c
    rel = th_w - th_c
    f = _phase_data(sch, delta.c[0])
    L = mech.length_scale
    locked = (rel - f["theta0"]) * L
    rho = np.where(f["kind"] == GEAR, sch.D - f["radius"], 0.0)
    gear = (rel - f["theta0"]) * rho + (delta - f["delta0"]) * f["radius"]
    # the pin on its slot: each pin's equation, kept where that pin is on a slot
    Cx, Cy = point(pose, j.carrier, sch.C)
    ex, ey = rotate(pose, wheel, (f["sx"], f["sy"]))
    slot = locked
    on_slot = np.isin(f["kind"], SLOT_PHASES)
    for i, p in enumerate(sch.pins):
        here = on_slot & (f["pin"] == i)
        if here.any():
            Bx, By = point(pose, driver, mech.points[p])
            slot = _select([(here, (Bx - Cx) * ey - (By - Cy) * ex)], slot)
    return [_select([(f["kind"] == GEAR, gear), (on_slot, slot)], locked)]


def row_slope(mech: Mechanism, j, delta: np.ndarray) -> np.ndarray:
    """|∂(the pair's equation)/∂θ_wheel| at driver rotations δ: the length scale while locked,
    D − r in the pin gear, the pin's distance |CB| from the wheel's centre on a slot."""
    sch = schedule(mech, j.name)
    f = _phase_data(sch, delta)
    v = np.array([p.v0 - p.start for p in sch.phases])[f["idx"]] + f["x"]  # the pin's angle
    r = f["radius"]
    on_slot = np.sqrt(sch.D**2 + r * r - 2 * sch.D * r * np.cos(v))
    out = np.where(f["kind"] == GEAR, sch.D - r, np.where(np.isin(f["kind"], SLOT_PHASES), on_slot,
                                                          mech.length_scale))
    return np.where(np.isfinite(delta), out, np.nan)


def pivots(mech: Mechanism, j) -> tuple[str, str]:
    """The points of the driver's and the wheel's revolutes on the carrier."""
    out = []
    for link in j.links:
        out.append(next(r.point for r in mech.joints
                        if isinstance(r, Revolute) and set(r.links) == {link, j.carrier}))
    return out[0], out[1]


def wheel_angle(mech: Mechanism, j, delta: np.ndarray) -> np.ndarray:
    """Closed-form angle of the wheel relative to the carrier (from the drawing) at driver
    rotations δ relative to the carrier (from the drawing)."""
    return schedule(mech, j.name).wheel_angle(delta)


# ---------------------------------------------------------------------------- transmission
def _psi_rates(v: np.ndarray, lam: float, order: int) -> np.ndarray:
    """dᵏψ/dvᵏ, k = 1 … order, of tan ψ = λ sin v/(1 − λ cos v): ψ′ = λ(cos v − λ)/(1 − 2λ cos v
    + λ²), its own derivatives from a jet in v."""
    vj = Jet(np.stack([v, np.ones_like(v)] + [np.zeros_like(v)] * max(order - 2, 0))[:max(order, 2)])
    c, _ = vj.cos_sin()
    d1 = (c - lam) * lam * ((c * (-2 * lam)) + (1 + lam * lam)).reciprocal()
    return np.stack([d1.derivative(k) for k in range(order)])


def transmission(mech: Mechanism, j, delta, order: int = 3, *, phase: np.ndarray | None = None
                 ) -> np.ndarray:
    """(order+1, N): the wheel's angle relative to the carrier and its derivatives with respect
    to the driver's rotation δ (the kinematic coefficients, *Übersetzungen*), in closed form.
    `phase` (indices into the schedule's phases) evaluates a given phase's law instead of the
    one each δ falls in (for one-sided limits at a boundary)."""
    sch = schedule(mech, j.name)
    delta = np.atleast_1d(np.asarray(delta, dtype=float))
    m, x, idx = sch.locate(delta, phase)
    out = np.zeros((order + 1,) + delta.shape)
    out[0] = -(sch.advance_at(delta, phase) - sch.advance_at(np.zeros(1))[0])
    for k, ph in enumerate(sch.phases):
        on = idx == k
        if order == 0 or not on.any() or ph.kind == DWELL:
            continue
        if ph.kind == GEAR:
            out[1, on] = -ph.radius / (sch.D - ph.radius)
        else:  # the pin on a slot: tan ψ = λ sin v/(1 − λ cos v)
            out[1:, on] = -_psi_rates(ph.v0 + x[on] - ph.start, ph.radius / sch.D, order)
    return out


def _chain(T: np.ndarray, w: np.ndarray, a: np.ndarray, jk: np.ndarray) -> tuple[np.ndarray, ...]:
    """The wheel's ω, α, jerk from the transmission θ′, θ″, θ‴ and the driver's ω, α, jerk
    (Faà di Bruno to third order)."""
    t1, t2, t3 = T[1], T[2], T[3]
    return (t1 * w, t2 * w * w + t1 * a, t3 * w**3 + 3 * t2 * w * a + t1 * jk)


def _relative_rates(sol, j) -> tuple[np.ndarray, np.ndarray]:
    """(K+1, N) angle and derivatives of the driver and of the wheel relative to the carrier."""
    Dc = sol.pose_derivatives(j.carrier)[..., 2]
    return (sol.pose_derivatives(j.links[0])[..., 2] - Dc,
            sol.pose_derivatives(j.links[1])[..., 2] - Dc)


def report(sol, name: str) -> dict[str, np.ndarray]:
    """Per sample: `phase` (code: index into `model.intermittent.PHASES`, 0 dwell), `slot`
    (the wheel's slot or entry in use, −1 while locked), `driver_angle` and `angle` (the
    driver's and the wheel's rotation relative to the carrier from the drawing), `omega`,
    `alpha` (the wheel's, relative to the carrier) and `ratio` = ω_wheel/ω_driver."""
    mech = sol.mechanism
    j = mech.joint(name)
    sch = schedule(mech, name)
    d, w = _relative_rates(sol, j)
    f = _phase_data(sch, d[0])
    ok = np.isfinite(d[0])
    out = {"phase": np.where(ok, f["kind"], -1), "slot": np.where(ok, sch.slot(f["m"], f["idx"]), -1),
           "driver_angle": d[0], "angle": w[0], "omega": w[1]}
    if sol.order >= 2:
        out["alpha"] = w[2]
    with np.errstate(invalid="ignore", divide="ignore"):
        out["ratio"] = w[1] / d[1]
    return out


def contact_normal(sol, name: str) -> tuple[np.ndarray, np.ndarray]:
    """A point X (N, 2) and unit direction (N, 2) of a line through the relative pole of driver
    and wheel, from the geometry alone: on a slot, the normal to the slot at the pin (Rosenauer
    §65); in the pin gear, the normal to the line of centres at the pitch point (the law of
    gearing puts the flanks' common normal through it); locked, the normal to the line of
    centres at the driver's pivot (the wheel rests on the carrier, so the driver turns about
    its pivot relative to it). The pole lies where this line meets the line of centres."""
    mech = sol.mechanism
    j = mech.joint(name)
    sch = schedule(mech, name)
    d, _ = _relative_rates(sol, j)
    f = _phase_data(sch, d[0])
    Mw = sol.point_on(j.carrier, sch.M).position
    Cw = sol.point_on(j.carrier, sch.C).position
    centres = (Cw - Mw) / sch.D
    X = Mw.copy()
    gear = f["kind"] == GEAR
    X[gear] = Mw[gear] + f["radius"][gear, None] * centres[gear]
    along = centres.copy()
    on_slot = np.isin(f["kind"], SLOT_PHASES)
    for i, p in enumerate(sch.pins):
        here = on_slot & (f["pin"] == i)
        B = sol.point_on(j.links[0], mech.points[p]).position
        X[here] = B[here]
        along[here] = B[here] - Cw[here]
    n = np.stack([-along[:, 1], along[:, 0]], axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return X, n / np.hypot(n[:, 0], n[:, 1])[:, None]


# ---------------------------------------------------------------------------- the report
@dataclass(frozen=True)
class Event:
    """A phase boundary met by the motion: `kind` 'entry' (a pin meets its slot), 'exit' (it
    leaves) or 'transfer' (between slot and pin gear in a star wheel); `angle`: the driver's
    rotation relative to the carrier there (from the drawing), `input` the driver's input value
    there (NaN if the mechanism is not driven at this pair's driver pivot); `before`/`after`:
    the phases; `slot`; the one-sided kinematic coefficients `left`, `right` (dθ/dδ, d²θ/dδ²,
    d³θ/dδ³ of the wheel); the one-sided ω, α, jerk of the wheel (`omega`, `alpha`, `jerk`, each
    (left, right)) at the driver's constant speed (NaN if its law is not a constant speed);
    `samples`: indices of the samples lying on this boundary, with their own one-sided values
    (`at_samples`: (left, right) × (ω, α, jerk) per sample, from each sample's input rates)."""

    kind: str
    angle: float
    input: float
    before: str
    after: str
    slot: int
    left: np.ndarray
    right: np.ndarray
    omega: tuple[float, float]
    alpha: tuple[float, float]
    jerk: tuple[float, float]
    samples: tuple[int, ...] = ()
    at_samples: np.ndarray = field(default_factory=lambda: np.zeros((0, 2, 3)))

    @property
    def velocity_jump(self) -> float:
        return self.omega[1] - self.omega[0]

    @property
    def acceleration_jump(self) -> float:
        return self.alpha[1] - self.alpha[0]


@dataclass(frozen=True)
class Engagement:
    """The phases of an intermittent pair over a solution (`engagement`).

    `phase` (names) and `slot` per sample; `intervals`: per phase of one driver turn, (name,
    start, end) in driver rotation relative to the carrier from the drawing (radians, the turn
    starting at the first group's entry, from `origin` on); `events`: every boundary the
    solution's driver range passes, with one-sided limits; `advance`: the wheel's turn per
    driver turn; `dwell_fraction`: the share of the driver's turn in which the wheel rests."""

    pair: str
    phase: np.ndarray
    slot: np.ndarray
    intervals: tuple[tuple[str, float, float], ...]
    events: tuple[Event, ...]
    advance: float
    dwell_fraction: float


def _event_kind(before: int, after: int) -> str:
    if before == DWELL:
        return "entry"
    if after == DWELL:
        return "exit"
    return "transfer"


def engagement(solution, pair: str, *, tol: float = 1e-9) -> Engagement:
    """Phases, entry and exit of intermittent pair `pair` over `solution`, with the velocity and
    acceleration jumps (left and right limits) at every boundary; a sample within `tol`
    (radians of driver turn) of a boundary is listed at it with both one-sided values."""
    mech = solution.mechanism
    j = mech.joint(pair)
    sch = schedule(mech, pair)
    rep = report(solution, pair)
    names = np.array(PHASES + ("unreachable",))[np.asarray(rep["phase"])]
    d, _ = _relative_rates(solution, j)
    K = d.shape[0] - 1
    rates = [d[k] if k <= K else np.zeros_like(d[0]) for k in range(1, 4)]
    # the driver's constant speed, if the mechanism is driven at this pair's driver pivot
    M = pivots(mech, j)[0]
    drv = next((dd for dd in mech.drivers if getattr(mech.joint(dd.joint), "point", None) == M
                and {dd.driven, dd.base} == {j.links[0], j.carrier}), None)
    speed = drv.law.speed if drv is not None and isinstance(drv.law, ConstantSpeed) else np.nan
    sense = 1.0 if drv is None or drv.driven == j.links[0] else -1.0
    u0 = mech.driver_input_at_design(drv) if drv is not None else np.nan
    ph = sch.phases
    n = len(ph)
    finite = d[0][np.isfinite(d[0])]
    events: list[Event] = []
    if finite.size:
        lo, hi = finite.min() - tol, finite.max() + tol
        m0 = int(np.floor((lo - sch.origin) / TWO_PI)) - 1
        m1 = int(np.floor((hi - sch.origin) / TWO_PI)) + 1
        for m in range(m0, m1 + 1):
            for k in range(n):
                before, after = ph[k - 1] if k else ph[-1], ph[k]
                if before.kind == after.kind == DWELL:
                    continue
                at = sch.origin + m * TWO_PI + after.start
                if not lo <= at <= hi:
                    continue
                sides = [transmission(mech, j, np.array([at]), phase=np.array([i]))[:, 0]
                         for i in ((k - 1) % n, k)]
                # the slot of the engaged side (phase 0 is an entry: its `before` is a dwell)
                slot = int(sch.slot(np.array([m]), np.array([k if after.kind != DWELL else k - 1]))[0])
                w = np.array(speed * sense)
                lim = [_chain(s, w, np.zeros(()), np.zeros(())) for s in sides]
                hit = np.flatnonzero(np.abs(d[0] - at) <= tol)
                at_s = np.array([[_chain(s, *(r[i] for r in rates)) for s in sides]
                                 for i in hit]).reshape(len(hit), 2, 3)
                events.append(Event(_event_kind(before.kind, after.kind), float(at),
                                    float(u0 + sense * at), before.name, after.name, slot,
                                    sides[0][1:], sides[1][1:],
                                    (float(lim[0][0]), float(lim[1][0])),
                                    (float(lim[0][1]), float(lim[1][1])),
                                    (float(lim[0][2]), float(lim[1][2])),
                                    tuple(int(i) for i in hit), at_s))
    events.sort(key=lambda e: e.angle)
    dwell = sum(p.end - p.start for p in ph if p.kind == DWELL) / TWO_PI
    return Engagement(pair, names, rep["slot"],
                      tuple((p.name, p.start + sch.origin, p.end + sch.origin) for p in ph),
                      tuple(events), sch.advance, dwell)
