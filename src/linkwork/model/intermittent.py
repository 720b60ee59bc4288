"""Intermittent pairs: indexing drives whose pair changes with the phase (*Schaltgetriebe*,
Pöschl §25).

`GenevaPair` — the Geneva wheel (*Malteserkreuzgetriebe*): a pin (*Triebstock*) on the driver,
at radius r about the driver's pivot M, runs into one of the n radial slots of the wheel pivoted
at C (centre distance D = |MC|), turns the wheel by 2π/n and leaves; then the locking arcs
(*Sperrbogen*, the cylinder faces sliding on each other) hold the wheel until the pin enters the
next slot. Engaged, the pin lies on the slot's line through C; locked, the wheel keeps its index
angle. The slots lie ±π/n from the line of centres where the pin enters and leaves, so the pin
circle must reach the slot lines, r ≥ D·sin(π/n); for r = D·sin(π/n) the pin enters along the
slot (shock-free, the wheel starts from rest; Pöschl's D_n = a/cos(π/n) with the wheel radius
a); a larger r enters with a jump of the wheel's velocity.

`StarWheelPair` — the star wheel (*Sternradgetriebe*, Pöschl §25b after Bock 1929): the driver
carries groups of pins (*Schaltgruppen*), each group equally spaced on one pitch circle. The
first pin of a group runs into the radial entry slot (*Einlaufschlitz*) and speeds the wheel
up as in a Geneva wheel until it stands on the line of centres at the slot's foot; from there
the pins drive the wheel as a pin gear (*Triebstockverzahnung*, epicycloidal flanks) at the
constant ratio r/(D − r); the last pin leaves by the radial exit slot (*Auslaufschlitz*) and
the wheel comes to rest on its locking arc until the next group. The steps need not be equal
(groups of different sizes) and groups on different pitch circles drive at different speeds.
A group of one pin is a Geneva step. The entry (and exit) slots lie ψₑ from the line of centres
where the pin meets them: ψₑ = asin(r/D) by default (shock-free).

Both pairs remove one freedom (h = 1), whichever phase holds. What holds when is fixed by the
driver's angle relative to the carrier alone (`IndexingSchedule`): the drawing defines the
geometry, and the wheel's angle in the drawing is its angle at the drawn driver angle, so the
slots' places on the wheel follow from the pins' (the wheel needs no drawn slots).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np

from ..errors import ModelError

if TYPE_CHECKING:  # pragma: no cover
    from .mechanism import Mechanism

#: phase codes of `IndexingSchedule.locate` (index into this tuple)
PHASES = ("dwell", "engaged", "entry", "gear", "exit")
DWELL, ENGAGED, ENTRY, GEAR, EXIT = range(5)
SLOT_PHASES = (ENGAGED, ENTRY, EXIT)  # the pin on a radial slot's line
#: relative tolerance on the drawing: pins on one pitch circle, equal spacing, tangent entry
TOL = 1e-7
TWO_PI = 2.0 * np.pi


@dataclass(frozen=True)
class GenevaPair:
    """Pin `pin` of `links[0]` (the driver) in the `slots` radial slots of `links[1]` (the
    wheel); both links are pivoted on `carrier`."""

    name: str
    links: tuple[str, str]
    pin: str
    slots: int
    carrier: str = "frame"
    kind = "geneva"

    @property
    def groups(self) -> tuple[tuple[str, ...], ...]:
        return ((self.pin,),)

    @property
    def entry(self) -> tuple[float, ...]:
        return (np.pi / self.slots,)


@dataclass(frozen=True)
class StarWheelPair:
    """The pin groups `groups` of `links[0]` (the driver) index the star wheel `links[1]`; both
    are pivoted on `carrier`. `entry`: per group, the angle ψₑ (radians) of its entry and exit
    slots from the line of centres where the pin meets them (None: asin(r/D), shock-free)."""

    name: str
    links: tuple[str, str]
    groups: tuple[tuple[str, ...], ...]
    carrier: str = "frame"
    entry: tuple[float | None, ...] | None = None
    kind = "star-wheel"


IntermittentPair = GenevaPair | StarWheelPair


def is_intermittent(j) -> bool:
    return isinstance(j, (GenevaPair, StarWheelPair))


@dataclass(frozen=True)
class Phase:
    """One phase of the driver's turn, from `start` to `end` (driver rotation past the
    schedule's origin, radians, 0 ≤ start < end ≤ 2π).

    `group`: the indexing group (−1 while locked); `pin` and `radius`: the pin on a slot or the
    pitch radius of the pin gear; `v0`: the pin's angle from the line of centres (at M, from M
    towards C, counter-clockwise) at `start`; `tau0`: the wheel's advance at `start` since the
    origin; `centre_tau`: its advance when the slot's pin stands on the line of centres (where
    the slot points from C to M)."""

    kind: int
    start: float
    end: float
    group: int = -1
    pin: str | None = None
    radius: float = 0.0
    v0: float = 0.0
    tau0: float = 0.0
    centre_tau: float = 0.0

    @property
    def name(self) -> str:
        return PHASES[self.kind]


def psi(v, lam: float):
    """Angle of the slot line from the line of centres (at C, from C towards M, in the wheel's
    forward sense) while the pin at angle v and radius λ·D drives it:
    tan ψ = λ sin v / (1 − λ cos v)."""
    return np.arctan2(lam * np.sin(v), 1.0 - lam * np.cos(v))


@dataclass(frozen=True)
class IndexingSchedule:
    """The phases of an intermittent pair over one turn of its driver relative to the carrier.

    The driver's rotation δ (relative to the carrier, from the drawing) runs through `phases`
    from `origin` (the first group's entry) on, period 2π; per turn the wheel advances by
    `advance` (it turns against the driver: the wheel's angle relative to the carrier is
    −(τ(δ) − τ(0)) with the advance τ). `M`, `C`: the pivots (drawing coordinates, in the
    carrier), `D` = |MC|, `gamma` the direction of MC; `pins`: pin -> (radius, angle from MC at
    the drawing); `slots`: how many slots (entries) the wheel has in all."""

    pair: str
    M: np.ndarray
    C: np.ndarray
    D: float
    gamma: float
    origin: float
    phases: tuple[Phase, ...]
    advance: float
    groups: int
    slots: int
    pins: dict

    @property
    def starts(self) -> np.ndarray:
        return np.array([p.start for p in self.phases])

    def locate(self, delta: np.ndarray, phase: np.ndarray | None = None
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(turn m, x, phase index) for driver rotations δ: δ = origin + 2πm + x, 0 ≤ x < 2π.
        A δ on a phase boundary belongs to the phase that begins there. With `phase` (phase
        indices), that phase in the turn where it holds nearest to δ (for one-sided limits at
        its ends)."""
        delta = np.asarray(delta, dtype=float)
        if phase is not None:
            idx = np.broadcast_to(phase, delta.shape)
            mid = np.array([0.5 * (p.start + p.end) for p in self.phases])[idx]
            m = np.round((delta - self.origin - mid) / TWO_PI)
            return m, delta - self.origin - m * TWO_PI, idx
        finite = np.isfinite(delta)
        d = np.where(finite, delta - self.origin, 0.0)
        m = np.floor(d / TWO_PI)
        x = d - TWO_PI * m
        wrap = x >= TWO_PI  # rounding of d − 2πm
        m, x = np.where(wrap, m + 1, m), np.where(wrap, x - TWO_PI, x)
        idx = np.searchsorted(self.starts, x, side="right") - 1
        return m, np.where(finite, x, np.nan), np.clip(idx, 0, len(self.phases) - 1)

    def advance_at(self, delta: np.ndarray, phase: np.ndarray | None = None) -> np.ndarray:
        """The wheel's advance τ(δ) (radians, in its forward sense) since the origin (`phase`:
        by the law of the given phases, see `locate`)."""
        m, x, idx = self.locate(delta, phase)
        tau = np.full(np.shape(x), np.nan)
        for k, ph in enumerate(self.phases):
            on = idx == k
            if not on.any():
                continue
            s = x[on] - ph.start
            if ph.kind == DWELL:
                t = np.full(s.shape, ph.tau0)
            elif ph.kind == GEAR:
                t = ph.tau0 + s * ph.radius / (self.D - ph.radius)
            else:
                lam = ph.radius / self.D
                t = ph.tau0 + psi(ph.v0 + s, lam) - psi(ph.v0, lam)
            tau[on] = t + m[on] * self.advance
        return tau

    def wheel_angle(self, delta: np.ndarray) -> np.ndarray:
        """The wheel's angle relative to the carrier, from the drawing, at driver rotations δ."""
        return -(self.advance_at(delta) - self.advance_at(np.zeros(1))[0])

    def slot_lines(self) -> tuple[tuple[float, float, float], ...]:
        """Every radial slot of the wheel (entry and exit slots of a star wheel) as (direction
        angle in the wheel's drawing coordinates, radius of its foot, radius where the pin
        meets it): the slot points from C to M when its pin stands on the line of centres."""
        design_tau = float(self.advance_at(np.zeros(1))[0])
        out = []
        for m in range(self.slots // self.groups):
            for p in self.phases:
                if p.kind not in SLOT_PHASES:
                    continue
                r, D = p.radius, self.D
                v = p.v0 if p.kind != EXIT else p.end - p.start  # where the pin is at the rim
                rim = float(np.sqrt(D * D + r * r - 2 * D * r * np.cos(v)))
                out.append((self.gamma + np.pi + p.centre_tau + m * self.advance - design_tau,
                            D - r, rim))
        return tuple(out)

    def flanks(self, samples: int = 32) -> tuple[np.ndarray, ...]:
        """The tooth flanks of a star wheel's pin gear (*Zahnflanken der Triebstockverzahnung*),
        each (samples, 2) in the wheel's drawing coordinates, round the whole wheel: the path
        of a pin relative to the wheel while it drives. Pin gearing driven by the pin wheel acts
        in recess only: a group's pins reach the line of centres one after another, each
        driving from there until the next one arrives (one pin pitch β), so its flank is an
        epicycloid arc from the pitch circle's foot (D − r from C) outwards. The last pin of a
        group leaves by the exit slot and draws no flank; a Geneva wheel has none."""
        design_tau = float(self.advance_at(np.zeros(1))[0])
        pins = list(self.pins)
        out = []
        for m in range(self.slots // self.groups):
            for ph in self.phases:
                if ph.kind != GEAR:
                    continue
                d0 = self.origin + ph.start + m * TWO_PI  # the leading pin on the line of centres
                span = ph.end - ph.start
                v0 = {p: _wrap(self.pins[p][1] + d0) for p in pins
                      if abs(self.pins[p][0] - ph.radius) <= TOL * self.D}
                group = sorted((p for p, v in v0.items() if -span - TOL <= v <= TOL),
                               key=lambda p: -v0[p])
                beta = span / (len(group) - 1)
                for i, p in enumerate(group[:-1]):
                    delta = d0 + beta * (i + np.linspace(0.0, 1.0, samples))
                    # the pin in the carrier, then in the wheel turned back by its angle
                    a = self.gamma + self.pins[p][1] + delta
                    B = self.M + ph.radius * np.stack([np.cos(a), np.sin(a)], axis=1) - self.C
                    w = -(self.advance_at(delta) - design_tau)
                    c, s = np.cos(-w), np.sin(-w)
                    out.append(self.C + np.stack([c * B[:, 0] - s * B[:, 1],
                                                  s * B[:, 0] + c * B[:, 1]], axis=1))
        return tuple(out)

    def slot(self, m: np.ndarray, idx: np.ndarray) -> np.ndarray:
        """Which slot (entry) of the wheel a sample's phase uses: 0 … slots − 1, −1 locked. The
        one the first group enters in the turn after the origin is 0."""
        group = np.array([p.group for p in self.phases])[idx]
        k = (m.astype(np.int64) * self.groups + group) % self.slots
        return np.where(group < 0, -1, k)


def _pivot(mech: "Mechanism", pair: IntermittentPair, link: str, role: str) -> str:
    from .mechanism import Revolute

    for j in mech.joints:
        if isinstance(j, Revolute) and set(j.links) == {link, pair.carrier}:
            return j.point
    raise ModelError(f"{pair.kind} pair '{pair.name}': the {role} '{link}' has no revolute pair "
                     f"with the carrier '{pair.carrier}' (its pivot)")


def _entry_phi(r: float, D: float, psi_e: float) -> float:
    """Driver angle from the line of centres at which a pin of radius r meets a slot lying ψₑ
    from the line of centres: where the pin circle cuts the slot line nearer to C. A pin
    circle drawn tangent to the slot line (to the drawing's precision) enters along the slot,
    where its bearing from C turns back: cos φₑ = r/D (computed so, as the general formula
    would lose half the digits there)."""
    if abs(r - D * np.sin(psi_e)) <= TOL * D:
        return float(np.arccos(r / D))
    disc = max(r * r - (D * np.sin(psi_e)) ** 2, 0.0)
    rho = D * np.cos(psi_e) - np.sqrt(disc)  # distance of the meeting point from C
    return float(np.arccos(np.clip((D * D + r * r - rho * rho) / (2 * D * r), -1.0, 1.0)))


def _wrap(a: float) -> float:
    """Angle in [−π, π)."""
    return float((a + np.pi) % TWO_PI - np.pi)


@lru_cache(maxsize=256)
def _cached(mech: "Mechanism", name: str) -> IndexingSchedule:
    return _build(mech, mech.joint(name))


def indexing_schedule(mech: "Mechanism", pair: IntermittentPair) -> IndexingSchedule:
    """The phases of `pair` (computed once per mechanism)."""
    return _cached(mech, pair.name)


def _build(mech: "Mechanism", pair: IntermittentPair) -> IndexingSchedule:
    what = f"{pair.kind} pair '{pair.name}'"
    driver, wheel = pair.links
    M = mech.points[_pivot(mech, pair, driver, "driver")]
    C = mech.points[_pivot(mech, pair, wheel, "wheel")]
    D = float(np.hypot(*(C - M)))
    if D <= TOL * mech.length_scale:
        raise ModelError(f"{what}: the driver's and the wheel's pivots coincide (centre distance 0)")
    gamma = float(np.arctan2(*(C - M)[::-1]))
    deg = np.degrees
    pins: dict[str, tuple[float, float]] = {}
    for group in pair.groups:
        for p in group:
            if p not in mech.points or p not in mech.link(driver).points:
                raise ModelError(f"{what}: the pin '{p}' must be a point of the driver '{driver}' "
                                 "(list it under [links])")
            if p in pins:
                raise ModelError(f"{what}: the pin '{p}' is listed twice")
            d = mech.points[p] - M
            r = float(np.hypot(*d))
            if not (TOL * D < r < D * (1 - TOL)):
                raise ModelError(
                    f"{what}: the pin '{p}' is {r:.6g} {mech.length_unit} from the driver's pivot; "
                    f"it must lie between the pivot and the centre distance D = {D:.6g} (else it "
                    "runs through the wheel's centre)")
            pins[p] = (r, _wrap(np.arctan2(d[1], d[0]) - gamma))
    entries = pair.entry if pair.entry is not None else (None,) * len(pair.groups)
    if len(entries) != len(pair.groups):
        raise ModelError(f"{what}: give one entry angle per pin group ({len(pair.groups)}), got "
                         f"{len(entries)}")
    spans = []  # per group: (its entry's δ, its length, its phases from there, step, names)
    for g, (group, psi_e) in enumerate(zip(pair.groups, entries)):
        names = ", ".join(group)
        radii = np.array([pins[p][0] for p in group])
        r = float(radii.mean())
        if np.ptp(radii) > TOL * D:
            raise ModelError(f"{what}: the pins {names} of one group lie on different pitch "
                             f"circles (radii {', '.join(f'{x:.6g}' for x in radii)}); a group's "
                             "pins share one pitch circle")
        if psi_e is None:
            psi_e = float(np.arcsin(r / D))
        reach = D * np.sin(psi_e)
        if not 0 < psi_e < np.pi / 2:
            raise ModelError(f"{what}: the entry angle must lie between 0° and 90°, got "
                             f"{deg(psi_e):.6g}°")
        if r < reach * (1 - TOL):
            hint = (f"a wheel of {pair.slots} slots at D = {D:.6g} needs r ≥ D·sin(π/{pair.slots}) "
                    f"= {reach:.6g} (r = D·sin(π/n): shock-free entry)"
                    if isinstance(pair, GenevaPair) else
                    f"slots at {deg(psi_e):.6g}° from the line of centres need r ≥ D·sin ψₑ = "
                    f"{reach:.6g}")
            raise ModelError(f"{what}: the pin circle (radius {r:.6g} {mech.length_unit} about "
                             f"the driver's pivot) does not reach into the slots: {hint}")
        phi_e = _entry_phi(r, D, psi_e)
        # engagement order: going round the pitch circle counter-clockwise, the largest gap
        # follows the leading pin, which meets the line of centres first as δ grows
        ring = sorted(group, key=lambda p: np.mod(pins[p][1], TWO_PI))
        at = np.array([np.mod(pins[p][1], TWO_PI) for p in ring])
        gaps = np.diff(np.concatenate([at, at[:1] + TWO_PI]))
        lead = int(np.argmax(gaps))
        seq = [ring[(lead - i) % len(ring)] for i in range(len(ring))]
        beta = 0.0
        if len(seq) > 1:
            inner = np.array([np.mod(pins[p][1] - pins[q][1], TWO_PI) for p, q in zip(seq, seq[1:])])
            beta = float(inner.mean())
            if np.ptp(inner) > TOL * TWO_PI:
                raise ModelError(f"{what}: the pins {names} are not equally spaced on their pitch "
                                 f"circle (gaps {', '.join(f'{deg(x):.6g}°' for x in inner)}); a "
                                 "pin gear needs equal pitch")
        k = len(seq)
        lam = r / D
        kappa = r / (D - r)
        lead_a, last = pins[seq[0]][1], seq[-1]
        half = float(psi(phi_e, lam))  # = ψₑ: the wheel's turn while a pin runs in or out
        if k == 1:
            rel = [Phase(ENGAGED, 0.0, 2 * phi_e, g, seq[0], r, -phi_e, 0.0, half)]
        else:
            w = (k - 1) * beta
            rel = [Phase(ENTRY, 0.0, phi_e, g, seq[0], r, -phi_e, 0.0, half),
                   Phase(GEAR, phi_e, phi_e + w, g, None, r, 0.0, half, half),
                   Phase(EXIT, phi_e + w, 2 * phi_e + w, g, last, r, 0.0, half + kappa * w,
                         half + kappa * w)]
        step = 2 * half + kappa * w if k > 1 else 2 * half
        spans.append((-lead_a - phi_e, rel[-1].end, rel, step, names))
    origin = spans[0][0]
    placed = sorted(((float(np.mod(s[0] - origin, TWO_PI)),) + s[1:] for s in spans),
                    key=lambda s: s[0])
    if placed[0][0] > TWO_PI * (1 - 1e-12):  # the first group's own start, wrapped by rounding
        placed[0] = (0.0,) + placed[0][1:]
    phases: list[Phase] = []
    tau = 0.0
    for i, (x0, length, rel, step, names) in enumerate(placed):
        nxt = placed[i + 1][0] if i + 1 < len(placed) else TWO_PI
        if x0 + length > nxt + TOL:
            other = placed[i + 1][4] if i + 1 < len(placed) else placed[0][4]
            raise ModelError(f"{what}: the pin groups ({names}) and ({other}) overlap: the "
                             f"second enters {deg(x0 + length - nxt):.6g}° of driver turn before "
                             "the first has left; space the groups further apart")
        for ph in rel:
            phases.append(Phase(ph.kind, x0 + ph.start, x0 + ph.end, ph.group, ph.pin, ph.radius,
                                ph.v0, tau + ph.tau0, tau + ph.centre_tau))
        end = min(x0 + length, nxt)
        tau += step
        if end < nxt:
            phases.append(Phase(DWELL, end, nxt, tau0=tau))
    # number the groups in the order they engage within the turn
    order = {}
    for p in phases:
        if p.group >= 0 and p.group not in order:
            order[p.group] = len(order)
    phases = [Phase(p.kind, p.start, p.end, order.get(p.group, -1), p.pin, p.radius, p.v0,
                    p.tau0, p.centre_tau) for p in phases]
    advance = tau
    q = TWO_PI / advance
    if abs(q - round(q)) > 1e-6 * q:
        raise ModelError(f"{what}: per turn of the driver the wheel advances "
                         f"{deg(advance):.6g}°, which does not divide the full turn (360°/"
                         f"{deg(advance):.6g}° = {q:.6g}): its slots would not meet the pins "
                         "again; choose the pin spacing or the entry angles so that it does")
    return IndexingSchedule(pair.name, M, C, D, gamma, float(origin), tuple(phases), advance,
                            len(pair.groups), int(round(q)) * len(pair.groups), pins)


def validate_intermittent(mech: "Mechanism", pair: IntermittentPair) -> None:
    """References and geometry of an intermittent pair (called by `Mechanism._validate`)."""
    what = f"{pair.kind} pair '{pair.name}'"
    if pair.carrier not in mech.link_index:
        raise ModelError(f"{what}: the carrier '{pair.carrier}' is not a link")
    if pair.carrier in pair.links:
        raise ModelError(f"{what}: the carrier '{pair.carrier}' cannot be the driver or the wheel")
    if isinstance(pair, GenevaPair):
        if int(pair.slots) != pair.slots or pair.slots < 3:
            raise ModelError(f"{what}: a Geneva wheel needs at least 3 slots (Pöschl §25: fewer "
                             f"indexing steps per turn are impossible), got {pair.slots}")
    elif not pair.groups or any(not g for g in pair.groups):
        raise ModelError(f"{what}: give the pins of each indexing group (groups = [[\"P1\", "
                         "\"P2\"], …])")
    indexing_schedule(mech, pair)  # builds (and keeps) the phases, refusing what cannot run
