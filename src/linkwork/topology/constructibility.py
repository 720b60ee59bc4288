"""Constructibility of velocity plans: Wittenbauer's rule, Rosenauer's rule and the auxiliary
points that make a direct (trial-free) ruler construction possible.

Source: Rosenauer 1937, paper 2 (digest `000-rosenauer-papers-1937.md` §4), papers 1 and 7
(§3, §9). The polar velocity plan is drawn with two rules only:

* two points X, Y of one link: y − x ⟂ XY (the projection theorem);
* Rosenauer's extension: points X of one link and Y of another that lie on one line through
  the joint J of the two links have equal velocity projections on that line (the line through
  x ⟂ XJ carries the image of *every* point of the second link on the line XJ).

So a point K with a known image, on a link L hinged at J to a link T, gives T a **line
condition** (the plan image of each point of T on the mechanism line KJ lies on the line through
k ⟂ KJ) — "crossing one joint". A sliding pair gives one along the normal of its guide, a given
velocity direction one along the normal of that direction (the line through the pole). Two line
conditions on T meet in an **auxiliary point** of T (Rosenauer's Q, R, D, E: the intersection of
two link lines, regarded as a point of T) whose image is known at once; a known point and one more
condition, or two points, determine the link (its velocity image is similar to it).

`plan_velocities` propagates these rules through the chain (`Chain`, built from a `Mechanism` or
written out for the free chains of the papers) and returns the numbered construction script as
the books write it: ``q = (a ⟂ AQ) ∩ (b ⟂ BQ)``. The chain is *directly constructible* (Rosenauer's
rule: nowhere more than two joints between known velocities, one from each side) exactly when the
propagation reaches every link; where it stops the chain needs the classical similar point rows
(*ähnliche Punktreihen*, false position) and the links it could not reach are named.
`wittenbauer_rule` is the older test (Wittenbauer, *Graphische Dynamik* 1923 §176): from every
joint to every other without crossing more than one third joint.

The test is on the graph (links, pairs, the given data) and on the collinearities the design
fixes (points of one link on a line); incidences that happen only at one position are not
known to it, and the construction (`linkwork.constructions`) reports them as degenerate there.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from ..model import CamContact, CircularSlot, Gear, Mechanism, Prismatic, Revolute, RollingContact, Slot

#: the frame's image, the pole o of the velocity plan
POLE = "o"
#: Rosenauer's names for auxiliary points, in the order he uses them
AUX_NAMES = ("Q", "R", "D", "E", "S", "U", "V", "W", "X", "Y", "Z")


def literal(name: str) -> str:
    """A user's point or link name for a label, escaped so that the drawing prints it as written
    (``link_j`` stays link_j; only the books' own notation, P_{13} or v_A, is set as sub- or
    superscript)."""
    return "".join("\\" + c if c in "\\_^{}" else c for c in name)


def script(name: str) -> str:
    """A user's name as a braced sub- or superscript, printed as written: ``W_`` + script(name)
    labels the inflection point of ``name`` (``W_{O2}``, ``W_{pin\\_A}``)."""
    return "{" + literal(name) + "}"


def prose(text: str) -> str:
    """A label or a sentence made with :func:`upper`, :func:`lower` or :func:`literal` as plain
    prose: the escapes dropped, so that a user's ``pin_A`` reads as written in a step's text
    (the books' ``O_2`` stays as it is)."""
    text = re.sub(r"(?<!\\)([_^])\{((?:\\.|[^{}\\])*)\}", r"\1\2", text)  # W_{O2} → W_O2
    return re.sub(r"\\([\\_^{}])", r"\1", text)


def lower(name: str) -> str:
    """Image label of point ``name`` in the plan: ``B`` → ``b``, ``O4`` → ``o_4``; any other name
    lower-cased and escaped (:func:`literal`), so that ``pin_A`` → ``pin_a`` as written."""
    m = re.match(r"^([A-Za-z]+)(\d+)$", name)
    return f"{m.group(1).lower()}_{m.group(2)}" if m else literal(name.lower())


def upper(name: str) -> str:
    """Label of point ``name`` in the books' notation: ``O4`` → ``O_4``; any other name as
    written (escaped, :func:`literal`). Sentences made with it are read through :func:`prose`."""
    m = re.match(r"^([A-Za-z]+)(\d+)$", name)
    return f"{m.group(1)}_{m.group(2)}" if m else literal(name)


# ---------------------------------------------------------------------------- the chain
@dataclass(frozen=True)
class Chain:
    """A chain with its given data, as the constructibility test sees it.

    ``hinges``: (point, link, link); ``slides``: (pair, guide link, sliding link, point) — the
    two links turn together; ``slots``: (pair, guide link, pin link, pin point); ``meshes``:
    (pair, gear, gear, pitch point, centre, centre): the pitch point is the gears' relative
    pole. ``known``: links whose velocity state is given (the frame); ``drivers``: (link,
    pivot, reference) turned at a given rate about a pivot of a known link (reference None: a
    block translated along its guide); ``given``: points with a given velocity; ``directions``:
    points with a given velocity direction; ``collinear``: sets of points that stay on a line.
    """

    links: Mapping[str, tuple[str, ...]]
    hinges: tuple[tuple[str, str, str], ...]
    slides: tuple[tuple[str, str, str, str], ...] = ()
    slots: tuple[tuple[str, str, str, str], ...] = ()
    meshes: tuple[tuple[str, str, str, str, str, str], ...] = ()
    known: tuple[str, ...] = ()
    drivers: tuple[tuple[str, str, str | None], ...] = ()
    given: tuple[str, ...] = ()
    directions: tuple[str, ...] = ()
    collinear: tuple[frozenset[str], ...] = ()
    unsupported: tuple[str, ...] = ()  # pairs the test does not know (named in the report)
    frame: str | None = None
    #: cam contacts (pair, cam link, follower link, contact point): the velocities of the two
    #: links project equally on the common normal at the contact
    contacts: tuple[tuple[str, str, str, str], ...] = ()
    #: rolling contacts (pair, link, link, contact point): the point of contact is the two
    #: links' relative pole, for velocities a hinge
    rolls: tuple[tuple[str, str, str, str], ...] = ()
    #: curved slots (pair, guide link, pin link, pin point, centre point of the guide link): the
    #: relative velocity is tangent to the arc, so both links project equally on its radius
    arcs: tuple[tuple[str, str, str, str, str], ...] = ()  # the link whose images are the pole o (None: a free chain)
    #: points that lie on a cam contact's common normal at every position (pair, point): a
    #: roller's centre (the normal of a circle passes through its centre)
    on_normals: tuple[tuple[str, str], ...] = ()

    def restricted(self, links, known) -> "Chain":
        """The part of the chain on ``links`` with the links ``known`` given (a group of the
        solution order on the links solved before it)."""
        keep = set(links)
        return Chain({ln: p for ln, p in self.links.items() if ln in keep},
                     tuple(h for h in self.hinges if {h[1], h[2]} <= keep),
                     tuple(s for s in self.slides if {s[1], s[2]} <= keep),
                     tuple(s for s in self.slots if {s[1], s[2]} <= keep),
                     tuple(m for m in self.meshes if {m[1], m[2]} <= keep),
                     # in the chain's order (a set's order would change with the hash seed)
                     known=tuple(ln for ln in self.links if ln in set(known)), collinear=self.collinear, frame=self.frame,
                     contacts=tuple(c for c in self.contacts if {c[1], c[2]} <= keep),
                     rolls=tuple(c for c in self.rolls if {c[1], c[2]} <= keep),
                     arcs=tuple(c for c in self.arcs if {c[1], c[2]} <= keep),
                     on_normals=self.on_normals)

    @classmethod
    def free(cls, links: Mapping[str, str | tuple[str, ...]], *, given: tuple[str, ...] = (),
             directions: tuple[str, ...] = (), known: tuple[str, ...] = (),
             drivers: tuple[tuple[str, str, str | None], ...] = ()) -> "Chain":
        """A hinge chain from its links (``{"CDG": "CDG", "AC": "AC"}`` or point tuples): every
        point shared by two links is a hinge between them."""
        pts = {k: tuple(v) for k, v in links.items()}
        hinges = []
        names = list(pts)
        for i, a in enumerate(names):
            for b in names[i + 1:]:
                for p in pts[a]:
                    if p in pts[b]:
                        hinges.append((p, a, b))
        return cls(pts, tuple(hinges), known=known, drivers=drivers, given=given, directions=directions)

    @classmethod
    def from_mechanism(cls, mech: Mechanism, given=None) -> "Chain":
        """The chain of ``mech`` with its drivers, or its given point velocities (``given``:
        other given data instead of the mechanism's own; they replace its drivers)."""
        links = {ln.name: tuple(ln.points) for ln in mech.links}
        hinges, slides, slots, meshes, unsupported, contacts, rolls, arcs = [], [], [], [], [], [], [], []
        on_normals = []
        for j in mech.joints:
            if isinstance(j, Revolute):
                hinges.append((j.point, *j.links))
            elif isinstance(j, Prismatic):
                slides.append((j.name, j.links[0], j.links[1], j.point))
            elif isinstance(j, Slot):
                slots.append((j.name, j.links[0], j.links[1], j.point))
            elif isinstance(j, CamContact):
                contacts.append((j.name, *j.links, contact_point_name(mech, j)))
                if j.follower == "roller" and j.point:
                    on_normals.append((j.name, j.point))
            elif isinstance(j, CircularSlot):
                arcs.append((j.name, *j.links, j.point, j.center))
            elif isinstance(j, RollingContact):
                rolls.append((j.name, *j.links, contact_point_name(mech, j)))
            elif isinstance(j, Gear) and j.gear_kind in ("external", "internal"):
                c1, c2 = (mech.wheel_centre(j, w) for w in j.links)
                meshes.append((j.name, *j.links, pitch_point_name(mech, j), c1, c2))
            else:
                unsupported.append(f"{j.name} ({j.kind})")
        for name, g1, g2, t, c1, c2 in meshes:
            links[g1] += (t,)
            links[g2] += (t,)
        for name, a, b, k in contacts + rolls:
            links[a] += (k,)
            links[b] += (k,)
        collinear = design_collinear(mech, meshes)
        for name, a, b, k in rolls:
            # wheels on two pivots of one carrier touch on the line of their centres
            carrier = getattr(mech.joint(name), "carrier", None)
            centres = [j.point for j in mech.joints for w in (a, b)
                       if carrier and isinstance(j, Revolute) and set(j.links) == {w, carrier}]
            if len(centres) == 2:
                collinear += (frozenset((k, *centres)),)
        drivers = []
        for d in mech.drivers:
            j = mech.joint(d.joint)
            if d.base != mech.frame:
                unsupported.append(f"driver {d.joint} (acts between two moving links)")
            elif isinstance(j, Revolute):
                drivers.append((d.driven, j.point, d.reference))
            elif isinstance(j, Prismatic):
                drivers.append((d.driven, j.point, None))
            else:
                unsupported.append(f"driver {d.joint} ({j.kind})")
        # given point velocities and directions (a chain without drivers, Rosenauer 1937 paper 2)
        data = mech.given if given is None else tuple(given)
        given = tuple(g.point for g in data if g.kind == "velocity")
        directions = tuple(g.point for g in data if g.kind == "direction")
        if data:
            drivers = []
        return cls(links, tuple(hinges), tuple(slides), tuple(slots), tuple(meshes),
                   known=(mech.frame,), drivers=tuple(drivers), given=given, directions=directions,
                   collinear=collinear, unsupported=tuple(unsupported),
                   frame=mech.frame, contacts=tuple(contacts), rolls=tuple(rolls), arcs=tuple(arcs),
                   on_normals=tuple(on_normals))


def contact_point_name(mech: Mechanism, pair) -> str:
    """The name of a cam contact's point of contact (the pair's name where it is free)."""
    return pair.name if pair.name not in mech.points else f"{pair.name}_contact"


def pitch_point_name(mech: Mechanism, gear: Gear) -> str:
    """The name of a gear pair's pitch point (Rosenauer's T), unused by the mechanism's points."""
    for name in ("T", f"T_{gear.name}"):
        if name not in mech.points:
            return name
    return f"T_{gear.name}_pitch"


def design_collinear(mech: Mechanism, meshes=()) -> tuple[frozenset[str], ...]:
    """Points of one link that lie on a line in the drawing (they stay so), and the centres and
    pitch point of each gear pair."""
    out: list[frozenset[str]] = []
    for ln in mech.links:
        pts = list(dict.fromkeys(ln.points))
        for i, a in enumerate(pts):
            for b in pts[i + 1:]:
                pa, pb = mech.points[a], mech.points[b]
                d = pb - pa
                if np.hypot(*d) == 0:
                    continue
                on = frozenset(p for p in pts if abs(d[0] * (mech.points[p] - pa)[1] - d[1] * (mech.points[p] - pa)[0])
                               <= 1e-9 * mech.length_scale * np.hypot(*d))
                if len(on) >= 3 and on not in out:
                    out.append(on)
    for _, _, _, t, c1, c2 in meshes:
        out.append(frozenset((t, c1, c2)))
    return tuple(out)


# ---------------------------------------------------------------------------- the script
@dataclass(frozen=True)
class MechLine:
    """A line on the mechanism drawing: through two points (``join``), or through ``points[0]``
    normal to the guide of ``pair`` (``normal``) or to a given velocity direction
    (``direction``)."""

    kind: str
    points: tuple[str, ...]
    pair: str | None = None

    def text(self) -> str:
        if self.kind == "join":
            return "".join(upper(p) for p in self.points)
        if self.kind == "normal":
            return f"the normal to {self.pair} at {upper(self.points[0])}"
        if self.kind == "contact":
            return f"the common normal of {self.pair} at {upper(self.points[0])}"
        return f"the normal to v_{upper(self.points[0])} at {upper(self.points[0])}"


@dataclass(frozen=True)
class PlanLine:
    """A line of the plan: through the image of ``anchor`` = (link, point), perpendicular to the
    mechanism line ``line`` (so parallel to a guide for a ``normal`` line)."""

    anchor: tuple[str, str]
    line: MechLine
    #: the pairs crossed from the anchor's link to the link the line is drawn for, as
    #: (from link, to link, hinge point or sliding pair): the velocity projection carries over
    #: unchanged, an acceleration's changes by the normal (and Coriolis) terms of each crossing
    via: tuple[tuple[str, str, str], ...] = ()


@dataclass(frozen=True)
class AuxPoint:
    """Rosenauer's auxiliary point: the intersection of two mechanism lines, taken as a point of
    ``link``."""

    name: str
    link: str
    lines: tuple[MechLine, MechLine]


@dataclass(frozen=True)
class Step:
    """One step of the construction script.

    kinds: ``driver`` (link, pivot, reference: the given rate), ``given`` (a point's given
    velocity), ``meet`` (the image of (link, point) where two plan lines meet), ``divide`` (a
    point on the line of two known images of its link, in the ratio of the drawing),
    ``copy`` (a point of a link that turns with ``partner``: its image differs from the known
    point's image as the partner's images do; the frame as partner: the link translates)."""

    kind: str
    link: str
    point: str
    text: str
    lines: tuple[PlanLine, ...] = ()
    aux: AuxPoint | None = None
    base: tuple[str, ...] = ()  # divide: two points of the link; copy: the known point
    partner: str | None = None
    reference: str | None = None


@dataclass(frozen=True)
class VelocityScript:
    """The result of the constructibility test: the numbered script, the auxiliary points, the
    order in which the links become known, and the verdicts."""

    steps: tuple[Step, ...]
    aux: tuple[AuxPoint, ...]
    order: tuple[str, ...]
    unreached: tuple[str, ...]
    unsupported: tuple[str, ...]
    labels: Mapping[tuple[str, str], str] = field(default_factory=dict)
    #: for each (link, point) the other (link, point) whose image it shares (hinges, pitch points)
    shared: Mapping[tuple[str, str], tuple[tuple[str, str], ...]] = field(default_factory=dict)
    #: false position (similar point rows): the script is drawn for this trial driver (link,
    #: pivot, reference) and then scaled about o to the given driver ``scale_by`` (Rosenauer
    #: 1937 paper 7, remark: a binary link driving)
    trial: tuple[str, str, str] | None = None
    scale_by: tuple[str, str, str] | None = None
    #: false position with two trials: the binary link (name, end K, its link there, end M, its
    #: link there) left out of the trial chain; the trial rate is found where the trial images
    #: of K and M again satisfy km ⟂ KM (the check, affine in the trial rate: two trials)
    check: tuple[str, str, str, str, str] | None = None
    #: steps whose two lines are (nearly) parallel at a position of the drawing although the
    #: planner chose the widest crossing the rules allow (only with the drawing's geometry)
    coincidences: tuple[str, ...] = ()

    @property
    def direct(self) -> bool:
        """Rosenauer's rule holds: every link reached without trial (similar point rows)."""
        return not self.unreached and not self.unsupported and self.trial is None

    @property
    def complete(self) -> bool:
        """Every link reached: directly, or by false position from a trial driver."""
        return not self.unreached and not self.unsupported

    @property
    def by_two_trials(self) -> bool:
        """Drawn by false position with two trials (similar point rows fixed by ``check``); the
        links the rule alone does not reach stay named in ``unreached``."""
        return self.check is not None and not self.unsupported

    def verdict(self) -> str:
        if self.check is not None:
            t, d, c = self.trial, self.scale_by, self.check
            src = f"the driver {d[0]}" if d is not None else "its given velocities"
            return (f"not directly constructible from {src} (Rosenauer's rule fails, and "
                    f"no second crank's trial rate makes it direct); by false position with two trials: "
                    f"without the binary link {c[0]} the chain is direct from {src} and a trial rate of "
                    f"{t[0]} about {upper(t[1])}; two trial rates give two rows of images, and the check "
                    f"{lower(c[1])}{lower(c[3])} ⟂ {upper(c[1])}{upper(c[3])} fixes the point of each "
                    "row (similar point rows)")
        if self.trial is not None:
            t, d = self.trial, self.scale_by
            return (f"not directly constructible from the driver {d[0]} (Rosenauer's rule fails); "
                    f"by false position: a trial rate of {t[0]} about {upper(t[1])} makes the plan "
                    f"direct, then every image is moved along its ray from o in the ratio of "
                    f"{d[0]}'s given to its trial velocity (similar point rows)")
        if self.unsupported:
            return ("not decided: the test does not know the pairs " + ", ".join(self.unsupported))
        if self.unreached:
            return ("not directly constructible: the links " + ", ".join(self.unreached) + " are "
                    "reached from known velocities only across more than two joints; the plan "
                    "needs similar point rows (false position)")
        n = len(self.aux)
        return prose("directly constructible (Rosenauer's rule holds)" +
                     (f", with {n} auxiliary point{'s' if n > 1 else ''} " +
                      ", ".join(f"{a.name} = {a.lines[0].text()} \u2229 {a.lines[1].text()} (in {a.link})"
                                for a in self.aux) if n else ", without auxiliary points"))

    def as_dict(self) -> dict:
        return {"direct": self.direct, "verdict": self.verdict(),
                "false_position": None if self.trial is None else
                {"trial_driver": self.trial[0], "pivot": self.trial[1],
                 "scaled_to": None if self.scale_by is None else self.scale_by[0],
                 "trials": 1 if self.check is None else 2,
                 "check_link": None if self.check is None else self.check[0]},
                "auxiliary_points": [{"name": a.name, "link": a.link,
                                      "lines": [prose(ln.text()) for ln in a.lines]} for a in self.aux],
                "order": list(self.order), "unreached": list(self.unreached),
                "unsupported": list(self.unsupported), "script": [prose(s.text) for s in self.steps]}

    def script(self) -> list[str]:
        """The numbered construction script (the names in it as written, :func:`prose`)."""
        return [f"{k:2d}. {prose(s.text)}" for k, s in enumerate(self.steps, 1)]


@dataclass(frozen=True)
class WittenbauerVerdict:
    holds: bool
    worst: tuple[str, str, tuple[str, ...]] | None  # two joints and the joints crossed between

    def as_dict(self) -> dict:
        return {"holds": self.holds, "verdict": self.text()}

    def text(self) -> str:
        if self.holds:
            return "holds: every joint reaches every other across at most one third joint"
        a, b, path = self.worst
        return (f"fails: from {a} to {b} the shortest way crosses {len(path)} joints "
                f"({', '.join(path)})")


def wittenbauer_rule(chain: Chain) -> WittenbauerVerdict:
    """Wittenbauer's rule (*Graphische Dynamik* §176): the velocity plan can be drawn directly
    if one can get from every joint to every other without crossing more than one third joint
    (joints are neighbours when they lie on one link)."""
    import networkx as nx

    joints: dict[str, set[str]] = {}
    for p, a, b in chain.hinges:
        joints.setdefault(p, set()).update((a, b))
    for entry in chain.slides + chain.slots + chain.contacts + tuple(a[:4] for a in chain.arcs):
        joints.setdefault(entry[3], set()).update(entry[1:3])
    # the points whose velocities are given count as joints of the chain (its free ends)
    for p in chain.given + chain.directions:
        joints.setdefault(p, set()).update(ln for ln, pts in chain.links.items() if p in pts)
    G = nx.Graph()
    G.add_nodes_from(joints)
    names = list(joints)
    for i, p in enumerate(names):
        for q in names[i + 1:]:
            if joints[p] & joints[q]:
                G.add_edge(p, q)
    worst = None
    for i, p in enumerate(names):
        lengths = nx.single_source_shortest_path_length(G, p)
        for q in names[i + 1:]:
            d = lengths.get(q, np.inf)
            if d > 2 and (worst is None or d > worst[0]):
                path = nx.shortest_path(G, p, q) if np.isfinite(d) else [p, "…", q]
                worst = (d, p, q, tuple(path[1:-1]))
    if worst is None:
        return WittenbauerVerdict(True, None)
    return WittenbauerVerdict(False, worst[1:])


# ---------------------------------------------------------------------------- the planner
class _Lines:
    """The mechanism lines met so far, with the points known to lie on each (so that a line
    named by two other of its points is recognised as the same line)."""

    def __init__(self, collinear) -> None:
        self.lines: list[tuple[MechLine, set[str]]] = []
        for s in collinear:
            pts = sorted(s)
            self.lines.append((MechLine("join", (pts[0], pts[1])), set(s)))

    def join(self, p: str, q: str) -> MechLine:
        # every line of the drawing is straight: a guide's or a contact's normal through two
        # known points of it is that line
        for line, members in self.lines:
            if line.kind != "direction" and p in members and q in members:
                return line
        line = MechLine("join", (p, q))
        self.lines.append((line, {p, q}))
        return line

    def special(self, kind: str, p: str, pair: str | None) -> MechLine:
        for line, members in self.lines:
            if line.kind == kind and line.pair == pair and p in members:
                return line
        line = MechLine(kind, (p,), pair)
        self.lines.append((line, {p}))
        return line

    def members(self, line: MechLine) -> set[str]:
        for ln, members in self.lines:
            if ln == line:
                return members
        raise KeyError(line)

    def parallel_family(self, a: MechLine, b: MechLine) -> bool:
        """Normals of one guide (or of one direction) are parallel: they never meet."""
        return a.kind == b.kind == "normal" and a.pair == b.pair


#: lines crossing at less than this sine (at some position) count as a coincidence of the drawing
NEAR_PARALLEL = 1e-3
#: the rules' first choice of lines is kept while they cross at least at this sine (about 6°)
COMFORTABLE = 0.1
#: lines through a point that cross at no more than this sine at every position drawn: the
#: points are in line there, and the image divides the known ones (`ensure_image`)
COLLINEAR = 1e-9


class _Planner:
    def __init__(self, chain: Chain, geometry: Mapping | None = None) -> None:
        self.c = chain
        self.geo = dict(geometry) if geometry is not None else None
        self.coincidences: list[str] = []
        # a gear pair's pitch point is the wheels' relative pole: for velocities, a hinge
        self.hinges = chain.hinges + tuple((t, g1, g2) for _, g1, g2, t, _, _ in chain.meshes) + \
            tuple((k, a, b) for _, a, b, k in chain.rolls)
        self.lines = _Lines(chain.collinear)
        for pair, point in chain.on_normals:
            for name, a, b, k in chain.contacts:
                if name == pair:
                    self.lines.members(self.lines.special("contact", k, pair)).add(point)
        self.steps: list[Step] = []
        self.aux: list[AuxPoint] = []
        self.order: list[str] = []
        self.points = {ln: list(dict.fromkeys(p)) for ln, p in chain.links.items()}
        used = {p for pts in chain.links.values() for p in pts}
        self.free_names = [n for n in AUX_NAMES if n not in used] + [f"Q{k}" for k in range(1, 100)
                                                                    if f"Q{k}" not in used]
        # image identity: a hinge's point has one image for both its links
        self.parent: dict[tuple[str, str], tuple[str, str]] = {}
        for p, a, b in self.hinges:
            self._union((a, p), (b, p))
        # rotation classes: links joined by sliding pairs turn together
        self.rot = {ln: ln for ln in chain.links}
        for _, g, s, _ in chain.slides:
            self.rot[self._rfind(g)] = self._rfind(s)
        self.known: set[str] = set()
        self.imaged: set[tuple[str, str]] = set()
        self.kpoints: dict[str, list[str]] = {ln: [] for ln in chain.links}
        self.conds: dict[str, list[PlanLine]] = {ln: [] for ln in chain.links}

    # ---------------------------------------------------------------- the drawing's geometry
    def _through(self, line: MechLine):
        """(point, direction) of a mechanism line in the drawing, or None where unknown."""
        g = self.geo
        if g is None:
            return None
        if line.kind == "join":
            p, q = (g.get(x) for x in line.points)
            return None if p is None or q is None else (p, q - p)
        d = g.get((line.kind, line.pair))
        p = g.get(line.points[0])
        return None if d is None or p is None else (p, d)

    def sine(self, a: MechLine, b: MechLine, reduce=np.min) -> float:
        """The smallest |sin| of the angle between two mechanism lines over the positions (1.0
        without geometry, so that the first choice stands; `reduce=np.max`: the largest)."""
        la, lb = self._through(a), self._through(b)
        if la is None or lb is None:
            return 1.0
        u, v = np.atleast_2d(la[1]), np.atleast_2d(lb[1])
        with np.errstate(invalid="ignore", divide="ignore"):
            s = np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) / (np.hypot(*u.T) * np.hypot(*v.T))
        s = s[~np.isnan(s)]  # positions where the mechanism is not assembled tell nothing
        return float(reduce(s)) if s.size else 1.0

    def place_aux(self, name: str, a: MechLine, b: MechLine) -> None:
        """Where the auxiliary point lies in the drawing (for the lines through it later)."""
        la, lb = self._through(a), self._through(b)
        if la is None or lb is None:
            return
        (p, u), (q, v) = (np.atleast_2d(x) for x in la), (np.atleast_2d(x) for x in lb)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            den = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
            t = ((q - p)[:, 0] * v[:, 1] - (q - p)[:, 1] * v[:, 0]) / den
            self.geo[name] = p + t[:, None] * u

    def note(self, sine: float, text: str) -> None:
        if self.geo is not None and sine < NEAR_PARALLEL:
            self.coincidences.append(f"{text}: the two lines are (nearly) parallel at a position of "
                                     "the drawing, and the rules allow no other lines here")

    # ---------------------------------------------------------------- bookkeeping
    def _find(self, k):
        while self.parent.get(k, k) != k:
            k = self.parent[k]
        return k

    def _union(self, a, b) -> None:
        ra, rb = self._find(a), self._find(b)
        if ra != rb:
            self.parent[ra] = rb

    def _rfind(self, ln: str) -> str:
        while self.rot[ln] != ln:
            ln = self.rot[ln]
        return ln

    def translates(self, ln: str) -> bool:
        """ln turns with the frame (slides on it, directly or through blocks)."""
        return self.c.frame is not None and self._rfind(ln) == self._rfind(self.c.frame)

    def omega_known(self, ln: str) -> bool:
        r = self._rfind(ln)
        return any(self._rfind(k) == r for k in self.known)

    def has_image(self, ln: str, p: str) -> bool:
        return self._find((ln, p)) in self.imaged

    def label(self, ln: str, p: str) -> str:
        """The plan label of the image of point p of link ln: o for the frame, b for a point
        whose image all its links share, b_link for one link's own point at a shared place."""
        if ln == POLE or ln == self.c.frame:
            return POLE
        if self.c.frame is not None and p in self.points[self.c.frame] and \
                self._find((ln, p)) == self._find((self.c.frame, p)):
            return POLE
        keys = {self._find((other, p)) for other, pts in self.points.items()
                if p in pts and other != self.c.frame}
        return lower(p) if len(keys) <= 1 else f"{lower(p)}_{{{literal(ln)}}}"

    def mark(self, ln: str, p: str) -> None:
        """The image of point p of link ln is now known (and so of every link hinged there)."""
        key = self._find((ln, p))
        self.imaged.add(key)
        for other, pts in self.points.items():
            if p in pts and self._find((other, p)) == key and p not in self.kpoints[other]:
                self.kpoints[other].append(p)

    def add_point(self, ln: str, p: str) -> None:
        if p not in self.points[ln]:
            self.points[ln].append(p)

    def pl_text(self, pl: PlanLine, target: str) -> str:
        a_ln, a_p = pl.anchor
        lab = self.label(a_ln, a_p)
        line = pl.line
        if line.kind == "join":
            members = self.lines.members(line)
            pair = (a_p, target) if a_p in members and target in members and a_p != target else line.points
            return f"({lab} \u27c2 {upper(pair[0])}{upper(pair[1])})"
        if line.kind == "normal":
            return f"({lab} \u2225 {line.pair})"
        if line.kind == "contact":
            return f"({lab} \u27c2 n_{line.pair})"
        return f"({lab} \u2225 v_{upper(line.points[0])})"

    # ---------------------------------------------------------------- steps
    def emit_meet(self, ln: str, p: str, a: PlanLine, b: PlanLine, aux: AuxPoint | None = None,
                  note: str = "") -> None:
        lab = self.label(ln, p)
        head = (f"{upper(p)} = {aux.lines[0].text()} \u2229 {aux.lines[1].text()}, a point of {ln}; "
                if aux else "")
        self.steps.append(Step("meet", ln, p, f"{head}{lab} = {self.pl_text(a, p)} \u2229 "
                                              f"{self.pl_text(b, p)}{note}", (a, b), aux))
        self.mark(ln, p)

    def ensure_image(self, ln: str, p: str) -> None:
        """Construct the image of point p of the known link ln (if not yet drawn)."""
        self.add_point(ln, p)
        if self.has_image(ln, p) or ln in self.c.known:
            if ln in self.c.known:
                self.mark(ln, p)
            return
        kp = [q for q in self.kpoints[ln] if q != p]
        r = self._rfind(ln)
        partner = next((k for k in self.known if self._rfind(k) == r and k != ln
                        and (k in self.c.known or len(self.kpoints[k]) >= 2)), None)
        if kp and partner is not None and partner in self.c.known:
            # a link translating with the frame: every image is the known one (no intersection
            # that the drawing's position could make parallel)
            self.steps.append(Step("copy", ln, p, f"{self.label(ln, p)} = {self.label(ln, kp[0])} "
                                   f"({ln} translates with the frame)", base=(kp[0],), partner=partner))
            self.mark(ln, p)
            return
        if len(kp) >= 2:
            pairs = [(x, y) for i, x in enumerate(kp) for y in kp[i + 1:] if not self.collinear(x, y, p)]
            choice = self.pick(pairs, lambda xy: self.sine(self.lines.join(xy[0], p), self.lines.join(xy[1], p)))
            best = None
            if choice is not None:
                x, y = choice
                lx, ly = self.lines.join(x, p), self.lines.join(y, p)
                best = (self.sine(lx, ly), x, y, lx, ly)
            line_pair = next(((x, y) for i, x in enumerate(kp) for y in kp[i + 1:]
                              if self.collinear(x, y, p)), None)
            if line_pair is None and best is not None and best[0] < NEAR_PARALLEL and \
                    self.sine(best[3], best[4], reduce=np.max) <= COLLINEAR:
                line_pair = best[1:3]  # in line at every position drawn (elliptical gears' M2)
            if best is not None and (best[0] >= NEAR_PARALLEL or line_pair is None):
                sn, x, y, lx, ly = best
                self.emit_meet(ln, p, PlanLine((ln, x), lx), PlanLine((ln, y), ly))
                self.note(sn, self.steps[-1].text)
                return
            # p on the line of two known points: divide their images (also where the two lines
            # of a meet would be parallel at this drawing)
            x, y = line_pair or kp[:2]
            self.steps.append(Step("divide", ln, p, f"{self.label(ln, p)} on {self.label(ln, x)}"
                                   f"{self.label(ln, y)}, dividing it as {upper(p)} divides "
                                   f"{upper(x)}{upper(y)}", base=(x, y)))
            self.mark(ln, p)
            return
        if kp and partner is not None:
            x = kp[0]
            if partner in self.c.known:
                text = f"{self.label(ln, p)} = {self.label(ln, x)} ({ln} translates with the frame)"
            else:
                for q in (x, p):
                    self.ensure_image(partner, q)
                text = (f"{self.label(ln, p)}: {self.label(ln, x)}{self.label(ln, p)} equal and parallel to "
                        f"{self.label(partner, x)}{self.label(partner, p)} ({ln} turns with {partner})")
            self.steps.append(Step("copy", ln, p, text, base=(x,), partner=partner))
            self.mark(ln, p)
            return
        raise AssertionError(f"link {ln} is not known enough to image {p}")

    def collinear(self, *pts: str) -> bool:
        return any(line.kind == "join" and set(pts) <= members for line, members in self.lines.lines)

    def on(self, p: str, line: MechLine) -> bool:
        return p in self.lines.members(line)

    def add_cond(self, ln: str, pl: PlanLine) -> bool:
        if ln in self.known or any(c.line == pl.line for c in self.conds[ln]):
            return False
        # a condition through a known point of the link tells nothing new
        if any(self.on(k, pl.line) for k in self.kpoints[ln]):
            return False
        self.conds[ln].append(pl)
        return True

    # ---------------------------------------------------------------- completing a link
    def complete(self, ln: str, level: int) -> bool:
        """Make ln known if its known points and line conditions allow; True if it is.

        ``level`` 0: only from what is known (two points, or a point and the turning of a
        partner); 1: also a point and one line condition (the dyad step); 2: also an auxiliary
        point where two line conditions meet. Returns whether a step was made or the link
        became known."""
        start = len(self.steps)
        while True:
            kp = self.kpoints[ln]
            if len(kp) >= 2 or (kp and self.omega_known(ln)):
                self.known.add(ln)
                self.order.append(ln)
                return True
            conds = [c for c in self.conds[ln] if not any(self.on(k, c.line) for k in kp)]
            if kp:
                if not conds or level < 1:
                    return len(self.steps) > start
                c = conds[0]
                x = kp[0]
                y = next((q for q in self.points[ln] if q != x and self.on(q, c.line)), None)
                if y is None and c.line.kind != "join" and c.line.points[0] != x:
                    y = c.line.points[0]  # the link's point at the guide's (a coincident point)
                    self.add_point(ln, y)
                aux = None
                if y is None:
                    if len(self.points[ln]) < 2:
                        return len(self.steps) > start
                    y = self.new_aux(ln, c.line, self.lines.join(x, self.other_point(ln, x, c.line)))
                    aux = self.aux[-1]
                self.emit_meet(ln, y, PlanLine((ln, x), self.lines.join(x, y)), c, aux)
                self.note(self.sine(self.lines.join(x, y), c.line) if aux is None else
                          self.sine(*aux.lines), self.steps[-1].text)
                continue
            pair = self.meeting_pair(conds)
            if pair is None or level < 2:
                return len(self.steps) > start
            a, b = pair
            common = [q for q in self.points[ln] if self.on(q, a.line) and self.on(q, b.line)]
            if common:
                self.emit_meet(ln, common[0], a, b)
            else:
                q = self.new_aux(ln, a.line, b.line)
                self.emit_meet(ln, q, a, b, self.aux[-1])
            self.note(self.sine(a.line, b.line), self.steps[-1].text)
            level = 1

    def meeting_pair(self, conds: list[PlanLine]):
        """Two line conditions that meet, in the order found; with the drawing's geometry the
        first pair that crosses at a comfortable angle, else the widest crossing."""
        cands = [(a, b) for i, a in enumerate(conds) for b in conds[i + 1:]
                 if not self.lines.parallel_family(a.line, b.line)]
        return self.pick(cands, lambda ab: self.sine(ab[0].line, ab[1].line))

    def pick(self, cands, sine):
        """The first candidate unless the drawing makes its lines cross at a small angle; then
        the first that crosses at COMFORTABLE or more, or else the widest."""
        if not cands:
            return None
        if self.geo is None:
            return cands[0]
        scored = [(sine(c), c) for c in cands]
        for sn, c in scored:
            if sn >= COMFORTABLE:
                return c
        return max(scored, key=lambda sc: sc[0])[1]

    def other_point(self, ln: str, x: str, line: MechLine | None = None) -> str:
        """A second point of ln for the line through x that meets ``line`` (the widest crossing
        in the drawing; the auxiliary point is not put at infinity by a coincidence)."""
        cands = [q for q in self.points[ln] if q != x]
        if line is None:
            return cands[0]
        return self.pick(cands, lambda q: self.sine(MechLine("join", (x, q)), line))

    def new_aux(self, ln: str, a: MechLine, b: MechLine) -> str:
        name = self.free_names.pop(0)
        self.place_aux(name, a, b)
        self.lines.members(a).add(name)
        self.lines.members(b).add(name)
        self.add_point(ln, name)
        self.aux.append(AuxPoint(name, ln, (a, b)))
        return name

    # ---------------------------------------------------------------- crossing joints
    def transfer(self) -> bool:
        """Carry what is known across every pair into the links not yet known."""
        new = False
        c = self.c
        for p, a, b in self.hinges:
            for L, T in ((a, b), (b, a)):
                if T in self.known:
                    continue
                if L in self.known:
                    if not self.has_image(T, p):
                        self.ensure_image(L, p)
                        new = True
                    continue
                kp = [k for k in self.kpoints[L] if k != p]
                if len(self.kpoints[L]) == 1 and kp:
                    new |= self.add_cond(T, PlanLine((L, kp[0]), self.lines.join(kp[0], p), ((L, T, p),)))
                for cond in list(self.conds[L]):
                    if self.on(p, cond.line):  # Rosenauer's extension: a line through the joint
                        new |= self.add_cond(T, PlanLine(cond.anchor, cond.line, cond.via + ((L, T, p),)))
                    elif cond.line.kind == "normal" and cond.anchor[0] == c.frame and self.translates(L):
                        # a link translating along a guide of the frame: the normal to the guide at
                        # any of its points carries its velocity's end (Rosenauer 1937 paper 8: the
                        # pole of the rolling lever on the normal to the slide at B)
                        line = self.lines.special("normal", p, cond.line.pair)
                        new |= self.add_cond(T, PlanLine((c.frame, p), line, cond.via + ((L, T, p),)))
        for pair, G, S, X in c.slides + c.slots:
            slide = (pair, G, S, X) in c.slides
            for L, T in ((G, S), (S, G)):
                if T in self.known:
                    continue
                normal = self.lines.special("normal", X, pair)
                if L in self.known:
                    self.ensure_image(L, X)
                    new |= self.add_cond(T, PlanLine((L, X), normal, ((L, T, pair),)))
                elif slide and len(self.kpoints[L]) == 1:
                    k = self.kpoints[L][0]
                    new |= self.add_cond(T, PlanLine((L, k), self.lines.special("normal", k, pair), ((L, T, pair),)))
                elif not slide and L == S and X in self.kpoints[S]:
                    new |= self.add_cond(T, PlanLine((L, X), normal, ((L, T, pair),)))
        for pair, G, S, X, C in c.arcs:
            for L, T in ((G, S), (S, G)):
                if T not in self.known and (L in self.known or (L == S and X in self.kpoints[S])):
                    self.ensure_image(L, X)
                    new |= self.add_cond(T, PlanLine((L, X), self.lines.join(C, X), ((L, T, pair),)))
        for pair, A, B, K in c.contacts:
            for L, T in ((A, B), (B, A)):
                if T not in self.known and L in self.known:
                    self.ensure_image(L, K)
                    new |= self.add_cond(T, PlanLine((L, K), self.lines.special("contact", K, pair),
                                                     ((L, T, pair),)))
        return new

    # ---------------------------------------------------------------- the run
    def run(self) -> VelocityScript:
        c = self.c
        for ln in c.known:
            self.known.add(ln)
            for p in self.points[ln]:
                self.mark(ln, p)
        for ln, pivot, ref in c.drivers:
            if ref is None:
                self.steps.append(Step("driver", ln, pivot, f"given: {self.label(ln, pivot)} = o + "
                                       f"v_{upper(pivot)} (the block {ln} slides at its given speed)"))
                self.mark(ln, pivot)
            else:
                self.steps.append(Step("driver", ln, ref, f"given: {self.label(ln, ref)} = o + "
                                       f"\u03c9\u00b7{upper(pivot)}{upper(ref)} turned 90\u00b0 "
                                       f"({ln} turns about {upper(pivot)})", reference=pivot))
                self.mark(ln, ref)
            self.known.add(ln)
            self.order.append(ln)
        for p in c.given:
            owners = [ln for ln, pts in c.links.items() if p in pts]
            self.steps.append(Step("given", owners[0], p, f"given: {lower(p)} = o + v_{upper(p)}"))
            self.mark(owners[0], p)
        for p in c.directions:
            for ln, pts in c.links.items():
                if p in pts:
                    self.conds[ln].append(PlanLine((POLE, p), self.lines.special("direction", p, None)))
        while True:
            changed = self.transfer()
            # with the drawing's geometry every line condition is carried as far as it goes before
            # a link is completed, so that the choice of an auxiliary point's lines sees them all
            # (without it the order of the papers' scripts is kept)
            while changed and self.geo is not None and self.transfer():
                pass
            done = False
            for level in (0, 1, 2):
                for ln in c.links:
                    if ln not in self.known and self.complete(ln, level):
                        done = True
                        break
                if done:
                    break
            if not done and not changed:
                break
        unreached = tuple(ln for ln in c.links if ln not in self.known)
        if not unreached:
            for ln, pts in c.links.items():
                for p in pts:
                    if ln not in c.known:
                        self.ensure_image(ln, p)
        labels, groups = {}, {}
        for ln, pts in self.points.items():
            for p in pts:
                labels[(ln, p)] = self.label(ln, p)
                groups.setdefault(self._find((ln, p)), []).append((ln, p))
        shared = {k: tuple(x for x in g if x != k) for g in groups.values() for k in g}
        return VelocityScript(tuple(self.steps), tuple(self.aux), tuple(self.order), unreached,
                              c.unsupported, labels, shared, coincidences=tuple(self.coincidences))


def plan_velocities(chain: Chain | Mechanism, geometry: Mapping | None = None) -> VelocityScript:
    """The direct velocity construction of ``chain`` (a `Chain`, or a `Mechanism` with its
    frame and drivers as given data): Rosenauer's rule as a propagation on the chain's graph.

    ``geometry`` (optional): the drawing's positions, as point name → (N, 2) coordinates, and
    ("normal", pair) / ("contact", pair) → (N, 2) directions of the normals of guides and cam
    contacts. Where the rules leave a choice (which two lines meet in an auxiliary point, which
    two known points give a further image) the planner then takes the lines that cross at the
    widest angle at every position, so that coincidences of the drawing (lines that are parallel
    or the same only there) are avoided; where no other lines are allowed it names them in
    `VelocityScript.coincidences`."""
    if isinstance(chain, Mechanism):
        chain = Chain.from_mechanism(chain)
    script = _Planner(chain, geometry).run()
    if script.direct or script.unsupported:
        return script
    if chain.given and not chain.drivers:
        # a chain driven by given point velocities (paper 2): two trials about a given point; the
        # links the rule itself does not reach stay named (`unreached`)
        from dataclasses import replace
        trials = _two_trials(chain, geometry)
        return script if trials is None else replace(trials, unreached=script.unreached)
    if len(chain.drivers) != 1 or chain.given or chain.directions or chain.drivers[0][2] is None \
            or chain.frame is None:
        return script
    return _false_position(chain, geometry) or _two_trials(chain, geometry) or script


def _false_position(chain: Chain, geometry=None) -> VelocityScript | None:
    """Where one crank drives a chain that Rosenauer's rule does not reach: the velocities are
    proportional to the driver's rate, so another link on a frame pivot may be given a trial
    rate; if the plan is direct from it, the true plan is the trial plan scaled about o in the
    ratio of the driver's given to its trial velocity (one trial: the rows pass through o)."""
    from dataclasses import replace

    driver = chain.drivers[0]
    for p, a, b in chain.hinges:
        if chain.frame not in (a, b):
            continue
        link = b if a == chain.frame else a
        if link == driver[0]:
            continue
        ref = next((q for q in chain.links[link] if q != p), None)
        if ref is None:
            continue
        trial = _Planner(replace(chain, drivers=((link, p, ref),)), geometry).run()
        if trial.direct:
            d, dp, dr = driver
            first = replace(trial.steps[0], text=(
                f"trial: {lower(ref)}* = o + ω*·{upper(p)}{upper(ref)} turned 90° "
                f"(an arbitrary rate of {link} about {upper(p)}; the images that follow are trial "
                "images x*)"))
            scale = Step("scale", d, dr, (
                f"similar point rows: {lower(dr)}* (the trial image of {upper(dr)}) and the given "
                f"{lower(dr)} = o + ω·{upper(dp)}{upper(dr)} turned 90° lie on one ray "
                f"from o; every image x lies on the ray o x*, with ox : ox* = o{lower(dr)} : "
                f"o{lower(dr)}*"))
            return replace(trial, steps=(first,) + trial.steps[1:] + (scale,),
                           trial=(link, p, ref), scale_by=driver)
    return None


def _two_trials(chain: Chain, geometry=None) -> VelocityScript | None:
    """False position with two trials (*ähnliche Punktreihen* in their general form): where no
    second crank's trial rate alone makes the plan direct, leave out a binary link KM and give
    a second crank a trial rate besides the true driver. The images are then affine in the trial
    rate, so they move on lines (similar point rows) that do not pass through o; two trials give
    each row, and the left-out link's check km ⟂ KM picks the point of every row."""
    from dataclasses import replace

    driver = chain.drivers[0] if chain.drivers else None
    true = () if driver is None else (driver,)
    binary = [ln for ln, pts in chain.links.items() if len(set(pts)) == 2 and ln != chain.frame
              and (driver is None or ln != driver[0])]
    cranks = []
    for p, a, b in chain.hinges:
        if chain.frame in (a, b):
            link = b if a == chain.frame else a
            ref = next((q for q in chain.links[link] if q != p), None)
            if (driver is None or link != driver[0]) and ref is not None:
                cranks.append((link, p, ref))
    # a chain driven by given point velocities: a trial rate of a link about one of its given
    # points (Rosenauer's free chains, paper 2, where the rule fails)
    for p in chain.given:
        for link, pts in chain.links.items():
            ref = next((q for q in pts if q != p), None)
            if p in pts and link != chain.frame and ref is not None:
                cranks.append((link, p, ref))
    for cut in binary:
        K, M = dict.fromkeys(chain.links[cut])
        ends = []
        for X in (K, M):
            ends.append(next((ln for q, a, b in chain.hinges for ln in (a, b)
                              if q == X and cut in (a, b) and ln != cut), None))
        if None in ends or chain.frame in ends:
            continue
        rest = replace(chain, links={ln: p for ln, p in chain.links.items() if ln != cut},
                       hinges=tuple(h for h in chain.hinges if cut not in h[1:]))
        for link, p, ref in cranks:
            if link == cut:
                continue
            trial = _Planner(replace(rest, drivers=true + ((link, p, ref),)), geometry).run()
            if not trial.direct:
                continue
            steps = list(trial.steps)
            if p in chain.given:
                # the trial turns about a given point: drawn after the given velocities
                k = next(i for i, s in enumerate(steps) if s.kind == "driver" and s.link == link)
                last = max(i for i, s in enumerate(steps) if s.kind == "given")
                steps.insert(last, steps.pop(k))
            k = next(i for i, s in enumerate(steps) if s.kind == "driver" and s.link == link)
            steps[k] = replace(steps[k], text=(
                f"trial: {lower(ref)}* = {lower(p) if p in chain.given else 'o'} + ω*·{upper(p)}{upper(ref)} turned 90° (two "
                f"arbitrary rates ω* of {link} about {upper(p)}, drawn one after the other; the "
                f"images that follow are trial images x*, x**; the binary link {cut} is left out)"))
            check = Step("check", cut, M, (
                f"check {cut}: the true images satisfy {lower(K)}{lower(M)} ⟂ {upper(K)}{upper(M)}; "
                f"on the trial rows {lower(K)}*{lower(K)}** and {lower(M)}*{lower(M)}** this holds at one "
                f"ratio, and every image x divides x*x** in that ratio (similar point rows)"),
                base=(K,))
            return replace(trial, steps=tuple(steps) + (check,), trial=(link, p, ref), scale_by=driver,
                           check=(cut, K, ends[0], M, ends[1]))
    return None
