"""Honest statuses near singular positions (`linkwork.kinematics.precision`).

A sample is `ok` only when its forward error bound (`Solution.errors`) is within 1e-9 of the
natural scale (or of the answer, where that is larger), and the bound holds: four-bars next to
their dead centres are compared with a 50-digit reference computed by hand in mpmath
(`mp_reference`), the parallelogram near its change point with its closed form (the coupler
translates, the follower turns with the crank).
"""

from __future__ import annotations

import json

import mpmath as mp
import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import linkwork
from linkwork import Status
from linkwork.kinematics.precision import TOLERANCE
from mechanism_texts import four_bar_text

import mp_reference as R

pytestmark = pytest.mark.filterwarnings("ignore::linkwork.errors.LinkworkWarning")


# ---------------------------------------------------------------------------- the parallelogram
def test_parallelogram_next_to_its_change_point_is_right_or_not_ok():
    """The issue's sample, --at 179.9999942704220 (degrees), reported ok with ω = 1.049·ω_true.
    Parallelogram (library, integer coordinates): the follower turns exactly with the crank,
    the coupler translates, so ω_follower = ω_crank, ω_coupler = 0, α = 0 at constant speed."""
    mech = linkwork.load("library:parallelogram")
    w = mech.drivers[0].law.speed
    deg = np.array([179.9999942704220, 179.9999, 179.999, 179.99, 179.9, 179.0, 170.0, 100.0])
    sol = linkwork.solve(mech, np.radians(deg))
    follower, coupler = sol.link("follower"), sol.link("coupler")
    err = np.maximum.reduce([np.abs(follower.omega - w) / w, np.abs(coupler.omega) / w,
                             np.abs(follower.alpha) / w ** 2, np.abs(coupler.alpha) / w ** 2])
    ok = sol.status == Status.OK
    assert (err[ok] <= TOLERANCE).all(), (deg[ok], err[ok])
    assert not ok[0]  # 6e-6° from the change point: no digit of α survives
    assert ok[-3:].all()  # a degree away and more: right, and said so
    # the bound holds wherever it claims digits (a first-order bound above 1e-2 says none)
    given_ = np.isfinite(err) & (sol.errors < 1e-2)
    assert (err[given_] <= sol.errors[given_]).all()
    assert (sol.status[~ok] == Status.SINGULAR).all()  # the pose is returned, marked


# ---------------------------------------------------------------------------- a tiny rocker
TINY_ROCKER = four_bar_text(name="9e-5 mm rocker in a 60 mm drawing", O2=(0, 0), A=(0, 20),
                            B=(60, 20), O4=(60, 20 - 9e-5))


def test_tiny_rocker_keeps_its_joint_closed_and_its_answer_alone_or_in_a_batch():
    mech = linkwork.load_text(TINY_ROCKER)
    L = mech.length_scale
    u0 = mech.driver_input_at_design(mech.drivers[0])
    alone = linkwork.solve(mech, [u0])
    # with a sample that cannot assemble and others near it
    batch = linkwork.solve(mech, [u0 + 0.1, u0, u0 + 1e-9, u0 - 1e-9])
    for name in mech.link_names:
        np.testing.assert_array_equal(batch.pose_derivatives(name)[:, 1], alone.pose_derivatives(name)[:, 0])
    assert batch.status[0] == Status.UNREACHABLE
    assert batch.status[1] == alone.status[0] and batch.errors[1] == alone.errors[0]
    # the hinge B is where both links carry it, far within the rocker's length (9e-5)
    B = mech.points["B"]
    gap = np.hypot(*(alone.point_on("coupler", B).position[0] - alone.point_on("rocker", B).position[0]))
    assert gap <= 1e-9 * L
    # every stored rotation is one
    for i in range(len(mech.link_names)):
        c, s = alone._trig(i)
        np.testing.assert_allclose(c * c + s * s, 1.0, rtol=0, atol=4e-16)
    # the design position itself is exact: the joint closed, the rocker on its drawn angle
    if alone.status[0] == Status.OK:
        assert alone.errors[0] <= TOLERANCE


# ---------------------------------------------------------------------------- dead centres
def _relative_errors(mech, sol, n, ref, w):
    """The sample's error against the reference per order (positions, rates, accelerations),
    each over the larger of the natural scale and the reference's size there, the natural scale
    widened by the drawing's extent (the solver measures link origins, which lie up to that far
    from the points)."""
    L = mech.length_scale
    xy = np.array(list(mech.points.values()))
    widen = 1 + 2 * max(1.0, np.abs(xy).max() / L)
    out = []
    for k, (pk, lk) in enumerate((("", 0), ("v", 1), ("a", 2))):
        scale = L * abs(w) ** k
        size, err = 1.0, 0.0
        for p in ("B", "C"):
            m = sol.point(p)
            got = (m.position, m.velocity, m.acceleration)[k][n]
            size = max(size, float(mp.norm(ref[pk + p])) / scale)
            err = max(err, float(mp.norm(R._v(got) - ref[pk + p])) / scale)
        for ln, key in (("coupler", "coupler"), ("rocker", "rocker")):
            k_ = sol.link(ln)
            got = (k_.angle - sol.reference_angle(ln), k_.omega, k_.alpha)[k][n]
            want = ref[key][k]
            size = max(size, abs(float(want)) / abs(w) ** k)
            d = float(got - want)
            if k == 0:
                d = float(np.angle(np.exp(1j * d)))
            err = max(err, abs(d) * (L if k == 0 else 1) / (L if k == 0 else abs(w) ** k))
        out.append(err / (size * widen if k else widen))
    return max(out)


coordinate = st.floats(-1.0, 1.0, allow_nan=False)


@settings(max_examples=25, deadline=None,
          suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(st.lists(st.tuples(coordinate, coordinate), min_size=4, max_size=4),
       st.sampled_from([1e-3, 1.0, 37.5, 1e4]), st.integers(0, 3), st.sampled_from([1, -1]),
       st.floats(0.3, 20.0))
def test_dead_centres_ok_only_when_right_and_the_bound_holds(pts, size, which, side, w):
    """Random four-bars at 10⁻¹ … 10⁻¹⁵ rad from a dead centre, where the condition number runs
    from 10 to 10⁸ (the regime the other property tests skip)."""
    A, B, O4, C = (tuple(size * np.array(p)) for p in pts)
    P = [(0.0, 0.0), A, B, O4, C]
    d = [np.hypot(*np.subtract(P[i], P[j])) for i, j in ((0, 1), (1, 2), (2, 3), (0, 3), (1, 4))]
    assume(min(d) > 0.15 * size)
    # not a change-point chain (s + l = p + q), whose branch the reference does not follow
    s_, p_, q_, l_ = sorted(d[:4])
    assume(abs(s_ + l_ - p_ - q_) > 1e-3 * size)
    folds = R.fold_inputs(*P[:4])
    assume(len(folds) > which % max(len(folds), 1))
    mech = linkwork.load_text(four_bar_text(O2=P[0], A=A, B=B, O4=O4, coupler_points={"C": C}))
    assume(linkwork.solve(mech).condition[0] < 1e2)
    u0 = mech.driver_input_at_design(mech.drivers[0])
    fold = u0 + float(folds[which % len(folds)])
    u = fold + side * np.logspace(-15, -1, 15)
    sol = linkwork.solve(mech, u, velocities=np.full(u.shape, w))
    for n in range(len(u)):
        ref = R.four_bar(*P[:4], u[n], w, C=C, u0=u0)
        if ref is None or sol.status[n] == Status.UNREACHABLE:
            continue  # beyond the dead centre (the reference and the solver may differ by 1 ulp)
        err = _relative_errors(mech, sol, n, ref, w)
        if not np.isfinite(err):
            assert sol.status[n] == Status.SINGULAR  # rates NaN: no digit of them is right
            continue
        # a first-order bound holds where it claims digits (above 1e-2 it says there are none)
        assert err <= sol.errors[n] or sol.errors[n] >= 1e-2, (n, err, sol.errors[n])
        if sol.status[n] == Status.OK:
            assert err <= TOLERANCE


# ---------------------------------------------------------------------------- outputs
def test_the_bound_is_in_every_output():
    sol = linkwork.solve(linkwork.load("library:parallelogram"), np.radians([100.0, 179.9999]))
    doc = sol.to_document()
    assert [s["error"] for s in doc["samples"]] == pytest.approx(list(sol.errors))
    json.dumps(doc)
    df = sol.to_pandas()
    np.testing.assert_array_equal(df["error"].to_numpy(), sol.errors)
    assert list(df["status"]) == ["ok", "singular"]


def test_the_compiled_bound_is_the_general_recurrence_unrolled():
    """`kernels._group_error_2` (the dyad and driver kernels' pass, order 2) against the
    general recurrence of `propagate_errors` on the same random sizes and bounds."""
    from linkwork.kinematics import kernels

    rng = np.random.default_rng(7)
    N = 50
    kappa = 10.0 ** rng.uniform(0, 8, N)
    m = 10.0 ** rng.uniform(-1, 3, (3, N))
    m[0] = np.maximum(m[0], 1.0)
    E = 10.0 ** rng.uniform(-16, -8, (3, N))
    Q = np.zeros((3, 1, 3, N))  # no link: the sizes stay those given
    m1, E1 = m.copy(), E.copy()
    kernels.propagate_errors(Q, np.zeros(0, dtype=np.int64), 1.0, np.ones(N), kappa, np.zeros(0),
                             m1, E1, 1e-16)
    m2, E2 = m.copy(), E.copy()
    for n in range(N):
        kernels._group_error_2(kappa[n], m2, E2, n, 1e-16, 0.0, 0.0, 0.0)
    np.testing.assert_allclose(E2, E1, rtol=1e-14)
    np.testing.assert_array_equal(m2, m1)
