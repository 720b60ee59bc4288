"""Immutable, batch-first geometry value objects for planar kinematics.

One object holds one item (``shape == ()``) or a batch (``shape == (N,)``, sample axis first).
Points and lines are homogeneous, so poles of translating links and directions of parallel
lines are exact points at infinity. Invalid constructions raise :class:`GeometryError`.
"""

from .circle import Arc, Circle
from .constructions import (
    collinear,
    foot_of_perpendicular,
    harmonic_conjugate,
    midpoint,
    orientation,
    perpendicular_bisector,
    polar,
    reflect,
)
from .errors import GeometryError
from .intersect import IntersectionPair, intersect
from .line import Line
from .point import Point, Vector

__all__ = [
    "Arc", "Circle", "GeometryError", "IntersectionPair", "Line", "Point", "Vector",
    "collinear", "foot_of_perpendicular", "harmonic_conjugate", "intersect", "midpoint",
    "orientation", "perpendicular_bisector", "polar", "reflect",
]
