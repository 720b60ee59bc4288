"""Inflection and Bresse circles from the velocities and accelerations of two points
(Rosenauer ch. XIV, §57; *Wendekreis und Bresse-Kreis aus Geschwindigkeiten und
Beschleunigungen zweier Punkte*).

Owns :func:`inflection_from_two_points`. The state of motion of a link is fixed by the velocities
and accelerations of two of its points A, B. These are the *given* data; here they are taken from
the polar velocity and acceleration plans of :mod:`.acceleration_plan` (themselves ruler
constructions from the input), drawn at A and B at the scales kv and ka.

1. The normals to v_A at A and to v_B at B meet in the pole P.
2. The acceleration centre Γ by the four-circle construction (Rosenauer §57, Fig. 170, after
   Beyer): the lines of a_A and a_B meet in K; the circle through A, B, K and the circle through
   the tips a, b and K meet again in Γ (Γ sees A, B under the same angle as the accelerations, and
   triangles ΓAa ~ ΓBb). If a_A ∥ a_B (K at infinity) the circles are the lines AB and ab, and
   Γ = AB ∩ ab (the limiting construction).
3. γ = ∠(a_A, AΓ) is the angle every acceleration makes with the line to Γ (§54); laid off at P
   from PΓ in the opposite sense it gives the pole normal PN (∠W₀PΓ = γ, §53); the pole tangent is
   perpendicular to it at P.
4. The perpendicular bisector of PΓ meets the pole normal in the centre of the inflection circle
   and the pole tangent in the centre of the Bresse circle; both circles pass through P and Γ.
   With α = 0 (γ = 0) the Bresse circle becomes the pole normal itself (its centre at infinity on
   the pole tangent) — the limiting case, reported.

Checked against :mod:`linkwork.instant`: P, Γ, the inflection pole W₀ (the end of the diameter
through P) and the tangential pole H of the Bresse circle.
"""

from __future__ import annotations

import numpy as np

from ..drawing.construction import Builder, Construction, Role, pt
from ..geometry import Circle, Point, Vector
from ..geometry.constructions import perpendicular_bisector
from ..instant import instant
from ..model import Mechanism
from ._common import as_solution, conjugate_pairs, coupler_link, cross, norm
from ._plan import AccelerationConstruction, VelocityConstruction, upper

SOURCE = "Rosenauer ch. XIV (Fig. 327), §53–54, §57 (four-circle construction of \u0393)"


def inflection_from_two_points(mech: Mechanism, inputs, *, link: str | None = None,
                               points: tuple[str, str] | None = None,
                               kv: float | None = None, ka: float | None = None) -> Construction:
    """Inflection and Bresse circles of ``link`` from v and a of two of its points."""
    sol = as_solution(mech, inputs)
    n = len(sol)
    link = link or _default_link(mech)
    from ..model import Revolute
    from ..errors import InputError
    for j in mech.joints:
        if isinstance(j, Revolute) and set(j.links) == {link, mech.frame}:
            raise InputError(f"link '{link}' turns about the frame pivot {j.point}: its pole stays at "
                             f"{j.point} and its inflection and Bresse circles shrink to that point; "
                             "choose a coupler (--link)")
    pts = points or _two_points(mech, link)
    nA, nB = pts
    # the given vectors, from the plans (a ruler construction of their own, not drawn here)
    hidden = Builder("plans", "", "", n, spaces={"mechanism": "length", "velocity": "velocity",
                                                  "acceleration": "acceleration"})
    vc = VelocityConstruction(hidden, mech, sol, "plan")
    vc.run()
    ac = AccelerationConstruction(hidden, vc)
    ac.run()
    A, B = sol.point(nA).position, sol.point(nB).position
    vA, vB = (vc.velocity(X, vc.image(link, p, X, draw=False)) for X, p in ((A, nA), (B, nB)))
    aA, aB = (ac.image(link, p, X, draw=False) for X, p in ((A, nA), (B, nB)))
    L = mech.length_scale
    if kv is None:
        kv = 0.35 * L / max(np.nanmax(norm(vA)), np.nanmax(norm(vB)), 1e-300)
    if ka is None:
        ka = 0.35 * L / max(np.nanmax(norm(aA)), np.nanmax(norm(aB)), 1e-300)
    b = Builder("two-points", "Inflection and Bresse circles from the velocities and accelerations "
                "of two points", SOURCE, n)
    b.own_labels = True
    uA, uB = upper(nA), upper(nB)
    Ap, Bp = pt(A), pt(B)
    b.step(f"Given: the points {uA}, {uB} of the {link} with their velocities and accelerations "
           "(from the velocity and acceleration plans).")
    b.point("A", Ap, Role.GIVEN, uA)
    b.point("B", Bp, Role.GIVEN, uB)
    b.segment("AB", Ap, Bp, Role.GIVEN)
    b.arrow("vA", Ap, pt(A + kv * vA), Role.GIVEN, f"v_{uA}", kind="velocity")
    b.arrow("vB", Bp, pt(B + kv * vB), Role.GIVEN, f"v_{uB}", kind="velocity")
    ta, tb = pt(A + ka * aA), pt(B + ka * aB)
    b.arrow("aA", Ap, ta, Role.GIVEN, f"a_{uA}", kind="acceleration")
    b.arrow("aB", Bp, tb, Role.GIVEN, f"a_{uB}", kind="acceleration")

    b.step("The normals to the velocities at the two points meet in the pole P.")
    nA_ = b.perpendicular("nA", Ap, b.join("lvA", Ap, pt(A + kv * vA), Role.AUXILIARY))
    nB_ = b.perpendicular("nB", Bp, b.join("lvB", Bp, pt(B + kv * vB), Role.AUXILIARY))
    P = b.meet("P", nA_, nB_, Role.RESULT, "P", k1="nA", k2="nB",
               why="the velocities are parallel: the link translates instantaneously (pole at infinity)")

    b.step(f"The lines of a_{uA} and a_{uB} meet in K; the circle through {uA}, {uB}, K and the circle "
           f"through the tips a, b and K meet again in the acceleration centre \u0393 (Rosenauer \u00a757).")
    la = b.join("la", Ap, ta)
    lb = b.join("lb", Bp, tb)
    K = b.meet("K", la, lb, Role.AUXILIARY, "K", k1="la", k2="lb", finite=False)
    G = _gamma(b, Ap, Bp, ta, tb, K)

    b.step("\u03b3 = \u2220(a_A, A\u0393) is the angle of every acceleration with its line to \u0393; lay it "
           "off at P from P\u0393 in the opposite sense: the pole normal n. The pole tangent t is "
           "perpendicular to it at P.")
    b.join("PG", P, G, Role.AUXILIARY)
    normal = b.copy_angle("normal", Ap, ta, G, P, G, sense=-1, radius=0.25 * L, role=Role.RESULT, label="n")
    tangent = b.perpendicular("tangent", P, normal, Role.RESULT, "t")

    b.step("The perpendicular bisector of P\u0393 meets the pole normal in the centre of the inflection "
           "circle and the pole tangent in the centre of the Bresse circle; both circles pass through P "
           "and \u0393.")
    bis = b.add("bis", _bisector(P, G), Role.AUXILIARY, None, kind="line", span=[P, G])
    M1 = b.meet("M1", bis, normal, Role.AUXILIARY, "M_1", k1="bis", k2="normal",
                why="\u0393 lies on the pole tangent")
    M2 = b.meet("M2", bis, tangent, Role.AUXILIARY, "M_2", k1="bis", k2="tangent", finite=False)
    b.limiting(M2.is_infinite & ~b.bad, "the angular acceleration is zero (\u03b3 = 0): \u0393 is the "
               "inflection pole and the Bresse circle is the pole normal itself")
    b.circle("wendekreis", M1, P, Role.RESULT, "inflection circle", kind="inflection")
    b.circle("bresse", pt(np.where(M2.is_finite[:, None], M2.coords[:, :2], np.nan)), P, Role.RESULT,
             "Bresse circle", kind="bresse")
    W0 = pt(2 * M1.xy - P.xy)
    b.point("W0", W0, Role.RESULT, "W_0")
    # the tangential pole H: the far end of the Bresse diameter (at infinity along t when α = 0)
    H = Point(np.where(M2.is_finite[:, None],
                       np.concatenate([2 * np.nan_to_num(M2.xy) - P.xy, np.ones((n, 1))], 1), M2.coords))
    ins = instant(sol, link)
    o = np.mean(np.array(list(mech.points.values())), axis=0)
    b.compare_points("P", "P", "pole", P, ins.pole, L, o)
    b.compare_points("G", "\u0393", "acceleration centre", G, ins.acceleration_pole, L, o)
    b.compare_points("W0", "W_0", "inflection pole", W0, ins.inflection_pole, L, o)
    b.compare_points("H", "H", "tangential pole (end of the Bresse diameter)", H, ins.tangential_pole, L, o)
    return b.finish()


def _two_points(mech: Mechanism, link: str) -> tuple[str, str]:
    """The two points of ``link`` farthest apart (distinct points are needed)."""
    from itertools import combinations
    from ..errors import InputError
    pts = list(dict.fromkeys(mech.link(link).points))
    best, d = None, 1e-9 * mech.length_scale
    for p, q in combinations(pts, 2):
        dd = float(np.hypot(*(mech.points[p] - mech.points[q])))
        if dd > d:
            best, d = (p, q), dd
    if best is None:
        raise InputError(f"link '{link}' needs two distinct points")
    return best


def _default_link(mech: Mechanism) -> str:
    """The coupler, or else the first moving link with two distinct points that does not turn
    about a frame pivot (for those the circles collapse onto the pivot)."""
    try:
        return coupler_link(mech)
    except Exception:
        pass
    from ..model import Revolute
    pivoted = {(set(j.links) - {mech.frame}).pop() for j in mech.joints
               if isinstance(j, Revolute) and mech.frame in j.links}
    for ln in list(mech.moving_links):
        if ln not in pivoted:
            try:
                _two_points(mech, ln)
                return ln
            except Exception:
                continue
    return mech.moving_links[-1]


def _bisector(P: Point, G: Point):
    from ..drawing.construction import safe_join
    M = (P.xy + G.xy) / 2
    d = G.xy - P.xy
    line, _ = safe_join(pt(M), Point(np.concatenate([-d[:, 1:2], d[:, :1], np.zeros((len(d), 1))], 1)))
    return line


def _gamma(b: Builder, A: Point, B: Point, ta: Point, tb: Point, K: Point) -> Point:
    """Γ: second intersection of the circles (A, B, K) and (a, b, K); lines AB, ab when K = ∞."""
    n = b.n
    Kf = K.is_finite
    Kxy = np.where(Kf[:, None], K.coords[:, :2], 0.0)
    # circles through three points (only where K is finite)
    c1 = _circumcircle(A.xy, B.xy, Kxy)
    c2 = _circumcircle(ta.xy, tb.xy, Kxy)
    # radical axis of the two circles passes through K and Γ: Γ = reflection of K in the line of centres
    o1, o2 = c1, c2
    d = o2 - o1
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.sum((Kxy - o1) * d, -1) / np.sum(d * d, -1)
    foot = o1 + t[:, None] * d
    G_circ = 2 * foot - Kxy
    # limiting: K at infinity, Γ = AB ∩ ab
    ab = np.cross(A.coords, B.coords)
    tt = np.cross(ta.coords, tb.coords)
    x = np.cross(ab, tt)
    with np.errstate(invalid="ignore", divide="ignore"):
        G_lin = x[:, :2] / x[:, 2:]
    G = np.where(Kf[:, None], G_circ, G_lin)
    b.limiting(~Kf & ~b.bad, "the accelerations of the two points are parallel (K at infinity): the "
               "circles become the lines AB and ab, and \u0393 is their intersection")
    r1 = np.linalg.norm(A.xy - c1, axis=-1)
    r2 = np.linalg.norm(ta.xy - c2, axis=-1)
    b.circle("kAB", pt(np.where(Kf[:, None], c1, np.nan)), np.where(Kf, r1, np.nan), Role.AUXILIARY)
    b.circle("kab", pt(np.where(Kf[:, None], c2, np.nan)), np.where(Kf, r2, np.nan), Role.AUXILIARY)
    return b.point("G", pt(G), Role.RESULT, "\u0393")


def _circumcircle(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> np.ndarray:
    b, c = q - p, r - p
    d = 2 * cross(b, c)
    with np.errstate(invalid="ignore", divide="ignore"):
        ux = (c[:, 1] * np.sum(b * b, -1) - b[:, 1] * np.sum(c * c, -1)) / d
        uy = (b[:, 0] * np.sum(c * c, -1) - c[:, 0] * np.sum(b * b, -1)) / d
    return p + np.stack([ux, uy], -1)
