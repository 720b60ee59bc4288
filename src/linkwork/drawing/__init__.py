"""Drawings as the textbooks draw them: SVG (and PNG/PDF from it), layers, scales, symbols,
the step-by-step construction model, and Matplotlib plots over the whole motion."""

from ..constructions.construction import (Arrow, Builder, Construction, ConstructionMismatch,
                           DegenerateConstruction, Element, Polygon, Result, Role, Segment, Step)
from .layers import LAYERS, Scene, draw_construction, scene_at, scene_figure
from ..constructions.scales import Scale, Scales, nice_ceil
from .svg import Figure

__all__ = ["Arrow", "Builder", "Construction", "ConstructionMismatch", "DegenerateConstruction",
           "Element", "Figure", "LAYERS", "Polygon", "Result", "Role", "Scale", "Scales", "Scene",
           "Segment", "Step", "draw_construction", "nice_ceil", "scene_at", "scene_figure"]
