"""Forward dynamics of a one-degree-of-freedom mechanism (German *Anlauf*, the run-up of a
crank): the driver's equation of motion J(q)·q̈ + ½·J′(q)·q̇² = T_motor + Q(q, q̇), integrated
with SciPy.

The effort the kinetostatics needs at (q, q̇) with q̈ = 0 is T₀ = ½·J′·q̇² − Q, and the effort
is linear in q̈ with slope J (`reduced.reduced_inertia`), so q̈ = (T_motor − T₀)/J: every
evaluation is one kinematic solve and one kinetostatic solve of a single sample, the same
code as the inverse problem (loads, springs, dampers, gravity, friction).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import InputError, SolveError
from ..kinematics import Status, solve
from ..model.inertia import Dynamics
from .kinetostatics import kinetostatics
from .reduced import reduced_inertia


@dataclass(frozen=True)
class Motion:
    """Times (s), the input q (rad or length unit), its speed and acceleration, each (N,)."""

    time: np.ndarray
    input: np.ndarray
    speed: np.ndarray
    acceleration: np.ndarray


def simulate(dyn: Dynamics, effort: float | Callable, duration: float, *, start: float | None = None,
             speed: float = 0.0, samples: int = 201, rtol: float = 1e-9) -> Motion:
    """Integrate the driver's motion over `duration` seconds from input `start` (default: the
    design position) at `speed` under the motor `effort` (N·m or N; a number, or a callable
    f(t, q, q̇)). The mechanism must have one driver; loads tabulated against time are not
    supported here."""
    mech = dyn.mechanism
    if len(mech.drivers) != 1:
        raise InputError("forward dynamics needs a mechanism with one driver")
    if not (np.isfinite(duration) and duration > 0) or samples < 2:
        raise InputError("simulate: give a positive duration and at least two samples")
    from scipy.integrate import solve_ivp
    dyn.require_masses(inertia=True)
    d = mech.drivers[0]
    per = dyn.metres_per_unit if mech.joint(d.joint).kind == "prismatic" else 1.0
    motor = effort if callable(effort) else (lambda t, q, w: float(effort))

    def acceleration(t: float, q: float, w: float) -> float:
        sol = solve(mech, [q], velocities=[w], accelerations=[0.0])
        if sol.status[0] == Status.UNREACHABLE:
            raise SolveError(f"forward dynamics: the mechanism cannot be assembled at input "
                             f"{q:g} (t = {t:g} s): it has run into a limit position")
        t0 = kinetostatics(dyn, sol, virtual_work=False).effort[0]
        J = reduced_inertia(dyn, [q]).inertia[0]
        if not (np.isfinite(t0) and J > 0):
            raise SolveError(f"forward dynamics: no finite reduced inertia or effort at input "
                             f"{q:g} (t = {t:g} s)")
        # J and the effort in SI; q of a prismatic driver is in the length unit
        return (motor(t, q, w) - t0) / J / per

    q0 = mech.driver_input_at_design(d) if start is None else float(start)
    t_eval = np.linspace(0.0, duration, samples)
    res = solve_ivp(lambda t, y: [y[1], acceleration(t, y[0], y[1])], (0.0, duration), [q0, speed],
                    t_eval=t_eval, rtol=rtol, atol=rtol * (1.0 + abs(speed)) * 1e-3, method="DOP853")
    if not res.success:
        raise SolveError(f"forward dynamics: the integration stopped: {res.message}")
    acc = np.array([acceleration(t, q, w) for t, q, w in zip(res.t, res.y[0], res.y[1])])
    return Motion(res.t, res.y[0], res.y[1], acc)
