"""The inertia forces of the reciprocating masses of a slider-crank (German
*Beschleunigungsdrücke*, *Massendrücke*; seed 004): exact, from the solved piston
acceleration, and as the first and second harmonic of the usual series,
F ≈ m·r·ω²·(cos φ + λ·cos 2φ), λ = r/l (the piston accelerates by
≈ −r·ω²·(cos φ + λ·cos 2φ)), with the error of that approximation.

φ is the crank angle from the outer dead centre (crank pin on the line of stroke, on the
crosshead's side); the force is the d'Alembert force −m·a of the reciprocating mass along the
line of stroke, positive from the crank axis towards the crosshead.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ModelError
from ..kinematics import Solution
from ..model import Prismatic, Revolute


@dataclass(frozen=True)
class ReciprocatingInertia:
    """Arrays (N,): crank angle φ (rad, from the outer dead centre), the exact inertia force
    (N), its first and second harmonics and their sum's error (exact − both harmonics)."""

    angle: np.ndarray
    exact: np.ndarray
    first: np.ndarray
    second: np.ndarray
    crank_radius: float
    rod_length: float

    @property
    def error(self) -> np.ndarray:
        return self.exact - self.first - self.second


def _slider_crank(mech):
    """(crank hinge, crank pin, crosshead pin, guide) of a centric slider-crank."""
    guide = next((j for j in mech.joints if isinstance(j, Prismatic) and mech.frame in j.links), None)
    d = mech.drivers[0] if len(mech.drivers) == 1 else None
    if guide is None or d is None or not isinstance(mech.joint(d.joint), Revolute):
        raise ModelError(f"'{mech.name}' is not a slider-crank driven at its crank (one revolute "
                         "driver on the frame and a block on a prismatic guide of the frame)")
    block = guide.links[1]
    hinge = lambda la, lb: next((j.point for j in mech.joints if isinstance(j, Revolute)
                                 and set(j.links) == {la, lb}), None)
    rods = [ln for ln in mech.moving_links if hinge(ln, block) and hinge(ln, d.driven)]
    if not rods:
        raise ModelError(f"'{mech.name}': no connecting rod hinged to both the crank "
                         f"'{d.driven}' and the block '{block}'")
    rod = rods[0]
    return mech.joint(d.joint).point, hinge(d.driven, rod), hinge(rod, block), guide


def reciprocating_inertia(sol: Solution, mass: float) -> ReciprocatingInertia:
    """The inertia force of the reciprocating `mass` (kg) of the slider-crank solved in `sol`
    (crank speed ω from the solution; lengths converted to metres by the mechanism's unit)."""
    from ..units import parse_quantity
    mech = sol.mechanism
    O, A, B, guide = _slider_crank(mech)
    m_per = parse_quantity(f"1 {mech.length_unit}", default_unit="m", kind="length unit")
    p = mech.points
    r = float(np.hypot(*(p[A] - p[O])))
    rod = float(np.hypot(*(p[B] - p[A])))
    u = guide.axis / np.hypot(*guide.axis)
    u = u if np.dot(p[B] - p[O], u) >= 0 else -u  # from the crank axis towards the crosshead
    d = p[O] - p[B]
    offset = abs(float(u[0] * d[1] - u[1] * d[0]))
    if offset > 1e-9 * mech.length_scale:
        raise ModelError(f"'{mech.name}' is an offset slider-crank (offset {offset:g}); the "
                         "harmonic series is that of the centric one")
    pin, crank_axis = sol.point(A).position, p[O]
    rel = pin - crank_axis
    phi = np.arctan2(rel[:, 1] * u[0] - rel[:, 0] * u[1], rel @ u)
    omega = sol.pose_derivatives(mech.drivers[0].driven)[1, :, 2]
    exact = -mass * m_per * (sol.point(B).acceleration @ u)
    c = mass * r * m_per * omega**2
    return ReciprocatingInertia(phi, exact, c * np.cos(phi), c * (r / rod) * np.cos(2 * phi), r, rod)
