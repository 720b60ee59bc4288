"""Constraint equations of every pair and driver, written once at position level over jets.

Link poses are (x, y, θ): a point with design coordinates s is at (x, y) + R(θ)·s, since every
link's own coordinates coincide with the frame's in the design position. Evaluating these
residuals on jets yields the constraint equations' time derivatives exactly; `groups.py` uses
them for Newton's method and for the velocity/acceleration/jerk linear solves.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from ..model import CircularSlot, Driver, Gear, Joint, Mechanism, Prismatic, Revolute, Slot
from . import contact, intermittent
from .jet import Jet

# pose(link) -> (x, y, θ, cos θ, sin θ) jets
PoseFn = Callable[[str], tuple[Jet, Jet, Jet, Jet, Jet]]


def point(pose: PoseFn, link: str, s: np.ndarray) -> tuple[Jet, Jet]:
    x, y, _, c, sn = pose(link)
    return x + c * s[0] - sn * s[1], y + sn * s[0] + c * s[1]


def rotate(pose: PoseFn, link: str, v: np.ndarray) -> tuple[Jet, Jet]:
    _, _, _, c, sn = pose(link)
    return c * v[0] - sn * v[1], sn * v[0] + c * v[1]


def joint_residuals(mech: Mechanism, j: Joint, pose: PoseFn) -> list[Jet]:
    """Residuals (zero when the pair is closed), each in units of length."""
    if contact.is_higher(j):
        return contact.residuals(mech, j, pose, point, rotate)
    if intermittent.is_intermittent(j):
        return intermittent.residuals(mech, j, pose, point, rotate)
    if isinstance(j, Gear):
        return [_gear(mech, j, pose)]
    P = mech.points[j.point]
    a, b = j.links
    if isinstance(j, Revolute):
        xa, ya = point(pose, a, P)
        xb, yb = point(pose, b, P)
        return [xb - xa, yb - ya]
    if isinstance(j, (Prismatic, Slot)):
        nx, ny = rotate(pose, a, np.array([-j.axis[1], j.axis[0]]))
        xa, ya = point(pose, a, P)
        xb, yb = point(pose, b, P)
        res = [nx * (xb - xa) + ny * (yb - ya)]
        if isinstance(j, Prismatic):
            # the block keeps its angle to the guide; scaled to length units
            res.append((pose(b)[2] - pose(a)[2]) * mech.length_scale)
        return res
    if isinstance(j, CircularSlot):
        R = j.radius(mech)
        xk, yk = point(pose, a, mech.points[j.center])
        xb, yb = point(pose, b, P)
        dx, dy = xb - xk, yb - yk
        return [(dx * dx + dy * dy - R * R) * (0.5 / R)]
    raise TypeError(j)  # pragma: no cover


def rack_sense(mech: Mechanism, g: Gear) -> float:
    """+1 or −1: rack displacement per pinion turn (relative to the carrier), divided by r."""
    guide = mech.rack_guide(g)
    centre = mech.points[mech.wheel_centre(g, g.links[0])]
    u = guide.axis
    n = np.array([-u[1], u[0]])
    probe = mech.points[g.point] if g.point else mech.points[guide.point]
    m = n if np.dot(probe - centre, n) >= 0 else -n
    return float(np.dot(np.array([-m[1], m[0]]), u))


def _gear(mech: Mechanism, g: Gear, pose: PoseFn) -> Jet:
    th_c = pose(g.carrier)[2]
    d1 = pose(g.links[0])[2] - th_c
    r1, r2 = g.radii
    if g.gear_kind == "rack":
        guide = mech.rack_guide(g)
        ux, uy = rotate(pose, g.carrier, guide.axis)
        xr, yr, *_ = pose(g.links[1])
        xc, yc, *_ = pose(g.carrier)
        s = ux * (xr - xc) + uy * (yr - yc)
        return s - d1 * (r1 * rack_sense(mech, g))
    d2 = pose(g.links[1])[2] - th_c
    # pitch circles roll: equal arc lengths, opposite senses for an external pair
    return d1 * r1 + d2 * (r2 if g.gear_kind == "external" else -r2)


def driver_residual(mech: Mechanism, d: Driver, pose: PoseFn, value: Jet) -> Jet:
    """Driver constraint: the pair's relative angle or slide equals the input."""
    j = mech.joint(d.joint)
    if isinstance(j, Prismatic):
        ux, uy = rotate(pose, d.base, j.axis)
        xb, yb, *_ = pose(d.driven)
        xa, ya, *_ = pose(d.base)
        return ux * (xb - xa) + uy * (yb - ya) - value
    rel = pose(d.driven)[2] - pose(d.base)[2]
    return (rel - (value - mech.driver_input_at_design(d))) * mech.length_scale
