"""Drawing layers (*Zeichenebenen*) that can be switched on and off, and the scene they draw.

Owns :data:`LAYERS` (the names the command line accepts), :class:`Scene` (a mechanism solved at
the drawn position, its whole motion for the paths, the scales) and one function per layer that
adds its primitives to a :class:`~.svg.Figure`:

* ``mechanism`` — links, hinges, frame bearings, sliders and slots in ISO 3952 symbols, labelled;
* ``paths`` — point paths over the whole motion (*Bahnkurven*), coupler curves included;
* ``velocities`` / ``accelerations`` — the vectors at the points, at the velocity/acceleration
  scale;
* ``poles``, ``pole-lines``, ``centrodes``, ``inflection``, ``return``, ``bresse``, ``gamma`` — the
  instantaneous geometry of :mod:`linkwork.instant` (poles and Aronhold–Kennedy lines, fixed and
  moving centrodes, inflection circle *Wendekreis*, return circle *Rückkehrkreis*, Bresse circle,
  acceleration centre Γ);
* ``contact``, ``equivalent`` — the contact point and common normal of higher pairs, and their
  equivalent linkage (dashed), from :mod:`.higher_layers` (which also draws the profiles of
  higher pairs in the ``mechanism`` layer);
* ``construction`` — the elements of a :class:`~.construction.Construction`, step by step.

:func:`scene_figure` assembles a figure from a list of layer names.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Iterable, Sequence

import numpy as np

from ..errors import InputError, LinkworkError
from ..geometry import Circle, Line, Point
from ..kinematics import Solution, solve, whole_motion
from ..kinematics.at import require_assembled
from ..model import (CircularSlot, Gear, Mechanism, Prismatic, Revolute, Slot, indexing_schedule,
                     is_intermittent)
from ..constructions.construction import Arrow, Construction, Element, Polygon, Segment, literal
from ..constructions.scales import SHEET_MM, Scale, Scales, nice_ceil
from .svg import _COMPASS, COLOURS, Figure, Style, style_for

MECHANISM_LAYERS = ("mechanism", "paths", "velocities", "accelerations")
INSTANT_LAYERS = ("poles", "pole-lines", "centrodes", "inflection", "return", "bresse", "gamma")
HIGHER_LAYERS = ("contact", "equivalent")  # drawing.higher_layers
LAYERS = MECHANISM_LAYERS + INSTANT_LAYERS + HIGHER_LAYERS + ("construction",)


def _rot(theta: float, v: np.ndarray) -> np.ndarray:
    c, s = np.cos(theta), np.sin(theta)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


@dataclass

class Scene:
    """What the layers draw: ``mech`` solved at one input (``sol`` has one sample), the drawing
    ``scales`` and, lazily, the whole motion for point paths and guide lengths."""

    mech: Mechanism
    sol: Solution
    scales: Scales | None = None
    index: int = 0
    #: the motions of the named points asked for so far (the layers, the scales and the box ask
    #: for the same points again and again)
    _points: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    #: what several layers compute from the solution, computed once (see `shared`)
    _shared: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    #: what depends on the whole motion only, not on the position drawn (`of_motion`), kept by
    #: a caller that draws many positions of one motion (the workbench's frames); None: per scene
    motion_kept: dict | None = field(default=None, repr=False, compare=False)

    @cached_property
    def motion(self) -> Solution | None:
        try:
            return whole_motion(self.mech, order=1)
        except LinkworkError:
            return None

    def _point(self, name: str):
        m = self._points.get(name)
        if m is None:
            m = self._points[name] = self.sol.point(name)
        return m

    def shared(self, key: tuple, make):
        """``make()``, computed once for this scene under ``key``: what several layers draw from
        the same solution (its poles, a link's instantaneous invariants)."""
        if key not in self._shared:
            self._shared[key] = make()
        return self._shared[key]

    def of_motion(self, key: tuple, make):
        """``make()`` of what depends only on ``motion``, computed once: in ``motion_kept`` when
        the caller keeps it with the motion, else for this scene (`shared`)."""
        if self.motion_kept is None:
            return self.shared(key, make)
        if key not in self.motion_kept:
            self.motion_kept[key] = make()
        return self.motion_kept[key]

    def pos(self, name: str) -> np.ndarray:
        return self._point(name).position[self.index]

    def vel(self, name: str) -> np.ndarray:
        return self._point(name).velocity[self.index]

    def acc(self, name: str) -> np.ndarray:
        return self._point(name).acceleration[self.index]

    def theta(self, link: str) -> float:
        """Rotation of ``link`` from its design position."""
        return float(self.sol.pose_derivatives(link)[0, self.index, 2])

    @property
    def moving_points(self) -> list[str]:
        mech = self.mech
        return [p for p in mech.points if mech.point_owner[p] != mech.frame]

    def box(self, grow: float = 0.6) -> tuple[np.ndarray, np.ndarray]:
        """World box around the mechanism, its paths and its higher pairs' profiles, grown by
        ``grow`` times its size."""
        pts = self._drawn_points(5)
        lo, hi = pts.min(0), pts.max(0)
        g = grow * max(float(np.max(hi - lo)), self.mech.length_scale * 0.2)
        return lo - g, hi + g

    def _drawn_points(self, step: int) -> np.ndarray:
        """The finite ones (M, 2) of the points at the drawn position, its profiles' points and
        every ``step``-th sample of the moving points' paths (those once per motion: `of_motion`)."""
        here = [self.pos(p) for p in self.mech.points] + self.profile_points()
        parts = [np.reshape(np.array(here, float), (-1, 2))]
        if self.motion is not None:
            parts.append(self.of_motion(("path points", step), lambda: np.concatenate(
                [self.motion.point(p).position[::step] for p in self.moving_points]
                or [np.empty((0, 2))])))
        pts = np.concatenate(parts)
        return pts[np.isfinite(pts).all(axis=1)]

    def profile_points(self) -> list[np.ndarray]:
        """Points of the higher pairs' profiles at the drawn position (every tenth), and the
        compass points of each Geneva or star wheel's rim (the wheel turns within it)."""
        out: list[np.ndarray] = []
        for j in self.mech.joints:
            if is_intermittent(j):
                sch = indexing_schedule(self.mech, j)
                C = self.sol.point_on(j.carrier, sch.C).position[self.index]
                R = max(o for _, _, o in sch.slot_lines())
                out += list(C + R * _COMPASS)
        if not any(j.kind in ("cam", "rolling") for j in self.mech.joints):
            return out
        from .higher_layers import outlines
        return out + [p for _, xy, _ in outlines(self) for p in xy[::10]]

    def extent(self) -> float:
        """Size of the drawing (mechanism, paths, profiles) in mechanism units."""
        pts = self._drawn_points(10)
        return float(np.max(np.ptp(pts, axis=0))) if len(pts) > 1 else self.mech.length_scale

    def auto_scales(self, *, length: float | None = None, velocity: float | None = None,
                    acceleration: float | None = None, paper_mm: float | None = None,
                    plan_mm: float | None = None) -> Scales:
        """Scales fitting the mechanism on the sheet, vectors about a third of the drawing; with
        ``plan_mm`` the velocity and acceleration scales fit plans of that size instead."""
        paper = paper_mm or (0.45 if plan_mm else 0.62) * SHEET_MM[0]
        ext = self.extent()
        pts = self.moving_points
        vmax = max((float(np.linalg.norm(self.vel(p))) for p in pts), default=1.0)
        amax = max((float(np.nan_to_num(np.linalg.norm(self.acc(p)))) for p in pts), default=1.0) \
            if self.sol.order >= 2 else 1.0  # a solve of velocities only (given point velocities)
        ls = length or nice_ceil(ext / paper)
        vec_mm = plan_mm or 0.3 * ext / ls
        return Scales.auto(self.mech.length_unit, ext, vmax=vmax or 1.0, amax=amax or 1.0,
                           paper_mm=paper, vector_mm=vec_mm, length=ls, velocity=velocity,
                           acceleration=acceleration)


def scene_at(mech: Mechanism, value: float, *, kind: str = "input") -> Scene:
    """Solve ``mech`` at one input value (or time) and wrap it as a scene."""
    sol = solve(mech, times=[value]) if kind == "time" else solve(mech, np.array([value]))
    require_assembled(sol)
    return Scene(mech, sol)


# ---------------------------------------------------------------------------- mechanism
def draw_mechanism(fig: Figure, sc: Scene, *, layer: str = "mechanism", labels: bool = True,
                   labelled: Iterable[str] = ()) -> None:
    """Links, joints and frame in ISO 3952 symbols at the scene's position; ``labelled``: points
    that something else (a construction) already labels."""
    labelled = set(labelled)
    mech = sc.mech
    frame = mech.frame
    P = {p: sc.pos(p) for p in mech.points}
    centroid = np.nanmean(np.array(list(P.values())), axis=0)
    joint_points = {j.point for j in mech.joints if getattr(j, "point", None)}
    ground_points = {j.point for j in mech.joints
                     if isinstance(j, Revolute) and frame in j.links}
    # links: bars and plates
    for link in mech.links:
        if link.name == frame:
            continue
        pts = list(dict.fromkeys(link.points))
        xy = np.array([P[p] for p in pts])
        if len(xy) < 2:
            continue
        hull = _hull(xy)
        ident = f"link-{link.name}"
        if len(hull) >= 3:
            fig.symbol("plate", points=xy[hull], layer=layer, ident=ident)
        else:
            d = xy - xy.mean(0)
            u = d[np.argmax(np.linalg.norm(d, axis=1))]
            t = d @ (u / (np.linalg.norm(u) or 1))
            fig.symbol("bar", at=xy[np.argmin(t)], to=xy[np.argmax(t)], layer=layer, ident=ident)
    # pairs
    for j in mech.joints:
        if isinstance(j, Revolute):
            if frame in j.links:
                fig.symbol("fixed-pivot", at=P[j.point], down=np.array([0.0, -1.0]), layer=layer,
                           ident=f"joint-{j.name}")
            else:
                fig.symbol("revolute", at=P[j.point], layer=layer, ident=f"joint-{j.name}")
        elif isinstance(j, (Prismatic, Slot)):
            _draw_slider(fig, sc, j, layer)
        elif isinstance(j, CircularSlot):
            c = P[j.center]
            r = j.radius(mech)
            fig.circle(c, r, arcs=[P[j.point]], style=Style(width=0.45), layer=layer, ident=f"joint-{j.name}")
            fig.symbol("revolute", at=P[j.point], layer=layer)
        elif isinstance(j, Gear):
            c1 = P[mech.wheel_centre(j, j.links[0])]
            fig.symbol("pitch-circle", at=c1, radius_world=j.radii[0], layer=layer, ident=f"joint-{j.name}")
            if j.gear_kind != "rack":
                c2 = P[mech.wheel_centre(j, j.links[1])]
                fig.symbol("pitch-circle", at=c2, radius_world=j.radii[1], layer=layer)
        elif is_intermittent(j):
            _draw_indexing(fig, sc, j, layer)
    if any(j.kind in ("cam", "rolling") for j in mech.joints):
        from .higher_layers import draw_elements
        draw_elements(fig, sc, layer)
    # tracer points and labels
    for p, xy in P.items():
        if p not in joint_points:
            fig.dot(xy, r=0.6, layer=layer, ident=f"point-{p}")
        if labels and p not in labelled:
            prefer = np.array([1.0, -1.0]) if np.allclose(xy, centroid) else (xy - centroid) * np.array([1, -1])
            if p in ground_points:
                prefer = np.array([1.0, 0.6])
            fig.label(xy, _point_label(p), prefer=prefer, ident=f"point-{p}",
                      clear=1.1 if p in joint_points else 0.3)


def _draw_indexing(fig: Figure, sc: Scene, j, layer: str) -> None:
    """A Geneva or star wheel, simply: its radial slots (from the foot to where the pin meets
    them) turned with the wheel, its rim through the slots' mouths, and the pins."""
    sch = indexing_schedule(sc.mech, j)
    wheel = j.links[1]
    C = sc.sol.point_on(j.carrier, sch.C).position[sc.index]
    th = sc.theta(wheel)
    lines = sch.slot_lines()
    for k, (a, inner, outer) in enumerate(lines):
        e = np.array([np.cos(a + th), np.sin(a + th)])
        fig.symbol("slot", start=C + inner * e, end=C + outer * e, layer=layer,
                   ident=f"joint-{j.name}" if k == 0 else None)
    fig.circle(C, max(o for _, _, o in lines), style=Style(width=0.3), layer=layer)
    from .higher_layers import draw_flanks
    draw_flanks(fig, sc, j, layer)
    for p in sch.pins:
        fig.symbol("revolute", at=sc.pos(p), layer=layer)


def _point_label(name: str) -> str:
    """``O2`` → ``O_2``: trailing digits of a point name become a subscript, as in the books."""
    import re
    m = re.match(r"^([A-Za-z]+)(\d+)$", name)
    return f"{m.group(1)}_{m.group(2)}" if m else literal(name)


def _draw_slider(fig: Figure, sc: Scene, j, layer: str) -> None:
    mech = sc.mech
    guide_link, moving = j.links
    p = sc.pos(j.point)
    axis = _rot(sc.theta(guide_link), np.asarray(j.axis, float))
    axis = axis / np.linalg.norm(axis)
    # travel of the point along the guide over the whole motion
    lo, hi = -0.15 * mech.length_scale, 0.15 * mech.length_scale
    if sc.motion is not None and guide_link == mech.frame:
        path = sc.motion.point(j.point).position
        t = (path - p) @ axis
        t = t[np.isfinite(t)]
        if t.size:
            lo, hi = min(lo, t.min()), max(hi, t.max())
    pad = 0.06 * mech.length_scale
    a, b = p + (lo - pad) * axis, p + (hi + pad) * axis
    # hatching on the side of the frame's pivots (books draw the guide below the crosshead)
    side = np.array([axis[1], -axis[0]])
    pivots = [sc.pos(jj.point) for jj in mech.joints
              if isinstance(jj, Revolute) and mech.frame in jj.links]
    towards = (np.mean(pivots, axis=0) - p) if pivots else np.array([0.0, -1.0])
    s_ = float(np.dot(side, towards))
    if abs(s_) < 1e-9 * mech.length_scale:
        s_ = float(np.dot(side, [0.0, -1.0])) or 1.0
    if s_ < 0:
        side = -side
    if isinstance(j, Prismatic):
        fig.symbol("block", at=p, axis=axis, layer=layer, ident=f"joint-{j.name}")
        if guide_link == mech.frame:
            fig.symbol("guide", start=a, end=b, side=side, layer=layer)
        else:
            fig.line(p, axis, [a, b], style=Style(width=0.5), layer=layer)
    else:
        if guide_link == mech.frame:
            fig.symbol("slot", start=a, end=b, layer=layer, ident=f"joint-{j.name}")
        else:
            fig.symbol("slot", start=p - 0.1 * mech.length_scale * axis, end=p + 0.1 * mech.length_scale * axis,
                       layer=layer, ident=f"joint-{j.name}")
        fig.symbol("revolute", at=p, layer=layer)


def _hull(xy: np.ndarray) -> list[int]:
    """Indices of the convex hull (counter-clockwise); fewer than 3 if the points are collinear."""
    pts = sorted(range(len(xy)), key=lambda k: (xy[k][0], xy[k][1]))
    if len(pts) < 3:
        return pts

    def cross(o, a, b):
        return (xy[a][0] - xy[o][0]) * (xy[b][1] - xy[o][1]) - (xy[a][1] - xy[o][1]) * (xy[b][0] - xy[o][0])
    span = np.ptp(xy, axis=0).max() or 1.0
    lower, upper = [], []
    for k in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], k) <= 1e-9 * span * span:
            lower.pop()
        lower.append(k)
    for k in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], k) <= 1e-9 * span * span:
            upper.pop()
        upper.append(k)
    hull = lower[:-1] + upper[:-1]
    return hull if len(hull) >= 3 else [pts[0], pts[-1]]


# ---------------------------------------------------------------------------- paths, vectors
def draw_paths(fig: Figure, sc: Scene, points: Sequence[str] | None = None) -> None:
    """Point paths over the whole motion (thin grey lines)."""
    if sc.motion is None:
        fig.note("paths: the whole motion could not be computed for this mechanism")
        return
    for p in points or sc.moving_points:
        xy = sc.motion.point(p).position
        fig.path(xy, style=Style(stroke=COLOURS["path"], width=0.2), layer="paths", ident=f"path-{p}")


def draw_vectors(fig: Figure, sc: Scene, which: str, points: Sequence[str] | None = None) -> None:
    """Velocity (``which='velocity'``) or acceleration vectors drawn at the points, to scale."""
    if which != "velocity" and sc.sol.order < 2:
        raise InputError(f"mechanism '{sc.mech.name}': its accelerations are not solved (a chain "
                         "driven by given point velocities needs their accelerations, or the "
                         "curvatures of their paths, for them)")
    scales = sc.scales
    k = scales.kv if which == "velocity" else scales.ka
    fig.used_scales.add(which)
    sym = "v" if which == "velocity" else "a"
    layer = "velocities" if which == "velocity" else "accelerations"
    for p in points or sc.moving_points:
        x = sc.pos(p)
        v = sc.vel(p) if which == "velocity" else sc.acc(p)
        if not np.all(np.isfinite(v)) or np.linalg.norm(v) * k < 1e-9 * sc.mech.length_scale:
            continue
        head = x + k * v
        fig.arrow(x, head, style=Style(stroke=COLOURS[which], width=0.4), layer=layer,
                  ident=f"{which}-{p}")
        fig.label(head, f"{sym}_{{{literal(p)}}}", colour=COLOURS[which],
                  size=3.0, prefer=np.array([v[0], -v[1]]), ident=f"{which}-{p}")


# ---------------------------------------------------------------------------- constructions
def _line_point_dir(line: Line) -> tuple[np.ndarray, np.ndarray]:
    a, b, c = line.coords
    n2 = a * a + b * b
    return np.array([-a * c / n2, -b * c / n2]), np.array([b, -a])


def draw_construction(fig: Figure, con: Construction, *, upto: int | None = None,
                      highlight: int | None = None, layer: str = "construction") -> None:
    """The elements of one sampled construction; ``upto`` limits the steps, ``highlight`` draws
    one step's elements in the highlight colour (step-by-step drawings)."""
    if con.sampled is None and con.n != 1:
        con = con.sample(0)
    last = len(con.steps) - 1 if upto is None else upto
    for k, st in enumerate(con.steps[:last + 1]):
        for key in st.keys:
            el = con.elements[key]
            if el.space not in fig.spaces:
                continue
            _draw_element(fig, el, k, highlight == k, layer)
    fig.captions = [f"{k + 1}. {s.text}" for k, s in enumerate(con.steps)]
    for line in con.legend:
        fig.note(line)
    for m in con.messages(0):
        fig.note(f"Note: {m}")


def _draw_element(fig: Figure, el: Element, step: int, hi: bool, layer: str) -> None:
    role = el.role.value
    st = style_for(role, el.kind)
    if hi:
        st = Style(stroke=COLOURS["highlight"], width=max(st.width, 0.45), dash=st.dash)
    obj = el.obj
    ident = f"el-{el.key}"
    colour = st.stroke if role != "auxiliary" or hi else "#333"
    kw = dict(space=el.space, style=st, layer=layer, ident=ident, step=step, cls=f"{role} {el.kind}".strip())
    if isinstance(obj, Point):
        if obj.is_infinite:
            if el.label:
                d = obj.direction.xy
                fig.note(f"{el.label} lies at infinity (direction {np.degrees(np.arctan2(d[1], d[0])) % 180:.2f}°)")
            return
        xy = obj.xy
        if not np.all(np.isfinite(xy)):
            return
        fig.dot(xy, r=0.5 if role == "auxiliary" else 0.65, filled=role != "auxiliary", **kw)
        if el.label:
            fig.label(xy, el.label, space=el.space, colour=colour, step=step, ident=ident)
    elif isinstance(obj, Line):
        if obj.is_at_infinity or not np.all(np.isfinite(obj.coords)):
            return
        o, d = _line_point_dir(obj)
        span = [p.xy for p in el.span if p.is_finite]
        fig.line(o, d, span or [o], **kw)
        if el.label and span:
            u = d / np.linalg.norm(d)
            t = [np.dot(s - o, u) for s in span]
            end = o + (max(t) + 3.0 * fig.spaces[el.space].per_mm) * u
            fig.label(end, el.label, space=el.space, colour=colour, step=step, size=3.0)
    elif isinstance(obj, Segment):
        a, b = obj.start.xy, obj.end.xy
        fig.path(np.array([a, b]), **kw)
        if el.label:
            fig.label((a + b) / 2, el.label, space=el.space, colour=colour, step=step, size=3.0)
    elif isinstance(obj, Arrow):
        a, b = obj.tail.xy, obj.head.xy
        fig.arrow(a, b, **kw)
        if el.space == "mechanism" and el.kind in ("velocity", "acceleration") and fig.scales_declared:
            fig.used_scales.add(el.kind)
        if el.label:
            d = b - a
            fig.label(a + 0.6 * d, el.label, space=el.space, colour=colour, step=step, size=3.0,
                      prefer=np.array([-d[1], -d[0]]))
    elif isinstance(obj, Circle):
        if obj.is_line:
            line = obj.tangent_line
            o, d = _line_point_dir(line)
            fig.line(o, d, [p.xy for p in el.arcs] or [obj.anchor.xy], **kw)
            return
        c = obj.centre.xy
        r = float(obj.radius)
        fig.circle(c, r, arcs=[p.xy for p in el.arcs if p.is_finite], **kw)
        if el.label:
            ang = np.radians(35.0)
            fig.label(c + r * np.array([np.cos(ang), np.sin(ang)]), el.label, space=el.space,
                      colour=colour, step=step, size=3.0)
    elif isinstance(obj, Polygon):
        xy = np.array([v.xy for v in obj.vertices])
        fig.path(xy, closed=True, **kw)


# ---------------------------------------------------------------------------- the figure
def construction_extent(con: Construction, space: str = "mechanism") -> float:
    """Size of the drawn construction in ``space`` (finite points, circles)."""
    pts = []
    for el in con.elements.values():
        if el.space != space:
            continue
        o = el.obj
        if isinstance(o, Point) and o.is_finite:
            pts.append(o.xy)
        elif isinstance(o, Circle) and not o.is_line and np.isfinite(o.radius):
            c, r = o.centre.xy, float(o.radius)
            if not el.arcs:
                pts += [c + r, c - r]
        elif isinstance(o, (Segment, Arrow)):
            pts += [o.start.xy, o.end.xy] if isinstance(o, Segment) else [o.tail.xy, o.head.xy]
    pts = np.array([p for p in pts if np.all(np.isfinite(p))]).reshape(-1, 2)
    return float(np.max(np.ptp(pts, axis=0))) if len(pts) > 1 else 0.0


def construction_box(con: Construction, space: str = "mechanism"):
    """World box of the finite points of a sampled construction in ``space`` (or None)."""
    pts = []
    for el in con.elements.values():
        if el.space == space and isinstance(el.obj, Point) and el.obj.is_finite:
            pts.append(el.obj.xy)
        elif el.space == space and isinstance(el.obj, Circle) and not el.obj.is_line and not el.arcs:
            c, r = el.obj.centre.xy, float(el.obj.radius)
            if np.all(np.isfinite(c)) and np.isfinite(r):
                pts += [c - r, c + r]
    pts = np.array([p for p in pts if np.all(np.isfinite(p))]).reshape(-1, 2)
    if len(pts) == 0:
        return None
    lo, hi = pts.min(0), pts.max(0)
    g = 0.05 * max(float(np.max(hi - lo)), 1e-12)
    return lo - g, hi + g


def construction_spaces(con: Construction, scales: Scales) -> dict[str, Scale]:
    out = {"mechanism": scales.length}
    for name, q in con.spaces.items():
        if name == "mechanism":
            continue
        s = scales.velocity if q == "velocity" else scales.acceleration
        if s is None:
            raise InputError(f"the construction needs a {q} scale")
        out[name] = s
    return out


def _points_labelled_by(con: Construction, sc: Scene) -> set[str]:
    """The mechanism's points at which the (sampled) construction puts a labelled point."""
    tol = 1e-9 * sc.mech.length_scale
    at = [el.obj.xy for el in con.elements.values()
          if el.space == "mechanism" and el.label and isinstance(el.obj, Point) and el.obj.is_finite]
    return {p for p in sc.mech.points
            if any(np.all(np.abs(np.asarray(q).reshape(2) - sc.pos(p)) <= tol) for q in at)}


#: how a figure is framed: ``mechanism`` keeps the mechanism the subject (layers larger than
#: the sheet are cut at a frame around it, arrows point to centres off the sheet); ``all`` fits
#: everything drawn on the sheet, however small the mechanism becomes
FRAMES = ("mechanism", "all", "inset")

#: the largest size (mm of paper) of the inset that shows a framed drawing whole
INSET_MM = (110.0, 120.0)


def scene_figure(sc: Scene, show: Iterable[str] = ("mechanism",), *,
                 construction: Construction | None = None, step: int | None = None,
                 title: str | None = None, paths: Sequence[str] | None = None,
                 frame: str = "mechanism") -> Figure:
    """A figure of the scene with the named layers (and a construction, up to ``step``);
    ``paths`` names the points whose paths the ``paths`` layer traces (default: every moving
    point); framed as ``frame`` says (:data:`FRAMES`)."""
    if frame not in FRAMES:
        raise InputError(f"unknown frame '{frame}'; the frames are {', '.join(FRAMES)}")
    show = list(show)
    unknown = [s for s in show if s not in LAYERS]
    if unknown:
        raise InputError(f"unknown layer(s) {', '.join(unknown)}; the layers are {', '.join(LAYERS)}")
    if sc.scales is None:
        plans = construction is not None and any(q != "length" for q in construction.spaces.values())
        ext = None
        if construction is not None:
            ext = max(sc.extent(), construction_extent(construction.sample(sc.index)
                                                       if construction.sampled is None else construction))
        sc.scales = sc.auto_scales(plan_mm=70.0 if plans else None,
                                   length=None if ext is None else nice_ceil(ext / (0.45 if plans else 0.9) / SHEET_MM[0]))
    spaces = {"mechanism": sc.scales.length}
    titles = {}
    if construction is not None:
        if construction.scales is not None:
            sc.scales = construction.scales
        spaces = construction_spaces(construction, sc.scales)
        titles = {n: {"velocity": "velocity plan", "acceleration": "acceleration plan"}.get(q, "")
                  for n, q in construction.spaces.items() if n != "mechanism"}
    fig = Figure(sc.scales, title=title or sc.mech.name, spaces=spaces, titles=titles)
    # vectors drawn on the mechanism by a construction are at the construction's own scales
    fig.scales_declared = construction is None or construction.scales is not None
    # the mechanism panel shows the mechanism, its paths and the construction; far-off circles,
    # centrodes and poles are cut at this box
    box = sc.box()
    if construction is not None:
        con = construction.sample(sc.index) if construction.sampled is None else construction
        cb = construction_box(con)
        if cb is not None:
            box = (np.minimum(box[0], cb[0]), np.maximum(box[1], cb[1]))
    if frame in ("mechanism", "inset"):
        fig.clip["mechanism"] = box
        fig.framed.add("mechanism")
    if frame == "inset":
        # its scale is known when everything is drawn (_finish_inset); labels may go there before
        fig.space("inset", sc.scales.length)
    for layer in show:
        if layer == "mechanism":
            # a construction that labels the mechanism's points in its own notation hides the
            # file's point names
            own = construction is not None and construction.own_labels
            draw_mechanism(fig, sc, labelled=_points_labelled_by(con, sc) if own else ())
        elif layer == "paths":
            draw_paths(fig, sc, paths)
        elif layer == "velocities":
            draw_vectors(fig, sc, "velocity")
        elif layer == "accelerations":
            draw_vectors(fig, sc, "acceleration")
        elif layer in INSTANT_LAYERS:
            from .instant_layers import draw_instant
            draw_instant(fig, sc, layer)
        elif layer in HIGHER_LAYERS:
            from .higher_layers import draw_higher
            draw_higher(fig, sc, layer)
    if frame == "inset":
        _finish_inset(fig)
    if construction is not None:
        con = construction.sample(sc.index) if construction.sampled is None else construction
        draw_construction(fig, con, upto=step, highlight=step)
        if step is not None:
            fig.current_step = step
            # every step's panels fitted to the whole construction, so that the mechanism does
            # not move or change its size when paging through the steps
            whole = scene_figure(sc, show, construction=construction, title=title, paths=paths,
                                 frame=frame)
            for name, tf in whole.transforms().items():
                if name not in fig.view:
                    fig.view[name] = (np.array(tf["lo"]), np.array(tf["hi"]))
    return fig


class InsetScale(Scale):
    """The length scale of an inset (its own legend symbol, M_l of the inset)."""

    @property
    def symbol(self) -> str:
        return "M_l (inset)"


def _finish_inset(fig: Figure) -> None:
    """``--frame inset``: the mechanism panel is cut at its frame, and what runs past it is drawn
    whole in a second panel at its own, smaller scale, with the frame marked in it. Without
    anything past the frame there is no inset."""
    main = [p for p in fig.prims if p.space == "mechanism"]
    if not fig._cut("mechanism"):
        del fig.spaces["inset"]
        fig.labels = [lab for lab in fig.labels if lab.space != "inset"]
        fig.prims = [p for p in fig.prims if p.space != "inset"]
        return
    # the inset shows what is bounded whole: the frame, the circles and the centres and poles;
    # lines and curves running off to infinity (a centrode's far branch) are cut at its edge
    lo, hi = (np.asarray(v, float) for v in fig.clip["mechanism"])
    pts = [lo, hi] + [lab.xy for lab in fig.labels if lab.space == "inset"]
    reach = 60.0 * float(np.max(hi - lo))  # a circle larger than this is a straight line here
    for p in fig.prims:
        if p.space in ("mechanism", "inset") and p.kind in ("circle", "dot"):
            q = fig._world_points(p)
            if p.kind == "dot" or p.data["r"] < reach:
                pts.extend(q)
    pts = np.array([q for q in pts if np.all(np.isfinite(q))]).reshape(-1, 2)
    size = pts.max(0) - pts.min(0)
    fig.view["inset"] = (pts.min(0), pts.max(0))
    length = fig.scales.length
    per_mm = nice_ceil(max(size[0] / INSET_MM[0], size[1] / INSET_MM[1], length.per_mm))
    scale = InsetScale(length.quantity, length.unit, per_mm)
    fig.spaces["inset"] = scale
    fig.titles["inset"] = "inset: the whole drawing"
    fig.extra_scales = [*getattr(fig, "extra_scales", []), scale]
    # the mechanism as bars and plates only: joint symbols and hatching at their paper size
    # would bury it at the inset's scale
    inset = [replace(p, space="inset", ident=None, layer="inset") for p in main
             if p.kind != "symbol" or p.data["name"] in ("bar", "plate")]
    frame = np.array([lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]])
    fig.prims += inset
    fig.path(frame, space="inset", closed=True, style=Style(stroke="#000", width=0.3, dash="1.2,0.8"),
             layer="inset", ident="inset-frame")
    fig.label(np.array([lo[0], hi[1]]), "frame", space="inset", size=2.4, italic=False, colour="#333")