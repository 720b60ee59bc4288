"""The mechanism model: links, pairs and drivers of a planar mechanism, immutable and validated once.

Nothing here computes motion; `linkwork.kinematics` solves a `Mechanism` into a `Solution`.
"""

from .laws import ConstantSpeed, MotionLaw, PolynomialLaw, TabulatedLaw
from .mechanism import (
    CircularSlot,
    Driver,
    Gear,
    Joint,
    Link,
    Mechanism,
    Prismatic,
    Revolute,
    Slot,
)

__all__ = [
    "CircularSlot", "ConstantSpeed", "Driver", "Gear", "Joint", "Link", "Mechanism", "MotionLaw",
    "PolynomialLaw", "Prismatic", "Revolute", "Slot", "TabulatedLaw",
]
