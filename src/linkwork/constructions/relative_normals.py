"""The relative normal accelerations v²/r drawn on the mechanism with Thales semicircles
(Rosenauer 1937, papers 4, 5, 8; digest 000 §2.6): the first half of every plan of relative
normal accelerations.

Owns :func:`relative_normals`. The rotated velocities are drawn first (Rosenauer's own form,
:mod:`.rotated_velocities`, at a scale k_v chosen so that k_v·|ω| < 1 for every link); for two
joints X, Y of a link the rotated relative velocity u = k_v·J(v_Y − v_X) lies along XY, with
|u| = k_v·ω·r (r = XY). A semicircle over XY and an arc about X of radius |u| meet at E; the foot
N of the perpendicular from E to XY gives XN = |u|²/r = k_v²·ω²·r (XE² = XN·XY in the right
triangle XEY): the relative normal acceleration of X about Y, at the acceleration scale k_v²,
directed from X towards Y. Results checked: every XN against the engine's ω²·XY.
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role, pt
from ..model import Mechanism
from ..topology.constructibility import upper
from ._common import as_solution, norm, singular_positions
from ._plan import VelocityConstruction

SOURCE = "Rosenauer 1937, papers 4, 5, 8 (Thales semicircle, relative normal accelerations)"


def _sides(mech: Mechanism, link: str) -> list[tuple[str, str]]:
    """The joints of a link taken round its outline (a binary link: its one side)."""
    hinge_pts = {getattr(j, "point", None) for j in mech.joints if link in j.links}
    pts = [p for p in dict.fromkeys(mech.link(link).points) if p in hinge_pts] or \
        list(dict.fromkeys(mech.link(link).points))
    if len(pts) < 2:
        return []
    if len(pts) == 2:
        return [(pts[0], pts[1])]
    return [(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]


def relative_normals(mech: Mechanism, inputs) -> Construction:
    """Rotated velocities, then every link side's relative normal acceleration by a Thales
    semicircle, on the mechanism drawing of ``mech`` at ``inputs``."""
    sol = as_solution(mech, inputs)
    w_max = max(float(np.nanmax(abs(sol.link(ln).omega))) for ln in mech.moving_links)
    kv = 0.8 / w_max if w_max > 0 else 1.0
    b = Builder("relative-normals", "Relative normal accelerations by Thales semicircles", SOURCE,
                len(sol), spaces={"mechanism": "length"})
    singular_positions(b, sol)
    b.step(f"Given: the mechanism in its position; rotated velocities at k_v = {kv:.4g} "
           f"{mech.length_unit} per {mech.length_unit}/s (every k_v\u00b7\u03c9 below 1, so each arc "
           "meets its semicircle), accelerations at k_v\u00b2.")
    vc = VelocityConstruction(b, mech, sol, "rotated", kv=kv, sense=1)
    vc.run()
    pos = vc.pos
    # the reference scale: the largest relative normal acceleration of the drawing
    scale = np.max([sol.link(ln).omega ** 2 for ln in mech.moving_links], axis=0) * mech.length_scale
    for ln in mech.moving_links:
        for X, Y in _sides(mech, ln):
            PX, PY = pos[X], pos[Y]
            tX, tY = vc.image(ln, X, draw=False), vc.image(ln, Y, draw=False)
            # the rotated relative velocity of Y about X: tip difference less the points' own
            u = (tY - PY) - (tX - PX)
            key = f"rn.{ln}.{X}{Y}"
            nX, nY = upper(X), upper(Y)
            b.step(f"{ln}: the rotated relative velocity u_{nY}{nX} lies along {nX}{nY}; over {nX}{nY} "
                   f"strike the semicircle, about {nX} the arc of radius |u|; from their meeting point E "
                   f"drop the perpendicular to {nX}{nY}: its foot N gives {nX}N = u\u00b2/{nX}{nY}, the "
                   f"normal acceleration of {nX} about {nY}.")
            b.segment(key + ".u", pt(PX), pt(PX + u), kind="velocity")
            mid = pt(0.5 * (PX + PY))
            semi = b.circle(key + ".semi", mid, 0.5 * norm(PY - PX))
            arc = b.circle(key + ".arc", pt(PX), norm(u), arcs=())
            E, _ = b.cut((key + ".E", None), semi, arc, labels=("E", None),
                         why=f"{ln}: the arc about {nX} misses the semicircle (k_v\u00b7\u03c9 \u2265 1)")
            side = b.join(key + ".XY", pt(PX), pt(PY))
            N = b.foot(key + ".N", E, side, Role.RESULT, "N")
            b.arrow(key + ".n", pt(PX), N, Role.RESULT, f"a^n_{nX}{nY}", kind="acceleration")
            got = (N.xy - PX) / kv ** 2
            wx = sol.link(ln).omega
            want = (wx * wx)[:, None] * (PY - PX)
            b.compare(f"an_{ln}_{X}{Y}", f"a^n_{nX}{nY}", f"normal acceleration of {nX} about {nY} "
                      f"({ln}), XN/k_v\u00b2", got, want, scale, f"{mech.length_unit}/s\u00b2")
    return b.finish()
