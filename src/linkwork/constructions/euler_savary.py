"""Euler–Savary by ruler: Rosenauer §19 Tasks I–III on a coupler (*Euler–Savary-Gleichung*).

Owns :func:`euler_savary`. Given two points A, B of a moving link with the centres of
curvature C_a, C_b of their paths (the four-bar's frame pivots; a point at infinity for a
crosshead on a straight guide):

1. the path normals meet in the pole P (rays I, II);
2. Task I on ray I gives its inflection point W_a, Task I on ray II gives W_b;
3. the perpendiculars to the rays at W_a and W_b meet in the inflection pole W₀ (§21), the circle
   on PW₀ is the inflection circle;
4. for a third point C of the link: the ray PC meets the inflection circle again in W_c, the
   foot of W₀ on the ray (Thales); Task II gives the centre of curvature C_c of C's path;
5. Task III on ray I, from P, W_a and C_a, gives back the point A (a check of the three tasks).

Every constructed point is compared with the curvature layer (:mod:`linkwork.instant`): W₀ and
the pole with ``instant``, W_a and W_b with the feet of its W₀ on the rays, C_c with
``curvature_centre`` — all from the engine's exact second-order solution.
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Construction, Role, pt
from ..instant import curvature_centre, instant
from ..model import Mechanism
from ._common import as_solution, dot, singular_positions
from ._coupler import coupler_data, draw_given, draw_pole, inflection_from_two_rays, task_I, task_II, task_III
from ._plan import upper
from ..topology.constructibility import script

SOURCE = "Rosenauer §18–19 (Euler–Savary, Tasks I–III), §21 (W\u2080 from two rays)"


def foot(W: np.ndarray, P: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Foot of W on the line PX (the second intersection of the ray with the circle on PW)."""
    d = X - P
    with np.errstate(invalid="ignore", divide="ignore"):
        return P + (dot(W - P, d) / dot(d, d))[:, None] * d


def euler_savary(mech: Mechanism, inputs, *, link: str | None = None,
                 point: str | None = None) -> Construction:
    """Euler–Savary Tasks I–III on ``link`` (default: the coupler) at ``inputs``."""
    sol = as_solution(mech, inputs)
    cd = coupler_data(mech, sol, link, point)
    b = Builder("euler-savary", "Euler\u2013Savary by ruler (Rosenauer \u00a719, Tasks I\u2013III)", SOURCE,
                len(sol))
    singular_positions(b, sol)
    b.own_labels = True
    draw_given(b, cd)
    P, r1, r2 = draw_pole(b, cd)
    nA, nB = upper(cd.names[0]), upper(cd.names[1])
    Wa = task_I(b, "T1a", P, cd.A, cd.Ca, r1, names=(nA, cd.centre_names[0], "W_" + script(cd.names[0])),
                ray_key="ray1", label="W_" + script(cd.names[0]), tag="1")
    Wb = task_I(b, "T1b", P, cd.B, cd.Cb, r2, names=(nB, cd.centre_names[1], "W_" + script(cd.names[1])),
                ray_key="ray2", label="W_" + script(cd.names[1]), tag="2")
    W0 = inflection_from_two_rays(b, P, r1, r2, Wa, Wb)
    ins = instant(sol, cd.link)
    L, o = cd.L, cd.origin
    Pa, Wa_ref = ins.pole.xy, ins.inflection_pole.xy
    Cc = None
    if cd.C is not None:
        nC = upper(cd.c_name)
        b.step(f"The ray P{nC} meets the inflection circle again in W_{script(cd.c_name)}, the foot of "
               f"the perpendicular from W_0 (Thales).")
        r3 = b.join("ray3", P, cd.C, Role.AUXILIARY, "III")
        Wc = b.foot("Wc", W0, r3, Role.AUXILIARY, "W_" + script(cd.c_name), k="ray3")
        Cc = task_II(b, "T2c", P, cd.C, Wc, r3, names=(nC, "W_" + script(cd.c_name), "C_" + script(cd.c_name)),
                     ray_key="ray3", label="C_" + script(cd.c_name), tag="3")
    A3 = task_III(b, "T3a", P, Wa, cd.Ca, r1, names=("W_" + script(cd.names[0]), cd.centre_names[0], nA + "'"),
                  ray_key="ray1", label=nA + "'", tag="4")
    # ---- checks against the curvature layer
    b.compare_points("P", "P", "pole", P, ins.pole, L, o)
    b.compare_points("W0", "W_0", "inflection pole", W0, ins.inflection_pole, L, o)
    b.compare_points("Wa", f"W_{nA}", f"inflection point on ray P{nA}", Wa,
                     pt(foot(Wa_ref, Pa, cd.A.xy)), L, o)
    b.compare_points("Wb", f"W_{nB}", f"inflection point on ray P{nB}", Wb,
                     pt(foot(Wa_ref, Pa, cd.B.xy)), L, o)
    if Cc is not None:
        b.compare_points("Cc", f"C_{cd.c_name}", f"centre of curvature of the path of {cd.c_name}", Cc,
                         curvature_centre(sol, cd.link, cd.c_name).centre, L, o)
    b.compare_points("A3", nA + "'", f"Task III gives back {nA}", A3, cd.A, L, o)
    return b.finish()
