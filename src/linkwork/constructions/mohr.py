"""Mohr's construction of the acceleration of the second pin from the crank pin's (Pöschl §47–48,
Abb. 51 and 53; seed 002).

Owns :func:`mohr`. Names as in Pöschl: crank centre O (O₁), crank pin A, crank r = OA, rod or
coupler AB = l; B slides on a straight line of stroke (slider-crank, §48) or swings about O₂ on
the rocker O₂B (four-bar, §47). Given: the velocity and acceleration of A; b_A is drawn at A at
a freely chosen acceleration scale (by default as long as the crank: Pöschl's b_A = r).

With Ω the rod's pole (on the crank line) and R₁ = AΩ, eq. (99) reads
b_AB^(n) = l ω² = (l/R₁)(r/R₁) b_A^(n). Pöschl's ruler variant without Ω (so that Ω may lie off
the sheet) realises the two ratios by similar triangles:

1. through the tip of b_A^(n) (laid off from A along AO) the parallel to BΩ — the perpendicular
   to B's path for the slider-crank, the rocker line O₂B for the four-bar — meets AB in α
   (Aα = b_A^(n)·l/R₁);
2. the parallel to OB through α meets the crank line AO in γ (γA = Aα·r/l);
3. the parallel to BΩ through γ meets AB in α′: **α′A represents b_AB^(n)** (= l ω²);
4. slider-crank: the perpendicular to AB at α′ (the direction of b_AB^(t)) meets the parallel to
   B's path through the tip of b_A in X; **X to the tip of b_A represents b_B** (the polygon
   tip of b_A → A → α′ → X is −b_A − b_AB^(n) − b_AB^(t) = −b_B, and b_B is along the path);
4′. four-bar: α′A carried to B (β′ on BA, Bβ′ = Aα′) and the line sequence reversed (parallels
   to the crank line, to O₂A, to the crank line) gives on BO₂ the tip of b_B^(n); at B form
   b_AB^(n) + b_A; the perpendicular to AB through its end and the perpendicular to BO₂ through
   the tip of b_B^(n) meet in **the tip of b_B**.

The rod's angular acceleration ε follows from the tangential component b_AB^(t) = ε·l, read off
the drawing along the perpendicular to AB.

Degenerate positions.

* Dead centres (*Totlagen*; for the four-bar the rocker's reversal points u₁, u₂): O, A, B are
  in line, the parallel to OB through α falls on the crank line and γ is undetermined — "für die
  diese Konstruktion versagen würde" (§48). There Ω = B, R₁ = l, and Pöschl's dead-centre
  construction is drawn instead (the limiting construction): OM = l on OB, b_A^(n) laid
  perpendicular at M to E; the line OE cuts off b_A^(n)·r/l = b_AB^(n) on the perpendicular at A
  (and, for the centric slider-crank, b_B = b_A(1 ± r/l) on the perpendicular at B, eqs. 100–101).
  Within :data:`NEAR_IN_LINE` of such a position (but not at it) the parallels of step 2 cross
  at a grazing angle and the drawing loses its digits: reported as degenerate.
* Slider-crank, rod perpendicular to the line of stroke: the perpendiculars to the path of steps
  1 and 3 are parallel to AB (α, α′ at infinity).
* Four-bar, crank parallel to the rocker: Ω lies at infinity (the coupler does not turn),
  b_AB^(n) = 0 while b_B^(n) is not, and the reversed line sequence at B collapses (the parallel
  to the crank through β′ = B is the rocker line itself). Near it the reversed sequence
  magnifies rounding by (R/l)²; within :data:`NEAR_PARALLEL` it is reported as degenerate.
* Coupler in line with the rocker (four-bar) or any other dead centre of the mechanism: the
  engine reports it (velocities undetermined).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .construction import Builder, Construction, Role, literal, mask_points, pt
from ..errors import InputError
from ..geometry import Point, Vector
from ..model import Mechanism, Revolute
from ._common import (NotACrank, as_solution, conjugate_pairs, cross, norm, perp, rotate,
                      singular_positions, slider_crank)

SOURCE = "Pöschl §47–48 (seed 002): Mohr's construction, Abb. 51, 53, 54"

#: sine of the angle between two lines of the construction below which they count as (nearly)
#: parallel: O, A, B nearly in line (step 2), or the crank nearly parallel to the rocker (four-bar,
#: reversed sequence). Above it the ruler construction keeps better than 1e-9 (relative).
NEAR_IN_LINE = 1e-6

#: four-bar: sine of the angle between crank and rocker below which the coupler's pole Ω counts
#: as off the sheet. The reversed line sequence at B magnifies drawing errors by (R/l)², R ~ l/sine;
#: at 1e-3 the engine's own rounding already shows at 1e-9 (found on the library's four-bars).
NEAR_PARALLEL = 3e-3


@dataclass(frozen=True)
class _Given:
    kind: str  # "slider-crank" or "four-bar"
    crank: str
    rod: str
    O: str
    A: str
    B: str
    O2: str | None  # the rocker pivot (four-bar)
    axis: np.ndarray | None  # the line of stroke, design frame (slider-crank)


def _given(mech: Mechanism) -> _Given:
    """Recognise the slider-crank or the four-bar (crank driven on the frame) in ``mech``."""
    try:
        sc = slider_crank(mech, "Mohr's construction")
        return _Given("slider-crank", sc.crank, sc.rod, sc.C, sc.P, sc.A, None, sc.axis)
    except NotACrank:
        raise
    except InputError:
        pass  # not a slider-crank: perhaps a four-bar
    d = mech.drivers[0]  # one revolute driver on the frame (checked by the recogniser)
    j = mech.joint(d.joint)
    crank = d.driven
    for pin in mech.joints:
        if not isinstance(pin, Revolute) or crank not in pin.links or mech.frame in pin.links:
            continue
        rod = pin.links[0] if pin.links[1] == crank else pin.links[1]
        for c in conjugate_pairs(mech, rod):
            if c.point != pin.point and c.centre is not None:
                return _Given("four-bar", crank, rod, j.point, pin.point, c.point, c.centre, None)
    raise InputError(f"mechanism '{mech.name}' is neither a slider-crank nor a four-bar for Mohr's "
                     "construction (a crank driven on the frame, a rod or coupler hinged to it whose "
                     "other pin slides on a straight frame guide or swings on a frame-pivoted rocker)")


def _sine(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore", divide="ignore"):
        return abs(cross(u, v)) / (norm(u) * norm(v))


def mohr(mech: Mechanism, inputs, *, ka: float | None = None) -> Construction:
    """Mohr's construction at the crank angles ``inputs`` (radians; or a Solution).

    ``ka``: acceleration scale, mechanism lengths per acceleration unit (default, per position:
    b_A drawn as long as the crank, Pöschl's b_A = r). Results, each compared with the engine:
    b_B (vector), b_AB^(n) = |Aα′| and the rod's angular acceleration (and b_B^(n) for the
    four-bar).
    """
    g = _given(mech)
    sol = as_solution(mech, inputs)
    n = len(sol)
    slider = g.kind == "slider-crank"
    Ox, Ax, Bx = (sol.point(p).position for p in (g.O, g.A, g.B))
    aA = sol.point(g.A).acceleration
    w1 = sol.link(g.crank).omega
    r, ll = norm(Ax - Ox), norm(Bx - Ax)
    if ka is None:
        with np.errstate(invalid="ignore", divide="ignore"):
            k = np.where(norm(aA) > 0, r / norm(aA), 1.0)
    else:
        k = np.full(n, float(ka))
    u = (Ox - Ax) / r[:, None]
    Tn = Ax + (k * w1 * w1 * r)[:, None] * u  # tip of b_A^(n), along AO
    Ta = Ax + k[:, None] * aA  # tip of b_A

    b = Builder("mohr", "Mohr's construction of the acceleration (b_B from b_A)", SOURCE, n)
    singular_positions(b, sol)
    b.own_labels = True
    b.legend.append("Mohr: b_A drawn as long as the crank (for a uniformly turning crank "
                    "M_b = \u03c9\u2081\u00b2\u00b7M_l)" if ka is None else
                    f"Mohr: accelerations drawn at {ka:g} {mech.length_unit} per {mech.length_unit}/s\u00b2")
    o = "O" if slider else "O_1"
    O, A, B = pt(Ox), pt(Ax), pt(Bx)
    if slider:
        b.step(f"Given: crank centre O ({g.O}), crank pin A ({g.A}) with b_A (its normal component "
               f"b_A^(n) = r\u03c9\u2081\u00b2 along AO), crosshead B ({g.B}) on the line of stroke.")
    else:
        b.step(f"Given: crank O_1A ({g.O}, {g.A}) with b_A (its normal component b_A^(n) = "
               f"r\u2081\u03c9\u2081\u00b2 along AO_1), coupler AB ({g.B}), rocker O_2B ({g.O2}).")
    # the drawn points keep the file's names; the steps speak the book's letters (the key)
    b.key({o: g.O, "A": g.A, "B": g.B} | ({} if slider else {"O_2": g.O2}))
    b.point("O", O, Role.GIVEN, literal(g.O))
    b.point("A", A, Role.GIVEN, literal(g.A))
    b.point("B", B, Role.GIVEN, literal(g.B))
    b.segment("crank", O, A, Role.GIVEN)
    b.segment("rod", A, B, Role.GIVEN)
    b.arrow("bAn", A, pt(Tn), Role.GIVEN, "b_A^(n)", kind="acceleration")
    b.arrow("bA", A, pt(Ta), Role.GIVEN, "b_A", kind="acceleration")
    if slider:
        axis = rotate(sol.pose_derivatives(mech.frame)[0, :, 2], np.broadcast_to(g.axis, (n, 2)))
        path = b.parallel("stroke", B, Vector(axis), Role.GIVEN)
        O2 = None
    else:
        O2 = b.point("O2", pt(sol.point(g.O2).position), Role.GIVEN, literal(g.O2))
        path = b.join("O2B", O2, B, Role.GIVEN)

    # O, A, B in line: a dead centre (the rocker's reversal point for the four-bar)
    s_in_line = _sine(Ax - Ox, Bx - Ox)
    dc = (s_in_line <= 1e-12) & ~b.bad
    b.degenerate((s_in_line <= NEAR_IN_LINE) & ~dc & ~b.bad,
                 f"O, A and B are within a hair of a {'dead centre' if slider else 'reversal point'} "
                 f"(in line to less than {NEAR_IN_LINE:g} rad): the parallel to OB meets the crank line "
                 "at a grazing angle and the construction loses its accuracy")
    if not slider:
        b.degenerate((_sine(Ax - Ox, Bx - O2.xy) <= NEAR_PARALLEL) & ~b.bad,
                     f"the crank is parallel to the rocker (to within {NEAR_PARALLEL:g} rad): the "
                     "coupler's pole \u03a9 lies at infinity or far off the sheet (b_AB^(n) \u2192 0), and "
                     "the reversed line sequence at B, which magnifies every drawing error by (R/l)\u00b2, "
                     "collapses there, so b_B^(n) is not found")
    tip = b.point("Tn", pt(Tn), Role.AUXILIARY, None)
    across = "the perpendicular to B's path" if slider else "the parallel to the rocker O_2B"

    def to_path(key: str, through: Point):
        return (b.perpendicular(key, through, path) if slider else b.parallel(key, through, path))
    why_ab = ("the rod stands perpendicular to the line of stroke, so the perpendiculars to B's path "
              "never meet it" if slider else "the coupler is in line with the rocker")

    b.step(f"Through the tip of b_A^(n) draw {across}; it meets AB in \u03b1.")
    AB = b.join("AB", A, B)
    alpha = b.meet("alpha", to_path("s1", tip), AB, label="\u03b1", k1="s1", k2="AB", why=why_ab)

    b.step(f"Through \u03b1 draw the parallel to {o}B; it meets the crank line A{o} in \u03b3.")
    OB = b.join("OB", O, B)
    AO = b.join("AO", A, O)
    gamma = b.meet("gamma", b.parallel("s2", mask_points(alpha, dc), OB), AO, label="\u03b3",
                   k1="s2", k2="AO", why=f"O, A and B are in line: the parallel to {o}B through \u03b1 "
                   "falls on the crank line, so \u03b3 is undetermined")

    b.step(f"Through \u03b3 draw {across} again; it meets AB in \u03b1\u2032: \u03b1\u2032A represents "
           "b_AB^(n) = l\u03c9\u00b2.")
    ap_reg = b.meet("alpha_p", to_path("s3", gamma), AB, label="\u03b1\u2032", k1="s3", k2="AB", why=why_ab)
    ap = ap_reg.xy
    if dc.any():
        b.limiting(dc, f"O, A and B are in line ({'a dead centre' if slider else 'a reversal point of the rocker'}): "
                   "Pöschl's dead-centre construction replaces steps 2 and 3 (\u03a9 = B, R = l)")
        b.step(f"At the {'dead centre' if slider else 'reversal point'} (O, A, B in line): make OM = l on "
               f"{o}B; lay b_A^(n) off perpendicular at M to E; the line {o}E cuts off b_AB^(n) = "
               "b_A^(n)\u00b7r/l on the perpendicular at A (carried onto AB towards B: \u03b1\u2032)"
               + (", and b_B = b_A(1 \u00b1 r/l) on the perpendicular at B." if slider else "."))
        keep = ~dc
        Od, Ad, Bd = (mask_points(p, keep) for p in (O, A, B))
        eOB = (Bx - Ox) / norm(Bx - Ox)[:, None]
        M = b.point("M", pt(Ox + ll[:, None] * eOB), Role.AUXILIARY, "M")
        b.circle("M.arc", Od, ll, arcs=(M,))
        E = b.point("E", pt(M.xy + norm(Tn - Ax)[:, None] * perp(eOB)), Role.AUXILIARY, "E")
        OE = b.join("OE", Od, E)
        EA = b.meet("EA", b.perpendicular("perpA", Ad, OB), OE, k1="perpA", k2="OE")
        ap_dc = Ax + norm(EA.xy - Ax)[:, None] * (Bx - Ax) / ll[:, None]
        b.circle("alpha_p.arc", Ad, EA, arcs=(EA, pt(ap_dc)))
        b.point("alpha_p_dc", pt(ap_dc), Role.AUXILIARY, "\u03b1\u2032")
        if slider:
            EB = b.meet("EB", b.perpendicular("perpB", Bd, OB), OE, Role.RESULT, "E_B",
                        k1="perpB", k2="OE")
        ap = np.where(dc[:, None], ap_dc, ap)
    Ap_ = pt(ap)
    b.segment("bABn", Ap_, A, Role.RESULT, "b_AB^(n)")

    if slider:
        b.step("The perpendicular to AB at \u03b1\u2032 (the direction of b_AB^(t)) meets the parallel to "
               "B's path through the tip of b_A in X: X to the tip of b_A represents b_B.")
        tA = b.point("Ta", pt(Ta), Role.AUXILIARY, None)
        X = b.meet("X", b.perpendicular("t", Ap_, AB), b.parallel("pa", tA, path), Role.RESULT, "X",
                   k1="t", k2="pa", why="the rod stands perpendicular to the line of stroke")
        b.arrow("bB", X, tA, Role.RESULT, "b_B", kind="acceleration")
        aB = (Ta - X.xy) / k[:, None]
        eps = -cross(Bx - Ax, X.xy - ap) / (k * ll * ll)
    else:
        b.step("Carry \u03b1\u2032A to B (\u03b2\u2032 on BA, B\u03b2\u2032 = A\u03b1\u2032) and reverse the line "
               "sequence: the parallel to the crank O_1A through \u03b2\u2032 meets BO_2 in \u03b4; the parallel "
               "to O_2A through \u03b4 meets BA in \u03b2; the parallel to O_1A through \u03b2 meets BO_2 in the "
               "tip of b_B^(n).")
        bp = pt(Bx + (Ax - ap))
        b.circle("beta_p.arc", B, norm(ap - Ax), arcs=(bp,))
        bp = b.point("beta_p", bp, Role.AUXILIARY, "\u03b2\u2032")
        why_r = ("the crank is parallel to the rocker: the coupler's pole \u03a9 lies at infinity and "
                 "the reversed sequence at B collapses")
        delta = b.meet("delta", b.parallel("r1", bp, AO), path, label="\u03b4", k1="r1", k2="O2B",
                       why=why_r)
        beta = b.meet("beta", b.parallel("r2", delta, b.join("O2A", O2, A)), AB, label="\u03b2",
                      k1="r2", k2="AB", why=why_r)
        tBn = b.meet("tBn", b.parallel("r3", beta, AO), path, k1="r3", k2="O2B", why=why_r)
        b.arrow("bBn", B, tBn, Role.RESULT, "b_B^(n)", kind="acceleration")
        b.step("At B form b_AB^(n) + b_A (to Q); the perpendicular to AB through Q and the perpendicular "
               "to BO_2 through the tip of b_B^(n) meet in the tip of b_B.")
        Q = pt(bp.xy + (Ta - Ax))
        b.arrow("bAB", B, bp, Role.AUXILIARY, "b_AB^(n)", kind="acceleration")
        b.arrow("bA.B", bp, Q, Role.AUXILIARY, "b_A", kind="acceleration")
        X = b.meet("X", b.perpendicular("t", Q, AB), b.perpendicular("tB", tBn, path), Role.RESULT, None,
                   k1="t", k2="tB", why="the coupler is in line with the rocker")
        b.arrow("bB", B, X, Role.RESULT, "b_B", kind="acceleration")
        aB = (X.xy - Bx) / k[:, None]
        eps = cross(Bx - Ax, X.xy - Q.xy) / (k * ll * ll)

    # ---- the numbers read off the drawing, next to the engine's
    unit = f"{mech.length_unit}/s\u00b2"
    aB_ref = sol.point(g.B).acceleration
    rod = sol.link(g.rod)
    scale = np.maximum(norm(aA), norm(aB_ref))
    b.compare("b_B", "b_B", "acceleration of B", aB, aB_ref, scale, unit)
    b.compare("b_ABn", "b_AB^(n)", "normal acceleration of B about A, |A\u03b1\u2032|",
              norm(ap - Ax) / k, ll * rod.omega ** 2, scale, unit)
    b.compare("eps", "\u03b5", "angular acceleration of the rod from b_AB^(t)", eps, rod.alpha,
              scale / ll, "rad/s\u00b2")
    if not slider:
        vB = sol.point(g.B).velocity
        r2 = norm(Bx - O2.xy)
        b.compare("b_Bn", "b_B^(n)", "normal acceleration of B about O_2 (v_B\u00b2/O_2B)",
                  norm(tBn.xy - Bx) / k, norm(vB) ** 2 / r2, scale, unit)
    elif dc.any():
        # Pöschl's dead-centre reading on the perpendicular at B (centric slider-crank, eqs. 100-101)
        centric = _sine(axis, Bx - Ox) <= 1e-12
        ref = np.where(dc & centric, abs(np.sum(aB_ref * axis, axis=-1)) / norm(axis), np.nan)
        b.compare("b_B0", "b_B0", "dead-centre acceleration b_A(1 \u00b1 r/l), cut off by OE at B",
                  np.where(dc & centric, norm(EB.xy - Bx) / k, np.nan), ref, scale, unit)
    return b.finish()
