"""Centrodes (polodes; *Polbahnen*, *poloidas*) of the motion of any link relative to any link.

Owns `centrodes` (and `centrode_profiles`, the centrodes as rolling profiles): over the samples of a solution (typically the whole motion), the fixed
centrode (*Rastpolbahn*, *nekustīgā poloida*: the pole's path in `relative_to`'s own
coordinates) and the moving centrode (*Gangpolbahn*, *kustīgā poloida*: the pole's path in
`link`'s own coordinates), which rolls on the fixed one without slipping (Rosenauer §5), with
the radii of curvature of both at every sample and the check 1/R − 1/R′ = 1/D
(Pöschl §39, eq. 94; Rosenauer §15, eq. 10).

The radii come from the exact derivatives of the pole's path, so they need jerks (solve with
order=3): with P = X + Jv/ω for a point X of the link (velocity v, acceleration a, jerk j),
P′ = u = v + Ja/ω − ω̇Jv/ω² and P″ = a + Jj/ω − 2ω̇Ja/ω² − ω̈Jv/ω² + 2ω̇²Jv/ω³; the moving
centrode's second derivative, seen from `relative_to`, is P″ − ωJu.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..geometry import Point
from ..geometry.profiles import SplineProfile
from ..kinematics import Solution
from .curvature import local_invariants
from .motion import TOL, dot, make_point, norm, perp, relative_motion


@dataclass(frozen=True)
class Centrodes:
    """Fixed and moving centrodes of `link` relative to `relative_to` at N samples.

    fixed: the poles in `relative_to`'s coordinates (the Rastpolbahn, a polyline over the
    samples); moving: the same poles in `link`'s coordinates (the Gangpolbahn). Poles of a
    relative translation are points at infinity (the centrodes go to infinity there).
    fixed_radius R′, moving_radius R: signed radii of curvature at each sample, positive when
    the centre of curvature lies on the side of the inflection pole W (the pole normal), inf
    where the centrode is straight; NaN without jerks. diameter D of the inflection circle.
    pole_velocity: u in `relative_to`'s coordinates (both centrodes are run through at |u|).
    """

    link: str
    relative_to: str
    fixed: Point
    moving: Point
    fixed_radius: np.ndarray
    moving_radius: np.ndarray
    diameter: np.ndarray
    pole_velocity: np.ndarray

    @property
    def fixed_xy(self) -> np.ndarray:
        """(N, 2) fixed centrode as a polyline (NaN where the pole is at infinity)."""
        return self.fixed.xy

    @property
    def moving_xy(self) -> np.ndarray:
        return self.moving.xy

    @property
    def residual(self) -> np.ndarray:
        """1/R − 1/R′ − 1/D (dimensionless, times D): zero up to rounding."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.diameter * (1 / self.moving_radius - 1 / self.fixed_radius) - 1


def centrodes(solution: Solution, link: str, relative_to: str | None = None, *,
              curvature: bool = True, tol: float = TOL) -> Centrodes:
    """The fixed and moving centrodes of `link` relative to `relative_to` (default: the
    frame) over the samples of `solution`. With `curvature` (default) the solution must hold
    jerks (order=3); `curvature=False` needs only accelerations and leaves the radii NaN."""
    rm = relative_motion(solution, link, relative_to)
    loc = local_invariants(rm, tol)
    N = len(rm)
    fixed = make_point(loc.pole)
    # moving centrode: s = e^{−iθ_rel}(P − z_rel) in link's own coordinates
    th = rm.derivatives[0, :, 2]
    c, s = np.cos(th), np.sin(th)
    Ph, z = loc.pole, rm.derivatives[0, :, :2]
    d = Ph[:, :2] - Ph[:, 2:] * z
    moving = make_point(np.concatenate([np.stack([c * d[:, 0] + s * d[:, 1],
                                                  -s * d[:, 0] + c * d[:, 1]], axis=1), Ph[:, 2:]], axis=1))
    w = loc.omega
    with np.errstate(divide="ignore", invalid="ignore"):
        u = perp(loc.b) / w[:, None]
        D = np.where(loc.translating, np.inf, norm(loc.b) / w ** 2)
        Rf = Rm = np.full(N, np.nan)
        if curvature:
            rm.require(3, "the curvature of the centrodes")
            al_raw = rm.angle_derivatives()[2]  # the exact ω̇ (not snapped) for P″
            v, a, j, wdd = loc.v, loc.a, loc.jerk, loc.omega_ddot
            Pdd = (a + perp(j) / w[:, None] - (2 * al_raw / w ** 2)[:, None] * perp(a)
                   - (wdd / w ** 2)[:, None] * perp(v) + (2 * al_raw ** 2 / w ** 3)[:, None] * perp(v))
            n = loc.b / norm(loc.b)[:, None]
            uu = dot(u, u)
            kf = dot(Pdd, n) / uu
            km = dot(Pdd - w[:, None] * perp(u), n) / uu
            L = rm.scale
            Rf = np.where(np.abs(kf) * L <= tol, np.inf, 1 / kf)
            Rm = np.where(np.abs(km) * L <= tol, np.inf, 1 / km)
            Rf[loc.translating] = np.nan
            Rm[loc.translating] = np.nan
    return Centrodes(rm.link, rm.relative_to, fixed, moving, Rf, Rm, D, u)



def centrode_profiles(cen: Centrodes, *, degree: int = 5) -> tuple[SplineProfile, SplineProfile]:
    """The two centrodes as profiles that roll on each other without slip (the motion's
    *Polbahnen* cut out as non-circular gears, Rosenauer §5): the fixed one in `relative_to`'s
    coordinates, the moving one in `link`'s, each an interpolating spline through the poles in
    sample order. Sample a range on which the pole stays finite and moves on (no relative
    translation, no stationary pole); the spline's error falls like the sixth power of the
    spacing of the samples."""
    fixed, moving = cen.fixed_xy, cen.moving_xy
    if not (np.isfinite(fixed).all() and np.isfinite(moving).all()):
        raise InputError(f"the centrodes of '{cen.link}' relative to '{cen.relative_to}' go to "
                            "infinity in these samples (a relative translation): choose a range "
                            "where the pole stays finite")
    return SplineProfile(fixed, degree=degree), SplineProfile(moving, degree=degree)
