"""Rosenauer's drawings for sliding pairs between two moving links (1937, papers 3 and 5;
digest 000 §5, §7): the slide-pair parallelogram of the velocity plan, the half-Coriolis
construction by similar triangles on the mechanism, and the double parallelogram of the
acceleration plan, with the papers' built-in check lines.

Owns :func:`slide_pairs`. For each sliding pair (prismatic pair or straight slot) whose guide G
and sliding link S both move, with A the pair's point (the pin, a point of S) and B a point of G:

* **Velocities (paper 3).** Given a = v_A (of S) and b′ = v_B (of G): the lines through a and b′
  parallel to the slide s and perpendicular to AB form the parallelogram a a′ b′ b:
  a′ = (a ∥ s) ∩ (b′ ⟂ AB) is v_A of G (the coincident point), b = (b′ ∥ s) ∩ (a ⟂ AB) is v_B
  of S, and a′a = b′b is the sliding velocity (the two links turn together). A rectangle where
  AB ∥ s; a line where AB ⟂ s (B is then chosen elsewhere on G if it can be, else the pair is
  reported degenerate). Check lines: the poles P_S, P_G lie on a normal to s (Aronhold–Kennedy:
  their relative pole is at infinity across s), and ob ⟂ BP_S, oa′ ⟂ AP_G (paper 3, Ex. 2:
  ob′ ⟂ BP₂₄).
* **Half-Coriolis (paper 5, §2.7).** On the mechanism with rotated velocities u = k_v·J v: the
  rotated sliding velocity on the relative ray at A, its end joined to the guide's pole P_G, and
  the parallel through the end of the rotated carrying velocity u_A(G) cut the ray at L with
  AL = ω·k_v²·v_rel (similar triangles): AL = ½ j_γ at the acceleration scale k_v².
* **Accelerations (paper 5).** The plan points x_G(A) = a, x_S(A) = a′ = a − j_γ, b = a + ω²·AB,
  b′ = b − j_γ (the basic parallelogram: sides the Coriolis and the relative normal
  acceleration); the given accelerations laid off at a′ (A of S) and b (B of G); the lines
  through their ends parallel to s and perpendicular to AB form the second parallelogram (sides
  perpendicular to the first's): its other corners are the ends of a_A of G (from a) and a_B of
  S (from b′), its sides along s the sliding acceleration.

Results checked against the engine: the constructed velocities and accelerations of the
coincident points, the sliding velocity and acceleration, the Coriolis acceleration, and the
check lines (as cosines that vanish).
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role, pt
from ..errors import InputError
from ..model import Mechanism, Prismatic, Slot
from ..model.intermittent import is_intermittent
from ..topology.constructibility import lower, upper
from ._common import as_solution, dot, material_point, norm, perp, singular_positions
from ._plan import AccelerationConstruction, VelocityConstruction, _meet

SOURCE = "Rosenauer 1937, paper 3 (slide-pair parallelogram), paper 5 (half-Coriolis, double parallelogram)"


def _unit(v: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore", divide="ignore"):
        return v / norm(v)[:, None]


def _pairs(mech: Mechanism) -> list:
    out = [j for j in mech.joints if isinstance(j, (Prismatic, Slot)) and mech.frame not in j.links]
    if not out:
        pins = [j for j in mech.joints if is_intermittent(j)]
        raise InputError(f"{mech.name}: no sliding pair between two moving links (papers 3 and 5 "
                         "treat slides in moving planes)" + "".join(
                             f"; the pins of the {j.kind} pair '{j.name}' slide in the wheel's slots "
                             "but turn relative to the wheel (no block turning with it), so the "
                             "slide-pair parallelogram does not apply: the velocity and acceleration "
                             "plans draw the pair" for j in pins))
    return out


def _choose_b(mech: Mechanism, pos, G: str, A: str, s: np.ndarray) -> str:
    """The point B of the guide for the parallelograms: away from the normal to s through A
    (there the figures degenerate into lines), preferring a hinge."""
    cands = [p for p in dict.fromkeys(mech.link(G).points) if p != A]
    if not cands:
        raise InputError(f"the guide {G} has no point besides {A} for the parallelogram")

    def score(p):
        d = _unit(pos[p] - pos[A])
        return float(np.nanmin(abs(dot(d, s))))
    return max(cands, key=score)


def slide_pairs(mech: Mechanism, inputs, kv: float | None = None) -> Construction:
    """The papers' drawings for every sliding pair between two moving links of ``mech``."""
    sol = as_solution(mech, inputs)
    pairs = _pairs(mech)
    b = Builder("slide-pairs", "Slide pairs in moving planes: parallelograms, half-Coriolis",
                SOURCE, len(sol), spaces={"mechanism": "length", "velocity": "velocity",
                                          "acceleration": "acceleration"})
    singular_positions(b, sol)
    b.step("Given: the mechanism in its position, the input's angular velocity and acceleration; "
           "the velocity and acceleration plans of the links before each pair.")
    vc = VelocityConstruction(b, mech, sol, "plan")
    vc.run()
    ac = AccelerationConstruction(b, vc)
    ac.run()
    pos = vc.pos
    n = len(sol)
    vscale = np.max([norm(sol.point(p).velocity) for p in mech.points], axis=0)
    ascale = np.max([norm(sol.point(p).acceleration) for p in mech.points], axis=0)
    for j in pairs:
        G, S = j.links
        A = j.point
        s = vc._axis(G, j.axis)
        B = _choose_b(mech, pos, G, A, s)
        PA, PB = pos[A], pos[B]
        AB = PB - PA
        nA, nB = upper(A), upper(B)
        la, lb = lower(A), lower(B)
        key = f"sp.{j.name}"
        w = vc.measured_omega(G)
        # ---------------------------------------------------------------- velocities
        a_S = vc.image(S, A)
        b_G = vc.image(G, B)
        b.step(f"Slide {j.name} ({S} in {G}), paper 3: through {la} (v_{nA} of {S}) and {lb}\u2032 "
               f"(v_{nB} of {G}) draw the parallels to the slide and the perpendiculars to {nA}{nB}; "
               f"they form the parallelogram {la} {la}\u2032 {lb}\u2032 {lb}: {la}\u2032 is v_{nA} of {G}, "
               f"{lb} is v_{nB} of {S}, {la}\u2032{la} = {lb}\u2032{lb} the sliding velocity.")
        along = s * vc.kv
        across = perp(AB)
        vc._line(key + ".v.as", a_S, along)
        vc._line(key + ".v.aperp", a_S, across)
        vc._line(key + ".v.bs", b_G, along)
        vc._line(key + ".v.bperp", b_G, across)
        a_G, par1 = _meet((a_S, along), (b_G, across))
        b_S, par2 = _meet((b_G, along), (a_S, across))
        b.degenerate((par1 | par2) & ~b.bad, f"slide {j.name}: {nA} and {nB} lie on a normal to the "
                     "slide here, so the parallelogram degenerates into a straight line (paper 3)")
        vc._point(key + ".v.aG", a_G, la + "\u2032", lines=(key + ".v.as", key + ".v.bperp"))
        vc._point(key + ".v.bS", b_S, lb, lines=(key + ".v.bs", key + ".v.aperp"))
        b.polygon(key + ".v.parallelogram", [pt(a_S), pt(a_G), pt(b_G), pt(b_S)], Role.RESULT,
                  space="velocity")
        vrel = vc.velocity(PA, a_S) - vc.velocity(PA, a_G)
        b.compare(f"v_{A}@{G}", f"v_{nA} ({G})", f"velocity of the point of {G} at {nA}",
                  vc.velocity(PA, a_G), material_point(sol, G, PA).velocity, vscale,
                  f"{mech.length_unit}/s")
        b.compare(f"v_{B}@{S}", f"v_{nB} ({S})", f"velocity of the point of {S} at {nB}",
                  vc.velocity(PB, b_S), material_point(sol, S, PB).velocity, vscale,
                  f"{mech.length_unit}/s")
        b.compare(f"vrel_{j.name}", f"v_rel {j.name}", f"sliding velocity in {j.name} (a\u2032a)",
                  vrel, sol.joint(j.name)["velocity"], vscale, f"{mech.length_unit}/s")
        # poles of S and G from the parallelogram's velocities, and the check lines
        vS_A, vS_B = vc.velocity(PA, a_S), vc.velocity(PB, b_S)
        vG_A, vG_B = vc.velocity(PA, a_G), vc.velocity(PB, b_G)
        b.step(f"Check lines (paper 3): the poles P_{S} = ({nA} \u27c2 v_{nA}) \u2229 ({nB} \u27c2 v_{nB}) of "
               f"{S} and P_{G} of {G} lie on a normal to the slide (their relative pole is at infinity "
               f"across it); o{lb} \u27c2 {nB}P_{S} and o{la}\u2032 \u27c2 {nA}P_{G}.")
        P_S = _pole(PA, vS_A, PB, vS_B, w)
        P_G = _pole(PA, vG_A, PB, vG_B, w)
        still = abs(w) <= 1e-12 * (vscale / mech.length_scale + 1e-300)
        b.degenerate(still & ~b.bad, f"slide {j.name}: the two links translate here; their poles are "
                     "at infinity")
        b.point(key + ".PS", pt(P_S), Role.RESULT, f"P_{S}")
        b.point(key + ".PG", pt(P_G), Role.RESULT, f"P_{G}")
        b.segment(key + ".PSPG", pt(P_S), pt(P_G), kind="line")
        b.segment(key + ".BPS", pt(PB), pt(P_S), kind="line")
        b.segment(key + ".APG", pt(PA), pt(P_G), kind="line")
        one = np.ones(n)
        b.compare(f"check_{j.name}_poles", f"P_{S}P_{G} \u27c2 s", "cosine of the poles' line with "
                  "the normal to the slide turned (zero: the line is normal to the slide)",
                  dot(_unit(P_G - P_S), s), np.zeros(n), one)
        b.compare(f"check_{j.name}_ob", f"o{lb} \u27c2 {nB}P_{S}", "cosine between ob and BP_S",
                  dot(_unit(vS_B), _unit(P_S - PB)), np.zeros(n), one)
        b.compare(f"check_{j.name}_oa", f"o{la}\u2032 \u27c2 {nA}P_{G}", "cosine between oa' and AP_G",
                  dot(_unit(vG_A), _unit(P_G - PA)), np.zeros(n), one)
        # ---------------------------------------------------------------- half-Coriolis
        top = float(np.nanmax(abs(w))) if np.isfinite(w).any() else 0.0
        # the drawing's scale: ω·k = ½; links that only translate (no Coriolis term, the
        # triangles collapse, reported above): velocities drawn at half the mechanism's size
        k = kv if kv is not None else 0.5 / top if top > 0.0 else \
            0.5 * mech.length_scale / max(float(np.nanmax(vscale)), 1e-300)
        u_rel = k * perp(vrel)                 # the rotated sliding velocity, on the relative ray
        u_car = k * perp(vG_A)                 # the rotated carrying velocity of A, along AP_G
        b.step(f"Half-Coriolis (paper 5): lay the rotated sliding velocity on the relative ray at "
               f"{nA} and the rotated velocity of {nA} as a point of {G}; join the first's end to P_{G}; "
               f"the parallel through the second's end cuts the ray at L: {nA}L = \u03c9\u00b7v_rel = "
               "\u00bd j_\u03b3 (at the acceleration scale k_v\u00b2).")
        E1, E2 = PA + u_rel, PA + u_car
        b.segment(key + ".urel", pt(PA), pt(E1), kind="velocity")
        b.segment(key + ".ucar", pt(PA), pt(E2), kind="velocity")
        b.segment(key + ".join", pt(E1), pt(P_G), kind="line")
        L, parL = _meet((E2, P_G - E1), (PA, perp(s)))
        b.degenerate(parL & ~b.bad & ~still, f"slide {j.name}: no sliding here, the Coriolis term vanishes "
                     "and the triangles collapse")
        b.point(key + ".L", pt(L), Role.RESULT, "L")
        cor = 2 * (L - PA) / k ** 2
        b.compare(f"cor_{j.name}", f"j_\u03b3 {j.name}", f"Coriolis acceleration in {j.name} (2\u00b7AL)",
                  cor, sol.joint(j.name)["coriolis"], ascale, f"{mech.length_unit}/s\u00b2")
        # ---------------------------------------------------------------- double parallelogram
        aS_A = ac.image(S, A)
        aG_B = ac.image(G, B)
        b.step(f"Double parallelogram (paper 5): from a point a lay a{lb} = \u03c9\u00b2\u00b7{nA}{nB} "
               f"(the relative normal acceleration) and {la}\u2032{la} = {lb}\u2032{lb} = j_\u03b3; lay off "
               f"a_{nA} of {S} at {la}\u2032 and a_{nB} of {G} at {lb}; the parallels to the slide and the "
               f"perpendiculars to {nA}{nB} through their ends form the second parallelogram.")
        o2 = np.zeros((n, 2))
        xa = o2 - aS_A - 0.5 * (aG_B - aS_A)   # a base point that keeps the figure near o'
        x_aG = xa
        x_aS = xa - cor
        x_bG = xa + (w * w)[:, None] * AB
        x_bS = x_bG - cor
        b.polygon(key + ".a.basic", [pt(x_aG), pt(x_aS), pt(x_bS), pt(x_bG)], Role.AUXILIARY,
                  space="acceleration")
        for nm, xy, lab in (("aG", x_aG, la), ("aS", x_aS, la + "\u2032"), ("bG", x_bG, lb),
                            ("bS", x_bS, lb + "\u2032")):
            b.point(key + ".a.x" + nm, pt(xy), Role.AUXILIARY, lab, space="acceleration")
        E_SA = x_aS + aS_A
        E_GB = x_bG + aG_B
        b.arrow(key + ".a.jSA", pt(x_aS), pt(E_SA), Role.GIVEN, None, kind="acceleration", space="acceleration")
        b.arrow(key + ".a.jGB", pt(x_bG), pt(E_GB), Role.GIVEN, None, kind="acceleration", space="acceleration")
        E_GA, q1 = _meet((E_SA, s), (E_GB, perp(AB)))
        E_SB, q2 = _meet((E_GB, s), (E_SA, perp(AB)))
        b.degenerate((q1 | q2) & ~b.bad, f"slide {j.name}: {nA} and {nB} lie on a normal to the slide, "
                     "both parallelograms are straight lines here (paper 5, special case II)")
        b.polygon(key + ".a.second", [pt(E_SA), pt(E_GA), pt(E_GB), pt(E_SB)], Role.RESULT,
                  space="acceleration")
        aG_A = E_GA - x_aG
        aS_B = E_SB - x_bS
        b.arrow(key + ".a.jGA", pt(x_aG), pt(E_GA), Role.RESULT, None, kind="acceleration", space="acceleration")
        b.arrow(key + ".a.jSB", pt(x_bS), pt(E_SB), Role.RESULT, None, kind="acceleration", space="acceleration")
        b.compare(f"a_{A}@{G}", f"a_{nA} ({G})", f"acceleration of the point of {G} at {nA}", aG_A,
                  material_point(sol, G, PA).acceleration, ascale, f"{mech.length_unit}/s\u00b2")
        b.compare(f"a_{B}@{S}", f"a_{nB} ({S})", f"acceleration of the point of {S} at {nB}", aS_B,
                  material_point(sol, S, PB).acceleration, ascale, f"{mech.length_unit}/s\u00b2")
        b.compare(f"arel_{j.name}", f"a_rel {j.name}", f"sliding acceleration in {j.name} (side along s)",
                  E_SA - E_GA, sol.joint(j.name)["acceleration"], ascale, f"{mech.length_unit}/s\u00b2")
        b.step("Check (paper 5): each side of the second parallelogram is perpendicular to the "
               "corresponding side of the first.")
        b.compare(f"check_{j.name}_sides1", "j_\u03b3 \u27c2 a_rel", "cosine between the Coriolis side "
                  "and the sliding-acceleration side", dot(_unit(x_aG - x_aS), _unit(E_SA - E_GA)),
                  np.zeros(n), one)
        b.compare(f"check_{j.name}_sides2", f"{la}{lb} \u27c2 ends", "cosine between the relative normal "
                  "side and the relative tangential side", dot(_unit(x_bG - x_aG), _unit(E_GB - E_GA)),
                  np.zeros(n), one)
    return b.finish()


def _pole(P1, v1, P2, v2, w) -> np.ndarray:
    """The pole of a link from the velocities of two of its points (lines ⟂ to them); a point
    at rest is the pole itself; where the two lines coincide (both points on a line through the
    pole) the pole is where the rotated velocity points: P = X + J·v/ω (digest 000 §2.2)."""
    x, par = _meet((P1, perp(v1)), (P2, perp(v2)))
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(par[:, None], P1 + perp(v1) / w[:, None], x)
    rest1 = norm(v1) == 0
    rest2 = norm(v2) == 0
    return np.where(rest1[:, None], P1, np.where(rest2[:, None], P2, x))
