"""Instantaneous kinematics of any link i relative to any link j: poles, centrodes, curvature.

Algorithms are functions over a `Solution` (NetworkX style), batch-first: one call answers one
sample or the whole motion. The moving link comes first, `relative_to` defaults to the frame.

    >>> sol = linkwork.solve(mech, np.radians([0, 30, 60]), order=3)
    >>> P = poles(sol)["frame", "coupler"]            # geometry.Point, shape (3,)
    >>> inflection_circle(sol, "coupler").radius       # Wendekreis, D/2
    >>> centrodes(linkwork.whole_motion(mech, order=3), "coupler").fixed_xy

Modules: `motion` (relative motion of two links, exact derivatives), `poles` (all poles from
velocities and by the Aronhold–Kennedy theorem, pole lines), `centrodes` (Rastpolbahn and
Gangpolbahn with their curvature), `curvature` (second-order curvature theory: inflection,
return and Bresse circles, Γ, Euler–Savary, envelopes, Bobillier; across a higher pair the
profiles' curvature centres as conjugate points), `equivalent` (the equivalent linkage of a
higher pair, Ersatzgetriebe), `third_order` (cubic of stationary curvature, Ball and Burmester
points).
"""

from .centrodes import Centrodes, centrode_profiles, centrodes
from .curvature import (Collineation, ContactCurvature, Envelope, Instant, PathCurvature,
                        acceleration_pole, bobillier_pole_tangent, bresse_circle, collineation_axis,
                        conjugate, contact_curvature, curvature_centre, element_centres, envelope,
                        euler_savary, inflection_circle, instant, line_envelope, path,
                        pole_velocity, return_circle)
from .equivalent import (EquivalentLinkage, equivalent_linkage, equivalent_mechanism,
                         solve_equivalent)
from .motion import RelativeMotion, relative_motion
from .poles import (PoleLine, Poles, PoleSchedule, PoleStep, agreement, kennedy_poles,
                    pole_count, pole_discrepancy, pole_line_count, pole_lines, pole_schedule,
                    poles)
from .third_order import (BurmesterPoints, StationaryCurvature, ball_point, burmester_points,
                          fourth_order, stationary_curvature)

__all__ = [
    "centrode_profiles",
    "BurmesterPoints", "Centrodes", "Collineation", "ContactCurvature", "Envelope",
    "EquivalentLinkage", "Instant", "PathCurvature",
    "PoleLine", "PoleSchedule", "PoleStep", "Poles", "RelativeMotion", "StationaryCurvature",
    "acceleration_pole", "agreement", "ball_point", "bobillier_pole_tangent", "bresse_circle",
    "burmester_points", "centrodes", "collineation_axis", "conjugate", "contact_curvature",
    "curvature_centre", "element_centres", "envelope", "equivalent_linkage",
    "equivalent_mechanism", "euler_savary", "fourth_order", "inflection_circle", "instant",
    "kennedy_poles", "line_envelope", "path", "pole_count", "pole_discrepancy",
    "pole_line_count", "pole_lines", "pole_schedule", "pole_velocity", "poles",
    "relative_motion", "return_circle", "solve_equivalent", "stationary_curvature",
]
