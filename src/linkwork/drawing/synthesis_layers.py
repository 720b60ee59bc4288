"""Drawings of finite-position synthesis (Pöschl ch. IX), from :mod:`linkwork.synthesis`.

Owns :func:`draw_positions`: the prescribed positions of the moving plane Σ (each as an arrow
from its origin along its x-axis, numbered), the poles P_ij of every two positions
(*Drehpole*), the pole triangles (*Poldreieck*) of the first three positions (of every three
when there are four), for four positions the centre-point and circle-point curves
(*Mittelpunkts-* and *Kreispunktkurve*, the latter drawn in position 1) from
:func:`~linkwork.synthesis.burmester.curve_samples`, and the chosen or Burmester dyads: the
centre point M_k, its circle point K_k in position 1 and the circle through K_k's homologous
points. Poles at infinity (translations) are listed in the legend instead of being drawn.
"""

from __future__ import annotations

from itertools import combinations

import numpy as np

from ..constructions.scales import Scales
from ..synthesis.burmester import Dyad, centre_point_curve, circle_point_curve, curve_samples
from ..synthesis.positions import Positions
from .svg import AUX_COLOUR as AUX, COLOURS, Figure, Style

__all__ = ["draw_positions", "pole_ident"]

_CENTRE_CURVE = "#1f4e9c"
_CIRCLE_CURVE = "#1b7a3a"


def pole_ident(i: int, j: int) -> str:
    """The SVG id of the drawn pole P_ij (0-based i < j; numbered from 1 as in the books)."""
    return f"pole-P{i + 1}{j + 1}"


def _broken(xy: np.ndarray, jump: float) -> np.ndarray:
    """The samples with a NaN row wherever neighbours are more than `jump` apart (the branch
    through the asymptote, or the switch between the two roots), so no chord is drawn there."""
    xy = np.asarray(xy, float)
    step = np.hypot(*np.diff(xy, axis=0).T)
    cut = np.flatnonzero(~(step <= jump)) + 1
    return np.insert(xy, cut, np.nan, axis=0)


def draw_positions(pos: Positions, dyads: tuple[Dyad, ...] | list[Dyad] = (), *, unit: str = "mm",
                   title: str = "", curves: bool = True, samples: int = 720) -> Figure:
    """A figure of the positions `pos`, their poles and pole triangles, for four positions the
    Burmester curves (unless `curves` is false), and `dyads` marked (centre point M_k, circle
    point K_k drawn in the dyad's reference position, the circle through its homologous points)."""
    poles = pos.poles()
    finite = {k: p.xy for k, p in poles.items() if p.is_finite}
    size = pos.size
    arrow = 0.2 * size if size > 1e-300 else 1.0
    pts = [pos.origin, pos.origin + arrow * np.column_stack([np.cos(pos.angle), np.sin(pos.angle)])]
    for d in dyads:
        if d.centre.is_finite:
            pts.append(np.atleast_2d(d.centre.xy))
        pts.append(d.homologous())
    base = np.vstack(pts)
    # poles far beyond the positions (nearly equal rotations) would shrink the drawing to a dot:
    # they stay in the file but outside the panel, with their place in the legend
    mid, reach = base.mean(0), 3.0 * max(float(np.ptp(base, axis=0).max()), arrow)
    far = {k for k, v in finite.items() if np.hypot(*(v - mid)) > reach}
    cloud = np.vstack([base] + [np.atleast_2d(v) for k, v in finite.items() if k not in far])
    lo, hi = cloud.min(0), cloud.max(0)
    extent = float(max(np.ptp(cloud, axis=0).max(), arrow))
    pad = 0.25 * extent
    fig = Figure(Scales.auto(unit, extent * 1.5), title=title or f"{len(pos)} positions of a moving plane")
    # the curves run off to infinity along their asymptote: show the neighbourhood of the data
    fig.clip["mechanism"] = (lo - pad, hi + pad)

    # the positions: Σ_k as an arrow along its x-axis from its origin
    for k, (d, th) in enumerate(zip(pos.origin, pos.angle)):
        tip = d + arrow * np.array([np.cos(th), np.sin(th)])
        fig.arrow(d, tip, style=Style(stroke="#000", width=0.5), layer="positions", ident=f"position-{k + 1}")
        fig.dot(d, r=0.45, layer="positions")
        fig.label(d, f"\u03a3_{k + 1}", size=2.8, ident=f"position-{k + 1}")
    fig.note("positions \u03a3_k: origin and x-axis of the moving plane")

    # pole triangles: of every three positions when there are at most four, else of 1, 2, 3
    triples = list(combinations(range(len(pos)), 3)) if len(pos) <= 4 else [(0, 1, 2)]
    for i, j, k in triples:
        corners = [(i, j), (i, k), (j, k)]
        if all(c in finite for c in corners):
            fig.path(np.array([finite[c] for c in corners]), closed=True,
                     style=Style(stroke=COLOURS["pole"], width=0.25, dash="1.5 0.8" if (i, j, k) != (0, 1, 2) else None),
                     layer="pole-triangle", ident=f"pole-triangle-{i + 1}{j + 1}{k + 1}")
    for (i, j), P in poles.items():
        label = f"P_{{{i + 1}{j + 1}}}"
        if P.is_finite:
            fig.dot(P.xy, r=0.6, style=Style(stroke=COLOURS["pole"]), layer="poles", ident=pole_ident(i, j))
            fig.label(P.xy, label, size=2.8, ident=pole_ident(i, j))
            if (i, j) in far:
                fig.note(f"{label} outside the drawing, at ({P.xy[0]:.4g}, {P.xy[1]:.4g})")
        else:
            u = P.direction.xy
            fig.note(f"{label} at infinity (direction {np.degrees(np.arctan2(u[1], u[0])) % 180:.1f}\u00b0): "
                     f"positions {i + 1} and {j + 1} differ by a translation")

    if curves and len(pos) == 4:
        for curve, colour, name in ((centre_point_curve(pos), _CENTRE_CURVE, "centre-point-curve"),
                                    (circle_point_curve(pos), _CIRCLE_CURVE, "circle-point-curve")):
            xy = curve_samples(curve, samples=samples)
            fig.path(_broken(xy, 0.1 * extent), style=Style(stroke=colour, width=0.35), layer="burmester",
                     ident=name)
        fig.note("centre-point curve (Mittelpunktskurve) blue, circle-point curve (Kreispunktkurve, "
                 "in position 1) green")

    for n, d in enumerate(dyads, start=1):
        Z = d.homologous()
        fig.dot(d.circle.xy, r=0.6, filled=False, style=Style(stroke=_CIRCLE_CURVE), layer="dyads",
                ident=f"circle-point-{n}")
        fig.label(d.circle.xy, f"K_{n}", colour=_CIRCLE_CURVE, size=2.8, ident=f"circle-point-{n}")
        fig.path(Z, style=Style(stroke=AUX, width=0.18), layer="dyads", ident=f"homologous-{n}")
        if d.centre.is_finite:
            M = d.centre.xy
            fig.dot(M, r=0.7, style=Style(stroke=_CENTRE_CURVE), layer="dyads", ident=f"centre-point-{n}")
            fig.label(M, f"M_{n}", colour=_CENTRE_CURVE, size=2.8, ident=f"centre-point-{n}")
            r = float(np.hypot(*(Z[0] - M)))
            fig.circle(M, r, arcs=list(Z), style=Style(stroke=AUX, width=0.18, dash="1.2 0.8"), layer="dyads",
                       ident=f"dyad-circle-{n}")
            fig.path(np.array([M, Z[0]]), style=Style(stroke="#000", width=0.5), layer="dyads", ident=f"crank-{n}")
        else:
            u = d.centre.direction.xy
            fig.note(f"M_{n} at infinity: K_{n} slides on a line normal to "
                     f"{np.degrees(np.arctan2(u[1], u[0])) % 180:.1f}\u00b0")
    if dyads:
        fig.note("M_k centre points (fixed pivots), K_k circle points (moving pivots, in position 1)")
    return fig

