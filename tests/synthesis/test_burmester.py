"""Burmester theory (`linkwork.synthesis.burmester`) against second methods: positions taken
from a four-bar written out here in closed form (its pivots must lie on the centre-point curve
and be found among the Burmester points), Pöschl's pole-curve condition (§61: the curve points
see two opposite sides of the pole quadrilateral under equal angles, and its asymptote is
parallel to (P₁₄ − P₁₃) − (P₂₄ − P₂₃)), circle points checked by carrying them with rotation
matrices, and the number of real Burmester points counted again by sign changes of the second
cubic along the sampled first one."""

from __future__ import annotations

import numpy as np
import pytest

from linkwork.errors import InputError
from linkwork.synthesis.burmester import (burmester_points, centre_point_curve, circle_point_curve,
                                          curve_samples)
from linkwork.synthesis.positions import Positions, SynthesisError
from four_bar_by_hand import O2, O4, generated, move

def spread_of_radii(pos, M, Z, ref=0):
    D = np.array([move(pos.poses[ref], pos.poses[k], Z) for k in range(len(pos))])
    r = np.hypot(*(D - M).T)
    return np.ptp(r) / r.max()


POS4, A4, B4 = generated([10, 45, 80, 120])


def test_centre_point_curve_passes_the_pivots_and_the_poles():
    K = centre_point_curve(POS4)
    assert abs(K(O2)) < 1e-12 and abs(K(O4)) < 1e-12
    for p in POS4.poles().values():
        assert abs(K(p.xy)) < 1e-12
    assert abs(K([1.0, 1.0])) > 1e-4
    # the same with the user's coefficients
    from numpy.polynomial.polynomial import polyval2d
    C = K.coefficients
    assert abs(polyval2d(*O4, C)) <= 1e-12 * np.abs(C).max() * 4**3


def test_circle_point_curve_passes_the_moving_pivots():
    k = circle_point_curve(POS4)
    assert abs(k(A4[0])) < 1e-12 and abs(k(B4[0])) < 1e-12
    for j in (1, 2, 3):
        assert abs(k(POS4.pole(0, j).xy)) < 1e-12
    assert abs(k([1.0, 1.0])) > 1e-5
    # drawn in position 3
    k3 = circle_point_curve(POS4, ref=2)
    assert abs(k3(A4[2])) < 1e-12 and abs(k3(B4[2])) < 1e-12


def test_a_centre_point_gives_its_circle_point():
    K = centre_point_curve(POS4)
    assert np.allclose(K.mate(O4).xy, B4[0], atol=1e-9)
    assert np.allclose(K.mate(O2).xy, A4[0], atol=1e-9)
    with pytest.raises(SynthesisError, match="not a centre point"):
        K.mate([1.0, 1.0])


def test_the_cubics_are_circular_with_poeschls_asymptote():
    for curve in (centre_point_curve(POS4), circle_point_curve(POS4)):
        for C in (curve.unit, curve.coefficients):
            scale = np.abs(C).max()
            assert C[3, 0] == pytest.approx(C[1, 2], abs=1e-12 * scale)
            assert C[0, 3] == pytest.approx(C[2, 1], abs=1e-12 * scale)
    P = {ij: POS4.pole(*ij).xy for ij in POS4.poles()}
    want = (P[0, 3] - P[0, 2]) - (P[1, 3] - P[1, 2])
    got = centre_point_curve(POS4).asymptote_direction
    w = want / np.hypot(*want)
    assert abs(w[0] * got[1] - w[1] * got[0]) < 1e-10


@pytest.mark.parametrize("seed", range(4))
def test_sampled_curve_sees_opposite_sides_under_equal_angles(seed):
    """Pöschl §61: Im[(P₂₃−X)(P₁₄−X)·conj((P₁₃−X)(P₂₄−X))] = 0 on the curve; and every sample's
    circle point has four concyclic homologous points."""
    rng = np.random.default_rng(seed)
    pos = Positions.from_poses(np.column_stack([rng.uniform(-3, 3, (4, 2)), rng.uniform(-1.5, 1.5, 4)]))
    K = centre_point_curve(pos)
    pts = curve_samples(K, samples=180)
    pts = pts[np.isfinite(pts).all(axis=1)]
    pts = pts[np.hypot(*pts.T) < 50]
    assert len(pts) > 100
    P = {ij: complex(*pos.pole(*ij).xy) for ij in pos.poles()}
    X = pts[:, 0] + 1j * pts[:, 1]
    w = (P[1, 2] - X) * (P[0, 3] - X) * np.conj((P[0, 2] - X) * (P[1, 3] - X))
    assert np.all(np.abs(w.imag) <= 1e-8 * np.abs(w) + 1e-12)
    for M in pts[::17]:
        Z = K.mate(M).xy
        assert spread_of_radii(pos, M, Z) < 1e-8


def test_burmester_points_contain_the_generating_four_bar():
    pos, A, B = generated([20, 50, 80, 110, 140])
    res = burmester_points(pos)
    assert len(res.dyads) in (2, 4) and res.complex_count == 4 - len(res.dyads)
    found = {tuple(np.round(d.centre.xy, 6)) for d in res.dyads}
    assert (0.0, 0.0) in found and (4.0, 0.0) in found
    for d in res.dyads:
        assert spread_of_radii(pos, d.centre.xy, d.circle.xy) < 1e-12
        if np.allclose(d.centre.xy, O4, atol=1e-9):
            assert np.allclose(d.circle.xy, B[0], atol=1e-9)
    # drawn in position 4: the same centre points, the circle points where they are in 4
    again = burmester_points(pos, ref=3)
    for d in again.dyads:
        assert spread_of_radii(pos, d.centre.xy, d.circle.xy, ref=3) < 1e-12
    assert {tuple(np.round(d.centre.xy, 6)) for d in again.dyads} == found


def sign_change_count(pos):
    """Real Burmester points counted along the sampled centre-point curve of positions 1–4:
    sign changes of the cubic of positions 1, 2, 3, 5 away from the shared poles."""
    K1 = centre_point_curve(pos.subset([0, 1, 2, 3]))
    K2 = centre_point_curve(pos.subset([0, 1, 2, 4]))
    n = 40000
    pts = curve_samples(K1, samples=n)
    shared = [pos.pole(0, 1).xy, pos.pole(0, 2).xy, pos.pole(1, 2).xy]
    count = 0
    for branch in (pts[:n], pts[n + 1:]):
        v = K2(branch)
        near = np.zeros(len(branch), bool)
        for p in shared:
            near |= np.hypot(*(branch - p).T) < 0.002 * (pos.size + np.hypot(*(p - shared[0])))
        ok = np.isfinite(v) & ~near
        s = np.sign(v)
        step = np.hypot(*np.diff(branch, axis=0).T)
        far = np.hypot(*(branch[:-1] - shared[0]).T)
        both = ok[:-1] & ok[1:] & (step < 0.01 * (pos.size + far))  # a continuous piece of the curve
        count += int(np.sum(both & (s[:-1] != s[1:])))
    return count


@pytest.mark.parametrize("seed", range(10))
def test_number_of_real_points_by_sign_changes(seed):
    rng = np.random.default_rng(1000 + seed)
    pos = Positions.from_poses(np.column_stack([rng.uniform(-3, 3, (5, 2)), rng.uniform(-1.2, 1.2, 5)]))
    res = burmester_points(pos)
    assert len(res.dyads) in (0, 2, 4)
    assert len(res.dyads) == sign_change_count(pos)
    for d in res.dyads:
        assert spread_of_radii(pos, d.centre.xy, d.circle.xy) < 1e-9
    if len(res.dyads) < 2:
        assert "no four-bar" in res.message


def test_wrong_numbers_of_positions_are_refused():
    with pytest.raises(InputError, match="five positions"):
        burmester_points(POS4)
    with pytest.raises(InputError, match="four positions"):
        centre_point_curve(generated([0, 10, 20, 30, 40])[0])
