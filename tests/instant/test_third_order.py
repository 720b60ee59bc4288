"""Third- and fourth-order properties: the cubic of stationary curvature, the Ball point and the
Burmester points, checked with the engine's jerks (dκ/dt from V, A and the jerk of each point)
and with finite differences of the engine's own curvature rates."""

import numpy as np
import pytest

import linkwork
from linkwork.instant import (ball_point, burmester_points, curvature_centre, fourth_order,
                              inflection_circle, stationary_curvature)

import instant_mechanisms as im
from instant_mechanisms import cross


def _mech():
    text, _ = im.four_bar(4.0, 1.5, 3.5, 3.0, 1.0, point=(1.0, 1.2))
    return linkwork.load_text(text)


def _kappa_rates(sol, link, xy):
    """(κ, dκ/dt) of the absolute paths of the points of `link` at frame positions xy, from
    the engine's velocity, acceleration and jerk."""
    pm = sol.point_on(link, sol.local(link, xy))
    V, A, J = pm.velocity, pm.acceleration, pm.jerk
    vv = (V * V).sum(1)
    kappa = cross(V, A) / vv ** 1.5
    dk = (cross(V, J) * vv - 3 * cross(V, A) * (V * A).sum(1)) / vv ** 2.5
    return kappa, dk


U = np.radians([25.0, 80.0, 160.0, 290.0])


def test_cubic_points_have_stationary_curvature():
    mech = _mech()
    sol = linkwork.solve(mech, U, velocities=np.array([1.0, 2.0, -1.0, 0.5]),
                         accelerations=np.array([0.0, 1.0, 3.0, -0.2]), order=3)
    sc = stationary_curvature(sol, "coupler")
    pts = sc.points(40, limit=3 * mech.length_scale)
    checked = 0
    for k in range(pts.shape[1]):
        xy = pts[:, k]
        fin = np.isfinite(xy).all(axis=1)
        fin &= np.linalg.norm(xy - sc.pole.xy, axis=1) > 1e-3  # the pole is the double point
        if not fin.any():
            continue
        kap, dk = _kappa_rates(sol, "coupler", np.where(fin[:, None], xy, 0.0))
        scale = np.abs(kap) * np.linalg.norm(sol.point_on("coupler", sol.local("coupler", np.where(fin[:, None], xy, 0))).velocity, axis=1)
        assert np.all(np.abs(dk[fin]) < 1e-8 * (scale[fin] + 1)), k
        assert np.all(np.abs(sc.residual(np.where(fin[:, None], xy, 0.0))[fin]) < 1e-10)
        checked += fin.sum()
    assert checked > 100


def test_cubic_canonical_form():
    # 1/ρ = 1/(M sin φ) + 1/(N cos φ), φ from the pole tangent t = J n
    mech = _mech()
    sol = linkwork.solve(mech, U, order=3)
    sc = stationary_curvature(sol, "coupler")
    pts = sc.points(12)
    phi = np.linspace(0.0, np.pi, 12, endpoint=False)
    for k in (1, 2, 4, 5, 7, 8, 10, 11):  # not along the tangent or the normal
        r = pts[:, k] - sc.pole.xy
        rho = (r * (np.cos(phi[k]) * sc.tangent + np.sin(phi[k]) * sc.normal)).sum(1)
        fin = np.isfinite(rho)
        lhs = 1 / rho[fin]
        rhs = 1 / (sc.M[fin] * np.sin(phi[k])) + 1 / (sc.N[fin] * np.cos(phi[k]))
        assert np.allclose(lhs, rhs, rtol=1e-9)


def test_ball_point():
    # on the inflection circle and on the cubic: zero curvature and zero curvature rate
    mech = _mech()
    sol = linkwork.solve(mech, U, velocities=np.array([1.0, 2.0, -1.0, 0.5]),
                         accelerations=np.array([0.3, 1.0, 3.0, -0.2]), order=3)
    Ub = ball_point(sol, "coupler")
    assert inflection_circle(sol, "coupler").contains(Ub).all()
    pm = sol.point_on("coupler", sol.local("coupler", Ub.xy))
    V, A, J = pm.velocity, pm.acceleration, pm.jerk
    nv = np.linalg.norm(V, axis=1)
    assert np.all(np.abs(cross(V, A)) < 1e-9 * nv * np.linalg.norm(A, axis=1))
    assert np.all(np.abs(cross(V, J)) < 1e-9 * nv * np.linalg.norm(J, axis=1))
    assert curvature_centre(sol, "coupler", sol.local("coupler", Ub.xy)).centre.is_infinite.all()


def test_fourth_order_matches_differenced_jerks():
    mech = _mech()
    h = 1e-4
    sol = fourth_order(linkwork.solve(mech, U, order=3))
    assert sol.order == 4
    base = linkwork.solve(mech, U, order=3)
    for ln in mech.link_names:
        assert np.array_equal(sol.pose_derivatives(ln)[:4], base.pose_derivatives(ln))
        jp = linkwork.solve(mech, U + h, order=3).pose_derivatives(ln)[3]
        jm = linkwork.solve(mech, U - h, order=3).pose_derivatives(ln)[3]
        # uniform crank (ω = 1): d/dt = d/du
        assert np.allclose(sol.pose_derivatives(ln)[4], (jp - jm) / (2 * h), rtol=1e-6, atol=1e-6)
    with pytest.raises(linkwork.LinkworkError, match="order=3"):
        fourth_order(linkwork.solve(mech, U, order=2))


def test_burmester_points():
    # the crank pins (circular paths: curvature constant) are always among them, and every
    # point found has dκ/dt = 0 (engine jerks) and d²κ/dt² = 0 (differenced engine rates)
    mech = _mech()
    sol = linkwork.solve(mech, U, order=3)
    bp = burmester_points(sol, "coupler")
    assert np.all(bp.count >= 2) and np.all(bp.count <= 4)
    for joint in ("A", "B"):
        X = sol.point(joint).position
        d = np.nanmin(np.linalg.norm(bp.points - X[:, None], axis=2), axis=1)
        assert np.all(d < 1e-7), (joint, d)
    h = 1e-4
    for k in range(4):
        xy = bp.points[:, k]
        fin = np.isfinite(xy).all(axis=1)
        if not fin.any():
            continue
        s = sol.local("coupler", np.where(fin[:, None], xy, 0.0))  # follow these material points
        kap, dk = _kappa_rates(sol, "coupler", np.where(fin[:, None], xy, 0.0))
        assert np.all(np.abs(dk[fin]) < 1e-7 * (np.abs(kap[fin]) + 1))

        def rate(x, s=s):
            sx = linkwork.solve(mech, x, order=3)
            return _kappa_rates(sx, "coupler", sx.point_on("coupler", s).position)[1]

        d2 = (rate(U + h) - rate(U - h)) / (2 * h)
        assert np.all(np.abs(d2[fin]) < 1e-5 * (np.abs(kap[fin]) + 1)), (k, d2)
    # their centres of curvature: the crank pins' are the fixed pivots
    for joint, pivot in (("A", "O2"), ("B", "O4")):
        X = sol.point(joint).position
        idx = np.nanargmin(np.linalg.norm(bp.points - X[:, None], axis=2), axis=1)
        C = bp.centres[np.arange(len(U)), idx]
        assert np.allclose(C, mech.points[pivot], atol=1e-7)


def test_third_order_needs_jerks():
    mech = _mech()
    with pytest.raises(linkwork.LinkworkError, match="order=3"):
        stationary_curvature(linkwork.solve(mech, U, order=2), "coupler")


def test_centre_point_curve_holds_the_conjugates():
    # the centre-point curve (Euler–Savary images of the cubic) against the osculating centres
    # computed from the engine's velocities and accelerations at the same points
    mech = _mech()
    sol = linkwork.solve(mech, U, order=3)
    sc = stationary_curvature(sol, "coupler")
    X, C = sc.points(9, limit=3 * mech.length_scale), sc.centre_points(9, limit=3 * mech.length_scale)
    for k in range(1, 9):
        fin = np.isfinite(X[:, k]).all(axis=1) & np.isfinite(C[:, k]).all(axis=1)
        if not fin.any():
            continue
        pm = sol.point_on("coupler", sol.local("coupler", np.where(fin[:, None], X[:, k], 0.0)))
        V, A = pm.velocity, pm.acceleration
        ref = pm.position + ((V * V).sum(1) / cross(V, A))[:, None] * np.c_[-V[:, 1], V[:, 0]]
        assert np.allclose(C[fin, k], ref[fin], rtol=1e-8, atol=1e-8)
