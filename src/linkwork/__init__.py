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


#: the layers, loaded as attributes on first use too (`linkwork.instant.poles(...)`)
_LAYERS = frozenset({"cli", "constructions", "drawing", "forces", "geometry", "instant", "io",
                     "kinematics", "model", "outputs", "structure", "sweeps", "synthesis",
                     "topology", "units", "web"})


def __getattr__(name: str):
    if name in _HOME:
        return getattr(importlib.import_module(_HOME[name], __name__), name)
    if name in _LAYERS:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_HOME))
