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

from .construction import Builder, Construction, Role, pt
from ..topology.constructibility import script
from ..geometry import Point
from ..instant import instant
from ..model import Mechanism
from ._common import as_solution, coupler_link, cross, norm, singular_positions
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
    # drawing scales per position (the vectors about a third of the mechanism), so that every
    # position is drawn, and constructed, as it would be on its own sheet
    if kv is None:
        kv = (0.35 * L / np.maximum(np.maximum(norm(vA), norm(vB)), 1e-300))[:, None]
    if ka is None:
        ka = (0.35 * L / np.maximum(np.maximum(norm(aA), norm(aB)), 1e-300))[:, None]
    b = Builder("two-points", "Inflection and Bresse circles from the velocities and accelerations "
                "of two points", SOURCE, n)
    singular_positions(b, sol)
    b.own_labels = True
    uA, uB = upper(nA), upper(nB)
    Ap, Bp = pt(A), pt(B)
    b.step(f"Given: the points {uA}, {uB} of the {link} with their velocities and accelerations "
           "(from the velocity and acceleration plans).")
    b.point("A", Ap, Role.GIVEN, uA)
    b.point("B", Bp, Role.GIVEN, uB)
    b.segment("AB", Ap, Bp, Role.GIVEN)
    b.arrow("vA", Ap, pt(A + kv * vA), Role.GIVEN, "v_" + script(nA), kind="velocity")
    b.arrow("vB", Bp, pt(B + kv * vB), Role.GIVEN, "v_" + script(nB), kind="velocity")
    ta, tb = pt(A + ka * aA), pt(B + ka * aB)
    b.arrow("aA", Ap, ta, Role.GIVEN, "a_" + script(nA), kind="acceleration")
    b.arrow("aB", Bp, tb, Role.GIVEN, "a_" + script(nB), kind="acceleration")

    b.step("The normals to the velocities at the two points meet in the pole P.")
    nA_ = b.perpendicular("nA", Ap, b.join("lvA", Ap, pt(A + kv * vA), Role.AUXILIARY))
    nB_ = b.perpendicular("nB", Bp, b.join("lvB", Bp, pt(B + kv * vB), Role.AUXILIARY))
    P = b.meet("P", nA_, nB_, Role.RESULT, "P", k1="nA", k2="nB",
               why="the velocities are parallel: the link translates instantaneously (pole at infinity)")
    from ._coupler import far_pole
    far_pole(b, P, L, np.mean(np.array(list(mech.points.values())), axis=0))

    b.step(f"Draw a_{uA} \u2212 a_{uB} at {uA} (to D): \u03b3 = \u2220D{uA}{uB}. Lay off \u03b3 from a_{uA} at "
           f"{uA} and from a_{uB} at {uB}, in the same sense as from {uA}D to {uA}{uB}: the two lines meet in "
           "the acceleration centre \u0393 (Zhukovsky's theorem, Rosenauer \u00a754, \u00a757).")
    D = pt(A + ka * (aA - aB))
    b.arrow("AD", Ap, D, Role.AUXILIARY, "D", kind="acceleration")
    gA = b.copy_angle("gA", Ap, D, Bp, Ap, ta, radius=0.2 * L)
    gB = b.copy_angle("gB", Ap, D, Bp, Bp, tb, radius=0.2 * L)
    G = _gamma(b, Ap, Bp, ta, tb, gA, gB)

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
    from .construction import safe_join
    M = (P.xy + G.xy) / 2
    d = G.xy - P.xy
    line, _ = safe_join(pt(M), Point(np.concatenate([-d[:, 1:2], d[:, :1], np.zeros((len(d), 1))], 1)))
    return line


def _gamma(b: Builder, A: Point, B: Point, ta: Point, tb: Point, gA, gB) -> Point:
    """Γ = intersection of the two γ-lines; where they (nearly) coincide (Γ on the line AB) the
    four-circle construction (Rosenauer §57, Fig. 170) is used instead: the circles (A, B, K) and
    (a, b, K), K the meet of the acceleration lines, or by Miquel's theorem (A, a, M) and (B, b, M),
    M = AB ∩ ab — whichever pair is better shaped."""
    u1, u2 = (np.array(ln.coords, float) for ln in (gA, gB))
    L = b.length or 1.0
    u1[:, 2] /= L
    u2[:, 2] /= L
    with np.errstate(invalid="ignore", divide="ignore"):
        u1 /= np.linalg.norm(u1, axis=1, keepdims=True)
        u2 /= np.linalg.norm(u2, axis=1, keepdims=True)
    x = np.cross(u1, u2)
    sine = abs(x[:, 2]) / np.maximum(np.linalg.norm(u1[:, :2], axis=1) * np.linalg.norm(u2[:, :2], axis=1), 1e-300)
    with np.errstate(invalid="ignore", divide="ignore"):
        Gz = x[:, :2] * L / x[:, 2:]
    poor = ~(sine > 1e-4)
    Axy, Bxy, axy, bxy = A.xy, B.xy, ta.xy, tb.xy
    Kh = np.cross(np.cross(A.coords, ta.coords), np.cross(B.coords, tb.coords))
    Mh = np.cross(np.cross(A.coords, B.coords), np.cross(ta.coords, tb.coords))
    with np.errstate(invalid="ignore", divide="ignore"):
        Kxy, Mxy = Kh[:, :2] / Kh[:, 2:], Mh[:, :2] / Mh[:, 2:]

    def second(p1, q1, p2, q2, X):
        c1, c2 = _circumcircle(p1, q1, X), _circumcircle(p2, q2, X)
        d = c2 - c1
        with np.errstate(invalid="ignore", divide="ignore"):
            t = np.sum((X - c1) * d, -1) / np.sum(d * d, -1)
        return 2 * (c1 + t[:, None] * d) - X, np.minimum(_fatness(p1, q1, X), _fatness(p2, q2, X))
    G1, f1 = second(Axy, Bxy, axy, bxy, Kxy)
    G2, f2 = second(Axy, axy, Bxy, bxy, Mxy)
    f1, f2 = np.nan_to_num(f1, nan=-1.0), np.nan_to_num(f2, nan=-1.0)
    Gc = np.where((f2 > f1)[:, None], G2, G1)
    usable = np.maximum(f1, f2) > 1e-3
    G = np.where(poor[:, None], Gc, Gz)
    b.limiting(poor & usable & ~b.bad, "the two \u03b3-lines nearly coincide (\u0393 near the line AB); "
               "\u0393 was found by the four-circle construction (Rosenauer \u00a757) instead")
    b.degenerate(poor & ~usable & ~b.bad, "\u0393 lies on the line of the two points and the four-circle "
                 "construction is degenerate too: \u0393 is undetermined by these two points")
    G = np.where((poor & ~usable)[:, None], np.nan, G)
    for k in ("gA", "gB"):
        b.extend(k, pt(G))
    return b.point("G", pt(G), Role.RESULT, "\u0393")


def _fatness(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> np.ndarray:
    """2·area / (longest side)² of the triangle pqr: 0 for degenerate, ~0.87 for equilateral."""
    sides = np.stack([np.linalg.norm(q - p, axis=-1), np.linalg.norm(r - q, axis=-1),
                      np.linalg.norm(p - r, axis=-1)], -1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return abs(cross(q - p, r - p)) / np.max(sides, -1) ** 2


def _circumcircle(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> np.ndarray:
    b, c = q - p, r - p
    d = 2 * cross(b, c)
    with np.errstate(invalid="ignore", divide="ignore"):
        ux = (c[:, 1] * np.sum(b * b, -1) - b[:, 1] * np.sum(c * c, -1)) / d
        uy = (b[:, 0] * np.sum(c * c, -1) - c[:, 0] * np.sum(b * b, -1)) / d
    return p + np.stack([ux, uy], -1)
