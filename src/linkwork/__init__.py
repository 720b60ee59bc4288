"""linkwork: kinematics of planar mechanisms, computed exactly and drawn as the textbooks do.

    >>> import linkwork
    >>> mech = linkwork.load("library:crank-rocker")
    >>> sol = linkwork.solve(mech, np.radians([0, 30, 60]))
    >>> sol.point("B").velocity

Layers: `model` (the mechanism), `io` (files), `topology` (solution order), `kinematics`
(solutions), `structure` (mobility), `instant` (poles, curvature), `cli`. See docs/ARCHITECTURE.md.
"""

from .errors import LinkworkError
from .io import load, load_text
from .kinematics import Solution, Status, solve, whole_motion
from .model import Mechanism

__all__ = ["LinkworkError", "Mechanism", "Solution", "Status", "load", "load_text", "solve",
           "whole_motion"]
