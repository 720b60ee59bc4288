"""DXF of the mechanism drawing and of point paths (*Bahnkurven*), for CAD users.

Coordinates are the mechanism's own, in the file's length unit (the DXF header's $INSUNITS says
which), y up as in the mechanism file; nothing is scaled to paper. One DXF layer per kind of
thing, so that a CAD user can switch them on and off:

* ``LINKS`` — each moving link as a polyline: a bar from end to end, a plate as its closed
  convex outline (as the ``mechanism`` drawing layer draws them);
* ``SLIDERS`` — each sliding block (*Gleitstein*, *Kreuzkopf*) as a closed rectangle about its
  pin, its long side along the guide;
* ``GUIDES`` — the guides: a guide on the frame as a line beside the block over the block's
  whole travel, a guide on a moving link as a line along its axis through the block, a slot
  (*Kulisse*) as its closed outline with round ends;
* ``FRAME`` — each fixed pivot's bearing block (*Gestelllager*) and ground line;
* ``HATCHING`` — the frame's hatching (HATCH entities, pattern ANSI31) under the ground lines
  and beyond the guides on the frame;
* ``PROFILES`` — the profiles of higher pairs (cam, roller, flat face, rolling curves) at the
  drawn position, as the ``mechanism`` drawing layer draws them;
* ``JOINTS`` — a circle at every hinge (revolute pair, pin of a slot);
* ``POINTS`` — the mechanism's points as DXF points, named by ``LABELS`` (text);
* ``PATHS`` — the path of every moving point over the whole motion as a polyline through the
  solver's positions (one polyline per reachable stretch: unreachable samples are gaps, not
  joined over).

The symbols are the drawing's (`layers.draw_mechanism`, read from its primitives, so that the
DXF shows what the SVG shows), at the size the drawing gives them on paper with the joint
circle's radius, 2 % of the mechanism's size, as the symbol millimetre.
"""

from __future__ import annotations

from pathlib import Path
from typing import Iterable

import numpy as np

from ..errors import InputError
from . import symbols as sym
from .layers import Scene

#: the drawing layers a DXF holds
DXF_LAYERS = ("mechanism", "paths")
#: $INSUNITS codes of the DXF reference for the length units the files use
_INSUNITS = {"in": 1, "inch": 1, "ft": 2, "foot": 2, "mm": 4, "millimeter": 4, "cm": 5,
             "centimeter": 5, "m": 6, "meter": 6, "km": 7, "um": 13, "µm": 13, "micrometer": 13,
             "dm": 14}
#: colour (AutoCAD colour index) of each DXF layer
_COLOURS = {"LINKS": 7, "SLIDERS": 7, "GUIDES": 7, "FRAME": 7, "HATCHING": 8, "PROFILES": 7,
            "JOINTS": 1, "POINTS": 7, "LABELS": 8, "PATHS": 5}
#: the line spacing of the ANSI31 hatch pattern at scale 1, in drawing units (1/8 in)
_ANSI31_SPACING = 3.175


def finite_runs(xy: np.ndarray) -> list[np.ndarray]:
    """The stretches of consecutive finite rows of `xy` (N, 2) with at least two rows each."""
    ok = np.isfinite(xy).all(axis=1)
    edges = np.flatnonzero(np.diff(np.r_[0, ok.astype(np.int8), 0]))
    return [xy[a:b] for a, b in zip(edges[::2], edges[1::2]) if b - a >= 2]


def scene_dxf(sc: Scene, show: Iterable[str] = ("mechanism",)):
    """An ezdxf document of the scene's layers `show` (a subset of DXF_LAYERS)."""
    import ezdxf

    show = list(show)
    other = [s for s in show if s not in DXF_LAYERS]
    if other:
        raise InputError(f"layer(s) {', '.join(other)} are not written to DXF; a DXF holds the "
                         f"layers {', '.join(DXF_LAYERS)}")
    mech = sc.mech
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = _INSUNITS.get(mech.length_unit, 0)
    for name, colour in _COLOURS.items():
        doc.layers.add(name, color=colour)
    doc.appids.new("LINKWORK")  # the point a path belongs to, in the path's extended data
    msp = doc.modelspace()
    if "mechanism" in show:
        P = {p: sc.pos(p) for p in mech.points}
        r = 0.02 * mech.length_scale
        _symbols(msp, sc, r / sym.JOINT_R)
        if any(j.kind in ("cam", "rolling") for j in mech.joints):
            from .higher_layers import outlines
            for _, xy, closed in outlines(sc):
                for run in finite_runs(np.asarray(xy, float)):
                    msp.add_lwpolyline([tuple(map(float, v)) for v in run], close=closed,
                                       dxfattribs={"layer": "PROFILES"})
        for p in dict.fromkeys(j.point for j in mech.joints if getattr(j, "point", None)):
            if np.isfinite(P[p]).all():
                msp.add_circle(tuple(map(float, P[p])), r, dxfattribs={"layer": "JOINTS"})
        for p, xy in P.items():
            if np.isfinite(xy).all():
                at = tuple(map(float, xy))
                msp.add_point(at, dxfattribs={"layer": "POINTS"})
                msp.add_text(p, height=1.5 * r, dxfattribs={"layer": "LABELS", "insert": at})
    if "paths" in show:
        if sc.motion is None:
            raise InputError(f"paths: the whole motion of '{mech.name}' could not be computed")
        for p in sc.moving_points:
            for run in finite_runs(sc.motion.point(p).position):
                msp.add_lwpolyline([tuple(map(float, v)) for v in run],
                                   dxfattribs={"layer": "PATHS"}).set_xdata(
                    "LINKWORK", [(1000, f"path {p}")])
    return doc


def _xy(v) -> tuple[float, float]:
    return float(v[0]), float(v[1])


def _hatched(msp, corners: np.ndarray, unit: float) -> None:
    """A HATCH (ANSI31, 45°, about the drawing's hatch spacing) filling the strip `corners`."""
    h = msp.add_hatch(dxfattribs={"layer": "HATCHING"})
    h.set_pattern_fill("ANSI31", scale=sym.HATCH_STEP * unit / _ANSI31_SPACING)
    h.paths.add_polyline_path([_xy(v) for v in corners], is_closed=True)


def _symbols(msp, sc: Scene, unit: float) -> None:
    """Links, blocks, guides, slots and the frame's bearings as the mechanism drawing places
    them (its primitives, in world coordinates), `unit` world length per symbol millimetre."""
    from .layers import draw_mechanism
    from .svg import Figure

    fig = Figure(sc.scales or sc.auto_scales())
    draw_mechanism(fig, sc, labels=False)
    for prim in fig.prims:
        d = prim.data
        if prim.kind == "line":  # a guide on a moving link, along its axis through the block
            u = d["direction"] / np.linalg.norm(d["direction"])
            t = [float((q - d["point"]) @ u) for q in d["span"]]
            msp.add_line(_xy(d["point"] + min(t) * u), _xy(d["point"] + max(t) * u),
                         dxfattribs={"layer": "GUIDES"})
            continue
        if prim.kind != "symbol":
            continue
        name, a = d["name"], d["args"]
        if name == "bar":
            msp.add_lwpolyline([_xy(a["at"]), _xy(a["to"])], dxfattribs={"layer": "LINKS"})
        elif name == "plate":
            msp.add_lwpolyline([_xy(v) for v in a["points"]], close=True,
                               dxfattribs={"layer": "LINKS"})
        elif name == "block":
            msp.add_lwpolyline([_xy(v) for v in sym.block_corners(a["at"], a["axis"], unit)],
                               close=True, dxfattribs={"layer": "SLIDERS"})
        elif name == "guide":  # on the frame: a line beside the block, hatched beyond it
            side = np.asarray(a["side"], float)
            p, q = a["start"] + side * sym.GUIDE_OFFSET * unit, a["end"] + side * sym.GUIDE_OFFSET * unit
            msp.add_line(_xy(p), _xy(q), dxfattribs={"layer": "GUIDES"})
            deep = side * sym.GUIDE_DEPTH * unit
            _hatched(msp, np.array([p, q, q + deep, p + deep]), unit)
        elif name == "slot":  # two sides joined by half circles (bulge 1)
            p, q = np.asarray(a["start"], float), np.asarray(a["end"], float)
            u = (q - p) / (np.linalg.norm(q - p) or 1.0)
            n = np.array([-u[1], u[0]]) * sym.SLOT_W * unit / 2
            msp.add_lwpolyline([(*_xy(p - n), 0.0), (*_xy(q - n), 1.0), (*_xy(q + n), 0.0),
                                (*_xy(p + n), 1.0)], format="xyb", close=True,
                               dxfattribs={"layer": "GUIDES"})
        elif name == "fixed-pivot":
            down = np.asarray(a.get("down", (0.0, -1.0)), float)
            tri, g0, g1 = sym.bearing(a["at"], down, unit)
            msp.add_lwpolyline([_xy(v) for v in tri], close=True, dxfattribs={"layer": "FRAME"})
            msp.add_line(_xy(g0), _xy(g1), dxfattribs={"layer": "FRAME"})
            deep = down / np.linalg.norm(down) * sym.GROUND_DEPTH * unit
            _hatched(msp, np.array([g0, g1, g1 + deep, g0 + deep]), unit)


def write_dxf(sc: Scene, path: Path, show: Iterable[str] = ("mechanism",)) -> None:
    """Write the scene's layers `show` as the DXF file `path`."""
    doc = scene_dxf(sc, show)
    try:
        doc.saveas(path)
    except OSError as exc:
        raise InputError(f"cannot write {path}: {exc.strerror or exc}") from None
