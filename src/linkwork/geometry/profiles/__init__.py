"""Profiles of higher pairs (see `base` for the protocol): circles, paths of lines and arcs,
splines through points, closed-form curves, offsets."""

from .base import (
    BaseProfile,
    CircleProfile,
    Profile,
    ProfileError,
    curvature,
    curvature_jumps,
    derivatives_at,
)

__all__ = [
    "BaseProfile", "CircleProfile", "Profile", "ProfileError", "curvature", "curvature_jumps",
    "derivatives_at",
]
