"""What the curvature constructions share: the coupler's given data and Rosenauer's three
Euler–Savary tasks by ruler.

Owns :class:`CouplerData` / :func:`coupler_data` (the moving link, two of its points A, B with
the centres of curvature C_a, C_b of their paths known from the structure — the four-bar's
frame pivots, or a point at infinity for a crosshead on a straight guide — an optional third
point C whose centre is sought, all at N positions), :func:`draw_pole` (the pole as the
intersection of the path normals, *Polstrahlen*), and the ruler constructions of Rosenauer §19
on one ray through the pole P, in which A is a moving point (C_α), C its centre of curvature
(C_e) and W the inflection point of the ray; they satisfy r² = k·k_w (§18, eq. 11):

* :func:`task_I` (given P, A, C → W): through A an arbitrary line (a) with a point K on it;
  PB ∥ CK meets (a) in B; BW ∥ KP meets the ray in W;
* :func:`task_II` (given P, A, W → C): PB ∥ WK meets (a) in B; BC ∥ KP meets the ray in C;
* :func:`task_III` (given P, W, C → A): any K off the ray; B = (∥ WK through P) ∩ (∥ PK
  through C); KB meets the ray in A.

The free choices are made once (the line (a) at 60° to the ray, K at the distance PA from A);
the results do not depend on them (two homotheties about A, Rosenauer's proof).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .construction import Builder, Role, pt
from ..errors import InputError
from ..geometry import Line, Point, Vector
from ..kinematics import Solution
from ..model import Mechanism
from ._common import conjugate_pairs, coupler_link, norm, perp, rotate
from ._plan import upper
from ..topology.constructibility import script

ANGLE_A = np.radians(60.0)  # direction of the arbitrary line (a) against the ray

#: a pole farther than this many times the mechanism's size from it is "off the sheet": the link
#: nearly translates, every line through P is nearly parallel to the next, and the constructions
#: through P lose accuracy (Pöschl §36 names this limitation of Euler–Savary and Bobillier)
POLE_FAR = 30.0


def far_pole(b: Builder, P: Point, L: float, origin: np.ndarray) -> np.ndarray:
    """Record the positions where the pole is off the sheet (see :data:`POLE_FAR`)."""
    with np.errstate(invalid="ignore"):
        rho = np.linalg.norm(P.xy - origin, axis=-1) / L
    far = P.is_finite & (rho > POLE_FAR)
    return b.degenerate(far & ~b.bad,
                        f"the pole lies more than {POLE_FAR:g} times the mechanism's size away (the link "
                        "nearly translates): the lines through P are nearly parallel and the ruler "
                        "construction loses its accuracy here (Pöschl \u00a736: the pole is off the sheet)")


@dataclass
class CouplerData:
    link: str
    names: tuple[str, str]  # A, B
    A: Point
    B: Point
    Ca: Point  # possibly at infinity
    Cb: Point
    centre_names: tuple[str, str]
    C: Point | None
    c_name: str | None
    L: float
    origin: np.ndarray


def coupler_data(mech: Mechanism, sol: Solution, link: str | None = None,
                 point: str | None = None) -> CouplerData:
    """The given data for the curvature constructions of ``link`` (default: the coupler)."""
    link = link or coupler_link(mech)
    pairs = conjugate_pairs(mech, link)
    if len(pairs) < 2:
        raise InputError(f"link '{link}' needs two points whose path centres of curvature follow "
                         "from the structure (pins on frame-pivoted links or on straight frame guides)")
    n = len(sol)
    a, b = pairs[0], pairs[1]

    def centre(c) -> tuple[Point, str]:
        if c.centre is not None:
            return Point.from_xy(sol.point(c.centre).position), upper(c.centre)
        g = np.broadcast_to(np.asarray(c.guide, float), (n, 2))
        return Point.at_infinity(perp(g)), "C_" + script(c.point)
    Ca, la = centre(a)
    Cb, lb = centre(b)
    design = mech.points
    others = [p for p in mech.link(link).points if p not in (a.point, b.point)
              and min(np.hypot(*(design[p] - design[a.point])), np.hypot(*(design[p] - design[b.point])))
              > 1e-9 * mech.length_scale]
    if point is not None:
        if point not in mech.link(link).points:
            raise InputError(f"point '{point}' is not a point of link '{link}'")
        others = [point]
    cname = others[0] if others else None
    C = Point.from_xy(sol.point(cname).position) if cname else None
    origin = np.mean(np.array(list(mech.points.values())), axis=0)
    return CouplerData(link, (a.point, b.point), Point.from_xy(sol.point(a.point).position),
                       Point.from_xy(sol.point(b.point).position), Ca, Cb, (la, lb), C, cname,
                       mech.length_scale, origin)


def draw_given(b: Builder, cd: CouplerData) -> None:
    nA, nB = upper(cd.names[0]), upper(cd.names[1])
    b.length = cd.L
    b.step(f"Given: the points {nA}, {nB} of the {cd.link} and the centres of curvature of their "
           f"paths, {cd.centre_names[0]} and {cd.centre_names[1]}"
           + (f"; the point {upper(cd.c_name)} whose centre of curvature is sought." if cd.c_name else "."))
    b.point("A", cd.A, Role.GIVEN, nA)
    b.point("B", cd.B, Role.GIVEN, nB)
    b.point("Ca", cd.Ca, Role.GIVEN, cd.centre_names[0])
    b.point("Cb", cd.Cb, Role.GIVEN, cd.centre_names[1])
    if cd.C is not None:
        b.point("C", cd.C, Role.GIVEN, upper(cd.c_name))
    b.segment("AB", cd.A, cd.B, Role.GIVEN)


def draw_pole(b: Builder, cd: CouplerData) -> tuple[Point, Line, Line]:
    nA, nB = upper(cd.names[0]), upper(cd.names[1])
    b.step(f"The path normals {cd.centre_names[0]}{nA} and {cd.centre_names[1]}{nB} (rays I and II) "
           "meet in the pole P.")
    r1 = b.join("ray1", cd.Ca, cd.A, Role.AUXILIARY, "I")
    r2 = b.join("ray2", cd.Cb, cd.B, Role.AUXILIARY, "II")
    P = b.meet("P", r1, r2, Role.RESULT, "P", k1="ray1", k2="ray2",
               why="the path normals are parallel: the pole lies at infinity (the link translates "
                   "instantaneously), so its curvature constructions degenerate")
    far_pole(b, P, cd.L, cd.origin)
    return P, r1, r2


def at_pole(b: Builder, P: Point, A: Point, name: str) -> None:
    """Record where the point lies at the pole: its ray is the path normal, but r = 0 leaves
    the Euler–Savary tasks without a measure (the point is at rest: a limit position)."""
    L = getattr(b, "length", 1.0)
    with np.errstate(invalid="ignore"):
        b.degenerate(norm(A.xy - P.xy) <= 1e-9 * L,
                     f"{name} lies at the pole (it is momentarily at rest: a limit position), so the "
                     "Euler\u2013Savary construction on its ray has no length to work with")


def _arbitrary(b: Builder, key: str, P: Point, A: Point, tag: str) -> tuple[Line, Point]:
    """The arbitrary line (a) through A and the point K on it."""
    d = A.xy - P.xy
    r = norm(d)
    u = rotate(np.full(len(r), ANGLE_A), d)
    a_line = b.parallel(key + ".a", A, Vector(np.where(np.isfinite(u), u, np.nan)), Role.AUXILIARY,
                        f"(a_{tag})")
    K = b.point(key + ".K", pt(A.xy + u), Role.AUXILIARY, f"K_{tag}")
    b.extend(key + ".a", K)
    return a_line, K


def task_I(b: Builder, key: str, P: Point, A: Point, Cx: Point, ray: Line, *, names: tuple[str, str, str],
           ray_key: str, label: str = "W", tag: str = "1") -> Point:
    """Rosenauer §19 Task I: the inflection point W of the ray P A from the centre Cx of A."""
    nA, nC, nW = names
    b.step(f"Euler\u2013Savary, Task I on the ray P{nA}: through {nA} draw any line (a) and take K on it; "
           f"through P draw the parallel to {nC}K, it meets (a) in S; through S the parallel to KP "
           f"meets the ray in the inflection point {nW}.")
    return _through_S(b, key, P, A, Cx, ray, given="C", found="W", ray_key=ray_key, label=label,
                      tag=tag, nA=nA)


def task_II(b: Builder, key: str, P: Point, A: Point, W: Point, ray: Line, *, names: tuple[str, str, str],
            ray_key: str, label: str = "C", tag: str = "2") -> Point:
    """Rosenauer §19 Task II: the centre of curvature of A's path from its inflection point W."""
    nA, nW, nC = names
    b.step(f"Euler\u2013Savary, Task II on the ray P{nA}: through {nA} draw any line (a) and take K on it; "
           f"through P draw the parallel to {nW}K, it meets (a) in S; through S the parallel to KP "
           f"meets the ray in the centre of curvature {nC}.")
    return _through_S(b, key, P, A, W, ray, given="W", found="C", ray_key=ray_key, label=label,
                      tag=tag, nA=nA)


def _through_S(b: Builder, key: str, P: Point, A: Point, X: Point, ray: Line, *, given: str,
               found: str, ray_key: str, label: str, tag: str, nA: str) -> Point:
    """Tasks I and II share their lines: any line (a) through A with K on it; the parallel to
    XK through P meets (a) in S; the parallel to KP through S meets the ray in the point sought
    (X the centre of curvature gives the inflection point, and the reverse). `given`/`found`
    name the element keys (…KC/…BW/…W for Task I, …KW/…BC/…C for Task II)."""
    at_pole(b, P, A, nA)
    a_line, K = _arbitrary(b, key, P, A, tag)
    KX = b.join(f"{key}.K{given}", K, X)
    KP = b.join(key + ".KP", K, P)
    PB = b.parallel(key + ".PB", P, KX)
    Bp = b.meet(key + ".B", PB, a_line, label=f"S_{tag}", k1=key + ".PB", k2=key + ".a", finite=False)
    BY = b.parallel(f"{key}.B{found}", Bp, KP)
    return b.meet(f"{key}.{found}", BY, ray, Role.RESULT, label, k1=f"{key}.B{found}", k2=ray_key,
                  finite=False)


def task_III(b: Builder, key: str, P: Point, W: Point, Cx: Point, ray: Line, *, names: tuple[str, str, str],
             ray_key: str, label: str = "A", tag: str = "3") -> Point:
    """Rosenauer §19 Task III: the moving point A whose centre is Cx, from P, W and Cx."""
    nW, nC, nA = names
    b.step(f"Euler\u2013Savary, Task III on the same ray: take any K off the ray; the parallel to {nW}K "
           f"through P and the parallel to PK through {nC} meet in S; KS meets the ray in the point "
           f"{nA} whose centre of curvature is {nC}.")
    L = getattr(b, "length", None) or 1.0
    with np.errstate(invalid="ignore"):
        near = Cx.is_finite & (norm(np.nan_to_num(Cx.coords[:, :2]) - P.xy) <= 1e-3 * L)
    b.degenerate(near & ~b.bad, f"the centre {nC} lies (almost) at the pole: then P, {nW} and {nC} "
                 "coincide and Task III leaves the point undetermined")
    dc = np.where(Cx.is_finite[:, None], Cx.coords[:, :2], W.xy) - P.xy
    dw = W.xy - P.xy
    d = np.where((norm(dc) >= norm(np.nan_to_num(dw)))[:, None], dc, dw)
    K = b.point(key + ".K", pt(P.xy + rotate(np.full(len(d), -ANGLE_A), d) * 0.7), Role.AUXILIARY,
                f"K_{tag}")
    KW = b.join(key + ".KW", K, W)
    KP = b.join(key + ".KP", K, P)
    l1 = b.parallel(key + ".PB", P, KW)
    l2 = b.parallel(key + ".CB", Cx, KP)
    Bp = b.meet(key + ".B", l1, l2, label=f"S_{tag}", k1=key + ".PB", k2=key + ".CB", finite=False)
    KB = b.join(key + ".KB", K, Bp)
    return b.meet(key + ".A", KB, ray, Role.RESULT, label, k1=key + ".KB", k2=ray_key, finite=False)


def inflection_from_two_rays(b: Builder, P: Point, ray1: Line, ray2: Line, W1: Point, W2: Point,
                             *, k1: str = "ray1", k2: str = "ray2", text: str | None = None) -> Point:
    """W₀ from the inflection points of two rays (the perpendiculars to the rays at their
    inflection points all pass through W₀, Rosenauer §21 step 5) and the inflection circle."""
    b.step(text or "The perpendiculars to the rays at their inflection points meet in the inflection "
                   "pole W_0; the circle on PW_0 as diameter is the inflection circle (Wendekreis), "
                   "the pole tangent t is perpendicular to PW_0 at P.")
    n1 = b.perpendicular("W0.n1", W1, ray1)
    n2 = b.perpendicular("W0.n2", W2, ray2)
    W0 = b.meet("W0", n1, n2, Role.RESULT, "W_0", k1="W0.n1", k2="W0.n2",
                why="the two rays coincide (both points on one ray through the pole), so W\u2080 is "
                    "undetermined")
    M = pt((P.xy + W0.xy) / 2)
    b.circle("wendekreis", M, P, Role.RESULT, "inflection circle", kind="inflection")
    b.join("PW0", P, W0, Role.AUXILIARY, "n")
    b.perpendicular("tangent", P, b.elements["PW0"].obj, Role.RESULT, "t")
    return W0
