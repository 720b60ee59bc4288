"""Curvature theory across higher pairs (Pöschl §38, §39; Rosenauer §15, §121 Task 3).

The two profiles' curvature centres at the contact come from the profiles' own derivatives
(geometry); the pole and the inflection circle of the relative motion come from the engine's
velocities and accelerations. They must satisfy:
- Euler–Savary: C₁ is the conjugate of C₂ in the motion of the follower relative to the cam,
  and C₂ that of C₁ in the inverse motion (each profile is the envelope of the other);
- Rosenauer's construction of §121 Task 3: the inflection circle of the relative motion cuts
  the common normal at W with 1/PW = 1/PC₂ − 1/PC₁ (signed along the normal);
- rolling (pure rolling of centrodes, Pöschl eq. 94): 1/R − 1/R′ = 1/D with R, R′ the
  radii of the rolling profiles and D the diameter of the relative inflection circle;
- the relative pole lies on the common normal (Reuleaux; Aronhold–Kennedy with higher pairs),
  and the velocity poles agree with the three-pole theorem's.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from higher_pair_mechanisms import eccentric, rolling_disc
from linkwork.errors import ModelError
from linkwork.instant import agreement, kennedy_poles, pole_schedule, poles
from linkwork.instant.curvature import contact_curvature, element_centres
from linkwork.instant.poles import pole_discrepancy
from spline_cams import cam_mechanism, elliptical_gears, rolling_ellipses, spline_cam

FOLLOWERS = ["roller", "knife", "flat", "rocker"]


def spline_solution(seed: int, follower: str, samples: int = 7):
    mech = cam_mechanism(spline_cam(seed, convex=follower in ("flat", "knife")), follower)
    x0 = mech.driver_input_at_design(mech.drivers[0])
    phi = x0 + np.sort(np.random.default_rng(seed).uniform(0.0, 2 * np.pi, samples))
    sol = linkwork.solve(mech, phi, order=2, velocities=np.full(samples, 1.3),
                         accelerations=np.full(samples, 0.4))
    assert (sol.status != linkwork.Status.UNREACHABLE).all()  # assembled
    return mech, sol


def cases():
    for seed in (0, 1, 2):
        for f in FOLLOWERS:
            yield pytest.param(seed, f, id=f"{f}-{seed}")


@pytest.mark.parametrize("seed,follower", list(cases()))
def test_profile_centres_are_conjugate_points(seed, follower):
    mech, sol = spline_solution(seed, follower)
    cc = contact_curvature(sol, "K")
    L = mech.length_scale
    C1, C2 = cc.centres
    P = cc.pole
    for conj, centre, given in ((cc.conjugates[0], C1, C2), (cc.conjugates[1], C2, C1)):
        gap = pole_discrepancy(conj, centre, L)
        assert np.isfinite(gap).all()
        # Euler–Savary maps a point near the pole to one far from it with the gain
        # (PC_out/PC_in)²: the tolerance follows the conditioning of each sample
        with np.errstate(invalid="ignore", divide="ignore"):
            gain = np.nan_to_num((_reach(centre, P, L) / _reach(given, P, L)) ** 2, nan=1.0, posinf=1.0)
        assert (gap <= 1e-9 * np.maximum(1.0, gain)).all(), (gap, gain)


def _reach(C, P, L):
    """|PC| in units of L (inf for a point at infinity)."""
    return np.where(C.is_infinite, np.inf, np.hypot(*(C.xy - P.xy).T) / L)


@pytest.mark.parametrize("seed,follower", list(cases()))
def test_rosenauer_inflection_point_on_the_common_normal(seed, follower):
    """§121 Task 3 step 4: W on the normal from the two centres, on the relative inflection
    circle (which the engine finds from accelerations)."""
    mech, sol = spline_solution(seed, follower)
    cc = contact_curvature(sol, "K")
    n, P = cc.normal, cc.pole.xy
    circle = cc.inflection_circle
    inv = []
    for C in cc.centres:  # 1/PC along the normal: 0 for a centre at infinity
        with np.errstate(divide="ignore"):
            inv.append(np.where(C.is_infinite, 0.0, 1.0 / np.einsum("ij,ij->i", C.xy - P, n)))
    W = P + (1.0 / (inv[1] - inv[0]))[:, None] * n
    gap = np.hypot(*(W - circle.centre.xy).T) - circle.radius
    np.testing.assert_allclose(gap, 0.0, atol=1e-9 * mech.length_scale)


@pytest.mark.parametrize("seed,follower", [(0, "roller"), (1, "flat"), (2, "rocker"), (0, "knife")])
def test_relative_pole_on_the_common_normal_of_a_spline_cam(seed, follower):
    mech, sol = spline_solution(seed, follower)
    rep = sol.joint("K")
    L = mech.length_scale
    P = poles(sol)["cam", "follower"]
    assert P.is_finite.all()
    d = P.xy - rep["point"]
    np.testing.assert_allclose(d[:, 0] * rep["normal"][:, 1] - d[:, 1] * rep["normal"][:, 0], 0.0,
                               atol=1e-9 * L)
    # and both curvature centres lie on that normal too
    for C in element_centres(sol, "K"):
        fin = C.is_finite
        e = C.xy[fin] - rep["point"][fin]
        np.testing.assert_allclose(e[:, 0] * rep["normal"][fin, 1] - e[:, 1] * rep["normal"][fin, 0],
                                   0.0, atol=1e-9 * L)
    gaps = agreement(poles(sol), kennedy_poles(sol, pole_schedule(mech)), L)
    assert max(np.nanmax(g) for g in gaps.values()) < 1e-9


def test_element_centres_of_an_eccentric_in_closed_form():
    """Disc centre E(cos φ, sin φ); roller: its centre; knife: its tip; flat face: at infinity
    along the vertical."""
    phi = np.radians([10.0, 100.0, 250.0])
    Ew = 10.0 * np.stack([np.cos(phi), np.sin(phi)], axis=1)
    for follower in ("roller", "knife", "flat"):
        sol = linkwork.solve(eccentric(follower), phi)
        C1, C2 = element_centres(sol, "K")
        np.testing.assert_allclose(C1.xy, Ew, atol=1e-12)
        if follower == "flat":
            assert C2.is_infinite.all() and np.allclose(C2.direction.unit().xy[:, 0], 0.0)
        else:
            np.testing.assert_allclose(C2.xy, sol.point("C").position, atol=1e-9)


@pytest.mark.parametrize("build,pair", [(rolling_disc, "T"), (rolling_ellipses, "T"),
                                        (elliptical_gears, "T")])
def test_rolling_profiles_satisfy_the_centrode_equation(build, pair):
    """Pure rolling: the profiles are the centrodes, the pole is the contact, and
    1/R − 1/R′ = 1/D (Pöschl eq. 94) with the signed radii along the pole normal."""
    mech = build()
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = linkwork.solve(mech, x0 + np.radians(np.arange(-30.0, 35.0, 10.0)))
    assert (sol.status != linkwork.Status.UNREACHABLE).all()  # assembled
    cc = contact_curvature(sol, pair)
    L = mech.length_scale
    np.testing.assert_allclose(cc.pole.xy, cc.contact, atol=1e-9 * L)
    ins = cc.relative
    nrm = ins.pole_normal.xy  # from P towards W
    r1, r2 = (np.einsum("ij,ij->i", C.xy - cc.contact, nrm) for C in cc.centres)
    # the moving centrode (the follower's profile) R, the fixed one (the profile of links[0]) R′
    np.testing.assert_allclose(1.0 / r2 - 1.0 / r1, 1.0 / ins.diameter, rtol=1e-8)
    for conj, centre in zip(cc.conjugates, cc.centres):
        assert np.nanmax(pole_discrepancy(conj, centre, L)) < 1e-9


def test_a_lower_pair_is_refused():
    sol = linkwork.solve(eccentric("roller"), [0.3])
    with pytest.raises(ModelError, match="'F' is a prismatic pair, not a higher pair"):
        contact_curvature(sol, "F")
