"""The mechanism model: links, pairs and drivers of a planar mechanism, immutable and validated once.

Nothing here computes motion; `linkwork.kinematics` solves a `Mechanism` into a `Solution`.
"""

from .higher_pairs import CamContact, DesignContact, HigherPair, RollingContact, design_contact
from .disc_cams import DiscCam
from .given import Given, GivenDirection, GivenVelocity, hinge_chain
from .intermittent import (GenevaPair, IndexingSchedule, IntermittentPair, StarWheelPair,
                           indexing_schedule, is_intermittent)
from .laws import ConstantSpeed, MotionLaw, PolynomialLaw, TabulatedLaw
from .motion_programs import CamDesignError, MotionProgram, Segment
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
    "CamContact", "CamDesignError", "CircularSlot", "ConstantSpeed", "DesignContact", "DiscCam",
    "HigherPair", "MotionProgram", "RollingContact", "Segment",
    "design_contact", "Driver", "Gear", "Given", "GivenDirection", "GivenVelocity", "hinge_chain", "Joint", "Link", "Mechanism", "MotionLaw",
    "PolynomialLaw", "Prismatic", "Revolute", "Slot", "TabulatedLaw",
    "GenevaPair", "IndexingSchedule", "IntermittentPair", "StarWheelPair", "indexing_schedule",
    "is_intermittent",
]
