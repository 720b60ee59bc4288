"""The applied loads of a `Dynamics` evaluated on a `Solution`: every load becomes forces at
material points of links and couples on links, at every sample at once.

A force is (link, design coordinates of its material point, force (N, 2) in N); a couple is
(link, torque (N,) in N·m). With `inertia`, the d'Alembert inertia forces −m·a_S at each centre
of mass S and couples −I_S·α are among them (German *Trägheitskräfte*), so that every link is
in equilibrium under all of them and the pair reactions (`kinetostatics`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..kinematics import Solution
from ..model.inertia import Dynamics, LoadTable


@dataclass(frozen=True)
class AppliedForce:
    link: str
    point: np.ndarray  # design coordinates (2,) or (N, 2), length unit
    force: np.ndarray  # (N, 2), N
    kind: str  # "inertia", "gravity", "force", "spring"


@dataclass(frozen=True)
class AppliedCouple:
    link: str
    torque: np.ndarray  # (N,), N·m
    kind: str  # "inertia", "torque", "spring"


def rotate(theta: np.ndarray, v) -> np.ndarray:
    """Vectors v (2,) or (N, 2) turned by the angles theta (N,)."""
    v = np.asarray(v, dtype=float)
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def _evaluate(value, k: int, sol: Solution, what: str) -> np.ndarray:
    """A load value at every sample: (N,) for k = 1, (N, 2) for k = 2."""
    N = len(sol)
    if isinstance(value, LoadTable) or callable(value):
        of = value.of if isinstance(value, LoadTable) else None
        if of == "time" and sol.time is None:
            raise InputError(f"{what} is tabulated against time, but the motion was solved at "
                             "inputs, not times (solve at times, or tabulate against the input)")
        x = sol.time if of == "time" else sol.inputs[:, 0]
        out = np.asarray(value(x) if of else value(sol.inputs[:, 0], sol.time), dtype=float)
    else:
        out = np.asarray(value, dtype=float)
    try:
        out = np.broadcast_to(out.reshape((-1,) if k == 1 else (-1, 2)), (N,) if k == 1 else (N, 2))
    except ValueError:
        raise InputError(f"{what}: expected {'a number' if k == 1 else 'two components'} per "
                         f"sample, got an array of shape {np.shape(out)}") from None
    return out


def applied_loads(dyn: Dynamics, sol: Solution, *, inertia: bool = True
                  ) -> tuple[list[AppliedForce], list[AppliedCouple]]:
    """The forces and couples on the links at every sample (see the module's docstring)."""
    mech, loads, m_per = dyn.mechanism, dyn.loads, dyn.metres_per_unit
    forces: list[AppliedForce] = []
    couples: list[AppliedCouple] = []
    g = np.asarray(loads.gravity, dtype=float)
    for ln in mech.moving_links:
        mp = dyn.masses.get(ln)
        if mp is None:
            continue
        if inertia:
            a = sol.point_on(ln, mp.center).acceleration
            forces.append(AppliedForce(ln, mp.center, -mp.mass * m_per * a, "inertia"))
            couples.append(AppliedCouple(ln, -mp.inertia * sol.pose_derivatives(ln)[2, :, 2],
                                         "inertia"))
        if loads.has_gravity and mp.mass:
            forces.append(AppliedForce(ln, mp.center, np.broadcast_to(mp.mass * g, (len(sol), 2)),
                                       "gravity"))
    for f in loads.forces:
        F = _evaluate(f.force, 2, sol, f"force '{f.name}'")
        if f.axes == "link":
            F = rotate(sol.pose_derivatives(f.link)[0, :, 2], F)
        forces.append(AppliedForce(f.link, f.point, F, "force"))
    for c in loads.couples:
        couples.append(AppliedCouple(c.link, _evaluate(c.torque, 1, sol, f"torque '{c.name}'"),
                                     "torque"))
    for s in loads.springs:
        (la, lb), (sa, sb) = s.links, s.points
        pa, pb = sol.point_on(la, sa), sol.point_on(lb, sb)
        d = pb.position - pa.position
        length = np.hypot(d[:, 0], d[:, 1])
        e = d / length[:, None]
        rate = np.einsum("ij,ij->i", e, pb.velocity - pa.velocity)
        free = float(np.hypot(*(np.asarray(sb) - sa))) if s.free_length is None else s.free_length
        tension = s.stiffness * (length - free) * m_per + s.preload + s.damping * rate * m_per
        forces.append(AppliedForce(la, sa, tension[:, None] * e, "spring"))
        forces.append(AppliedForce(lb, sb, -tension[:, None] * e, "spring"))
    for t in loads.torsion_springs:
        a, b = mech.joint(t.joint).links
        Da, Db = sol.pose_derivatives(a), sol.pose_derivatives(b)
        phi, rate = Db[0, :, 2] - Da[0, :, 2], Db[1, :, 2] - Da[1, :, 2]
        torque = -t.stiffness * (phi - t.free_angle) - t.damping * rate
        couples.append(AppliedCouple(b, torque, "spring"))
        couples.append(AppliedCouple(a, -torque, "spring"))
    return forces, couples


def load_power(sol: Solution, forces: list[AppliedForce], couples: list[AppliedCouple],
               metres_per_unit: float) -> np.ndarray:
    """Σ F·v + M·ω of the loads (W) with the velocities of `sol` (the motion, or a unit-speed
    motion of one driver, which gives the generalized force of virtual work)."""
    P = np.zeros(len(sol))
    for f in forces:
        v = sol.point_on(f.link, f.point).velocity
        P += metres_per_unit * np.einsum("ij,ij->i", f.force, v)
    for c in couples:
        P += c.torque * sol.pose_derivatives(c.link)[1, :, 2]
    return P
