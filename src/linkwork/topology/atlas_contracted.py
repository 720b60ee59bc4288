"""Generation engine of the chain atlas: link-type mixes, contracted graphs, binary strings.

This module owns the combinatorics behind :func:`linkwork.topology.atlas.enumerate_chains`.
The method is the classical *contracted-graph* number synthesis (Yan and Hwang
1990; Tsai 2001, ch. 3):

1. **Link-type mixes.**  A chain of ``n`` links with ``n_i`` links of ``i``
   hinges satisfies ``sum n_i = n`` and ``sum i n_i = 2j`` with Grübler's
   ``j = 3n/2 - 2`` (Rosenauer's eqs. 44, 46, 47), hence
   ``n_2 = 4 + sum (i - 3) n_i`` (his eq. 48) and ``i <= n/2`` (eq. 49).
2. **Contracted graphs.**  Remove the binary links; every maximal string of
   binary links becomes one edge between the two non-binary links it joins.
   What remains is a loopless multigraph whose vertex degrees are the types of
   the non-binary links.  These are generated once per mix, up to isomorphism
   (NetworkX certificate + exact test).
3. **Binary strings.**  A chain is a contracted graph plus a number ``k >= 0``
   of binary links on each edge (``sum k = n_2``).  Two such labellings give
   isomorphic chains exactly when an automorphism of the contracted graph maps
   one onto the other, so only the lexicographically greatest labelling of each
   orbit is kept (Yan and Hwang's use of permutation groups).  The rigidity
   filter (:mod:`linkwork.topology.atlas_rigidity`) then removes chains with a
   rigid sub-chain.

The automorphisms of the contracted graph that fix a labelling are exactly the
automorphisms of the chain, so they are returned with every chain; inversions
and input choices are computed from them without a second graph search.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from dataclasses import dataclass
from functools import lru_cache

import networkx as nx
import numpy as np

from linkwork.topology.atlas_rigidity import rigid_subchain


def hinge_count(n_links: int) -> int:
    """Hinges of a closed one-degree-of-freedom hinge chain: ``j = 3n/2 - 2`` (Grübler)."""
    return (3 * n_links - 4) // 2


def link_type_mixes(n_links: int) -> list[tuple[int, ...]]:
    """All ``(n_2, n_3, …, n_{n/2})`` with ``sum n_i = n`` and ``sum i n_i = 2j``.

    The tuple has one entry per link type from binary up to the largest type
    ``n/2`` allowed by Rosenauer's eq. (49).  Sorted by ascending ``n_2``.
    """
    if n_links < 4 or n_links % 2:
        return []
    total_degree = 2 * hinge_count(n_links)
    max_type = n_links // 2
    found: list[tuple[int, ...]] = []

    def rec(link_type: int, links_left: int, degree_left: int, acc: list[int]) -> None:
        if link_type > max_type:
            if 2 * links_left == degree_left:
                found.append((links_left, *acc))
            return
        for count in range(links_left + 1):
            if count * link_type > degree_left:
                break
            rec(link_type + 1, links_left - count, degree_left - count * link_type, [*acc, count])

    rec(3, n_links, total_degree, [])
    return sorted(found)


@dataclass(frozen=True)
class ContractedGraph:
    """A loopless multigraph of the non-binary links, with its automorphisms.

    ``types[v]`` is the number of hinges of link ``v`` (its degree).
    ``edges`` lists one entry per string of binary links (parallel edges repeat).
    ``automorphisms`` holds pairs ``(sigma, pi)``: a permutation of the
    vertices and the matching permutation of ``edges`` (edge ``e`` goes to edge
    ``pi[e]``), identity first.
    """

    types: tuple[int, ...]
    edges: tuple[tuple[int, int], ...]
    automorphisms: tuple[tuple[tuple[int, ...], tuple[int, ...]], ...]


def _multiplicity_matrices(types: tuple[int, ...], max_mult: int) -> Iterator[list[list[int]]]:
    """Loopless multigraphs with the given (non-increasing) degrees, filled row by row.

    A cheap partial symmetry break prunes the search: for two consecutive
    vertices of equal degree, swapping them must not make the matrix
    lexicographically larger (read row by row).  The lexicographically largest
    labelling of every multigraph passes this test, so nothing is lost; the
    remaining duplicates are removed later with an exact isomorphism test.
    """
    c = len(types)
    a = [[0] * c for _ in range(c)]
    rem = list(types)
    pairs = [(i, j) for i in range(c) for j in range(i + 1, c)]
    swaps = {i for i in range(c - 1) if types[i] == types[i + 1]}

    def swap_not_larger(i: int) -> bool:
        # Only rows i and i+1 change under the swap of i and i+1 (apart from
        # column swaps in rows < i, which were compared when rows i, i+1 were
        # not yet complete, so compare the full prefix up to row i+1 here).
        perm = list(range(c))
        perm[i], perm[i + 1] = perm[i + 1], perm[i]
        for r in range(i + 2):
            for col in range(r + 1, c):
                x = a[perm[r]][perm[col]]
                y = a[r][col]
                if x != y:
                    return x < y
        return True

    def rec(k: int) -> Iterator[list[list[int]]]:
        if k == len(pairs):
            # The last row has no pair of its own: check its swap here.
            if not any(rem) and (c - 2 not in swaps or swap_not_larger(c - 2)):
                yield [row[:] for row in a]
            return
        i, j = pairs[k]
        row_done = j == c - 1
        hi = min(rem[i], rem[j], max_mult)
        lo = rem[i] if row_done else 0
        for mu in range(hi, lo - 1, -1):
            rem[i] -= mu
            rem[j] -= mu
            a[i][j] = a[j][i] = mu
            # Row i is complete: the swap (i-1, i) can now be checked.
            if not row_done or (i - 1 not in swaps or swap_not_larger(i - 1)):
                yield from rec(k + 1)
            rem[i] += mu
            rem[j] += mu
            a[i][j] = a[j][i] = 0

    if c == 1:
        return
    yield from rec(0)


def automorphisms(types: tuple[int, ...], edges: tuple[tuple[int, int], ...]) -> list[tuple[tuple[int, ...], tuple[int, ...]]]:
    """All automorphisms ``(sigma, pi)`` of a loopless multigraph (edges ``(a, b)`` with
    ``a < b``, parallel edges repeated): the vertex permutations that keep the types and the
    edge multiplicities, found by backtracking, each with every matching of parallel edges.

    The same set as the automorphisms of the graph with every edge subdivided by a node of its
    own (vertex kinds kept apart; a NetworkX ``GraphMatcher`` search, which the tests compare
    with), found some ten times faster: the graphs have at most ten vertices.
    """
    c = len(types)
    mult = [[0] * c for _ in range(c)]
    classes: dict[tuple[int, int], list[int]] = {}
    for e, (a, b) in enumerate(edges):
        mult[a][b] += 1
        mult[b][a] += 1
        classes.setdefault((a, b), []).append(e)
    sigmas: list[tuple[int, ...]] = []
    perm = [-1] * c
    used = [False] * c

    def rec(v: int) -> None:
        if v == c:
            sigmas.append(tuple(perm))
            return
        for w in range(c):
            if used[w] or types[w] != types[v]:
                continue
            if any(mult[u][v] != mult[perm[u]][w] for u in range(v)):
                continue
            perm[v], used[w] = w, True
            rec(v + 1)
            used[w] = False
        perm[v] = -1

    rec(0)
    autos = []
    for sigma in sigmas:
        sources, targets = [], []
        for (a, b), es in classes.items():
            x, y = sigma[a], sigma[b]
            sources.append(es)
            targets.append(list(itertools.permutations(classes[(min(x, y), max(x, y))])))
        for choice in itertools.product(*targets):
            pi = [0] * len(edges)
            for es, fs in zip(sources, choice):
                for e, f in zip(es, fs):
                    pi[e] = f
            autos.append((sigma, tuple(pi)))
    return autos


@lru_cache(maxsize=None)
def contracted_graphs(types: tuple[int, ...], n_binary: int) -> tuple[ContractedGraph, ...]:
    """Non-isomorphic contracted graphs for non-binary links of the given types.

    ``n_binary`` only bounds the edge multiplicity: ``mu`` parallel strings
    between two links need at least ``2 mu - 2`` binary links, otherwise the
    two links and those strings form a rigid sub-chain.
    """
    types = tuple(sorted(types, reverse=True))
    max_mult = max(1, (n_binary + 2) // 2)
    buckets: dict[str, list[nx.Graph]] = {}
    found: list[ContractedGraph] = []
    for mat in _multiplicity_matrices(types, max_mult):
        c = len(types)
        g = nx.Graph()
        for v, t in enumerate(types):
            g.add_node(v, type=str(t))
        for i in range(c):
            for j in range(i + 1, c):
                if mat[i][j]:
                    g.add_edge(i, j, mult=str(mat[i][j]))
        # A chain with a cut link has mobility >= 2 (the blocks' mobilities
        # add), so the contracted graph must be 2-connected.
        if not nx.is_connected(g) or (c > 2 and next(nx.articulation_points(g), None) is not None):
            continue
        key = nx.weisfeiler_lehman_graph_hash(g, node_attr="type", edge_attr="mult")
        bucket = buckets.setdefault(key, [])
        if any(
            nx.is_isomorphic(
                g, h, node_match=lambda x, y: x["type"] == y["type"], edge_match=lambda x, y: x["mult"] == y["mult"]
            )
            for h in bucket
        ):
            continue
        bucket.append(g)
        edges = tuple((i, j) for i in range(c) for j in range(i + 1, c) for _ in range(mat[i][j]))
        autos = automorphisms(types, edges)
        identity = (tuple(range(c)), tuple(range(len(edges))))
        autos.sort(key=lambda p: p != identity)
        found.append(ContractedGraph(types, edges, tuple(autos)))
    return tuple(found)


def _compositions(total: int, parts: int) -> np.ndarray:
    """All ways to put ``total`` binary links on ``parts`` edges, lexicographically descending."""
    if parts == 1:
        return np.array([[total]], dtype=np.int16)
    # Stars and bars: the positions of parts-1 bars among total+parts-1 slots.
    slots = total + parts - 1
    bars = np.array(list(itertools.combinations(range(slots), parts - 1)), dtype=np.int16).reshape(-1, parts - 1)
    edges = np.hstack(
        [np.full((len(bars), 1), -1, dtype=np.int16), bars, np.full((len(bars), 1), slots, dtype=np.int16)]
    )
    arr = np.diff(edges, axis=1) - 1
    order = np.lexsort(arr.T[::-1])[::-1]
    return arr[order]


def _orbit_representatives(cg: ContractedGraph, comps: np.ndarray) -> np.ndarray:
    """Keep the labellings that are lexicographically greatest in their orbit."""
    keep = np.ones(len(comps), dtype=bool)
    rows = np.arange(len(comps))
    for _sigma, pi in cg.automorphisms[1:]:
        inv = np.empty(len(pi), dtype=np.intp)
        inv[list(pi)] = np.arange(len(pi))
        # The image labelling k' has k'[pi[e]] = k[e], i.e. k' = k[inv].
        diff = comps[:, inv] - comps
        nonzero = diff != 0
        first = nonzero.argmax(axis=1)
        larger = nonzero.any(axis=1) & (diff[rows, first] > 0)
        keep &= ~larger
    return comps[keep]


def _cheap_rejects(cg: ContractedGraph, comps: np.ndarray) -> np.ndarray:
    """Mask of labellings that are certainly not simple chains without rigid sub-chains.

    Two strings between the same pair of links must hold >= 2 binary links
    together (otherwise: a double hinge, or a triangle), and a triangle of
    contracted edges without binary links is a rigid triangle of links.  The
    pebble game would find these too; the vectorised test is just faster.
    """
    bad = np.zeros(len(comps), dtype=bool)
    by_pair: dict[tuple[int, int], list[int]] = {}
    for e, pair in enumerate(cg.edges):
        by_pair.setdefault(pair, []).append(e)
    for group in by_pair.values():
        for e, f in itertools.combinations(group, 2):
            bad |= comps[:, e] + comps[:, f] < 2
    c = len(cg.types)
    for x, y, z in itertools.combinations(range(c), 3):
        for e in by_pair.get((x, y), ()):
            for f in by_pair.get((x, z), ()):
                for h in by_pair.get((y, z), ()):
                    bad |= (comps[:, e] + comps[:, f] + comps[:, h]) == 0
    return bad


@dataclass(frozen=True)
class RawChain:
    """A chain as produced by the engine: 0-based hinges and its automorphism group."""

    n_links: int
    hinges: tuple[tuple[int, int], ...]
    automorphisms: tuple[tuple[int, ...], ...]  # link permutations, identity first


def expand(cg: ContractedGraph, labelling: tuple[int, ...]) -> RawChain:
    """Insert the binary links of ``labelling`` into ``cg`` and lift its stabiliser.

    Links ``0 .. c-1`` are the non-binary links; the binary links of edge ``e``
    follow, numbered from the end ``edges[e][0]`` towards ``edges[e][1]``.
    """
    c = len(cg.types)
    nxt = c
    strings: list[list[int]] = []
    hinges: list[tuple[int, int]] = []
    for (a, b), k in zip(cg.edges, labelling):
        string = list(range(nxt, nxt + k))
        nxt += k
        strings.append(string)
        path = [a, *string, b]
        hinges.extend(zip(path, path[1:]))
    autos: list[tuple[int, ...]] = []
    for sigma, pi in cg.automorphisms:
        if any(labelling[pi[e]] != labelling[e] for e in range(len(pi))):
            continue
        perm = list(sigma) + [0] * (nxt - c)
        for e, string in enumerate(strings):
            image = strings[pi[e]]
            # Same orientation when the image edge starts where our start goes.
            if cg.edges[pi[e]][0] != sigma[cg.edges[e][0]]:
                image = image[::-1]
            for x, y in zip(string, image):
                perm[x] = y
        autos.append(tuple(perm))
    return RawChain(nxt, tuple(hinges), tuple(autos))


def cycle_chain(n_links: int) -> RawChain:
    """The all-binary closed chain (only the four-bar satisfies Grübler)."""
    hinges = tuple((i, (i + 1) % n_links) for i in range(n_links))
    autos = []
    for shift in range(n_links):
        autos.append(tuple((i + shift) % n_links for i in range(n_links)))
    for shift in range(n_links):
        autos.append(tuple((shift - i) % n_links for i in range(n_links)))
    return RawChain(n_links, hinges, tuple(autos))


@dataclass(frozen=True)
class WorkUnit:
    """One contracted graph of one mix: the granule of the progress bar."""

    mix: tuple[int, ...]
    graph: ContractedGraph | None  # None: the all-binary four-bar


def work_units(n_links: int) -> list[WorkUnit]:
    """All (mix, contracted graph) pairs to be expanded for ``n_links``."""
    units: list[WorkUnit] = []
    for mix in link_type_mixes(n_links):
        types = tuple(t for t, count in enumerate(mix[1:], start=3) for _ in range(count))
        if not types:
            units.append(WorkUnit(mix, None))
            continue
        for cg in contracted_graphs(types, mix[0]):
            units.append(WorkUnit(mix, cg))
    return units


def expand_unit(unit: WorkUnit) -> list[RawChain]:
    """All chains without rigid sub-chains that one work unit yields, one per isomorphism class."""
    n_binary = unit.mix[0]
    if unit.graph is None:
        return [cycle_chain(n_binary)] if n_binary == 4 else []
    cg = unit.graph
    comps = _compositions(n_binary, len(cg.edges))
    comps = comps[~_cheap_rejects(cg, comps)]
    comps = _orbit_representatives(cg, comps)
    chains = []
    for row in comps:
        raw = expand(cg, tuple(int(x) for x in row))
        if rigid_subchain(raw.n_links, raw.hinges) is None:
            chains.append(raw)
    return chains
