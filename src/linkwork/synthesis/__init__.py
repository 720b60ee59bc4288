"""Synthesis: mechanisms designed from what they must do.

- `cams`: disc cams from a follower motion program (`model.motion_programs`, `model.disc_cams`):
  follower diagrams, pressure angle, radius of curvature, cusps and undercut, the smallest base
  circle, and the mechanism file of the designed cam.
"""

from .cams import (CamReport, analyse, corners, cusps, follower_diagrams, mechanism_text,
                   pressure_angle, radius_of_curvature, smallest_base_radius, with_base_radius)

__all__ = ["CamReport", "analyse", "corners", "cusps", "follower_diagrams", "mechanism_text",
           "pressure_angle", "radius_of_curvature", "smallest_base_radius", "with_base_radius"]
