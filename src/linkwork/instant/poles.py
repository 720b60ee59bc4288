"""Poles (instantaneous centres, *Momentanpole*, *momentānie poli*) of every pair of links.

Owns two independent ways to the n(n−1)/2 relative poles P_ij of an n-link mechanism:

* `poles(solution)`: from the velocity solution. P_ij is the point where the velocity fields
  of links i and j agree (Rosenauer §62, eq. 33: V¹³₁₂ = V²³₁₂).
* `pole_schedule(mechanism)` and `kennedy_poles(solution)`: the classical way. Start from the
  primary poles (hinges; sliders at infinity normal to the guide; gear pitch points; the
  contact normal of a pin in a slot as a line through its pole) and apply the Aronhold–Kennedy
  three-pole theorem (Rosenauer §62, §75, §91–92; Pöschl §51): P_ij lies on the line of P_ik and
  P_jk for every third link k. Lines that are one line for every position (three links on one
  hinge) count once. The schedule prints like a textbook ("P13 = P12P23 ∩ P14P34") and names
  the poles the theorem alone cannot reach (chains without four-bar loops, Rosenauer 1937,
  "Koppeltriebe ohne Gelenkvierecke").

Also `pole_lines` (the n(n−1)(n−2)/6 lines holding three poles each, Rosenauer §85) and
`pole_discrepancy` to compare two pole sets. Poles at infinity (translations, sliders) are
homogeneous `geometry.Point`s with w = 0 and their direction, never large numbers.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import combinations
from math import comb
from typing import Iterator

import numpy as np

from ..errors import ModelError
from ..geometry import Line, Point
from ..kinematics import Solution
from ..kinematics.intermittent import contact_normal
from ..model import (CamContact, CircularSlot, Gear, Mechanism, Prismatic, Revolute, RollingContact,
                     Slot, is_intermittent)
from .motion import TOL, make_point, perp, rotate

Pair = tuple[str, str]


def pole_count(n: int) -> int:
    """Number of relative poles of n links: n(n−1)/2 (Rosenauer §84, eq. 42)."""
    return comb(n, 2)


def pole_line_count(n: int) -> int:
    """Number of pole lines of n links: n(n−1)(n−2)/6 (Rosenauer §85, eq. 43)."""
    return comb(n, 3)


# ---------------------------------------------------------------------------- the pole set
@dataclass(frozen=True)
class Poles:
    """The relative poles of every pair of links, each a `Point` of shape (N,) in the frame.

    Index by a pair of link names in either order: ``poles["crank", "coupler"]``. Links are
    numbered 1..n in the mechanism's order for the textbook labels (``label(a, b) == "P12"``).
    A pole the method could not determine is all-NaN.
    """

    links: tuple[str, ...]
    points: dict[Pair, Point] = field(repr=False)
    method: str = "velocities"

    def key(self, a: str, b: str) -> Pair:
        if a == b:
            raise ModelError(f"a link has no pole relative to itself ('{a}')")
        for ln in (a, b):
            if ln not in self.links:
                raise ModelError(f"no link '{ln}' (links: {', '.join(self.links)})")
        ia, ib = self.links.index(a), self.links.index(b)
        return (a, b) if ia < ib else (b, a)

    def __getitem__(self, pair: Pair) -> Point:
        return self.points[self.key(*pair)]

    def __iter__(self) -> Iterator[Pair]:
        return iter(self.points)

    def __len__(self) -> int:
        return len(self.points)

    def number(self, link: str) -> int:
        return self.links.index(link) + 1

    def label(self, a: str, b: str) -> str:
        return pole_label(self.links, self.key(a, b))

    def legend(self) -> str:
        return ", ".join(f"{i + 1} = {ln}" for i, ln in enumerate(self.links))


def pole_label(links: tuple[str, ...], pair: Pair) -> str:
    i, j = sorted(links.index(ln) + 1 for ln in pair)
    return f"P{i}{j}" if len(links) <= 9 else f"P{i},{j}"


def _all_pairs(links: tuple[str, ...]) -> list[Pair]:
    return list(combinations(links, 2))


# ---------------------------------------------------------------------------- from velocities
def poles(solution: Solution, *, tol: float = TOL) -> Poles:
    """All n(n−1)/2 relative poles at every sample, from the velocity solution.

    The velocity of the point X of link k is V_k(X) = c_k + ω_k J(X − M) with M a fixed point
    near the mechanism, so V_i(X) = V_j(X) at X = M + J(c_i − c_j)/(ω_i − ω_j), carried in
    homogeneous form (Δω·M + J Δc, Δω). A pole farther than length_scale/tol is a translation
    pole, exactly at infinity in the direction J Δc (normal to the common velocity). A pair at
    relative rest at a sample has an undefined (NaN) pole there.
    """
    mech = solution.mechanism
    links = mech.link_names
    L = mech.length_scale
    M = np.mean(np.array(list(mech.points.values())), axis=0)
    D = np.stack([solution.pose_derivatives(ln) for ln in links], axis=2)  # (K+1, N, n, 3)
    o, v, w = D[0, ..., :2], D[1, ..., :2], D[1, ..., 2]
    c = v + w[..., None] * perp(M - o)  # velocity of the point of each link at M
    vscale = (np.sqrt((c * c).sum(-1)) + np.abs(w) * L).max(axis=1)  # (N,)
    out: dict[Pair, Point] = {}
    for a, b in _all_pairs(links):
        ia, ib = mech.link_index[a], mech.link_index[b]
        dc, dw = c[:, ia] - c[:, ib], w[:, ia] - w[:, ib]
        out[(a, b)] = _pole_from_velocity_difference(M, dc, dw, L, vscale, tol)
    return Poles(links, out, "velocities")


def _pole_from_velocity_difference(M, dc, dw, L, vscale, tol) -> Point:
    ndc = np.sqrt((dc * dc).sum(-1))
    translating = np.abs(dw) * L <= tol * ndc
    rest = ndc + np.abs(dw) * L <= tol * vscale
    w_ = np.where(translating, 0.0, dw)
    h = np.concatenate([w_[:, None] * M + perp(dc), w_[:, None]], axis=1)
    h[rest] = np.nan
    return make_point(h)


# ---------------------------------------------------------------------------- Kennedy
@dataclass(frozen=True)
class PoleLineSource:
    """One line known to pass through a pole: the line of two known poles, or the contact
    normal of a pin in a slot (straight: normal to the slot; curved: through the slot centre)."""

    poles: tuple[Pair, Pair] | None = None
    joint: str | None = None

    def text(self, links: tuple[str, ...]) -> str:
        if self.poles is not None:
            return "".join(pole_label(links, p) for p in self.poles)
        return f"n({self.joint})"


#: the rules of poles read off a pair directly (the others are intersections of lines)
PRIMARY_RULES = ("hinge", "slider", "gear", "rolling", "common hinge")


@dataclass(frozen=True)
class PoleStep:
    """How one pole is found. `rule` is 'hinge' (the hinge point), 'slider' (at infinity
    normal to the guide), 'gear' (pitch point), 'common hinge' (three links on one hinge
    point), 'normals' (two contact normals) or 'three-pole' (Aronhold–Kennedy)."""

    pair: Pair
    rule: str
    joint: str | None = None
    lines: tuple[PoleLineSource, ...] = ()

    def text(self, links: tuple[str, ...]) -> str:
        lab = pole_label(links, self.pair)
        if self.rule == "hinge":
            return f"{lab} = hinge {self.joint}"
        if self.rule == "slider":
            return f"{lab} = ∞ normal to the guide of {self.joint}"
        if self.rule == "gear":
            return f"{lab} = pitch point of gear {self.joint}"
        if self.rule == "rolling":
            return f"{lab} = contact point of rolling pair {self.joint}"
        if self.rule == "common hinge":
            return f"{lab} = hinge {self.joint} (common to three links)"
        a, b = self.lines[:2]
        return f"{lab} = {a.text(links)} ∩ {b.text(links)}"


@dataclass(frozen=True)
class PoleSchedule:
    """The order in which a textbook finds the poles: primary poles first, then each derived
    pole from two different lines through already known poles. `unreachable` are the poles the
    three-pole theorem cannot reach from the primary poles: no two different lines through
    them are known (they need velocities, or Rosenauer's auxiliary points of 1937)."""

    links: tuple[str, ...]
    steps: tuple[PoleStep, ...]
    unreachable: tuple[Pair, ...]

    @property
    def primary(self) -> tuple[PoleStep, ...]:
        return tuple(s for s in self.steps if s.rule in PRIMARY_RULES)

    @property
    def derived(self) -> tuple[PoleStep, ...]:
        return tuple(s for s in self.steps if s.rule in ("three-pole", "normals"))

    def lines(self) -> list[str]:
        out = [s.text(self.links) for s in self.steps]
        if self.unreachable:
            labs = ", ".join(pole_label(self.links, p) for p in self.unreachable)
            out.append(f"not reachable by the three-pole theorem: {labs}")
        return out

    def text(self) -> str:
        legend = ", ".join(f"{i + 1} = {ln}" for i, ln in enumerate(self.links))
        return "\n".join([legend] + self.lines())


def _pair(links: tuple[str, ...], a: str, b: str) -> Pair:
    return (a, b) if links.index(a) < links.index(b) else (b, a)


def pole_schedule(mechanism: Mechanism) -> PoleSchedule:
    """The Aronhold–Kennedy schedule of `mechanism`'s poles (topology only, no numbers).

    Primary poles come from the pairs: a revolute is the pole of its two links, a prismatic
    pair's pole is at infinity normal to the guide, a gear pair's is its pitch point; a pin in
    a straight or circular slot gives one line through the pole (its contact normal,
    Rosenauer §65). Then, repeatedly, the first unknown pole with two known, independent lines
    through it is found as their intersection; each derived step keeps one line of every
    independent line known at that moment, so that `kennedy_poles` can use the best-conditioned
    pair at each sample.

    Lines are independent when they are not one line for the topology alone. Where three links
    share a hinge (Jansen's linkage), the lines P_ik P_km and P_im' P_km' through the common
    hinge coincide for every position, and intersecting them gives no point; such lines are
    recognised (`_IncidenceStructure`) and count once. A pole with fewer than two independent
    lines is in `unreachable`.
    """
    links = mechanism.link_names
    known: dict[Pair, PoleStep] = {}
    hinge_point: dict[Pair, str] = {}
    normals: dict[Pair, list[PoleLineSource]] = {}
    steps: list[PoleStep] = []
    inc = _IncidenceStructure(links)

    def add(step: PoleStep) -> None:
        known[step.pair] = step
        steps.append(step)

    for j in mechanism.joints:
        a, b = j.links
        p = _pair(links, a, b)
        if isinstance(j, Revolute):
            if p not in known:
                add(PoleStep(p, "hinge", j.name))
                hinge_point[p] = j.point
        elif isinstance(j, Prismatic):
            if p not in known:
                add(PoleStep(p, "slider", j.name))
        elif isinstance(j, Gear):
            if p not in known:
                add(PoleStep(p, "gear", j.name))
        elif isinstance(j, RollingContact):
            if p not in known:  # rolling without slip: the contact point is the pole
                add(PoleStep(p, "rolling", j.name))
        elif isinstance(j, (Slot, CircularSlot, CamContact)) or is_intermittent(j):
            # the relative pole lies on the contact normal (Rosenauer §65; for higher pairs the
            # common normal of the profiles, Reuleaux, Pöschl §45)
            normals.setdefault(p, []).append(PoleLineSource(joint=j.name))
    # links sharing one hinge point (a multiple joint drawn as several revolutes)
    changed = True
    while changed:
        changed = False
        for i, k in combinations(links, 2):
            p = _pair(links, i, k)
            if p in known:
                continue
            for m in links:
                if m in (i, k):
                    continue
                pa, pb = _pair(links, i, m), _pair(links, k, m)
                if pa in hinge_point and pb in hinge_point and hinge_point[pa] == hinge_point[pb]:
                    add(PoleStep(p, "common hinge", known[pa].joint))
                    hinge_point[p] = hinge_point[pa]
                    inc.same_point(p, pa, pb)
                    changed = True
                    break
    for p, srcs in normals.items():
        for src in srcs:
            inc.add_normal(p, src, _normal_points(mechanism, src.joint, hinge_point))
    inc.close()
    # pairs joined by two slots: the two contact normals (if they are two lines)
    for p in normals:
        srcs = [] if p in known else inc.independent_lines(p, {})
        if len(srcs) >= 2:
            add(PoleStep(p, "normals", lines=tuple(srcs)))
    # the three-pole theorem, one pole at a time
    while True:
        found = None
        for p in combinations(links, 2):
            if p in known:
                continue
            srcs = inc.independent_lines(p, known)
            if len(srcs) >= 2:
                found = PoleStep(p, "three-pole", lines=tuple(srcs))
                break
        if found is None:
            break
        add(found)
    unreachable = tuple(p for p in _all_pairs(links) if p not in known)
    return PoleSchedule(links, tuple(steps), unreachable)


def _normal_points(mechanism: Mechanism, joint: str, hinge_point: dict[Pair, str]) -> list[Pair]:
    """Hinge poles that lie on the contact normal of a pin in a slot for every position: the
    hinges at the pin (on the pin's link) and, for a circular slot, at the slot's centre (on the
    slot's link). Needed so that a normal is not taken as a second line where it is the pole
    line of those hinges."""
    j = mechanism.joint(joint)
    slot_link, pin_link = j.links
    if is_intermittent(j):
        return []  # the pin, the pitch point or the driver's pivot, by phase: no one hinge
    if isinstance(j, CamContact) and j.follower not in ("roller", "knife"):
        return []  # a face or profile: no point of the follower stays on the normal
    on = [(j.point, pin_link)]
    if isinstance(j, CircularSlot):
        on.append((j.center, slot_link))
    return [p for p, x in hinge_point.items() for pt, ln in on if x == pt and ln in p]


class _IncidenceStructure:
    """Which poles are one point and which pole lines are one line, for the topology alone.

    Points: a pole is its own point, except the poles of links on one hinge, which are one.
    Lines: the three poles of every three links (Aronhold–Kennedy) and every contact normal
    with the hinge poles on it. Two lines sharing two different points are one line; `close`
    merges them until no two share two points (union–find over the lines). Then two different
    lines through an unknown pole meet in that pole alone, in a general position."""

    def __init__(self, links: tuple[str, ...]) -> None:
        self.links = links
        self._point: dict[Pair, Pair] = {}      # union–find over poles: pole -> same point
        self._points: list[set[Pair]] = []       # the points of each line (of a merged one: empty)
        self._parent: list[int] = []             # union–find over lines
        self._triple: dict[frozenset[str], int] = {}
        self._normals: dict[int, list[tuple[Pair, PoleLineSource]]] = {}  # line -> (pole, normal)

    def point(self, p: Pair) -> Pair:
        while self._point.get(p, p) != p:
            p = self._point[p]
        return p

    def same_point(self, p: Pair, *others: Pair) -> None:
        for q in others:
            a, b = self.point(p), self.point(q)
            if a != b:
                self._point[b] = a

    def line(self, i: int) -> int:
        while self._parent[i] != i:
            i = self._parent[i]
        return i

    def _new_line(self, points: set[Pair]) -> int:
        self._points.append(points)
        self._parent.append(len(self._parent))
        return len(self._parent) - 1

    def add_normal(self, p: Pair, src: PoleLineSource, on: list[Pair]) -> None:
        self._normals[self._new_line({p, *on})] = [(p, src)]

    def close(self) -> None:
        """Add the pole lines of all triples of links and merge coincident lines. Call once,
        after every `same_point` and `add_normal`."""
        self._points = [{self.point(p) for p in pts} for pts in self._points]
        for t in combinations(self.links, 3):
            pts = {self.point(_pair(self.links, a, b)) for a, b in combinations(t, 2)}
            if len(pts) == 3:  # else the three links are on one hinge: one point, no line
                self._triple[frozenset(t)] = self._new_line(pts)
        owner: dict[frozenset[Pair], int] = {}  # a line through each two points met so far
        todo = list(range(len(self._points)))
        while todo:
            i = self.line(todo.pop())
            for two in combinations(sorted(self._points[i]), 2):
                j = self.line(owner.setdefault(frozenset(two), i))
                if j != i:  # two points in common: one line
                    self._parent[j] = i
                    self._points[i] |= self._points[j]
                    self._points[j] = set()
                    self._normals.setdefault(i, []).extend(self._normals.pop(j, []))
                    todo.append(i)  # its points grew: look at all their pairs again
                    break

    def independent_lines(self, p: Pair, known: dict[Pair, PoleStep]) -> list[PoleLineSource]:
        """One source for each different line through the unknown pole p that is determined by
        a contact normal or by two known poles of different points: p's own normals first,
        then, in the order of the third link m, the textbook pair P_im P_km, else any normal on
        the line, else the first two known poles on it (a line reached through one it
        coincides with)."""
        i, k = p
        order = [ln for ln, srcs in self._normals.items() if any(q == p for q, _ in srcs)]
        rank = {q: n for n, q in enumerate(known)}
        textbook: dict[int, tuple[Pair, Pair]] = {}
        for m in self.links:
            t = self._triple.get(frozenset((i, k, m)))
            if m in (i, k) or t is None:
                continue
            ln = self.line(t)
            order.append(ln)
            pa, pb = _pair(self.links, i, m), _pair(self.links, k, m)
            if pa in rank and pb in rank:
                # of the textbook pairs on one line, the one known earliest (hinges first)
                best = textbook.get(ln)
                if best is None or max(rank[pa], rank[pb]) < max(rank[x] for x in best):
                    textbook[ln] = (pa, pb)
        out: list[PoleLineSource] = []
        for ln in dict.fromkeys(order):  # each line once, in order
            normals = self._normals.get(ln, [])
            own = [s for q, s in normals if q == p]
            given: dict[Pair, Pair] = {}  # point -> its first known pole, in schedule order
            for q in known:
                if self.point(q) in self._points[ln]:
                    given.setdefault(self.point(q), q)
            if own:
                out.append(own[0])
            elif ln in textbook:
                out.append(PoleLineSource(poles=textbook[ln]))
            elif normals:
                out.append(normals[0][1])
            elif len(given) >= 2:
                out.append(PoleLineSource(poles=tuple(given.values())[:2]))
        return out


def _scaled(h: np.ndarray, L: float) -> np.ndarray:
    """Homogeneous rows with x, y in units of L, normalised to unit length (NaN stays NaN)."""
    s = np.concatenate([h[:, :2] / L, h[:, 2:]], axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return s / np.linalg.norm(s, axis=1, keepdims=True)


def _unscaled(s: np.ndarray, L: float) -> np.ndarray:
    return np.concatenate([s[:, :2] * L, s[:, 2:]], axis=1)


def primary_pole(solution: Solution, step: PoleStep) -> np.ndarray:
    """Homogeneous (N, 3) coordinates of a primary pole (read off its pair: a hinge, at infinity
    normal to a guide, a gear pair's pitch point, a rolling pair's point of contact)."""
    mech = solution.mechanism
    j = mech.joint(step.joint)
    N = len(solution)
    if isinstance(j, Revolute):
        xy = solution.point_on(j.links[0], mech.points[j.point]).position
        return np.concatenate([xy, np.ones((N, 1))], axis=1)
    if isinstance(j, Prismatic):
        g = rotate(solution.pose_derivatives(j.links[0])[0, :, 2], j.axis)
        return np.concatenate([perp(g), np.zeros((N, 1))], axis=1)
    if isinstance(j, Gear):
        return np.concatenate([gear_pitch_point(solution, j), np.ones((N, 1))], axis=1)
    if isinstance(j, RollingContact):
        return np.concatenate([solution.joint(j.name)["point"], np.ones((N, 1))], axis=1)
    raise TypeError(j)  # pragma: no cover


def gear_pitch_point(solution: Solution, g: Gear) -> np.ndarray:
    """(N, 2) pitch point of a gear pair: the relative pole of its two wheels (the point where
    the pitch circles touch and roll)."""
    mech = solution.mechanism
    c1 = solution.point_on(g.carrier, mech.points[mech.wheel_centre(g, g.links[0])]).position
    r1, r2 = g.radii
    if g.gear_kind == "rack":
        guide = mech.rack_guide(g)
        centre = mech.points[mech.wheel_centre(g, g.links[0])]
        n = np.array([-guide.axis[1], guide.axis[0]])
        probe = mech.points[g.point] if g.point else mech.points[guide.point]
        m = n if np.dot(probe - centre, n) >= 0 else -n
        return c1 + r1 * rotate(solution.pose_derivatives(g.carrier)[0, :, 2], m)
    c2 = solution.point_on(g.carrier, mech.points[mech.wheel_centre(g, g.links[1])]).position
    if g.gear_kind == "external":
        return (r2 * c1 + r1 * c2) / (r1 + r2)
    return (r2 * c1 - r1 * c2) / (r2 - r1)


def contact_normal_line(solution: Solution, joint: str) -> tuple:
    """The line through the relative pole of the two links of a pin in a slot, a cam contact or
    an intermittent pair (Rosenauer §65; for higher pairs the profiles' common normal, Reuleaux,
    Pöschl §45): a point X (N, 2) of it, its direction (N, 2), and for a circular slot its
    centre K (N, 2), the line's second point (else None)."""
    mech = solution.mechanism
    j = mech.joint(joint)
    a, b = j.links
    if is_intermittent(j):
        X, n = contact_normal(solution, joint)
        return X, n, None
    if isinstance(j, CamContact):
        rep = solution.joint(joint)
        return rep["point"], rep["normal"], None  # the normal through the contact point
    X = solution.point_on(b, mech.points[j.point]).position
    if isinstance(j, Slot):  # normal to the slot at the pin
        return X, -perp(rotate(solution.pose_derivatives(a)[0, :, 2], j.axis)), None
    return X, None, solution.point_on(a, mech.points[j.center]).position


def _normal_line(solution: Solution, joint: str, L: float) -> np.ndarray:
    """Scaled homogeneous line (N, 3) of `contact_normal_line`."""
    X, d, K = contact_normal_line(solution, joint)
    if K is None:
        g = perp(d)
        line = np.concatenate([g, -(g * X).sum(1, keepdims=True) / L], axis=1)
    else:
        ones = np.ones((len(X), 1))
        line = np.cross(_scaled(np.concatenate([X, ones], axis=1), L),
                        _scaled(np.concatenate([K, ones], axis=1), L))
    with np.errstate(invalid="ignore", divide="ignore"):
        return line / np.linalg.norm(line, axis=1, keepdims=True)


def kennedy_poles(solution: Solution, schedule: PoleSchedule | None = None) -> Poles:
    """All poles the three-pole theorem reaches, evaluated at every sample by `schedule`
    (default: `pole_schedule` of the solution's mechanism). Each derived pole is the
    intersection of the best-conditioned pair among the lines known at its step; the poles
    in `schedule.unreachable` are all-NaN. The schedule's lines of a step are different lines
    for a general position, so a derived pole is NaN elsewhere only at a sample where all of
    them coincide (a special position) or a pole they are drawn through is NaN."""
    mech = solution.mechanism
    schedule = schedule or pole_schedule(mech)
    L = mech.length_scale
    N = len(solution)
    scaled: dict[Pair, np.ndarray] = {}
    for step in schedule.steps:
        if step.rule in PRIMARY_RULES:
            scaled[step.pair] = _scaled(primary_pole(solution, step), L)
            continue
        lines = []
        for src in step.lines:
            if src.poles is not None:
                p, q = (scaled[x] for x in src.poles)
                ln = np.cross(p, q)
                with np.errstate(invalid="ignore", divide="ignore"):
                    nrm = np.linalg.norm(ln, axis=1, keepdims=True)
                    ln = np.where(nrm > 1e-12, ln / nrm, np.nan)
            else:
                ln = _normal_line(solution, src.joint, L)
            lines.append(ln)
        best = np.full((N, 3), np.nan)
        quality = np.full(N, -1.0)
        for l1, l2 in combinations(lines, 2):
            x = np.cross(l1, l2)
            qn = np.linalg.norm(x, axis=1)
            better = np.isfinite(qn) & (qn > quality) & (qn > 1e-14)
            with np.errstate(invalid="ignore", divide="ignore"):
                best[better] = (x / qn[:, None])[better]
            quality = np.where(better, qn, quality)
        scaled[step.pair] = best
    out: dict[Pair, Point] = {}
    for p in _all_pairs(schedule.links):
        h = _unscaled(scaled[p], L) if p in scaled else np.full((N, 3), np.nan)
        out[p] = make_point(_snap_infinite(h, L))
    return Poles(schedule.links, out, "three-pole theorem")


def _snap_infinite(h: np.ndarray, L: float, tol: float = TOL) -> np.ndarray:
    """Points farther than L/tol (|w|·L ≤ tol·|xy|) are put exactly at infinity."""
    h = h.copy()
    far = np.abs(h[:, 2]) * L <= tol * np.linalg.norm(h[:, :2], axis=1)
    h[far, 2] = 0.0
    return h


# ---------------------------------------------------------------------------- comparisons
def pole_discrepancy(p: Point, q: Point, scale: float) -> np.ndarray:
    """(N,) projective distance of two batches of poles: the sine of the angle between their
    homogeneous coordinates with lengths in units of `scale`. About |p − q|/scale for nearby
    finite poles, small for distant poles in nearly the same direction, and the sine of the
    angle between the directions of two poles at infinity. NaN where either is undefined."""
    a, b = _scaled(np.asarray(p.coords), scale), _scaled(np.asarray(q.coords), scale)
    return np.linalg.norm(np.cross(a, b), axis=1)


def agreement(first: Poles, second: Poles, scale: float) -> dict[Pair, np.ndarray]:
    """Per pole, `pole_discrepancy` between two pole sets of one mechanism (NaN where either
    set lacks the pole)."""
    if tuple(first.links) != tuple(second.links):
        raise ModelError("the two pole sets belong to different mechanisms")
    return {p: pole_discrepancy(first.points[p], second.points[p], scale) for p in first}


# ---------------------------------------------------------------------------- pole lines
@dataclass(frozen=True)
class PoleLine:
    """The line of the three poles P_ij, P_jk, P_ik of links (i, j, k) (the 'polu taisne',
    Rosenauer §62). `residual` (N,) is the collinearity defect of the three poles (0 for
    exactly collinear, dimensionless); `line` is through the best-separated two of them."""

    links: tuple[str, str, str]
    pairs: tuple[Pair, Pair, Pair]
    line: Line
    residual: np.ndarray


def pole_lines(poles_: Poles, scale: float) -> list[PoleLine]:
    """All n(n−1)(n−2)/6 pole lines of a pole set (Rosenauer §85)."""
    out = []
    for i, j, k in combinations(poles_.links, 3):
        prs = ((i, j), (j, k), (i, k))
        S = [_scaled(np.asarray(poles_.points[p].coords), scale) for p in prs]
        with np.errstate(invalid="ignore"):
            residual = np.abs(np.linalg.det(np.stack(S, axis=1)))
        cands = [np.cross(S[0], S[1]), np.cross(S[1], S[2]), np.cross(S[0], S[2])]
        nr = np.stack([np.linalg.norm(c, axis=1) for c in cands], axis=1)
        pick = np.argmax(np.where(np.isfinite(nr), nr, -1.0), axis=1)
        ln = np.take_along_axis(np.stack(cands, axis=1), pick[:, None, None], axis=1)[:, 0]
        ln = np.concatenate([ln[:, :2], ln[:, 2:] * scale], axis=1)
        bad = ~np.isfinite(ln).all(axis=1) | (np.abs(ln) < 1e-300).all(axis=1)
        ln[bad] = np.nan
        out.append(PoleLine((i, j, k), prs, Line(ln), residual))
    return out
