"""DXF of the mechanism drawing and of point paths (*Bahnkurven*), for CAD users.

Coordinates are the mechanism's own, in the file's length unit (the DXF header's $INSUNITS says
which), y up as in the mechanism file; nothing is scaled to paper. One DXF layer per kind of
thing, so that a CAD user can switch them on and off:

* ``LINKS`` — each moving link as a polyline: a bar from end to end, a plate as its closed
  convex outline (as the ``mechanism`` drawing layer draws them);
* ``PROFILES`` — the profiles of higher pairs (cam, roller, flat face, rolling curves) at the
  drawn position, as the ``mechanism`` drawing layer draws them;
* ``JOINTS`` — a circle at every hinge (revolute pair, pin of a slot);
* ``POINTS`` — the mechanism's points as DXF points, named by ``LABELS`` (text);
* ``PATHS`` — the path of every moving point over the whole motion as a polyline through the
  solver's positions (one polyline per reachable stretch: unreachable samples are gaps, not
  joined over).
"""

from __future__ import annotations

from pathlib import Path
from typing import Iterable

import numpy as np

from ..errors import InputError
from .layers import Scene, _hull

#: the drawing layers a DXF holds
DXF_LAYERS = ("mechanism", "paths")
#: $INSUNITS codes of the DXF reference for the length units the files use
_INSUNITS = {"in": 1, "inch": 1, "ft": 2, "foot": 2, "mm": 4, "millimeter": 4, "cm": 5,
             "centimeter": 5, "m": 6, "meter": 6, "km": 7, "um": 13, "µm": 13, "micrometer": 13,
             "dm": 14}
#: colour (AutoCAD colour index) of each DXF layer
_COLOURS = {"LINKS": 7, "PROFILES": 7, "JOINTS": 1, "POINTS": 7, "LABELS": 8, "PATHS": 5}


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
        for link in mech.links:
            if link.name == mech.frame:
                continue
            xy = np.array([P[p] for p in dict.fromkeys(link.points)])
            if len(xy) < 2 or not np.isfinite(xy).all():
                continue
            hull = _hull(xy)
            msp.add_lwpolyline([tuple(map(float, xy[k])) for k in hull], close=len(hull) >= 3,
                               dxfattribs={"layer": "LINKS"})
        if any(j.kind in ("cam", "rolling") for j in mech.joints):
            from .higher_layers import outlines
            for _, xy, closed in outlines(sc):
                for run in finite_runs(np.asarray(xy, float)):
                    msp.add_lwpolyline([tuple(map(float, v)) for v in run], close=closed,
                                       dxfattribs={"layer": "PROFILES"})
        r = 0.02 * mech.length_scale
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


def write_dxf(sc: Scene, path: Path, show: Iterable[str] = ("mechanism",)) -> None:
    """Write the scene's layers `show` as the DXF file `path`."""
    doc = scene_dxf(sc, show)
    try:
        doc.saveas(path)
    except OSError as exc:
        raise InputError(f"cannot write {path}: {exc.strerror or exc}") from None
