"""The drawing of higher pairs (cams, profile contact, rolling profiles).

Owns the elements of higher pairs in the ``mechanism`` layer (`draw_elements`: each profile
carried by its link, turned and moved with the link's pose at the drawn position — the cam
disc's outline, a mate profile, a track — and the follower's element: the roller's circle with
its hinge, the flat face as a line along the contacts' run; a star wheel's tooth flanks,
`draw_flanks`), and two layers of their own:

* ``contact`` — the contact point and the common normal of every higher pair (the relative pole
  of the two links lies on it), with the pressure angle in the legend;
* ``equivalent`` — the equivalent linkage (*Ersatzgetriebe*, Rosenauer §121) dashed: the
  curvature centres C₁, C₂ on the normal, the coupler C₁C₂ (or the slider along a straight
  element) and the bars that join the centres to their links' pivots; for a rolling pair the
  osculating circles that roll as gears on the carrier C₁C₂.

`outlines` gives the world polylines of the elements, so that the scene's box holds them.
"""

from __future__ import annotations

import numpy as np

from ..instant.equivalent import equivalent_linkage
from ..kinematics.contact import is_higher
from ..model import CamContact, Revolute, indexing_schedule
from .svg import Figure, Style

PROFILE_SAMPLES = 720
FLANK_SAMPLES = 48
EQUIVALENT = Style(stroke="#8b1a89", width=0.35, dash="2.5 1.2")
CONTACT = Style(stroke="#b3001b", width=0.25)


def _rot(theta: float, v: np.ndarray) -> np.ndarray:
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def _carry(sc, link: str, xy: np.ndarray) -> np.ndarray:
    """Design coordinates of `link` to the frame at the drawn position."""
    pose = sc.sol.pose_derivatives(link)[0, sc.index]
    return pose[:2] + _rot(float(pose[2]), np.asarray(xy, float))


def _run(sc, j, which: str, at: float) -> tuple[float, float]:
    """The parameters along an element (`which` = 'u' or 'v') that the contact runs over in the
    whole motion, with a margin; around `at` when the whole motion is not known."""
    L = sc.mech.length_scale
    lo, hi = at - 0.25 * L, at + 0.25 * L
    if sc.motion is not None:
        vals = sc.motion.joint(j.name)[which]
        vals = vals[np.isfinite(vals)]
        if vals.size:
            pad = 0.1 * L
            lo, hi = min(lo, float(vals.min()) - pad), max(hi, float(vals.max()) + pad)
    return lo, hi


def _profile_xy(sc, j, name: str, link: str, which: str) -> np.ndarray:
    """World polyline of profile `name` carried by `link`: a closed profile whole, an open one
    over its domain, cut to the contact's run where that is infinite (a line)."""
    prof = sc.mech.profiles[name]
    lo, hi = prof.domain
    if not (np.isfinite(lo) and np.isfinite(hi)):
        at = float(sc.sol.joint(j.name)[which][sc.index])
        run = _run(sc, j, which, at)
        lo, hi = max(lo, run[0]), min(hi, run[1])
    u = np.linspace(lo, hi, PROFILE_SAMPLES, endpoint=not prof.closed)
    br = np.asarray(prof.breaks, float)
    u = np.union1d(u, br[(br >= lo) & (br <= hi)])
    xy = _carry(sc, link, prof.derivatives(u, 0)[0])
    return xy[np.isfinite(xy).all(axis=1)]


def _face_xy(sc, j) -> np.ndarray:
    """The flat face of the follower over the contact's run, in the frame."""
    P = sc.mech.points[j.point]
    e = np.asarray(j.axis, float) / np.hypot(*j.axis)
    lo, hi = _run(sc, j, "v", float(sc.sol.joint(j.name)["v"][sc.index]))
    return _carry(sc, j.links[1], P + np.outer([lo, hi], e))


def outlines(sc) -> list[tuple[str, np.ndarray, bool]]:
    """(ident, world polyline, closed) of every higher pair's elements at the drawn position."""
    out = []
    for j in sc.mech.joints:
        if not is_higher(j):
            continue
        a, b = j.links
        first = j.profile if isinstance(j, CamContact) else j.profiles[0]
        out.append((f"profile-{j.name}-{first}", _profile_xy(sc, j, first, a, "u"),
                    sc.mech.profiles[first].closed))
        follower = j.follower if isinstance(j, CamContact) else "rolling"
        if follower == "roller":
            c = sc.pos(j.point)
            t = np.linspace(0.0, 2 * np.pi, 181)[:-1]
            out.append((f"roller-{j.name}", c + j.radius * np.stack([np.cos(t), np.sin(t)], axis=1), True))
        elif follower == "flat":
            out.append((f"face-{j.name}", _face_xy(sc, j), False))
        elif follower in ("profile", "rolling"):
            mate = j.mate if isinstance(j, CamContact) else j.profiles[1]
            out.append((f"profile-{j.name}-{mate}", _profile_xy(sc, j, mate, b, "v"),
                        sc.mech.profiles[mate].closed))
    return out


def draw_elements(fig: Figure, sc, layer: str = "mechanism") -> None:
    """The profiles and follower elements of the higher pairs (part of the mechanism layer)."""
    for ident, xy, closed in outlines(sc):
        if len(xy) < 2:
            continue
        fig.path(xy, closed=closed, style=Style(width=0.5 if ident.startswith("face") else 0.4),
                 layer=layer, ident=ident)
    for j in sc.mech.joints:
        if isinstance(j, CamContact) and j.follower == "roller":
            fig.symbol("revolute", at=sc.pos(j.point), layer=layer)


def draw_flanks(fig: Figure, sc, j, layer: str = "mechanism") -> None:
    """The tooth flanks of a star wheel (`IndexingSchedule.flanks`: the epicycloid arcs its
    pins drive along), turned and moved with the wheel as its slots are; nothing for a
    Geneva wheel."""
    for k, xy in enumerate(indexing_schedule(sc.mech, j).flanks(FLANK_SAMPLES)):
        fig.path(_carry(sc, j.links[1], xy), style=Style(width=0.4), layer=layer,
                 ident=f"flank-{j.name}-{k}")


def draw_higher(fig: Figure, sc, layer: str) -> None:
    """The ``contact`` or ``equivalent`` layer."""
    pairs = [j for j in sc.mech.joints if is_higher(j)]
    if not pairs:
        fig.note(f"{layer}: the mechanism has no higher pair")
        return
    for j in pairs:
        if layer == "contact":
            _draw_contact(fig, sc, j)
        else:
            _draw_equivalent(fig, sc, j)


def _draw_contact(fig: Figure, sc, j) -> None:
    i, L = sc.index, sc.mech.length_scale
    rep = sc.sol.joint(j.name)
    X, n = rep["point"][i], rep["normal"][i]
    if not (np.isfinite(X).all() and np.isfinite(n).all()):
        fig.note(f"{j.name}: no contact at this position")
        return
    fig.line(X, n, [X - 0.3 * L * n, X + 0.3 * L * n], style=CONTACT, layer="contact",
             ident=f"normal-{j.name}")
    fig.dot(X, r=0.6, style=Style(stroke=CONTACT.stroke), layer="contact", ident=f"contact-{j.name}")
    fig.label(X, f"K_{{{j.name}}}" if j.name != "K" else "K", colour=CONTACT.stroke, size=3.0,
              prefer=-n * np.array([1.0, -1.0]), ident=f"contact-{j.name}")
    fig.note(f"{j.name}: contact point and common normal n–n; pressure angle "
             f"{np.degrees(rep['pressure_angle'][i]):.2f}°")


def _pivot(sc, link: str, centre: np.ndarray) -> np.ndarray | None:
    """Where a substitute bar from `centre` ends on `link`: its hinge on the frame, else its
    hinge nearest to the centre (None for the frame itself)."""
    mech = sc.mech
    if link == mech.frame:
        return None
    hinges = [j.point for j in mech.joints if isinstance(j, Revolute) and link in j.links]
    if not hinges:
        return None
    ground = [j.point for j in mech.joints if isinstance(j, Revolute) and set(j.links) == {link, mech.frame}]
    pick = ground or hinges
    return min((sc.pos(p) for p in pick), key=lambda p: float(np.hypot(*(p - centre))))


def _draw_equivalent(fig: Figure, sc, j) -> None:
    i, L = sc.index, sc.mech.length_scale
    eq = equivalent_linkage(sc.sol, j.name)
    kind = str(eq.kind[i])
    if kind in ("", "PP"):
        fig.note(f"{j.name}: no equivalent linkage at this position"
                 + (" (both elements straight at the contact)" if kind == "PP" else ""))
        return
    lay = "equivalent"
    finite = []
    for k, (C, link) in enumerate(zip(eq.centres, eq.links)):
        if not C.is_finite[i]:
            continue
        c = C.xy[i]
        finite.append(c)
        fig.symbol("revolute", at=c, colour=EQUIVALENT.stroke, layer=lay)
        fig.label(c, f"C_{k + 1}", colour=EQUIVALENT.stroke, size=3.0, ident=f"centre-{j.name}-{k + 1}")
        end = _pivot(sc, link, c)
        if end is not None and np.hypot(*(end - c)) > 1e-9 * L:
            fig.path(np.array([c, end]), style=EQUIVALENT, layer=lay, ident=f"equivalent-bar-{j.name}-{k + 1}")
        if eq.rolling:  # the osculating circle rolling as a pitch circle
            fig.circle(c, abs(float(eq.radii[i, k])), style=EQUIVALENT, layer=lay,
                       ident=f"equivalent-circle-{j.name}-{k + 1}")
    if len(finite) == 2:
        fig.path(np.array(finite), style=Style(stroke=EQUIVALENT.stroke, width=0.5, dash=EQUIVALENT.dash),
                 layer=lay, ident=f"equivalent-coupler-{j.name}")
    else:  # a slider along the straight element, through the finite centre
        c, t = finite[0], eq.tangent[i]
        fig.symbol("block", at=c, axis=t, colour=EQUIVALENT.stroke, layer=lay,
                   ident=f"equivalent-slider-{j.name}")
        fig.line(c, t, [c - 0.2 * L * t, c + 0.2 * L * t], style=EQUIVALENT, layer=lay,
                 ident=f"equivalent-guide-{j.name}")
    length = "" if not np.isfinite(eq.coupler[i]) else f", C₁C₂ = {eq.coupler[i]:.4g} {sc.mech.length_unit}"
    fig.note(f"{j.name}: equivalent linkage (dashed) {eq.name(sc.mech, i).split(' (')[0]}{length}")
