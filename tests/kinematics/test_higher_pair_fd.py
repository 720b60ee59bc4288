"""Finite differences through higher pairs on random profiles: the engine's exact derivatives
(the profile's derivatives composed into the contact's jets) against differences of the
engine's own lower-order results at nearby inputs.

Random smooth periodic cams (closed quintic splines through seeded random points around a
circle, `spline_cams`) drive a translating or an oscillating roller follower, a knife edge or a
flat face. At random cam angles (uniform input speed ω = 1, so time derivatives are input
derivatives):
- velocities are the central differences of positions, accelerations those of velocities,
  jerks those of accelerations (fourth-order stencil, step 1e-4 rad);
- the contact report: the contact point's speed along the cam (`profile_speed`) is the
  difference quotient of its arc length on the cam, and its motion relative to each link — the
  differences of the contact point's coordinates in the cam's and in the follower's plane — is
  `profile_speed` along the cam and `follower_speed` along the follower's element; the
  difference of the two runs along the common tangent is the sliding velocity.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from spline_cams import cam_mechanism, spline_cam

# the cams are quintic splines: the contact's position is C⁴ in the input but its seventh
# derivative jumps at a knot, so a stencil straddling one misses the jerk by ~h²·(jump of the
# third derivative of the acceleration); h = 1e-4 keeps that below 1e-7·L, and the rounding
# error of the engine's values (~1e-13·L) over h well below it too
H = 1e-4
STENCIL = np.array([1.0, -8.0, 0.0, 8.0, -1.0]) / (12.0 * H)  # f′ from f(x − 2h) … f(x + 2h)
OFFSETS = np.array([-2.0, -1.0, 0.0, 1.0, 2.0]) * H


def stencil(seed: int, follower: str, order: int, n: int = 6):
    """The cam of `seed` with `follower`, solved in one call at the five stencil points of n
    random cam angles: (mechanism, solution, a reshaper of arrays to (5, n, ...), the slice of
    the middle points)."""
    mech = cam_mechanism(spline_cam(seed, convex=follower in ("flat", "knife")), follower)
    x0 = mech.driver_input_at_design(mech.drivers[0])
    phi = x0 + np.random.default_rng(1000 + seed).uniform(0.0, 2 * np.pi, n)
    sol = linkwork.solve(mech, (phi[None, :] + OFFSETS[:, None]).ravel(), order=order)
    assert (sol.status == linkwork.Status.OK).all()
    return mech, sol, lambda a: np.asarray(a).reshape((5, n) + np.shape(a)[1:]), slice(2 * n, 3 * n)


def difference(f5: np.ndarray) -> np.ndarray:
    return np.tensordot(STENCIL, f5, axes=(0, 0))


CASES = [pytest.param(seed, f, id=f"{f}-{seed}") for seed in (0, 1, 2, 3) for f in
         ("roller", "rocker", "knife", "flat")]


@pytest.mark.parametrize("seed,follower", CASES)
def test_rates_are_differences_of_lower_orders(seed, follower):
    mech, sol, r, mid = stencil(seed, follower, 3)
    L = mech.length_scale
    for p in ("C",) + (("F",) if "F" in mech.points else ("B0",)):
        m = sol.point(p)
        for lo, hi in (("position", "velocity"), ("velocity", "acceleration"), ("acceleration", "jerk")):
            fd = difference(r(getattr(m, lo)))
            exact = getattr(m, hi)[mid]
            np.testing.assert_allclose(fd, exact, rtol=0, atol=1e-7 * L, err_msg=f"{p} {hi}")
    D = sol.pose_derivatives("follower")
    for k in (1, 2, 3):
        np.testing.assert_allclose(difference(r(D[k - 1, :, 2])), D[k, mid, 2], rtol=0, atol=1e-7)


def _turn(theta, v):
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]], axis=1)


@pytest.mark.parametrize("seed,follower", CASES)
def test_contact_report_from_differences_of_the_contact_point(seed, follower):
    mech, sol, r, mid = stencil(seed, follower, 1)
    L = mech.length_scale
    rep = sol.joint("K")
    prof = mech.profiles["cam"]
    # the run along the cam: the difference quotient of the arc length at the contact
    s = prof.arc_length(rep["u"])
    np.testing.assert_allclose(difference(r(s)), rep["profile_speed"][mid], rtol=0, atol=1e-7 * L)
    # the contact point seen from each link, its rate turned back into the frame
    X = rep["point"]
    t = prof.derivatives(rep["u"][mid], 1)[1]
    th_cam = sol.pose_derivatives("cam")[0, mid, 2]
    th_fol = sol.pose_derivatives("follower")[0, mid, 2]
    tangent = _turn(th_cam, t / np.hypot(*t.T)[:, None])
    on_cam = _turn(th_cam, difference(r(sol.local("cam", X))))
    on_follower = _turn(th_fol, difference(r(sol.local("follower", X))))
    np.testing.assert_allclose(on_cam, rep["profile_speed"][mid, None] * tangent, rtol=0, atol=1e-7 * L)
    # along the follower's element: a roller's or a knife's run is counted along the common
    # tangent, a flat face's along its own axis
    along = _turn(th_fol, np.tile(mech.joint("K").axis, (len(th_fol), 1))) if follower == "flat" else tangent
    np.testing.assert_allclose(on_follower, rep["follower_speed"][mid, None] * along, rtol=0,
                               atol=1e-7 * L)
    sliding = np.einsum("ij,ij->i", on_cam - on_follower, tangent)
    np.testing.assert_allclose(rep["sliding_velocity"][mid], sliding, rtol=0, atol=1e-7 * L)
    if follower in ("roller", "rocker"):
        # a roller turning freely rolls off the follower's run: spin = −sliding/ρ
        rho = mech.joint("K").radius
        np.testing.assert_allclose(rep["roller_spin"][mid], -sliding / rho, rtol=0, atol=1e-7 * L / rho)
