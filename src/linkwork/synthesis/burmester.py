"""Burmester theory (Pöschl §§60–63): the centre-point and circle-point curves of four positions
(*Mittelpunkts-* und *Kreispunktkurve*, Pöschl's *Pollagenkurve*) and the Burmester points of
five positions, computed exactly from polynomials.

With the dyad forms of `positions.dyad_forms` (Ẑᵀ B_k M̂ = 0: the point Z of Σ stays on a circle
about M from position `ref` to position k), a centre point M of four positions has a circle
point iff the three rows B_k M̂ have a common null vector:

    K(M) = det[B_a M̂, B_b M̂, B_c M̂] = 0,

a cubic in (m_x, m_y) (each row is affine in M, the determinant trilinear in the rows). Its
cubic part is |M|²·(a linear form): a circular cubic through the two circular points with one
real asymptote, through all six poles and the points Π (Pöschl §61). The circle-point cubic is
the same determinant of the columns Ẑᵀ B_k.

Five positions: the Burmester points are the common points of the centre-point cubics K₁ of
positions (ref, a, b, c) and K₂ of (ref, a, b, d), apart from the three poles the two share
(P_ref,a, P_ref,b, P_ab) and the circular points: 9 − 3 − 2 = 4, of which 0, 2 or 4 are real.
They are found from the pencil of lines through one shared pole P: on the line
M = P + t·(e₁ + s·e₂) both cubics vanish at t = 0, so K₁ = t·(a₂t² + a₁t + a₀) and
K₂ = t·(b₂t² + b₁t + b₀), with a_k, b_k polynomials in s; the two quadratics have a common
root t iff their resultant

    R(s) = (a₂b₀ − a₀b₂)² − (a₂b₁ − a₁b₂)(a₁b₀ − a₀b₁)

vanishes, a polynomial of degree 8 in s. It carries the factor 1 + s² (the lines to the
circular points) and the factors s − s₁, s − s₂ of the lines to the other two shared poles;
divided by them it leaves a quartic whose roots are the Burmester points' directions, the
common root t = (a₂b₀ − a₀b₂)/(a₁b₂ − a₂b₁) their distance. Each point is then refined by
Newton's method on the four dyad equations in (M, Z) together. Everything is computed in the
frame of `positions.normalised` (the origins spread over a unit square), so the polynomial
coefficients are of one size.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import product

import numpy as np
from numpy.polynomial import polynomial as npoly
from scipy.signal import convolve2d

from ..errors import InputError
from ..geometry import Point
from .positions import Positions, SynthesisError, _from_homogeneous, dyad_forms, mate, normalised

__all__ = ["BurmesterPoints", "Cubic", "Dyad", "burmester_points", "centre_point_curve",
           "circle_point_curve", "curve_samples", "dyad"]


# ---------------------------------------------------------------------------- 2-D polynomials
def _compose(C: np.ndarray, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Σ C[i, j]·X^i·Y^j for bivariate polynomials X, Y (coefficient arrays, [p, q] the
    coefficient of u^p v^q)."""
    out = np.zeros((1, 1))
    xp = [np.ones((1, 1))]
    yp = [np.ones((1, 1))]
    for _ in range(C.shape[0] - 1):
        xp.append(convolve2d(xp[-1], X))
    for _ in range(C.shape[1] - 1):
        yp.append(convolve2d(yp[-1], Y))
    for i, j in product(range(C.shape[0]), range(C.shape[1])):
        if C[i, j] == 0:
            continue
        term = C[i, j] * convolve2d(xp[i], yp[j])
        shape = np.maximum(out.shape, term.shape)
        out = np.pad(out, [(0, shape[0] - out.shape[0]), (0, shape[1] - out.shape[1])])
        out[: term.shape[0], : term.shape[1]] += term
    return out


def _determinant_cubic(rows: np.ndarray) -> np.ndarray:
    """(4, 4) coefficients C[i, j] of m_x^i m_y^j of det[R₀ M̂, R₁ M̂, R₂ M̂] for three (3, 3)
    matrices R (trilinear expansion over the columns: M̂ = (m_x, m_y, 1))."""
    C = np.zeros((4, 4))
    power = ((1, 0), (0, 1), (0, 0))
    for a, b, c in product(range(3), repeat=3):
        d = np.linalg.det(np.column_stack([rows[0][:, a], rows[1][:, b], rows[2][:, c]]))
        i = power[a][0] + power[b][0] + power[c][0]
        j = power[a][1] + power[b][1] + power[c][1]
        C[i, j] += d
    return C


# ---------------------------------------------------------------------------- the cubics
@dataclass(frozen=True, eq=False)
class Cubic:
    """A plane cubic Σ c_ij x^i y^j = 0 (i + j ≤ 3), the centre-point or circle-point curve of
    four positions. `coefficients` are in the user's coordinates; `unit` in the normalised
    frame x̂ = (x − centre)/scale, where it is evaluated."""

    unit: np.ndarray  # (4, 4)
    centre: np.ndarray
    scale: float
    kind: str  # "centre-point" or "circle-point"
    positions: Positions
    ref: int = 0

    @property
    def coefficients(self) -> np.ndarray:
        s, (cx, cy) = self.scale, self.centre
        X = np.array([[-cx / s, 0.0], [1 / s, 0.0]])  # (x − cx)/s as a polynomial in (x, y)
        Y = np.array([[-cy / s, 1 / s], [0.0, 0.0]])
        out = np.zeros((4, 4))
        full = _compose(self.unit, X, Y)
        out[: full.shape[0], : full.shape[1]] = full[:4, :4]
        return out

    def __call__(self, xy) -> np.ndarray:
        """The cubic's value at points xy (..., 2), in normalised units (0 on the curve)."""
        p = (np.asarray(xy, dtype=float) - self.centre) / self.scale
        return npoly.polyval2d(p[..., 0], p[..., 1], self.unit)

    @property
    def asymptote_direction(self) -> np.ndarray:
        """Unit direction of the one real point at infinity: where the cubic part
        |M|²·(αx + βy) vanishes, αx + βy = 0."""
        a, b = self.unit[3, 0], self.unit[0, 3]  # x³ and y³ coefficients: α and β
        v = np.array([-b, a])
        return v / np.hypot(*v)

    def slider(self) -> Dyad:
        """The centre-point curve's point at infinity and its circle point, whose four
        homologous points lie on a straight line (the line of stroke of a slider)."""
        if self.kind != "centre-point":
            raise InputError("the slider belongs to the centre-point curve")
        return dyad(self.positions, Point.at_infinity(self.asymptote_direction), ref=self.ref)

    def mate(self, xy) -> Point:
        """The circle point of a centre point on the centre-point curve (or the centre point of
        a circle point on the circle-point curve); `SynthesisError` off the curve."""
        return mate(self.positions, xy, "centre" if self.kind == "centre-point" else "circle", self.ref)


def _forms(pos: Positions, ref: int):
    if len(pos) != 4:
        raise InputError(f"the centre-point and circle-point curves belong to four positions, got {len(pos)}")
    if not 0 <= ref < 4:
        raise InputError(f"ref must be a position index 0 … 3, got {ref}")
    unit, c, s = normalised(pos)
    return dyad_forms(unit, ref), c, s


def centre_point_curve(pos: Positions, ref: int = 0) -> Cubic:
    """The centre-point curve (*Mittelpunktskurve*) of four positions: the fixed pivots of all
    cranks that guide Σ through them."""
    B, c, s = _forms(pos, ref)
    return Cubic(_determinant_cubic(B), c, s, "centre-point", pos, ref)


def circle_point_curve(pos: Positions, ref: int = 0) -> Cubic:
    """The circle-point curve (*Kreispunktkurve*) of four positions, drawn in position `ref`:
    the points of Σ whose four homologous points lie on a circle."""
    B, c, s = _forms(pos, ref)
    return Cubic(_determinant_cubic(np.transpose(B, (0, 2, 1))), c, s, "circle-point", pos, ref)


def _line_coefficients(cubic: np.ndarray, p: np.ndarray, u: np.ndarray) -> np.ndarray:
    """(N, 4): q_k of K(p + t·u_n) = Σ q_k t^k for directions u (N, 2) (exact for a cubic:
    four values and the inverse Vandermonde matrix)."""
    ts = np.array([-1.0, 0.0, 1.0, 2.0])
    pts = p + ts[None, :, None] * u[:, None, :]
    vals = npoly.polyval2d(pts[..., 0], pts[..., 1], cubic)
    return vals @ np.linalg.inv(np.vander(ts, 4, increasing=True)).T


def curve_samples(curve: Cubic, samples: int = 720, through: Point | None = None) -> np.ndarray:
    """(2·samples + 1, 2) points of the curve: on each of `samples` lines through a point of it
    (a finite pole, or `through`), the two other points where the line meets the cubic (NaN
    where they are complex or beyond 1e6 sizes). The two halves are the two roots in turn; a
    jump between neighbours marks the asymptote."""
    pos = curve.positions
    if through is None:
        poles = [pos.pole(min(curve.ref, k), max(curve.ref, k)) for k in range(4) if k != curve.ref]
        finite = [p for p in poles if p.is_finite]
        if not finite:
            raise SynthesisError("every pole of these positions is at infinity (translations)")
        p0 = finite[0].xy  # on both curves: the circle point P_ref,k stays put from ref to k
    else:
        p0 = through.xy
    P = (p0 - curve.centre) / curve.scale
    psi = np.linspace(0.0, np.pi, samples, endpoint=False)
    u = np.column_stack([np.cos(psi), np.sin(psi)])
    q = _line_coefficients(curve.unit, P, u)
    a, b, c = q[:, 3], q[:, 2], q[:, 1]  # K/t = a t² + b t + c
    disc = b * b - 4 * a * c
    with np.errstate(invalid="ignore", divide="ignore"):
        root = np.sqrt(np.where(disc >= 0, disc, np.nan))
        big = -(b + np.copysign(root, b)) / 2  # stable pair of roots
        t1, t2 = big / a, c / big
    out = []
    for t in (t1, t2):
        t = np.where(np.abs(t) < 1e6, t, np.nan)
        out.append(P + t[:, None] * u)
    pts = np.vstack([out[0], [P], out[1]])
    return pts * curve.scale + curve.centre


# ---------------------------------------------------------------------------- five positions
@dataclass(frozen=True, eq=False)
class Dyad:
    """A crank (*Kurbel*, *Zweischlag* with the frame) that guides Σ through the positions: its
    fixed pivot `centre` and its moving pivot `circle` drawn in position `ref` (homogeneous:
    a centre at infinity is a slider's guide, normal to its direction)."""

    centre: Point
    circle: Point
    positions: Positions
    ref: int = 0
    residual: float = 0.0  # largest |Ẑᵀ B_k M̂| after refinement, normalised units

    @property
    def is_slider(self) -> bool:
        return bool(self.centre.is_infinite)

    @property
    def length(self) -> float:
        return float(np.hypot(*(self.circle.xy - self.centre.xy)))

    def homologous(self) -> np.ndarray:
        """(n, 2): the moving pivot in every position."""
        return self.positions.homologous(self.circle.xy, self.ref)


def dyad(pos: Positions, centre=None, *, circle=None, ref: int = 0) -> Dyad:
    """The dyad of a chosen centre point (x, y, or a `Point`; at infinity: a slider whose line
    of stroke is normal to its direction) or of a chosen circle point drawn in position `ref`.
    Two positions leave a line of mates: give both points then (they are checked)."""
    if (centre is None) == (circle is None) and len(pos) > 2:
        raise InputError("give the centre point or the circle point")
    as_point = (lambda p: p if isinstance(p, Point) else Point.from_xy(np.asarray(p, dtype=float)))
    if len(pos) == 2:
        if centre is None or circle is None:
            raise InputError("two positions: give both the centre point and the circle point")
        M, Z = as_point(centre), as_point(circle)
        line = mate(pos, Z, "circle", ref)
        if not line.contains(M, tol=1e-9):
            raise SynthesisError("the circle point's two positions are not equally far from the centre point")
        return Dyad(M, Z, pos, ref)
    if centre is not None:
        M = as_point(centre)
        return Dyad(M, mate(pos, M, "centre", ref), pos, ref)
    Z = as_point(circle)
    return Dyad(mate(pos, Z, "circle", ref), Z, pos, ref)


@dataclass(frozen=True)
class BurmesterPoints:
    """The Burmester points of five positions: the real dyads, how many of the four solutions
    are complex, and the quartic's roots (directions s of the pencil) for inspection."""

    dyads: tuple[Dyad, ...]
    complex_count: int
    roots: np.ndarray = field(repr=False)
    deflation_remainder: float = field(default=0.0, repr=False)

    @property
    def pairs(self) -> int:
        """How many four-bars the real points give (each two of them)."""
        n = len(self.dyads)
        return n * (n - 1) // 2

    @property
    def message(self) -> str:
        n = len(self.dyads)
        if n >= 2:
            return f"{n} real Burmester points ({self.complex_count} complex): {self.pairs} four-bar(s)"
        return (f"only {n} real Burmester point{'s' if n != 1 else ''} ({self.complex_count} complex): no "
                "four-bar guides the plane through these five positions (change a position)")


def _direction_parameter(v: np.ndarray, e1: np.ndarray, e2: np.ndarray) -> float:
    return float(np.dot(v, e2) / np.dot(v, e1))


def _pencil_frame(specials: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Axes (e₁, e₂) for the pencil M = P + t(e₁ + s e₂): the special directions (to the other
    shared poles) kept well away from s = ∞."""
    best, frame = -1.0, None
    for g in np.linspace(0, np.pi, 24, endpoint=False) + 0.1234:
        e1, e2 = np.array([np.cos(g), np.sin(g)]), np.array([-np.sin(g), np.cos(g)])
        worst = min(abs(np.dot(d, e1)) / np.hypot(*d) for d in specials)
        if worst > best:
            best, frame = worst, (e1, e2)
    return frame


def _pole_vector(p: Point, P: np.ndarray) -> np.ndarray:
    """The direction from P to the pole p; p may be at infinity."""
    if p.is_infinite:
        return p.direction.xy
    return p.xy - P


def _refine(B: np.ndarray, M: np.ndarray, Z: np.ndarray, iterations: int = 30):
    """Newton's method on the four dyad equations Ẑᵀ B_k M̂ = 0 in (m_x, m_y, x, y)."""
    x = np.concatenate([M, Z])
    for _ in range(iterations):
        Mh, Zh = np.r_[x[:2], 1.0], np.r_[x[2:], 1.0]
        f = np.einsum("i,kij,j->k", Zh, B, Mh)
        J = np.column_stack([np.einsum("i,kij->kj", Zh, B)[:, :2], (B @ Mh)[:, :2]])
        try:
            dx = np.linalg.solve(J, -f)
        except np.linalg.LinAlgError:
            break
        x = x + dx
        if np.abs(dx).max() <= 1e-15 * max(1.0, np.abs(x).max()):
            break
    Mh, Zh = np.r_[x[:2], 1.0], np.r_[x[2:], 1.0]
    res = float(np.abs(np.einsum("i,kij,j->k", Zh, B, Mh)).max())
    return x[:2], x[2:], res


def burmester_points(pos: Positions, ref: int = 0, *, tol: float = 1e-9) -> BurmesterPoints:
    """The Burmester points of five positions: every centre point whose circle point's five
    homologous points lie on one circle, with that circle point (drawn in position `ref`).
    Real points only among `dyads`; `complex_count` says how many of the four are complex.
    A centre point at infinity (a slider whose pin's five homologous points lie on a line) is
    among them when the positions have one (`_common_slider`); five general positions have
    none."""
    if len(pos) != 5:
        raise InputError(f"Burmester points belong to five positions, got {len(pos)}")
    if not 0 <= ref < 5:
        raise InputError(f"ref must be a position index 0 … 4, got {ref}")
    unit, c, s = normalised(pos)
    B = dyad_forms(unit, ref)  # rows for the four other positions, in order
    others = [k for k in range(5) if k != ref]
    a, b = others[0], others[1]
    K1 = _determinant_cubic(B[[0, 1, 2]])
    K2 = _determinant_cubic(B[[0, 1, 3]])
    shared = [unit.pole(min(ref, a), max(ref, a)), unit.pole(min(ref, b), max(ref, b)), unit.pole(a, b)]
    finite = [p for p in shared if p.is_finite]
    if not finite:
        raise SynthesisError("the poles of positions "
                             f"{ref + 1}, {a + 1}, {b + 1} are all at infinity (translations)")
    centre_pole = min(finite, key=lambda p: float(np.hypot(*p.xy)))
    P = centre_pole.xy
    specials = [_pole_vector(p, P) for p in shared if p is not centre_pole]
    if min(np.hypot(*d) for d in specials) <= 1e-12:
        raise SynthesisError("two poles of these positions coincide: the Burmester points are not "
                             "isolated")
    e1, e2 = _pencil_frame(specials)
    # the line through P as bivariate polynomials in (t, s): x = P_x + t e1_x + t s e2_x
    X = np.array([[P[0], 0.0], [e1[0], e2[0]]])
    Y = np.array([[P[1], 0.0], [e1[1], e2[1]]])
    T1, T2 = (_compose(K, X, Y) for K in (K1, K2))
    a0, a1, a2 = (T1[k, :] if k < T1.shape[0] else np.zeros(1) for k in (1, 2, 3))
    b0, b1, b2 = (T2[k, :] if k < T2.shape[0] else np.zeros(1) for k in (1, 2, 3))
    mul, sub = npoly.polymul, npoly.polysub
    R = sub(npoly.polypow(sub(mul(a2, b0), mul(a0, b2)), 2),
            mul(sub(mul(a2, b1), mul(a1, b2)), sub(mul(a1, b0), mul(a0, b1))))
    known = np.array([1.0, 0.0, 1.0])  # 1 + s²
    for d in specials:
        known = mul(known, [-_direction_parameter(d, e1, e2), 1.0])
    quartic, remainder = npoly.polydiv(R, known)
    scale_R = np.abs(R).max()
    rem = float(np.abs(remainder).max() / scale_R) if scale_R > 0 else 0.0
    roots = npoly.polyroots(npoly.polytrim(quartic, 1e-14 * np.abs(quartic).max()))
    dyads = []
    for r in roots:
        if abs(r.imag) > 1e-6 * (1 + abs(r)):
            continue
        sr = r.real
        ev = [npoly.polyval(sr, v) for v in (a0, a1, a2, b0, b1, b2)]
        A0, A1, A2, B0, B1, B2 = ev
        den = A1 * B2 - A2 * B1
        num = A2 * B0 - A0 * B2
        if abs(den) <= 1e-14 * max(abs(num), 1e-300):
            continue  # a common point at infinity: `_common_slider` below
        M = P + (num / den) * (e1 + sr * e2)
        rows = B @ np.r_[M, 1.0]
        _, _, vt = np.linalg.svd(rows / np.linalg.norm(rows, axis=1, keepdims=True))
        v = vt[-1]
        if abs(v[2]) <= 1e-12 * np.abs(v).max():
            continue  # a circle point at infinity: not a crank
        M2, Z2, res = _refine(B, M, v[:2] / v[2])
        if res > tol or not np.isfinite(res):
            continue  # a near-real pair that does not refine to a real point
        dyads.append(Dyad(_from_homogeneous(np.r_[M2, 1.0], c, s), _from_homogeneous(np.r_[Z2, 1.0], c, s),
                          pos, ref, res))
    slider = _common_slider(pos, K1, K2, ref)
    if slider is not None:
        # the quartic meets the point at infinity as a root t → ∞, which rounding leaves as
        # far finite points (a crank of hundreds of sizes) approximating the slider: drop them
        middle = pos.origin.mean(axis=0)
        dyads = [d for d in dyads if np.hypot(*(d.centre.xy - middle)) <= 100 * pos.size]
        dyads.append(slider)
    dyads = _distinct(dyads, pos.size)
    complex_count = int(np.sum(np.abs(roots.imag) > 1e-6 * (1 + np.abs(roots))))
    return BurmesterPoints(tuple(dyads), complex_count, roots, rem)


def _common_slider(pos: Positions, K1: np.ndarray, K2: np.ndarray, ref: int) -> Dyad | None:
    """The Burmester point at infinity, when the five positions have one: both centre-point
    cubics' real points at infinity (where the linear factor αx + βy of their cubic parts
    |M|²(αx + βy) vanishes) coincide, and that direction's circle point (a slider's pin) has
    five homologous points on a line (checked by `mate` against all five positions)."""
    n1, n2 = np.array([K1[3, 0], K1[0, 3]]), np.array([K2[3, 0], K2[0, 3]])
    if np.hypot(*n1) == 0 or np.hypot(*n2) == 0:
        return None
    if abs(n1[0] * n2[1] - n1[1] * n2[0]) > 1e-9 * np.hypot(*n1) * np.hypot(*n2):
        return None  # five general positions: no common point at infinity
    d = np.array([-n1[1], n1[0]]) / np.hypot(*n1)
    try:
        found = dyad(pos, Point.at_infinity(d), ref=ref)
    except SynthesisError:
        return None
    if found.circle.is_infinite:
        return None
    return found


def _distinct(dyads: list[Dyad], size: float) -> list[Dyad]:
    """A double root refines twice to one point: keep it once."""
    out: list[Dyad] = []
    for d in dyads:
        if not any(np.hypot(*(d.centre.xy - e.centre.xy)) <= 1e-7 * size for e in out):
            out.append(d)
    return out
