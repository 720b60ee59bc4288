"""Profiles of higher pairs: the curves a cam, a follower face, a track or a rolling wheel carries
(see `base` for the protocol and the conventions every profile keeps).

- `CircleProfile`, `EllipseProfile`, `InvoluteProfile`, `ArchimedeanSpiral`, `LogarithmicSpiral`,
  `LineProfile`: closed forms.
- `PathProfile` of `LineTo` and `ArcTo` segments: the books' cams; `joins()` and `curvature_jumps`.
- `SplineProfile`: an interpolating spline (quintic by default) through points.
- `PolarProfile` r(φ) and `ParametricProfile` c(u): curves given by code with their derivatives.
- `OffsetProfile` and `offset_cusps`: pitch curves of rollers and their undercut.
"""

from .base import (
    BaseProfile,
    CircleProfile,
    Profile,
    ProfileError,
    curvature,
    curvature_jumps,
    derivatives_at,
)
from .curves import (
    ArchimedeanSpiral,
    EllipseProfile,
    InvoluteProfile,
    LineProfile,
    LogarithmicSpiral,
    ParametricProfile,
    PolarProfile,
)
from .offset import OffsetProfile, offset_cusps, sign_changes
from .path import ArcTo, Joins, LineTo, PathProfile
from .spline import SplineProfile

__all__ = [
    "ArcTo", "ArchimedeanSpiral", "BaseProfile", "CircleProfile", "EllipseProfile", "InvoluteProfile",
    "Joins", "LineProfile", "LineTo", "LogarithmicSpiral", "OffsetProfile", "ParametricProfile",
    "PathProfile", "PolarProfile", "Profile", "ProfileError", "SplineProfile", "curvature",
    "curvature_jumps", "derivatives_at", "offset_cusps", "sign_changes",
]
