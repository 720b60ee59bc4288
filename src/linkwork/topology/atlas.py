"""The chain atlas: planar one-degree-of-freedom hinge chains with 4 to 12 links.

This module owns the public, data-level API of the structural atlas:

* :class:`Chain`, a frozen record of one kinematic chain (*kinematische Kette*,
  Latvian *kinēmatiska ķēde*) given by its topological graph (links — *Glieder*,
  *locekļi* — are vertices, simple revolute hinges — *Gelenke* — are edges),
  with its link-type mix, number of independent loops, poles and pole lines,
  classical name, inversions and input choices;
* :func:`enumerate_chains`, all chains of ``n`` links (4, 6, 8, 10, 12) up to
  isomorphism that have no rigid sub-chain — 1, 2, 16, 230 and 6856 of them;
* isomorphism helpers (:func:`isomorphic`, :func:`certificate`,
  :func:`identify`, :func:`canonical_form`) built on NetworkX;
* the structural checks (:func:`mobility`, :func:`find_rigid_subchain`,
  :func:`is_constrained_chain`).

The combinatorial engine is in :mod:`linkwork.topology.atlas_contracted`, the
rigidity test in :mod:`linkwork.topology.atlas_rigidity` and the drawings in
:mod:`linkwork.topology.atlas_svg` (:func:`write_atlas_svg` is re-exported
here).  See ``docs/atlas.md`` for the method and its sources.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Iterable
from contextlib import nullcontext
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Union

import networkx as nx

from linkwork.topology.atlas_contracted import RawChain, expand_unit, link_type_mixes, work_units
from linkwork.topology.atlas_rigidity import rigid_subchain
from linkwork.topology.atlas_svg import write_atlas_svg  # re-exported
from linkwork.topology.counts import kutzbach

__all__ = [
    "SUPPORTED_LINK_COUNTS",
    "TYPE_NAMES",
    "Chain",
    "ChainLike",
    "canonical_form",
    "certificate",
    "enumerate_chains",
    "find_rigid_subchain",
    "identify",
    "is_constrained_chain",
    "isomorphic",
    "link_type_mixes",
    "mobility",
    "write_atlas_svg",
]

#: Link counts the atlas enumerates.  One-degree-of-freedom hinge chains need an
#: even number of links (Grübler: j = 3n/2 - 2); 14 links and more would take
#: far longer and are out of scope.
SUPPORTED_LINK_COUNTS: tuple[int, ...] = (4, 6, 8, 10, 12)

#: Names of link types by number of hinges.
TYPE_NAMES: dict[int, str] = {2: "binary", 3: "ternary", 4: "quaternary", 5: "quinary", 6: "senary"}

Hinge = tuple[int, int]


@dataclass(frozen=True)
class Chain:
    """One planar one-degree-of-freedom kinematic chain of simple hinges.

    Links are numbered ``1 .. n_links``: the non-binary links first (highest
    type first), then the binary links string by string.  ``number`` is the
    chain's place in the atlas of its link count, so ``label`` (``"8.3"``) names
    it uniquely for a given linkwork version.
    """

    n_links: int
    number: int
    edges: tuple[Hinge, ...]
    #: ``(n_2, n_3, …, n_{n/2})``: how many links carry 2, 3, … hinges.
    mix: tuple[int, ...]
    #: Independent loops ``j - n + 1``.
    loops: int
    #: Classical name, where one exists ("four-bar", "Watt", "Stephenson").
    name: str | None
    #: Orbits of links under the chain's automorphisms: one orbit per distinct
    #: mechanism obtained by fixing a link as frame (one inversion each).
    inversions: tuple[tuple[int, ...], ...]
    #: Orbits of ordered pairs ``(frame, input)``, input hinged to the frame:
    #: one orbit per distinct mechanism with a driving link next to the frame.
    input_choices: tuple[tuple[Hinge, ...], ...]

    @property
    def label(self) -> str:
        return f"{self.n_links}.{self.number}"

    @property
    def n_hinges(self) -> int:
        return len(self.edges)

    @property
    def poles(self) -> int:
        """Number of poles (instantaneous centres) ``n(n-1)/2`` (Rosenauer eq. 42)."""
        return math.comb(self.n_links, 2)

    @property
    def pole_lines(self) -> int:
        """Number of pole lines ``n(n-1)(n-2)/6`` (Rosenauer eq. 43)."""
        return math.comb(self.n_links, 3)

    @property
    def n_inversions(self) -> int:
        return len(self.inversions)

    @property
    def n_input_choices(self) -> int:
        return len(self.input_choices)

    @property
    def link_types(self) -> dict[int, int]:
        """Number of hinges on each link."""
        degree = dict.fromkeys(range(1, self.n_links + 1), 0)
        for a, b in self.edges:
            degree[a] += 1
            degree[b] += 1
        return degree

    def graph(self) -> nx.Graph:
        """The topological graph: links as nodes ``1..n``, hinges as edges."""
        g = nx.Graph()
        g.add_nodes_from(range(1, self.n_links + 1))
        g.add_edges_from(self.edges)
        return g

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready description of the chain."""
        return {
            "label": self.label,
            "n_links": self.n_links,
            "number": self.number,
            "n_hinges": self.n_hinges,
            "mix": {TYPE_NAMES.get(t, f"{t}-hinge"): count for t, count in enumerate(self.mix, start=2)},
            "loops": self.loops,
            "poles": self.poles,
            "pole_lines": self.pole_lines,
            "name": self.name,
            "hinges": [list(e) for e in self.edges],
            "n_inversions": self.n_inversions,
            "inversions": [list(orbit) for orbit in self.inversions],
            "n_input_choices": self.n_input_choices,
            "input_choices": [[list(pair) for pair in orbit] for orbit in self.input_choices],
        }


ChainLike = Union[Chain, nx.Graph, Iterable[tuple[Hashable, Hashable]]]


def _as_graph(x: ChainLike) -> nx.Graph:
    if isinstance(x, Chain):
        return x.graph()
    if isinstance(x, nx.Graph):
        if x.is_directed() or x.is_multigraph():
            raise TypeError("a chain graph must be a simple undirected nx.Graph")
        return x
    g = nx.Graph()
    for a, b in x:
        if g.has_edge(a, b):
            # Two hinges between the same two links: not a simple chain.
            raise ValueError(f"links {a!r} and {b!r} are joined twice; use simple hinges")
        g.add_edge(a, b)
    return g


def _typed(g: nx.Graph) -> nx.Graph:
    """A copy of ``g`` whose nodes carry their link type (number of hinges)."""
    h = nx.Graph()
    h.add_nodes_from((v, {"type": str(d)}) for v, d in g.degree())
    h.add_edges_from(g.edges())
    return h


def _wl_hash(typed: nx.Graph) -> str:
    # Three refinement rounds: on the 12-link atlas they leave only a few
    # hundred colliding pairs for the exact test, and more rounds cost more
    # than the exact tests they save.
    return nx.weisfeiler_lehman_graph_hash(typed, node_attr="type", iterations=3)


def certificate(x: ChainLike) -> str:
    """An isomorphism invariant (Weisfeiler–Lehman hash of the link-type-coloured graph).

    Isomorphic chains always get the same certificate; different chains
    usually, but not always, get different ones, so use it to bucket and
    :func:`isomorphic` to decide.
    """
    return _wl_hash(_typed(_as_graph(x)))


def isomorphic(a: ChainLike, b: ChainLike) -> bool:
    """True when the two chains have the same topology (an exact NetworkX test)."""
    ga, gb = _as_graph(a), _as_graph(b)
    return nx.faster_could_be_isomorphic(ga, gb) and nx.is_isomorphic(ga, gb)


def mobility(x: ChainLike) -> int:
    """Grübler mobility ``3(n - 1) - 2j`` of the whole chain."""
    g = _as_graph(x)
    return kutzbach(g.number_of_nodes(), lower=g.number_of_edges())


def find_rigid_subchain(x: ChainLike) -> frozenset[Hashable] | None:
    """A set of links forming a sub-chain of mobility <= 0 (a structure), or ``None``.

    Uses the pebble game (see :mod:`linkwork.topology.atlas_rigidity`), so it
    stays fast for chains with many links.
    """
    g = _as_graph(x)
    nodes = list(g.nodes())
    index = {v: i for i, v in enumerate(nodes)}
    found = rigid_subchain(len(nodes), [(index[a], index[b]) for a, b in g.edges()])
    return None if found is None else frozenset(nodes[i] for i in found)


def is_constrained_chain(x: ChainLike) -> bool:
    """True for a closed chain with constrained motion and no rigid sub-chain.

    That is: simple hinges, mobility 1 (Rosenauer's criterion 2j - 3n + 4 = 0)
    and no sub-chain of mobility <= 0.  Connectivity, the absence of cut links
    and Rosenauer's bounds (>= 4 binary links, <= n/2 hinges per link) follow.
    """
    g = _as_graph(x)
    if g.number_of_nodes() < 4 or any(a == b for a, b in g.edges()):
        return False
    return mobility(g) == 1 and find_rigid_subchain(g) is None


def _name(n_links: int, hinges: tuple[Hinge, ...], degree: dict[int, int]) -> str | None:
    if n_links == 4:
        return "four-bar"
    if n_links == 6:
        ternary = [v for v, d in degree.items() if d == 3]
        adjacent = any({a, b} == set(ternary) for a, b in hinges)
        # Rosenauer §90: Watt's chain has the two ternary links hinged
        # together, Stephenson's has them apart.
        return "Watt" if adjacent else "Stephenson"
    return None


def _to_chain(raw: RawChain, number: int, mix: tuple[int, ...]) -> Chain:
    # 1-based link numbers, as in the textbooks (links 1 … n).
    hinges = tuple(sorted((min(a, b) + 1, max(a, b) + 1) for a, b in raw.hinges))
    autos = [tuple(p + 1 for p in perm) for perm in raw.automorphisms]
    links = range(1, raw.n_links + 1)
    # The automorphism list is the whole group, so an orbit is a set of images.
    inversions = sorted({tuple(sorted({g[v - 1] for g in autos})) for v in links})
    arcs = [(a, b) for a, b in hinges] + [(b, a) for a, b in hinges]
    choices = sorted({tuple(sorted({(g[f - 1], g[i - 1]) for g in autos})) for f, i in arcs})
    degree = dict.fromkeys(links, 0)
    for a, b in hinges:
        degree[a] += 1
        degree[b] += 1
    return Chain(
        n_links=raw.n_links,
        number=number,
        edges=hinges,
        mix=mix,
        loops=len(hinges) - raw.n_links + 1,
        name=_name(raw.n_links, hinges, degree),
        inversions=tuple(inversions),
        input_choices=tuple(choices),
    )


def _check_n(n_links: int) -> None:
    if isinstance(n_links, bool) or not isinstance(n_links, int):
        raise TypeError(f"n_links must be an int, got {type(n_links).__name__}")
    if n_links not in SUPPORTED_LINK_COUNTS:
        why = " (a one-degree-of-freedom hinge chain has an even number of links)" if n_links % 2 else ""
        raise ValueError(f"n_links must be one of {', '.join(map(str, SUPPORTED_LINK_COUNTS))}, got {n_links}{why}")


# Built atlases by link count (a few MB for 12 links; built once per process).
_cache: dict[int, tuple[Chain, ...]] = {}


def _progress_bar(progress: bool) -> Any:
    """A transient Rich progress bar on stderr, or a context yielding ``None``."""
    if not progress:
        return nullcontext(None)
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    return Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        console=Console(stderr=True),
        transient=True,
    )


def _refined_colours(n: int, hinges: Iterable[Hinge]) -> tuple[int, ...]:
    """An isomorphism invariant of a chain: colour refinement from the link types (three
    rounds, each link coloured by its colour and the multiset of its neighbours'), as the
    sorted colours. Isomorphic chains get equal invariants; the converse need not hold."""
    nbrs: list[list[int]] = [[] for _ in range(n)]
    for a, b in hinges:
        nbrs[a].append(b)
        nbrs[b].append(a)
    col = [len(x) for x in nbrs]
    for _ in range(3):
        col = [hash((col[v], tuple(sorted([col[w] for w in nbrs[v]])))) for v in range(n)]
    return tuple(sorted(col))


def _build(n_links: int, *, progress: bool) -> tuple[Chain, ...]:
    raws: list[tuple[RawChain, tuple[int, ...]]] = []
    chains: list[Chain] = []
    with _progress_bar(progress) as bar:
        task = bar.add_task(f"{n_links} links: contracted graphs", total=None) if bar else None
        units = work_units(n_links)
        if bar:
            bar.update(task, total=len(units), completed=0)
        for unit in units:
            if bar:
                bar.update(task, description=f"{n_links} links: chains of mix {'/'.join(map(str, unit.mix))}")
            raws.extend((raw, unit.mix) for raw in expand_unit(unit))
            if bar:
                bar.advance(task)

        # By construction (one labelling per orbit of each contracted graph) no
        # two chains are isomorphic.  The invariant + exact test below is the
        # independent guard the atlas relies on for that claim: chains are bucketed
        # by colour refinement (`_refined_colours`, a fraction of a millisecond per
        # chain in plain Python, where NetworkX's hash of a graph built for it took
        # most of the guard's 2 s on 12 links), and only chains sharing a bucket are
        # built as graphs and compared exactly.
        if bar:
            bar.update(task, description=f"{n_links} links: isomorphism check", total=len(raws), completed=0)
        buckets: dict[tuple, list[list]] = {}
        for raw, mix in raws:
            bucket = buckets.setdefault((mix, _refined_colours(raw.n_links, raw.hinges)), [])
            g = nx.Graph(raw.hinges) if bucket else None
            for other in bucket:
                if other[1] is None:
                    other[1] = nx.Graph(other[0])
            if g is None or not any(nx.is_isomorphic(g, other[1]) for other in bucket):
                bucket.append([raw.hinges, g])
                chains.append(_to_chain(raw, len(chains) + 1, mix))
            if bar:
                bar.advance(task)
    return tuple(chains)


def enumerate_chains(n_links: int, *, progress: bool = False) -> list[Chain]:
    """All planar 1-DOF hinge chains of ``n_links`` links without rigid sub-chains.

    One chain per isomorphism class, ordered by link-type mix (fewest binary
    links first) and then by generation order.  ``progress`` shows a Rich
    progress bar on stderr while the atlas is built; the result is cached for
    the rest of the process.
    """
    _check_n(n_links)
    if n_links not in _cache:
        _cache[n_links] = _build(n_links, progress=progress)
    return list(_cache[n_links])


def identify(x: ChainLike) -> Chain:
    """The atlas chain isomorphic to ``x`` (links of ``x`` may carry any labels).

    Raises ``ValueError`` when ``x`` is not a one-degree-of-freedom chain
    without rigid sub-chains, or has a link count outside the atlas.
    """
    g = _as_graph(x)
    n = g.number_of_nodes()
    if n not in SUPPORTED_LINK_COUNTS:
        raise ValueError(f"the atlas covers {', '.join(map(str, SUPPORTED_LINK_COUNTS))} links, got {n}")
    if not is_constrained_chain(g):
        raise ValueError("not a one-degree-of-freedom hinge chain without rigid sub-chains")
    key = certificate(g)
    for chain in _index(n).get(key, ()):
        if nx.is_isomorphic(g, chain.graph()):
            return chain
    raise AssertionError("no isomorphic atlas chain found; the atlas is incomplete")  # pragma: no cover


def canonical_form(x: ChainLike) -> tuple[Hinge, ...]:
    """The hinges of the atlas representative of ``x``: equal for isomorphic chains only."""
    return identify(x).edges


@lru_cache(maxsize=None)
def _index(n_links: int) -> dict[str, tuple[Chain, ...]]:
    index: dict[str, list[Chain]] = {}
    for chain in enumerate_chains(n_links):
        index.setdefault(certificate(chain), []).append(chain)
    return {k: tuple(v) for k, v in index.items()}

