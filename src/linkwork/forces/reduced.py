"""The reduced (equivalent) moment of inertia or mass at a driver (German *reduziertes
Massenträgheitsmoment*), its derivative along the input, and flywheel sizing.

With every link's centre-of-mass velocity and angular velocity proportional to the input speed
q̇ (one degree of freedom), the kinetic energy is ½·J(q)·q̇² with
J(q) = Σ m·|∂r_S/∂q|² + I_S·(∂θ/∂q)², and the driver's equation of motion (Lagrange) is
T = J·q̈ + ½·J′·q̇² − Q (Q the generalized force of the loads). J and J′ come from one solve at
unit input speed and zero input acceleration, where velocities are ∂/∂q and accelerations
∂²/∂q².
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..kinematics import solve
from ..model import Prismatic
from ..model.inertia import Dynamics


@dataclass(frozen=True)
class ReducedInertia:
    """J (N,) in kg·m² for a revolute driver (kg for a prismatic one) and dJ/dq (N,) per
    radian (per metre), at the inputs `inputs` (N,)."""

    inputs: np.ndarray
    inertia: np.ndarray
    derivative: np.ndarray


def reduced_inertia(dyn: Dynamics, inputs, *, driver: int = 0) -> ReducedInertia:
    """J(q) and J′(q) of driver number `driver` at `inputs` (the other drivers held still)."""
    mech = dyn.mechanism
    dyn.require_masses(inertia=True)
    q = np.atleast_1d(np.asarray(inputs, dtype=float))
    nd = len(mech.drivers)
    if not 0 <= driver < nd:
        raise InputError(f"driver number {driver}: the mechanism has {nd} driver(s)")
    values = q[:, None] if nd == 1 else q
    if values.ndim != 2 or values.shape[1] != nd:
        raise InputError(f"inputs: give one value per driver ({nd}) for each sample")
    unit = np.zeros_like(values)
    unit[:, driver] = 1.0
    sol = solve(mech, values, velocities=unit, accelerations=np.zeros_like(unit), order=2)
    m = dyn.metres_per_unit
    # per metre of a prismatic input: lengths per length unit stay, angles per unit scale
    per = m if isinstance(mech.joint(mech.drivers[driver].joint), Prismatic) else 1.0
    J = np.zeros(len(sol))
    dJ = np.zeros(len(sol))
    for ln in mech.moving_links:
        mp = dyn.masses[ln]
        pm = sol.point_on(ln, mp.center)
        D = sol.pose_derivatives(ln)
        v, a = m * pm.velocity / per, m * pm.acceleration / per**2
        w, al = D[1, :, 2] / per, D[2, :, 2] / per**2
        J += mp.mass * np.einsum("ij,ij->i", v, v) + mp.inertia * w * w
        dJ += 2 * (mp.mass * np.einsum("ij,ij->i", v, a) + mp.inertia * w * al)
    return ReducedInertia(q, J, dJ)


@dataclass(frozen=True)
class Flywheel:
    """Flywheel sizing from the energy fluctuation over one period: the largest swing ΔE (J) of
    ∫(T − T_mean)·dq, and the moment of inertia J = ΔE / (δ·ω_m²) that keeps the coefficient
    of speed fluctuation δ = (ω_max − ω_min)/ω_m (German *Ungleichförmigkeitsgrad*) at the mean
    speed ω_m (first-order estimate, the mechanism's own varying inertia left out)."""

    mean_effort: float
    energy_fluctuation: float
    inertia: float


def flywheel(angle, effort, *, mean_speed: float, fluctuation: float) -> Flywheel:
    """Size a flywheel from the driving torque `effort` (N·m) over one full period of `angle`
    (rad, increasing; the last sample one period after the first), trapezoidal rule."""
    q = np.asarray(angle, dtype=float)
    T = np.asarray(effort, dtype=float)
    if q.ndim != 1 or q.shape != T.shape or len(q) < 3 or np.any(np.diff(q) <= 0):
        raise InputError("flywheel: give the torque at increasing angles over one period "
                         "(at least three samples)")
    if not np.isfinite(T).all():
        raise InputError("flywheel: the torque is not finite at every sample (a dead centre?)")
    if not (fluctuation > 0 and mean_speed != 0):
        raise InputError("flywheel: the coefficient of speed fluctuation must be positive and "
                         "the mean speed non-zero")
    steps = 0.5 * (T[1:] + T[:-1]) * np.diff(q)
    mean = steps.sum() / (q[-1] - q[0])
    E = np.concatenate([[0.0], np.cumsum(steps - mean * np.diff(q))])
    dE = float(E.max() - E.min())
    return Flywheel(float(mean), dE, dE / (fluctuation * mean_speed**2))
