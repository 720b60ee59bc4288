"""The layers of instantaneous geometry, drawn from :mod:`linkwork.instant`.

Owns :func:`draw_instant`: ``poles`` (all relative poles P_ij, numbered as the books number the
links), ``pole-lines`` (the Aronhold–Kennedy lines of the pole schedule), ``centrodes`` (fixed
and moving centrode of each moving link over the whole motion: *Rastpolbahn*, *Gangpolbahn*,
the moving one carried to the drawn position), ``inflection`` (*Wendekreis* with W₀ and the pole
tangent and normal), ``return`` (*Rückkehrkreis*), ``bresse`` (Bresse circle) and ``gamma``
(acceleration centre Γ). The curvature layers are drawn for the links whose motion is not a pure
rotation about a frame pivot (for those the circles collapse onto the pivot); points at infinity
are listed in the legend instead of being drawn.
"""

from __future__ import annotations

from dataclasses import fields
from functools import lru_cache

import numpy as np

from ..constructions.construction import literal
from ..geometry import Circle
from ..instant import (bresse_circle, centrodes, inflection_circle, instant, pole_schedule, poles,
                       return_circle)
from ..model import Revolute
from .svg import COLOURS, DASHES, Figure, Style


def curvature_links(sc) -> list[str]:
    """Moving links not turning about a frame pivot (their circles are worth drawing)."""
    mech = sc.mech
    pivoted = {(set(j.links) - {mech.frame}).pop() for j in mech.joints
               if isinstance(j, Revolute) and mech.frame in j.links}
    return [ln for ln in mech.moving_links if ln not in pivoted]


def _label(t: str) -> str:
    return "P_{" + t[1:] + "}" if t.startswith("P") else t


def _inside(fig: Figure, xy: np.ndarray) -> np.ndarray:
    """Which of the world points ``xy`` lie inside the mechanism panel's clip box (all when the
    figure is not clipped), a little in from its edges so that a label there stays on the sheet."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    ok = np.all(np.isfinite(xy), axis=1)
    if "mechanism" not in fig.clip:
        return ok
    lo, hi = (np.asarray(v, float) for v in fig.clip["mechanism"])
    pad = 0.06 * (hi - lo)
    return ok & np.all((xy >= lo + pad) & (xy <= hi - pad), axis=1)


def _label_on_curve(fig: Figure, xy: np.ndarray, text: str, colour: str, at: float = 0.3) -> bool:
    """Label a curve where it is: at the drawn point of ``xy`` nearest the fraction ``at`` of its
    length that lies inside the frame; False if none does."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    ok = np.flatnonzero(_inside(fig, xy))
    if not len(ok):
        if "inset" in fig.spaces:  # off the frame: labelled where it is drawn whole, in the inset
            ok = np.flatnonzero(np.all(np.isfinite(xy), axis=1))
            if len(ok):
                k = ok[np.argmin(abs(ok - at * (len(xy) - 1)))]
                fig.label(xy[k], text, space="inset", colour=colour, size=2.6, italic=False)
                return True
        return False
    k = ok[np.argmin(abs(ok - at * (len(xy) - 1)))]
    fig.label(xy[k], text, colour=colour, size=2.8, italic=False)
    return True


def _towards(fig: Figure, centre: np.ndarray, text: str, colour: str, layer: str) -> None:
    """An arrow at the frame's edge pointing to a centre off the sheet, labelled with it (with an
    inset the centre is drawn there instead, marked and labelled)."""
    if "mechanism" not in fig.clip or _inside(fig, centre)[0]:
        return
    if "inset" in fig.spaces:
        fig.dot(centre, space="inset", r=0.5, style=Style(stroke=colour), layer="inset")
        fig.label(centre, text, space="inset", colour=colour, size=2.6, italic=False)
        return
    lo, hi = (np.asarray(v, float) for v in fig.clip["mechanism"])
    mid = (lo + hi) / 2
    d = centre - mid
    # where the ray from the box's middle to the centre leaves the box (a little inside it)
    t = min(abs((hi - mid)[k] / d[k]) if d[k] else np.inf for k in range(2)) * 0.92
    head = mid + t * d
    u = d / np.linalg.norm(d)
    tail = head - 9.0 * fig.spaces["mechanism"].per_mm * u
    fig.arrow(tail, head, style=Style(stroke=colour, width=0.3), layer=layer)
    fig.label(tail, text, colour=colour, size=2.6, italic=False, prefer=np.array([-u[0], u[1]]))


def _circle(fig: Figure, c: Circle, i: int, layer: str, kind: str, label: str, span) -> None:
    c = c[i]
    st = Style(stroke=COLOURS[kind], width=0.35, dash=DASHES.get(kind))
    if bool(c.is_line):
        line = c.tangent_line
        a, b, k = line.coords
        o = np.array([-a * k, -b * k]) / (a * a + b * b)
        fig.line(o, np.array([b, -a]), span, style=st, layer=layer, ident=f"{layer}-line")
        fig.note(f"{label} is a straight line at this position")
        return
    ctr, r = c.centre.xy, float(c.radius)
    if not (np.all(np.isfinite(ctr)) and np.isfinite(r)):
        return
    fig.circle(ctr, r, style=st, layer=layer, ident=f"{layer}-circle")
    t = np.linspace(0.0, 2 * np.pi, 145)[:-1]
    on = ctr + r * np.stack([np.cos(t), np.sin(t)], -1)
    if not _label_on_curve(fig, on, label, COLOURS[kind], at=0.6 / (2 * np.pi)):
        fig.note(f"{label}: centre ({ctr[0]:.4g}, {ctr[1]:.4g}), radius {r:.4g}; off the frame")
    _towards(fig, ctr, f"centre of the {label}", COLOURS[kind], layer)


def _pole_line(fig: Figure, sc, o: np.ndarray, d: np.ndarray, span: list, ends: list) -> None:
    """An Aronhold–Kennedy line drawn thin past the poles in ``span``. Where it runs along a bar
    of the mechanism (its two poles are both points of one link) only its parts beyond the bar
    are drawn, so that the bar keeps a single outline."""
    style = Style(stroke="#888", width=0.18)
    mech = sc.mech
    along = None
    if len(ends) == 2:
        for ln in mech.moving_links:
            pts = [sc.pos(x) for x in mech.link(ln).points]
            tol = 1e-9 * mech.length_scale
            if all(any(np.all(np.abs(e - q) <= tol) for q in pts) for e in ends):
                along = ends
                break
    if along is None:
        fig.line(o, d, span, style=style, layer="pole-lines")
        return
    u = d / np.linalg.norm(d)
    t = np.array([np.dot(x - o, u) for x in span])
    ta, tb = sorted(float(np.dot(x - o, u)) for x in along)
    over = 4.0 * fig.spaces["mechanism"].per_mm
    lo, hi = t.min() - over, t.max() + over
    for a, b in ((lo, ta), (tb, hi)):
        if b - a > 1e-9 * mech.length_scale:
            fig.path(np.array([o + a * u, o + b * u]), style=style, layer="pole-lines")


class _Structure:
    """A mechanism as a cache key: equal to another when their links and pairs are, every
    field of every pair by value (their coordinates aside, which a drag changes)."""

    def __init__(self, mech) -> None:
        self.mech = mech
        self.key = (mech.frame, mech.links, tuple(
            (type(j).__name__,) + tuple(_value(getattr(j, f.name)) for f in fields(j))
            for j in mech.joints))

    def __hash__(self) -> int:
        return hash(self.key)

    def __eq__(self, other) -> bool:
        return isinstance(other, _Structure) and self.key == other.key


def _value(v):
    """A pair's field as a hashable value (axes are arrays)."""
    if isinstance(v, np.ndarray):
        return v.shape, tuple(v.ravel().tolist())
    if isinstance(v, (list, tuple)):
        return tuple(_value(x) for x in v)
    return v


@lru_cache(maxsize=32)
def _schedule(structure: _Structure):
    return pole_schedule(structure.mech)


def schedule_of(mech):
    """`instant.pole_schedule(mech)` (the topology alone: the same for every frame of a drag,
    which moves points only), computed once for each structure."""
    try:
        return _schedule(_Structure(mech))
    except TypeError:  # a pair with a field that is no value (unhashable): not cached
        return pole_schedule(mech)


def draw_instant(fig: Figure, sc, layer: str) -> None:
    sol, i, mech = sc.sol, sc.index, sc.mech
    if layer in ("poles", "pole-lines"):
        ps = sc.shared(("poles",), lambda: poles(sol))
        if layer == "poles":
            fig.note("poles: " + ", ".join(f"{k + 1} = {literal(ln)}" for k, ln in enumerate(ps.links)))
        if layer == "pole-lines":
            sch = schedule_of(mech)
            for st in sch.derived:
                for src in st.lines[:2]:
                    if src.poles is None:
                        continue
                    p, q = (ps[x].coords[i] for x in src.poles)
                    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(q))):
                        continue
                    ln = np.cross(p, q)
                    a, b, k = ln
                    if a == 0 and b == 0:
                        continue
                    o = np.array([-a * k, -b * k]) / (a * a + b * b)
                    # the line reaches the pole it is drawn for, however far it lies
                    R = ps[st.pair].coords[i]
                    span = [x[:2] / x[2] for x in (p, q, R) if x[2] != 0 and np.all(np.isfinite(x))]
                    _pole_line(fig, sc, o, np.array([b, -a]), span, [x[:2] / x[2] for x in (p, q) if x[2] != 0])
        if layer == "pole-lines":
            return
        for pair in ps:
            P = ps[pair][i]
            lab = _label(ps.label(*pair))
            if P.is_finite:
                fig.dot(P.xy, r=0.6, style=Style(stroke="#000"), layer="poles", ident=f"pole-{ps.label(*pair)}")
                fig.label(P.xy, lab, size=2.8, ident=f"pole-{ps.label(*pair)}")
            elif P.is_infinite:
                d = P.direction.xy
                fig.note(f"{lab} at infinity (direction {np.degrees(np.arctan2(d[1], d[0])) % 180:.1f}\u00b0)")
        return
    links = curvature_links(sc)
    ext = sc.extent()
    for ln in links:
        ins = sc.shared(("instant", ln), lambda: instant(sol, ln))
        P = ins.pole[i]
        if not P.is_finite:
            fig.note(f"{literal(ln)}: translating instantaneously (pole at infinity), no {layer} drawn")
            continue
        span = [P.xy - ext * 0.3 * np.array([1, 0]), P.xy + ext * 0.3 * np.array([1, 0])]
        if layer == "centrodes":
            if sc.motion is None:
                continue
            from ..kinematics import solve
            # the centrodes depend on the whole motion alone: once per motion, not per position
            full = sc.of_motion(("centrode-motion",), lambda: solve(
                mech, sc.motion.inputs, velocities=sc.motion.link(mech.drivers[0].driven).omega
                if len(mech.drivers) == 1 else None))
            cen = sc.of_motion(("centrodes", ln), lambda: centrodes(full, ln, curvature=False))
            fig.path(cen.fixed_xy, style=Style(stroke=COLOURS["centrode"], width=0.35), layer="centrodes",
                     ident=f"centrode-fixed-{ln}")
            _label_on_curve(fig, cen.fixed_xy, f"fixed centrode ({literal(ln)})", COLOURS["centrode"], 0.25)
            # the moving centrode, carried into the drawn position of the link
            th = float(sol.pose_derivatives(ln)[0, i, 2])
            x0 = sol.pose_derivatives(ln)[0, i, :2]
            m = cen.moving_xy
            R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
            moving = m @ R.T + x0
            fig.path(moving, style=Style(stroke=COLOURS["centrode"], width=0.35, dash=DASHES["moving-centrode"]),
                     layer="centrodes", ident=f"centrode-moving-{ln}")
            _label_on_curve(fig, moving, f"moving centrode ({literal(ln)})", COLOURS["centrode"], 0.75)
            fig.note(f"centrodes of {literal(ln)}: fixed solid, moving dashed")
        elif layer == "inflection":
            _circle(fig, inflection_circle(sol, ln), i, "inflection", "inflection", f"inflection circle ({literal(ln)})", span)
            W = ins.inflection_pole[i]
            if W.is_finite:
                fig.dot(W.xy, r=0.6, style=Style(stroke=COLOURS["inflection"]), layer="inflection")
                fig.label(W.xy, "W_0", colour=COLOURS["inflection"], size=3.0)
                fig.line(P.xy, W.xy - P.xy, [P.xy, W.xy], style=Style(stroke="#555", width=0.18),
                         layer="inflection", ident=f"pole-normal-{ln}")
            t = ins.pole_tangent.xy[i]
            if np.all(np.isfinite(t)):
                fig.line(P.xy, t, [P.xy - 0.2 * ext * t, P.xy + 0.2 * ext * t],
                         style=Style(stroke="#555", width=0.18), layer="inflection", ident=f"pole-tangent-{ln}")
            fig.dot(P.xy, r=0.6, layer="inflection")
            fig.label(P.xy, "P", size=3.0)
        elif layer == "return":
            _circle(fig, return_circle(sol, ln), i, "return", "return", f"return circle ({literal(ln)})", span)
        elif layer == "bresse":
            _circle(fig, bresse_circle(sol, ln), i, "bresse", "bresse", f"Bresse circle ({literal(ln)})", span)
        elif layer == "gamma":
            G = ins.acceleration_pole[i]
            if G.is_finite:
                fig.dot(G.xy, r=0.7, style=Style(stroke=COLOURS["gamma"]), layer="gamma", ident=f"gamma-{ln}")
                fig.label(G.xy, "\u0393", colour=COLOURS["gamma"], size=3.2)
                _towards(fig, G.xy, f"\u0393 ({literal(ln)})", COLOURS["gamma"], "gamma")
