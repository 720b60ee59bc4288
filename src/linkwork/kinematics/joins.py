"""Where the contact of a higher pair runs over a join of its profile.

The books' cams are drawn from circular arcs and straight lines (Pöschl ch. IV): at a join the
tangent goes on but the curvature jumps (*Krümmungssprung*), so the follower's position and
velocity go on while its acceleration jumps — the cam's hard spot. A solution samples the motion;
this module finds the inputs at which the contact crosses a join and solves the mechanism there
twice, with the piece of the profile that ends at the join and with the piece that starts there:
the one-sided limits before and after the crossing, exactly, never smoothed.

Owns `join_crossings`. It uses only `solve` and the profiles' `side` argument.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from types import MappingProxyType

import numpy as np

from ..errors import InputError, ModelError
from ..geometry.profiles import curvature
from ..model import CamContact, RollingContact
from .solution import Solution, Status
from .solver import solve


@dataclass(frozen=True)
class JoinCrossing:
    """The contact of `pair` crosses the join at parameter `parameter` of profile `profile`
    when the driver's input is `input`. `before` and `after` are one-sample solutions there: the
    limits of every quantity as the input approaches from the side the motion comes from and
    from the other (positions and velocities agree; accelerations and the contact's curvature
    jump)."""

    pair: str
    profile: str
    parameter: float
    input: float
    before: Solution
    after: Solution
    curvature: tuple[float, float]

    def jump(self, link: str) -> float:
        """The jump of `link`'s angular acceleration, after − before."""
        return float(self.after.link(link).alpha[0] - self.before.link(link).alpha[0])

    def point_jump(self, point: str) -> np.ndarray:
        """The jump of `point`'s acceleration (2,), after − before."""
        return self.after.point(point).acceleration[0] - self.before.point(point).acceleration[0]


class _OneSided:
    """A profile that, at parameters within `tol` of the join `u_join` (or a copy of it a whole
    period away), evaluates the piece on `side` of the join; elsewhere it is the profile."""

    def __init__(self, profile, u_join: float, side: int, tol: float) -> None:
        self._profile, self._u, self._side, self._tol = profile, u_join, side, tol

    def __getattr__(self, name):
        return getattr(self._profile, name)

    def _snap(self, u: np.ndarray) -> np.ndarray:
        # the join itself, not u − d: wrapping u − d back into the domain may round off the join
        d = _signed_distance(self._profile, np.asarray(u, dtype=float), self._u)
        return np.where(np.abs(d) <= self._tol, self._u, u)

    def derivatives(self, u, order: int, side: int = 1) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        return self._profile.derivatives(self._snap(u), order, side=self._side)


def _signed_distance(profile, u: np.ndarray, u_join: float) -> np.ndarray:
    """u − u_join, for a closed profile to the nearest copy of the join a period away."""
    d = u - u_join
    if getattr(profile, "closed", False):
        period = profile.domain[1] - profile.domain[0]
        d = (d + period / 2) % period - period / 2
    return d


def _elements(mech, pair) -> list[tuple[str, int]]:
    """(profile name, contact coordinate: 0 = u, 1 = v) of every profile the pair runs on."""
    if isinstance(pair, CamContact):
        out = [(pair.profile, 0)]
        if pair.follower == "profile":
            out.append((pair.mate, 1))
        return out
    if isinstance(pair, RollingContact):
        return [(pair.profiles[0], 0), (pair.profiles[1], 1)]
    raise ModelError(f"joint '{pair.name}' is a {pair.kind} pair, not a higher pair: it runs on no profile")


def join_crossings(solution: Solution, pair: str) -> list[JoinCrossing]:
    """Every crossing of a join (a break of curvature) of the profiles of higher pair `pair`
    between consecutive samples of `solution` (a one-driver solution, ordered along the
    motion), with the one-sided limits at the crossing."""
    from .contact import report  # the contact parameters (u, v) at the samples

    mech = solution.mechanism
    j = mech.joint(pair)
    if len(mech.drivers) != 1:
        raise InputError("join crossings are found along the input of a one-driver mechanism")
    elements = _elements(mech, j)
    rep = report(solution, pair)
    x = solution.input
    ok = solution.status != Status.UNREACHABLE
    out: list[JoinCrossing] = []
    for name, coord in elements:
        prof = mech.profiles[name]
        breaks = np.asarray(prof.breaks, dtype=float)
        if breaks.size == 0:
            continue
        u = rep["u" if coord == 0 else "v"]
        tol = 1e-12 * max(1.0, float(np.abs(np.asarray(prof.domain, dtype=float)[np.isfinite(prof.domain)]).max(initial=1.0)))
        for b in breaks:
            d = _signed_distance(prof, u, b)
            # a sign change between neighbours that are both assembled and close (not a wrap)
            step = np.abs(np.diff(u))
            cross = np.flatnonzero(ok[:-1] & ok[1:] & (np.sign(d[:-1]) != np.sign(d[1:]))
                                   & (np.abs(d[:-1]) + np.abs(d[1:]) <= step + tol * 10))
            for k in cross:
                out.append(_crossing(solution, j, name, coord, float(b), x[k], x[k + 1],
                                     float(d[k]), float(d[k + 1]), tol))
    out.sort(key=lambda c: c.input)
    return out


def _crossing(sol: Solution, j, name: str, coord: int, b: float, x0: float, x1: float,
              d0: float, d1: float, tol: float) -> JoinCrossing:
    from .contact import report

    mech = sol.mechanism
    prof = mech.profiles[name]
    key = "u" if coord == 0 else "v"

    def dist(x: float) -> float:
        one = solve(mech, [x], order=1)
        return float(_signed_distance(prof, report(one, j.name)[key], b)[0])

    if d0 == 0.0:
        x = x0
    elif d1 == 0.0:
        x = x1
    else:
        from scipy.optimize import brentq  # SciPy loads when first needed
        x = brentq(dist, x0, x1, xtol=1e-14 * max(1.0, abs(x0)), rtol=1e-15)
    before_side = -1 if d0 < 0 or (d0 == 0 and d1 > 0) else 1

    def sided(side: int) -> Solution:
        profiles = dict(mech.profiles)
        profiles[name] = _OneSided(prof, b, side, tol)
        return solve(replace(mech, profiles=MappingProxyType(profiles)), [x], order=sol.order)

    kb, ka = curvature(prof, np.array([b]), side=before_side)[0], curvature(prof, np.array([b]), side=-before_side)[0]
    return JoinCrossing(j.name, name, b, x, sided(before_side), sided(-before_side), (float(kb), float(ka)))
