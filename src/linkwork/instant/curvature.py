"""Curvature theory of the plane motion of link i relative to link j, at every sample at once.

Owns the second-order instantaneous invariants and everything built on them:

* `instant`: ω, ω̇ (Rosenauer τ), the pole P (Ω in Pöschl), the pole velocity u
  (*Polwechselgeschwindigkeit*, Rosenauer V_p), the acceleration of the point coinciding with
  the pole (Pöschl b_Ω, Rosenauer j_p), pole tangent and pole normal, the inflection pole W
  (*Wendepol*, infleksijas centrs W₀) with the diameter D = u/ω, the tangential pole H of the
  Bresse circle (D′ = uω/ω̇) and the acceleration pole Γ (*Beschleunigungspol*, Pöschl G).
* the circles: `inflection_circle` (*Wendekreis*, *infleksijas riņķis*, La Hire's circle: zero
  normal acceleration), `return_circle` (*Rückkehrkreis*, *atgriezes riņķis*: the conjugate of
  the line at infinity, i.e. the inflection circle of the inverse motion), `bresse_circle`
  (Pöschl's *Tangentialkreis*: zero tangential acceleration).
* Euler–Savary (`euler_savary`, `curvature_centre`, `path`, `conjugate`), envelopes of curves
  carried by link i (`envelope`, `line_envelope`; Aronhold's first and second theorems), the
  collineation axis and Bobillier's theorem (`collineation_axis`, `bobillier_pole_tangent`).

Every function takes the engine's `Solution` (batch-first, one call for one sample or the whole
motion), the moving link and `relative_to` (the frame by default). Results are drawn in the
frame at each sample (`Point`, `Vector`, `Circle`, `Line` of shape (N,)), except `path`, which
is a curve in `relative_to`'s own coordinates. Quantities at infinity (the pole of a relative
translation, the tangential pole when ω̇ = 0) are exact points at infinity; circles through
them are straight lines (radius inf).

Formulas (Pöschl §30–33, Rosenauer §43–53), with r measured from the pole, J the quarter turn:
b_Ω = acceleration of the point at P,  u = J b_Ω/ω,  W = P + b_Ω/ω²,  H = P + J b_Ω/ω̇,
Γ = P + (ω² + ω̇J) b_Ω/(ω⁴ + ω̇²),  Euler–Savary: C = P − (d·r)/(|r|² − d·r)·r with d = W − P.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from ..geometry import Circle, Line, Point, Vector, intersect
from ..kinematics import Solution
from .motion import TOL, RelativeMotion, cross, dot, make_point, norm, perp, relative_motion, rotate


# ---------------------------------------------------------------------------- the invariants
@dataclass(frozen=True)
class Local:
    """The invariants in `relative_to`'s coordinates (arrays over samples); see `Instant`."""

    X0: np.ndarray  # reference point of the moving link
    v: np.ndarray
    a: np.ndarray
    jerk: np.ndarray | None
    omega: np.ndarray  # ω with relative translations set exactly to 0
    alpha: np.ndarray  # ω̇ with negligible values set exactly to 0 (Bresse circle a line)
    omega_ddot: np.ndarray | None
    translating: np.ndarray
    pole: np.ndarray  # homogeneous (N, 3)
    b: np.ndarray  # acceleration of the point at the pole (NaN when translating)


@dataclass(frozen=True)
class Instant:
    """Instantaneous invariants of the motion of `link` relative to `relative_to` (N samples),
    drawn in the frame.

    omega, alpha (ω̇), omega_ddot (ω̈, with jerks): relative angular velocity and derivatives.
    pole: P (Rosenauer P(π), Pöschl Ω). translating: where ω = 0 (P at infinity).
    pole_velocity: u, the velocity of the pole along the fixed centrode.
    pole_acceleration: b_Ω, the acceleration of the point of `link` at the pole (along the
    pole normal, towards W; Rosenauer's j_p = Dω²).
    pole_tangent, pole_normal: unit vectors; the tangent along u, the normal towards W.
    diameter: D = |u|/|ω| of the inflection circle (inf when translating).
    inflection_pole W, tangential_pole H (Bresse circle), acceleration_pole Γ.
    """

    motion: RelativeMotion
    local: Local
    pole: Point
    pole_velocity: Vector
    pole_acceleration: Vector
    pole_tangent: Vector
    pole_normal: Vector
    diameter: np.ndarray
    inflection_pole: Point
    tangential_pole: Point
    acceleration_pole: Point

    @property
    def omega(self) -> np.ndarray:
        return self.local.omega

    @property
    def alpha(self) -> np.ndarray:
        return self.local.alpha

    @property
    def omega_ddot(self) -> np.ndarray | None:
        return self.local.omega_ddot

    @property
    def translating(self) -> np.ndarray:
        return self.local.translating

    @property
    def link(self) -> str:
        return self.motion.link

    @property
    def relative_to(self) -> str:
        return self.motion.relative_to

    @property
    def tangential_diameter(self) -> np.ndarray:
        """D′ = |u ω/ω̇| of the Bresse circle (inf when ω̇ = 0)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.local.alpha == 0, np.inf, norm(self.local.b) / np.abs(self.local.alpha))


def local_invariants(rm: RelativeMotion, tol: float = TOL) -> Local:
    """The second- (and third-) order invariants in `relative_to`'s coordinates."""
    rm.require(2, "curvature theory")
    X = rm.point(rm.reference)
    X0, v, a = X[0], X[1], X[2]
    jerk = X[3] if rm.order >= 3 else None
    th = rm.angle_derivatives()
    w, al = th[1], th[2]
    wdd = th[3] if rm.order >= 3 else None
    L = rm.scale
    translating = np.abs(w) * L <= tol * norm(v)
    w = np.where(translating, 0.0, w)
    with np.errstate(divide="ignore", invalid="ignore"):
        b = a - (al / w)[:, None] * v - w[:, None] * perp(v)
        b[translating] = np.nan
        # a rotation about a fixed pole (u = 0, e.g. a crank): b = 0 exactly, D = 0
        fixed = ~translating & (norm(b) <= tol * (norm(a) + (w * w + np.abs(al)) * L))
        b[fixed] = 0.0
        ascale = np.where(translating, norm(a), np.where(fixed, (w * w + np.abs(al)) * L, norm(b)))
        al = np.where(np.abs(al) * L <= tol * ascale, 0.0, al)
    pole = np.concatenate([w[:, None] * X0 + perp(v), w[:, None]], axis=1)
    return Local(X0, v, a, jerk, w, al, wdd, translating, pole, b)


def instant(solution: Solution, link: str, relative_to: str | None = None, *,
            tol: float = TOL) -> Instant:
    """The instantaneous invariants of `link` relative to `relative_to` (default: the frame)
    at every sample of `solution` (which must hold accelerations, order ≥ 2).

    `tol`: a pole farther than length_scale/tol counts as at infinity (relative translation),
    and an ω̇ whose tangential pole lies farther than that counts as zero.
    """
    rm = relative_motion(solution, link, relative_to)
    loc = local_invariants(rm, tol)
    w, al, b, X0, v, a = loc.omega, loc.alpha, loc.b, loc.X0, loc.v, loc.a
    with np.errstate(divide="ignore", invalid="ignore"):
        u = perp(b) / w[:, None]
        D = np.where(loc.translating, np.inf, norm(b) / w ** 2)
        t = u / norm(u)[:, None]
        n = b / norm(b)[:, None]
    W = np.concatenate([(w ** 3)[:, None] * X0 + w[:, None] * a - al[:, None] * v, (w ** 3)[:, None]], axis=1)
    H = np.concatenate([al[:, None] * X0 + perp(a) + w[:, None] * v, al[:, None]], axis=1)
    H[(norm(b) == 0) & (al == 0)] = np.nan  # uniform rotation about a fixed pole: every point
    den = al ** 2 + w ** 4
    G = np.concatenate([den[:, None] * X0 + al[:, None] * perp(a) + (w ** 2)[:, None] * a, den[:, None]], axis=1)
    return Instant(
        motion=rm, local=loc, pole=rm.point_to_world(loc.pole),
        pole_velocity=rm.vector_to_world(u), pole_acceleration=rm.vector_to_world(b),
        pole_tangent=rm.vector_to_world(t), pole_normal=rm.vector_to_world(n), diameter=D,
        inflection_pole=rm.point_to_world(W), tangential_pole=rm.point_to_world(H),
        acceleration_pole=rm.point_to_world(G))


def pole_velocity(solution: Solution, link: str, relative_to: str | None = None) -> Vector:
    """u, the velocity with which the pole runs along the fixed centrode (*Polwechsel-
    geschwindigkeit*, Rosenauer V_p = Dω, eq. 16)."""
    return instant(solution, link, relative_to).pole_velocity


def acceleration_pole(solution: Solution, link: str, relative_to: str | None = None) -> Point:
    """Γ, the point of `link` with zero acceleration relative to `relative_to`
    (*Beschleunigungspol*, Rosenauer's paātrinājumu centrs §53; Pöschl G, eq. 85)."""
    return instant(solution, link, relative_to).acceleration_pole


# ---------------------------------------------------------------------------- circles
def _inflection_local(rm: RelativeMotion, loc: Local) -> tuple[np.ndarray, ...]:
    w, al, X0, v, a = loc.omega, loc.alpha, loc.X0, loc.v, loc.a
    with np.errstate(divide="ignore", invalid="ignore"):
        P = X0 + perp(v) / w[:, None]
        d = loc.b / (w ** 2)[:, None]
        centre = P + d / 2
        radius = norm(d) / 2
        # relative translation: the line −ω̇ v·r + (a × v) = 0 (zero normal acceleration)
        through = X0 + (cross(a, v) / (al * dot(v, v)))[:, None] * v
    return centre, radius, loc.translating, v, through


def inflection_circle(solution: Solution, link: str, relative_to: str | None = None, *,
                      tol: float = TOL) -> Circle:
    """The inflection circle (*Wendekreis*, *infleksijas riņķis*, La Hire's circle): the
    points of `link` whose paths relative to `relative_to` have an inflection (zero normal
    acceleration, Rosenauer §12, §52; Pöschl eq. 81). Diameter D = u/ω on the pole normal, from
    P to the inflection pole W. A straight line where the relative motion translates."""
    rm = relative_motion(solution, link, relative_to)
    loc = local_invariants(rm, tol)
    return rm.circle_to_world(*_inflection_local(rm, loc))


def return_circle(solution: Solution, link: str, relative_to: str | None = None, *,
                  tol: float = TOL) -> Circle:
    """The return circle (*Rückkehrkreis*, *atgriezes riņķis*, Rosenauer §13): the centres of
    curvature of the paths of the points at infinity of `link`; the mirror image of the
    inflection circle in the pole tangent. Computed as the inflection circle of the inverse
    motion (`relative_to` relative to `link`), which it is (Rosenauer §17, §76)."""
    inv = relative_motion(solution, relative_to or solution.mechanism.frame, link)
    loc = local_invariants(inv, tol)
    return inv.circle_to_world(*_inflection_local(inv, loc))


def bresse_circle(solution: Solution, link: str, relative_to: str | None = None, *,
                  tol: float = TOL) -> Circle:
    """The Bresse circle (Pöschl's *Tangentialkreis*, Rosenauer §52 II): the points with zero
    tangential acceleration. Through P with diameter D′ = uω/ω̇ on the pole tangent, to the
    tangential pole H = P + J b_Ω/ω̇ (eq. 84). When ω̇ = 0 it is the pole normal (a straight
    line); for a relative translation the line ω̇(Jv)·r = a·v."""
    rm = relative_motion(solution, link, relative_to)
    loc = local_invariants(rm, tol)
    w, al, X0, v, a = loc.omega, loc.alpha, loc.X0, loc.v, loc.a
    with np.errstate(divide="ignore", invalid="ignore"):
        P = X0 + perp(v) / w[:, None]
        e = perp(loc.b) / al[:, None]
        centre = P + e / 2
        radius = norm(e) / 2
        flat = loc.translating | (al == 0)
        # ω̇ = 0: the pole normal, i.e. the line through P with normal u ∝ J b
        normal = np.where(loc.translating[:, None], perp(v), perp(loc.b))
        through = np.where(loc.translating[:, None],
                           X0 + (dot(a, v) / (al * dot(v, v)))[:, None] * perp(v), P)
    return rm.circle_to_world(centre, radius, flat, normal, through)


# ---------------------------------------------------------------------------- Euler–Savary
def euler_savary(pole: Point, inflection_pole: Point, point: Point, *, scale: float = 1.0,
                 tol: float = TOL) -> Point:
    """The conjugate point (centre of curvature of the path) of `point` by Euler–Savary,
    from the pole P and the inflection pole W (all drawn in one plane, batches (N,)).

    With d = W − P and r = X − P: C = P − (d·r)/(|r|² − d·r)·r, which is Pöschl's eq. (88)
    ρ = r²/W′A and Rosenauer's (11) r² = k·k_w. Points on the inflection circle give C at
    infinity; a point at infinity (direction e) gives C = P − (d·e)e/|e|² on the return circle.
    Needs a finite pole (no relative translation). A centre farther than scale/tol (a
    radius of curvature beyond that) is put exactly at infinity.
    """
    P, Wp, X = (np.asarray(p.coords) for p in (pole, inflection_pole, point))
    with np.errstate(divide="ignore", invalid="ignore"):
        Pxy = P[:, :2] / P[:, 2:]
        d = Wp[:, :2] / Wp[:, 2:] - Pxy
        # r in homogeneous form: (X_xy − w P, w)
        r = X[:, :2] - X[:, 2:] * Pxy
        wx = X[:, 2]
        dr, rr = dot(d, r), dot(r, r)
        den = rr - dr * wx  # |r|² − d·r, homogenised by w
        # |C − X| = |r|³/|den| for finite X: beyond scale/tol the centre is at infinity
        den = np.where((wx != 0) & (np.abs(den) * scale <= tol * rr ** 1.5), 0.0, den)
        h = np.concatenate([Pxy * den[:, None] - (dr[:, None] * r), den[:, None]], axis=1)
    return make_point(h)


@dataclass(frozen=True)
class PathCurvature:
    """A point's path with its curvature at every sample.

    position (N, 2); centre: the centre of curvature (a `Point`, at infinity at an inflection
    of the path); radius (N,) ≥ 0 (inf at an inflection, 0 at a cusp); curvature (N,) signed,
    positive where the path turns counter-clockwise.
    """

    position: np.ndarray
    centre: Point
    radius: np.ndarray
    curvature: np.ndarray

    @property
    def evolute(self) -> np.ndarray:
        """(N, 2) centres of curvature (NaN at inflections): the evolute as a polyline."""
        return self.centre.xy


def _design(solution: Solution, point) -> np.ndarray:
    mech = solution.mechanism
    if isinstance(point, str):
        if point not in mech.points:
            raise ModelError(f"mechanism '{mech.name}' has no point '{point}'")
        return np.asarray(mech.points[point], dtype=float)
    return np.asarray(point, dtype=float)


def osculating_centre(x: np.ndarray, v: np.ndarray, a: np.ndarray, scale: float,
                      tol: float = TOL) -> np.ndarray:
    """Homogeneous (N, 3) centre of the osculating circle of a curve at x with first and second
    derivatives v, a (in time or in any parameter): x + |v|²·Jv/(v × a), carried as
    (x·(v × a) + |v|²·Jv, v × a). A centre farther than scale/tol (an inflection, a straight
    piece) is exactly at infinity, in the direction of the normal Jv."""
    cr = cross(v, a)
    vv = dot(v, v)
    cr = np.where(np.abs(cr) * scale <= tol * vv ** 1.5, 0.0, cr)
    return np.concatenate([x * cr[:, None] + vv[:, None] * perp(v), cr[:, None]], axis=1)


def _path_local(rm: RelativeMotion, s: np.ndarray, tol: float) -> tuple[np.ndarray, ...]:
    rm.require(2, "path curvature")
    X = rm.point(s)
    x, v, a = X[0], X[1], X[2]
    vv = dot(v, v)
    vscale = norm(rm.point(rm.reference)[1]) + np.abs(rm.omega) * rm.scale
    cusp = np.sqrt(vv) <= tol * vscale
    h = osculating_centre(x, v, a, rm.scale, tol)
    cr = h[:, 2].copy()
    flat = ~cusp & (cr == 0)
    h[cusp] = np.concatenate([x, np.ones((len(x), 1))], axis=1)[cusp]
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = np.where(cusp, np.inf, cr / vv ** 1.5)
        radius = np.where(cusp, 0.0, np.where(flat, np.inf, vv ** 1.5 / np.abs(cr)))
    return x, h, radius, kappa


def curvature_centre(solution: Solution, link: str, point, relative_to: str | None = None, *,
                     tol: float = TOL) -> PathCurvature:
    """The centre of curvature of the path of `point` (a name, or design coordinates (2,) or
    (N, 2) of a point of `link`'s plane) relative to `relative_to`, drawn in the frame at each
    sample: C = X + |V|²·JV/(V × A), the centre of the osculating circle (for points on the
    inflection circle at infinity; at the pole, a cusp, C = X). Equal to `euler_savary`."""
    rm = relative_motion(solution, link, relative_to)
    x, h, radius, kappa = _path_local(rm, _design(solution, point), tol)
    return PathCurvature(rm.to_world(x), rm.point_to_world(h), radius, kappa)


def path(solution: Solution, link: str, point, relative_to: str | None = None, *,
         tol: float = TOL) -> PathCurvature:
    """The path of `point` of `link` relative to `relative_to`, as a curve in
    `relative_to`'s own coordinates (for the frame: the drawing), with its centre of curvature
    at every sample; over the whole motion the centres trace the evolute."""
    rm = relative_motion(solution, link, relative_to)
    x, h, radius, kappa = _path_local(rm, _design(solution, point), tol)
    return PathCurvature(x, make_point(h), radius, kappa)


def conjugate(solution: Solution, link: str, direction, relative_to: str | None = None, *,
              tol: float = TOL) -> Point:
    """The conjugate of the point at infinity of `link` in `direction` (design axes): the centre
    of curvature of the envelopes of all lines of `link` normal to `direction`. It lies on the
    return circle (Aronhold's first theorem, Rosenauer §16). For finite points use
    `curvature_centre`."""
    ins = instant(solution, link, relative_to, tol=tol)
    rm = ins.motion
    ew = rotate(rm.derivatives[0, :, 2] + rm.base[:, 2], np.asarray(direction, dtype=float))
    inf = Point(np.concatenate([ew, np.zeros((len(rm), 1))], axis=1))
    return euler_savary(ins.pole, ins.inflection_pole, inf)


# ---------------------------------------------------------------------------- envelopes
@dataclass(frozen=True)
class Envelope:
    """The envelope (in `relative_to`) of a curve carried by `link`, at each sample.

    contact: the point(s) where the curve touches its envelope, on the common normal through
    the pole (Rosenauer §14); for a circle of radius ρ both points C ± ρ·(C − P)/|C − P|,
    shape (N, 2, 2) (nearer the pole first), for a line (N, 1, 2).
    centre: the envelope's centre of curvature, the conjugate of the curve's centre of
    curvature (Rosenauer §15; Pöschl §38, eq. 93). radius: |contact − centre|, (N, 2) or (N, 1).
    """

    contact: np.ndarray
    centre: Point
    radius: np.ndarray


def envelope(solution: Solution, link: str, centre, radius: float, relative_to: str | None = None, *,
             tol: float = TOL) -> Envelope:
    """The envelope of the circle of `radius` about `centre` (design coordinates or a point
    name) carried by `link`: any curve of `link` with that centre of curvature has an envelope
    with the same centre of curvature, the conjugate of `centre` (Euler–Savary)."""
    ins = instant(solution, link, relative_to, tol=tol)
    cc = curvature_centre(solution, link, centre, relative_to, tol=tol)
    C = cc.position
    P = ins.pole.xy
    with np.errstate(divide="ignore", invalid="ignore"):
        nu = (C - P) / norm(C - P)[:, None]
    E = np.stack([C - radius * nu, C + radius * nu], axis=1)
    ce = cc.centre.xy
    with np.errstate(invalid="ignore"):
        rad = np.where(cc.centre.is_infinite[:, None], np.inf, norm(E - ce[:, None]))
    return Envelope(E, cc.centre, rad)


def line_envelope(solution: Solution, link: str, point, direction, relative_to: str | None = None, *,
                  tol: float = TOL) -> Envelope:
    """The envelope of the straight line of `link` through `point` with `direction` (design
    coordinates). It touches at the foot E of the perpendicular from the pole, and its centre
    of curvature lies on the return circle on the ray PE (Aronhold's first theorem)."""
    ins = instant(solution, link, relative_to, tol=tol)
    rm = ins.motion
    s = _design(solution, point)
    gw = rotate(rm.derivatives[0, :, 2] + rm.base[:, 2], np.asarray(direction, dtype=float))
    gw = gw / norm(gw)[:, None]
    Q = rm.to_world(rm.point(s)[0])
    P = ins.pole.xy
    E = Q + dot(P - Q, gw)[:, None] * gw
    nrm = perp(gw)
    C = euler_savary(ins.pole, ins.inflection_pole, Point(np.concatenate([nrm, np.zeros((len(rm), 1))], axis=1)))
    with np.errstate(invalid="ignore"):
        rad = norm(E - C.xy)[:, None]
    return Envelope(E[:, None], C, rad)


# ---------------------------------------------------------------------------- Bobillier
@dataclass(frozen=True)
class Collineation:
    """The collineation of two rays (Rosenauer §21–24, Pöschl §34): for points A, B of `link`
    and their conjugates C_A, C_B, the lines AB and C_A C_B meet at Q on the collineation axis
    PQ, which depends only on the two rays."""

    axis: Line
    q: Point
    centres: tuple[Point, Point]


def collineation_axis(solution: Solution, link: str, a, b, relative_to: str | None = None, *,
                      tol: float = TOL) -> Collineation:
    """The collineation axis of the rays of points `a` and `b` (names or design coordinates)."""
    ins = instant(solution, link, relative_to, tol=tol)
    ca = curvature_centre(solution, link, a, relative_to, tol=tol)
    cb = curvature_centre(solution, link, b, relative_to, tol=tol)
    A, B = Point.from_xy(ca.position), Point.from_xy(cb.position)
    q = intersect(Line.through(A, B), Line.through(ca.centre, cb.centre), coincident="nan")
    return Collineation(Line.through(ins.pole, q), q, (ca.centre, cb.centre))


def _angle(v: np.ndarray) -> np.ndarray:
    return np.arctan2(v[:, 1], v[:, 0])


def bobillier_pole_tangent(solution: Solution, link: str, a, b, relative_to: str | None = None, *,
                           tol: float = TOL) -> Vector:
    """The pole tangent found by Bobillier's theorem from two points and their conjugates:
    the angle from the pole tangent to ray PA equals the angle from ray PB to the collineation
    axis (Rosenauer §22, Pöschl §34). A unit direction (its sense is not significant)."""
    ins = instant(solution, link, relative_to, tol=tol)
    col = collineation_axis(solution, link, a, b, relative_to, tol=tol)
    P = ins.pole.xy
    ra = curvature_centre(solution, link, a, relative_to, tol=tol).position - P
    rb = curvature_centre(solution, link, b, relative_to, tol=tol).position - P
    beta = _angle(col.axis.direction.xy) - _angle(rb)
    t = _angle(ra) - beta
    return Vector(np.stack([np.cos(t), np.sin(t)], axis=1))



# ---------------------------------------------------------------------------- higher pairs
def _carried(solution: Solution, link: str, h: np.ndarray) -> np.ndarray:
    """Homogeneous points (N, 3) in `link`'s design coordinates, drawn in the frame."""
    pose = solution.pose_derivatives(link)[0]
    return np.concatenate([rotate(pose[:, 2], h[:, :2]) + h[:, 2:] * pose[:, :2], h[:, 2:]], axis=1)


def _higher_pair(solution: Solution, pair: str):
    from ..kinematics.contact import is_higher
    j = solution.mechanism.joint(pair)
    if not is_higher(j):
        raise ModelError(f"pair '{pair}' is a {j.kind} pair, not a higher pair (cam or rolling)")
    return j


def element_centres(solution: Solution, pair: str, *, tol: float = TOL) -> tuple[Point, Point]:
    """The centres of curvature, at the contact of higher pair `pair`, of the two elements in
    touch (*Krümmungsmittelpunkte der Profile*): C₁ of the profile of links[0] and C₂ of the
    follower's element of links[1] — a roller's centre, a knife edge's tip (radius 0, C₂ is the
    contact point), a flat face's centre at infinity along its normal, or the centre of the
    mate profile. From the profiles' own derivatives at the contact parameters (geometry, not
    motion); both lie on the common normal. A profile straight at the contact (radius of
    curvature beyond length_scale/tol) has its centre exactly at infinity."""
    from ..model import CamContact
    j = _higher_pair(solution, pair)
    mech = solution.mechanism
    a, b = j.links
    L = mech.length_scale
    rep = solution.joint(pair)
    prof = mech.profiles[j.profile if isinstance(j, CamContact) else j.profiles[0]]
    D = prof.derivatives(rep["u"], 2)
    C1 = _carried(solution, a, osculating_centre(D[0], D[1], D[2], L, tol))
    follower = j.follower if isinstance(j, CamContact) else "rolling"
    N = len(solution)
    if follower == "roller":
        h2 = np.concatenate([solution.point_on(b, mech.points[j.point]).position, np.ones((N, 1))], axis=1)
    elif follower == "knife":
        h2 = np.concatenate([rep["point"], np.ones((N, 1))], axis=1)
    elif follower == "flat":
        face = rotate(solution.pose_derivatives(b)[0, :, 2], np.asarray(j.axis, dtype=float))
        h2 = np.concatenate([perp(face), np.zeros((N, 1))], axis=1)
    else:
        mate = mech.profiles[j.mate if isinstance(j, CamContact) else j.profiles[1]]
        M = mate.derivatives(rep["v"], 2)
        h2 = _carried(solution, b, osculating_centre(M[0], M[1], M[2], L, tol))
    return make_point(C1), make_point(h2)


@dataclass(frozen=True)
class ContactCurvature:
    """Curvature theory through a higher pair (Pöschl §38, Rosenauer §15, §121): the motion of
    the follower (links[1]) relative to the profile's link (links[0]), seen from the contact.

    contact, normal (N, 2): the contact point and the unit common normal (from links[0]'s
    profile towards the follower). centres (C₁, C₂): the elements' curvature centres at the
    contact (`element_centres`). relative: the instantaneous invariants of links[1] relative to
    links[0] (pole on the common normal, inflection pole W, …), inverse: those of links[0]
    relative to links[1]; inflection_circle: the inflection circle of the relative motion.
    conjugates: the Euler–Savary conjugate of C₂ in the relative motion (the centre of curvature
    of the path C₂ describes on links[0]) and that of C₁ in the inverse motion. As any curve of
    links[1] with centre C₂ envelopes on links[0] a curve with centre at C₂'s conjugate
    (Aronhold, Pöschl eq. 93), the conjugates are C₁ and C₂ again: the two profiles are
    conjugate curves, and C₁, C₂ are a pair of conjugate points."""

    pair: str
    links: tuple[str, str]
    contact: np.ndarray
    normal: np.ndarray
    centres: tuple[Point, Point]
    relative: Instant
    inverse: Instant
    inflection_circle: Circle
    conjugates: tuple[Point, Point]

    @property
    def pole(self) -> Point:
        """The relative pole P of the two links (on the common normal)."""
        return self.relative.pole


def contact_curvature(solution: Solution, pair: str, *, tol: float = TOL) -> ContactCurvature:
    """Curvature theory of higher pair `pair` at every sample (the solution needs
    accelerations): the elements' curvature centres and their Euler–Savary conjugates in the
    relative motion of the two links. Where the relative motion is a translation (ω of the
    two links equal) the pole is at infinity, and where the two links are at relative rest (a
    dwell: their relative velocities negligible beside the mechanism's) there is no pole; the
    conjugates are undefined (NaN) there."""
    j = _higher_pair(solution, pair)
    a, b = j.links
    L = solution.mechanism.length_scale
    rep = solution.joint(pair)
    C1, C2 = element_centres(solution, pair, tol=tol)
    rel = instant(solution, b, a, tol=tol)
    inv = instant(solution, a, b, tol=tol)
    conj2 = euler_savary(rel.pole, rel.inflection_pole, C2, scale=L, tol=tol)
    conj1 = euler_savary(inv.pole, inv.inflection_pole, C1, scale=L, tol=tol)
    # the two links at relative rest (a dwell): no pole, no conjugates
    rm = rel.motion
    moving = norm(rm.point(rm.reference)[1]) + np.abs(rm.omega) * L
    scale = np.max([norm(D[1, :, :2]) + np.abs(D[1, :, 2]) * L for D in
                    (solution.pose_derivatives(ln) for ln in solution.mechanism.link_names)], axis=0)
    rest = moving <= tol * scale
    if rest.any():
        conj2, conj1 = (Point(np.where(rest[:, None], np.nan, c.coords)) for c in (conj2, conj1))
    return ContactCurvature(pair, (a, b), rep["point"], rep["normal"], (C1, C2), rel, inv,
                            inflection_circle(solution, b, a, tol=tol), (conj2, conj1))
