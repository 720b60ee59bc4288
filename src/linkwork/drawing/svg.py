"""The SVG renderer: one drawing model, written as SVG; PNG and PDF are converted from that SVG.

Owns :class:`Figure` — primitives (paths, lines drawn just past the points they serve,
circles, compass arcs, arrows, point marks, kinematic symbols, labels) in world coordinates of
named *spaces* (the mechanism in its length unit, the velocity plan in velocity units, the
acceleration plan in acceleration units), each drawn at its own :class:`~.scales.Scale` in its
own panel — the layout of the panels on the sheet, line weights by role (given, auxiliary,
result), arrowheads, the label placer that keeps labels off each other and off the lines, the
legend with the scales, the step captions of step-by-step drawings (one file per step, or one
SMIL-animated SVG), and :meth:`Figure.save` to ``.svg``, ``.png`` or ``.pdf`` (the last two with
cairosvg from the very same SVG text, so the formats cannot diverge).
"""

from __future__ import annotations

import html
import math
import re
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any, Iterable

import numpy as np

from ..errors import InputError
from ..outputs import output_path, write_output_file
from . import symbols as sym
from ..constructions.scales import Scale, Scales

FONT = "DejaVu Serif, 'Times New Roman', Times, serif"
LABEL_SIZE = 3.4  # mm
SMALL = 2.6
MARGIN = 9.0  # mm around a panel's content
GAP = 10.0  # mm between panels
TITLE_H = 9.0
FRAME_PAD = 6.0  # mm between a framed panel's content and its frame
#: how far (mm) a label's nearest edge may be put from its point, nearest first
LABEL_DISTANCES = (1.0, 2.2, 3.8, 5.6, 8.0)
#: a label farther than this (mm) from its point is joined to it by a leader line
LEADER_FROM = 4.5
#: half the width of a bar's stroke and a little more: a label keeps this clear of drawn lines
INK_PAD = 0.6
SCALE_BAR = 20.0  # mm, the length of a scale bar
SCALE_TEXT_SIZE, SCALE_VALUE_SIZE = 2.8, 2.5
LEGEND_SIZE, LEGEND_LINE = 3.0, 4.2  # legend lines: font size and baseline distance (mm)
#: below a scale bar: its value's baseline 3.6 under the bar, the value's descent, a gap
SCALE_BELOW = 3.6 + 0.3 * SCALE_VALUE_SIZE + 1.5
#: depth of a row of scale bars: the words' ascent (baseline 1 under the bar) above it
SCALE_ROW = 0.8 * SCALE_TEXT_SIZE - 1.0 + SCALE_BELOW + 1.0


@dataclass(frozen=True)
class Style:
    stroke: str = "#000"
    width: float = 0.35
    dash: str | None = None
    fill: str = "none"
    opacity: float = 1.0

    def attrs(self) -> str:
        return _style_attrs(self)


@lru_cache(maxsize=256)
def _style_attrs(style: Style) -> str:
    """The SVG attributes of a style (a frozen value: the few styles of a drawing are written
    once, whatever the number of primitives and frames)."""
    a = f'stroke="{style.stroke}" stroke-width="{sym._f(style.width)}" fill="{style.fill}"'
    if style.dash:
        a += f' stroke-dasharray="{style.dash}"'
    if style.opacity != 1.0:
        a += f' opacity="{style.opacity}"'
    return a


#: colours by the kind of quantity, weights by role (books: given heavy, construction lines
#: thin, the result heavy and marked)
COLOURS = {"velocity": "#1f4e9c", "acceleration": "#1b7a3a", "coriolis": "#8a2be2",
           "pole": "#000", "inflection": "#b3001b", "return": "#b36b00", "bresse": "#006d77",
           "centrode": "#5a5a5a", "path": "#7a7a7a", "gamma": "#006d77", "highlight": "#e06c00"}
#: dash patterns, one per kind of curve that shares a figure with others: the return circle
#: dash-dotted, the moving centrode dashed (the fixed one solid)
DASHES = {"return": "3 1 0.6 1", "moving-centrode": "3 1.5"}
WEIGHTS = {"given": 0.5, "auxiliary": 0.18, "result": 0.6}
RESULT_COLOUR = "#b3001b"
AUX_COLOUR = "#555"


def style_for(role: str, kind: str = "") -> Style:
    """The line style of an element of ``role`` (given/auxiliary/result) and ``kind``."""
    w = WEIGHTS.get(role, 0.35)
    colour = COLOURS.get(kind)
    if colour is None:
        colour = RESULT_COLOUR if role == "result" else (AUX_COLOUR if role == "auxiliary" else "#000")
    elif role == "auxiliary":
        w = max(w, 0.25)
    return Style(stroke=colour, width=w, dash=DASHES.get(kind))


# ---------------------------------------------------------------------------- primitives
@dataclass
class Prim:
    kind: str  # path, line, circle, arc, arrow, dot, symbol
    space: str
    data: dict
    style: Style = field(default_factory=Style)
    layer: str = "mechanism"
    ident: str | None = None
    cls: str = ""
    step: int | None = None


@dataclass
class Label:
    space: str
    xy: np.ndarray
    text: str
    colour: str = "#000"
    size: float = LABEL_SIZE
    layer: str = "labels"
    ident: str | None = None
    prefer: np.ndarray | None = None  # preferred direction (paper, y down) to put the label
    step: int | None = None
    italic: bool = True
    clear: float = 0.0  # keep this far (mm) from the anchor, e.g. the radius of a joint circle


def _esc(text: str) -> str:
    """Escape for XML; symbols the serif face lacks (≙) are set in DejaVu Sans."""
    t = html.escape(text)
    return t.replace("\u2259", '<tspan font-family="DejaVu Sans, sans-serif">\u2259</tspan>')


#: what follows ``_`` or ``^`` unbraced: letters, digits, Greek (``a^n_BO_4``, the books' name
#: O_4 in a subscript, sets BO4 as one subscript)
_RUN = re.compile(r"[0-9A-Za-z\u0370-\u03ff]+")
SUB, SUP = -1, 1
SCRIPT = 0.7  # size of sub- and superscripts relative to the label
_SHIFT = {SUB: 0.32, SUP: -0.42}  # baseline shift (em, y down)


def segments(text: str) -> list[tuple[str, int]]:
    """A label in the books' notation as runs of (text, level): level 0 on the baseline, ``SUB``
    or ``SUP``. ``P_{13}``, ``P_13`` and ``v_A`` are subscripts, ``v^2``, ``b_B^(n)`` and
    ``x^{(n)}`` superscripts; a backslash takes the next character literally (user names are
    escaped with :func:`~linkwork.constructions.construction.literal`, so ``link_j`` is printed
    as written; a braced script is taken as written: ``v_{p_1}``)."""
    out: list[tuple[str, int]] = []

    def put(t: str, level: int) -> None:
        if not t:
            return
        if out and out[-1][1] == level:
            out[-1] = (out[-1][0] + t, level)
        else:
            out.append((t, level))
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "\\" and i + 1 < n:
            put(text[i + 1], 0)
            i += 2
            continue
        if c in "_^" and i + 1 < n:
            level = SUB if c == "_" else SUP
            nxt = text[i + 1]
            close = {"{": "}", "(": ")"}.get(nxt) if (nxt == "{" or (nxt == "(" and c == "^")) else None
            if close:
                j = text.find(close, i + 2)
                if j > 0:
                    body = text[i + 2:j] if close == "}" else text[i + 1:j + 1]
                    put(re.sub(r"\\(.)", r"\1", body), level)
                    i = j + 1
                    continue
            m = _RUN.match(text, i + 1)
            if m:
                put(m.group(0), level)
                i = m.end()
                continue
        put(c, 0)
        i += 1
    return out


@lru_cache(maxsize=4)
def _face(family: str, italic: bool):
    """A face shipped with Matplotlib (DejaVu) at 100 px per em."""
    from matplotlib import font_manager
    from matplotlib.ft2font import FT2Font
    path = font_manager.findfont(font_manager.FontProperties(
        family=family, style="italic" if italic else "normal"))
    face = FT2Font(path)
    face.set_size(100, 72)
    return face


@lru_cache(maxsize=4096)
def _advance(text: str, size: float, italic: bool) -> float:
    """Advance width (mm) of ``text`` set at ``size`` mm, from the glyph metrics of the label
    face; glyphs the serif face lacks (≙) are measured in DejaVu Sans, where :func:`_esc` sets them."""
    faces = (_face("DejaVu Serif", italic), _face("DejaVu Sans", False))
    px = 0.0
    for ch in text:
        face = next((f for f in faces if f.get_char_index(ord(ch))), None)
        # a glyph neither face has is set by the viewer's fallback font: about an em wide
        px += face.load_char(ord(ch)).linearHoriAdvance / 65536.0 if face else 100.0
    return px / 100.0 * size


#: labels laid out and written, by (text, size, italic): a drawing's labels are the same from
#: frame to frame (and from drawing to drawing), only their places change
TEXT_CACHE = 4096


@lru_cache(maxsize=TEXT_CACHE)
def _segments(text: str) -> tuple[tuple[str, int], ...]:
    return tuple(segments(text))


@lru_cache(maxsize=TEXT_CACHE)
def _layout_runs(text: str, size: float, italic: bool) -> tuple[tuple[str, int, float, float, float], ...]:
    """(text, level, x, width, font size) of each run; a superscript right after a subscript (or
    the other way round) is stacked on it, as the books set b_B^(n) and a^n_A."""
    runs, x, last = [], 0.0, None
    for t, level in _segments(text):
        fs = size if level == 0 else SCRIPT * size
        w = _advance(t, fs, italic)
        if level and last is not None and last[1] == -level:
            x0 = last[2]
            runs.append((t, level, x0, w, fs))
            x = max(x, x0 + w)
        else:
            runs.append((t, level, x, w, fs))
            x += w
        last = runs[-1]
    return tuple(runs)


@lru_cache(maxsize=TEXT_CACHE)
def label_markup(text: str, size: float = LABEL_SIZE, italic: bool = False) -> str:
    """SVG text content for a label in the books' notation (see :func:`segments`), sub- and
    superscripts as shifted tspans placed at measured positions (mm for a label of ``size``)."""
    out, y, pos = [], 0.0, 0.0
    for t, level, x, w, fs in _layout_runs(text, size, italic):
        dy = _SHIFT.get(level, 0.0) * size - y
        attrs = ""
        if abs(x - pos) > 1e-6:
            attrs += f' dx="{sym._f(x - pos)}"'
        if abs(dy) > 1e-9:
            attrs += f' dy="{sym._f(dy)}"'
        if level:
            attrs += f' font-size="{sym._f(fs)}"'
        out.append(f"<tspan{attrs}>{_esc(t)}</tspan>" if attrs else _esc(t))
        y += dy
        pos = x + w
    return "".join(out)


def plain(text: str) -> str:
    """The label as plain text (for titles, XML ids and reports)."""
    return "".join(t for t, _ in _segments(text))


@lru_cache(maxsize=TEXT_CACHE)
def text_width(text: str, size: float, italic: bool = False) -> float:
    """Width of a label (mm) measured from the font's metrics, sub- and superscripts included."""
    runs = _layout_runs(text, size, italic)
    return max((x + w for _, _, x, w, _ in runs), default=0.0)


def _ident(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]", "-", text)


# ---------------------------------------------------------------------------- the figure
class Figure:
    """A drawing: primitives in world coordinates of named spaces, laid out in panels.

    ``spaces`` maps a space name to its scale; the mechanism space uses the length scale, the
    plans use the velocity/acceleration scales. Panels appear left to right in the order of
    ``spaces``; ``titles`` gives each panel a heading (e.g. "velocity plan").
    """

    def __init__(self, scales: Scales, *, title: str = "", spaces: dict[str, Scale] | None = None,
                 titles: dict[str, str] | None = None) -> None:
        self.scales = scales
        self.title = title
        self.spaces: dict[str, Scale] = spaces or {"mechanism": scales.length}
        self.titles = titles or {}
        self.prims: list[Prim] = []
        self.labels: list[Label] = []
        self.legend: list[str] = []
        self.captions: list[str] = []  # one per step for step drawings
        self.current_step: int | None = None  # highlight this step (single-step drawing)
        self._ids: set[str] = set()
        self.used_scales: set[str] = {s.quantity for s in self.spaces.values()}
        self.clip: dict[str, tuple[np.ndarray, np.ndarray]] = {}  # space -> world box shown
        # space -> world box the panel is fitted to, whatever is drawn (frames of an animation
        # keep one layout)
        self.view: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        self.scales_declared = True  # vectors on the mechanism are at self.scales
        # spaces drawn inside a visible frame (``--frame mechanism``): what runs past the clip
        # box is cut at the frame, not at the sheet's edge
        self.framed: set[str] = set()

    # ------------------------------------------------------------------ adding
    def space(self, name: str, scale: Scale, title: str = "") -> None:
        self.spaces[name] = scale
        self.used_scales.add(scale.quantity)
        if title:
            self.titles[name] = title

    def _id(self, ident: str | None) -> str | None:
        if ident is None:
            return None
        base = _ident(ident)
        k, out = 1, base
        while out in self._ids:
            k += 1
            out = f"{base}-{k}"
        self._ids.add(out)
        return out

    def add(self, kind: str, space: str = "mechanism", *, style: Style | None = None,
            layer: str = "mechanism", ident: str | None = None, cls: str = "",
            step: int | None = None, **data) -> None:
        if space not in self.spaces:
            raise InputError(f"the figure has no space '{space}' (it has {', '.join(self.spaces)})")
        self.prims.append(Prim(kind, space, data, style or Style(), layer, self._id(ident), cls, step))

    def path(self, xy: Any, space: str = "mechanism", closed: bool = False, **kw) -> None:
        xy = np.asarray(xy, float)
        self.add("path", space, xy=xy, closed=closed, **kw)

    def line(self, point: Any, direction: Any, span: Iterable[Any], space: str = "mechanism", **kw) -> None:
        """An infinite line drawn just past the points in ``span`` (world coordinates)."""
        self.add("line", space, point=np.asarray(point, float), direction=np.asarray(direction, float),
                 span=[np.asarray(p, float) for p in span], **kw)

    def circle(self, centre: Any, radius: float, space: str = "mechanism",
               arcs: Iterable[Any] = (), **kw) -> None:
        self.add("circle", space, centre=np.asarray(centre, float), r=float(radius),
                 arcs=[np.asarray(p, float) for p in arcs], **kw)

    def arrow(self, tail: Any, head: Any, space: str = "mechanism", **kw) -> None:
        self.add("arrow", space, tail=np.asarray(tail, float), head=np.asarray(head, float), **kw)

    def dot(self, xy: Any, space: str = "mechanism", r: float = 0.55, filled: bool = True, **kw) -> None:
        self.add("dot", space, xy=np.asarray(xy, float), r=r, filled=filled, **kw)

    def symbol(self, name: str, space: str = "mechanism", **kw) -> None:
        """A kinematic symbol from :mod:`.symbols`; world points are passed as ``at``, ``to``…"""
        layer = kw.pop("layer", "mechanism")
        ident = kw.pop("ident", None)
        step = kw.pop("step", None)
        self.add("symbol", space, layer=layer, ident=ident, step=step, name=name, args=kw)

    def label(self, xy: Any, text: str, space: str = "mechanism", **kw) -> None:
        xy = np.asarray(xy, float)
        if not np.isfinite(xy).all() or not text:
            return
        if kw.get("ident"):
            kw["ident"] = self._id("label-" + kw["ident"])
        self.labels.append(Label(space, xy, text, **kw))

    def note(self, text: str) -> None:
        if text not in self.legend:
            self.legend.append(text)

    # ------------------------------------------------------------------ layout
    def _world_points(self, p: Prim) -> np.ndarray:
        """The world points (n, 2) that a primitive's extent is made of."""
        d = p.data
        if p.kind == "path":
            return d["xy"].reshape(-1, 2)
        if p.kind == "line":
            return np.array([*d["span"], d["point"]], float).reshape(-1, 2)
        if p.kind == "circle":
            if d["arcs"]:
                return np.array(d["arcs"], float).reshape(-1, 2)
            return d["centre"] + d["r"] * _COMPASS
        if p.kind == "arrow":
            return np.array([d["tail"], d["head"]])
        if p.kind == "dot":
            return d["xy"].reshape(-1, 2)
        if p.kind == "symbol":
            return _stacked([np.asarray(v, float).reshape(-1, 2) for k, v in d["args"].items()
                             if k in ("at", "to", "points", "start", "end")])
        return NONE

    def _space_points(self, name: str) -> np.ndarray:
        """The world points (n, 2) of the primitives drawn in space ``name``, in their order."""
        return _stacked([self._world_points(p) for p in self.prims if p.space == name])

    def _layout(self) -> tuple[dict, float, float]:
        boxes = {}
        for name, scale in self.spaces.items():
            pts = np.concatenate([self._space_points(name)]
                                 + [lab.xy.reshape(-1, 2) for lab in self.labels if lab.space == name])
            pts = pts[np.all(np.isfinite(pts), axis=1)]
            if name in self.clip:
                clo, chi = self.clip[name]
                pts = pts[np.all((pts >= clo) & (pts <= chi), axis=1)]
            if name in self.view:
                lo, hi = (np.asarray(v, float) for v in self.view[name])
            elif len(pts) == 0:
                continue
            else:
                lo, hi = pts.min(0), pts.max(0)
            size = (hi - lo) / scale.per_mm
            boxes[name] = (lo, hi, size, scale)
        x = MARGIN
        panels = {}
        top = TITLE_H + (6.0 if any(self.titles.get(n) for n in boxes) else 0.0) + MARGIN * 0.5
        if self.framed:
            top += FRAME_PAD - MARGIN * 0.5 + 1.5  # the frame clear of the title
        height = 0.0
        for name, (lo, hi, size, scale) in boxes.items():
            w, h = max(size[0], 20.0), max(size[1], 15.0)
            ox = x + (w - size[0]) / 2
            oy = top + (h - size[1]) / 2
            panels[name] = dict(lo=lo, hi=hi, scale=scale, ox=ox, oy=oy, x=x, y=top, w=w, h=h)
            x += w + GAP + 2 * MARGIN
            height = max(height, h)
        width = max(x - GAP - MARGIN + 22.0, 120.0)  # room for labels right of the last panel
        return panels, width, top + height + MARGIN

    def transforms(self) -> dict[str, dict]:
        """How each panel maps its world coordinates to the SVG's (mm of paper, y down):
        x_svg = origin[0] + (x − lo[0])/per_mm, y_svg = origin[1] + (hi[1] − y)/per_mm."""
        return self._transforms(self._layout()[0])

    @staticmethod
    def _transforms(panels: dict) -> dict[str, dict]:
        return {n: {"origin": [float(p["ox"]), float(p["oy"])], "lo": [float(v) for v in p["lo"]],
                    "hi": [float(v) for v in p["hi"]], "per_mm": float(p["scale"].per_mm)}
                for n, p in panels.items()}

    def svg_and_transforms(self) -> tuple[str, dict[str, dict]]:
        """`to_svg()` and `transforms()` from one layout (the workbench draws a frame with both)."""
        laid = self._layout()
        return self._svg(laid), self._transforms(laid[0])

    @staticmethod
    def _tf(panel: dict):
        # x_svg = ox + (x − lo[0])/s, y_svg = oy + (hi[1] − y)/s, written as one expression on
        # the whole array (the sign flip is exact, the origin is past the margin: not −0)
        ref = np.array([panel["lo"][0], panel["hi"][1]], float)
        origin = np.array([panel["ox"], panel["oy"]], float)
        s = panel["scale"].per_mm

        def tf(p):
            return origin + (np.asarray(p, float) - ref) * _FLIP_Y / s
        return tf

    # ------------------------------------------------------------------ rendering
    def to_svg(self, *, animate: float | None = None) -> str:
        """The drawing as an SVG document. ``animate``: seconds per step for a SMIL animation
        in which the construction steps appear one after another."""
        return self._svg(self._layout(), animate)

    def _svg(self, laid: tuple[dict, float, float], animate: float | None = None) -> str:
        panels, width, body_h = laid
        tfs = {n: self._tf(p) for n, p in panels.items()}
        cut = {n: self._cut(n) for n in panels}  # whether each panel is framed (see _cut)
        legend = list(self.legend)
        caption_h = 0.0
        captions = self.captions if animate else ([self.captions[self.current_step]]
                                                  if self.current_step is not None and self.captions else [])
        if captions:
            # as deep as the longest caption of all steps: every step's sheet is the same size
            caption_h = 5.0 + 4.4 * max(len(_wrap(c, width)) for c in self.captions)
        drawn: dict[str, list[np.ndarray]] = {n: [] for n in panels}  # sample points, by panel
        layers: dict[str, list[str]] = {}
        for p in self.prims:
            if p.space not in panels:
                continue
            svg, pts = self._render(p, tfs[p.space], panels[p.space])
            if not svg:
                continue
            svg = f'<g clip-path="url(#clip-{_ident(p.space)})">{svg}</g>'
            drawn[p.space].append(pts)
            if animate and p.step is not None:
                svg = _appear(svg, p.step, animate)
            elif self.current_step is not None and p.step is not None and p.step > self.current_step:
                continue
            layers.setdefault(p.layer, []).append(svg)
        samples = []  # what the labels keep off: the sample points on each panel with its margin
        for name, parts in drawn.items():
            pnl, pts = panels[name], _stacked(parts)
            x0, y0 = pnl["x"] - MARGIN, pnl["y"] - MARGIN
            x1, y1 = pnl["x"] + pnl["w"] + MARGIN, pnl["y"] + pnl["h"] + MARGIN
            samples.append(pts[(x0 <= pts[:, 0]) & (pts[:, 0] <= x1) & (y0 <= pts[:, 1]) & (pts[:, 1] <= y1)])
        out = []
        if self.title:
            out.append(f'<text x="{MARGIN}" y="{TITLE_H - 1.5}" font-size="4.2" '
                       f'font-weight="bold">{html.escape(plain(self.title))}</text>')
        for name, pnl in panels.items():
            if self.titles.get(name):
                out.append(f'<text x="{sym._f(pnl["x"])}" y="{sym._f(TITLE_H + 5)}" font-size="3.4" '
                           f'font-style="italic" fill="#333">{html.escape(self.titles[name])}</text>')
        for layer, parts in layers.items():
            out.append(f'<g id="layer-{_ident(layer)}" class="layer">')
            out += parts
            out.append("</g>")
        out.append('<g id="labels" class="layer">')
        out += self._place_labels(tfs, panels, samples, animate, cut)
        out.append("</g>")
        y = body_h
        if captions:
            out.append('<g id="captions">')
            for k, c in enumerate(captions):
                lines = _wrap(c, width)
                txt = "".join(f'<tspan x="{MARGIN}" dy="{0 if i == 0 else 4.4}">{html.escape(t)}</tspan>'
                              for i, t in enumerate(lines))
                el = f'<text x="{MARGIN}" y="{sym._f(y + 4.5)}" font-size="3.3" fill="#222">{txt}</text>'
                if animate:
                    el = _appear(el, k, animate, vanish=k < len(captions) - 1)
                out.append(el)
            out.append("</g>")
            y += caption_h
        leg, y = self._legend(y, width, legend)
        out.append(leg)
        height = y + 3.0
        head = ['<?xml version="1.0" encoding="UTF-8"?>',
                f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{sym._f(width)}mm" '
                f'height="{sym._f(height)}mm" viewBox="0 0 {sym._f(width)} {sym._f(height)}" '
                f'font-family="{FONT}">',
                f'<title>{html.escape(plain(self.title))}</title>',
                f'<rect x="0" y="0" width="{sym._f(width)}" height="{sym._f(height)}" fill="#fff"/>',
                "<defs>" + "".join(
                    f'<clipPath id="clip-{_ident(n)}">{self._clip_rect(p, cut[n])}</clipPath>'
                    for n, p in panels.items()) + "</defs>"]
        frames = [f'<g id="frame-{_ident(n)}" class="frame">'
                  + self._clip_rect(p, True).replace("/>", ' fill="none" stroke="#000" stroke-width="0.35"/>')
                  + "</g>" for n, p in panels.items() if cut[n]]
        out = frames + out
        return "\n".join(head + out + ["</svg>"]) + "\n"

    def _cut(self, name: str) -> bool:
        """Whether something drawn in the framed space ``name`` runs past its clip box (then the
        frame is drawn, and cuts it)."""
        if name not in self.framed or name not in self.clip:
            return False
        lo, hi = (np.asarray(v, float) for v in self.clip[name])
        pts = self._space_points(name)
        pts = pts[np.all(np.isfinite(pts), axis=1)]
        return bool(np.any((pts < lo) | (pts > hi)))

    @staticmethod
    def _clip_rect(p: dict, cut: bool) -> str:
        """The rectangle drawing is cut at: the frame (FRAME_PAD around the panel) where the
        space's layers run past the sheet (`cut`, see `_cut`), else the panel with its margin."""
        pad = FRAME_PAD if cut else MARGIN
        return (f'<rect x="{sym._f(p["x"] - pad)}" y="{sym._f(p["y"] - pad)}" '
                f'width="{sym._f(p["w"] + 2 * pad)}" height="{sym._f(p["h"] + 2 * pad)}"/>')

    def _legend(self, y: float, width: float, extra: list[str]) -> tuple[str, float]:
        parts = ['<g id="legend" font-size="3">',
                 f'<line x1="{MARGIN}" y1="{sym._f(y + 1)}" x2="{sym._f(width - MARGIN)}" '
                 f'y2="{sym._f(y + 1)}" stroke="#999" stroke-width="0.2"/>']
        scales = [self.scales.length] + [s for s in (self.scales.velocity, self.scales.acceleration)
                                         if s is not None and s.quantity in self.used_scales]
        scales += getattr(self, "extra_scales", [])  # e.g. the force scale of drawing.force_layers
        # scale bars in rows, each as wide as its measured text; a row is as deep as the bar's
        # value under it, so that the legend's lines below never touch it
        x = MARGIN
        yy = y + 5.5
        for s in scales:
            w = self._scale_bar_width(s)
            if x > MARGIN and x + w > width - MARGIN:
                x, yy = MARGIN, yy + SCALE_ROW
            parts.append(self._scale_bar(x, yy, s))
            x += w + 6.0
        yy += SCALE_BELOW + 0.8 * LEGEND_SIZE  # the first line's ascent below the last row
        for t in extra:
            for line in _wrap(t, width, LEGEND_SIZE):
                parts.append(f'<text x="{MARGIN}" y="{sym._f(yy)}">{label_markup(line, LEGEND_SIZE)}</text>')
                yy += LEGEND_LINE
        parts.append("</g>")
        return "".join(parts), yy

    @staticmethod
    def _scale_words_at(s: Scale) -> float:
        """Where the scale in words starts, right of the bar's value (centred under its end)."""
        return SCALE_BAR + max(3.0, text_width(_scale_value(s), SCALE_VALUE_SIZE) / 2 + 1.5)

    def _scale_bar_width(self, s: Scale) -> float:
        return self._scale_words_at(s) + text_width(s.text(), SCALE_TEXT_SIZE)

    def _scale_bar(self, x: float, y: float, s: Scale) -> str:
        """A scale bar (*Maßstabsleiste*) of 20 mm with its value, and the scale in words."""
        L = SCALE_BAR
        ticks = "".join(f'<line x1="{sym._f(x + t)}" y1="{sym._f(y - 1.2)}" x2="{sym._f(x + t)}" '
                        f'y2="{sym._f(y + 0.4)}" stroke="#000" stroke-width="0.25"/>' for t in (0, 10, 20))
        return (f'<g class="scale" id="scale-{s.quantity}">'
                f'<line x1="{sym._f(x)}" y1="{sym._f(y)}" x2="{sym._f(x + L)}" y2="{sym._f(y)}" '
                f'stroke="#000" stroke-width="0.5"/>{ticks}'
                f'<text x="{sym._f(x)}" y="{sym._f(y + 3.6)}" font-size="{SCALE_VALUE_SIZE}">0</text>'
                f'<text x="{sym._f(x + L)}" y="{sym._f(y + 3.6)}" font-size="{SCALE_VALUE_SIZE}" '
                f'text-anchor="middle">{html.escape(_scale_value(s))}</text>'
                f'<text x="{sym._f(x + self._scale_words_at(s))}" y="{sym._f(y + 1)}" '
                f'font-size="{SCALE_TEXT_SIZE}">{label_markup(s.text(), SCALE_TEXT_SIZE)}</text></g>')

    def _render(self, p: Prim, tf, panel: dict) -> tuple[str, np.ndarray]:
        d, st = p.data, p.style
        ident = f' id="{p.ident}"' if p.ident else ""
        cls = f' class="{p.cls}"' if p.cls else ""
        if p.kind == "path":
            xy = tf(d["xy"])
            far = _far(panel)
            ok = np.isfinite(xy).all(-1) & np.all((xy > far[0]) & (xy < far[1]), axis=-1)
            if ok.sum() < 2:
                return "", NONE
            # the runs of consecutive points kept, each drawn as one polyline
            kept = np.flatnonzero(ok)
            runs = [xy[r] for r in np.split(kept, np.flatnonzero(np.diff(kept) > 1) + 1) if len(r) >= 2]
            if not runs:
                return "", NONE
            dd = " ".join(_polyline(r) for r in runs)
            if d["closed"] and len(runs) == 1 and ok.all():
                dd += " Z"
            pts = np.concatenate([_resample(r) for r in runs])
            return f'<path{ident}{cls} d="{dd}" {st.attrs()} stroke-linejoin="round"/>', pts
        if p.kind == "line":
            pts = [q for q in d["span"] if np.all(np.isfinite(q))]
            u = d["direction"]
            if not np.all(np.isfinite(u)) or np.linalg.norm(u) == 0 or not np.all(np.isfinite(d["point"])):
                return "", NONE
            u = u / np.linalg.norm(u)
            o = d["point"]
            if not pts:
                pts = [o]
            t = np.array([np.dot(q - o, u) for q in pts])
            over = 4.0 * panel["scale"].per_mm
            if np.ptp(t) == 0:
                over = 12.0 * panel["scale"].per_mm
            a, b = o + (t.min() - over) * u, o + (t.max() + over) * u
            pa, pb = _clip_segment(tf(a), tf(b), _far(panel))
            if pa is None:
                return "", NONE
            return (f'<line{ident}{cls} x1="{sym._f(pa[0])}" y1="{sym._f(pa[1])}" x2="{sym._f(pb[0])}" '
                    f'y2="{sym._f(pb[1])}" {st.attrs()}/>', _resample(np.array([pa, pb])))
        if p.kind == "circle":
            c, r = d["centre"], d["r"]
            if not (np.all(np.isfinite(c)) and np.isfinite(r)):
                return "", NONE
            pc = tf(c)
            rp = r / panel["scale"].per_mm
            if rp > 4000.0:
                # a circle this large is a straight line on the sheet: its tangent nearest the panel
                mid = np.array([panel["x"] + panel["w"] / 2, panel["y"] + panel["h"] / 2])
                u = (mid - pc) / np.linalg.norm(mid - pc)
                q = pc + rp * u
                t = np.array([-u[1], u[0]]) * 2 * (panel["w"] + panel["h"])
                a, b = q - t, q + t
                return (f'<line{ident}{cls} x1="{sym._f(a[0])}" y1="{sym._f(a[1])}" x2="{sym._f(b[0])}" '
                        f'y2="{sym._f(b[1])}" {st.attrs()}/>', _resample(np.array([a, b]), 2.0))
            if not d["arcs"]:
                t = np.linspace(0, 2 * np.pi, max(12, int(2 * np.pi * rp / 0.8)))
                pts = pc + rp * np.stack([np.cos(t), np.sin(t)], -1)
                return (f'<circle{ident}{cls} cx="{sym._f(pc[0])}" cy="{sym._f(pc[1])}" r="{sym._f(rp)}" '
                        f'{st.attrs()}/>', pts)
            parts, pts = [], []
            for q in d["arcs"]:
                pq = tf(q)
                if not np.all(np.isfinite(pq)):
                    continue
                a0 = math.atan2(pq[1] - pc[1], pq[0] - pc[0])
                half = min(math.pi, 5.0 / max(rp, 1e-9))
                t = np.linspace(a0 - half, a0 + half, 16)
                xy = pc + rp * np.stack([np.cos(t), np.sin(t)], -1)
                parts.append(_polyline(xy))
                pts.append(xy)
            return f'<path{ident}{cls} d="{" ".join(parts)}" {st.attrs()}/>', _stacked(pts)
        if p.kind == "arrow":
            a, b = tf(d["tail"]), tf(d["head"])
            if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
                return "", NONE
            L = float(np.linalg.norm(b - a))
            if L < 1e-6:
                return f'<g{ident}{cls}/>', NONE
            u = (b - a) / L
            head = sym.arrowhead(a, b, st.width, st.stroke)
            b2 = b - u * min(1.5, 0.4 * L)
            return (f'<g{ident}{cls}><line x1="{sym._f(a[0])}" y1="{sym._f(a[1])}" x2="{sym._f(b2[0])}" '
                    f'y2="{sym._f(b2[1])}" {st.attrs()}/>{head}</g>', _resample(np.array([a, b])))
        if p.kind == "dot":
            c = tf(d["xy"])
            if not np.all(np.isfinite(c)):
                return "", NONE
            fill = st.stroke if d["filled"] else "#fff"
            return (f'<circle{ident}{cls} cx="{sym._f(c[0])}" cy="{sym._f(c[1])}" r="{sym._f(d["r"])}" '
                    f'fill="{fill}" stroke="{st.stroke}" stroke-width="0.25"/>', c[None, :])
        if p.kind == "symbol":
            args = {}
            for k, v in d["args"].items():
                if k in ("at", "to", "start", "end"):
                    args[k] = tf(v)
                elif k == "points":
                    args[k] = tf(np.asarray(v, float))
                elif k == "radius_world":
                    args["r"] = v / panel["scale"].per_mm
                elif k in ("down", "side", "axis"):
                    v = np.asarray(v, float)
                    args[k] = np.array([v[0], -v[1]])
                else:
                    args[k] = v
            if any(not np.all(np.isfinite(v)) for k, v in args.items() if isinstance(v, np.ndarray)):
                return "", NONE
            svg, pts = _symbol(d["name"], args)
            return f'<g{ident} class="symbol {d["name"]}{(" " + p.cls) if p.cls else ""}">{svg}</g>', pts
        return "", NONE

    def _place_labels(self, tfs: dict, panels: dict, samples: list, animate: float | None,
                      cut: dict[str, bool]) -> list[str]:
        """Each label beside its point where it covers least: other labels (measured boxes), the
        drawn geometry (sampled lines, symbols) and the other labels' points. Greedy first, in
        order, then a second pass moves each label to its best place among all the others (a
        crowded corner settles); a label put far from its point gets a thin leader line."""
        todo = []  # (label, anchor on paper, width, height, frame box or None)
        for lab in self.labels:
            if lab.space not in tfs:
                continue
            if self.current_step is not None and lab.step is not None and lab.step > self.current_step and not animate:
                continue
            a = tfs[lab.space](lab.xy)
            frame = None
            if cut.get(lab.space):
                pn = panels[lab.space]
                frame = (pn["x"] - FRAME_PAD, pn["y"] - FRAME_PAD, pn["x"] + pn["w"] + FRAME_PAD,
                         pn["y"] + pn["h"] + FRAME_PAD)
                if not (frame[0] <= a[0] <= frame[2] and frame[1] <= a[1] <= frame[3]):
                    continue  # its point is cut off with the drawing at the frame
            w, h = text_width(lab.text, lab.size, lab.italic) + 0.4, lab.size * 0.95
            todo.append((lab, a, w, h, frame))
        if not todo:
            return []
        ink = _stacked(samples)
        ink = ink[np.all(np.isfinite(ink), axis=1)]
        points = np.array([t[1] for t in todo], float).reshape(-1, 2)
        placed = np.full((len(todo), 4), np.nan)  # the boxes chosen so far (x0, y0, x1, y1)

        # every label's candidate boxes at once: directions in order of preference, each at the
        # distances nearest first (k: the direction's rank, d: the distance)
        n, nd = len(todo), len(LABEL_DISTANCES)
        dirs = np.array([_candidates(t[0].prefer) for t in todo], float).reshape(n, -1, 2)
        wh = np.array([(t[2], t[3]) for t in todo], float).reshape(n, 2)
        dist = np.array(LABEL_DISTANCES) + np.array([t[0].clear for t in todo], float)[:, None]
        k = np.repeat(np.arange(dirs.shape[1]), nd)
        d = np.tile(dist, (1, dirs.shape[1]))
        c = points[:, None, :] + dirs[:, k] * (d[:, :, None] + wh[:, None, :] / 2)  # box centres
        boxes = np.concatenate([c - wh[:, None, :] / 2, c + wh[:, None, :] / 2], axis=2)
        # the drawn lines have a width: what runs just past a box touches it too
        wide = boxes + np.array([-INK_PAD, -INK_PAD, INK_PAD, INK_PAD])
        on_ink = _inside_counts(ink, wide.reshape(-1, 4)).reshape(n, -1)
        # another label's point under this label costs most (its own does not count)
        under = ((points[None, None, :, 0] >= wide[:, :, None, 0]) & (points[None, None, :, 0] <= wide[:, :, None, 2])
                 & (points[None, None, :, 1] >= wide[:, :, None, 1]) & (points[None, None, :, 1] <= wide[:, :, None, 3]))
        under[np.arange(n), :, np.arange(n)] = False
        on_points = under.sum(axis=2)
        preference = 0.15 * k + 0.6 * d
        scored = []  # per label: its boxes, its area, what each box costs whatever the others' boxes
        for i, (_, _, w, h, frame) in enumerate(todo):
            costs = [2.0 * on_ink[i], 12.0 * on_points[i], preference[i]]
            if frame is not None:
                b = boxes[i]
                across = ((b[:, 0] < frame[0]) | (b[:, 2] > frame[2]) | (b[:, 1] < frame[1])
                          | (b[:, 3] > frame[3]))
                costs.append(1e4 * across)
            # the boxes' edges as columns, to meet the other labels' boxes (rows)
            scored.append((boxes[i], boxes[i].T[:, :, None], w * h, costs))

        def best_box(i: int):
            """The candidate box of label i that covers least: its fixed costs and the area it
            shares with the other labels' boxes (all candidates at once)."""
            box, (x0, y0, x1, y1), area, costs = scored[i]
            keep = np.isfinite(placed[:, 0])
            keep[i] = False
            ox0, oy0, ox1, oy1 = placed[keep].T
            ow = np.minimum(x1, ox1) - np.maximum(x0, ox0)
            oh = np.minimum(y1, oy1) - np.maximum(y0, oy0)
            shared = np.maximum(ow, 0.0, out=ow) * np.maximum(oh, 0.0, out=oh)
            score = 40.0 * shared.sum(axis=1) / area
            for cost in costs:  # added in this order, as they always were (equal scores, same pick)
                score += cost
            return box[int(np.argmin(score))]

        for _ in range(2):  # greedy, then each label again among all the others
            for i in range(len(todo)):
                placed[i] = best_box(i)
        out = []
        for (lab, a, w, h, frame), (x0, y0, x1, y1) in zip(todo, placed):
            ident = f' id="{lab.ident}"' if lab.ident else ""
            style = ' font-style="italic"' if lab.italic else ""
            el = (f'<text{ident} x="{sym._f(x0 + 0.2)}" y="{sym._f(y1 - 0.22 * lab.size)}" '
                  f'font-size="{sym._f(lab.size)}"{style} fill="{lab.colour}">{label_markup(lab.text, lab.size, lab.italic)}</text>')
            # a white halo keeps labels readable over thin construction lines
            halo = (f'<rect x="{sym._f(x0)}" y="{sym._f(y0 + 0.1)}" width="{sym._f(x1 - x0)}" '
                    f'height="{sym._f(y1 - y0 - 0.1)}" fill="#fff" fill-opacity="0.75"/>')
            leader = ""
            q = np.clip(a, [x0, y0], [x1, y1])  # the box's point nearest the label's point
            far = np.linalg.norm(q - a)
            if far > LEADER_FROM + lab.clear:
                e = a + (q - a) * (lab.clear + 0.6) / far
                leader = (f'<line class="leader" x1="{sym._f(e[0])}" y1="{sym._f(e[1])}" x2="{sym._f(q[0])}" '
                          f'y2="{sym._f(q[1])}" stroke="{lab.colour}" stroke-width="0.12"/>')
            el = f"<g>{leader}{halo}{el}</g>"
            if animate and lab.step is not None:
                el = _appear(el, lab.step, animate)
            out.append(el)
        return out

    # ------------------------------------------------------------------ output
    def save(self, path: str | Path, *, dpi: float = 200.0, animate: float | None = None) -> Path:
        """Write ``.svg``, ``.png`` (``dpi``) or ``.pdf``; PNG and PDF are converted from the SVG."""
        path = Path(path)
        svg = self.to_svg(animate=animate)
        suffix = path.suffix.lower()
        if suffix not in (".svg", ".png", ".pdf"):
            raise InputError(f"cannot write '{path}': the drawing formats are .svg, .png and .pdf")
        if suffix == ".svg":
            write_output_file(path, svg)
        else:
            convert(svg, path, dpi=dpi)
        return path


def convert(svg: str, path: Path, dpi: float = 200.0) -> None:
    """SVG text to PNG or PDF with cairosvg (needs the system cairo library)."""
    try:
        import cairosvg
    except (ImportError, OSError) as exc:  # cairocffi raises OSError when libcairo is missing
        raise InputError(f"writing {path.suffix} needs cairosvg and the cairo library "
                         f"(e.g. apt-get install libcairo2); write .svg instead ({exc})") from None
    data = svg.encode("utf-8")
    with output_path(path) as tmp:  # all or nothing: the previous file stays until this one is whole
        if path.suffix.lower() == ".png":
            cairosvg.svg2png(bytestring=data, write_to=str(tmp), dpi=dpi)
        else:
            cairosvg.svg2pdf(bytestring=data, write_to=str(tmp))


def _symbol(name: str, a: dict) -> tuple[str, np.ndarray]:
    if name == "revolute":
        return sym.revolute(a["at"], a.get("colour", sym.INK))
    if name == "fixed-pivot":
        return sym.fixed_pivot(a["at"], a.get("down", (0, 1)))
    if name == "bar":
        return sym.bar(a["at"], a["to"])
    if name == "plate":
        return sym.plate(a["points"])
    if name == "block":
        return sym.block(a["at"], a["axis"], a.get("colour", sym.INK))
    if name == "guide":
        return sym.guide(a["start"], a["end"], a["side"])
    if name == "slot":
        return sym.slot(a["start"], a["end"])
    if name == "ground":
        return sym.ground(a["start"], a["end"], a["side"])
    if name == "pitch-circle":
        return sym.pitch_circle(a["at"], a["r"])
    raise ValueError(f"unknown symbol {name!r}")


def _appear(svg: str, step: int, dur: float, vanish: bool = False) -> str:
    begin = step * dur
    anim = f'<set attributeName="visibility" to="visible" begin="{begin:g}s"/>'
    if vanish:
        anim += f'<set attributeName="visibility" to="hidden" begin="{begin + dur:g}s"/>'
    return f'<g visibility="hidden">{anim}{svg}</g>'


def _far(panel: dict) -> tuple[np.ndarray, np.ndarray]:
    """A box well beyond the panel (paper mm): geometry outside it is not written at all."""
    pad = 2 * (panel["w"] + panel["h"]) + 50
    return (np.array([panel["x"] - pad, panel["y"] - pad]),
            np.array([panel["x"] + panel["w"] + pad, panel["y"] + panel["h"] + pad]))


def _clip_segment(a: np.ndarray, b: np.ndarray, box) -> tuple:
    """Liang–Barsky clipping of the segment a–b to ``box``; (None, None) if it misses."""
    lo, hi = box
    d = b - a
    t0, t1 = 0.0, 1.0
    for k in range(2):
        for p, q in ((-d[k], a[k] - lo[k]), (d[k], hi[k] - a[k])):
            if p == 0:
                if q < 0:
                    return None, None
                continue
            r = q / p
            if p < 0:
                t0 = max(t0, r)
            else:
                t1 = min(t1, r)
    if t0 > t1 or not np.isfinite(t0 + t1):
        return None, None
    return a + t0 * d, a + t1 * d


def _wrap(text: str, width: float, size: float = 3.3) -> list[str]:
    """``text`` broken at spaces into lines whose measured width fits the sheet's ``width``."""
    room = width - 2 * MARGIN
    words, lines, cur = text.split(), [], ""
    for w in words:
        trial = f"{cur} {w}".strip()
        if cur and text_width(trial, size) > room:
            lines.append(cur)
            cur = w
        else:
            cur = trial
    if cur:
        lines.append(cur)
    return lines or [""]


def _scale_value(s: Scale) -> str:
    """The value a scale bar's 20 mm stand for."""
    return f"{SCALE_BAR * s.per_mm:.4g} {s.unit}"


def _resample(xy: np.ndarray, step: float = 0.8) -> np.ndarray:
    return sym.resample(xy, step)


_FLIP_Y = np.array([1.0, -1.0])
#: a circle's extent: its points east, west, north and south of the centre, per unit radius
_COMPASS = np.array([(1, 0), (-1, 0), (0, 1), (0, -1)], float)

#: no sample points
NONE = np.empty((0, 2))
NONE.flags.writeable = False


def _stacked(parts: list[np.ndarray]) -> np.ndarray:
    """Arrays of points (n, 2) one after another."""
    return np.concatenate(parts) if parts else NONE


def _polyline(xy: np.ndarray) -> str:
    """SVG path data 'M x y L x y …' through the points (n, 2)."""
    s = sym._fs(xy)
    return "M " + " L ".join(f"{a} {b}" for a, b in zip(s[::2], s[1::2]))


def _inside_counts(pts: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """How many of the points (n, 2) lie in each box (m, 4: x0, y0, x1, y1, edges included).

    The points are cut into horizontal bands as tall as the tallest box (a box meets at most
    two) and sorted by band, then by x: a box's points are within one slice of each band it
    meets, found by one search on the key band·S + x (S wider than the points' spread, so
    that bands keep apart; rounding the key keeps its order, so a slice holds every point it
    must), and each point of the slices is tested exactly."""
    if len(pts) == 0 or len(boxes) == 0:
        return np.zeros(len(boxes), dtype=np.intp)
    x, y = pts[:, 0], pts[:, 1]
    x_min, y_min = x.min(), y.min()
    spread = float(x.max() - x_min)
    tall = max(float(np.max(boxes[:, 3] - boxes[:, 1])), 1e-3 * (spread + 1.0))
    bands = int((float(y.max()) - float(y_min)) // tall) + 1
    step = spread + 10.0
    band = np.floor((y - y_min) / tall).astype(np.intp)
    key = band * step + (x - x_min)
    order = np.argsort(key, kind="stable")
    key, xs, ys = key[order], x[order], y[order]
    # the bands each box meets (none for a box above or below all the points)
    first = np.maximum(np.floor((boxes[:, 1] - y_min) / tall), 0)
    last = np.minimum(np.floor((boxes[:, 3] - y_min) / tall), bands - 1)
    n_bands = np.maximum(last - first + 1, 0).astype(np.intp)
    box_q = np.repeat(np.arange(len(boxes)), n_bands)
    band_q = first[box_q] + (np.arange(len(box_q)) - np.repeat(np.cumsum(n_bands) - n_bands, n_bands))
    # the box's x range, clipped to the points' (which keeps the slice's points the same)
    x0 = np.clip(boxes[box_q, 0] - x_min, -1.0, spread + 1.0)
    x1 = np.clip(boxes[box_q, 2] - x_min, -1.0, spread + 1.0)
    lo = np.searchsorted(key, band_q * step + x0, "left")
    span = np.maximum(np.searchsorted(key, band_q * step + x1, "right") - lo, 0)
    query = np.repeat(np.arange(len(box_q)), span)
    at = np.arange(len(query)) - np.repeat(np.cumsum(span) - span, span) + lo[query]
    box_of = box_q[query]
    b = boxes[box_of]
    ok = (xs[at] >= b[:, 0]) & (xs[at] <= b[:, 2]) & (ys[at] >= b[:, 1]) & (ys[at] <= b[:, 3])
    return np.bincount(box_of[ok], minlength=len(boxes))


#: the directions a label may be put in from its point (paper, y down), unit vectors
_DIRECTIONS = [(dx / math.hypot(dx, dy), dy / math.hypot(dx, dy))
               for dx, dy in [(1, -1), (1, 1), (-1, -1), (-1, 1), (1, 0), (-1, 0), (0, -1), (0, 1)]]


def _candidates(prefer: np.ndarray | None) -> list[tuple[float, float]]:
    """:data:`_DIRECTIONS`, those nearest ``prefer`` first."""
    dirs = list(_DIRECTIONS)
    if prefer is not None and np.all(np.isfinite(prefer)):
        norm = np.linalg.norm(prefer)
        if norm > 0:
            px, py = (np.asarray(prefer, float) / norm).tolist()
            dirs.sort(key=lambda d: -(d[0] * px + d[1] * py))
    return dirs
