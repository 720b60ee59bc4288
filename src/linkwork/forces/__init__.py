"""Forces: kinetostatics on the exact kinematics (pair reactions, driving torques, shaking
forces, Coulomb friction as an option), the reduced inertia at the driver and flywheel sizing,
forward dynamics of one driver, and the inertia forces of reciprocating masses.

    >>> from linkwork.io import load_dynamics
    >>> dyn = load_dynamics("library:crank-rocker")
    >>> fa = kinetostatics(dyn, linkwork.whole_motion(dyn.mechanism))
    >>> fa.effort  # the driving torque over the cycle, N·m
"""

from .kinetostatics import CONDITION_LIMIT, ForceAnalysis, Reaction, kinetostatics
from .loads import AppliedCouple, AppliedForce, applied_loads
from .reciprocating import ReciprocatingInertia, reciprocating_inertia
from .reduced import Flywheel, ReducedInertia, flywheel, reduced_inertia
from .simulation import Motion, simulate

__all__ = ["AppliedCouple", "AppliedForce", "CONDITION_LIMIT", "Flywheel", "ForceAnalysis", "Motion",
           "Reaction", "ReciprocatingInertia", "ReducedInertia", "applied_loads", "flywheel",
           "kinetostatics", "reciprocating_inertia", "reduced_inertia", "simulate"]
