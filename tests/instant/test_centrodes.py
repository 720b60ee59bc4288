"""Centrodes against closed forms (Rosenauer §5 Examples 3–4, §31, §43; Pöschl §39 Beispiel 10)
and their radii of curvature against circles fitted to the densely sampled polylines."""

import numpy as np
import pytest

import linkwork
from linkwork.instant import centrodes

import instant_mechanisms as im
from instant_mechanisms import osculating_centre


def test_ellipsograph_cardan_circles():
    # fixed centrode: circle of radius l about O; moving: radius l/2 about the rod's midpoint;
    # R′ = l, R = l/2, D = l (Pöschl Beispiel 10; Rosenauer §31, §44 Ex. 17)
    l = 2.0
    mech = linkwork.load_text(im.ellipsograph(l, np.radians(50)))
    sol = linkwork.whole_motion(mech, order=3)
    assert len(sol) > 300
    c = centrodes(sol, "rod")
    ok = np.isfinite(c.fixed_xy).all(axis=1)
    assert ok.mean() > 0.95
    assert np.allclose(np.linalg.norm(c.fixed_xy[ok], axis=1), l)
    M = mech.points["M"]
    assert np.allclose(np.linalg.norm(c.moving_xy[ok] - M, axis=1), l / 2)
    assert np.allclose(c.fixed_radius[ok], l) and np.allclose(c.moving_radius[ok], l / 2)
    assert np.allclose(c.diameter[ok], l)
    assert np.allclose(c.residual[ok], 0, atol=1e-12)
    # the fixed centrode is run through all the way round (one turn of the rod)
    ang = np.unwrap(np.arctan2(c.fixed_xy[ok, 1], c.fixed_xy[ok, 0]))
    assert np.ptp(ang) > 1.9 * np.pi


@pytest.mark.parametrize("a,c,t", [(2.0, 1.0, 1.2), (1.0, 2.0, 1.5)])
def test_antiparallelogram_conics(a, c, t):
    # Rosenauer §5 Ex. 3 (frame on the shorter link): ellipses, PC + PD = 2a = πA + πB;
    # Ex. 4 (longer link, conclusion lost in the OCR, classically): hyperbolas |PC − PD| = 2a
    text, pts = im.antiparallelogram(a, c, t)  # t: away from the change points
    mech = linkwork.load_text(text)
    assert np.isclose(np.linalg.norm(pts["A"] - pts["B"]), 2 * c)
    u0 = mech.driver_input_at_design(mech.drivers[0])
    sol = linkwork.solve(mech, u0 + np.radians(np.linspace(-25, 25, 11)), order=3)
    assert (sol.status == linkwork.Status.OK).all()
    cen = centrodes(sol, "coupler")
    P, pi = cen.fixed_xy, cen.moving_xy
    dC, dD = (np.linalg.norm(P - pts[k], axis=1) for k in ("C", "D"))
    dA, dB = (np.linalg.norm(pi - pts[k], axis=1) for k in ("A", "B"))
    if a > c:
        assert np.allclose(dC + dD, 2 * a) and np.allclose(dA + dB, 2 * a)
    else:
        assert np.allclose(np.abs(dC - dD), 2 * a) and np.allclose(np.abs(dA - dB), 2 * a)
    # the two centrodes are congruent: equal curvature at the contact point, opposite sense
    assert np.allclose(cen.moving_radius, -cen.fixed_radius, rtol=1e-9)


def test_rolling_wheel():
    # fixed centrode: the line y = 0 (R′ = ∞); moving: the rim (R = r); D = r
    r = 1.5
    mech = linkwork.load_text(im.rolling_wheel(r))
    sol = linkwork.solve(mech, np.linspace(-3, 3, 13), order=3)
    c = centrodes(sol, "wheel")
    assert np.allclose(c.fixed_xy[:, 1], 0, atol=1e-12)
    assert np.allclose(c.fixed_xy[:, 0], np.linspace(-3, 3, 13))
    assert np.isinf(c.fixed_radius).all()
    assert np.allclose(np.linalg.norm(c.moving_xy - mech.points["O"], axis=1), r)
    assert np.allclose(c.moving_radius, r) and np.allclose(c.diameter, r)


def test_epicycloid_equal_wheels():
    # Rosenauer §15, (10) with ρ_p = ρ_π: D = ρ/2 (a wheel rolling on an equal fixed wheel)
    mech = linkwork.load_text(im.planetary(1.0, 1.0))
    sol = linkwork.solve(mech, np.radians([0.0, 70.0, 190.0]), order=3)
    c = centrodes(sol, "planet")
    assert np.allclose(np.linalg.norm(c.fixed_xy, axis=1), 1.0)
    assert np.allclose(c.fixed_radius, -1.0) and np.allclose(c.moving_radius, 1.0)
    assert np.allclose(c.diameter, 0.5)


@pytest.mark.parametrize("link,rel", [("coupler", None), ("crank", "rocker"), ("rocker", "crank")])
def test_four_bar_centrode_radii_equal_fitted_circles(link, rel):
    text, _ = im.four_bar(4.0, 1.5, 3.5, 3.0, 1.0)
    mech = linkwork.load_text(text)
    u = np.radians([35.0, 100.0, 230.0, 300.0])
    sol = linkwork.solve(mech, u, order=3)
    c = centrodes(sol, link, rel)

    def fixed(x):
        return centrodes(linkwork.solve(mech, x, order=2), link, rel, curvature=False).fixed_xy

    def moving(x):
        return centrodes(linkwork.solve(mech, x, order=2), link, rel, curvature=False).moving_xy

    for poly, R, get in ((c.fixed_xy, c.fixed_radius, fixed), (c.moving_xy, c.moving_radius, moving)):
        ref = osculating_centre(get, u, 2e-3)
        rad = np.linalg.norm(ref - poly, axis=1)
        assert np.allclose(np.abs(R), rad, rtol=1e-5)
    # the moving centrode seen in the link's own frame rolls on the fixed one: the same speed
    h = 1e-6
    dF = np.linalg.norm(fixed(u + h) - fixed(u - h), axis=1)
    dM = np.linalg.norm(moving(u + h) - moving(u - h), axis=1)
    assert np.allclose(dF, dM, rtol=1e-6)
    assert np.allclose(c.residual, 0, atol=1e-9)


def test_curvature_needs_jerks():
    text, _ = im.four_bar(4.0, 1.5, 3.5, 3.0, 1.0)
    sol = linkwork.solve(linkwork.load_text(text), [1.0], order=2)
    with pytest.raises(linkwork.LinkworkError, match="order=3"):
        centrodes(sol, "coupler")
    assert np.isnan(centrodes(sol, "coupler", curvature=False).fixed_radius).all()
