"""Klein's construction of the piston acceleration of the slider-crank (seed 004, §175).

Owns :func:`klein`. Names as in the steam-engine text: crank centre C, crank pin P, crosshead
(piston pin) A, line of stroke AC; the crank turns uniformly at ω.

1. Extend the rod line AP to meet the perpendicular to the line of stroke through C in N.
2. Strike the circle k₁ about P with radius PN.
3. Bisect AP in E and strike the circle k₂ about E through P (the circle on AP as diameter).
4. k₁ and k₂ meet in F and G. Their common chord FG is perpendicular to the line of centres
   AP; it cuts the rod line in L and the line of stroke in H.
5. Then, with CP representing the crank pin's centripetal acceleration ω²·CP, **HC represents the
   piston acceleration**: a_A = ω²·HC. By-products: the rod's angular velocity ω' = ω·PN/AP and
   angular acceleration ε' = ω²·LH/AP.

Why (the text's proof, restated): the rod's pole I = CP × (normal to the stroke at A) gives
similar triangles AIP ~ NCP, so ω'/ω = PN/AP; the normal acceleration of A about P is
ω'²·AP = ω²·PN²/AP = ω²·PF²/AP = ω²·PL (PF = PN, and PF² = PL·PA in the right triangle AFP on
the diameter AP); the tangential part is perpendicular to AP, i.e. along FG; closing the
acceleration polygon C→P→L→H on the stroke gives HC.

For an offset (*geschränkte*) slider-crank the same construction holds with the line of stroke
replaced, in the last step, by its parallel through C (for the centric slider-crank that is the
line of stroke itself); the similar-triangle proof does not use the offset.

Degenerate cases. At the dead centres (*Totlagen*) the rod line passes through C, so N = C and
the triangles of the proof collapse, but the construction itself stays valid — this is its
advantage over Mohr's and Rittershaus's constructions, which fail there; the result is the
closed form r ω² (1 ± r/l). Where the rod's angular velocity vanishes (crank perpendicular to
the stroke, centric case) N = P, k₁ shrinks to the point P and F = G = P: the chord FG is
then the limiting chord, the perpendicular to AP at P, which the construction draws anyway
because it draws FG as the perpendicular from F to AP. If the rod stood perpendicular to the
line of stroke, N would lie at infinity; this is reported as degenerate.
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role, literal
from ..errors import InputError
from ..geometry import Point
from ..geometry.constructions import midpoint
from ..model import Mechanism
from ._common import singular_positions, as_solution, cross, dot, norm, perp, rotate, slider_crank

SOURCE = "seed 004 (steam-engine text), §175: Klein's construction"


def klein(mech: Mechanism, inputs, *, omega: float | None = None) -> Construction:
    """Klein's construction at the crank angles ``inputs`` (radians; or a Solution).

    Given: the positions of C, P, A and the line of stroke, and the crank's uniform angular
    velocity (the driver's speed unless ``omega`` is given). Results, each compared with the
    engine: the piston acceleration (vector), the rod's angular velocity and acceleration.
    """
    sc = slider_crank(mech)
    sol = as_solution(mech, inputs)
    n = len(sol)
    crank = sol.link(sc.crank)
    w = crank.omega if omega is None else np.full(n, float(omega))
    if np.any(abs(crank.alpha) > 1e-12 * np.maximum(1.0, w * w)):
        raise InputError("Klein's construction assumes the crank turns uniformly (zero angular "
                         "acceleration); this input has a crank angular acceleration")
    C = Point.from_xy(sol.point(sc.C).position)
    Pp = Point.from_xy(sol.point(sc.P).position)
    A = Point.from_xy(sol.point(sc.A).position)
    axis = rotate(sol.pose_derivatives(mech.frame)[0, :, 2], np.broadcast_to(sc.axis, (n, 2)))

    b = Builder("klein", "Klein's construction of the piston acceleration", SOURCE, n)
    singular_positions(b, sol)
    b.own_labels = True
    b.legend.append("Klein: CP represents the crank pin's acceleration \u03c9\u00b2\u00b7CP, so HC represents "
                    "a_A at M_a = \u03c9\u00b2\u00b7M_l")
    b.step("Given: crank centre C, crank pin P and crosshead A on the line of stroke; the crank "
           "turns uniformly at \u03c9, so CP represents the crank pin's acceleration \u03c9\u00b2\u00b7CP.")
    # the drawn points keep the file's names; the steps speak the book's letters (the key)
    b.key({"C": sc.C, "P": sc.P, "A": sc.A})
    b.point("C", C, Role.GIVEN, literal(sc.C))
    b.point("P", Pp, Role.GIVEN, literal(sc.P))
    b.point("A", A, Role.GIVEN, literal(sc.A))
    b.segment("crank", C, Pp, Role.GIVEN)
    b.segment("rod", Pp, A, Role.GIVEN)
    from ..geometry import Vector
    stroke = b.parallel("stroke", A, Vector(axis), Role.GIVEN)
    b.extend("stroke", C)
    centric = abs(cross(axis, C.xy - A.xy)) <= 1e-12 * np.maximum(norm(A.xy - C.xy), 1e-300)

    b.step("Extend the rod line AP to meet the perpendicular to the line of stroke through C in N.")
    AP = b.join("AP", A, Pp)
    perp_C = b.perpendicular("CN", C, stroke)
    N = b.meet("N", AP, perp_C, label="N", k1="AP", k2="CN",
               why="the rod stands perpendicular to the line of stroke, so N lies at infinity")

    b.step("Strike the circle k_1 about P with radius PN.")
    k1 = b.circle("k1", Pp, N, label="k_1")

    b.step("Bisect AP in E and strike the circle k_2 about E through P (the circle on AP as diameter).")
    E = b.point("E", midpoint(A, Pp), Role.AUXILIARY, "E")
    k2 = b.circle("k2", E, Pp, label="k_2")

    b.step("The circles k_1 and k_2 meet in F and G.")
    F, G = b.cut(("F", "G"), k1, k2, labels=("F", "G"),
                 why="the circles k\u2081 and k\u2082 do not meet (PN > AP: not a slider-crank position)")
    b.limiting(norm(N.xy - Pp.xy) <= 1e-9 * norm(A.xy - Pp.xy),
               "the rod does not turn here (N = P): k\u2081 shrinks to the point P and F = G = P; the "
               "chord FG becomes its limit, the perpendicular to AP at P")

    if centric.all():
        hline = stroke
        b.step("Draw the common chord FG (perpendicular to AP); it cuts the rod line in L and the "
               "line of stroke in H.")
    else:
        b.step("Draw the common chord FG (perpendicular to AP); it cuts the rod line in L. Draw the "
               "parallel to the line of stroke through C (offset slider-crank); FG cuts it in H.")
        hline = b.parallel("stroke_C", C, stroke)
    FG = b.perpendicular("FG", F, AP)
    b.extend("FG", G)
    L = b.meet("L", FG, AP, label="L", k1="FG", k2="AP")
    H = b.meet("H", FG, hline, Role.RESULT, "H", k1="FG", k2="stroke" if centric.all() else "stroke_C",
               why="the chord FG is parallel to the line of stroke")

    b.step("HC represents the piston acceleration: a_A = \u03c9\u00b2\u00b7HC; the rod turns at "
           "\u03c9' = \u03c9\u00b7PN/AP with \u03b5' = \u03c9\u00b2\u00b7LH/AP.")
    b.arrow("aA", H, C, Role.RESULT, "a_A", kind="acceleration")
    b.segment("LH", L, H, Role.RESULT, "LH")

    # ---- numbers read off the drawing (lengths measured, senses from the figure)
    Cx, Px, Ax, Nx, Lx, Hx = (q.xy for q in (C, Pp, A, N, L, H))
    AP_len = norm(Px - Ax)
    a_piston = (w * w)[:, None] * (Cx - Hx)
    # ω' and ε' with their senses: N beyond P seen from A means the rod turns against the crank
    s_w = dot(Nx - Px, Px - Ax) / AP_len
    w_rod = -w * s_w / AP_len
    s_e = dot(Hx - Lx, perp(Px - Ax)) / AP_len
    e_rod = (w * w) * s_e / AP_len

    exact_a = sol.point(sc.A).acceleration
    rod = sol.link(sc.rod)
    r = norm(Px - Cx)
    b.compare("a_A", "a_A", "piston acceleration \u03c9\u00b2\u00b7HC", a_piston, exact_a, w * w * r,
              f"{mech.length_unit}/s\u00b2")
    b.compare("omega_rod", "\u03c9'", "rod angular velocity \u03c9\u00b7PN/AP", w_rod, rod.omega,
              abs(w), "rad/s")
    b.compare("alpha_rod", "\u03b5'", "rod angular acceleration \u03c9\u00b2\u00b7LH/AP", e_rod, rod.alpha,
              w * w, "rad/s\u00b2")
    return b.finish()
