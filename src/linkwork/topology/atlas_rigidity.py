"""Rigid sub-chains of planar hinge chains (the structural filter of the chain atlas).

This module owns one question: does a kinematic chain (*kinematische Kette*) of
links joined by simple revolute hinges contain a sub-chain whose mobility is
zero or negative, i.e. a structure (a triangle, a Stephenson-like over-closed
group, …)?

A sub-chain of ``k`` links with ``j`` hinges among them has Grübler mobility
``3(k - 1) - 2j``.  "No rigid sub-chain" means ``2j <= 3k - 4`` for every set of
``k >= 2`` links.  Counting every hinge twice turns this into the
``(3, 4)``-sparsity of a multigraph (``e <= 3k - 4`` on every vertex set that
spans an edge), which the *pebble game* of Jacobs and Hendrickson (1997), in
the general ``(k, l)`` form of Lee and Streinu (2008), decides in polynomial
time instead of looking at all ``2**n`` link sets.

Links are the integers ``0 .. n-1`` here; the public wrappers in
:mod:`linkwork.topology.atlas` translate arbitrary link labels.
"""

from __future__ import annotations

from collections.abc import Sequence

# (k, l) of the pebble game: 3 pebbles per link (its 3 planar degrees of freedom),
# l = 4 because a sub-chain must keep one degree of freedom beyond the 3 of a
# rigid body: 3k - 4 doubled hinges at most.
_PEBBLES_PER_LINK = 3
_L = 4


def rigid_subchain(n: int, hinges: Sequence[tuple[int, int]]) -> frozenset[int] | None:
    """Return a set of links that forms a sub-chain of mobility <= 0, or ``None``.

    ``hinges`` are pairs of link indices in ``range(n)``.  The returned set is
    the first over-constrained block the pebble game meets; it may be the whole
    chain when the chain itself has mobility <= 0.  A multiple hinge between
    the same two links is reported as that pair (two links, two hinges:
    mobility -1).
    """
    pebbles = [_PEBBLES_PER_LINK] * n
    # out[v] lists the heads of the (doubled) hinge copies whose pebble v holds.
    out: list[list[int]] = [[] for _ in range(n)]

    def search(start: int, blocked: int) -> list[int] | None:
        """Depth-first search along out-edges for a free pebble; returns the path."""
        seen = {start, blocked}
        path = [start]
        iters = [iter(out[start])]
        while iters:
            for w in iters[-1]:
                if w in seen:
                    continue
                seen.add(w)
                path.append(w)
                if pebbles[w] > 0:
                    return path
                iters.append(iter(out[w]))
                break
            else:
                iters.pop()
                path.pop()
        return None

    def reach(u: int, v: int) -> frozenset[int]:
        """Links reachable from u or v along out-edges: the over-constrained block."""
        seen = {u, v}
        stack = [u, v]
        while stack:
            x = stack.pop()
            for w in out[x]:
                if w not in seen:
                    seen.add(w)
                    stack.append(w)
        return frozenset(seen)

    for u, v in hinges:
        if u == v:
            raise ValueError(f"a hinge must join two different links, got ({u}, {v})")
        # Each hinge removes two degrees of freedom: insert two copies of the edge.
        for _ in range(2):
            while pebbles[u] + pebbles[v] < _L + 1:
                for a, b in ((u, v), (v, u)):
                    path = search(a, b)
                    if path is not None:
                        # Move the pebble found at the end of the path back to a,
                        # reversing the orientation of every edge on the path.
                        pebbles[path[-1]] -= 1
                        for x, y in zip(path, path[1:]):
                            out[x].remove(y)
                            out[y].append(x)
                        pebbles[a] += 1
                        break
                else:
                    return reach(u, v)
            if pebbles[u] > 0:
                pebbles[u] -= 1
                out[u].append(v)
            else:
                pebbles[v] -= 1
                out[v].append(u)
    return None

