"""The polar velocity plan (*Geschwindigkeitsplan*, Rosenauer §42 *polārais ātrumu plāns*).

Owns :func:`velocity_plan`: from the pole o of the plan the velocities of all points are laid off
at the velocity scale, group by group (the engine is :mod:`._plan`); the image of every link is
similar to the link and turned by 90° (Rosenauer §42: Δa'b'c' ~ ΔABC, ratio ω). Results checked:
every point's velocity, every link's angular velocity (ω = ab/AB, sense from the image), the
sliding velocities of the sliding pairs.
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role, pt
from ..model import Mechanism
from ._common import as_solution, material_point, singular_positions, norm
from ._plan import VelocityConstruction

SOURCE = "Rosenauer §40–42, Pöschl §47 (velocity plan, velocity image)"


def compare_velocities(b: Builder, vc: VelocityConstruction, sol, mech: Mechanism) -> None:
    pts = [p for p in mech.points if mech.point_owner[p] != mech.frame]
    vscale = np.max([norm(sol.point(p).velocity) for p in pts], axis=0)
    for p in pts:
        owner = mech.point_owner[p]
        img = vc.image(owner, p, draw=False)
        b.compare(f"v_{p}", f"v_{p}", f"velocity of {p}", vc.velocity(vc.pos[p], img),
                  sol.point(p).velocity, vscale, f"{mech.length_unit}/s")
    wscale = np.max([abs(sol.link(ln).omega) for ln in mech.moving_links], axis=0)
    for ln in mech.moving_links:
        b.compare(f"omega_{ln}", f"\u03c9_{ln}", f"angular velocity of {ln}", vc.measured_omega(ln),
                  sol.link(ln).omega, wscale, "rad/s")
    # auxiliary points (Rosenauer's Q, R, …), pitch points and coincident points: the velocity
    # of the link's material point there
    for link, entries in vc.known.items():
        for X, img, name in entries:
            if name in mech.points or link == mech.frame:
                continue
            b.compare(f"v_{name}@{link}", f"v_{name}", f"velocity of {name} as a point of {link}",
                      vc.velocity(X, img), material_point(sol, link, X).velocity, vscale,
                      f"{mech.length_unit}/s")
    for jname, v in vc.sliding.items():
        b.compare(f"vrel_{jname}", f"v_rel {jname}", f"sliding velocity in {jname}", v,
                  sol.joint(jname)["velocity"], vscale, f"{mech.length_unit}/s")


def draw_images(b: Builder, vc: VelocityConstruction, mech: Mechanism, what: str) -> None:
    """Velocity images of links with three or more points (similar figures in the plan)."""
    polys = []
    for link in mech.links:
        if link.name == mech.frame or len(link.points) < 3:
            continue
        polys.append((link.name, [vc.images[(link.name, p)] for p in dict.fromkeys(link.points)]))
    if polys:
        b.step(f"Join the images of each link's points: the {what} image of the link, similar to it.")
        for name, verts in polys:
            b.polygon(f"img.{vc.space}.{name}", [pt(v) for v in verts], Role.RESULT, space=vc.space)


def velocity_plan(mech: Mechanism, inputs) -> Construction:
    """The polar velocity plan of ``mech`` at ``inputs`` (radians/length unit, or a Solution)."""
    sol = as_solution(mech, inputs)
    b = Builder("velocity-plan", "Polar velocity plan", SOURCE, len(sol),
                spaces={"mechanism": "length", "velocity": "velocity"})
    singular_positions(b, sol)
    b.step("Given: the mechanism in its position.")
    vc = VelocityConstruction(b, mech, sol, "plan")
    vc.run()
    draw_images(b, vc, mech, "velocity")
    b.step("Read off the velocities: v_X = oX (from the pole o to the image x), \u03c9 = xy/XY.")
    for p in mech.points:
        if mech.point_owner[p] != mech.frame:
            img = vc.image(mech.point_owner[p], p, draw=False)
            b.arrow(f"v.res.{p}", pt(vc.o), pt(img), Role.RESULT, None, space="velocity")
    compare_velocities(b, vc, sol, mech)
    return b.finish()
