"""SVG sketches of atlas chains: links as bars and plates, hinges as small circles.

This module owns the drawing of a :class:`linkwork.topology.atlas.Chain`.  It
writes plain SVG text (no drawing dependency): every binary link is a ``<line>``
(a bar), every link with three or more hinges a ``<polygon>`` (triangle,
quadrilateral, …) through its hinges, and every hinge a ``<circle>``.  Nothing
else in the picture uses those three element kinds, so a reader (or a test) can
count links and hinges from the file.

Hinge positions come from NetworkX's spring layout of the *line graph* of the
chain (hinges as nodes, two hinges adjacent when they sit on a common link),
started for planar chains from Tutte's barycentric drawing so that bars rarely
cross (see :func:`hinge_positions`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING
from xml.sax.saxutils import escape, quoteattr

import networkx as nx
import numpy as np

from ..errors import OutputError
from ..outputs import write_output_file

if TYPE_CHECKING:
    from linkwork.topology.atlas import Chain

_MARGIN = 28.0
_CAPTION = 22.0


def _outer_face(g: nx.Graph) -> list[int] | None:
    """The longest face of a planar embedding of ``g`` (``None`` if ``g`` is not planar)."""
    planar, embedding = nx.check_planarity(g)
    if not planar:
        return None
    seen: set[tuple[int, int]] = set()
    best: list[int] = []
    for u, v in sorted(embedding.edges()):
        if (u, v) in seen:
            continue
        face = embedding.traverse_face(u, v, mark_half_edges=seen)
        if len(face) > len(best):
            best = face
    return best


def _barycentric(g: nx.Graph, outer: list[int]) -> dict[int, np.ndarray]:
    """Tutte's barycentric placement: outer face on a circle, every other link at the
    mean of its neighbours.  For a planar chain this starts the layout without
    crossings (Tutte 1963); NetworkX has no such layout, and it is one linear solve.
    """
    nodes = sorted(g.nodes())
    index = {v: i for i, v in enumerate(nodes)}
    a = np.zeros((len(nodes), len(nodes)))
    rhs = np.zeros((len(nodes), 2))
    for i, v in enumerate(outer):
        angle = 2 * math.pi * i / len(outer)
        a[index[v], index[v]] = 1.0
        rhs[index[v]] = (math.cos(angle), math.sin(angle))
    on_outer = set(outer)
    for v in nodes:
        if v in on_outer:
            continue
        a[index[v], index[v]] = g.degree(v)
        for w in g[v]:
            a[index[v], index[w]] -= 1.0
    xy = np.linalg.solve(a, rhs)
    return {v: xy[index[v]] for v in nodes}


def hinge_positions(chain: Chain, *, size: float = 300.0) -> dict[tuple[int, int], tuple[float, float]]:
    """Drawing coordinates (SVG units, y down) of every hinge of ``chain``.

    The hinges are laid out by NetworkX's spring layout on the line graph (hinge
    nodes, joined when they sit on a common link), so the sides of every link
    get similar lengths.  For a planar chain the layout starts from Tutte's
    barycentric drawing of the link graph (hinges at the middle of their edges)
    with the hinges of the outer face held fixed, which keeps most sketches free
    of crossing bars; non-planar chains start from a seeded random layout.
    """
    g = chain.graph()
    line = nx.Graph()
    line.add_nodes_from(sorted(chain.edges))
    for v in sorted(g.nodes()):
        at_v = sorted(tuple(sorted((v, w))) for w in g[v])
        line.add_edges_from(itertools.combinations(at_v, 2))
    outer = _outer_face(g)
    if outer is None:
        pos = nx.spring_layout(line, seed=7)
    else:
        links = _barycentric(g, outer)
        start = {(a, b): (links[a] + links[b]) / 2 for a, b in chain.edges}
        fixed = [tuple(sorted((outer[i], outer[(i + 1) % len(outer)]))) for i in range(len(outer))]
        # Few iterations: enough to open up collinear binary strings and flat
        # plates, too few to undo the planar start.
        pos = nx.spring_layout(line, pos=start, fixed=fixed, iterations=20, seed=7)
    xs = [p[0] for p in pos.values()]
    ys = [p[1] for p in pos.values()]
    span = max(max(xs) - min(xs), max(ys) - min(ys)) or 1.0
    scale = (size - 2 * _MARGIN) / span
    cx = (max(xs) + min(xs)) / 2
    cy = (max(ys) + min(ys)) / 2
    return {
        h: (size / 2 + (float(p[0]) - cx) * scale, size / 2 - (float(p[1]) - cy) * scale)  # type: ignore[misc]
        for h, p in pos.items()
    }


def _fmt(v: float) -> str:
    return f"{v:.1f}"


def chain_svg(chain: Chain, *, size: float = 300.0) -> str:
    """The SVG document (text) sketching ``chain``."""
    pos = hinge_positions(chain, size=size)
    by_link: dict[int, list[tuple[float, float]]] = {v: [] for v in range(1, chain.n_links + 1)}
    for a, b in chain.edges:
        by_link[a].append(pos[(a, b)])
        by_link[b].append(pos[(a, b)])

    height = size + _CAPTION
    title = f"Chain {chain.label}" + (f" ({chain.name})" if chain.name else "")
    mix = "/".join(str(c) for c in chain.mix)
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{_fmt(size)}" height="{_fmt(height)}" '
        f'viewBox="0 0 {_fmt(size)} {_fmt(height)}">',
        f"<title>{escape(title)}</title>",
        f"<desc>{escape(f'{chain.n_links} links, {chain.n_hinges} hinges, link-type mix {mix}')}</desc>",
        '<rect x="0" y="0" width="100%" height="100%" fill="white"/>',
        '<g id="links" stroke="#1f3a5f" stroke-linejoin="round" stroke-linecap="round">',
    ]
    labels = []
    # Plates first, bars on top, so bars crossing a plate stay visible.
    for link in sorted(by_link, key=lambda v: -len(by_link[v])):
        pts = by_link[link]
        mx = sum(p[0] for p in pts) / len(pts)
        my = sum(p[1] for p in pts) / len(pts)
        ident = quoteattr(f"link-{link}")
        if len(pts) == 2:
            (x1, y1), (x2, y2) = pts
            out.append(
                f'<line class="link" id={ident} x1="{_fmt(x1)}" y1="{_fmt(y1)}" '
                f'x2="{_fmt(x2)}" y2="{_fmt(y2)}" stroke-width="6"/>'
            )
        else:
            # Order the hinges around their centroid so the plate is a simple polygon.
            pts = sorted(pts, key=lambda p: math.atan2(p[1] - my, p[0] - mx))
            points = " ".join(f"{_fmt(x)},{_fmt(y)}" for x, y in pts)
            out.append(
                f'<polygon class="link" id={ident} points="{points}" '
                'fill="#9fbfdf" fill-opacity="0.75" stroke-width="3"/>'
            )
        labels.append(
            f'<text x="{_fmt(mx)}" y="{_fmt(my - 6)}" font-size="11" font-family="sans-serif" '
            f'text-anchor="middle" fill="#7a1f1f">{link}</text>'
        )
    out.append("</g>")
    out.append('<g id="hinges" fill="white" stroke="black" stroke-width="1.5">')
    for (a, b), (x, y) in sorted(pos.items()):
        out.append(f'<circle class="hinge" id={quoteattr(f"hinge-{a}-{b}")} cx="{_fmt(x)}" cy="{_fmt(y)}" r="4.5"/>')
    out.append("</g>")
    out.append('<g id="labels">')
    out.extend(labels)
    out.append("</g>")
    out.append(
        f'<text x="{_fmt(size / 2)}" y="{_fmt(size + _CAPTION / 2)}" font-size="13" font-family="sans-serif" '
        f'text-anchor="middle">{escape(title + " — mix " + mix)}</text>'
    )
    out.append("</svg>")
    return "\n".join(out) + "\n"


def svg_filename(chain: Chain) -> str:
    """File name used by :func:`write_atlas_svg` (sorts in atlas order)."""
    return f"chain-{chain.n_links:02d}-{chain.number:04d}.svg"


def write_atlas_svg(chains: Iterable[Chain], directory: str | Path, *, progress: bool = False) -> list[Path]:
    """Write one SVG sketch per chain into ``directory`` (created if missing), each file whole
    or not at all (`outputs.write_output_file`: a full disk or a Ctrl-C leaves the previous
    sketch, no partial one); a directory that cannot be made or written is one `OutputError`.

    Returns the written paths in the order of ``chains``.
    """
    target = Path(directory)
    if target.exists() and not target.is_dir():
        raise OutputError(f"cannot write SVG files to '{directory}': it is not a directory")
    try:
        target.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"cannot write SVG files to '{directory}': "
                          f"{exc.strerror or exc}") from None
    chains = list(chains)
    written: list[Path] = []
    if progress and len(chains) > 50:
        from rich.console import Console
        from rich.progress import track

        iterable: Iterable[Chain] = track(
            chains, description="drawing chains", console=Console(stderr=True), transient=True
        )
    else:
        iterable = chains
    for chain in iterable:
        path = target / svg_filename(chain)
        write_output_file(path, chain_svg(chain))
        written.append(path)
    return written
