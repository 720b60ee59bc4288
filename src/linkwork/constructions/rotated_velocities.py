"""Rotated ("orthogonal") velocities on the mechanism drawing, the way Rosenauer works.

Owns :func:`rotated_velocities`. Rosenauer's *ortogonālais ātrums* (Pöschl's *gedrehte
Geschwindigkeit*, §27): every velocity is turned by 90° (here clockwise, the same for all points)
and laid off at its own point, at the scale kv. For one link the tips then form a figure
homothetic to the link about its pole, so the tips of two points of a link lie on a line parallel
to the link (Rosenauer §38-2, §68): through the tip A' draw the parallel to AB, it cuts the path
normal of B (the ray to its pole, the crank line of a rocker, the normal of a guide) in the tip
B'. No pole is needed. A point on a fixed pivot has its tip at itself; a point sliding on a guide
has its tip on the normal to the guide through the tip of the guide's coincident point
(Rosenauer §39: a line's tips lie on a parallel line at the distance of its sliding velocity).

The scale: by default Rosenauer's choice, the rotated velocity of the crank pin is the crank
itself (kv = 1/|ω|), so the crank's tip is the crank centre; pass ``scales`` to choose another.
Results checked: every point's velocity and every link's angular velocity.
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role, pt
from .scales import Scale, Scales, nice_ceil
from ..model import Mechanism, Revolute
from ._common import singular_positions, as_solution
from ._plan import VelocityConstruction
from .velocity_plan import compare_velocities, draw_images

SOURCE = "Rosenauer §38–39, §68; Pöschl §27 (gedrehte Geschwindigkeiten)"


def default_kv(mech: Mechanism, sol) -> float:
    """A nice kv (s) near 1/|ω| of the input crank (Rosenauer's choice), 1 otherwise; given point
    velocities (no crank): the fastest given point's rotated velocity a fifth of the drawing."""
    if not mech.drivers:
        v = max((float(np.nanmax(np.hypot(*np.asarray(sol.point(g.point).velocity).T))) for g in mech.given),
                default=0.0)
        return 0.2 * mech.length_scale / v if v > 0 else 1.0
    d = mech.drivers[0]
    if isinstance(mech.joint(d.joint), Revolute):
        w = float(np.nanmax(abs(sol.link(d.driven).omega)))
        if w > 0:
            return 1.0 / w
    return 1.0


def rotated_velocities(mech: Mechanism, inputs, *, scales: Scales | None = None,
                       sense: int | None = None) -> Construction:
    """Rotated velocities of all points of ``mech`` at ``inputs`` (radians or a Solution).

    ``sense`` (+1 counter-clockwise, −1 clockwise) turns every velocity the same way; by default
    the one that turns the crank pin's velocity towards the crank centre, so that with
    Rosenauer's scale the crank pin's tip is the crank centre itself."""
    sol = as_solution(mech, inputs)
    if sense is None and not mech.drivers:
        sense = -1
    if sense is None:
        d = mech.drivers[0]
        w0 = sol.link(d.driven).omega
        sense = 1 if (isinstance(mech.joint(d.joint), Revolute) and np.nanmean(w0) > 0) else -1
    if scales is not None:
        kv = scales.kv
    else:
        kv = default_kv(mech, sol)
        ls = Scale("length", mech.length_unit, nice_ceil(mech.length_scale / 170.0))
        scales = Scales(ls, Scale("velocity", f"{mech.length_unit}/s", ls.per_mm / kv))
    b = Builder("rotated-velocities", "Rotated (orthogonal) velocities", SOURCE, len(sol),
                scales=scales)
    singular_positions(b, sol)
    turn = "counter-clockwise" if sense > 0 else "clockwise"
    b.step(f"Given: the mechanism in its position; velocities are turned by 90\u00b0 {turn} and "
           f"laid off at their points ({scales.velocity.text()}).")
    vc = VelocityConstruction(b, mech, sol, "rotated", kv, sense)
    vc.run()
    draw_images(b, vc, mech, "rotated-velocity")
    b.step("The rotated velocities are the segments from each point to its tip X'; turned back by "
           "90\u00b0 they are the velocities.")
    for p in mech.points:
        if mech.point_owner[p] != mech.frame:
            img = vc.image(mech.point_owner[p], p, draw=False)
            b.arrow(f"v.res.{p}", pt(vc.pos[p]), pt(img), Role.RESULT, None, kind="velocity")
    compare_velocities(b, vc, sol, mech)
    return b.finish()
