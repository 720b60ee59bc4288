"""Structural decomposition: the groups (Assur groups, *Gruppen*) in the order they are solved.

Starting from the frame, the next group is the smallest set of still-unknown links whose pairs
with the known links and among themselves remove exactly 3 degrees of freedom per link. A driver
removes one more at its pair. Two-link groups are the dyads (RRR, RRP, RPR, PRP, …), one-link
groups arise from sliding pairs (a rod with a pin in a slot), larger groups are the triads of
eight-link chains or the six-link group of Heusinger's valve gear. This is the one place that
decides the solution order; the kinematics layer follows it.

**Closed slider groups (the wedge, *Keil*, *ķīlis*).** A straight sliding pair removes two
freedoms: the offset of the block from its guide line, and its turning against the guide. In a
closed loop of sliding pairs only, the last of those "no turning" conditions repeats what the
others already impose (if A does not turn against B, nor B against C, then C does not turn
against A). Such a pair removes one freedom, not two. This is Rosenauer's exception to the
count, §95 (seed digest `001c-rosenauer-textbook-ch10-11.md`, "§95. Rules for introducing
prismatic pairs", exception to restriction 2 and to restriction 3). There the three-link slider
chain, the wedge or cotter joint (*ķīļsavienojums*, Figs. 273–274), is constrained, and a chain
with γ closed slider groups moves when 2z − 3n + 4 = γ. `structure.mobility` counts the same γ
(`slider_groups`). The order counts a pair that closes a loop of sliding pairs once. It keeps the
pair's name in `Group.wedge_pairs`, one per loop. The kinematics can then drop that pair's
repeated rotation equation. The rotation conditions that remain are independent, and the group's
system is square.

A wedge transmits motion only if its guides cross. Rosenauer's restriction 1 (same section)
says that a link joined to the chain by two sliding pairs must not have parallel slide
directions, otherwise it could move alone. Rosenauer §70, Example 27 (digest
`001b-rosenauer-textbook-ch7-9.md`) splits the input slide's velocity along the other two
sliding directions. That split fails when those directions are parallel. A group made of sliding
pairs only keeps its links' relative angles, so this can be checked from the drawing alone. Such
a group is refused with a `StructureError` naming the pairs, rather than left to fail in the
solver (`_check_slider_group`).
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass
from threading import Lock

import numpy as np

from ..errors import StructureError
from ..model import Joint, Mechanism

#: degrees of freedom each pair removes (Grübler's g₁ pairs count 2, point contact pairs 1; a
#: cam contact h = 1, a rolling contact, self-closed, h = 2 as Rosenauer §110 counts it; the
#: intermittent pairs of Geneva and star wheels h = 1 in every phase: the pin on its slot, the
#: pin gear, or the locking arc each leave the wheel no freedom of its own)
PAIR_CONSTRAINTS = {"revolute": 2, "prismatic": 2, "slot": 1, "circular-slot": 1, "gear": 1,
                    "cam": 1, "rolling": 2, "geneva": 1, "star-wheel": 1}


@dataclass(frozen=True)
class Group:
    """A set of links fixed by its pairs to the links solved before it.

    `wedge_pairs` are the group's sliding pairs that close a loop of sliding pairs (Rosenauer's
    wedge exception, §95). Each one's "no turning" condition repeats the other pairs of its
    loop, so it removes one freedom (its offset from the guide line), not two."""

    links: tuple[str, ...]
    joints: tuple[str, ...]
    drivers: tuple[str, ...]
    wedge_pairs: tuple[str, ...] = ()

    @property
    def size(self) -> int:
        return len(self.links)


def pair_constraints(j: Joint) -> int:
    """Freedoms pair `j` removes (a rolling pair on two pivots of one carrier: 1, as a gear)."""
    return getattr(j, "constraints", None) or PAIR_CONSTRAINTS[j.kind]


def _involved(j: Joint) -> tuple[str, ...]:
    return tuple(j.links) + ((j.carrier,) if getattr(j, "carrier", None) else ())


def constraint_count(joints: list[Joint], driver_joints: set[str],
                     wedge_pairs: tuple[str, ...] | set[str] = ()) -> int:
    """Freedoms the pairs remove, drivers included: 2 per lower pair, 1 per point contact or gear,
    1 per driver. A pair in `wedge_pairs` counts 1, because its rotation condition repeats the
    others of its closed slider group."""
    return sum(pair_constraints(j) + (j.name in driver_joints) - (j.name in wedge_pairs)
               for j in joints)


# ---------------------------------------------------------------------------- rotation classes
class RotationClasses:
    """Links that cannot turn against each other because sliding pairs join them (a union-find
    over the straight sliding pairs taken so far)."""

    def __init__(self, links, parent: dict[str, str] | None = None) -> None:
        self.parent = dict(parent) if parent is not None else {ln: ln for ln in links}

    def copy(self) -> "RotationClasses":
        return RotationClasses((), self.parent)

    def find(self, v: str) -> str:
        while self.parent[v] != v:
            self.parent[v] = self.parent[self.parent[v]]
            v = self.parent[v]
        return v

    def join(self, a: str, b: str) -> bool:
        """Join a's and b's classes. False if they were one class already: the sliding pair
        between them closes a loop of sliding pairs."""
        ra, rb = self.find(a), self.find(b)
        if ra == rb:
            return False
        self.parent[ra] = rb
        return True


def _wedge_pairs(js: list[Joint], rotations: RotationClasses) -> tuple[tuple[str, ...], RotationClasses]:
    """The sliding pairs of `js` that close a loop of sliding pairs, given the classes of the
    pairs solved before, and the classes with `js` added."""
    rot = rotations.copy()
    closing = tuple(j.name for j in js if j.kind == "prismatic" and not rot.join(*j.links))
    return closing, rot


def slider_loop(mech: Mechanism, pair: str, among: set[str] | None = None) -> tuple[str, ...]:
    """The sliding pairs of a loop of sliding pairs through `pair` (one shortest such loop,
    `pair` first), taken from the pairs named in `among` (default: all of the mechanism's).
    Returns () if `pair` closes no such loop."""
    import networkx as nx

    j0 = mech.joint(pair)
    G = nx.MultiGraph()
    for j in mech.joints:
        if j.kind == "prismatic" and j.name != pair and (among is None or j.name in among):
            G.add_edge(*j.links, name=j.name)
    a, b = j0.links
    if a not in G or b not in G or not nx.has_path(G, a, b):
        return ()
    path = nx.shortest_path(G, a, b)
    names = [pair]
    for u, v in zip(path, path[1:]):
        names.append(min(d["name"] for d in G.get_edge_data(u, v).values()))
    return tuple(names)


def _check_slider_group(mech: Mechanism, group: Group, rot: RotationClasses,
                        solved_pairs: set[str]) -> None:
    """Refuse a group of sliding pairs only (prismatic drivers allowed) whose guides cannot fix
    its links' positions.

    All the group's links and the known links it slides on are in one rotation class (else the
    count would have refused the group). So their pairs' guide lines keep the angles they have in
    the drawing, and the offset conditions are linear in the links' translations with constant
    coefficients. The group is determined exactly when that matrix (rows: each pair's guide
    normal, each driver's axis; columns: the x and y of each group link) has full column rank.
    Otherwise the rows that depend on each other are parallel guides, and they are named."""
    pairs = [mech.joint(jn) for jn in group.joints]
    if not pairs or any(j.kind != "prismatic" for j in pairs):
        return
    touched = {ln for j in pairs for ln in j.links}
    if len({rot.find(ln) for ln in touched}) != 1:
        return
    col = {ln: 2 * i for i, ln in enumerate(group.links)}
    rows, names = [], []

    def row(j, direction: np.ndarray) -> np.ndarray:
        """The condition `direction`·(translation of links[1] − of links[0]) on the unknowns."""
        a, b = j.links
        r = np.zeros(2 * group.size)
        if b in col:
            r[col[b]:col[b] + 2] += direction
        if a in col:
            r[col[a]:col[a] + 2] -= direction
        return r

    for j in pairs:
        e = np.asarray(j.axis, dtype=float)
        e = e / np.hypot(*e)
        rows.append(row(j, np.array([-e[1], e[0]])))  # the offset across the guide
        names.append(j.name)
        if j.name in group.drivers:
            rows.append(row(j, e))  # the driven slide along it
            names.append(f"{j.name} (driver)")
    M = np.array(rows)
    U, sv, Vt = np.linalg.svd(M)
    tol = 1e-9 * max(sv.max(initial=0.0), 1.0)
    rank = int((sv > tol).sum())
    if rank == 2 * group.size:
        return
    # rows in a dependency (left null space) and links free to slide (right null space)
    left = U[:, rank:]
    dep = [names[i] for i in np.flatnonzero(np.abs(left).max(axis=1) > 1e-8)] or names
    free = Vt[rank:]
    loose = [ln for ln, c in col.items() if np.abs(free[:, c:c + 2]).max() > 1e-8]
    order = {j.name: i for i, j in enumerate(mech.joints)}
    loops = []
    for w in group.wedge_pairs:
        loop = slider_loop(mech, w, solved_pairs | set(group.joints))
        if loop:
            loops.append(", ".join(sorted(loop, key=order.get)))
    pairs_text = " and ".join([", ".join(dep[:-1]), dep[-1]] if len(dep) > 1 else dep)
    them = "its position" if len(loose) == 1 else "their positions"
    wedge = (f"; the closed slider group (wedge) {'; '.join(loops)} cannot transmit the input's "
             "motion" if loops else "")
    raise StructureError(
        f"sliding pairs with parallel guides: the pairs {pairs_text} hold {', '.join(loose)} on "
        f"parallel lines, so they do not fix {them}{wedge} (Rosenauer §95: a link joined by two "
        "sliding pairs must not have parallel slide directions); give one of these pairs "
        "another axis")


# ---------------------------------------------------------------------------- the order
#: at most this many candidate groups are tried for one group before the search gives up
MAX_CANDIDATES = 200_000


def _check_connected(mech: Mechanism) -> None:
    """Connected components first: links that no chain of pairs joins to the frame are free
    bodies, whatever the rest does; name them at once rather than search for their group."""
    import networkx as nx

    G = nx.Graph()
    G.add_nodes_from(mech.link_names)
    for j in mech.joints:
        inv = _involved(j)
        G.add_edges_from((a, b) for a in inv for b in inv if a != b)
    loose = sorted(set(mech.link_names) - nx.node_connected_component(G, mech.frame),
                   key=mech.link_names.index)
    if loose:
        raise StructureError(
            f"under-constrained: the links {', '.join(loose)} are not determined by the drivers: "
            f"no chain of pairs joins {'it' if len(loose) == 1 else 'them'} to the frame "
            f"'{mech.frame}'")


def _connected_subsets(unknown: list[str], joints: list[Joint], size: int):
    """The sets of `size` unknown links that the pairs among them keep connected, in a fixed
    order. A group is such a set: a set falling apart in two would have each part fixed (or
    over-fixed) by its own pairs, and the smaller parts are tried first. So only connected sets
    are tried, which keeps the search small where the links are many but joined sparsely."""
    index = {ln: i for i, ln in enumerate(unknown)}
    nbrs: dict[str, set[str]] = {ln: set() for ln in unknown}
    for j in joints:
        inv = [ln for ln in _involved(j) if ln in index]
        for a in inv:
            nbrs[a].update(b for b in inv if b != a)
    layer = {frozenset([ln]) for ln in unknown}
    tried = 0
    for _ in range(size - 1):
        grown = set()
        for s in layer:
            for a in s:
                for b in nbrs[a] - s:
                    grown.add(s | {b})
            tried += 1
            if len(grown) > MAX_CANDIDATES:
                raise StructureError(
                    f"the solution order: more than {MAX_CANDIDATES} candidate groups of {size} "
                    f"links among {len(unknown)} undetermined ones; the chain is too large to "
                    "order (split it, or check its drivers and pairs)")
        layer = grown
    yield from sorted((tuple(sorted(s, key=index.get)) for s in layer),
                      key=lambda t: [index[ln] for ln in t])


def structure_key(mech: Mechanism) -> tuple:
    """What the solution order depends on: the links, the frame, each pair's name, kind, the
    links it involves and the freedoms it removes, and the driven pairs. Not the drawing: a
    design point moved (a drag in the workbench) keeps the key, and with it the order."""
    return (mech.frame, mech.link_names,
            tuple((j.name, j.kind, _involved(j), pair_constraints(j)) for j in mech.joints),
            tuple(d.joint for d in mech.drivers))


#: structure key -> (the groups found, the message of the StructureError that ended the
#: search or None); the last ORDERS_KEPT structures
_orders: OrderedDict = OrderedDict()
ORDERS_KEPT = 64
_orders_lock = Lock()


def solution_order(mech: Mechanism) -> tuple[Group, ...]:
    """The groups of `mech` in solution order, from the frame and the drivers.

    A sliding pair that closes a loop of sliding pairs counts one freedom, not two (Rosenauer's
    wedge exception, see the module's docstring) and is listed in its group's `wedge_pairs`.

    Raises `StructureError` naming the links that stay undetermined (too few inputs), the pairs
    that over-determine a group (redundant constraints), or the parallel guides of a wedge that
    cannot transmit motion.

    The search counts freedoms only, so it is kept per `structure_key` and done once for every
    mechanism of that structure; the one check that reads the drawing (the guides of a group of
    sliding pairs, `_check_slider_group`) is made for each mechanism, group by group in the
    order, before the search's own verdict.
    """
    key = structure_key(mech)
    with _orders_lock:
        found = _orders.get(key)
        if found is not None:
            _orders.move_to_end(key)
    if found is None:
        found = _search(mech)
        with _orders_lock:
            _orders[key] = found
            while len(_orders) > ORDERS_KEPT:
                _orders.popitem(last=False)
    groups, failure = found
    rotations = RotationClasses(mech.link_names)
    solved: set[str] = set()
    for g in groups:
        _, rot = _wedge_pairs([mech.joint(n) for n in g.joints], rotations)
        _check_slider_group(mech, g, rot, solved)
        rotations = rot
        solved.update(g.joints)
    if failure is not None:
        raise StructureError(failure)
    return groups


def _search(mech: Mechanism) -> tuple[tuple[Group, ...], str | None]:
    """The groups in solution order (`solution_order`, without the check of the guides), and
    the message of the StructureError that stopped the search after them (None: complete)."""
    groups: list[Group] = []
    try:
        _search_into(mech, groups)
    except StructureError as exc:
        return tuple(groups), str(exc)
    return tuple(groups), None


def _search_into(mech: Mechanism, groups: list[Group]) -> None:
    driver_joints = {d.joint for d in mech.drivers}
    known = {mech.frame}
    unknown = [n for n in mech.link_names if n != mech.frame]
    remaining = list(mech.joints)
    rotations = RotationClasses(mech.link_names)
    _check_connected(mech)
    while unknown:
        found = None
        for size in range(1, len(unknown) + 1):
            for subset in _connected_subsets(unknown, remaining, size):
                reach = known.union(subset)
                js = [j for j in remaining
                      if set(_involved(j)) <= reach and any(ln in subset for ln in j.links)]
                wedge, rot = _wedge_pairs(js, rotations)
                count = constraint_count(js, driver_joints, wedge)
                if count > 3 * size:
                    raise StructureError(
                        f"over-constrained: the links {', '.join(subset)} are fixed by the pairs "
                        f"{', '.join(j.name for j in js)}, which remove {count} degrees of freedom "
                        f"where {3 * size} determine them (a redundant pair, or too many drivers)")
                if count == 3 * size:
                    found = Group(tuple(subset), tuple(j.name for j in js),
                                  tuple(j.name for j in js if j.name in driver_joints), wedge)
                    break
            if found:
                break
        if found is None:
            js = list(remaining)
            wedge, _ = _wedge_pairs(js, rotations)
            missing = 3 * len(unknown) - constraint_count(js, driver_joints, wedge)
            raise StructureError(
                f"under-constrained: the links {', '.join(unknown)} are not determined by the "
                f"drivers ({', '.join(sorted(driver_joints)) or 'none'}); the mechanism needs "
                f"{max(missing, 1)} more input{'s' if missing > 1 else ''} or pairs")
        groups.append(found)
        rotations = rot
        known.update(found.links)
        unknown = [n for n in unknown if n not in found.links]
        remaining = [j for j in remaining if j.name not in found.joints]
    if remaining:
        raise StructureError(
            "over-constrained: the pairs " + ", ".join(j.name for j in remaining)
            + " join links that the other pairs already determine (redundant constraints); "
            "remove them or a link")
