"""SVG sketches of atlas chains: links as bars and plates, hinges as small circles.

This module owns the drawing of a :class:`linkwork.structure.atlas.Chain`.  It
writes plain SVG text (no drawing dependency): every binary link is a ``<line>``
(a bar), every link with three or more hinges a ``<polygon>`` (triangle,
quadrilateral, …) through its hinges, and every hinge a ``<circle>``.  Nothing
else in the picture uses those three element kinds, so a reader (or a test) can
count links and hinges from the file.

Hinge positions come from a NetworkX Kamada–Kawai layout of the *line graph* of
the chain (hinges as nodes, two hinges adjacent when they sit on a common
link): the sides of every link are then pulled to about the same length, which
gives the bar-and-plate look of the textbook figures.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING
from xml.sax.saxutils import escape, quoteattr

import networkx as nx

if TYPE_CHECKING:
    from linkwork.structure.atlas import Chain

_MARGIN = 28.0
_CAPTION = 22.0


def hinge_positions(chain: Chain, *, size: float = 300.0) -> dict[tuple[int, int], tuple[float, float]]:
    """Drawing coordinates (SVG units, y down) of every hinge of ``chain``."""
    line = nx.line_graph(chain.graph())
    # Sort nodes so the layout does not depend on set iteration order.
    ordered = nx.Graph()
    ordered.add_nodes_from(sorted(line.nodes()))
    ordered.add_edges_from(sorted(tuple(sorted(e)) for e in line.edges()))
    start = nx.circular_layout(ordered)
    pos = nx.kamada_kawai_layout(ordered, pos=start)
    xs = [p[0] for p in pos.values()]
    ys = [p[1] for p in pos.values()]
    span = max(max(xs) - min(xs), max(ys) - min(ys)) or 1.0
    scale = (size - 2 * _MARGIN) / span
    cx = (max(xs) + min(xs)) / 2
    cy = (max(ys) + min(ys)) / 2
    return {
        tuple(sorted(h)): (size / 2 + (p[0] - cx) * scale, size / 2 - (p[1] - cy) * scale)  # type: ignore[misc]
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
    """Write one SVG sketch per chain into ``directory`` (created if missing).

    Returns the written paths in the order of ``chains``.
    """
    target = Path(directory)
    target.mkdir(parents=True, exist_ok=True)
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
        path.write_text(chain_svg(chain), encoding="utf-8")
        written.append(path)
    return written
