"""Kinematic symbols in the style of ISO 3952-1 (*Getriebesymbole*), drawn in paper millimetres.

Owns the SVG fragments of the symbols: the revolute joint (*Drehgelenk*, small open circle), the
fixed pivot (*Gestelllager*: the joint circle on a bearing block standing on hatched ground), the
frame (hatched ground line, *Gestell*), binary and ternary links (bars and plates, *Glieder*),
the block on a guide (*Schubgelenk*: a rectangle sliding on a line with hatching on the frame
side), the pin in a slot (*Kurvengelenk/Kulisse*: a slot outline round the pin), and gear pitch
circles (dash-dot). Each function takes paper coordinates (mm, y downwards) and returns
``(svg_fragment, sample_points)``, the sample points an (n, 2) array: they let the label placer
avoid the symbol.

Sizes follow the proportions of ISO 3952 drawings at textbook size: joint circles 2 mm in
diameter, bearing blocks 5 mm wide, hatching at 45° every 1.2 mm.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

JOINT_R = 1.0  # radius of a joint circle [mm]
LINK_W = 0.7  # line weight of links [mm]
THIN = 0.25
HATCH_STEP = 1.2
INK = "#000"
#: the bearing block of a fixed pivot: height and half-width of its foot, and how far the
#: ground line runs past the foot on either side [mm]
BEARING_H, BEARING_W, GROUND_OVERHANG = 3.6, 2.6, 1.4
#: depth of the hatching under a ground line and beyond a guide [mm]
GROUND_DEPTH, GUIDE_DEPTH = 2.0, 1.6
#: a sliding block's length and height, and a guide's offset from the block's axis [mm]
BLOCK_L, BLOCK_H, GUIDE_OFFSET = 7.0, 4.0, 2.0
#: a slot's width [mm]
SLOT_W = 2.6


def _f(v: float) -> str:
    """A number of the SVG text: mm to 3 decimals, trailing zeros dropped."""
    return f"{v:.3f}".rstrip("0").rstrip(".") if -1e6 < v < 1e6 else f"{v:.1f}"


def _fs(values) -> list[str]:
    """:func:`_f` of every number of ``values`` (any shape, in C order), at once: a drawing
    writes thousands of coordinates a frame, and one list of Python floats formats faster than
    NumPy scalars one by one."""
    return [f"{v:.3f}".rstrip("0").rstrip(".") if -1e6 < v < 1e6 else f"{v:.1f}"
            for v in np.ravel(values).tolist()]


def _pts(xy: np.ndarray) -> str:
    s = _fs(xy)
    return " ".join(f"{x},{y}" for x, y in zip(s[::2], s[1::2]))


def _line(p, q, w=THIN, colour=INK, extra="") -> str:
    return _lines(np.concatenate((np.ravel(p), np.ravel(q))), w, colour, extra)


def _lines(ends: np.ndarray, w=THIN, colour=INK, extra="") -> str:
    """Lines from p to q, one a row (x_p, y_p, x_q, y_q) of ``ends``, all of one weight."""
    s = _fs(ends)
    tail = f'stroke="{colour}" stroke-width="{_f(w)}" stroke-linecap="round"{extra}/>'
    return "".join(f'<line x1="{s[k]}" y1="{s[k + 1]}" x2="{s[k + 2]}" y2="{s[k + 3]}" {tail}'
                   for k in range(0, len(s), 4))


def _fractions(n: int) -> np.ndarray:
    """n fractions 0 … 1 as a column; the few short ones that symbols use over and over are
    made once (read-only: shared by every caller)."""
    return _short_fractions(n) if n <= 256 else np.linspace(0, 1, n)[:, None]


@lru_cache(maxsize=256)
def _short_fractions(n: int) -> np.ndarray:
    t = np.linspace(0, 1, n)[:, None]
    t.flags.writeable = False
    return t


def _samples(p, q, step=0.6) -> np.ndarray:
    """Points (n, 2) along p–q about ``step`` apart, both ends included."""
    p, q = np.asarray(p, float), np.asarray(q, float)
    n = max(2, int(np.linalg.norm(q - p) / step) + 1)
    return p + _fractions(n) * (q - p)


def resample(xy: np.ndarray, step: float = 0.6) -> np.ndarray:
    """:func:`_samples` along each segment of the polyline ``xy`` (n, 2), one after another, all
    segments at once."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    a, d = xy[:-1], xy[1:] - xy[:-1]
    if len(a) == 0:
        return np.empty((0, 2))
    per = np.linalg.norm(d, axis=1) / step
    if not np.all(np.isfinite(per)):  # as _samples takes them (it refuses what cannot be counted)
        return np.concatenate([_samples(p, q, step) for p, q in zip(xy[:-1], xy[1:])])
    counts = np.maximum(2, per.astype(int) + 1)
    # a length a rounding away from a whole number of steps: counted as _samples counts it
    # (the norm of one vector sums its squares in another order)
    for k in np.flatnonzero(np.abs(per - np.rint(per)) <= 1e-9 * np.maximum(per, 1.0)):
        counts[k] = max(2, int(np.linalg.norm(d[k]) / step) + 1)
    t = np.concatenate([_fractions(n) for n in counts.tolist()])
    return np.repeat(a, counts, axis=0) + t * np.repeat(d, counts, axis=0)


def _outline_samples(v: np.ndarray) -> np.ndarray:
    """:func:`_samples` along each edge of the closed polygon ``v``, one edge after another."""
    return resample(np.concatenate((v, v[:1])))


def hatch(p: np.ndarray, q: np.ndarray, side: np.ndarray, depth: float = GROUND_DEPTH,
          colour: str = INK) -> str:
    """45° hatching along the ground line p–q on the side ``side`` (a unit vector)."""
    p, q, side = (np.asarray(v, float) for v in (p, q, side))
    d = q - p
    L = float(np.linalg.norm(d))
    if L == 0:
        return ""
    u = d / L
    # a stroke every HATCH_STEP from 0.3 on, as far as the line goes
    at = np.arange(int(L / HATCH_STEP) + 1) * HATCH_STEP + 0.3
    a = p + u * at[at <= L][:, None]
    b = a + side * depth - u * depth * 0.8
    return _line(p, q, 0.35, colour) + _lines(np.concatenate((a, b), axis=1), 0.18, colour)


#: a joint circle's ring of sample points about its centre
_RING_ANGLES = np.linspace(0.0, 2 * np.pi, 9)[:-1]
_RING = JOINT_R * np.stack([np.cos(_RING_ANGLES), np.sin(_RING_ANGLES)], -1)


def revolute(c: np.ndarray, colour: str = INK) -> tuple[str, np.ndarray]:
    """A moving hinge: an open circle."""
    c = np.asarray(c, float)
    svg = (f'<circle cx="{_f(c[0])}" cy="{_f(c[1])}" r="{_f(JOINT_R)}" fill="#fff" '
           f'stroke="{colour}" stroke-width="0.35"/>')
    return svg, np.concatenate(([c], c + _RING))  # its ring, so that labels keep off the circle


def bearing(c: np.ndarray, down: np.ndarray, unit: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The outline of a fixed pivot's bearing block (a quadrilateral narrowing to the joint
    circle, (4, 2)) and the ends of its ground line, with `unit` length per symbol millimetre
    (1 on paper; the DXF draws symbols in the mechanism's coordinates)."""
    c, down = np.asarray(c, float), np.asarray(down, float)
    down = down / np.linalg.norm(down)
    side = np.array([-down[1], down[0]])
    h, w, r = BEARING_H * unit, BEARING_W * unit, JOINT_R * unit
    base = c + down * h
    tri = np.array([c + down * r * 0.6 + side * r * 0.9, base + side * w,
                    base - side * w, c + down * r * 0.6 - side * r * 0.9])
    over = (BEARING_W + GROUND_OVERHANG) * unit
    return tri, base + side * over, base - side * over


def fixed_pivot(c: np.ndarray, down: np.ndarray = (0.0, 1.0), colour: str = INK) -> tuple[str, np.ndarray]:
    """A frame bearing: joint circle on a triangular block standing on hatched ground.

    ``down`` is the unit direction (paper) from the pivot to the ground line.
    """
    c, down = np.asarray(c, float), np.asarray(down, float)
    down = down / np.linalg.norm(down)
    tri, g0, g1 = bearing(c, down)
    base = c + down * BEARING_H
    svg = (f'<polygon points="{_pts(tri)}" fill="#fff" stroke="{colour}" stroke-width="0.35" '
           f'stroke-linejoin="round"/>')
    svg += hatch(g1, g0, down, colour=colour)
    s, pts = revolute(c, colour)
    return svg + s, np.concatenate((pts, _samples(c, base), _samples(g0, g1)))


def ground(p: np.ndarray, q: np.ndarray, side: np.ndarray, colour: str = INK) -> tuple[str, np.ndarray]:
    """A hatched frame line from p to q, hatching on ``side``."""
    return hatch(p, q, side, colour=colour), _samples(p, q)


def bar(p: np.ndarray, q: np.ndarray, colour: str = INK, width: float = LINK_W) -> tuple[str, np.ndarray]:
    """A binary link drawn as a heavy line between its joints."""
    return _line(p, q, width, colour), _samples(p, q)


def plate(vertices: np.ndarray, colour: str = INK, fill: str = "#ececec") -> tuple[str, np.ndarray]:
    """A ternary (or larger) link: a lightly filled plate with heavy edges, welded corners."""
    v = np.asarray(vertices, float)
    svg = (f'<polygon points="{_pts(v)}" fill="{fill}" stroke="{colour}" '
           f'stroke-width="{_f(LINK_W * 0.8)}" stroke-linejoin="round"/>')
    return svg, _outline_samples(v)


def block_corners(c: np.ndarray, axis: np.ndarray, unit: float = 1.0) -> np.ndarray:
    """The corners (4, 2) of a sliding block centred at c, its long side along ``axis``."""
    c, axis = np.asarray(c, float), np.asarray(axis, float)
    u = axis / np.linalg.norm(axis)
    n = np.array([-u[1], u[0]])
    a, b = u * BLOCK_L * unit / 2, n * BLOCK_H * unit / 2
    return np.array([c + a + b, c - a + b, c - a - b, c + a - b])


def block(c: np.ndarray, axis: np.ndarray, colour: str = INK) -> tuple[str, np.ndarray]:
    """A sliding block (crosshead, *Kreuzkopf*) centred at c, long side along ``axis``."""
    r = block_corners(c, axis)
    svg = (f'<polygon points="{_pts(r)}" fill="#fff" stroke="{colour}" stroke-width="0.5" '
           f'stroke-linejoin="round"/>')
    return svg, _outline_samples(r)


def guide(p: np.ndarray, q: np.ndarray, side: np.ndarray, offset: float = GUIDE_OFFSET,
          colour: str = INK) -> tuple[str, np.ndarray]:
    """The frame's guide for a block: a line p–q (offset from the block axis) hatched outside."""
    p, q, side = (np.asarray(v, float) for v in (p, q, side))
    return hatch(p + side * offset, q + side * offset, side, depth=GUIDE_DEPTH, colour=colour), _samples(p, q)


def slot(p: np.ndarray, q: np.ndarray, colour: str = INK, width: float = SLOT_W) -> tuple[str, np.ndarray]:
    """A straight slot (pin guide, *Kulisse*) from p to q: two parallel lines, rounded ends."""
    p, q = np.asarray(p, float), np.asarray(q, float)
    d = q - p
    L = float(np.linalg.norm(d))
    if L == 0:
        return "", np.empty((0, 2))
    u = d / L
    n = np.array([-u[1], u[0]]) * width / 2
    r = width / 2
    path = (f'M {_f((p + n)[0])} {_f((p + n)[1])} L {_f((q + n)[0])} {_f((q + n)[1])} '
            f'A {_f(r)} {_f(r)} 0 0 0 {_f((q - n)[0])} {_f((q - n)[1])} '
            f'L {_f((p - n)[0])} {_f((p - n)[1])} A {_f(r)} {_f(r)} 0 0 0 {_f((p + n)[0])} {_f((p + n)[1])} Z')
    svg = f'<path d="{path}" fill="none" stroke="{colour}" stroke-width="0.45"/>'
    return svg, np.concatenate((_samples(p + n, q + n), _samples(p - n, q - n)))


def pitch_circle(c: np.ndarray, r: float, colour: str = INK) -> tuple[str, np.ndarray]:
    """A gear's pitch circle (*Teilkreis*), dash-dot."""
    c = np.asarray(c, float)
    svg = (f'<circle cx="{_f(c[0])}" cy="{_f(c[1])}" r="{_f(r)}" fill="none" stroke="{colour}" '
           f'stroke-width="0.35" stroke-dasharray="6 1.2 0.8 1.2"/>')
    t = np.linspace(0, 2 * np.pi, max(8, int(2 * np.pi * r / 0.8)))
    return svg, c + r * np.stack([np.cos(t), np.sin(t)], -1)


def arrowhead(tail: np.ndarray, head: np.ndarray, width: float, colour: str) -> str:
    """A filled arrowhead at ``head`` pointing away from ``tail`` (size grows with the line weight)."""
    tail, head = np.asarray(tail, float), np.asarray(head, float)
    d = head - tail
    L = float(np.linalg.norm(d))
    if L == 0 or not np.isfinite(L):
        return ""
    u = d / L
    n = np.array([-u[1], u[0]])
    length = min(2.2 + 2.0 * width, 0.45 * L)
    half = length * 0.32
    tri = np.array([head, head - u * length + n * half, head - u * length * 0.82, head - u * length - n * half])
    return f'<polygon points="{_pts(tri)}" fill="{colour}" stroke="none"/>'
