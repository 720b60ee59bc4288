"""Third- and fourth-order instantaneous properties, beyond the seeds (Bottema & Roth,
*Theoretical Kinematics*, ch. 4; Veldkamp 1963): from the jerk of the relative motion.

Owns:

* `stationary_curvature`: the cubic of stationary curvature (circling-point curve,
  *Kreispunktkurve*): the points whose paths have stationary curvature (four-point contact with
  the osculating circle). With P the pole, b the acceleration of the point at P, j_P its jerk
  and L = ω j_P − 3ω̇ b − 3ω² J b, a point P + ρe lies on it when
  |r|²(L·r) + 3(b·r)(Jb·r) = 0, i.e. ρ = −3(b·e)(Jb·e)/(L·e); in the canonical frame (x along
  the pole tangent t = Jb/|b|, y along the pole normal) 1/ρ = 1/(M sin φ) + 1/(N cos φ). The
  conjugate curve (centre-point curve, *Mittelpunktkurve*) holds the centres of curvature.
* `ball_point`: the Ball point, where the cubic meets the inflection circle (an undulation:
  the path is straight to third order), on the ray e ⊥ (ω j_P − 3ω̇ b).
* `burmester_points`: the instantaneous Burmester points, where the path's curvature is
  stationary to second order (five-point contact). They need the fourth derivative of the
  motion: `fourth_order` solves a solution's inputs again with `solve(..., order=4)`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..geometry import Point
from ..kinematics import Solution, solve
from .curvature import Local, euler_savary, local_invariants
from .motion import (TOL, RelativeMotion, _c, dot, exp_derivatives, leibniz, make_point, norm, perp,
                     relative_motion)


@dataclass(frozen=True)
class _Third:
    P: np.ndarray  # (N, 2) pole (NaN when translating)
    b: np.ndarray  # acceleration of the point at P
    jP: np.ndarray  # jerk of the point at P
    L: np.ndarray  # ω j_P − 3ω̇ b − 3ω² J b
    w: np.ndarray
    al: np.ndarray
    wdd: np.ndarray


def _third(rm: RelativeMotion, loc: Local) -> _Third:
    rm.require(3, "third-order curvature theory")
    th = rm.angle_derivatives()
    w, al, wdd = loc.omega, th[2], th[3]
    with np.errstate(divide="ignore", invalid="ignore"):
        r = perp(loc.v) / w[:, None]  # P − X0
        P = loc.X0 + r
        jP = loc.jerk + (wdd - w ** 3)[:, None] * perp(r) - (3 * w * al)[:, None] * r
    b = loc.b
    L = w[:, None] * jP - (3 * al)[:, None] * b - (3 * w ** 2)[:, None] * perp(b)
    return _Third(P, b, jP, L, w, al, wdd)


@dataclass(frozen=True)
class StationaryCurvature:
    """The cubic of stationary curvature of `link` relative to `relative_to` at N samples.

    pole, tangent t, normal n (frame), and the canonical constants M, N (N,) of
    1/ρ = 1/(M sin φ) + 1/(N cos φ), φ measured from t towards n (inf: that term vanishes).
    `points(k)` samples the cubic, `centre_points(k)` its conjugate (centre-point curve).
    """

    motion: RelativeMotion
    third: _Third
    pole: Point
    tangent: np.ndarray
    normal: np.ndarray
    M: np.ndarray
    N: np.ndarray

    def _rho(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        t3 = self.third
        n = t3.b / norm(t3.b)[:, None]
        t = perp(n)
        e = np.cos(phi)[None, :, None] * t[:, None] + np.sin(phi)[None, :, None] * n[:, None]
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = -3 * dot(t3.b[:, None], e) * dot(perp(t3.b)[:, None], e) / dot(t3.L[:, None], e)
        return rho, e

    def points(self, k: int = 361, *, limit: float | None = None) -> np.ndarray:
        """(N, k, 2) points of the cubic in the frame for φ in [0, π); points farther from the
        pole than `limit` (default 20 length scales) are NaN (the asymptote)."""
        phi = np.linspace(0.0, np.pi, k, endpoint=False)
        rho, e = self._rho(phi)
        lim = 20 * self.motion.scale if limit is None else limit
        rho = np.where(np.abs(rho) <= lim, rho, np.nan)
        X = self.third.P[:, None] + rho[..., None] * e
        return np.stack([self.motion.to_world(X[:, i]) for i in range(k)], axis=1)

    def centre_points(self, k: int = 361, *, limit: float | None = None) -> np.ndarray:
        """(N, k, 2): the centres of curvature of the points of the cubic (the centre-point
        curve), NaN at infinity."""
        X = self.points(k, limit=limit)
        out = np.empty_like(X)
        ins_P, ins_W = self.pole, _inflection_pole(self.motion, self.third)
        for i in range(k):
            out[:, i] = euler_savary(ins_P, ins_W, Point.from_xy(X[:, i]), scale=self.motion.scale).xy
        return out

    def residual(self, xy: np.ndarray) -> np.ndarray:
        """(N,) dimensionless defect of frame points (N, 2) from the cubic (0 on it)."""
        t3 = self.third
        rm = self.motion
        loc = rm.to_local(xy) - t3.P
        f = dot(loc, loc) * dot(t3.L, loc) + 3 * dot(t3.b, loc) * dot(perp(t3.b), loc)
        scale = norm(t3.L) * norm(loc) ** 3 + 3 * dot(t3.b, t3.b) * dot(loc, loc)
        return f / scale


def _inflection_pole(rm: RelativeMotion, t3: _Third) -> Point:
    with np.errstate(divide="ignore", invalid="ignore"):
        W = t3.P + t3.b / (t3.w ** 2)[:, None]
    return rm.point_to_world(np.concatenate([W, np.ones((len(W), 1))], axis=1))


def stationary_curvature(solution: Solution, link: str, relative_to: str | None = None, *,
                         tol: float = TOL) -> StationaryCurvature:
    """The cubic of stationary curvature (circling-point curve) of `link` relative to
    `relative_to` at every sample; the solution must hold jerks (order=3)."""
    rm = relative_motion(solution, link, relative_to)
    loc = local_invariants(rm, tol)
    t3 = _third(rm, loc)
    n = t3.b / norm(t3.b)[:, None]
    t = perp(n)
    bb = dot(t3.b, t3.b)
    with np.errstate(divide="ignore", invalid="ignore"):
        M = -3 * bb / dot(t3.L, t)
        N = -3 * bb / dot(t3.L, n)
    pole = rm.point_to_world(np.concatenate([t3.P, np.ones((len(rm), 1))], axis=1))
    return StationaryCurvature(rm, t3, pole, rm.rotate_to_world(t), rm.rotate_to_world(n), M, N)


def ball_point(solution: Solution, link: str, relative_to: str | None = None, *,
               tol: float = TOL) -> Point:
    """The Ball point: the point of the inflection circle on the cubic of stationary
    curvature, whose path is straight to the third order (an undulation). NaN where the whole
    inflection circle lies on the cubic (ω j_P = 3ω̇ b) or the motion translates."""
    rm = relative_motion(solution, link, relative_to)
    loc = local_invariants(rm, tol)
    t3 = _third(rm, loc)
    g = t3.w[:, None] * t3.jP - (3 * t3.al)[:, None] * t3.b
    with np.errstate(divide="ignore", invalid="ignore"):
        e = perp(g) / norm(g)[:, None]
        U = t3.P + (dot(t3.b, e) / t3.w ** 2)[:, None] * e
    return rm.point_to_world(np.concatenate([U, np.ones((len(rm), 1))], axis=1))


# ---------------------------------------------------------------------------- fourth order
def _input_derivatives(solution: Solution, driver) -> np.ndarray:
    """(order+1, N) derivatives of a driver's input, recovered from the link poses."""
    mech = solution.mechanism
    j = mech.joint(driver.joint)
    Dd, Db = solution.pose_derivatives(driver.driven), solution.pose_derivatives(driver.base)
    out = np.empty(Dd.shape[:2])
    if j.kind == "prismatic":
        E = exp_derivatives(Db[..., 2], sign=-1.0)
        z = leibniz(E, _c(Dd[..., :2]) - _c(Db[..., :2]))
        ax = j.axis[0] - 1j * j.axis[1]
        out[:] = (z * ax).real
    else:
        out[:] = Dd[..., 2] - Db[..., 2]
    col = mech.drivers.index(driver)
    out[0] = solution.inputs[:, col]
    return out


def fourth_order(solution: Solution, input_snap=None) -> Solution:
    """`solution` solved again at order 4 (`solve(..., order=4)`): the fourth time derivative of
    every link pose, exact, not differenced. The inputs' first three derivatives are recovered
    from the driven links (so a solution at times, or with its own input speeds, keeps them);
    their fourth derivative is `input_snap` ((N,) or (N, drivers); default 0, right for
    uniform drives and cubic laws).
    """
    if solution.order < 3:
        raise InputError("the fourth derivatives are built on the jerks: solve the mechanism "
                         f"with order=3 (this solution has order {solution.order})")
    mech = solution.mechanism
    N = len(solution)
    rates = np.stack([_input_derivatives(solution, d) for d in mech.drivers], axis=-1)
    snap = None if input_snap is None else np.asarray(input_snap, dtype=float).reshape(N, -1)
    out = solve(mech, solution.inputs, velocities=rates[1], accelerations=rates[2],
                jerks=rates[3], snaps=snap, order=4)
    out.time = solution.time
    return out


def _poly_mul(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Product of polynomials in ρ with coefficient axis last."""
    out = np.zeros(p.shape[:-1] + (p.shape[-1] + q.shape[-1] - 1,))
    for i in range(p.shape[-1]):
        for k in range(q.shape[-1]):
            out[..., i + k] += p[..., i] * q[..., k]
    return out


def _cr(f: tuple, g: tuple) -> np.ndarray:
    """cross(F, G) for fields F = f0 + ρ f1 (complex), as a polynomial in ρ."""
    f0, f1 = f
    g0, g1 = g
    return np.stack([np.imag(np.conj(f0) * g0), np.imag(np.conj(f0) * g1 + np.conj(f1) * g0),
                     np.imag(np.conj(f1) * g1)], axis=-1)


def _dt(f: tuple, g: tuple) -> np.ndarray:
    f0, f1 = f
    g0, g1 = g
    return np.stack([np.real(np.conj(f0) * g0), np.real(np.conj(f0) * g1 + np.conj(f1) * g0),
                     np.real(np.conj(f1) * g1)], axis=-1)


@dataclass(frozen=True)
class BurmesterPoints:
    """Instantaneous Burmester points at N samples: `points` (N, 4, 2) in the frame (NaN
    where fewer are real), their centres of curvature `centres` (N, 4, 2) and `count` (N,)."""

    points: np.ndarray
    centres: np.ndarray
    count: np.ndarray


def burmester_points(solution: Solution, link: str, relative_to: str | None = None, *,
                     input_snap=None, grid: int = 1440, tol: float = TOL) -> BurmesterPoints:
    """The points of `link` whose paths relative to `relative_to` have five-point contact with
    their osculating circles (dκ/dt = d²κ/dt² = 0): the intersections of the cubic of
    stationary curvature with the fourth-order curve, at most four real.

    Along a ray e from the pole each field is F(P + ρe) = F_P + ρλ_F e (λ complex: iω for
    velocity, −ω² + iω̇ for acceleration, …). Writing N = V × A, Q = |V|², the condition
    d²κ/dt² = 0 on the cubic is N″Q − ½N′Q′ − (3/2)N Q″ = 0, a polynomial in ρ whose constant
    and quartic coefficients vanish; with ρ = num/den from the cubic the remaining expression
    is a trigonometric polynomial in the ray angle, whose roots are found on a grid of `grid`
    angles and refined by bisection, for all samples at once (in blocks of `CHUNK` samples,
    which bounds the memory of the grid).
    """
    sol4 = solution if solution.order >= 4 else fourth_order(solution, input_snap)
    full = relative_motion(sol4, link, relative_to)
    parts = []
    for start in range(0, len(full), CHUNK):
        sl = slice(start, start + CHUNK)
        rm = RelativeMotion(full.link, full.relative_to, full.derivatives[:, sl], full.base[sl],
                            full.reference, full.scale)
        parts.append(_burmester(rm, grid, tol))
    return BurmesterPoints(*(np.concatenate(a) for a in zip(*parts, strict=True)))


#: samples per block in `burmester_points`
CHUNK = 256


def _burmester(rm: RelativeMotion, grid: int, tol: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    loc = local_invariants(rm, tol)
    t3 = _third(rm, loc)
    th = rm.angle_derivatives()
    w, al, wdd, w3 = t3.w, t3.al, t3.wdd, th[4]
    X = rm.point(rm.reference)
    snap0 = _c(X[4])
    rP = _c(t3.P - loc.X0)
    lv, la = 1j * w, -w ** 2 + 1j * al
    lk = -3 * w * al + 1j * (wdd - w ** 3)
    ls = (w ** 4 - 3 * al ** 2 - 4 * w * wdd) + 1j * (w3 - 6 * w ** 2 * al)
    bP, kP, sP = _c(t3.b), _c(t3.jP), snap0 + ls * rP
    n = t3.b / norm(t3.b)[:, None]
    t = perp(n)

    def h(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        e2 = np.cos(phi)[..., None] * t[:, None] + np.sin(phi)[..., None] * n[:, None]
        e = _c(e2)
        col = (slice(None), None)
        V = (np.zeros_like(e), lv[col] * e)
        A = (bP[col] * np.ones_like(e), la[col] * e)
        K = (kP[col] * np.ones_like(e), lk[col] * e)
        S = (sP[col] * np.ones_like(e), ls[col] * e)
        Nc, N1 = _cr(V, A), _cr(V, K)
        N2 = _cr(A, K) + _cr(V, S)
        Q0, Q1 = _dt(V, V), 2 * _dt(V, A)
        Q2 = 2 * (_dt(A, A) + _dt(V, K))
        G = _poly_mul(N2, Q0) - 0.5 * _poly_mul(N1, Q1) - 1.5 * _poly_mul(Nc, Q2)
        num = -3 * dot(t3.b[:, None], e2) * dot(perp(t3.b)[:, None], e2)
        den = dot(t3.L[:, None], e2)
        Jbe = dot(perp(t3.b)[:, None], e2)
        # G = ρ(c1 + c2ρ + c3ρ²); c1 = 3ω|b|²(b·e); divide by (b·e) and clear den
        bb = dot(t3.b, t3.b)[:, None]
        val = 3 * w[:, None] * bb * den ** 2 - 3 * Jbe * (G[..., 2] * den + G[..., 3] * num)
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = num / den
        return val, rho

    phi = np.linspace(0.0, np.pi, grid + 1)
    vals, _ = h(phi)
    Nn = len(rm)
    scale = np.nanmax(np.abs(vals), axis=1, keepdims=True)
    s = np.sign(vals / scale)
    change = (s[:, :-1] * s[:, 1:] < 0)
    lo = np.where(change, phi[None, :-1], np.nan)
    hi = np.where(change, phi[None, 1:], np.nan)
    # keep at most 4 brackets per sample (the first found)
    order = np.argsort(~change, axis=1, kind="stable")[:, :4]
    lo = np.take_along_axis(lo, order, axis=1)
    hi = np.take_along_axis(hi, order, axis=1)
    valid = np.isfinite(lo)
    lo, hi = np.where(valid, lo, 0.0), np.where(valid, hi, 0.0)

    def hv(x: np.ndarray) -> np.ndarray:  # h at per-sample angles x (N, 4)
        return h(x)[0]

    flo = hv(lo)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        fm = hv(mid)
        left = np.sign(fm) == np.sign(flo)
        lo, flo = np.where(left, mid, lo), np.where(left, fm, flo)
        hi = np.where(left, hi, mid)
    root = 0.5 * (lo + hi)
    pts = np.full((Nn, 4, 2), np.nan)
    cen = np.full((Nn, 4, 2), np.nan)
    for k in range(4):
        e2 = np.cos(root[:, k])[:, None] * t + np.sin(root[:, k])[:, None] * n
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = -3 * dot(t3.b, e2) * dot(perp(t3.b), e2) / dot(t3.L, e2)
        Xk = t3.P + rho[:, None] * e2
        good = valid[:, k] & np.isfinite(Xk).all(axis=1) & (np.abs(rho) > 1e-9 * rm.scale)
        Xw = rm.to_world(Xk)
        pts[good, k] = Xw[good]
        Ph = make_point(np.concatenate([t3.P, np.ones((Nn, 1))], axis=1))
        with np.errstate(divide="ignore", invalid="ignore"):
            Wl = t3.P + t3.b / (w ** 2)[:, None]
        Cl = euler_savary(Ph, Point.from_xy(Wl), Point.from_xy(np.where(np.isfinite(Xk), Xk, 0.0)),
                          scale=rm.scale).xy
        cen[good, k] = rm.to_world(Cl)[good]
    count = np.isfinite(pts[..., 0]).sum(axis=1)
    return pts, cen, count

