"""The equivalent linkage of a higher pair (Ersatzgetriebe, Rosenauer §121 Method II, Pöschl §43,
§49): the coupler through the two curvature centres has the cam's velocities and accelerations.

Independent expectations:
- an eccentric disc: its centre and the roller's are the centres, the coupler is R + ρ (a knife:
  R) in closed form, and the substitute is the slider-crank for every position, so the
  mechanism built at one sample and solved over the whole turn reproduces the cam's positions,
  velocities, accelerations and jerks at every sample; a flat face gives the Scotch yoke;
- a disc rolling on a circle: the substitute's gears are the disc and the track themselves;
- random spline cams, elliptical gears, rolling ellipses, a knife on a straight flank, a wheel
  on a straight track: the substitute built and solved by the engine at a sample (a different
  mechanism, of lower pairs only) gives every link's ω and α and every point's velocity and
  acceleration of the higher-pair solution there, to 1e-9; its jerks differ (the substitute
  is equivalent to second order only, which shows the comparison is not empty).
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from higher_pair_mechanisms import E, R, RHO, eccentric, rolling_disc
from linkwork.errors import InputError, ModelError
from linkwork.geometry.profiles import CircleProfile, LineProfile
from linkwork.instant.equivalent import (KINDS, driver_rates, equivalent_linkage,
                                         equivalent_mechanism, solve_equivalent)
from linkwork.model import CamContact, Mechanism, Prismatic, Revolute, RollingContact
from spline_cams import cam_mechanism, elliptical_gears, rolling_ellipses, spline_cam

PHI = np.radians(np.arange(0.0, 360.0, 15.0) + 0.7)


def assert_same_rates(sol, n, eq, scale, *, jerk=False):
    """ω, α of every link and velocity, acceleration of every point of `sol` at sample n equal
    those of the equivalent solution `eq` (one sample), to 1e-9 (lengths relative to `scale`)."""
    mech = sol.mechanism
    for ln in mech.link_names:
        np.testing.assert_allclose(eq.pose_derivatives(ln)[1:3, 0, 2], sol.pose_derivatives(ln)[1:3, n, 2],
                                   rtol=0, atol=1e-9, err_msg=ln)
    for p in mech.points:
        a, b = sol.point(p), eq.point(p)
        np.testing.assert_allclose(b.position[0], a.position[n], rtol=0, atol=1e-9 * scale, err_msg=p)
        np.testing.assert_allclose(b.velocity[0], a.velocity[n], rtol=0, atol=1e-9 * scale, err_msg=p)
        np.testing.assert_allclose(b.acceleration[0], a.acceleration[n], rtol=0, atol=1e-9 * scale, err_msg=p)


# ---------------------------------------------------------------------------- the eccentric
@pytest.mark.parametrize("follower,coupler", [("roller", R + RHO), ("knife", R)])
@pytest.mark.parametrize("offset", [0.0, 7.0])
def test_eccentric_centres_and_coupler_in_closed_form(follower, coupler, offset):
    mech = eccentric(follower, offset=offset)
    sol = linkwork.solve(mech, PHI)
    eq = equivalent_linkage(sol, "K")
    assert (eq.kind == "RR").all() and not eq.rolling
    assert eq.name(mech) == "slider-crank (Schubkurbel)"
    np.testing.assert_allclose(eq.coupler, coupler, rtol=0, atol=1e-10 * R)
    Ew = E * np.stack([np.cos(PHI), np.sin(PHI)], axis=1)
    np.testing.assert_allclose(eq.centres[0].xy, Ew, atol=1e-10 * R)
    C2 = sol.point("C").position if follower == "roller" else sol.joint("K")["point"]
    np.testing.assert_allclose(eq.centres[1].xy, C2, atol=1e-10 * R)
    # both centres on the common normal through the contact: C₁ at −R, C₂ at +ρ (or 0)
    np.testing.assert_allclose(eq.radii, np.tile([-R, coupler - R], (PHI.size, 1)), atol=1e-10 * R)


@pytest.mark.parametrize("follower", ["roller", "knife", "flat"])
def test_eccentric_substitute_is_exact_over_the_whole_turn(follower):
    """Circles have constant curvature: the substitute built at one sample is the same
    mechanism at every sample (slider-crank; Scotch yoke for the flat face) and reproduces the
    cam exactly, jerks included."""
    mech = eccentric(follower, offset=0.0 if follower == "flat" else 7.0)
    cam = linkwork.solve(mech, PHI, order=3)
    sub = equivalent_mechanism(cam, 5)
    assert not any(j.kind in ("cam", "rolling") for j in sub.joints)
    ref = linkwork.solve(sub, PHI, order=3)
    for k in ("position", "velocity", "acceleration", "jerk"):
        np.testing.assert_allclose(getattr(ref.point("C"), k), getattr(cam.point("C"), k),
                                   rtol=0, atol=1e-9 * R, err_msg=k)


def test_flat_face_is_a_scotch_yoke():
    sol = linkwork.solve(eccentric("flat"), PHI)
    eq = equivalent_linkage(sol, "K")
    assert (eq.kind == "RP").all() and np.isinf(eq.coupler).all()
    assert eq.name(sol.mechanism) == "Scotch yoke (Kreuzschleife)"
    assert eq.centres[1].is_infinite.all()
    # the face's centre at infinity along its normal (vertical)
    np.testing.assert_allclose(np.abs(eq.centres[1].direction.unit().xy[:, 1]), 1.0, atol=1e-12)
    sub = equivalent_mechanism(sol, 3)
    kinds = {j.name: j.kind for j in sub.joints}
    assert kinds["K.R1"] == "revolute" and kinds["K.P"] == "prismatic"


def test_rolling_disc_substitute_carries_the_disc_and_track_as_gears():
    mech = rolling_disc()
    phi = np.radians(np.linspace(65.0, 115.0, 6))
    sol = linkwork.solve(mech, phi)
    eq = equivalent_linkage(sol, "T")
    assert eq.rolling and (eq.kind == "RR").all()
    np.testing.assert_allclose(eq.radii, np.tile([-40.0, 10.0], (phi.size, 1)), atol=1e-10 * 40)
    np.testing.assert_allclose(eq.centres[0].xy, 0.0, atol=1e-10 * 40)
    np.testing.assert_allclose(eq.centres[1].xy, sol.point("W").position, atol=1e-10 * 40)
    sub = equivalent_mechanism(sol, 2)
    gear = sub.joint("T.G")
    assert gear.gear_kind == "external" and np.allclose(gear.radii, (40.0, 10.0))
    for n in range(phi.size):
        assert_same_rates(sol, n, solve_equivalent(sol, n), 40.0)


# ---------------------------------------------------------------------------- general profiles
@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("follower,name", [("roller", "slider-crank (Schubkurbel)"),
                                           ("knife", "slider-crank (Schubkurbel)"),
                                           ("flat", "Scotch yoke (Kreuzschleife)"),
                                           ("rocker", "four-bar (Gelenkviereck)")])
def test_spline_cam_substitute_has_the_cams_velocities_and_accelerations(seed, follower, name):
    mech = cam_mechanism(spline_cam(seed, convex=follower in ("flat", "knife")), follower)
    x0 = mech.driver_input_at_design(mech.drivers[0])
    rng = np.random.default_rng(100 + seed)
    phi = x0 + np.sort(rng.uniform(0.0, 2 * np.pi, 5))
    sol = linkwork.solve(mech, phi, order=3, velocities=np.full(5, 2.5), accelerations=np.full(5, -0.7))
    assert (sol.status == linkwork.Status.OK).all()
    eq = equivalent_linkage(sol, "K")
    assert eq.name(mech) == name
    jerk_gap = 0.0
    for n in range(phi.size):
        sub = solve_equivalent(sol, n)
        assert_same_rates(sol, n, sub, mech.length_scale)
        # the substitute's jerk: a different mechanism's (recomputed at order 3 to compare)
        sub3 = linkwork.solve(sub.mechanism, sub.inputs, velocities=[[2.5]], accelerations=[[-0.7]], order=3)
        jerk_gap = max(jerk_gap, float(np.abs(sub3.point("C").jerk[0] - sol.point("C").jerk[n]).max()))
    assert jerk_gap > 1e-3 * mech.length_scale


def test_elliptical_gears_substitute_is_a_four_bar():
    """Two-curve drive (Pöschl §46): the elliptical gears' substitute is the four-bar through
    the two curvature centres; their contact rolls (the relative pole is the contact point)."""
    mech = elliptical_gears()
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = linkwork.solve(mech, x0 + np.radians(np.arange(-45.0, 50.0, 15.0)))
    assert (sol.status == linkwork.Status.OK).all()
    np.testing.assert_allclose(sol.joint("T")["sliding_velocity"], 0.0, atol=1e-9 * 60)
    eq = equivalent_linkage(sol, "T")
    assert (eq.kind == "RR").all() and eq.name(mech) == "four-bar (Gelenkviereck)"
    for n in range(len(sol)):
        assert_same_rates(sol, n, solve_equivalent(sol, n), 60.0)


def test_rolling_ellipses_substitute():
    mech = rolling_ellipses()
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = linkwork.solve(mech, x0 + np.radians(np.arange(-40.0, 45.0, 10.0)))
    assert (sol.status == linkwork.Status.OK).all()
    eq = equivalent_linkage(sol, "T")
    assert eq.rolling and (eq.kind == "RR").all()
    # a convex wheel outside a convex track: the centres on either side of the contact
    assert ((eq.radii[:, 0] < 0) & (eq.radii[:, 1] > 0)).all()
    for n in range(len(sol)):
        assert_same_rates(sol, n, solve_equivalent(sol, n), 60.0)


def test_knife_on_a_straight_flank_is_a_pin_in_a_slot():
    """A straight profile has its centre at infinity: the substitute is a block hinged at the
    knife's tip sliding along the flank ('PR')."""
    C = np.array([0.0, 25.0])
    mech = Mechanism.build(
        name="knife on a flank", points={"O": [0, 0], "A": [10, 0], "C": C, "F": [0, 45]},
        links={"frame": ["O"], "cam": ["O", "A"], "follower": ["C", "F"]},
        joints=[Revolute("O", "O", ("frame", "cam")),
                Prismatic("F", "F", ("frame", "follower"), np.array([0.0, 1.0])),
                CamContact("K", ("cam", "follower"), "flank", "knife", point="C")],
        drivers=[{"joint": "O", "reference": "A"}],
        profiles={"flank": LineProfile((-10.0, 15.0), (1.0, 1.0))})
    sol = linkwork.solve(mech, np.radians([-20.0, -5.0, 10.0]))
    eq = equivalent_linkage(sol, "K")
    assert (eq.kind == "PR").all() and eq.centres[0].is_infinite.all()
    np.testing.assert_allclose(eq.centres[1].xy, sol.point("C").position, atol=1e-12)
    for n in range(3):
        assert_same_rates(sol, n, solve_equivalent(sol, n), 45.0)


def test_wheel_on_a_straight_track_is_a_rack_on_the_carrier():
    r, W = 8.0, np.array([0.0, 8.0])
    A = np.array([30.0, 20.0])
    mech = Mechanism.build(
        name="wheel on a track", points={"O2": [40, 0], "A": A, "W": W, "M": W + [r, 0]},
        links={"frame": ["O2"], "crank": ["O2", "A"], "rod": ["A", "W"], "wheel": ["W", "M"]},
        joints=[Revolute("O2", "O2", ("frame", "crank")), Revolute("A", "A", ("crank", "rod")),
                Revolute("W", "W", ("rod", "wheel")),
                RollingContact("T", ("frame", "wheel"), ("track", "rim"))],
        drivers=[{"joint": "O2", "reference": "A"}],
        profiles={"track": LineProfile((0.0, 0.0), (1.0, 0.0)), "rim": CircleProfile(tuple(W), r)})
    x0 = mech.driver_input_at_design(mech.drivers[0])
    sol = linkwork.solve(mech, x0 + np.radians([-10.0, 0.0, 15.0]))
    eq = equivalent_linkage(sol, "T")
    assert (eq.kind == "PR").all()
    sub = equivalent_mechanism(sol, 0)
    assert sub.joint("T.G").gear_kind == "rack"
    for n in range(3):
        assert_same_rates(sol, n, solve_equivalent(sol, n), 45.0)


# ---------------------------------------------------------------------------- the API
def test_driver_rates_are_the_inputs_speeds():
    sol = linkwork.solve(eccentric("roller"), PHI[:3], velocities=[1.5, 2.0, 2.5],
                         accelerations=[0.1, 0.2, 0.3])
    np.testing.assert_allclose(driver_rates(sol, 1)[:, 0], [0.0, 2.0, 0.2], atol=1e-15)


def test_errors_name_the_problem():
    sol = linkwork.solve(eccentric("roller"), PHI[:3])
    with pytest.raises(ModelError, match="pair 'O' is a revolute pair, not a higher pair"):
        equivalent_linkage(sol, "O")
    with pytest.raises(InputError, match="sample 7 is out of range"):
        equivalent_mechanism(sol, 7)
    assert set(KINDS) == {"RR", "RP", "PR", "PP"}


# ---------------------------------------------------------------------------- the library
def _library_with_higher_pairs() -> list[str]:
    from linkwork.io.files import library_names
    out = []
    for name in library_names():
        mech = linkwork.load(f"library:{name}")
        if any(j.kind in ("cam", "rolling") for j in mech.joints):
            out.append(name)
    return out


@pytest.mark.parametrize("name", _library_with_higher_pairs())
def test_library_higher_pairs_have_their_equivalent_linkages(name):
    """Every shipped mechanism with a cam or rolling pair: at six positions over its whole
    motion the substitute gives the same ω, α, velocities and accelerations, and the
    profiles' curvature centres are conjugate points of the relative motion."""
    from linkwork.instant import contact_curvature
    from linkwork.instant.poles import pole_discrepancy
    mech = linkwork.load(f"library:{name}")
    sol = linkwork.whole_motion(mech, order=2)
    ok = np.flatnonzero(sol.status == linkwork.Status.OK)
    assert ok.size > 10
    picks = ok[np.linspace(0, ok.size - 1, 6).astype(int)]
    for pair in (j.name for j in mech.joints if j.kind in ("cam", "rolling")):
        cc = contact_curvature(sol, pair)
        gap = pole_discrepancy(cc.conjugates[0], cc.centres[0], mech.length_scale)[picks]
        assert (gap < 1e-9).all(), (pair, gap)
    for n in picks:
        assert_same_rates(sol, int(n), solve_equivalent(sol, int(n)), mech.length_scale)


def test_unreachable_samples_are_marked_not_invented():
    """A follower line 38 from the pivot is reached by the roller (R + ρ = 35 about a centre
    e = 10 from it) only where e cos φ ≥ 3: elsewhere the substitute is undefined."""
    mech = eccentric("roller", offset=38.0)
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    sol = linkwork.solve(mech, phi)
    far = sol.status == linkwork.Status.UNREACHABLE
    assert far.any() and (E * np.cos(phi[~far]) >= 38.0 - (R + RHO) - 1e-12).all()
    eq = equivalent_linkage(sol, "K")
    assert (eq.kind[far] == "").all() and np.isnan(eq.coupler[far]).all()
    assert (eq.kind[~far] == "RR").all() and np.allclose(eq.coupler[~far], R + RHO)
    with pytest.raises(InputError, match="not assembled at sample"):
        equivalent_mechanism(sol, int(np.flatnonzero(far)[0]))


def test_one_of_two_higher_pairs_replaced():
    """A disc driving a roller follower above it and a flat-faced follower beside it: either
    pair alone, or both, replaced; a pair kept is carried into the new drawing (its profile
    turned with the disc) and still solved as a cam."""
    y0 = np.sqrt((R + RHO) ** 2 - E**2)
    mech = Mechanism.build(
        name="two followers",
        points={"O": [0, 0], "E": [E, 0], "C": [0, y0], "F": [0, -20], "Q": [E + R, 0], "G": [E + R + 15, 0]},
        links={"frame": ["O"], "cam": ["O", "E"], "lifter": ["C", "F"], "pusher": ["Q", "G"]},
        joints=[Revolute("O", "O", ("frame", "cam")),
                Prismatic("F", "F", ("frame", "lifter"), np.array([0.0, 1.0])),
                Prismatic("G", "G", ("frame", "pusher"), np.array([1.0, 0.0])),
                CamContact("K1", ("cam", "lifter"), "disc", "roller", point="C", radius=RHO),
                CamContact("K2", ("cam", "pusher"), "disc", "flat", point="Q", axis=np.array([0.0, 1.0]))],
        drivers=[{"joint": "O", "reference": "E"}], profiles={"disc": CircleProfile((E, 0.0), R)})
    sol = linkwork.solve(mech, np.radians([20.0, 75.0, 130.0]), velocities=[1.5] * 3)
    for pairs, kept in ((["K1"], {"K2"}), (["K2"], {"K1"}), (None, set())):
        for n in range(3):
            sub = solve_equivalent(sol, n, pairs)
            assert {j.name for j in sub.mechanism.joints if j.kind == "cam"} == kept
            assert_same_rates(sol, n, sub, 60.0)
