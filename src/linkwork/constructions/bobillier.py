"""Bobillier's construction of the inflection circle and the collineation axis
(*Kollineationsachse*, *kollineācijas ass*), with Aronhold's transfer to a third ray.

Owns :func:`bobillier` (Rosenauer §21–25, Pöschl §34). Given two points A, B of a moving link
and the centres of curvature C_a, C_b of their paths:

1. the path normals meet in the pole P;
2. Q = AB ∩ C_aC_b; PQ is the **collineation axis** of rays I and II (the lines joining
   conjugate points of the two rays all meet on it);
3. through P the parallel to C_aC_b meets AB in S; through S the parallel to PQ meets ray I in W_a
   and ray II in W_b (W_aW_b ∥ PQ);
4. the perpendiculars to the rays at W_a and W_b meet in W₀; the circle on PW₀ is the inflection
   circle; the pole tangent t is perpendicular to PW₀ (Bobillier's theorem: ∠(t, ray I) =
   ∠(ray II, PQ));
5. for a third point C (Aronhold §24, Pöschl Beispiel 9): the ray PC meets the inflection circle
   in W_c; by the chord theorem (§25) the collineation axis of rays I and III is the parallel
   to W_aW_c through P; F = AC ∩ that axis, and FC_a meets ray III in the centre of curvature
   C_c. The same with ray II (axis ∥ W_bW_c, F' = BC ∩ axis, F'C_b) must meet ray III in the
   same point — Pöschl's check, F, F', F'' on one line.

A crosshead on a straight guide has C at infinity: the line C_aC_b is then the parallel to ray II
through C_a (Rosenauer §26, the slider-crank's coupler), and W_b = B. Checked against
:mod:`linkwork.instant` (pole, W₀, pole tangent, collineation axis, centre of curvature of C).
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role
from ..geometry import Point
from ..instant import collineation_axis, curvature_centre, instant
from ..model import Mechanism
from ._common import singular_positions, as_solution
from ._coupler import coupler_data, draw_given, draw_pole, inflection_from_two_rays
from ._plan import upper
from ..topology.constructibility import script

SOURCE = "Rosenauer §21–25 (Bobillier, collineation axis, Aronhold), Pöschl §34, Beispiel 9"


def _direction(line) -> Point:
    """The point at infinity of each line (NaN for undefined lines and the line at infinity)."""
    c = np.asarray(line.coords)
    d = np.stack([c[..., 1], -c[..., 0], np.zeros(c.shape[:-1])], axis=-1)
    bad = ~np.isfinite(d).all(-1) | (d == 0).all(-1)
    return Point(np.where(bad[..., None], np.nan, d))


def bobillier(mech: Mechanism, inputs, *, link: str | None = None,
              point: str | None = None) -> Construction:
    """Bobillier's construction on ``link`` (default: the coupler) at ``inputs``."""
    sol = as_solution(mech, inputs)
    cd = coupler_data(mech, sol, link, point)
    b = Builder("bobillier", "Bobillier's construction, collineation axis, Aronhold's transfer",
                SOURCE, len(sol))
    singular_positions(b, sol)
    b.own_labels = True
    draw_given(b, cd)
    P, r1, r2 = draw_pole(b, cd)
    nA, nB = upper(cd.names[0]), upper(cd.names[1])
    la, lb = cd.centre_names
    for Cx, nm in ((cd.Ca, la), (cd.Cb, lb)):
        with np.errstate(invalid="ignore"):
            at_p = Cx.is_finite & (np.linalg.norm(Cx.xy - P.xy, axis=-1) <= 1e-9 * cd.L)
        b.degenerate(at_p & ~b.bad, f"the centre of curvature {nm} lies at the pole, so the line "
                     f"{la}{lb} runs along a ray and Q and S fall onto it; Bobillier's construction gives "
                     "no inflection circle here (use Euler\u2013Savary, construction euler-savary)")
    b.step(f"The lines {nA}{nB} and {la}{lb} meet in Q; PQ is the collineation axis of rays I and II.")
    AB = b.join("lAB", cd.A, cd.B)
    CC = b.join("lCC", cd.Ca, cd.Cb)
    Q = b.meet("Q", AB, CC, Role.AUXILIARY, "Q", k1="lAB", k2="lCC", finite=False)
    axis = b.join("axis", P, Q, Role.RESULT, "a", why="Q coincides with the pole")
    b.step(f"Through P draw the parallel to {la}{lb}; it meets {nA}{nB} in S. Through S draw the parallel "
           f"to the collineation axis; it meets ray I in W_{script(cd.names[0])} and ray II in "
           f"W_{script(cd.names[1])}.")
    PS = b.parallel("PS", P, CC)
    S = b.meet("S", PS, AB, Role.AUXILIARY, "S", k1="PS", k2="lAB", finite=not np.all(cd.Ca.is_infinite & cd.Cb.is_infinite),
               why=f"{nA}{nB} is parallel to {la}{lb} (Q at infinity), so S falls to infinity and "
                   "Bobillier's construction gives no inflection points; use Euler\u2013Savary Task I "
                   "(construction euler-savary) at this position")
    SW = b.parallel("SW", S, axis)
    Wa = b.meet("Wa", SW, r1, Role.RESULT, "W_" + script(cd.names[0]), k1="SW", k2="ray1", finite=False)
    Wb = b.meet("Wb", SW, r2, Role.RESULT, "W_" + script(cd.names[1]), k1="SW", k2="ray2", finite=False)
    # a point on a straight guide is its own inflection point (centre at infinity, Rosenauer §26)
    inf_a, inf_b = cd.Ca.is_infinite, cd.Cb.is_infinite
    if np.any(inf_a | inf_b):
        b.step("A point guided on a straight line has its centre of curvature at infinity: it is its "
               "own inflection point (Rosenauer \u00a726, W = A).")
        Wa = Point(np.where(inf_a[:, None], cd.A.coords, Wa.coords))
        Wb = Point(np.where(inf_b[:, None], cd.B.coords, Wb.coords))
        b.point("Wa*", Wa, Role.RESULT, None)
        b.point("Wb*", Wb, Role.RESULT, None)
    W0 = inflection_from_two_rays(b, P, r1, r2, Wa, Wb)
    tangent = b.elements["tangent"].obj
    ins = instant(sol, cd.link)
    L, o = cd.L, cd.origin
    if cd.C is not None:
        nC = upper(cd.c_name)
        c = script(cd.c_name)
        b.step(f"Third ray P{nC}: it meets the inflection circle in W_{c} (foot of W_0). By the chord theorem "
               f"the collineation axis of rays I and III is the parallel to W_{script(cd.names[0])}W_{c} "
               f"through P; it meets {nA}{nC} in F; F{la} meets ray III in the centre of curvature C_{c}.")
        r3 = b.join("ray3", P, cd.C, Role.AUXILIARY, "III")
        Wc = b.foot("Wc", W0, r3, Role.AUXILIARY, f"W_{c}", k="ray3")
        ax13 = b.parallel("axis13", P, b.join("WaWc", Wa, Wc), Role.AUXILIARY, "a_13")
        F1 = b.meet("F1", b.join("lAC", cd.A, cd.C), ax13, Role.AUXILIARY, "F", k1="lAC", k2="axis13",
                    finite=False)
        Cc = b.meet("Cc", b.join("F1Ca", F1, cd.Ca), r3, Role.RESULT, f"C_{c}", k1="F1Ca", k2="ray3",
                    finite=False)
        b.step(f"Check with ray II: the axis of rays II and III is the parallel to W_{script(cd.names[1])}W_{c} "
               f"through P; it meets {nB}{nC} in F'; F'{lb} meets ray III in the same point C_{c}.")
        ax23 = b.parallel("axis23", P, b.join("WbWc", Wb, Wc), Role.AUXILIARY, "a_23")
        F2 = b.meet("F2", b.join("lBC", cd.B, cd.C), ax23, Role.AUXILIARY, "F'", k1="lBC", k2="axis23",
                    finite=False)
        Cc2 = b.meet("Cc2", b.join("F2Cb", F2, cd.Cb), r3, Role.AUXILIARY, None, k1="F2Cb", k2="ray3",
                     finite=False)
        ref = curvature_centre(sol, cd.link, cd.c_name).centre
        b.compare_points("Cc", f"C_{cd.c_name}", f"centre of curvature of {cd.c_name} (via ray I)", Cc, ref, L, o)
        b.compare_points("Cc2", f"C_{cd.c_name}'", f"centre of curvature of {cd.c_name} (via ray II)", Cc2, ref, L, o)
    b.compare_points("P", "P", "pole", P, ins.pole, L, o)
    b.compare_points("W0", "W_0", "inflection pole", W0, ins.inflection_pole, L, o)
    col = collineation_axis(sol, cd.link, cd.names[0], cd.names[1])
    b.compare_points("axis", "a", "direction of the collineation axis", _direction(axis),
                     _direction(col.axis), 1.0)
    t_ref = Point.at_infinity(np.where(np.isfinite(ins.pole_tangent.xy), ins.pole_tangent.xy, np.nan))
    b.compare_points("t", "t", "direction of the pole tangent", _direction(tangent), t_ref, 1.0)
    return b.finish()
