"""Synthesis: mechanisms designed from what they must do.

- `cams`: disc cams from a follower motion program (`model.motion_programs`, `model.disc_cams`):
  follower diagrams, pressure angle, radius of curvature, cusps and undercut, the smallest base
  circle, and the mechanism file of the designed cam.
- `positions`: finite positions of a moving plane: poles, rotation angles, the pole triangle,
  image poles, Pöschl's image point, circle point ↔ centre point (two and three positions).
- `reflections`: Hamilton's construction (Pöschl §57) of the poles, the pole triangle and
  homologous points by reflections, step by step (`constructions` model, checked).
- `burmester`: the centre-point and circle-point cubics of four positions, the Burmester points
  of five (polynomial roots), dyads.
- `linkages`: four-bars and slider-cranks from two dyads, their mechanism files and checks
  (Grashof type, order, circuit and branch defects, transmission angle, the engine's poses).
- `function`: function generation with Freudenstein's equation (four-bar, slider-crank):
  precision points, Chebyshev spacing, least squares, the structural error.
- `path`: path generation: a four-bar's coupler point through target points (least squares
  from several starts, with or without prescribed timing).
- `six_bar_path`: path generation with Watt I and Stephenson III six-bars (least squares
  from several starts, each a random six-bar fitted onto the targets by a similarity).
- `second_order`: Alt's dwell linkage and Pröll's substitution, from curvature theory.
- `cognates`: the Roberts–Chebyshev cognates of a four-bar's coupler point.
- `straight_line`: straight-line guidance: the straightness of any path (over a stroke), a
  Ball-point tracer, Watt's, Chebyshev's and Evans's linkages from requirements, Hart's exact
  line from any four-bar.
"""

from .burmester import (BurmesterPoints, Cubic, Dyad, burmester_points, centre_point_curve,
                        circle_point_curve, curve_samples, dyad)
from .cognates import Cognates, cognates
from .cams import (CamReport, analyse, corners, cusps, follower_diagrams, mechanism_text,
                   pressure_angle, radius_of_curvature, smallest_base_radius, with_base_radius)
from .function import FunctionGenerator, FunctionTask, chebyshev_spacing, freudenstein, function_generator
from .linkages import Linkage, LinkageCheck, linkages
from .path import PathGenerator, path_generator
from .six_bar_path import SixBarPath, six_bar_path_generator
from .second_order import DwellLinkage, Substitution, alt_dwell, proell_substitution
from .straight_line import (Straightness, StraightLineLinkage, ball_point_linkage, chebyshev_linkage,
                            evans_linkage, hart_straight_line, path_straightness, straightness,
                            watt_linkage)
from .positions import (Positions, SynthesisError, centre_points, circle_points, image_point,
                        image_pole, pole_triangle)

__all__ = ["BurmesterPoints", "CamReport", "Cognates", "cognates", "Cubic", "DwellLinkage", "Dyad", "FunctionGenerator",
           "FunctionTask", "Linkage", "LinkageCheck", "PathGenerator", "Positions", "Substitution",
           "SynthesisError", "alt_dwell", "chebyshev_spacing", "freudenstein", "function_generator",
           "path_generator", "proell_substitution", "analyse", "burmester_points", "centre_point_curve", "centre_points",
           "circle_point_curve", "circle_points", "corners", "curve_samples", "cusps", "dyad",
           "follower_diagrams", "image_point", "image_pole", "linkages", "mechanism_text",
           "pole_triangle", "pressure_angle", "radius_of_curvature", "smallest_base_radius",
           "with_base_radius", "Straightness", "StraightLineLinkage", "ball_point_linkage",
           "chebyshev_linkage", "evans_linkage", "hart_straight_line", "path_straightness", "straightness",
           "watt_linkage", "SixBarPath", "six_bar_path_generator"]
