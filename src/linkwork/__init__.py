"""linkwork: kinematics of planar mechanisms, computed exactly and drawn as the textbooks do.

    >>> import linkwork
    >>> mech = linkwork.load("library:crank-rocker")
    >>> sol = linkwork.solve(mech, np.radians([0, 30, 60]))
    >>> sol.point("B").velocity

Layers: `model` (the mechanism), `io` (files), `topology` (solution order), `kinematics`
(solutions), `structure` (mobility), `instant` (poles, curvature), `cli`. See docs/ARCHITECTURE.md.
"""

from __future__ import annotations

import importlib

from .errors import LinkworkError

#: where each name of the package's surface lives; loaded on first use (PEP 562), so that a
#: command that needs little (`linkwork library`) does not import the solver
_HOME = {"load": ".io", "load_text": ".io", "Mechanism": ".model", "Solution": ".kinematics",
         "Status": ".kinematics", "solve": ".kinematics", "whole_motion": ".kinematics"}

__all__ = ["LinkworkError", "Mechanism", "Solution", "Status", "load", "load_text", "solve",
           "whole_motion"]


def __getattr__(name: str):
    if name in _HOME:
        return getattr(importlib.import_module(_HOME[name], __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_HOME))
