"""Shared by the construction modules: reading the *given* data off a mechanism, and the
*analytic* reference values the constructions are checked against.

Owns

* the recognisers that find, in any mechanism, what a classical construction starts from: the
  slider-crank's crank centre, crank pin, crosshead and line of stroke (:func:`slider_crank`),
  and for a moving link the points whose path centres of curvature are known from the structure
  alone (:func:`conjugate_pairs`: a pin of a link hinged to the frame has its path centre at the
  frame pivot — the four-bar's Gelenkpunkte; a pin sliding on a straight frame guide has it at
  infinity, perpendicular to the guide);
* the analytic references computed from the core engine's solution (positions, velocities and
  accelerations of the link's points, ω and α): pole, pole acceleration, inflection pole W₀,
  centre of curvature of a point path, pole-transfer velocity, acceleration centre Γ and the
  Bresse circle. They are closed-form consequences of the engine's exact kinematics and share
  nothing with the ruler constructions; ``linkwork.instant`` computes the same quantities, and
  the tests cross-check the two where it is available.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..kinematics import Solution, solve_at
from ..model import Mechanism, Prismatic, Revolute, Slot


def perp(v: np.ndarray) -> np.ndarray:
    """Counter-clockwise quarter turn of (..., 2) vectors."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore", over="ignore"):
        return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.sum(a * b, axis=-1)


def norm(a: np.ndarray) -> np.ndarray:
    return np.linalg.norm(a, axis=-1)


def farthest_apart(points) -> tuple[int, int]:
    """Indices of the two of a link's known points to read its rotation off: the two farthest
    apart in the drawing (the largest smallest separation over the samples, the first such pair
    on a tie). Two coincident points — an auxiliary point that falls on a hinge in this
    position, like Rosenauer's Q on P_78 of the Heusinger gear at its design position — fix no
    direction, so ω and α read off them, and images found from them, would be noise."""
    best, pair = -1.0, (0, 1)
    for i in range(len(points)):
        for j in range(i + 1, len(points)):
            d = np.ravel(norm(np.asarray(points[j], float) - np.asarray(points[i], float)))
            d = d[~np.isnan(d)]  # samples marked unreachable do not vote
            d = float(d.min()) if d.size else 0.0
            if d > best:
                best, pair = d, (i, j)
    return pair


def rotate(theta: np.ndarray, v: np.ndarray) -> np.ndarray:
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


#: a position where some link turns this many times faster than the input counts as (nearly) a
#: dead centre for the constructions (regular positions of the library mechanisms stay below 10)
NEAR_DEAD_CENTRE = 30.0


def singular_positions(b, sol: Solution) -> None:
    """Record the positions the engine reports as dead centres or change points (a singular
    group Jacobian: velocities are not determined there) or as unassemblable."""
    from ..kinematics import Status
    b.length = sol.mechanism.length_scale
    st = np.asarray(sol.status)
    b.degenerate((st == Status.SINGULAR) & ~b.bad,
                 "the mechanism is at a dead centre or change point here (its velocities are not "
                 "determined by the input), so no construction can be made at this position")
    b.degenerate((st == Status.UNREACHABLE) & ~b.bad, "the mechanism cannot be assembled at this input")
    amp = velocity_amplification(sol)
    b.degenerate((amp > NEAR_DEAD_CENTRE) & ~b.bad,
                 f"the mechanism is within a hair of a dead centre (a link turns more than "
                 f"{NEAR_DEAD_CENTRE:g} times as fast as the input): velocities grow without bound "
                 "there and neither the drawing nor the exact solution is meaningful")


def velocity_amplification(sol: Solution) -> np.ndarray:
    """max |ω_link| / |input rate| (per length_scale for a prismatic input): unbounded at dead
    centres, a few units elsewhere."""
    mech = sol.mechanism
    if len(mech.drivers) != 1:  # several drivers, or given point velocities: no one input rate
        return np.zeros(len(sol))
    d = mech.drivers[0]
    w = np.max(np.abs(np.stack([sol.link(ln).omega for ln in mech.moving_links])), axis=0)
    if mech.joint(d.joint).kind == "revolute":
        rate = np.abs(sol.link(d.driven).omega - (sol.link(d.base).omega if d.base != mech.frame else 0))
    else:
        rate = np.abs(np.linalg.norm(sol.point(mech.joint(d.joint).point).velocity, axis=1)) / mech.length_scale
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(rate > 0, w / rate, 0.0)


def as_solution(mech: Mechanism, inputs) -> Solution:
    """A solution at ``inputs`` (radians or length; an existing Solution is passed through)."""
    if isinstance(inputs, Solution):
        return inputs
    return solve_at(mech, None if inputs is None else np.atleast_1d(np.asarray(inputs, float)),
                    asked="input values (pass None, or its solve_given Solution)")


# ---------------------------------------------------------------------------- recognisers
@dataclass(frozen=True)
class SliderCrank:
    """The parts of a slider-crank, named as in the seed 004 text (Klein): crank centre C,
    crank pin P, crosshead A on the line of stroke with direction ``axis`` (design frame)."""

    crank: str
    rod: str
    C: str
    P: str
    A: str
    axis: np.ndarray


class NotACrank(InputError):
    """The mechanism is not driven by one crank on the frame (the construction's given)."""


def slider_crank(mech: Mechanism, construction: str = "Klein's construction") -> SliderCrank:
    """Recognise a slider-crank: a driven crank on the frame, a rod hinged to it, and the rod's
    other end guided straight on the frame (pin in a slot, or hinged to a block on a guide).
    Raises `NotACrank` (naming `construction`) when the driver is not such a crank, and
    InputError when the rest is not a slider-crank."""
    if len(mech.drivers) != 1:
        raise NotACrank(f"{construction} needs one driver (the crank)")
    d = mech.drivers[0]
    j = mech.joint(d.joint)
    if not isinstance(j, Revolute) or mech.frame not in j.links:
        raise NotACrank(f"{construction} needs the crank to be driven by a revolute pair on the "
                        "frame")
    crank = d.driven
    for pin in mech.joints:
        if not isinstance(pin, Revolute) or crank not in pin.links or mech.frame in pin.links:
            continue
        rod = pin.links[0] if pin.links[1] == crank else pin.links[1]
        for g in mech.joints:
            if isinstance(g, Slot) and g.links == (mech.frame, rod):
                return SliderCrank(crank, rod, j.point, pin.point, g.point, np.asarray(g.axis, float))
            if isinstance(g, Revolute) and rod in g.links and g is not pin and mech.frame not in g.links:
                block = g.links[0] if g.links[1] == rod else g.links[1]
                for gp in mech.joints:
                    if isinstance(gp, Prismatic) and gp.links == (mech.frame, block):
                        return SliderCrank(crank, rod, j.point, pin.point, g.point,
                                           np.asarray(gp.axis, float))
    raise InputError(f"mechanism '{mech.name}' is not a slider-crank (a crank on the frame, a rod "
                     "hinged to it whose other end slides on a straight guide of the frame)")


@dataclass(frozen=True)
class Conjugate:
    """A point of a moving link and the centre of curvature of its path, known from structure:
    ``centre`` names a frame point, or ``normal`` (design frame) gives the direction of a centre
    at infinity (the normal of a straight guide)."""

    point: str
    centre: str | None = None
    guide: np.ndarray | None = None  # direction of the straight path (centre at infinity ⟂ it)


def conjugate_pairs(mech: Mechanism, link: str) -> list[Conjugate]:
    """The points of ``link`` whose path centres of curvature the structure gives directly:
    pins hinged to a link that turns about a frame pivot (centre: that pivot) and pins guided
    on a straight frame guide (centre at infinity)."""
    out: list[Conjugate] = []
    frame = mech.frame
    for j in mech.joints:
        if isinstance(j, Revolute) and link in j.links and frame not in j.links:
            other = j.links[0] if j.links[1] == link else j.links[1]
            for k in mech.joints:
                if isinstance(k, Revolute) and set(k.links) == {other, frame}:
                    out.append(Conjugate(j.point, centre=k.point))
                if isinstance(k, Prismatic) and k.links == (frame, other):
                    out.append(Conjugate(j.point, guide=np.asarray(k.axis, float)))
        if isinstance(j, Slot) and j.links == (frame, link):
            out.append(Conjugate(j.point, guide=np.asarray(j.axis, float)))
    seen, uniq = set(), []
    for c in out:
        if c.point not in seen:
            seen.add(c.point)
            uniq.append(c)
    return uniq


def coupler_link(mech: Mechanism) -> str:
    """The moving link with the most known conjugate pairs (the coupler of a four-bar or the
    connecting rod of a slider-crank)."""
    best, n = None, 1
    for ln in mech.moving_links:
        k = len(conjugate_pairs(mech, ln))
        if k > n:
            best, n = ln, k
    if best is None:
        raise InputError(f"mechanism '{mech.name}' has no link with two points whose path "
                         "centres of curvature follow from the structure (a coupler)")
    return best


# ---------------------------------------------------------------------------- references
def link_motion(sol: Solution, link: str) -> tuple[np.ndarray, np.ndarray]:
    """(ω, α) of ``link``: (N,), (N,)."""
    m = sol.link(link)
    return m.omega, m.alpha


def pole(sol: Solution, link: str) -> np.ndarray:
    """Instantaneous pole (N, 2) of ``link`` from the engine's velocities (NaN if ω = 0)."""
    pm = sol.point_on(link, np.zeros(2))
    w = sol.link(link).omega
    with np.errstate(divide="ignore", invalid="ignore"):
        return pm.position + perp(pm.velocity) / w[:, None]


def material_point(sol: Solution, link: str, world: np.ndarray):
    """Motion of the points of ``link`` that are at ``world`` (N, 2) at each sample."""
    return sol.point_on(link, sol.local(link, world))


def pole_acceleration(sol: Solution, link: str) -> np.ndarray:
    """Acceleration of the link's material point at the pole (*Polbeschleunigung*, Dω²)."""
    return material_point(sol, link, pole(sol, link)).acceleration


def inflection_pole(sol: Solution, link: str) -> np.ndarray:
    """W₀ = P + a_P/ω² (Pöschl eq. 82: D = b_Ω/ω², along the pole normal)."""
    w = sol.link(link).omega
    return pole(sol, link) + pole_acceleration(sol, link) / (w * w)[:, None]


def pole_velocity(sol: Solution, link: str) -> np.ndarray:
    """Pole-transfer velocity (*Polwechselgeschwindigkeit*) u = J a_P / ω."""
    w = sol.link(link).omega
    return perp(pole_acceleration(sol, link)) / w[:, None]


def curvature_centre(position: np.ndarray, velocity: np.ndarray, acceleration: np.ndarray) -> np.ndarray:
    """Centre of curvature of a path from v and a: X + |v|² J v / (v × a) (NaN-free only where
    the path is curved; an inflection point gives ±inf components)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return position + perp(velocity) * (dot(velocity, velocity) / cross(velocity, acceleration))[..., None]


def acceleration_centre(sol: Solution, link: str) -> np.ndarray:
    """Γ, the point of the link with zero acceleration: Γ = Q − a_Q / (−ω² + iα)."""
    w, a = link_motion(sol, link)
    q = sol.point_on(link, np.zeros(2))
    z = (q.acceleration[:, 0] + 1j * q.acceleration[:, 1]) / (-w * w + 1j * a)
    return q.position - np.stack([z.real, z.imag], axis=-1)


def bresse_centre(sol: Solution, link: str) -> np.ndarray:
    """Centre of the Bresse circle (zero tangential acceleration): P + J a_P / (2α)."""
    w, a = link_motion(sol, link)
    with np.errstate(divide="ignore", invalid="ignore"):
        return pole(sol, link) + perp(pole_acceleration(sol, link)) / (2 * a)[:, None]
