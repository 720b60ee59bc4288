"""The library's mechanisms with higher pairs, each against its seed facts and an independent
closed form.

- Eccentric disc cams (Pöschl §43, Abb. 46 Nr. 20; §49, Abb. 56, 57, 59): an eccentric circle
  with a roller is exactly the slider-crank (centric or offset) through the disc's centre, with a
  flat face the Scotch yoke, with an oscillating roller lever the four-bar; the closed forms are
  derived here from the design dimensions, not from the solver.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

import linkwork
from linkwork import Status

PHI = np.radians(np.arange(0.0, 360.0, 2.5) + 0.7)


@lru_cache(maxsize=None)
def mech(name: str):
    return linkwork.load(f"library:{name}")


def solve(name: str, phi=PHI, order: int = 3):
    sol = linkwork.solve(mech(name), phi, order=order)
    assert (sol.status == Status.OK).all()
    return sol


# ---------------------------------------------------------------------------- eccentric cams
E_, R_, RHO_ = 10.0, 30.0, 8.0  # disc eccentricity, radius and roller radius of the files


def offset_slider_crank(phi, crank, rod, offset):
    """Slider on the line x = offset driven by crank `crank` (pin at angle φ, ω = 1) and rod
    `rod`: y = crank·sin φ + √(rod² − (offset − crank·cos φ)²) and its first three derivatives."""
    c, s = np.cos(phi), np.sin(phi)
    g, g1, g2, g3 = offset - crank * c, crank * s, crank * c, -crank * s
    w = np.sqrt(rod**2 - g * g)
    w1 = -g * g1 / w
    w2 = -(g1 * g1 + g * g2 + w1 * w1) / w
    w3 = -(3 * g1 * g2 + g * g3 + 3 * w1 * w2) / w
    return crank * s + w, crank * c + w1, -crank * s + w2, -crank * c + w3


@pytest.mark.parametrize("name,offset", [("radial-roller-cam", 0.0), ("offset-roller-cam", 15.0)])
def test_roller_on_an_eccentric_is_the_slider_crank_through_its_centre(name, offset):
    m = mech(name)
    assert np.allclose(m.points["E"], [E_, 0.0]) and m.joint("K").radius == RHO_
    w = 2 * np.pi  # 60 rpm
    sol = solve(name)
    C = sol.point("C")
    y, y1, y2, y3 = offset_slider_crank(PHI, E_, R_ + RHO_, offset)
    np.testing.assert_allclose(C.position[:, 0], offset, atol=1e-12)
    np.testing.assert_allclose(C.position[:, 1], y, atol=1e-10 * R_)
    np.testing.assert_allclose(C.velocity[:, 1], w * y1, atol=1e-10 * R_ * w)
    np.testing.assert_allclose(C.acceleration[:, 1], w**2 * y2, atol=1e-9 * R_ * w**2)
    np.testing.assert_allclose(C.jerk[:, 1], w**3 * y3, atol=1e-8 * R_ * w**3)
    # the pressure angle: between the line of stroke and the normal E–C (the rod of the
    # equivalent slider-crank): sin α = |offset − e cos φ|/(R + ρ)
    np.testing.assert_allclose(sol.joint("K")["pressure_angle"],
                               np.arcsin(np.abs(offset - E_ * np.cos(PHI)) / (R_ + RHO_)), atol=1e-12)


def test_lift_of_the_roller_cams():
    """Stroke of the slider-crank: √((l + r)² − f²) − √((l − r)² − f²) with r = e, l = R + ρ."""
    phi = np.radians(np.arange(0.0, 360.0, 0.25))
    for name, f in [("radial-roller-cam", 0.0), ("offset-roller-cam", 15.0)]:
        y = linkwork.solve(mech(name), phi).point("C").position[:, 1]
        l, r = R_ + RHO_, E_
        assert np.ptp(y) == pytest.approx(np.sqrt((l + r) ** 2 - f * f) - np.sqrt((l - r) ** 2 - f * f),
                                          abs=1e-4)


def test_flat_face_on_an_eccentric_is_a_scotch_yoke():
    """Pöschl §49 (Abb. 57): the flat follower's motion is the projection of the disc centre's on
    the stem: y = R + e·sin φ, and so its derivatives; the pressure angle is zero."""
    w = 2 * np.pi
    sol = solve("flat-faced-cam", order=4)
    C = sol.point("C")
    np.testing.assert_allclose(C.position[:, 1], R_ + E_ * np.sin(PHI), atol=1e-10 * R_)
    np.testing.assert_allclose(C.velocity[:, 1], w * E_ * np.cos(PHI), atol=1e-10 * R_ * w)
    np.testing.assert_allclose(C.acceleration[:, 1], -w**2 * E_ * np.sin(PHI), atol=1e-9 * R_ * w**2)
    np.testing.assert_allclose(C.jerk[:, 1], -w**3 * E_ * np.cos(PHI), atol=1e-8 * R_ * w**3)
    np.testing.assert_allclose(sol.joint("K")["pressure_angle"], 0.0, atol=1e-9)
    # the contact lies straight above the disc's centre (the face's normal through it)
    np.testing.assert_allclose(sol.joint("K")["point"][:, 0], E_ * np.cos(PHI), atol=1e-10 * R_)


def four_bar_output(phi, O, a, b, c, B0, C0):
    """Rocker angle of the four-bar O–A–C–B0 (crank a at angle φ, coupler b, rocker c), on the
    assembly branch of the design point C0, by intersecting two circles."""
    A = O + a * np.stack([np.cos(phi), np.sin(phi)], axis=1)
    d = B0 - A
    D = np.hypot(*d.T)
    x = (b * b - c * c + D * D) / (2 * D)
    h = np.sqrt(b * b - x * x)
    ex = d / D[:, None]
    u, v = B0 - O - [a, 0.0], C0 - O - [a, 0.0]  # the design: crank pin at (a, 0)
    side = np.sign(u[0] * v[1] - u[1] * v[0])
    C = A + x[:, None] * ex + side * h[:, None] * np.stack([-ex[:, 1], ex[:, 0]], axis=1)
    return np.arctan2(C[:, 1] - B0[1], C[:, 0] - B0[0])


def test_oscillating_roller_lever_is_the_four_bar_through_the_disc_centre():
    """Pöschl §43 Nr. 20, §49 Abb. 59: crank O–E (e), coupler E–C (R + ρ), rocker C–B0. Angles
    from circle intersections; ω, α from central differences of that closed form."""
    m = mech("oscillating-roller-cam")
    B0, C0 = m.points["B0"], m.points["C"]
    arm = float(np.hypot(*(C0 - B0)))
    assert arm == pytest.approx(40.0, abs=1e-12)
    sol = solve("oscillating-roller-cam", order=2)

    def psi(phi):
        return four_bar_output(phi, np.zeros(2), E_, R_ + RHO_, arm, B0, C0)

    got = sol.pose_derivatives("rocker")
    ref = np.arctan2(C0[1] - B0[1], C0[0] - B0[0])
    np.testing.assert_allclose(np.angle(np.exp(1j * (got[0, :, 2] + ref - psi(PHI)))), 0.0, atol=1e-11)
    w, h = 2 * np.pi, 1e-4
    d1 = np.angle(np.exp(1j * (psi(PHI + h) - psi(PHI - h)))) / (2 * h)
    d2 = np.angle(np.exp(1j * (psi(PHI + h) - 2 * psi(PHI) + psi(PHI - h)))) / h**2
    np.testing.assert_allclose(got[1, :, 2], w * d1, atol=1e-7 * w)
    np.testing.assert_allclose(got[2, :, 2], w**2 * d2, atol=1e-4 * w**2)
