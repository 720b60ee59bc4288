"""The classical graphical constructions, each drawn step by step and checked against the
exact result of the core engine (:mod:`linkwork.kinematics`) and the curvature layer
(:mod:`linkwork.instant`).

One module per construction; each public function takes ``(mechanism, inputs)`` — input values
in radians (or the length unit for a prismatic driver), or a ready `Solution` — and returns a
:class:`linkwork.drawing.Construction` evaluated at all positions at once (batch-first). Call
``.check()`` to raise if any result misses its analytic value by more than 1e-9 (relative),
``.sample(i)`` to draw one position, ``.describe()`` for the steps in words.

==================  ========================================================================
name                construction
==================  ========================================================================
rotated-velocities  Rosenauer's rotated (orthogonal) velocities on the mechanism (§38–39, §68)
velocity-plan       polar velocity plan with velocity images (§40–42); groups beyond the dyads
                    by Rosenauer's auxiliary points (1937, papers 1, 2, 7) or false position
acceleration-plan   velocity and acceleration plans, normal/tangential/Coriolis components;
                    groups beyond the dyads by the plan of relative normal accelerations
euler-savary        Euler–Savary by ruler, Rosenauer §19 Tasks I–III
bobillier           Bobillier's construction, collineation axis, Aronhold's transfer (§21–25)
hartmann            Hartmann's construction: pole-transfer velocity, centres of curvature
two-points          inflection and Bresse circles from v and a of two points (ch. XIV)
klein               Klein's construction of the piston acceleration (seed 004)
kennedy             Aronhold–Kennedy construction of all poles, line by line
mohr                Mohr's construction of b_B from b_A, slider-crank and four-bar (Pöschl §47–48)
relative-normals    relative normal accelerations v²/r by Thales semicircles on the mechanism
                    (Rosenauer 1937, papers 4, 5, 8)
rolling-lever       paper 8: the rolling lever's inflection circle, pole acceleration j_p = ω·V_p,
                    the valve's sliding acceleration (Rosenauer 1937)
slide-pairs         slides in moving planes: the velocity parallelogram, half-Coriolis by similar
                    triangles, the double parallelogram, the check lines (Rosenauer 1937, p. 3, 5)
==================  ========================================================================
"""

from __future__ import annotations

from typing import Callable

from .construction import Construction
from ..errors import InputError
from .acceleration_plan import acceleration_plan
from .bobillier import bobillier
from .euler_savary import euler_savary
from .hartmann import hartmann
from .kennedy import kennedy
from .klein import klein
from .mohr import mohr
from .relative_normals import relative_normals
from .rolling_lever import rolling_lever
from .rotated_velocities import rotated_velocities
from .slide_pairs import slide_pairs
from .two_points import inflection_from_two_points
from .velocity_plan import velocity_plan

CONSTRUCTIONS: dict[str, Callable[..., Construction]] = {
    "rotated-velocities": rotated_velocities,
    "velocity-plan": velocity_plan,
    "acceleration-plan": acceleration_plan,
    "euler-savary": euler_savary,
    "bobillier": bobillier,
    "hartmann": hartmann,
    "two-points": inflection_from_two_points,
    "klein": klein,
    "kennedy": kennedy,
    "mohr": mohr,
    "slide-pairs": slide_pairs,
    "relative-normals": relative_normals,
    "rolling-lever": rolling_lever,
}


def construct(name: str, mechanism, inputs, **options) -> Construction:
    """Run the construction ``name`` (see :data:`CONSTRUCTIONS`) at ``inputs``."""
    try:
        fn = CONSTRUCTIONS[name]
    except KeyError:
        raise InputError(f"unknown construction '{name}'; the constructions are "
                         f"{', '.join(CONSTRUCTIONS)}") from None
    return fn(mechanism, inputs, **options)


__all__ = ["CONSTRUCTIONS", "acceleration_plan", "bobillier", "construct", "euler_savary",
           "hartmann", "inflection_from_two_points", "kennedy", "klein", "mohr", "relative_normals",
           "rolling_lever", "rotated_velocities", "slide_pairs", "velocity_plan"]
