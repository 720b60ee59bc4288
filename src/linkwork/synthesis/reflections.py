"""The poles of three positions and their homologous points by Hamilton's reflections (Pöschl
§57, Abb. 72–73), as a ruler-and-compass construction drawn step by step
(`constructions.construction.Builder`; `linkwork synth poles --steps`).

Three positions Σ₁, Σ₂, Σ₃ of a moving plane are given by one segment A_kB_k of it in each
(its origin and a point of its x-axis). The pole P_ij is where the perpendicular bisectors of
A_iA_j and B_iB_j meet (*Drehpol*); the pole triangle P₁₂P₁₃P₂₃ has at P₁₂ and P₂₃ the half
rotations φ₁₂, φ₂₃ as angles and φ₁₃ as its exterior angle at P₁₃ (Hamilton's composition of
finite rotations). A point D₁ of Σ₁ is mirrored in the side P₁₂P₁₃ to the image point 𝔇
(Pöschl's Fraktur 𝔇, labelled D* in the drawings); its mirror images in the sides P₁₂P₂₃ and P₁₃P₂₃ are D₂ and D₃, the
homologous points of D₁ in Σ₂ and Σ₃.

Every result is compared with the analytic one (`positions.Positions`: the poles from the
rotation formula, the half angles from the poses, the homologous points by moving D₁ with the
displacements); a disagreement beyond 1e-9 is an error, as in every construction.
"""

from __future__ import annotations

import numpy as np

from ..constructions.construction import Builder, Construction, Role
from ..errors import InputError
from ..geometry import Point
from .positions import Positions, wrap

__all__ = ["pole_construction"]


def _pt(xy) -> Point:
    return Point.from_xy(np.asarray(xy, dtype=float).reshape(1, 2))


def pole_construction(pos: Positions, point=None, *, triple: tuple[int, int, int] = (0, 1, 2)) -> Construction:
    """Hamilton's construction for the positions `triple` (0-based) of `pos`: the poles, the
    pole triangle and, for the point `point` of the first of them (x, y drawn in that position;
    default: the midpoint of its segment AB), the image point and the homologous points."""
    i, j, k = triple
    if len(set(triple)) != 3 or not all(0 <= t < len(pos) for t in triple):
        raise InputError(f"triple {triple}: give three different positions 0 … {len(pos) - 1}")
    size = pos.size
    tips = pos.origin + 0.2 * size * np.column_stack([np.cos(pos.angle), np.sin(pos.angle)])
    D1xy = (pos.origin[i] + tips[i]) / 2 if point is None else np.asarray(point, dtype=float)
    if D1xy.shape != (2,) or not np.isfinite(D1xy).all():
        raise InputError("give the point D1 as x, y")
    num = {i: 1, j: 2, k: 3}
    b = Builder("hamilton", "Poles, pole triangle and homologous points by reflection (Hamilton)",
                "Pöschl §57, Abb. 72–73", 1)
    b.length = size
    b.step("Given: the positions Σ_1, Σ_2, Σ_3 of the moving plane, each by its segment A_kB_k.")
    A, B = {}, {}
    for t in triple:
        n = num[t]
        A[t] = b.point(f"A{n}", _pt(pos.origin[t]), Role.GIVEN, f"A_{n}")
        B[t] = b.point(f"B{n}", _pt(tips[t]), Role.GIVEN, f"B_{n}")
        b.segment(f"A{n}B{n}", A[t], B[t], Role.GIVEN)
    poles = {}
    for p, q in ((i, j), (j, k), (i, k)):
        a, c = num[p], num[q]
        name = f"P{a}{c}"
        b.step(f"The pole P_{a}{c}: the perpendicular bisectors of A_{a}A_{c} and B_{a}B_{c} meet there.")
        bis = []
        for X, tag in ((A, "A"), (B, "B")):
            mid = b.point(f"{tag}{a}{c}.mid", _pt((X[p].xy[0] + X[q].xy[0]) / 2), Role.AUXILIARY)
            chord = b.join(f"{tag}{a}{tag}{c}", X[p], X[q])
            bis.append(b.perpendicular(f"{tag}{a}{c}.bisector", mid, chord))
        poles[(p, q)] = b.meet(name, bis[0], bis[1], Role.RESULT, f"P_{{{a}{c}}}", kind="pole",
                               k1=f"A{a}{c}.bisector", k2=f"B{a}{c}.bisector",
                               why=f"the positions {a} and {c} differ by a translation (P_{a}{c} at infinity)")
        b.compare_points(name, f"P_{a}{c}", f"pole of positions {a}, {c}", poles[(p, q)],
                         _pole(pos, p, q), size, pos.origin.mean(axis=0))
    P12, P23, P13 = poles[(i, j)], poles[(j, k)], poles[(i, k)]
    b.step("The pole triangle P_12 P_13 P_23: its angles at P_12 and P_23 are the half rotations φ_12 and "
           "φ_23, its exterior angle at P_13 is φ_13 (Hamilton's composition of rotations).")
    b.polygon("pole-triangle", [P12, P13, P23], Role.RESULT)
    for (p, q), V, U, W in (((i, j), P12, P13, P23), ((j, k), P23, P12, P13), ((i, k), P13, P12, P23)):
        ang = _angle_at(V.xy[0], U.xy[0], W.xy[0])
        half = 0.5 * wrap(pos.angle[q] - pos.angle[p])
        b.compare(f"phi{num[p]}{num[q]}", f"|sin φ_{num[p]}{num[q]}|",
                  f"sine of the triangle's angle at P_{num[p]}{num[q]} against the half rotation",
                  [abs(np.sin(ang))], [abs(np.sin(half))], 1.0)
    b.step("The image point: D_1 of Σ_1 mirrored in the side P_12P_13 (the foot F_1 of the "
           "perpendicular, then as far beyond it).")
    D1 = b.point("D1", _pt(D1xy), Role.GIVEN, "D_1")
    s12_13 = b.join("P12P13", P12, P13)
    F1 = b.foot("F1", D1, s12_13, label="F_1", k="P12P13")
    img = b.point("image", _pt(2 * F1.xy[0] - D1xy), Role.RESULT, "D^{*}")
    want = pos.homologous(D1xy, i)
    found = {}
    for (side, p1, p2, t, n) in (("P12P23", P12, P23, j, 2), ("P13P23", P13, P23, k, 3)):
        b.step(f"D_{n}: the image point mirrored in the side {side[:3]}{side[3:]}.".replace("P1", "P_1")
               .replace("P2", "P_2"))
        line = b.join(side, p1, p2)
        F = b.foot(f"F{n}", img, line, label=f"F_{n}", k=side)
        found[t] = b.point(f"D{n}", _pt(2 * F.xy[0] - img.xy[0]), Role.RESULT, f"D_{n}")
        b.compare_points(f"D{n}", f"D_{n}", f"homologous point of D_1 in position {n}", found[t],
                         _pt(want[t]), size, pos.origin.mean(axis=0))
    return b.finish()


def _pole(pos: Positions, p: int, q: int) -> Point:
    P = pos.pole(min(p, q), max(p, q))
    return Point(np.asarray(P.coords, dtype=float).reshape(1, 3))


def _angle_at(V: np.ndarray, U: np.ndarray, W: np.ndarray) -> float:
    u, w = U - V, W - V
    return float(np.arctan2(abs(u[0] * w[1] - u[1] * w[0]), u @ w))
