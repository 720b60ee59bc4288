"""Rosenauer's acceleration construction for the rolling-lever valve gear (*Wälzhebelsteuerung*;
1937, paper 8; digest 000 §10): the lever's inflection circle from Euler–Savary on the common
normal, the pole acceleration j_p = ω·V_p, and the plan of relative normal accelerations that
gives j_d and the valve's sliding acceleration j_b.

Owns :func:`rolling_lever`. The mechanism: a lever L touching a profile of the frame (a cam
contact, common normal n–n at E), hinged at B to a block or rod that slides on a frame guide
(so B moves on a straight line), and at D to a rod from a driven crank (A). Steps:

1. the velocity plan (polar, :mod:`.velocity_plan`);
2. the pole P of L = (normal to the slide at B) ∩ n–n;
3. the centres of curvature C_α (lever's profile) and C_e (bank) on n–n (the equivalent link);
   Euler–Savary by an auxiliary point (D): PF ∥ C_eD with F on C_αD, FW ∥ DP with W on n–n;
4. the inflection circle through B, P, W (B moves on a line: an inflection point); the inflection
   pole W₀ where it meets the line of the slide through B again (opposite P);
5. V_p = |v_{W₀}| (the velocity of W₀ from the plan), j_p = ω·V_p along PW₀ (tg δ = ω);
6. the plan of relative normal accelerations: d, a = d + ω²_rod·DA, b = d + ω²·DB, p = d + ω²·DP;
   j_p laid off at p — check: its end lies on the line through b parallel to the slide;
7. end(j_d) = (end(j_a) ⟂ AD) ∩ (end(j_p) ⟂ DP); j_b on the slide through b from the line
   through end(j_d) ⟂ BD.

Results checked against the engine and the curvature layer: P, W₀ (the inflection pole), V_p
(the pole-change velocity), j_p (the pole acceleration), j_d, j_b, the check line.
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role, pt
from ..errors import InputError
from ..model import CamContact, Mechanism, Prismatic, Revolute
from ._common import (as_solution, cross, dot, inflection_pole, material_point, norm, perp, pole,
                      pole_acceleration, pole_velocity, singular_positions)
from ._plan import VelocityConstruction, _meet

SOURCE = "Rosenauer 1937, paper 8 (rolling-lever valve gear: inflection circle, pole acceleration)"


def _parts(mech: Mechanism) -> dict:
    """The lever, its contact with the frame, the sliding hinge B and the rod's hinge D."""
    for cam in (j for j in mech.joints if isinstance(j, CamContact) and mech.frame in j.links):
        L = cam.links[1] if cam.links[0] == mech.frame else cam.links[0]
        hinges = [j for j in mech.joints if isinstance(j, Revolute) and L in j.links and mech.frame not in j.links]
        B = D = None
        for h in hinges:
            other = h.links[0] if h.links[1] == L else h.links[1]
            guide = next((g for g in mech.joints if isinstance(g, Prismatic) and set(g.links) == {mech.frame, other}), None)
            if guide is not None:
                B, valve, slide = h, other, guide
            else:
                rod_pts = [p for p in mech.link(other).points if p != h.point]
                crank = next((j for j in mech.joints if isinstance(j, Revolute) and other in j.links
                              and j.point in rod_pts), None)
                if crank is not None:
                    D, rod, A = h, other, crank.point
        if B is not None and D is not None:
            return dict(cam=cam, lever=L, B=B.point, valve=valve, slide=slide, D=D.point, rod=rod, A=A)
    raise InputError(f"{mech.name}: no lever touching a profile of the frame with one hinge on a "
                     "slider of the frame and one on a rod (the rolling-lever valve gear of paper 8)")


def rolling_lever(mech: Mechanism, inputs) -> Construction:
    """Paper 8's construction of the valve's sliding acceleration for ``mech`` at ``inputs``."""
    from ..instant.equivalent import equivalent_linkage
    sol = as_solution(mech, inputs)
    p = _parts(mech)
    L, rod = p["lever"], p["rod"]
    n = len(sol)
    b = Builder("rolling-lever", "Rolling-lever valve gear: inflection circle and pole acceleration",
                SOURCE, n, spaces={"mechanism": "length", "velocity": "velocity",
                                   "acceleration": "acceleration"})
    singular_positions(b, sol)
    b.step("Given: the mechanism in its position, the crank's angular velocity and acceleration.")
    vc = VelocityConstruction(b, mech, sol, "plan")
    vc.run()
    pos = vc.pos
    B, D, A = pos[p["B"]], pos[p["D"]], pos[p["A"]]
    eq = equivalent_linkage(sol, p["cam"].name)
    E, nn = eq.contact, eq.normal
    s = vc._axis(p["slide"].links[0], p["slide"].axis)
    w = vc.measured_omega(L)
    w_rod = vc.measured_omega(rod)
    L_scale = mech.length_scale
    # ---------------------------------------------------------------- the pole
    b.step(f"The pole P of {L}: the normal to the slide at B meets the common normal n\u2013n at E.")
    b.segment("rl.nn", pt(E - nn * L_scale), pt(E + nn * L_scale), kind="line", label="n\u2013n")
    P, par = _meet((B, perp(s)), (E, nn))
    b.degenerate(par & ~b.bad, "the common normal is parallel to the normal of the slide: the pole is at infinity")
    b.point("rl.P", pt(P), Role.RESULT, "P")
    b.compare_points("P", "P", f"pole of {L}", pt(P), pt(pole(sol, L)), L_scale)
    # ---------------------------------------------------------------- Euler–Savary
    frame_first = p["cam"].links[0] == mech.frame
    C_e, C_a = (eq.centres[0], eq.centres[1]) if frame_first else (eq.centres[1], eq.centres[0])
    Ce, Ca = C_e.xy, C_a.xy
    b.step("Euler\u2013Savary on n\u2013n: the centres of curvature C_\u03b1 (lever) and C_e (bank), joined "
           "to the auxiliary point D; PF \u2225 C_eD with F on C_\u03b1D, FW \u2225 DP with W on n\u2013n.")
    b.point("rl.Ca", C_a, Role.GIVEN, "C_\u03b1")
    b.point("rl.Ce", C_e, Role.GIVEN, "C_e")
    F, _ = _meet((P, D - Ce), (Ca, D - Ca))
    W, parW = _meet((F, P - D), (E, nn))
    b.degenerate((parW | ~np.isfinite(Ce).all(1) | ~np.isfinite(Ca).all(1)) & ~b.bad,
                 "a centre of curvature at infinity or the auxiliary point on n\u2013n: choose another")
    b.segment("rl.PF", pt(P), pt(F), kind="line")
    b.segment("rl.FW", pt(F), pt(W), kind="line")
    b.point("rl.F", pt(F), Role.AUXILIARY, "F")
    b.point("rl.W", pt(W), Role.RESULT, "W")
    # ---------------------------------------------------------------- inflection circle
    b.step("The inflection circle through B, P and W (B moves on a straight line); it meets the line "
           "of the slide through B again in the inflection pole W\u2080 (diametrically opposite P).")
    circ = b.circle_through("rl.circle", pt(B), pt(P), pt(W))
    # W₀: the foot of P on the slide's line through B is B itself (BP ⟂ slide), so W₀ is where the
    # diameter from P meets that line: the circle's centre reflected
    M = circ.centre.xy
    W0 = 2 * M - P
    b.point("rl.W0", pt(W0), Role.RESULT, "W\u2080")
    b.compare_points("W0", "W\u2080", f"inflection pole of {L}", pt(W0), pt(inflection_pole(sol, L)), L_scale)
    # ---------------------------------------------------------------- pole-change velocity
    b.step("V_p: the velocity of W\u2080 (from the plan); the pole moves along the pole tangent at that "
           "speed; j_p = \u03c9\u00b7V_p along PW\u2080 (the angle \u03b4 with tg \u03b4 = \u03c9).")
    w0_img = vc.image(L, "W0", W0, label="w\u2080")
    Vp = norm(vc.velocity(W0, w0_img))
    vscale = np.max([norm(sol.point(q).velocity) for q in mech.points], axis=0)
    b.compare("Vp", "V_p", "pole-change velocity (speed)", Vp, norm(pole_velocity(sol, L)), vscale,
              f"{mech.length_unit}/s")
    with np.errstate(invalid="ignore", divide="ignore"):
        jp = (abs(w) * Vp)[:, None] * (W0 - P) / norm(W0 - P)[:, None]
    ascale = np.max([norm(sol.point(q).acceleration) for q in mech.points], axis=0)
    b.compare("jp", "j_p", f"pole acceleration of {L}", jp, pole_acceleration(sol, L), ascale,
              f"{mech.length_unit}/s\u00b2")
    # ---------------------------------------------------------------- the plan
    b.step("Plan of relative normal accelerations: d; da = \u03c9\u00b2_rod\u00b7DA, db = \u03c9\u00b2\u00b7DB, "
           "\u0394dbp ~ \u0394DBP; j_p laid off at p. Check: its end lies on the line through b parallel "
           "to the slide.")
    xd = np.zeros((n, 2))
    xa = xd + (w_rod * w_rod)[:, None] * (A - D)
    xb = xd + (w * w)[:, None] * (B - D)
    xp = xd + (w * w)[:, None] * (P - D)
    for key, xy, lab in (("d", xd, "d"), ("a", xa, "a"), ("b", xb, "b"), ("p", xp, "p")):
        b.point(f"rl.x{key}", pt(xy), Role.AUXILIARY, lab, space="acceleration")
    Ep = xp + jp
    b.arrow("rl.jp", pt(xp), pt(Ep), Role.RESULT, "j_p", kind="acceleration", space="acceleration")
    one = np.ones(n)
    with np.errstate(invalid="ignore", divide="ignore"):
        off = Ep - xb
        b.compare("check_jp", "end(j_p) on b \u2225 s", "sine between b\u2192end(j_p) and the slide",
                  cross(off, s) / np.maximum(norm(off), 1e-300 + 0 * norm(off)), np.zeros(n), one)
    b.step("j_a laid off at a; end(j_d) = (end(j_a) \u27c2 AD) \u2229 (end(j_p) \u27c2 DP); the line through "
           "end(j_d) \u27c2 BD cuts the sliding acceleration j_b off the line through b along the slide.")
    crank = next(j for j in mech.joints if isinstance(j, Revolute) and j.point == p["A"])
    c_link = crank.links[0] if crank.links[1] == rod else crank.links[1]
    # the crank's given motion: a_A = ω²·AO + α·J·OA about its fixed pivot
    piv = next(j.point for j in mech.joints if isinstance(j, Revolute) and set(j.links) == {mech.frame, c_link})
    O = pos[piv]
    wc, ac = sol.link(c_link).omega, sol.link(c_link).alpha
    ja = (wc * wc)[:, None] * (O - A) + ac[:, None] * perp(A - O)
    Ea = xa + ja
    b.arrow("rl.ja", pt(xa), pt(Ea), Role.GIVEN, "j_a", kind="acceleration", space="acceleration")
    Ed, pard = _meet((Ea, perp(D - A)), (Ep, perp(P - D)))
    Eb, parb = _meet((Ed, perp(B - D)), (xb, s))
    b.degenerate(pard & ~b.bad, "the pole P lies on the rod's line AD here (the rod translates for "
                 "the instant): the lines \u27c2 AD and \u27c2 DP are parallel and leave j_d open")
    b.degenerate(parb & ~b.bad, "BD is perpendicular to the slide here: the line \u27c2 BD runs along it")
    jd, jb = Ed - xd, Eb - xb
    b.arrow("rl.jd", pt(xd), pt(Ed), Role.RESULT, "j_d", kind="acceleration", space="acceleration")
    b.arrow("rl.jb", pt(xb), pt(Eb), Role.RESULT, "j_b", kind="acceleration", space="acceleration")
    b.compare("a_D", "j_d", "acceleration of D", jd, sol.point(p["D"]).acceleration, ascale,
              f"{mech.length_unit}/s\u00b2")
    b.compare("a_B", "j_b", "acceleration of B (the valve's sliding acceleration)", jb,
              sol.point(p["B"]).acceleration, ascale, f"{mech.length_unit}/s\u00b2")
    b.compare("arel_valve", "j_b \u00b7 s", f"sliding acceleration of {p['valve']} along its guide",
              dot(jb, s), dot(material_point(sol, p["valve"], B).acceleration, s), ascale,
              f"{mech.length_unit}/s\u00b2")
    return b.finish()
