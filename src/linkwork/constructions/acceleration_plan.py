"""The polar acceleration plan (*Beschleunigungsplan*) with normal, tangential and Coriolis
components and the acceleration images of the links.

Owns :func:`acceleration_plan`. First the polar velocity plan (:mod:`.velocity_plan`) gives
every link's ω and every pair's sliding velocity; then, from the pole o' of the acceleration
plan and group by group, each unknown acceleration is the intersection of two lines:
a_B = a_A + a^n_BA (ω²·BA, towards A, laid off from the velocity plan as (ab)²/AB) + a^t_BA
(⟂ AB) for two points of a link, and a_B = a_{B∈G} + a_cor (2ω_G × v_rel) + a_rel (∥ guide) for a
point sliding on a guide link G. The images of a link's points form a figure similar to the link
(Burmester's theorem, Rosenauer §59; Mehmke §60). Results checked: every point's acceleration,
every link's angular acceleration α (a^t/l with its sense), the Coriolis accelerations.
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role, pt
from ..model import Mechanism
from ._common import as_solution, material_point, singular_positions, norm
from ._plan import AccelerationConstruction, VelocityConstruction
from .velocity_plan import compare_velocities, draw_images

SOURCE = "Rosenauer ch. VIII, XIII; Pöschl §47–48 (acceleration plan)"


def acceleration_plan(mech: Mechanism, inputs) -> Construction:
    """Velocity plan and acceleration plan of ``mech`` at ``inputs`` (radians or a Solution)."""
    sol = as_solution(mech, inputs)
    b = Builder("acceleration-plan", "Polar velocity and acceleration plans", SOURCE, len(sol),
                spaces={"mechanism": "length", "velocity": "velocity", "acceleration": "acceleration"})
    singular_positions(b, sol)
    b.step("Given: the mechanism in its position, the input's angular velocity and acceleration.")
    vc = VelocityConstruction(b, mech, sol, "plan")
    vc.run()
    draw_images(b, vc, mech, "velocity")
    ac = AccelerationConstruction(b, vc)
    ac.run()
    polys = []
    for link in mech.links:
        if link.name != mech.frame and len(link.points) >= 3:
            polys.append((link.name, [ac.images[(link.name, p)] for p in dict.fromkeys(link.points)]))
    if polys:
        b.step("Join the acceleration images of each link's points: similar to the link (Burmester).")
        for name, verts in polys:
            b.polygon(f"img.acc.{name}", [pt(v) for v in verts], Role.RESULT, space="acceleration")
    b.step("Read off the accelerations: a_X = o'x'; \u03b1 = a^t/l.")
    for p in mech.points:
        if mech.point_owner[p] != mech.frame:
            img = ac.image(mech.point_owner[p], p, draw=False)
            b.arrow(f"a.res.{p}", pt(ac.o), pt(img), Role.RESULT, None, kind="acceleration",
                    space="acceleration")
    compare_velocities(b, vc, sol, mech)
    pts = [p for p in mech.points if mech.point_owner[p] != mech.frame]
    ascale = np.max([norm(sol.point(p).acceleration) for p in pts], axis=0)
    for p in pts:
        img = ac.image(mech.point_owner[p], p, draw=False)
        b.compare(f"a_{p}", f"a_{p}", f"acceleration of {p}", img, sol.point(p).acceleration, ascale,
                  f"{mech.length_unit}/s\u00b2")
    # auxiliary and coincident points: the acceleration of the link's material point there
    for link, entries in ac.known.items():
        for X, img, name in entries:
            if name in mech.points or link == mech.frame:
                continue
            b.compare(f"a_{name}@{link}", f"a_{name}", f"acceleration of {name} as a point of {link}",
                      img, material_point(sol, link, X).acceleration, ascale, f"{mech.length_unit}/s\u00b2")
    wscale = np.max([np.maximum(abs(sol.link(ln).alpha), sol.link(ln).omega ** 2)
                     for ln in mech.moving_links], axis=0)
    for ln in mech.moving_links:
        b.compare(f"alpha_{ln}", f"\u03b1_{ln}", f"angular acceleration of {ln}", ac.measured_alpha(ln),
                  sol.link(ln).alpha, wscale, "rad/s\u00b2")
    for jname, cor in ac.coriolis.items():
        b.compare(f"cor_{jname}", f"a_cor {jname}", f"Coriolis acceleration in {jname}", cor,
                  sol.joint(jname)["coriolis"], ascale, f"{mech.length_unit}/s\u00b2")
    return b.finish()
