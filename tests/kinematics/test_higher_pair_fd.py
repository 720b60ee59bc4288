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
- and, for any smooth cam Hypothesis draws, the same for the velocity, the acceleration and
  the contact's run.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import linkwork
from linkwork.geometry.profiles import SplineProfile, curvature
from spline_cams import R0, RHO, cam_mechanism, spline_cam

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
    assert (sol.status != linkwork.Status.UNREACHABLE).all()  # assembled
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


def test_a_design_the_contact_leaves_undetermined_is_marked_not_a_crash():
    """Elliptical gears drawn with the common normal through both pivots (the ellipses touching
    at their vertices): the contact alone does not fix the speed ratio there, Newton's method
    cannot start from the design, and every sample is marked unreachable (it used to raise a
    shape error inside the continuation)."""
    from spline_cams import elliptical_gears
    sol = linkwork.solve(elliptical_gears(0.0), np.radians([0.0, 10.0, 20.0]))
    assert (sol.status == linkwork.Status.UNREACHABLE).all()


# ---------------------------------------------------------------------------- Hypothesis

@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(radii=st.lists(st.floats(R0 - 3.0, R0 + 3.0), min_size=6, max_size=10),
       jitter=st.floats(-0.3, 0.3), at=st.floats(0.0, 2 * np.pi), oscillating=st.booleans())
def test_random_cam_velocity_and_run_are_differences(radii, jitter, at, oscillating):
    """Any smooth cam Hypothesis draws (a closed quintic spline through points around a circle,
    no hollow sharper than the roller): the follower's velocity and acceleration and the
    contact's run along the cam are the differences of the position, velocity and arc length."""
    k = len(radii)
    phi = (np.arange(k) + jitter * np.sin(np.arange(k))) * 2 * np.pi / k
    prof = SplineProfile(np.column_stack([np.multiply(radii, np.cos(phi)), np.multiply(radii, np.sin(phi))]),
                         closed=True)
    u = np.linspace(*prof.domain, 2000, endpoint=False)
    assume((curvature(prof, u) > -0.5 / RHO).all())
    mech = cam_mechanism(prof, "rocker" if oscillating else "roller")
    x = mech.driver_input_at_design(mech.drivers[0]) + at + OFFSETS
    sol = linkwork.solve(mech, x, order=2)
    assume((sol.status != linkwork.Status.UNREACHABLE).all())  # a rocker may reach a limit position
    L = mech.length_scale
    C = sol.point("C")
    np.testing.assert_allclose(difference(C.position), C.velocity[2], rtol=0, atol=1e-7 * L)
    np.testing.assert_allclose(difference(C.velocity), C.acceleration[2], rtol=0, atol=1e-7 * L)
    rep = sol.joint("K")
    np.testing.assert_allclose(difference(prof.arc_length(rep["u"])), rep["profile_speed"][2],
                               rtol=0, atol=1e-7 * L)
