"""Grashof's classification of four-bars and slider-cranks, the names of their inversions, their
limit positions and their transmission angle range, in closed form.

**Four-bar** (*Gelenkviereck*, *šarnīru četrstūris*), shortest link s, longest l, the others p,
q (Grashof 1883, Pöschl eq. 98): if s + l < p + q some link turns fully; fixing the shortest
gives the double crank (*Doppelkurbel*), fixing a neighbour of it the crank-rocker
(*Schwingkurbelgetriebe*; not Pöschl's *Kurbelschwinge*, which is a slider-crank inversion),
fixing the link opposite it the (Grashof) double rocker, whose coupler turns fully. If
s + l > p + q no link turns fully (non-Grashof double rocker, triple rocker). If s + l = p + q
the chain has change points (*Wechsellagen*, *maiņas punkti*: all four hinges in line), as the
parallel crank, the antiparallel crank and the kite (Galloway) do.

**Slider-crank chain** (three hinges and a slider; *Schubkurbelkette*, *kloķa mehānisms*),
with the two hinge-hinge links of lengths r and l and the offset e of the slider's line
(the distance between the lines through the hinges of the two sliding links along the slide):
the link r turns fully against the others if r + |e| < l. Rosenauer (§4) names the four
inversions by the fixed link, r being the crank (1), l the rod (2), the sliding link next to
the rod the block (3) and the one next to the crank the guide (4):

* type I, guide fixed: the slider-crank of engines and pumps (*Schubkurbel*), centric or offset
  (*geschränkt*, eccentric);
* type II, rod fixed: the oscillating crank-slotted lever (*schwingende Kurbelschleife*,
  *svārstīgā kloķa cilpa*), also the oscillating-cylinder engine (Pöschl's *Kurbelschwinge*)
  and the shaping machine's quick return;
* type III, crank fixed: the rotating crank-slotted lever (*umlaufende / rotierende
  Kurbelschleife*, *rotējošā kloķa cilpa*), the Gnome rotary aero engine and Whitworth's quick
  return;
* type IV, block fixed: unnamed in Rosenauer; Pöschl's *Schubschwinge* (the hand pump).

Angles are in radians, lengths in the mechanism's unit. Limit positions (*Totlagen*,
*Umkehrlagen*) are given as driver input values near the design position, so that they compare
with `linkwork.kinematics.motion.input_limits`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import networkx as nx
import numpy as np

from ..errors import StructureError
from ..model import Mechanism
from ..topology.groups import Group, solution_order

TOL = 1e-9  # relative, for the Grashof equality

# ---------------------------------------------------------------------------- pure classification


@dataclass(frozen=True)
class FourBarClass:
    """Grashof class of a four-bar with the frame fixed and the input at one frame pivot."""

    frame: float
    input: float
    coupler: float
    output: float
    grashof: str  # "Grashof", "change point", "non-Grashof"
    type: str  # "crank-rocker", "rocker-crank", "double crank", "double rocker"
    input_turns_fully: bool
    output_turns_fully: bool
    coupler_turns_fully: bool  # relative to the frame's neighbours
    special: str | None = None  # parallelogram, antiparallelogram, kite … for change points

    @property
    def name(self) -> str:
        german = {"crank-rocker": "Schwingkurbelgetriebe", "rocker-crank": "Schwingkurbelgetriebe",
                  "double crank": "Doppelkurbel", "double rocker": "Doppelschwinggetriebe"}[self.type]
        kind = {"Grashof": "Grashof", "change point": "change-point (Wechsellage)",
                "non-Grashof": "non-Grashof"}[self.grashof]
        base = self.type
        if self.type == "rocker-crank":
            base = "crank-rocker driven at its rocker"
        if self.type == "double rocker" and self.grashof == "Grashof":
            base = "double rocker (the coupler turns fully)"
        if self.type == "double rocker" and self.grashof == "non-Grashof":
            base = "double rocker (triple rocker: no link turns fully)"
        extra = f", {self.special}" if self.special else ""
        return f"{kind} {base} ({german}{extra})"


def classify_four_bar(frame: float, input: float, coupler: float, output: float, *,
                      crossed: bool | None = None) -> FourBarClass:
    """Grashof class of the four-bar with these link lengths, the frame fixed, the input and the
    output pivoted on the frame. `crossed` (the coupler crosses the frame's line between the
    pivots, as drawn) tells a parallel from an antiparallel crank."""
    lengths = [frame, input, coupler, output]
    if min(lengths) <= 0:
        raise StructureError("four-bar link lengths must be positive")
    scale = max(lengths)
    srt = sorted(lengths)
    s, p, q, l = srt
    diff = (s + l) - (p + q)
    if abs(diff) <= TOL * scale:
        grashof = "change point"
    elif diff < 0:
        grashof = "Grashof"
    else:
        grashof = "non-Grashof"

    def short(x: float) -> bool:
        return abs(x - s) <= TOL * scale

    # Grashof's theorem: a link turns fully against a neighbour when one of the two is the
    # shortest link of a Grashof (or change-point) chain
    turning = grashof != "non-Grashof"
    inp = turning and (short(frame) or short(input))
    out = turning and (short(frame) or short(output))
    cpl = turning and short(coupler)
    kind = {(True, True): "double crank", (True, False): "crank-rocker",
            (False, True): "rocker-crank", (False, False): "double rocker"}[(inp, out)]
    special = None
    if grashof == "change point":
        eq = lambda x, y: abs(x - y) <= TOL * scale  # noqa: E731
        if eq(frame, coupler) and eq(input, output):
            if eq(frame, input):
                special = "rhombus"
            elif crossed is None:
                special = "parallel or antiparallel crank"
            else:
                special = ("antiparallel crank, Antiparallelkurbel" if crossed
                           else "parallel crank, Parallelkurbel")
        elif (eq(frame, input) and eq(coupler, output)) or (eq(frame, output) and eq(coupler, input)):
            special = "kite (deltoid, Galloway)"
    return FourBarClass(frame, input, coupler, output, grashof, kind, inp, out, cpl, special)


@dataclass(frozen=True)
class SliderCrankClass:
    """The slider-crank chain's inversion by its fixed link (Rosenauer's types I–IV)."""

    crank: float  # r: the hinge-hinge link that can turn fully (the shorter one if none can)
    rod: float  # l: the other hinge-hinge link
    offset: float  # e ≥ 0
    grashof: str  # "Grashof" (r + e < l), "change point" (=), "non-Grashof" (>)
    fixed: str  # which link of the chain is fixed: "guide", "rod", "crank", "block"

    @property
    def inversion(self) -> str:
        return {"guide": "I", "rod": "II", "crank": "III", "block": "IV"}[self.fixed]

    @property
    def centric(self) -> bool:
        return self.offset <= TOL * max(self.crank, self.rod)

    @property
    def name(self) -> str:
        base = {
            "I": ("slider-crank (Schubkurbel, kloķa mehānisms), "
                  + ("centric" if self.centric else "offset (geschränkt, eccentric)")
                  + ": engine or pump"),
            "II": ("oscillating crank-slotted lever (schwingende Kurbelschleife, svārstīgā kloķa "
                   "cilpa): oscillating-cylinder engine (Kurbelschwinge), shaping machine"),
            "III": ("rotating crank-slotted lever (umlaufende Kurbelschleife, rotējošā kloķa "
                    "cilpa): Gnome rotary engine, Whitworth quick return"),
            "IV": "fixed block (Schubschwinge, hand pump)",
        }[self.inversion]
        tail = {"Grashof": "", "change point": "; change-point chain (r + e = l)",
                "non-Grashof": "; no link turns fully (r + e > l)"}[self.grashof]
        return f"type {self.inversion}: {base}{tail}"


def classify_slider_crank(crank: float, rod: float, offset: float = 0.0,
                          fixed: str = "guide") -> SliderCrankClass:
    """The slider-crank chain of crank r, rod l and offset e, fixed on `fixed` ('guide', 'rod',
    'crank' or 'block'; named as in type I)."""
    if crank <= 0 or rod <= 0 or offset < 0:
        raise StructureError("slider-crank lengths must be positive and the offset non-negative")
    if fixed not in ("guide", "rod", "crank", "block"):
        raise StructureError(f"unknown fixed link '{fixed}' (guide, rod, crank or block)")
    scale = max(crank, rod, offset)
    diff = crank + offset - rod
    grashof = "change point" if abs(diff) <= TOL * scale else ("Grashof" if diff < 0 else "non-Grashof")
    return SliderCrankClass(crank, rod, offset, grashof, fixed)


# ---------------------------------------------------------------------------- closed forms


def four_bar_transmission(frame: float, input: float, coupler: float, output: float
                          ) -> tuple[float, float]:
    """Range (μ_min, μ_max) of the transmission angle μ, the angle between coupler and output
    at their hinge, over the motion of the input on one assembly branch (cosine law on the
    diagonal from the input's moving hinge to the output's fixed pivot)."""
    a, b, c, d = input, coupler, output, frame
    f_lo = max(abs(d - a), abs(b - c))
    f_hi = min(d + a, b + c)
    if f_lo > f_hi:
        raise StructureError("these four-bar lengths cannot be assembled")

    def mu(f: float) -> float:
        return math.acos(max(-1.0, min(1.0, (b * b + c * c - f * f) / (2 * b * c))))

    return mu(f_lo), mu(f_hi)


def min_transmission(mu_range: tuple[float, float]) -> float:
    """The worst transmission angle over the range: the least of μ and π − μ."""
    lo, hi = mu_range
    return min(lo, math.pi - hi)


def slider_crank_transmission(crank: float, rod: float, offset: float) -> tuple[float, float]:
    """Range of the transmission angle μ = 90° − |β| of a type I slider-crank driven by its
    crank, β the angle between the rod and the line of stroke."""
    r, l, e = crank, rod, abs(offset)
    s_hi = min(1.0, (r + e) / l)
    s_lo = 0.0 if e <= r else (e - r) / l
    return math.pi / 2 - math.asin(s_hi), math.pi / 2 - math.asin(min(1.0, s_lo))


# ---------------------------------------------------------------------------- mechanisms


@dataclass(frozen=True)
class LoopReport:
    """Grashof report of a four-link loop of a mechanism (the mechanism itself or its base loop:
    the frame, the driving link and the first dyad)."""

    chain: str  # "four-bar", "slider-crank", "two-slider", "three-slider", "four-slider"
    links: dict[str, str]  # role -> link name
    lengths: dict[str, float]
    name: str
    grashof: str | None = None
    type: str | None = None
    inversion: str | None = None
    input_turns_fully: bool | None = None
    transmission: tuple[float, float] | None = None
    min_transmission: float | None = None
    input_limits: tuple[float, float] | None = None
    dead_positions: dict | None = None
    notes: tuple[str, ...] = field(default=())

    def as_dict(self) -> dict:
        def deg(v):
            return None if v is None else [math.degrees(x) for x in v]

        return {
            "chain": self.chain, "links": self.links, "lengths": self.lengths, "name": self.name,
            "grashof": self.grashof, "type": self.type, "inversion": self.inversion,
            "input_turns_fully": self.input_turns_fully,
            "transmission_angle_deg": deg(self.transmission),
            "min_transmission_angle_deg": (None if self.min_transmission is None
                                           else math.degrees(self.min_transmission)),
            "input_limits": None if self.input_limits is None else list(self.input_limits),
            "dead_positions": self.dead_positions, "notes": list(self.notes),
        }


def _unfolded(mech: Mechanism):
    from .assur import unfold

    everything = Group(links=mech.link_names, joints=tuple(j.name for j in mech.joints), drivers=())
    G, _, _ = unfold(mech, everything)
    return G


def _cycle_edges(G, cycle: list[str]):
    """Edges (u, v, data) along the node cycle, or None if the loop is not simple."""
    out = []
    for i, u in enumerate(cycle):
        v = cycle[(i + 1) % len(cycle)]
        data = G.get_edge_data(u, v)
        if not data or len(data) != 1:
            return None
        out.append((u, v, next(iter(data.values()))))
    return out


def _loop_candidates(mech: Mechanism, G) -> list[list[str]]:
    """Four-link loops to classify: the whole mechanism if it is one, else the frame, the
    driving link and the first group attached to both (the base four-bar of a six-bar)."""
    if G.number_of_nodes() == 4 and G.number_of_edges() == 4:
        simple = nx.Graph(G)
        cycles = [c for c in nx.simple_cycles(simple) if len(c) == 4]
        if cycles:
            return [cycles[0]]
    try:
        groups = solution_order(mech)
    except StructureError:  # over- or under-constrained: no base loop to speak of
        return []
    if not groups or groups[0].size != 1 or not groups[0].drivers:
        return []
    crank = groups[0].links[0]
    out = []
    for g in groups[1:]:
        members = set(g.links) | {n for n in G.nodes if isinstance(n, str) and ":" in n
                                  and _owner_joint(n) in g.joints}
        nodes = members | {mech.frame, crank}
        if len(nodes) != 4:
            continue
        sub = nx.Graph(G.subgraph(nodes))
        if G.subgraph(nodes).number_of_edges() != 4:
            continue
        cycles = [c for c in nx.simple_cycles(sub) if len(c) == 4]
        if cycles:
            out.append(cycles[0])
            break
    return out


def _owner_joint(node: str) -> str:
    return node.split(":", 1)[0]


def _pt(mech: Mechanism, name: str) -> np.ndarray:
    return np.asarray(mech.points[name], dtype=float)


def _edge_point(mech: Mechanism, d: dict) -> np.ndarray | None:
    if d["letter"] == "R" and "point" in d:
        return _pt(mech, d["point"])
    if d["letter"] == "P" and "center" in d:  # curved slot: a hinge at the arc's centre
        return _pt(mech, d["center"])
    return None


def loop_cycles(mech: Mechanism) -> list[list[str]]:
    """The four-link loops `loops` classifies: found from the structure alone (links, pairs,
    solution order), so the same for every drawing of it (a design sweep finds them once)."""
    return _loop_candidates(mech, _unfolded(mech))


def loops(mech: Mechanism, cycles: list[list[str]] | None = None) -> list[LoopReport]:
    """Grashof reports of the four-link loops of `mech` (see `LoopReport`); `cycles`: its
    `loop_cycles`, if known (those of another drawing of the same structure)."""
    G = _unfolded(mech)
    out = []
    for cyc in _loop_candidates(mech, G) if cycles is None else cycles:
        # rotate so that the frame comes first
        k = cyc.index(mech.frame)
        cyc = cyc[k:] + cyc[:k]
        edges = _cycle_edges(G, cyc)
        if edges is None or any(d.get("gear") for *_, d in edges):
            continue
        out.append(_classify_loop(mech, cyc, edges))
    return out


def _driver_of(mech: Mechanism, cyc: list[str]):
    """The driver acting on the loop at the frame, and the driven link's name."""
    for d in mech.drivers:
        if d.base == mech.frame and d.driven in cyc:
            return d
    return None


def _classify_loop(mech: Mechanism, cyc: list[str], edges) -> LoopReport:
    curved = [d for *_, d in edges if d["letter"] == "P" and "center" in d]
    effective = ["R" if (d["letter"] == "R" or "center" in d) else "P" for *_, d in edges]
    notes = tuple(f"curved slot {d['joint']} counted as a hinge at its centre {d['center']}"
                  for d in curved)
    nP = effective.count("P")
    if nP == 0:
        return _four_bar(mech, cyc, edges, notes)
    if nP == 1:
        return _slider_crank(mech, cyc, edges, effective, notes)
    names = {2: "two-slider", 3: "three-slider", 4: "four-slider"}
    links = {f"link{i}": ln for i, ln in enumerate(cyc)}
    if nP == 2:
        i, j = [k for k, x in enumerate(effective) if x == "P"]
        adjacent = (j - i) % 4 in (1, 3)
        if adjacent:
            shared = cyc[j] if (j - i) % 4 == 1 else cyc[i]
            if shared == mech.frame:
                name = "double slider (Kreuzschieber, elliptic trammel; Rosenauer's basic task V)"
            else:
                name = ("two adjacent sliders on a moving link: Scotch yoke (Kreuzschleife; "
                        "Rosenauer's basic task V)")
        else:
            name = "two opposite sliders (Rosenauer's basic task VI)"
        return LoopReport("two-slider", links, {}, name, notes=notes)
    if nP == 3:
        return LoopReport(names[3], links, {}, "three sliders: the fourth hinge cannot turn, the "
                          "chain acts as the three-link wedge (Rosenauer §95)", notes=notes)
    return LoopReport(names[4], links, {}, "four sliders: not constrained (Rosenauer §95)",
                      notes=notes)


def _four_bar(mech: Mechanism, cyc, edges, notes) -> LoopReport:
    P = [_edge_point(mech, d) for *_, d in edges]  # P[i] joins cyc[i] and cyc[i+1]
    lengths = [float(np.hypot(*(P[i - 1] - P[i]))) for i in range(4)]  # of cyc[i]
    drv = _driver_of(mech, cyc)
    # input: the driven link if it is pivoted on the frame, else cyc[1]
    if drv is not None and drv.driven in (cyc[1], cyc[3]):
        inp = drv.driven
    else:
        inp = cyc[1]
    if inp == cyc[3]:  # walk the loop the other way so that the input follows the frame
        cyc = [cyc[0], cyc[3], cyc[2], cyc[1]]
        P = [P[3], P[2], P[1], P[0]]
        lengths = [lengths[0], lengths[3], lengths[2], lengths[1]]
    d_, a, b, c = lengths
    O_in, A, B, O_out = P[0], P[1], P[2], P[3]
    # crossed (antiparallel) when the loop O_in A B O_out, as drawn, intersects itself
    crossed = _segments_cross(O_in, A, B, O_out) or _segments_cross(A, B, O_out, O_in)
    cls = classify_four_bar(d_, a, b, c, crossed=crossed)
    mu = four_bar_transmission(d_, a, b, c)
    report = dict(
        chain="four-bar",
        links={"frame": cyc[0], "input": cyc[1], "coupler": cyc[2], "output": cyc[3]},
        lengths={"frame": d_, "input": a, "coupler": b, "output": c},
        name=cls.name, grashof=cls.grashof, type=cls.type,
        input_turns_fully=cls.input_turns_fully, transmission=mu,
        min_transmission=min_transmission(mu), notes=notes)
    if drv is not None and drv.driven == cyc[1] and mech.joint(drv.joint).kind == "revolute":
        offset = _input_offset(mech, drv, O_in, A)
        lim = _four_bar_input_limits(O_in, A, O_out, a, b, c, d_)
        if lim is not None:
            report["input_limits"] = (lim[0] + offset, lim[1] + offset)
        elif not cls.output_turns_fully:
            report["dead_positions"] = _four_bar_dead_positions(O_in, A, B, O_out, a, b, c, d_, offset)
    return LoopReport(**report)


def _cross2(u: np.ndarray, v: np.ndarray) -> float:
    return float(u[0] * v[1] - u[1] * v[0])


def _segments_cross(p1, p2, q1, q2) -> bool:
    """The segments p1p2 and q1q2 cross at a point inside both."""
    d1, d2 = _cross2(p2 - p1, q1 - p1), _cross2(p2 - p1, q2 - p1)
    d3, d4 = _cross2(q2 - q1, p1 - q1), _cross2(q2 - q1, p2 - q1)
    return d1 * d2 < 0 and d3 * d4 < 0


def _angle(v: np.ndarray) -> float:
    return float(math.atan2(v[1], v[0]))


def _input_offset(mech: Mechanism, drv, hinge: np.ndarray, moving: np.ndarray) -> float:
    """Driver input minus the angle of the line hinge → moving hinge (constant)."""
    return mech.driver_input_at_design(drv) - _angle(moving - hinge)


def _four_bar_input_limits(O: np.ndarray, A: np.ndarray, O4: np.ndarray, a, b, c, d):
    """(lo, hi) angles of the input line O→A at its limit positions (coupler and output in
    line), unwrapped around the design angle; None if the input turns fully."""
    theta_f = _angle(O4 - O)
    phi0 = math.remainder(_angle(A - O) - theta_f, 2 * math.pi)  # signed, (−π, π]
    f_lo, f_hi = abs(b - c), b + c
    c_hi = (a * a + d * d - f_lo * f_lo) / (2 * a * d)
    c_lo = (a * a + d * d - f_hi * f_hi) / (2 * a * d)
    if c_hi >= 1 and c_lo <= -1:
        return None
    a1 = math.acos(min(1.0, max(-1.0, c_hi)))
    a2 = math.acos(min(1.0, max(-1.0, c_lo)))
    if c_hi >= 1:  # one interval about φ = 0
        lo, hi = -a2, a2
    elif c_lo <= -1:  # one interval about φ = π
        lo, hi = a1, 2 * math.pi - a1
        if phi0 < 0:
            phi0 += 2 * math.pi
    elif phi0 >= 0:
        lo, hi = a1, a2
    else:
        lo, hi = -a2, -a1
    base = _angle(A - O)
    return base + (lo - phi0), base + (hi - phi0)


def _assembly_sign(A, B, O4) -> float:
    """Side of B relative to the diagonal A → O4 (the four-bar's assembly branch)."""
    u, v = O4 - A, B - A
    return float(np.sign(u[0] * v[1] - u[1] * v[0]))


def _four_bar_dead_positions(O, A, B, O4, a, b, c, d, offset) -> dict | None:
    """Output limit positions of a crank-driven four-bar (crank and coupler in line): input
    values there, output angles, output swing, the crank's dead-position angle δ
    (*Totlagenwinkel*) and the time ratio (π + δ)/(π − δ)."""
    sigma = _assembly_sign(A, B, O4)
    out = []
    for g, stretched in ((b + a, True), (b - a, False)):
        if g <= 0 or g > d + c or g < abs(d - c):
            return None
        cands = []
        for s in (1.0, -1.0):
            # B on the circle about O4 with |OB| = g: angle at O between O→O4 and O→B
            cosb = (d * d + g * g - c * c) / (2 * d * g)
            beta = math.acos(max(-1.0, min(1.0, cosb)))
            th = _angle(O4 - O) + s * beta
            Bp = O + g * np.array([math.cos(th), math.sin(th)])
            u = (Bp - O) / g
            Ap = O + (a * u if stretched else -a * u)
            if _assembly_sign(Ap, Bp, O4) in (sigma, 0.0):
                cands.append((Ap, Bp))
        if not cands:
            return None
        Ap, Bp = cands[0]
        out.append((Ap, Bp))
    (A1, B1), (A2, B2) = out
    in1, in2 = _angle(A1 - O) + offset, _angle(A2 - O) + offset
    o1, o2 = _angle(B1 - O4), _angle(B2 - O4)
    swing = abs(math.remainder(o1 - o2, 2 * math.pi))
    crank_between = abs(math.remainder(in1 - in2, 2 * math.pi))
    delta = abs(math.pi - crank_between)
    return {"input": [in1, in2], "output_angle": [o1, o2], "output_swing": swing,
            "dead_position_angle": delta,
            "time_ratio": (math.pi + delta) / (math.pi - delta) if delta < math.pi else None}


def _slider_crank(mech: Mechanism, cyc, edges, effective, notes) -> LoopReport:
    k = effective.index("P")  # pair k joins cyc[k] and cyc[k+1]
    u = np.asarray(edges[k][2]["axis"], dtype=float)
    u = u / np.hypot(*u)
    P = [_edge_point(mech, d) for *_, d in edges]
    pl_a, pl_b = cyc[k], cyc[(k + 1) % 4]  # the two sliding links
    R_a, R_b = P[(k - 1) % 4], P[(k + 1) % 4]  # their hinges
    X, Y = cyc[(k + 3) % 4], cyc[(k + 2) % 4]  # hinge-hinge links next to pl_a and pl_b
    hinge_xy = P[(k + 2) % 4]  # the hinge joining X and Y
    len_X = float(np.hypot(*(R_a - hinge_xy)))
    len_Y = float(np.hypot(*(R_b - hinge_xy)))
    e = abs(_cross2(u, R_a - R_b))
    tol = TOL * max(len_X, len_Y, e)
    # the crank is the hinge-hinge link that turns fully (the shorter one if neither does);
    # the guide is the sliding link next to it, the block the one next to the rod
    # (crank = rod: the one hinged to the frame's sliding link is the crank, type I)
    if abs(len_X - len_Y) <= tol and mech.frame in (pl_a, pl_b):
        use_X = pl_a == mech.frame
    else:
        use_X = len_X + e <= len_Y + tol or (len_Y + e > len_X + tol and len_X <= len_Y)
    if use_X:
        crank, rod, guide, block = X, Y, pl_a, pl_b
        r, l = len_X, len_Y
        H_cg, H_cr, H_rb = R_a, hinge_xy, R_b  # hinges crank-guide, crank-rod, rod-block
    else:
        crank, rod, guide, block = Y, X, pl_b, pl_a
        r, l = len_Y, len_X
        H_cg, H_cr, H_rb = R_b, hinge_xy, R_a
    role = {guide: "guide", rod: "rod", crank: "crank", block: "block"}
    cls = classify_slider_crank(r, l, e, role[mech.frame])
    report = dict(chain="slider-crank",
                  links={"crank": crank, "rod": rod, "block": block, "guide": guide},
                  lengths={"crank": r, "rod": l, "offset": e}, name=cls.name,
                  grashof=cls.grashof, type=f"type {cls.inversion}", inversion=cls.inversion,
                  notes=notes)
    drv = _driver_of(mech, cyc)
    if mech.frame in (guide, block):
        # types I and IV: the line of stroke is fixed. D is the hinge-hinge link pivoted on the
        # frame (at O), E the other one, hinged to D at A and to the sliding link at B.
        if mech.frame == guide:
            D, O, A, B = crank, H_cg, H_cr, H_rb
        else:
            D, O, A, B = rod, H_rb, H_cr, H_cg
        rd, le = float(np.hypot(*(A - O))), float(np.hypot(*(B - A)))
        mu = slider_crank_transmission(rd, le, e)
        report["transmission"] = mu
        report["min_transmission"] = min_transmission(mu)
        turns = rd + e <= le + tol
        if drv is not None:
            report["input_turns_fully"] = turns and drv.driven == D
            report.update(_stroke_limits(mech, drv, D, O, A, B, u, rd, le, turns))
    elif cls.inversion == "II" and drv is not None:
        # the rod is fixed: the crank turns about H_cr, the slotted lever (the block) swings
        # about H_rb; its line passes through the crank pin H_cg
        report["input_turns_fully"] = drv.driven == crank and cls.grashof != "non-Grashof"
        if drv.driven == crank and cls.grashof == "Grashof" and mech.joint(drv.joint).kind == "revolute":
            report["dead_positions"] = _lever_limits(mech, drv, H_cr, H_cg, H_rb, u, r, l, e)
    elif cls.inversion == "III" and drv is not None:
        report["input_turns_fully"] = cls.grashof != "non-Grashof"
    return LoopReport(**report)


def _stroke_limits(mech: Mechanism, drv, D, O, A, B, u, r, l, turns) -> dict:
    """Limit positions of a slider-crank whose line of stroke is fixed (types I and IV): the
    dead centres (link D on the frame and the rod in line) when D turns fully, else the limits
    of D's swing; as driver input values."""
    n = np.array([-u[1], u[0]])
    e_signed = float(np.dot(B - O, n))  # the line of stroke is {O + s·u + e·n}
    s0 = float(np.dot(B - O, u))
    joint = mech.joint(drv.joint)
    if joint.kind == "revolute" and drv.driven != D:
        return {}
    if not turns:
        if joint.kind != "revolute":
            return {}
        # D swings: |r sin φ − e| ≤ l, φ measured from u towards n
        phi0 = math.atan2(float(np.dot(A - O, n)), float(np.dot(A - O, u)))
        lims = []
        for b_ in ((e_signed + l) / r, (e_signed - l) / r):
            if abs(b_) <= 1:
                x = math.asin(b_)
                lims += [x, math.pi - x]
        rel = [math.remainder(x - phi0, 2 * math.pi) for x in lims]
        below = [x for x in rel if x < 0]
        above = [x for x in rel if x > 0]
        if not below or not above:
            return {}
        off = mech.driver_input_at_design(drv)
        return {"input_limits": (off + max(below), off + min(above))}
    sign = 1.0 if s0 - float(np.dot(A - O, u)) >= 0 else -1.0  # side of the pin along u
    s_ext = sign * math.sqrt(max(0.0, (l + r) ** 2 - e_signed ** 2))
    if abs(l - r) <= TOL * l and abs(e_signed) <= TOL * l:
        return _isosceles_stroke(mech, drv, O, A, u, n, s_ext, e_signed, s0, joint)
    s_fold = sign * math.sqrt(max(0.0, (l - r) ** 2 - e_signed ** 2))
    # crank angles at the dead centres: D points at (stretched) or away from the pin
    B_ext = O + s_ext * u + e_signed * n
    B_fold = O + s_fold * u + e_signed * n
    th_ext = _angle(B_ext - O)
    th_fold = _angle(O - B_fold)
    stroke = abs(s_ext - s_fold)
    between = abs(math.remainder(th_ext - th_fold, 2 * math.pi))
    delta = abs(math.pi - between)
    if joint.kind == "prismatic":
        ax = float(np.dot(joint.axis, u))
        lo, hi = sorted(((s_fold - s0) * ax, (s_ext - s0) * ax))
        return {"input_limits": (lo, hi)}
    offset = _input_offset(mech, drv, O, A)
    return {"dead_positions": {"input": [th_ext + offset, th_fold + offset],
                               "slider_position": [s_ext, s_fold], "stroke": stroke,
                               "dead_position_angle": delta,
                               "time_ratio": (math.pi + delta) / (math.pi - delta)}}


def _isosceles_stroke(mech: Mechanism, drv, O, A, u, n, s_ext, e_signed, s0, joint) -> dict:
    """The centric slider-crank whose rod is as long as its crank: its "folded dead centre"
    puts the slider on the crank pivot O, where the slider may also stay for good (every crank
    angle then closes the chain), a change position (*Verzweigungslage*) at the crank normal to
    the stroke. Followed through it, as the solver's branches do, the slider runs on to the
    other side: two stretched dead centres half a turn apart, stroke 2(l + r) = 4r, no quick
    return."""
    if joint.kind == "prismatic":
        ax = float(np.dot(joint.axis, u))
        lo, hi = sorted(((-abs(s_ext) - s0) * ax, (abs(s_ext) - s0) * ax))
        return {"input_limits": (lo, hi)}
    th = _angle(O + s_ext * u + e_signed * n - O)
    offset = _input_offset(mech, drv, O, A)
    return {"dead_positions": {"input": [th + offset, th + math.pi + offset],
                               "slider_position": [s_ext, -s_ext], "stroke": 2 * abs(s_ext),
                               "dead_position_angle": 0.0, "time_ratio": 1.0,
                               "change_positions": [th + math.pi / 2 + offset,
                                                    th - math.pi / 2 + offset]}}


def _lever_limits(mech: Mechanism, drv, C, A, B, u, r, d, e) -> dict:
    """Oscillating crank-slotted lever (type II) driven by its crank C–A: the lever about B
    swings while its slot line (through the pin A, at distance e from B) sweeps the crank
    circle; its limits are where the line touches the circle. Input values there, the lever's
    swing, δ and the time ratio of the quick return."""
    CB = C - B
    n0 = np.array([-u[1], u[0]])
    if float(np.dot(A - B, n0)) < 0:
        n0 = -n0  # the slot's normal pointing from B to the line: n·(X − B) = e on the line
    w = CB / d
    alpha0 = math.atan2(_cross2(w, n0), float(np.dot(w, n0)))  # from C − B to the normal
    a1, a2 = math.acos(max(-1.0, min(1.0, (e + r) / d))), math.acos(max(-1.0, min(1.0, (e - r) / d)))
    limits = (a1, a2) if alpha0 >= 0 else (-a1, -a2)
    inputs = []
    offset = _input_offset(mech, drv, C, A)
    for a in limits:
        n = np.array([w[0] * math.cos(a) - w[1] * math.sin(a), w[0] * math.sin(a) + w[1] * math.cos(a)])
        touch = C - (d * math.cos(a) - e) * n
        inputs.append(_angle(touch - C) + offset)
    between = abs(math.remainder(inputs[0] - inputs[1], 2 * math.pi))
    delta = abs(math.pi - between)
    return {"input": inputs, "output_swing": a2 - a1, "dead_position_angle": delta,
            "time_ratio": (math.pi + delta) / (math.pi - delta)}


__all__ = ["FourBarClass", "LoopReport", "SliderCrankClass", "classify_four_bar",
           "classify_slider_crank", "four_bar_transmission", "loops", "min_transmission",
           "slider_crank_transmission"]
