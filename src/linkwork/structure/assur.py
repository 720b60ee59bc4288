"""Assur groups (*Assursche Gruppen*, *Zweischläge* for dyads): the names and classes of the
groups that `topology.groups.solution_order` finds, in its order.

There is one decomposition, `solution_order`; this module only names its groups. Each group is
first *unfolded* into lower pairs the way the seeds draw it:

* a pin in a slot (`slot`, `circular-slot`) becomes the die block (*Stein*, *kulises akmens*)
  with a hinge on the pin's link and a sliding pair in the slotted link (a curved one for a
  Kulisse, which acts like a hinge at the arc's centre);
* a gear pair, a non-self-closed higher pair, becomes one extra link hinged to both wheels at
  the centres of curvature of the pitch circles (Rosenauer §97, Pöschl's *Ersatzgetriebe*); a
  rack, whose pitch line has its centre at infinity, is joined by a sliding pair instead.

Then a group of k links and 3k/2 lower pairs is named by Assur's and Artobolevsky's rules:
class I is a driving link on the frame; class II the dyads (two links, three pairs; the types
RRR, RRP, RPR, PRP, PPR after the letters along the group); class III the groups whose links
hang on a ternary link without a closed loop inside the group (the triad: one ternary link,
three legs; Heusinger's six-link group: two ternaries); class m ≥ IV those with a closed loop of
m links inside. The *order* is the number of pairs by which the group is attached to the links
solved before it. The class of a mechanism is the highest class of its groups.
"""

from __future__ import annotations

from dataclasses import dataclass

import networkx as nx

from ..model import Mechanism
from ..topology.groups import Group, solution_order

ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI", 7: "VII", 8: "VIII"}

#: the dyad types by their pair letters read from one outer pair to the other; a reversed
#: reading names the same type
DYAD_TYPES = ("RRR", "RRP", "RPR", "PRP", "PPR")


def dyad_type(letters: str) -> str:
    """The dyad type of three pair letters read along the dyad (RRP and PRR are one type)."""
    for t in DYAD_TYPES:
        if letters in (t, t[::-1]):
            return t
    raise ValueError(f"not a dyad: {letters!r}")


@dataclass(frozen=True)
class AssurGroup:
    """One group of the solution order, with its structural name."""

    group: Group
    kind: str  # "driver", "dyad", "triad", "group", "driven group"
    assur_class: int | None
    order: int  # pairs to links solved before (free elements of the group)
    dyad: str | None  # RRR, RRP, RPR, PRP or PPR for dyads
    letters: str  # dyads: pair letters read along the dyad; others: outer pairs | inner pairs
    unfolded_links: int
    unfolded_pairs: int
    notes: tuple[str, ...] = ()

    @property
    def links(self) -> tuple[str, ...]:
        return self.group.links

    @property
    def joints(self) -> tuple[str, ...]:
        return self.group.joints

    @property
    def higher(self) -> bool:
        """The group holds a higher pair (a gear), named by its equivalent lower-pair group."""
        return any(n.startswith("gear pair") for n in self.notes)

    @property
    def name(self) -> str:
        cls = f"class {ROMAN.get(self.assur_class, self.assur_class)}" if self.assur_class else ""
        if self.higher:
            cls += "; with a gear pair, by its equivalent link"
        if self.kind == "driver":
            return f"driving link ({cls})"
        if self.kind == "dyad":
            return f"dyad {self.dyad} ({cls})"
        if self.kind == "triad":
            return f"triad ({cls}, order {self.order})"
        if self.kind == "driven group":
            return f"driven group of {len(self.links)} links"
        return f"group of {self.unfolded_links} links ({cls}, order {self.order})"

    def as_dict(self) -> dict:
        return {"links": list(self.links), "joints": list(self.joints),
                "drivers": list(self.group.drivers), "kind": self.kind, "name": self.name,
                "class": self.assur_class, "order": self.order, "dyad": self.dyad,
                "letters": self.letters, "unfolded_links": self.unfolded_links,
                "unfolded_pairs": self.unfolded_pairs, "notes": list(self.notes)}


def unfold(mech: Mechanism, group: Group) -> tuple[nx.MultiGraph, set, list[str]]:
    """The group's links and pairs as a multigraph of lower pairs. Nodes are link names (the
    group's links, the known links it attaches to, and the die blocks and gear equivalents,
    which belong to the group); each edge carries its pair `letter` 'R' or 'P', the model
    `joint` it comes from, and its geometry: `point` (hinge point name) for a hinge, `axis`
    (unit direction) for a straight slider, `center` (arc centre) for a curved one."""
    G = nx.MultiGraph()
    internal = set(group.links)
    notes: list[str] = []
    for jn in group.joints:
        j = mech.joint(jn)
        a, b = j.links
        if j.kind == "revolute":
            G.add_edge(a, b, letter="R", joint=jn, point=j.point)
        elif j.kind == "prismatic":
            G.add_edge(a, b, letter="P", joint=jn, axis=j.axis)
        elif j.kind in ("slot", "circular-slot"):
            block = f"{jn}:block"
            internal.add(block)
            G.add_edge(b, block, letter="R", joint=jn, point=j.point)
            if j.kind == "slot":
                G.add_edge(block, a, letter="P", joint=jn, axis=j.axis)
                notes.append(f"pin-in-slot {jn}: die block unfolded (hinge on {b}, slider in {a})")
            else:
                G.add_edge(block, a, letter="P", joint=jn, center=j.center)
                notes.append(f"curved slot {jn}: die block in a Kulisse about {j.center} "
                             "(acts as a hinge at the arc's centre)")
        elif j.kind == "gear":
            eq = f"{jn}:equivalent"
            internal.add(eq)
            G.add_edge(a, eq, letter="R", joint=jn, gear=True)
            G.add_edge(eq, b, letter="P" if j.gear_kind == "rack" else "R", joint=jn, gear=True)
            notes.append(f"gear pair {jn} (higher pair) replaced by its equivalent link through "
                         "the pitch-circle centres (Rosenauer §97)")
    for ln in internal:
        G.add_node(ln)
    return G, internal, notes


def classify(mech: Mechanism, group: Group) -> AssurGroup:
    """Name one group of `solution_order(mech)`."""
    G, internal, notes = unfold(mech, group)
    edges = list(G.edges(data=True))
    outer = [(u, v, d) for u, v, d in edges if (u in internal) != (v in internal)]
    inner = [(u, v, d) for u, v, d in edges if u in internal and v in internal]
    letters = ("".join(d["letter"] for *_, d in outer) + "|"
               + "".join(d["letter"] for *_, d in inner))
    n_links, n_pairs = len(internal), len(edges)
    common = dict(group=group, order=len(outer), letters=letters, unfolded_links=n_links,
                  unfolded_pairs=n_pairs, notes=tuple(notes))
    if group.drivers:
        if group.size == 1 and n_links == 1:
            common["letters"] = "".join(d["letter"] for *_, d in outer)
            return AssurGroup(kind="driver", assur_class=1, dyad=None, **common)
        return AssurGroup(kind="driven group", assur_class=None, dyad=None, **common)
    H = nx.Graph()
    H.add_nodes_from(internal)
    H.add_edges_from((u, v) for u, v, _ in inner)
    multi = len(inner) > H.number_of_edges()  # two pairs between the same two group links
    longest = max((len(c) for c in nx.simple_cycles(H)), default=0)
    if multi:
        longest = max(longest, 2)
    ternary = any(H.degree(v) >= 3 for v in H.nodes)
    if n_links == 2 and len(edges) == 3 and len(inner) == 1 and len(outer) == 2:
        u, v, mid = inner[0]
        # read the letters along the dyad: outer pair of one link, inner pair, outer of the other
        first = next(d for a, b, d in outer if u in (a, b))
        last = next(d for a, b, d in outer if v in (a, b))
        along = first["letter"] + mid["letter"] + last["letter"]
        common["letters"] = along
        return AssurGroup(kind="dyad", assur_class=2, dyad=dyad_type(along), **common)
    cls = max(3 if ternary else 2, longest if longest >= 4 else 0)
    if longest == 3:  # a triangle of group links: rigid inside, counts as a ternary base link
        cls = max(cls, 3)
    kind = "triad" if (n_links == 4 and len(outer) == 3 and ternary and not longest) else "group"
    return AssurGroup(kind=kind, assur_class=cls, dyad=None, **common)


def assur_groups(mech: Mechanism) -> tuple[AssurGroup, ...]:
    """The named groups of `mech` in solution order (raises `StructureError` where
    `solution_order` does: over- or under-constrained mechanisms)."""
    return tuple(classify(mech, g) for g in solution_order(mech))


def mechanism_class(groups: tuple[AssurGroup, ...]) -> int | None:
    """The class of the mechanism: the highest class among its groups."""
    classes = [g.assur_class for g in groups if g.assur_class]
    return max(classes) if classes else None


__all__ = ["AssurGroup", "DYAD_TYPES", "assur_groups", "classify", "dyad_type", "mechanism_class",
           "unfold"]
