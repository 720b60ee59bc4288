"""Kinetostatics (German *Kinetostatik*): the pair reactions and the driving torques or forces
of a mechanism whose motion is prescribed, at every sample at once.

Every moving link is in equilibrium under its applied loads, the d'Alembert inertia forces
(`loads.applied_loads`) and the reactions of its pairs and drivers: three equations per link
(forces in x and y, moments about a point of the link), one square linear system per sample,
solved for all samples in one batched call. Unknowns, with the sign convention:

- every pair's reaction is the force that its links[0] exerts on its links[1] (links[0] feels
  the opposite), in N, acting at the pair's point:
  revolute: (x, y) at the hinge; prismatic: the normal force along n = the guide's direction
  turned 90° counter-clockwise, at the block's point, and the couple (N·m) the guide holds;
  slot: the normal force along n at the pin; circular slot: the radial force along the unit
  vector from the arc's centre to the pin; gear: the tangential tooth force at the pitch point
  along the pitch circles' tangent t = e turned 90° counter-clockwise, e from the first
  wheel's centre to the pitch point (the radial share from the pressure angle loads the
  bearings only and is left out); cam: the normal force along the common normal from the
  profile to the follower (positive presses them together); rolling: normal and tangential
  (along the normal turned 90° counter-clockwise), or on two pivots of a carrier the
  tangential force only, as a gear.
- every driver's effort is the torque (N·m, counter-clockwise) or force (N, along the guide's
  direction) that the base link (the frame, for a motor on it) exerts on the driven link.

No friction: the pairs are ideal (their reactions do no work), which the power balance
checks. The frame is in no equation; the force and moment that the moving links exert on it
through its pairs and drivers are reported (`frame_force`, `frame_moment`), as are the
shaking force and moment (the resultant of the inertia forces, German *Massenkräfte*, and their
moment, about the frame's origin).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from types import MappingProxyType
from typing import Mapping

import numpy as np

from ..errors import LinkworkWarning, ModelError, StructureError
from ..kinematics import Solution, Status, solve
from ..kinematics import contact
from ..model import (CamContact, CircularSlot, Gear, Prismatic, Revolute, RollingContact, Slot,
                     is_intermittent)
from ..model.inertia import Dynamics
from ..geometry._base import cross2 as _cross, norm, rot90 as _perp
from .loads import AppliedCouple, AppliedForce, applied_loads, load_power, rotate as _rotate

#: condition number (of the system scaled to comparable units) above which a sample's reactions
#: are not computed: a dead centre or a toggle position, where they grow without bound
CONDITION_LIMIT = 1e12


def _unit(v: np.ndarray) -> np.ndarray:
    return v / norm(v)[..., None]


@dataclass(frozen=True)
class Reaction:
    """The reaction of one pair: the force (N, 2) in N that links[0] exerts on links[1] at
    `point` (N, 2; length unit), the couple (N,) in N·m that it exerts besides (a prismatic
    pair's; zero for the others), and its components by name ('x', 'y'; 'normal', 'couple';
    'radial'; 'tangential'), each (N,)."""

    joint: str
    links: tuple[str, str]
    point: np.ndarray
    force: np.ndarray
    couple: np.ndarray
    components: Mapping[str, np.ndarray]

    @property
    def magnitude(self) -> np.ndarray:
        return np.hypot(self.force[:, 0], self.force[:, 1])


@dataclass(frozen=True)
class ForceAnalysis:
    """The result of `kinetostatics` (arrays with the sample axis first; SI units except
    points, which are in the mechanism's length unit).

    `efforts`: per driver joint, the torque (N·m) or force (N) on the driven link;
    `virtual_work`: the same by the principle of virtual work from unit-speed velocities alone,
    without the reactions (one-degree-of-freedom check, *Prinzip der virtuellen Arbeit*);
    `power_residual`: driver power + power of all loads − rate of kinetic energy (W), which
    ideal pairs make zero, and `power_scale` the sum of the magnitudes of its terms;
    `condition`: of each sample's system (NaN where not solved); `solved`: samples whose
    reactions were computed (assembled, and not at a dead centre of the force transmission)."""

    dynamics: Dynamics
    solution: Solution
    inertia: bool
    reactions: Mapping[str, Reaction]
    efforts: Mapping[str, np.ndarray]
    virtual_work: Mapping[str, np.ndarray]
    frame_force: np.ndarray
    frame_moment: np.ndarray
    shaking_force: np.ndarray | None
    shaking_moment: np.ndarray | None
    kinetic_energy: np.ndarray | None
    kinetic_energy_rate: np.ndarray | None
    driver_power: np.ndarray
    power_residual: np.ndarray
    power_scale: np.ndarray
    condition: np.ndarray
    solved: np.ndarray

    def __len__(self) -> int:
        return len(self.solution)

    @property
    def effort(self) -> np.ndarray:
        """The one driver's torque or force (N,) (the first driver's with several)."""
        return next(iter(self.efforts.values()))


class _System:
    """The batched equilibrium equations A x = b: rows (3 per moving link: Fx, Fy, M about the
    link's reference point), columns the unknown reaction components and efforts."""

    def __init__(self, dyn: Dynamics, sol: Solution) -> None:
        self.mech = mech = dyn.mechanism
        self.sol, self.m = sol, dyn.metres_per_unit
        self.row = {ln: 3 * i for i, ln in enumerate(mech.moving_links)}
        # moments about a point of each link (its first), in metres
        self.ref = {ln: self.m * sol.point_on(ln, mech.points[mech.link(ln).points[0]]).position
                    for ln in mech.moving_links}
        self.columns: list[list[tuple[str, np.ndarray | None, np.ndarray | None, float]]] = []
        self.b = np.zeros((len(sol), 3 * len(mech.moving_links)))

    def column(self, *parts) -> int:
        """A new unknown; parts: (link, direction (N, 2) or None for a couple, point in metres,
        sign)."""
        self.columns.append([p for p in parts if p[0] in self.row])
        return len(self.columns) - 1

    def load(self, link: str, force: np.ndarray | None, point: np.ndarray | None,
             torque: np.ndarray | None = None) -> None:
        """A known load moves to the right-hand side."""
        if link not in self.row:
            return
        r = self.row[link]
        if force is not None:
            self.b[:, r:r + 2] -= force
            self.b[:, r + 2] -= _cross(point - self.ref[link], force)
        if torque is not None:
            self.b[:, r + 2] -= torque

    def matrix(self, sl: slice) -> np.ndarray:
        """A of the samples `sl` (n, equations, unknowns)."""
        n = len(range(*sl.indices(len(self.sol))))
        M, K = self.b.shape[1], len(self.columns)
        A = np.zeros((n, M, K))
        for k, parts in enumerate(self.columns):
            for ln, d, p, sign in parts:
                r = self.row[ln]
                if d is None:
                    A[:, r + 2, k] += sign
                else:
                    A[:, r:r + 2, k] += sign * d[sl]
                    A[:, r + 2, k] += sign * _cross(p[sl] - self.ref[ln][sl], d[sl])
        return A


def kinetostatics(dyn: Dynamics, sol: Solution, *, inertia: bool = True,
                  virtual_work: bool = True) -> ForceAnalysis:
    """Pair reactions and driver efforts of `dyn` moving as `sol` (solved to accelerations when
    `inertia`); `inertia=False` gives the static equilibrium (*statische Kräfte*) at the same
    positions. See the module's docstring for the sign convention. `virtual_work=False` skips
    that check (a second kinematic solve per driver; `ForceAnalysis.virtual_work` is then
    empty); the power balance is always computed."""
    mech = dyn.mechanism
    if mech is not sol.mechanism and not _same_drawing(mech, sol.mechanism):
        raise ModelError(f"the solution is of mechanism '{sol.mechanism.name}', the mass data "
                         f"of '{mech.name}', whose links or points differ")
    if inertia and sol.order < 2:
        raise ModelError("inertia forces need accelerations: solve to order 2 at least")
    dyn.require_masses(inertia=inertia)
    m = dyn.metres_per_unit
    forces, couples = applied_loads(dyn, sol, inertia=inertia)
    system = _System(dyn, sol)
    for f in forces:
        system.load(f.link, f.force, m * sol.point_on(f.link, f.point).position)
    for c in couples:
        system.load(c.link, None, None, c.torque)
    pairs = {j.name: _pair_columns(system, j) for j in mech.joints}
    drivers = {d.joint: _driver_column(system, d) for d in mech.drivers}
    x, cond, solved = _solve(system, mech.length_scale * m, sol)
    reactions = {name: _reaction(x, spec) for name, spec in pairs.items()}
    if dyn.loads.friction:
        x, reactions, f_forces, f_couples = _with_friction(dyn, sol, system, x, pairs, reactions)
        forces, couples = forces + f_forces, couples + f_couples
    efforts = {name: x[:, k] for name, (k, _, _) in drivers.items()}
    frame_force, frame_moment = _on_frame(mech, reactions, efforts, drivers, m)
    rates = {d.joint: _driver_rate(sol, d, m) for d in mech.drivers}
    driver_power = sum(efforts[jn] * rates[jn] for jn in efforts)
    p_loads = [load_power(sol, [f], [], m) for f in forces] + \
        [load_power(sol, [], [c], m) for c in couples]
    power_residual = driver_power + sum(p_loads, np.zeros(len(sol)))
    power_scale = np.abs(driver_power) + sum((np.abs(p) for p in p_loads), np.zeros(len(sol)))
    virtual = _virtual_work(dyn, sol, forces, couples) if virtual_work else {}
    have_masses = all(ln in dyn.masses for ln in mech.moving_links)
    energy = _energy(dyn, sol) if have_masses else (None, None)
    shaking = _shaking(dyn, sol) if have_masses and sol.order >= 2 else (None, None)
    return ForceAnalysis(dyn, sol, inertia, MappingProxyType(reactions), MappingProxyType(efforts),
                         MappingProxyType(virtual), frame_force, frame_moment, *shaking, *energy,
                         driver_power, power_residual, power_scale, cond, solved)


#: fixed-point iterations for Coulomb friction, and their relative tolerance
FRICTION_ITERATIONS, FRICTION_TOLERANCE = 100, 1e-14


def _with_friction(dyn: Dynamics, sol: Solution, system: "_System", x: np.ndarray,
                   pairs: dict, reactions: dict):
    """Coulomb friction by fixed-point iteration: the friction forces from the reactions of
    the previous step, moved to the right-hand side, until the reactions stop changing
    (contraction for μ·(lever arms) small enough: the usual case). The friction becomes part
    of each pair's reaction (component 'friction': a revolute pair's friction torque on
    links[1], N·m, signed; a sliding pair's friction force μ·|N|, N, opposing the sliding of
    links[1]) and of the loads (so that the power balance books its dissipation)."""
    m, b0 = dyn.metres_per_unit, system.b.copy()
    L = dyn.mechanism.length_scale * m
    scale = np.nanmax(np.abs(x), axis=1, initial=0.0)
    for _ in range(FRICTION_ITERATIONS):
        f_forces, f_couples, signed = _friction_loads(dyn, sol, reactions)
        system.b = b0.copy()
        for f in f_forces:
            system.load(f.link, f.force, m * sol.point_on(f.link, f.point).position)
        for c in f_couples:
            system.load(c.link, None, None, c.torque)
        with warnings.catch_warnings():  # said once, by the first solve
            warnings.simplefilter("ignore", LinkworkWarning)
            x_new, _, _ = _solve(system, L, sol)
        change = np.nanmax(np.abs(x_new - x), axis=1, initial=0.0)
        x = x_new
        reactions = {name: _reaction(x, spec) for name, spec in pairs.items()}
        if np.all(~(change > FRICTION_TOLERANCE * np.maximum(scale, np.nanmax(np.abs(x), axis=1, initial=0.0)))):
            break
    else:
        warnings.warn(f"Coulomb friction: the reactions did not settle in {FRICTION_ITERATIONS} "
                      "iterations (friction coefficients too large for this mechanism?); the "
                      "last iterate is given", LinkworkWarning, stacklevel=3)
    f_forces, f_couples, signed = _friction_loads(dyn, sol, reactions)
    for jn, (force, couple, value) in signed.items():
        r = reactions[jn]
        reactions[jn] = Reaction(r.joint, r.links, r.point, r.force + force, r.couple + couple,
                                 MappingProxyType({**r.components, "friction": value}))
    return x, reactions, f_forces, f_couples


def _friction_loads(dyn: Dynamics, sol: Solution, reactions: dict):
    """The friction of every pair with friction, as loads on both links, and per pair (force on
    links[1] (N, 2), couple on links[1] (N,), signed value (N,))."""
    mech, m = dyn.mechanism, dyn.metres_per_unit
    forces: list[AppliedForce] = []
    couples: list[AppliedCouple] = []
    signed = {}
    N = len(sol)
    for fr in dyn.loads.friction:
        j = mech.joint(fr.joint)
        a, b = j.links
        r = reactions[fr.joint]
        if j.kind == "revolute":
            w = sol.pose_derivatives(b)[1, :, 2] - sol.pose_derivatives(a)[1, :, 2]
            torque = -fr.coefficient * fr.radius * m * r.magnitude * np.sign(w)
            couples += [AppliedCouple(b, torque, "friction"), AppliedCouple(a, -torque, "friction")]
            signed[fr.joint] = (np.zeros((N, 2)), torque, torque)
            continue
        normal = np.abs(r.components["normal"] if "normal" in r.components else r.components["radial"])
        if j.kind == "cam":
            at = sol.joint(fr.joint)["point"]
            on_b = sol.local(b, at)
        else:
            on_b = np.broadcast_to(mech.points[j.point], (N, 2))
            at = sol.point_on(b, on_b).position
        on_a = sol.local(a, at)
        v = sol.point_on(b, on_b).velocity - sol.point_on(a, on_a).velocity
        speed = norm(v)
        t = np.divide(v, speed[:, None], out=np.zeros_like(v), where=speed[:, None] > 0)
        force = -fr.coefficient * normal[:, None] * t
        forces += [AppliedForce(b, on_b, force, "friction"), AppliedForce(a, on_a, -force, "friction")]
        signed[fr.joint] = (force, np.zeros(N), fr.coefficient * normal * (speed > 0))
    return forces, couples, signed


def _same_drawing(a, b) -> bool:
    """Two loads of one file: the same links carrying the same points at the same places."""
    return a.links == b.links and a.points.keys() == b.points.keys() and all(
        np.array_equal(a.points[p], b.points[p]) for p in a.points)


# ---------------------------------------------------------------------- columns of the pairs
def _pair_columns(s: _System, j) -> dict:
    """The unknowns of pair j: {'joint', 'links', 'point' (length unit), 'cols': {component:
    (column, direction or None for a couple)}}."""
    sol, mech, m = s.sol, s.mech, s.m
    a, b = j.links[0], j.links[1]
    if is_intermittent(j):
        raise ModelError(f"pair '{j.name}': forces in intermittent pairs ({j.kind}) are not "
                         "computed yet")
    cols: dict[str, tuple[int, np.ndarray | None]] = {}

    def force(name: str, d: np.ndarray, p: np.ndarray, on=(a, b)) -> None:
        cols[name] = (s.column((on[1], d, p, 1.0), (on[0], d, p, -1.0)), d)

    if isinstance(j, Revolute):
        p = m * sol.point(j.point).position
        N = len(sol)
        force("x", np.broadcast_to([1.0, 0.0], (N, 2)), p)
        force("y", np.broadcast_to([0.0, 1.0], (N, 2)), p)
    elif isinstance(j, (Prismatic, Slot)):
        p = m * sol.point_on(b, mech.points[j.point]).position
        u = _rotate(sol.pose_derivatives(a)[0, :, 2], j.axis / np.hypot(*j.axis))
        force("normal", _perp(u), p)
        if isinstance(j, Prismatic):
            cols["couple"] = (s.column((b, None, None, 1.0), (a, None, None, -1.0)), None)
    elif isinstance(j, CircularSlot):
        p = m * sol.point_on(b, mech.points[j.point]).position
        c = m * sol.point_on(a, mech.points[j.center]).position
        force("radial", _unit(p - c), p)
    elif isinstance(j, Gear):
        p, t = _pitch_point(sol, j)
        p = m * p
        force("tangential", t, p)
    elif isinstance(j, (CamContact, RollingContact)):
        rep = contact.report(sol, j.name)
        p, n = m * rep["point"], rep["normal"]
        if not (isinstance(j, RollingContact) and j.carrier):
            force("normal", n, p)
        if isinstance(j, RollingContact):
            force("tangential", _perp(n), p)
    else:  # pragma: no cover - every pair kind is handled above
        raise ModelError(f"pair '{j.name}': forces in {j.kind} pairs are not computed")
    return {"joint": j.name, "links": (a, b), "point": p / m, "cols": cols}


def _pitch_point(sol: Solution, g: Gear) -> tuple[np.ndarray, np.ndarray]:
    """The pitch point (length unit) and the unit tangent of the pitch circles there."""
    mech = sol.mechanism
    c1 = sol.point(mech.wheel_centre(g, g.links[0])).position
    r1, r2 = g.radii
    if g.gear_kind == "rack":
        guide = mech.rack_guide(g)
        n = _perp(_rotate(sol.pose_derivatives(g.carrier)[0, :, 2], guide.axis / np.hypot(*guide.axis)))
        probe = mech.points[g.point] if g.point else mech.points[guide.point]
        n0 = np.array([-guide.axis[1], guide.axis[0]])
        side = 1.0 if np.dot(probe - mech.points[mech.wheel_centre(g, g.links[0])], n0) >= 0 else -1.0
        e = side * n
    else:
        c2 = sol.point(mech.wheel_centre(g, g.links[1])).position
        e = _unit(c2 - c1)
        if g.gear_kind == "internal" and r1 < r2:
            e = -e  # the pinion touches the ring on its far side from the ring's centre
    return c1 + r1 * e, _perp(e)


def _driver_column(s: _System, d) -> tuple[int, np.ndarray | None, np.ndarray | None]:
    """(column, direction, point in metres) of a driver's effort; a torque has no direction."""
    sol, mech = s.sol, s.mech
    j = mech.joint(d.joint)
    if isinstance(j, Prismatic):
        u = _rotate(sol.pose_derivatives(d.base)[0, :, 2], j.axis / np.hypot(*j.axis))
        p = s.m * sol.point_on(d.driven, mech.points[j.point]).position
        return s.column((d.driven, u, p, 1.0), (d.base, u, p, -1.0)), u, p
    return s.column((d.driven, None, None, 1.0), (d.base, None, None, -1.0)), None, None


def _driver_rate(sol: Solution, d, m: float) -> np.ndarray:
    """The driver's speed: ω of the driven link relative to the base (rad/s), or the sliding
    velocity along the guide (m/s)."""
    if isinstance(sol.mechanism.joint(d.joint), Prismatic):  # its links are (base, driven)
        return m * sol.joint(d.joint)["sliding_velocity"]
    return sol.pose_derivatives(d.driven)[1, :, 2] - sol.pose_derivatives(d.base)[1, :, 2]


# ---------------------------------------------------------------------- solving
#: samples per block of the batched solve: the systems of a block stay in the CPU cache
BLOCK = 4096


def _solve(system: "_System", L: float, sol: Solution) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """x (N, K) of A x = b per sample, block by block; moment rows divided by L (and couple
    columns multiplied by L) so that the condition number (1-norm) compares like with like."""
    N, M, K = len(sol), system.b.shape[1], len(system.columns)
    if K < M:
        raise StructureError(
            f"the mechanism has {M - K} more degree(s) of freedom than drivers: its links are "
            "not in equilibrium under arbitrary loads (drive every freedom)")
    if K > M:
        warnings.warn(f"the mechanism is over-closed: {K - M} reaction component(s) are "
                      "statically indeterminate for rigid links; the reactions given are the "
                      "least-squares (minimum-norm) ones", LinkworkWarning, stacklevel=3)
    row_scale = np.ones(M)
    row_scale[2::3] = 1.0 / L
    col_scale = np.array([L if all(d is None for _, d, _, _ in parts) else 1.0
                          for parts in system.columns])
    x = np.full((N, K), np.nan)
    cond = np.full(N, np.nan)
    solved = np.zeros(N, dtype=bool)
    for lo in range(0, N, BLOCK):
        sl = slice(lo, min(N, lo + BLOCK))
        As = system.matrix(sl) * row_scale[None, :, None] * col_scale[None, None, :]
        bs = system.b[sl] * row_scale
        ok = np.isfinite(As).all(axis=(1, 2)) & np.isfinite(bs).all(axis=1) & \
            (sol.status[sl] != Status.UNREACHABLE)
        if not ok.any():
            continue
        As, bs = As[ok], bs[ok]
        inv = None
        if K == M:
            try:
                inv = np.linalg.inv(As)
            except np.linalg.LinAlgError:  # a sample exactly at a dead centre: the SVD below
                pass
        if inv is not None:
            c = np.abs(As).sum(axis=1).max(axis=1) * np.abs(inv).sum(axis=1).max(axis=1)
        else:
            sv = np.linalg.svd(As, compute_uv=False)
            c = sv[:, 0] / np.maximum(sv[:, -1], np.finfo(float).tiny)
            inv = np.linalg.pinv(As)
        good = np.isfinite(c) & (c < CONDITION_LIMIT)
        idx = np.flatnonzero(ok) + lo
        cond[idx] = c
        solved[idx] = good
        x[idx[good]] = np.einsum("nkm,nm->nk", inv[good], bs[good])
    return x * col_scale, cond, solved


def _reaction(x: np.ndarray, spec: dict) -> Reaction:
    N = x.shape[0]
    force = np.zeros((N, 2))
    couple = np.zeros(N)
    comps = {}
    for name, (k, d) in spec["cols"].items():
        comps[name] = x[:, k]
        if d is None:
            couple = couple + x[:, k]
        else:
            force = force + x[:, k, None] * d
    return Reaction(spec["joint"], spec["links"], spec["point"], force, couple, MappingProxyType(comps))


def _on_frame(mech, reactions: dict, efforts: dict, drivers: dict, m: float
              ) -> tuple[np.ndarray, np.ndarray]:
    # reaction points are in the length unit, driver points (`_driver_column`) in metres
    """Force and moment (about the frame's origin) that the moving links exert on the frame
    through its pairs and drivers."""
    N = len(next(iter(efforts.values())))
    F, M = np.zeros((N, 2)), np.zeros(N)
    for jn, r in reactions.items():
        a, b = r.links
        sign = -1.0 if a == mech.frame else 1.0 if b == mech.frame else 0.0
        if sign:
            F += sign * r.force
            M += sign * (_cross(m * r.point, r.force) + r.couple)
    for d in mech.drivers:
        if d.base != mech.frame:
            continue
        _, u, p = drivers[d.joint]
        if u is None:
            M -= efforts[d.joint]
        else:
            f = efforts[d.joint][:, None] * u
            F -= f
            M -= _cross(p, f)
    return F, M


# ---------------------------------------------------------------------- checks and energies
def _virtual_work(dyn: Dynamics, sol: Solution, forces: list[AppliedForce],
                  couples: list[AppliedCouple]) -> dict[str, np.ndarray]:
    """Each driver's effort from the principle of virtual work: minus the generalized force of
    all loads (inertia forces included), with the velocities of a motion in which that driver
    moves at unit speed and the others stand still (solved again at the same inputs)."""
    mech = dyn.mechanism
    nd = len(mech.drivers)
    out = {}
    for i, d in enumerate(mech.drivers):
        unit = np.zeros((len(sol), nd))
        unit[:, i] = 1.0
        # order 2: the compiled path of the solver (its accelerations are not used)
        vsol = solve(mech, sol.inputs, velocities=unit, accelerations=np.zeros_like(unit))
        scale = dyn.metres_per_unit if isinstance(mech.joint(d.joint), Prismatic) else 1.0
        out[d.joint] = -load_power(vsol, forces, couples, dyn.metres_per_unit) / scale
    return out


def _energy(dyn: Dynamics, sol: Solution) -> tuple[np.ndarray, np.ndarray | None]:
    """Kinetic energy (J) and its rate (W) of the moving links."""
    m = dyn.metres_per_unit
    T = np.zeros(len(sol))
    dT = np.zeros(len(sol)) if sol.order >= 2 else None
    for ln in dyn.mechanism.moving_links:
        mp = dyn.masses[ln]
        pm = sol.point_on(ln, mp.center)
        D = sol.pose_derivatives(ln)
        v = m * pm.velocity
        T += 0.5 * mp.mass * np.einsum("ij,ij->i", v, v) + 0.5 * mp.inertia * D[1, :, 2] ** 2
        if dT is not None:
            dT += mp.mass * m * np.einsum("ij,ij->i", v, pm.acceleration) + \
                mp.inertia * D[1, :, 2] * D[2, :, 2]
    return T, dT


def _shaking(dyn: Dynamics, sol: Solution) -> tuple[np.ndarray, np.ndarray]:
    """Shaking force −Σ m·a_S and moment −Σ (r_S × m·a_S + I_S·α) about the frame's origin."""
    m = dyn.metres_per_unit
    F, M = np.zeros((len(sol), 2)), np.zeros(len(sol))
    for ln in dyn.mechanism.moving_links:
        mp = dyn.masses[ln]
        pm = sol.point_on(ln, mp.center)
        f = -mp.mass * m * pm.acceleration
        F += f
        M += _cross(m * pm.position, f) - mp.inertia * sol.pose_derivatives(ln)[2, :, 2]
    return F, M
