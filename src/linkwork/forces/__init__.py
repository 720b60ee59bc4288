"""Forces: kinetostatics on the exact kinematics (pair reactions, driving torques, shaking
forces), reduced inertia at the driver, and the inertia forces of reciprocating masses.

    >>> dyn = linkwork.forces.load_dynamics("library:crank-rocker")
    >>> fa = kinetostatics(dyn, linkwork.whole_motion(dyn.mechanism))
    >>> fa.effort  # the driving torque over the cycle, N·m
"""

from .kinetostatics import CONDITION_LIMIT, ForceAnalysis, Reaction, kinetostatics
from .loads import AppliedCouple, AppliedForce, applied_loads

__all__ = ["AppliedCouple", "AppliedForce", "CONDITION_LIMIT", "ForceAnalysis", "Reaction",
           "applied_loads", "kinetostatics"]
