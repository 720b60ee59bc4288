"""Topology of mechanisms: the bare graph of links and pairs, below the kinematics.

The solution order (groups, *Gruppen*, in the order they are solved), the counting formulas and
the chain atlas need only `model` and NetworkX, never a solved position, so `kinematics` builds on
them. The analyses that need the solver (real mobility, Grashof, Assur classes) live in
`structure`, above `kinematics`.
"""

from .counts import kutzbach
from .groups import (Group, RotationClasses, constraint_count, slider_loop, solution_order,
                     structure_key)

__all__ = ["Group", "RotationClasses", "constraint_count", "kutzbach", "slider_loop",
           "solution_order", "structure_key"]
