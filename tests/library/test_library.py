"""Every library mechanism: it loads, its whole motion assembles, every pair stays closed at every
sample, and the four-bars move as Grashof's inequality says they must.

Expected values come from outside the solver: pair closure is an identity the solved poses must
satisfy (for a cam or rolling pair: the reported contact point lies on both elements, tangent to
both, and the links' points there do not separate, nor slip when rolling), Grashof's class and the swing angles follow from the link lengths (cosine law), the
Jansen lengths are Jansen's holy numbers, the Römer slide velocity comes from Rosenauer's
Construction I (projection theorem), the Whitworth time ratio and the ellipsograph's ellipse are
closed forms of their drawings.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest
from scipy.optimize import brentq

import linkwork
from linkwork import Status
from library_solutions import driven_names, mech, motion
from linkwork.io.files import library_names
from linkwork.kinematics.motion import input_limits
from linkwork.model import (CamContact, CircularSlot, Gear, GenevaPair, Prismatic, Revolute,
                            RollingContact, Slot, StarWheelPair)

NAMES = driven_names()  # the chains driven by given point velocities have no whole motion
NEW = ["double-crank", "double-rocker", "parallelogram", "antiparallelogram", "slider-crank-centric",
       "slider-crank-offset", "oscillating-crank-slotted-lever", "rotating-crank-slotted-lever",
       "whitworth-quick-return", "ellipsograph", "watt-i-six-bar", "stephenson-iii-six-bar",
       "jansen-linkage", "roemer-mechanism"]


@lru_cache(maxsize=None)
def limits(name: str):
    return input_limits(mech(name))


def _speed(d) -> float:
    """A driver's constant speed, or the largest speed of its time law over its duration."""
    if hasattr(d.law, "speed"):
        return abs(d.law.speed)
    return float(np.abs(d.law.derivatives(np.linspace(0, d.law.duration, 201))[1]).max())


def _scales(m):
    """(length, velocity, acceleration) scales: L, L·|ω|, L·ω² (a slider input: its speed)."""
    L = m.length_scale
    d = max(m.drivers, key=_speed)
    w = _speed(d)
    if m.joint(d.joint).kind == "prismatic":
        return L, w, w * w / L
    return L, L * w, L * w * w


def test_all_new_mechanisms_are_in_the_library():
    assert set(NEW) <= set(NAMES)


# ---------------------------------------------------------------------------- loading
@pytest.mark.parametrize("name", NAMES)
def test_loads_with_name_description_units_and_driver(name):
    m = mech(name)
    assert m.name.strip()
    assert m.description.strip() and "\n" not in m.description
    assert m.length_unit
    assert len(m.drivers) >= 1
    assert m.frame in m.link_names


# ---------------------------------------------------------------------------- whole motion
@pytest.mark.parametrize("name", NAMES)
def test_whole_motion_has_no_unreachable_sample(name):
    sol = motion(name)
    assert len(sol) > 100
    marked = np.zeros(len(sol), dtype=bool)
    if name == "galloway-kite":  # its folds (crank on the frame, θ ≡ 0) are passed, the samples
        u = sol.inputs[:, 0]     # exactly on them marked: B is free on its circle there
        marked = np.abs((u + np.pi) % (2 * np.pi) - np.pi) < 1e-9
        assert marked.sum() == 2
    assert ((sol.status == Status.UNREACHABLE) == marked).all()
    for p in mech(name).points:
        assert np.isfinite(sol.point(p).position[~marked]).all(), p


def _angle_change(sol, link):
    return sol.pose_derivatives(link)[0, :, 2]


@pytest.mark.parametrize("name", NAMES)
def test_loop_closure_at_every_sample(name):
    """Each pair's geometric condition, evaluated from both of its links' solved poses."""
    m, sol = mech(name), motion(name)
    L, V, A = _scales(m)
    ok = sol.status == Status.OK
    for j in m.joints:
        if isinstance(j, (CamContact, RollingContact)):
            _check_contact(m, sol, j, L, V, ok)
            continue
        if isinstance(j, Gear):
            r1, r2 = j.radii
            d1 = _angle_change(sol, j.links[0]) - _angle_change(sol, j.carrier)
            if j.gear_kind == "rack":
                # the rack's slide along its guide, in the carrier, equals the rolled arc r·Δθ
                slide = sol.local(j.carrier, sol.pose_derivatives(j.links[1])[0, :, :2]) @ m.rack_guide(j).axis
                np.testing.assert_allclose(np.abs(slide), r1 * np.abs(d1), atol=1e-9 * L, err_msg=j.name)
                continue
            d2 = _angle_change(sol, j.links[1]) - _angle_change(sol, j.carrier)
            # pitch circles roll: equal arcs, opposite senses for an external pair
            rolled = r1 * d1 + (r2 if j.gear_kind == "external" else -r2) * d2
            np.testing.assert_allclose(rolled, 0.0, atol=1e-9 * L, err_msg=j.name)
            continue
        if isinstance(j, GenevaPair):
            _geneva_closure(m, sol, j)
            continue
        if isinstance(j, StarWheelPair):
            continue  # its phases are checked against the seed's facts below
        a, b = j.links
        P = m.points[j.point]
        on_b = sol.point_on(b, P)
        if isinstance(j, Revolute):
            on_a = sol.point_on(a, P)
            np.testing.assert_allclose(on_b.position, on_a.position, rtol=0, atol=1e-9 * L, err_msg=j.name)
            np.testing.assert_allclose(on_b.velocity[ok], on_a.velocity[ok], rtol=0, atol=1e-8 * V,
                                       err_msg=j.name)
            np.testing.assert_allclose(on_b.acceleration[ok], on_a.acceleration[ok], rtol=0,
                                       atol=1e-7 * A, err_msg=j.name)
            continue
        loc = sol.local(a, on_b.position) - P  # the pin in the guiding link's drawing coordinates
        if isinstance(j, (Prismatic, Slot)):
            n = np.array([-j.axis[1], j.axis[0]])
            np.testing.assert_allclose(loc @ n, 0.0, atol=1e-9 * L, err_msg=j.name)
            # the pin's velocity relative to the guide lies along the guide
            coinc = sol.point_on(a, sol.local(a, on_b.position))
            th = sol.pose_derivatives(a)[0, :, 2]
            nw = np.c_[-np.sin(th) * j.axis[0] - np.cos(th) * j.axis[1],
                       np.cos(th) * j.axis[0] - np.sin(th) * j.axis[1]]
            v_rel = on_b.velocity - coinc.velocity
            np.testing.assert_allclose((v_rel * nw).sum(1)[ok], 0.0, atol=1e-8 * V, err_msg=j.name)
            if isinstance(j, Prismatic):  # the block does not turn in its guide
                np.testing.assert_allclose(_angle_change(sol, b) - _angle_change(sol, a), 0.0,
                                           atol=1e-12, err_msg=j.name)
        elif isinstance(j, CircularSlot):
            c = m.points[j.center]
            R = np.hypot(*(P - c))
            np.testing.assert_allclose(np.hypot(*(loc + P - c).T), R, atol=1e-9 * L, err_msg=j.name)


def _check_contact(m, sol, j, L, V, ok):
    """A higher pair from the contact report `Solution.joint`: the contact point lies on the
    profile of links[0] and on the follower's element (roller circle, knife tip, flat face or
    mate profile), both tangent to the common tangent there; the two links' material points at
    the contact have no relative velocity along the common normal (and none at all when rolling)."""
    rep = sol.joint(j.name)
    a, b = j.links
    P, n = rep["point"], rep["normal"]
    prof = m.profiles[j.profile if isinstance(j, CamContact) else j.profiles[0]]
    d = prof.derivatives(rep["u"], 1)
    np.testing.assert_allclose(sol.local(a, P), d[0], atol=1e-9 * L, err_msg=j.name)
    th_a = sol.pose_derivatives(a)[0, :, 2]
    t_a = np.c_[np.cos(th_a) * d[1][:, 0] - np.sin(th_a) * d[1][:, 1],
                np.sin(th_a) * d[1][:, 0] + np.cos(th_a) * d[1][:, 1]]
    np.testing.assert_allclose((t_a * n).sum(1) / np.hypot(*t_a.T), 0.0, atol=1e-9, err_msg=j.name)
    follower = j.follower if isinstance(j, CamContact) else "profile"
    if follower in ("roller", "knife"):
        C = sol.point(j.point).position
        np.testing.assert_allclose(C - P, j.radius * n, atol=1e-9 * L, err_msg=j.name)
    elif follower == "flat":
        loc = sol.local(b, P) - m.points[j.point]
        np.testing.assert_allclose(loc @ np.array([-j.axis[1], j.axis[0]]), 0.0, atol=1e-9 * L,
                                   err_msg=j.name)
    else:
        mate = m.profiles[j.mate if isinstance(j, CamContact) else j.profiles[1]]
        e = mate.derivatives(rep["v"], 1)
        np.testing.assert_allclose(sol.local(b, P), e[0], atol=1e-9 * L, err_msg=j.name)
        t_b = e[1] / np.hypot(*e[1].T)[:, None]
        t_a_loc = d[1] / np.hypot(*d[1].T)[:, None]
        th_b = sol.pose_derivatives(b)[0, :, 2]
        # the mate's tangent, turned into the frame, is parallel to the profile's
        cross = (np.cos(th_a - th_b) * t_a_loc[:, 0] - np.sin(th_a - th_b) * t_a_loc[:, 1]) * t_b[:, 1] \
            - (np.sin(th_a - th_b) * t_a_loc[:, 0] + np.cos(th_a - th_b) * t_a_loc[:, 1]) * t_b[:, 0]
        np.testing.assert_allclose(cross, 0.0, atol=1e-9, err_msg=j.name)
    v_rel = (sol.point_on(b, sol.local(b, P)).velocity - sol.point_on(a, sol.local(a, P)).velocity)
    np.testing.assert_allclose((v_rel * n).sum(1)[ok], 0.0, atol=1e-8 * V, err_msg=j.name)
    if isinstance(j, RollingContact):
        np.testing.assert_allclose(v_rel[ok], 0.0, atol=1e-8 * V, err_msg=j.name)


def _pivot(m, link, carrier):
    return next(m.points[j.point] for j in m.joints
                if isinstance(j, Revolute) and set(j.links) == {link, carrier})


def _geneva_closure(m, sol, j):
    """Within the wheel's rim (|CB| < D·cos(π/n), the pin circle's entry radius) the pin lies on
    one of the n equally spaced radial slots of the wheel; outside it the wheel stands at one of
    its n index angles."""
    driver, wheel = j.links
    M, C = _pivot(m, driver, j.carrier), _pivot(m, wheel, j.carrier)
    D, n = np.hypot(*(C - M)), j.slots
    B = sol.point_on(driver, m.points[j.pin]).position
    inside = np.hypot(*(B - sol.point_on(j.carrier, C).position).T) < D * np.cos(np.pi / n) * (1 - 1e-9)
    local = sol.local(wheel, B) - C
    bearing = np.arctan2(local[:, 1], local[:, 0])
    index = _angle_change(sol, wheel) - _angle_change(sol, j.carrier)

    def spread(a):  # of angles modulo 2π/n, about their circular mean
        z = np.exp(1j * n * a)
        return np.abs(np.angle(z / np.mean(z))).max() / n

    assert inside.any() and (~inside).any(), j.name
    assert spread(bearing[inside]) < 1e-9, j.name
    assert spread(index[~inside]) < 1e-9, j.name


@pytest.mark.parametrize("name", NAMES)
def test_whole_motion_is_continuous(name):
    """No jump between consecutive samples (a change of assembly branch between regular samples
    would be one): every point moves at most what its velocity and acceleration allow."""
    m, sol = mech(name), motion(name)
    L = m.length_scale
    dt = (np.diff(sol.time) if sol.time is not None
          else np.abs(np.diff(sol.input)) / abs(m.drivers[0].law.speed))
    ok = (sol.status[:-1] == Status.OK) & (sol.status[1:] == Status.OK)
    for p in m.points:
        pm = sol.point(p)
        step = np.hypot(*np.diff(pm.position, axis=0).T)
        v = np.hypot(*pm.velocity.T)
        a = np.hypot(*pm.acceleration.T)
        bound = 2 * (np.maximum(v[:-1], v[1:]) * dt + np.maximum(a[:-1], a[1:]) * dt * dt) + 1e-9 * L
        assert (step[ok] <= bound[ok]).all(), p


# ---------------------------------------------------------------------------- Grashof
def _four_bar_loops(m):
    """Four-bars (pivot, input pin, output pin, output pivot) made of the driven link, a coupler
    and an output link pivoted on the frame, all joined by revolutes."""
    d = m.drivers[0]
    drv = m.joint(d.joint)
    if not isinstance(drv, Revolute) or m.frame not in drv.links:
        return []
    rev = [j for j in m.joints if isinstance(j, Revolute)]
    inp = d.driven
    loops = []
    for j1 in rev:
        if inp not in j1.links or j1 is drv:
            continue
        cpl = j1.links[1] if j1.links[0] == inp else j1.links[0]
        if cpl == m.frame:
            continue
        for j2 in rev:
            if cpl not in j2.links or j2 is j1:
                continue
            out = j2.links[1] if j2.links[0] == cpl else j2.links[0]
            if out in (m.frame, inp):
                continue
            for j3 in rev:
                if set(j3.links) == {out, m.frame}:
                    loops.append(dict(input=inp, coupler=cpl, output=out,
                                      pts=[m.points[j.point] for j in (drv, j1, j2, j3)]))
    return loops


def grashof_class(frame: float, inp: float, coupler: float, output: float) -> str:
    """Grashof's inequality s + l ≤ p + q and the position of the shortest link."""
    lengths = dict(frame=frame, input=inp, coupler=coupler, output=output)
    v = sorted(lengths.values())
    s, l, pq = v[0], v[-1], v[1] + v[2]
    if abs(s + l - pq) <= 1e-9 * l:
        return "change-point"
    if s + l > pq:
        return "triple-rocker"
    shortest = min(lengths, key=lengths.get)
    return {"frame": "double-crank", "input": "crank-rocker", "coupler": "double-rocker",
            "output": "rocker-crank"}[shortest]


def _lengths(pts):
    O2, A, B, O4 = pts
    return (np.hypot(*(O4 - O2)), np.hypot(*(A - O2)), np.hypot(*(B - A)), np.hypot(*(B - O4)))


EXPECTED_CLASS = {
    "crank-rocker": "crank-rocker",
    "pmks-teaching-four-bar": "crank-rocker",
    "double-crank": "double-crank",
    "double-rocker": "double-rocker",
    "parallelogram": "change-point",
    "antiparallelogram": "change-point",
}
# The Galloway kite (Rosenauer §100) runs through its fold, where its crank lies on the frame,
# as a kite of the other sense (tests/kinematics/test_whole_motion_folds.py): its crank turns.
# Mechanisms with several drivers follow their time laws, not the limits of one input.
LOOPED = [n for n in NAMES if _four_bar_loops(mech(n)) and len(mech(n).drivers) == 1]


def test_four_bar_files_are_recognised():
    assert set(EXPECTED_CLASS) <= set(LOOPED)
    for n in EXPECTED_CLASS:
        assert len(_four_bar_loops(mech(n))) == 1
    for n in ["watt-i-six-bar", "stephenson-iii-six-bar", "pmks-stephenson-iii"]:
        assert len(_four_bar_loops(mech(n))) == 1
    assert len(_four_bar_loops(mech("jansen-linkage"))) == 2


@pytest.mark.parametrize("name", sorted(EXPECTED_CLASS))
def test_grashof_class_of_four_bar_files(name):
    (loop,) = _four_bar_loops(mech(name))
    assert grashof_class(*_lengths(loop["pts"])) == EXPECTED_CLASS[name]


def _spans_full_turn(angle: np.ndarray) -> bool:
    a = np.unwrap(angle)
    return np.ptp(a) >= 2 * np.pi - 1e-6


@pytest.mark.parametrize("name", LOOPED)
def test_motion_agrees_with_grashof(name):
    """The input turns fully exactly when Grashof makes it a crank (for a bare four-bar; in a
    six-bar the other loops may stop it earlier), and the output turns fully only in a
    double-crank."""
    m, sol = mech(name), motion(name)
    full = limits(name) is None
    bare = len(m.links) == 4
    for loop in _four_bar_loops(m):
        cls = grashof_class(*_lengths(loop["pts"]))
        input_is_crank = cls in ("crank-rocker", "double-crank", "change-point")
        if bare:
            assert full == input_is_crank, cls
        elif not input_is_crank:
            assert not full, cls
        if full and cls != "change-point":
            assert _spans_full_turn(sol.link(loop["output"]).angle) == (cls == "double-crank"), cls
        if not full:
            assert not _spans_full_turn(sol.link(loop["input"]).angle)


@pytest.mark.parametrize("name", LOOPED)
def test_rocker_swing_equals_cosine_law(name):
    """Crank-rocker loops: the rocker's extreme positions are where crank and coupler are
    stretched (|O2B| = a + b) and folded (|O2B| = b − a)."""
    m, sol = mech(name), motion(name)
    for loop in _four_bar_loops(m):
        d, a, b, c = _lengths(loop["pts"])
        if grashof_class(d, a, b, c) != "crank-rocker" or limits(name) is not None:
            continue

        def psi(dist):  # angle O2-O4-B by the cosine law
            return np.arccos((d * d + c * c - dist * dist) / (2 * d * c))

        swing = psi(a + b) - psi(b - a)
        got = np.ptp(np.unwrap(sol.link(loop["output"]).angle))
        # 1° samples: the extremes are flat, so sampling loses O(h²) of the swing
        assert got == pytest.approx(swing, abs=2e-4), loop["output"]


# ---------------------------------------------------------------------------- change points
CHANGE_POINT = {"parallelogram": +1, "antiparallelogram": -1}


@pytest.mark.parametrize("name", sorted(CHANGE_POINT))
def test_change_points_are_flagged_singular(name):
    """All four pivots collinear (crank at 0° or 180°): the dyad's Jacobian is singular there and
    nowhere else."""
    m, sol = mech(name), motion(name)
    crank = np.degrees(sol.link("crank").angle) % 180.0
    at_change = np.minimum(crank, 180.0 - crank) < 1e-6
    assert at_change.sum() == 2
    assert (sol.status[at_change] == Status.SINGULAR).all()
    assert (sol.status[~at_change] == Status.OK).all()


@pytest.mark.parametrize("name", sorted(CHANGE_POINT))
def test_design_half_turn_keeps_its_form(name):
    """Between the change points next to the design position the parallelogram's follower stays
    parallel to its crank (ω equal), the antiparallelogram's turns the other way."""
    m, sol = mech(name), motion(name)
    crank = np.degrees(sol.link("crank").angle)
    half = (crank > 0.5) & (crank < 179.5)
    w_in, w_out = sol.link("crank").omega[half], sol.link("follower").omega[half]
    if CHANGE_POINT[name] > 0:
        np.testing.assert_allclose(w_out, w_in, rtol=1e-9)
        np.testing.assert_allclose(sol.link("coupler").omega[half], 0.0, atol=1e-9)
    else:
        assert (w_out * w_in < 0).all()


@pytest.mark.parametrize("name", sorted(CHANGE_POINT))
def test_whole_turn_keeps_its_form(name):
    """Past the change points the motion with continuous velocities goes on in the same form:
    the parallelogram's follower turns with the crank, the antiparallelogram's against it."""
    sol = motion(name)
    ok = sol.status == Status.OK
    w_in, w_out = sol.link("crank").omega[ok], sol.link("follower").omega[ok]
    if CHANGE_POINT[name] > 0:
        np.testing.assert_allclose(w_out, w_in, rtol=1e-9)
    else:
        assert (w_out * w_in < 0).all()


# ---------------------------------------------------------------------------- single mechanisms
HOLY = dict(a=38.0, b=41.5, c=39.3, d=40.1, e=55.8, f=39.4, g=36.7, h=65.7, i=49.0, j=50.0,
            k=61.9, l=7.8, m=15.0)


def test_jansen_lengths_are_the_holy_numbers():
    P = mech("jansen-linkage").points
    pairs = dict(m="OA", b="BC", j="AC", c="BD", k="AD", d="BE", e="CE", f="EF", g="DF", i="DG", h="FG")
    for key, (p, q) in pairs.items():
        assert np.hypot(*(P[p] - P[q])) == pytest.approx(HOLY[key], abs=1e-9), key
    assert P["O"] - P["B"] == pytest.approx([HOLY["a"], HOLY["l"]], abs=1e-12)


def test_jansen_crank_turns_fully():
    assert limits("jansen-linkage") is None
    assert (motion("jansen-linkage").status == Status.OK).all()


def test_ellipsograph_point_traces_its_ellipse():
    m, sol = mech("ellipsograph"), motion("ellipsograph")
    P, A, B = (m.points[k] for k in "PAB")
    ax, ay = np.hypot(*(P - B)), np.hypot(*(P - A))  # semi-axes along the A and B guides
    xy = sol.point("P").position
    np.testing.assert_allclose((xy[:, 0] / ax) ** 2 + (xy[:, 1] / ay) ** 2, 1.0, atol=1e-12)
    assert limits("ellipsograph") is None
    assert (sol.status == Status.OK).all()
    assert np.ptp(xy[:, 0]) == pytest.approx(2 * ax, rel=1e-4)
    assert np.ptp(xy[:, 1]) == pytest.approx(2 * ay, rel=1e-4)


def test_oscillating_slotted_lever_swing():
    """The lever's limits are where the slot is tangent to the crank circle: ±asin(r/d)."""
    m, sol = mech("oscillating-crank-slotted-lever"), motion("oscillating-crank-slotted-lever")
    r = np.hypot(*(m.points["A"] - m.points["C"]))
    d = np.hypot(*(m.points["B"] - m.points["C"]))
    assert np.ptp(np.unwrap(sol.link("lever").angle)) == pytest.approx(2 * np.arcsin(r / d), abs=2e-4)


def test_rotating_slotted_lever_turns_once_per_crank_turn():
    sol = motion("rotating-crank-slotted-lever")
    lever = np.unwrap(sol.link("lever").angle)
    crank = np.unwrap(sol.link("crank").angle)
    assert lever[-1] - lever[0] == pytest.approx(crank[-1] - crank[0], abs=1e-9)
    assert (sol.link("lever").omega > 0).all()


def test_whitworth_stroke_and_time_ratio():
    """Ram dead centres: the lever lies along the ram guide (through O4), i.e. the crank pin is on
    that line: sin φ = −O2O4/r. Stroke 2·O4C; cutting and return take π ± 2·asin(O2O4/r)."""
    name = "whitworth-quick-return"
    m, sol = mech(name), motion(name)
    P = m.points
    r, e = np.hypot(*(P["A"] - P["O2"])), np.hypot(*(P["O4"] - P["O2"]))
    arm = np.hypot(*(P["C"] - P["O4"]))
    x = sol.point("D").position[:, 0]
    assert np.ptp(x) == pytest.approx(2 * arm, abs=1e-3)

    def ram_velocity(phi):
        return linkwork.solve(m, [phi]).point("D").velocity[0, 0]

    phi = sol.input
    v = sol.point("D").velocity[:, 0]
    flips = np.flatnonzero(np.sign(v[:-1]) != np.sign(v[1:]))
    assert len(flips) == 2
    dead = [brentq(ram_velocity, phi[k], phi[k + 1], xtol=1e-13) for k in flips]
    expect = sorted(np.mod([-np.arcsin(e / r), np.pi + np.arcsin(e / r)], 2 * np.pi))
    assert sorted(np.mod(dead, 2 * np.pi)) == pytest.approx(expect, abs=1e-9)
    # the stroke in +x (cutting) takes the longer crank arc
    k0, k1 = flips
    forward = np.mean(v[k0 + 1:k1 + 1]) > 0
    inner = (dead[1] - dead[0]) % (2 * np.pi)
    cutting, ret = (inner, 2 * np.pi - inner) if forward else (2 * np.pi - inner, inner)
    assert cutting == pytest.approx(np.pi + 2 * np.arcsin(e / r), abs=1e-9)
    assert cutting / ret == pytest.approx(2.0, abs=1e-9)


def test_roemer_slide_velocity_by_rosenauers_construction_i():
    """Construction I (Rosenauer 1937, paper 1): Q = KA ∩ BN and R = MC ∩ BN, points of ABC on
    the normal BN to the slide, move parallel to the slide; their speeds follow from K's and M's
    by the projection theorem, and B's is interpolated linearly between them along BN."""
    name = "roemer-mechanism"
    m, sol = mech(name), motion(name)
    g = next(j for j in m.joints if isinstance(j, Gear))
    r1, r2 = g.radii
    w1 = m.drivers[0].law.speed
    w2 = -w1 * r1 / r2  # external mesh about fixed axes
    ok = sol.status == Status.OK
    pos = {p: sol.point(p).position[ok] for p in "KMABC"}
    O1, O2 = m.points["O1"], m.points["O2"]
    vK = w1 * np.c_[-(pos["K"] - O1)[:, 1], (pos["K"] - O1)[:, 0]]
    vM = w2 * np.c_[-(pos["M"] - O2)[:, 1], (pos["M"] - O2)[:, 0]]
    slide = m.joint("slide")
    s = slide.axis  # the guide is fixed in the frame
    n = np.array([-s[1], s[0]])
    B = pos["B"]

    def on_normal(P, Q):
        """Intersection of line PQ with the normal BN through B."""
        d = Q - P
        t = ((B - P) @ s) / (d @ s)
        return P + t[:, None] * d

    def speed(P, Q, vP):
        u = (Q - P) / np.hypot(*(Q - P).T)[:, None]
        return (vP * u).sum(1) / (u @ s)  # projection theorem along the link

    Qp, Rp = on_normal(pos["K"], pos["A"]), on_normal(pos["M"], pos["C"])
    lq, lr = speed(pos["K"], pos["A"], vK), speed(pos["M"], pos["C"], vM)
    hq, hr, hb = Qp @ n, Rp @ n, B @ n
    vB = lq + (lr - lq) * (hb - hq) / (hr - hq)
    got = sol.point("B").velocity[ok] @ s
    L, V, _ = _scales(m)
    np.testing.assert_allclose(got, vB, rtol=0, atol=1e-8 * V)
    assert np.ptp(vB) > 0.1 * V  # the check is not vacuous


def test_crank_driven_wedge_lifts_by_the_tangent_of_its_face():
    """The face, at 25° to the slide, lifts the vertically guided follower by tan 25° times the
    wedge's travel against the slide (and so its speed and acceleration)."""
    m, sol = mech("crank-driven-wedge"), motion("crank-driven-wedge")
    B, C = sol.point("B"), sol.point("C")
    k = np.tan(np.radians(25.0))
    np.testing.assert_allclose(C.position[:, 1] - m.points["C"][1],
                               -k * (B.position[:, 0] - m.points["B"][0]), atol=1e-9)
    np.testing.assert_allclose(C.velocity[:, 1], -k * B.velocity[:, 0], atol=1e-9)
    np.testing.assert_allclose(C.acceleration[:, 1], -k * B.acceleration[:, 0], atol=1e-7)
    np.testing.assert_allclose(C.position[:, 0], m.points["C"][0], atol=1e-9)
