"""Kinematics: solving a `Mechanism` into a `Solution` (positions, velocities, accelerations)."""

from .at import solve_at
from .designs import solve_designs
from .intermittent import engagement
from .kernels import compiled_loops
from .motion import whole_motion
from .solution import LinkMotion, PointMotion, Solution, Status
from .solver import solve

__all__ = ["LinkMotion", "compiled_loops", "PointMotion", "Solution", "Status", "engagement", "solve",
           "solve_at", "solve_designs",
           "whole_motion"]
