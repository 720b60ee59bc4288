"""Finite displacements (`linkwork.synthesis.positions`) against second methods: poles as fixed
points of the displacement computed from the poses, Hamilton's composition of rotations
(Pöschl §57: the pole triangle's angles are the half rotations), image poles as mirror images in
the pole triangle's sides, Pöschl's image point 𝔇 (§57, §58: the homologous points are its
mirror images, the centre point its isogonal conjugate, written here from trilinear
coordinates), the smallest circle through three homologous points (§59: radius = the incircle's
diameter), the Steiner lines through the orthocentre and Alt's four-bar whose coupler point
traces the centres of circles of one radius (§59)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize

from linkwork.errors import InputError
from linkwork.geometry import Line, Point, reflect
from linkwork.synthesis.positions import (Positions, SynthesisError, centre_points, circle_points,
                                          image_point, image_pole, pole_triangle)

RNG = np.random.default_rng(20261125)


def random_positions(n, rng=RNG):
    return Positions.from_poses(np.column_stack([rng.uniform(-5, 5, (n, 2)), rng.uniform(-2.5, 2.5, n)]))


def move(pose_i, pose_j, X):
    """X (in the fixed plane, plane in pose i) moved with the plane to pose j, by rotation
    matrices (a second writing of the displacement)."""
    def R(t):
        return np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    local = R(pose_i[2]).T @ (np.asarray(X) - pose_i[:2])
    return R(pose_j[2]) @ local + pose_j[:2]


def angle_mod_pi(v):
    return np.arctan2(v[1], v[0])


def same_mod_pi(a, b, tol=1e-9):
    d = np.remainder(a - b + np.pi / 2, np.pi) - np.pi / 2
    return abs(d) <= tol


@pytest.mark.parametrize("seed", range(12))
def test_pole_is_the_fixed_point_of_the_displacement(seed):
    pos = random_positions(4, np.random.default_rng(seed))
    P = pos.poses
    for (i, j), pole in pos.poles().items():
        xy = pole.xy
        assert np.allclose(move(P[i], P[j], xy), xy, atol=1e-9 * (1 + np.abs(xy).max()))
        # any other point turns about it through θ_ij
        X = np.array([1.3, -0.7])
        Y = move(P[i], P[j], X)
        assert np.hypot(*(Y - xy)) == pytest.approx(np.hypot(*(X - xy)), rel=1e-11)
        a = np.arctan2((Y - xy)[1], (Y - xy)[0]) - np.arctan2((X - xy)[1], (X - xy)[0])
        assert np.cos(a - pos.rotation(i, j)) == pytest.approx(1.0, abs=1e-12)


def test_pole_of_a_translation_is_at_infinity_normal_to_it():
    pos = Positions.from_poses([[0, 0, 0.4], [3, 1, 0.4]])
    P = pos.pole(0, 1)
    assert P.is_infinite
    assert abs(np.dot(P.direction.xy, [3, 1])) < 1e-15
    # a small rotation gives a far pole near that direction, continuously
    Q = Positions.from_poses([[0, 0, 0.4], [3, 1, 0.4 + 1e-9]]).pole(0, 1)
    assert Q.is_finite and np.hypot(*Q.xy) > 1e8
    u = Q.xy / np.hypot(*Q.xy)
    assert abs(np.dot(u, [3, 1])) / np.hypot(3, 1) < 1e-8


@pytest.mark.parametrize("seed", range(12))
def test_pole_triangle_angles_are_the_half_rotations(seed):
    """Hamilton (Pöschl §57): P₁₃ lies on the line through P₁₂ at −φ₁₂ from P₁₂P₂₃ and on the
    line through P₂₃ at +φ₂₃ from P₂₃P₁₂ (rotation 2φ = two reflections)."""
    pos = random_positions(3, np.random.default_rng(100 + seed))
    (P12, P13, P23), (f12, f13, f23) = pole_triangle(pos)
    a, b, c = P12.xy, P13.xy, P23.xy
    assert same_mod_pi(angle_mod_pi(b - a), angle_mod_pi(c - a) - f12)
    assert same_mod_pi(angle_mod_pi(b - c), angle_mod_pi(a - c) + f23)
    # the exterior angle at P13 is φ13 = φ12 + φ23 (mod π)
    assert same_mod_pi(f13, f12 + f23)


@pytest.mark.parametrize("seed", range(8))
def test_image_pole_is_the_mirror_image_in_the_pole_triangle(seed):
    pos = random_positions(3, np.random.default_rng(200 + seed))
    side = Line.through(pos.pole(0, 1), pos.pole(0, 2))
    assert image_pole(pos, 1, 2).equals(reflect(pos.pole(1, 2), side))
    side = Line.through(pos.pole(0, 2), pos.pole(1, 2))
    assert image_pole(pos, 0, 1, ref=2).equals(reflect(pos.pole(0, 1), side))


def isogonal_conjugate(X, A, B, C):
    """From trilinear coordinates: signed distances to the sides, inverted, turned back into
    Cartesian coordinates with the side lengths as weights."""
    def dist(P, Q, R):  # signed distance of P from line QR, positive on A's side
        n = np.array([-(R - Q)[1], (R - Q)[0]]) / np.hypot(*(R - Q))
        return np.dot(P - Q, n)
    sides = [(B, C, A), (C, A, B), (A, B, C)]
    tri = [dist(X, Q, R) / dist(V, Q, R) * np.sign(1) for Q, R, V in sides]  # normalised trilinears
    lengths = [np.hypot(*(C - B)), np.hypot(*(A - C)), np.hypot(*(B - A))]
    heights = [abs(dist(V, Q, R)) for Q, R, V in sides]
    t = [tri[k] * heights[k] for k in range(3)]  # signed distances
    inv = [1 / v for v in t]
    w = [lengths[k] * inv[k] for k in range(3)]
    return (w[0] * A + w[1] * B + w[2] * C) / sum(w)


@pytest.mark.parametrize("seed", range(10))
def test_image_point_reflections_and_isogonal_centre(seed):
    """Pöschl §57/§58: D₁, D₂, D₃ are the mirror images of 𝔇 in the three sides of the pole
    triangle, and the centre point of the circle through them is 𝔇's isogonal conjugate."""
    rng = np.random.default_rng(300 + seed)
    pos = random_positions(3, rng)
    D1 = rng.uniform(-4, 4, 2)
    img = image_point(pos, D1)
    P12, P13, P23 = (pos.pole(*ij) for ij in ((0, 1), (0, 2), (1, 2)))
    D = pos.homologous(D1)
    assert np.allclose(reflect(img, Line.through(P12, P13)).xy, D[0], atol=1e-9)
    assert np.allclose(reflect(img, Line.through(P12, P23)).xy, D[1], atol=1e-9)
    assert np.allclose(reflect(img, Line.through(P13, P23)).xy, D[2], atol=1e-9)
    M = centre_points(pos, D1)
    assert np.allclose(M.xy, isogonal_conjugate(img.xy, P12.xy, P13.xy, P23.xy), atol=1e-8)


def incircle(A, B, C):
    a, b, c = np.hypot(*(B - C)), np.hypot(*(C - A)), np.hypot(*(A - B))
    s = (a + b + c) / 2
    area = np.sqrt(s * (s - a) * (s - b) * (s - c))
    return (a * A + b * B + c * C) / (a + b + c), area / s


@pytest.mark.parametrize("seed", range(5))
def test_smallest_circle_through_three_homologous_points(seed):
    """Pöschl §59: the smallest circle belongs to 𝔇 = the incentre of the pole triangle and its
    radius is the incircle's diameter; a minimisation over all circle points finds no smaller."""
    pos = random_positions(3, np.random.default_rng(400 + seed))
    P12, P13, P23 = (pos.pole(*ij) for ij in ((0, 1), (0, 2), (1, 2)))
    I, r_in = incircle(P12.xy, P13.xy, P23.xy)
    D1 = reflect(Point.from_xy(I), Line.through(P12, P13)).xy
    M = centre_points(pos, D1).xy
    radius = np.hypot(*(D1 - M))
    assert radius == pytest.approx(2 * r_in, rel=1e-9)

    def r(z):
        c = centre_points(pos, z)
        return np.hypot(*(z - c.xy)) if c.is_finite else 1e300
    best = min((minimize(r, D1 + d, method="Nelder-Mead", options={"xatol": 1e-10, "fatol": 1e-12})
                for d in ([0.3, 0.1], [-0.2, 0.4])), key=lambda res: res.fun)
    assert best.fun >= radius * (1 - 1e-7)


def test_steiner_lines_pass_through_the_orthocentre():
    """Pöschl §59: 𝔇 on the circumcircle of the pole triangle gives three collinear homologous
    points (centre at infinity: a slider), on a line through the orthocentre."""
    pos = random_positions(3, np.random.default_rng(7))
    P12, P13, P23 = (pos.pole(*ij) for ij in ((0, 1), (0, 2), (1, 2)))
    A, B, C = P12.xy, P13.xy, P23.xy
    from linkwork.geometry import Circle
    circ = Circle.through(P12, P13, P23)
    H = A + B + C - 2 * circ.centre.xy  # orthocentre from the Euler line
    for t in (0.3, 1.7, 4.0):
        img = circ.centre.xy + circ.radius * np.array([np.cos(t), np.sin(t)])
        D1 = reflect(Point.from_xy(img), Line.through(P12, P13)).xy
        M = centre_points(pos, D1)
        assert M.is_infinite
        D = pos.homologous(D1)
        line = Line.through(Point.from_xy(D[0]), Point.from_xy(D[2]))
        assert line.contains(Point.from_xy(H), tol=1e-7)


@pytest.mark.parametrize("seed", range(6))
def test_circle_point_and_centre_point_are_inverse(seed):
    rng = np.random.default_rng(500 + seed)
    pos = random_positions(3, rng)
    M = rng.uniform(-4, 4, 2)
    z = circle_points(pos, M).xy
    D = pos.homologous(z)
    r = np.hypot(*(D - M).T)
    assert np.ptp(r) <= 1e-10 * r.max()
    assert np.allclose(centre_points(pos, z).xy, M, atol=1e-9)
    # position 2 as reference: the circle point drawn in position 2
    z2 = circle_points(pos, M, ref=1).xy
    assert np.allclose(z2, D[1], atol=1e-9)


def test_two_positions_give_lines_through_the_pole():
    pos = random_positions(2)
    z = np.array([0.7, 2.0])
    line = centre_points(pos, z)
    assert isinstance(line, Line) and line.contains(pos.pole(0, 1))
    M = np.array([1.0, -3.0])
    circ = circle_points(pos, M)
    assert circ.contains(pos.pole(0, 1))
    foot = circ.project(Point.from_xy([5.0, 5.0])).xy
    D = pos.homologous(foot)
    assert np.hypot(*(D[0] - M)) == pytest.approx(np.hypot(*(D[1] - M)), rel=1e-12)


def test_four_positions_need_a_point_of_the_curve():
    pos = random_positions(4)
    with pytest.raises(SynthesisError, match="centre-point curve"):
        circle_points(pos, [0.1, 0.2])
    with pytest.raises(SynthesisError, match="circle-point curve"):
        centre_points(pos, [0.1, 0.2])


def test_bad_positions_are_refused():
    with pytest.raises(SynthesisError, match="positions 1 and 2 coincide"):
        Positions.from_poses([[1, 2, 0.5], [1, 2, 0.5 + 2 * np.pi], [0, 0, 0]])
    with pytest.raises(InputError, match="at least two"):
        Positions.from_poses([[1, 2, 0.5]])
    with pytest.raises(InputError, match=r"\(n, 3\)"):
        Positions.from_poses([[1, 2], [3, 4]])
    with pytest.raises(SynthesisError, match="rigid"):
        Positions.from_points([[0, 0], [1, 1]], [[1, 0], [1, 3]])
    with pytest.raises(InputError, match="finite"):
        Positions.from_poses([[0, 0, np.nan], [1, 1, 0]])


def test_from_points_agrees_with_poses():
    pos = random_positions(3)
    A = pos.origin
    B = np.stack([pos.carry(pos.origin[0] + [np.cos(pos.angle[0]), np.sin(pos.angle[0])], 0, k)
                  for k in range(3)])
    again = Positions.from_points(A, B)
    assert np.allclose(again.origin, pos.origin)
    assert np.allclose(np.cos(again.angle - pos.angle), 1.0)


@pytest.mark.parametrize("seed", range(5))
def test_dyad_forms_are_the_halved_difference_of_squared_distances(seed):
    """Ẑᵀ B_k M̂ = (|Z_k − M|² − |Z − M|²)/2, with Z_k from the rotation matrices."""
    from linkwork.synthesis.positions import dyad_forms
    rng = np.random.default_rng(600 + seed)
    pos = random_positions(5, rng)
    B = dyad_forms(pos, ref=1)
    Z, M = rng.uniform(-3, 3, 2), rng.uniform(-3, 3, 2)
    others = [k for k in range(5) if k != 1]
    for form, k in zip(B, others):
        Zk = move(pos.poses[1], pos.poses[k], Z)
        want = (np.sum((Zk - M) ** 2) - np.sum((Z - M) ** 2)) / 2
        assert np.r_[Z, 1] @ form @ np.r_[M, 1] == pytest.approx(want, rel=1e-12, abs=1e-12)


def circle_meet(c1, r1, c2, r2, side):
    d = np.hypot(*(c2 - c1))
    u = (c2 - c1) / d
    x = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    h2 = r1 * r1 - x * x
    if h2 < 0:
        return None
    return c1 + x * u + side * np.sqrt(h2) * np.array([-u[1], u[0]])


@pytest.mark.parametrize("seed", range(4))
def test_alts_four_bar_traces_the_centres_of_circles_of_one_radius(seed):
    """Pöschl §59 (H. Alt's theorem, the digest's construction): on the altitude through P₁₂
    mark A at r/2; the parallel to P₁₃P₂₃ through A meets P₁₂P₂₃ at B and P₁₂P₁₃ at C; the
    four-bar on P₂₃, P₁₃ with cranks |P₁₂B|, |P₁₂C| and coupler |BC|, its coupler point Δ
    making ΔUV ≅ P₁₂BC, traces centre points whose circles through three homologous points all
    have radius r."""
    pos = random_positions(3, np.random.default_rng(900 + seed))
    P12, P13, P23 = (pos.pole(*ij).xy for ij in ((0, 1), (0, 2), (1, 2)))
    n = np.array([-(P23 - P13)[1], (P23 - P13)[0]])
    n /= np.hypot(*n)
    if np.dot(P13 - P12, n) < 0:
        n = -n  # the altitude from P12 towards the opposite side
    r = 3 * incircle(P12, P13, P23)[1]  # above the smallest radius, 2·r_in (§59)
    A = P12 + r / 2 * n
    side_dir = (P23 - P13) / np.hypot(*(P23 - P13))

    def meet(p, q):  # the parallel through A with the line pq
        d = q - p
        t = ((A - p)[0] * side_dir[1] - (A - p)[1] * side_dir[0]) / (d[0] * side_dir[1] - d[1] * side_dir[0])
        return p + t * d
    B, C = meet(P12, P23), meet(P12, P13)
    lu, lv, lc = np.hypot(*(B - P12)), np.hypot(*(C - P12)), np.hypot(*(B - C))
    works = {}
    for alpha in np.linspace(0, 2 * np.pi, 360, endpoint=False):
        U = P23 + lu * np.array([np.cos(alpha), np.sin(alpha)])
        for branch in (1, -1):
            V = circle_meet(U, lc, P13, lv, branch)
            if V is None:
                continue
            for side in (1, -1):
                D = circle_meet(U, lu, V, lv, side)
                z = circle_points(pos, D).xy
                ok = abs(np.hypot(*(z - D)) - r) <= 1e-9 * r
                works.setdefault((branch, side), []).append(ok)
    # one side of the coupler (the congruent triangle's orientation) works wherever it assembles
    assert any(len(v) >= 4 and all(v) for v in works.values())
