"""`solve_at`: a mechanism where a command or the workbench asks for it — at input values, at
times, or (asked nothing) where it stands in its file. The one place that knows that a chain
driven by given point velocities (`[[given]]`, paper 2's free and open chains) has no inputs and
is solved at its drawn position only."""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..model import Mechanism, Prismatic
from .solution import Solution, Status
from .solver import solve


def solve_at(mech: Mechanism, inputs=None, *, times=None, order: int | None = None,
             previous: Mechanism | None = None, asked: str = "input values") -> Solution:
    """`solve(mech, inputs, times=…, order=…, previous=…)`, the design position when neither
    inputs nor times are given (order 2 unless given). A chain driven by given point
    velocities is solved at its drawn position by `point_inputs.solve_given`, to `order` (at
    most 2; an order its data do not give is refused, naming what is missing) or, unset, as far
    as its data go (accelerations where they give them or their paths' curvatures); inputs or
    times are then refused, the message naming them as the caller calls them (`asked`:
    "--at", "at or times", …)."""
    if mech.given:
        if (inputs is not None and np.size(inputs)) or times is not None:
            raise InputError(f"mechanism '{mech.name}' is driven by given point velocities: it is "
                             f"solved at its drawn position only, and takes no {asked}")
        from .point_inputs import solve_given
        return solve_given(mech, order=None if order is None else min(order, 2))
    order = 2 if order is None else order
    if times is not None:
        return solve(mech, times=times, order=order, previous=previous)
    return solve(mech, inputs, order=order, previous=previous)


def require_assembled(sol: Solution, i: int = 0, where: str | None = None) -> None:
    """An `InputError` when sample `i` of `sol` cannot be assembled (unreachable), naming
    where: `where`, else the sample's input values (and time)."""
    if sol.status[i] != Status.UNREACHABLE:
        return
    mech = sol.mechanism
    if where is None:
        parts = []
        for d, v in zip(mech.drivers, sol.inputs[i]):
            prismatic = isinstance(mech.joint(d.joint), Prismatic)
            parts.append(f"{d.joint} = {v:.6g} {mech.length_unit}" if prismatic
                         else f"{d.joint} = {np.degrees(v):.6g}°")
        where = "input " + ", ".join(parts)
        if sol.time is not None:
            where = f"t = {sol.time[i]:g} s ({where})"
    raise InputError(f"mechanism '{mech.name}' cannot be assembled at {where}: its chain does "
                     "not close there (beyond a limit position of its input, or its links too "
                     "short to reach)")
