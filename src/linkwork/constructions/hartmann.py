"""Hartmann's construction: the pole-transfer velocity and centres of curvature
(W. Hartmann, "Krümmungsmittelpunkte der Rast- und Gangpolbahn", Z. VDI 1893).

Owns :func:`hartmann` (Pöschl §35, Rosenauer §44 Example 16 — the Chebyshev four-bar). The path
normals n_A = C_aA and n_B = C_bB turn about C_a and C_b; their intersection, the pole P, slides
along both, so its velocity u (*Polwechselgeschwindigkeit*) has the projections u_A ⟂ n_A and
u_B ⟂ n_B of the points of the turning normals that lie at P:

1. the path normals meet in the pole P;
2. the velocity v_A (given, ⟂ n_A) is drawn at A; the line from its tip to C_a meets the
   perpendicular to n_A through P in the tip of u_A (u_A = v_A·C_aP/C_aA);
3. v_B from v_A by the angle δ (Rosenauer §38-1: tan δ = ω, the same for every ray): the line P
   to the tip of v_A makes δ with ray I; δ laid off at P from ray II (compass) meets the
   perpendicular to ray II at B in the tip of v_B; then as in 2 the tip of u_B;
4. the parallels to n_A through the tip of u_A and to n_B through the tip of u_B meet in the
   tip of u: the pole-transfer velocity, along the pole tangent;
5. the inflection pole W₀: D = |u|/ω, found on ray I by the δ-line (the point whose velocity is
   |u|) and laid off with the compass on the pole normal, on the side −J u/ω;
6. for a third point C: v_C by the δ-line, u_C the projection of u perpendicular to ray PC; the
   line through the tips of v_C and u_C meets the ray PC in the centre of curvature K_C.

Velocities are drawn on the mechanism at kv (mechanism lengths per velocity unit; Rosenauer's
choice, kv = 1/|ω_crank|, by default). Checked against :mod:`linkwork.instant`: u, W₀, the centre
of curvature of C.
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role, pt
from ..topology.constructibility import script
from ..instant import curvature_centre, instant
from ..model import Mechanism, Revolute
from ._common import as_solution, cross, norm, perp, singular_positions
from ._coupler import coupler_data, draw_given, draw_pole
from ._plan import upper

SOURCE = "Pöschl §35; Rosenauer §44 (Hartmann, Example 16)"


def hartmann(mech: Mechanism, inputs, *, link: str | None = None, point: str | None = None,
             kv: float | None = None) -> Construction:
    """Hartmann's construction on ``link`` (default: the coupler) at ``inputs``."""
    sol = as_solution(mech, inputs)
    cd = coupler_data(mech, sol, link, point)
    n = len(sol)
    nA, nB = upper(cd.names[0]), upper(cd.names[1])
    # the given velocity of A: A's link turns about C_a (a frame pivot)
    vA = sol.point(cd.names[0]).velocity
    if kv is None:
        w0 = np.nanmax(abs(sol.link(mech.drivers[0].driven).omega)) if isinstance(
            mech.joint(mech.drivers[0].joint), Revolute) else 0.0
        vmax = np.nanmax(norm(vA))
        kv = 0.5 * cd.L / vmax if not w0 > 0 else 0.6 / w0
        if not np.isfinite(kv) or kv <= 0:
            kv = 1.0
    b = Builder("hartmann", "Hartmann's construction (pole-transfer velocity, centres of curvature)",
                SOURCE, n)
    singular_positions(b, sol)
    b.own_labels = True
    draw_given(b, cd)
    P, r1, r2 = draw_pole(b, cd)
    A, B = cd.A, cd.B
    b.step(f"Given: the velocity v_{nA} of {nA} (\u27c2 ray I). The line from its tip to {cd.centre_names[0]} "
           f"meets the perpendicular to ray I through P in the tip of u_{nA}.")
    ta = pt(A.xy + kv * vA)
    b.arrow("vA", A, ta, Role.GIVEN, "v_" + script(cd.names[0]), kind="velocity")
    l1 = b.join("taCa", ta, cd.Ca)
    p1 = b.perpendicular("p1", P, r1)
    tuA = b.meet("tuA", l1, p1, Role.AUXILIARY, None, k1="taCa", k2="p1", finite=False)
    b.arrow("uA", P, tuA, Role.AUXILIARY, "u_" + script(cd.names[0]), kind="velocity")
    b.step(f"Velocity of {nB}: the line P to the tip of v_{nA} makes the angle \u03b4 (tan \u03b4 = \u03c9) "
           f"with ray I; lay off \u03b4 at P from ray II; it meets the perpendicular to ray II at {nB} in the "
           f"tip of v_{nB}. The line from that tip to {cd.centre_names[1]} meets the perpendicular to ray "
           f"II through P in the tip of u_{nB}.")
    b.join("delta1", P, ta, Role.AUXILIARY, "\u03b4")
    # the sense: δ is laid off from ray II with the same orientation as from ray I (P→A) to P→tip
    dline = b.copy_angle("delta2", P, A, ta, P, B, radius=0.3 * norm(A.xy - P.xy))
    nB_ = b.perpendicular("nvB", B, r2)
    tb = b.meet("tb", dline, nB_, Role.AUXILIARY, None, k1="delta2", k2="nvB",
                why=f"{nB} lies at the pole")
    b.arrow("vB", B, tb, Role.RESULT, "v_" + script(cd.names[1]), kind="velocity")
    l2 = b.join("tbCb", tb, cd.Cb)
    p2 = b.perpendicular("p2", P, r2)
    tuB = b.meet("tuB", l2, p2, Role.AUXILIARY, None, k1="tbCb", k2="p2", finite=False)
    b.arrow("uB", P, tuB, Role.AUXILIARY, "u_" + script(cd.names[1]), kind="velocity")
    b.step("The parallel to ray I through the tip of u_A and the parallel to ray II through the tip of "
           "u_B meet in the tip of the pole-transfer velocity u; its direction is the pole tangent t.")
    q1 = b.parallel("q1", tuA, r1)
    q2 = b.parallel("q2", tuB, r2)
    tu = b.meet("tu", q1, q2, Role.RESULT, None, k1="q1", k2="q2",
                why="rays I and II coincide, so the pole velocity is undetermined")
    b.arrow("u", P, tu, Role.RESULT, "u", kind="velocity")
    b.step("W_0 is the point of the pole normal whose velocity equals u (D = u/\u03c9): the parallel to ray I "
           "at the distance |u| meets the \u03b4-line in X; its foot on ray I is at the distance D from P; "
           "lay D off on the pole normal.")
    u_len = norm(tu.xy - P.xy)
    eA = vA / norm(vA)[:, None]
    # the parallel to ray I through A + |u| e_A, on v_A's side
    U = pt(A.xy + u_len[:, None] * eA)
    par = b.parallel("par_u", U, r1)
    X = b.meet("X", par, b.elements["delta1"].obj, Role.AUXILIARY, "X", k1="par_u", k2="delta1",
               why="the pole velocity is zero")
    Xf = b.foot("Xf", X, r1, Role.AUXILIARY, None, k="ray1")
    D = norm(Xf.xy - P.xy)
    # the pole normal: perpendicular to u at P, W₀ on the side J⁻¹u·sign(ω) (ω's sense from v_A)
    w_sense = np.sign(cross(A.xy - P.xy, vA))
    b.perpendicular("normal", P, b.join("tline", P, tu, Role.RESULT, "t"), Role.AUXILIARY, "n")
    d_n = -perp(tu.xy - P.xy) * w_sense[:, None]
    d_n = d_n / norm(d_n)[:, None]
    W0 = b.point("W0", pt(P.xy + D[:, None] * d_n), Role.RESULT, "W_0")
    b.circle("W0.arc", P, D, Role.AUXILIARY, arcs=(Xf, W0))  # the compass carries D over
    b.extend("normal", W0)
    ins = instant(sol, cd.link)
    L, o = cd.L, cd.origin
    if cd.C is not None:
        nC = upper(cd.c_name)
        c = cd.c_name  # the file's name (as written, in the labels below)
        b.step(f"Third point {nC}: its velocity v_{c} by the \u03b4-angle from ray P{nC}; u_{c}, the projection of u "
               f"perpendicular to ray P{nC}; the line through the tips of v_{c} and u_{c} meets the ray in the "
               f"centre of curvature K_{c}.")
        C = cd.C
        r3 = b.join("ray3", P, C, Role.AUXILIARY, "III")
        dl3 = b.copy_angle("delta3", P, A, ta, P, C, radius=0.25 * norm(A.xy - P.xy))
        tc = b.meet("tc", dl3, b.perpendicular("nvC", C, r3), Role.AUXILIARY, None, k1="delta3", k2="nvC")
        b.arrow("vC", C, tc, Role.RESULT, "v_" + script(c), kind="velocity")
        p3 = b.perpendicular("p3", P, r3)
        tuC = b.foot("tuC", tu, p3, Role.AUXILIARY, None, k="p3")
        b.arrow("uC", P, tuC, Role.AUXILIARY, "u_" + script(c), kind="velocity")
        K = b.meet("KC", b.join("tips", tc, tuC), r3, Role.RESULT, "K_" + script(c), k1="tips", k2="ray3",
                   finite=False)
        b.compare_points("KC", f"K_{cd.c_name}", f"centre of curvature of {cd.c_name}", K,
                         curvature_centre(sol, cd.link, cd.c_name).centre, L, o)
    u_ref = ins.pole_velocity.xy
    b.compare("u", "u", "pole-transfer velocity", (tu.xy - P.xy) / kv, u_ref,
              np.maximum(norm(vA), norm(u_ref)), f"{mech.length_unit}/s")
    b.compare_points("W0", "W_0", "inflection pole", W0, ins.inflection_pole, L, o)
    vB = sol.point(cd.names[1]).velocity
    b.compare("vB", f"v_{nB}", f"velocity of {nB} by the \u03b4-angle", (tb.xy - B.xy) / kv, vB,
              np.maximum(norm(vA), norm(vB)), f"{mech.length_unit}/s")
    return b.finish()
