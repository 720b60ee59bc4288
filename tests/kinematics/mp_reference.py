"""A 50-digit reference for four-bars and slider-cranks, independent of linkwork's solver.

The drawing's coordinates and the input are taken as the exact binary numbers they are, and the
motion is computed from the loop closure by hand in mpmath: the crank turned about its pivot, the
hinge B as the intersection of two circles (four-bar) or of a circle and the guide line
(slider-crank) on the side of the drawing, velocities and accelerations from the differentiated
loop equations (2×2 systems solved exactly). With 50 digits the reference is exact to far below
any tolerance a test states, down to a few digits' distance from a dead centre.
"""

from __future__ import annotations

import mpmath as mp

mp.mp.dps = 50


def _v(p):
    return mp.matrix([mp.mpf(float(p[0])), mp.mpf(float(p[1]))])


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _perp(a):
    return mp.matrix([-a[1], a[0]])


def _rot(t, a):
    c, s = mp.cos(t), mp.sin(t)
    return mp.matrix([c * a[0] - s * a[1], s * a[0] + c * a[1]])


def _solve2(c1, c2, rhs):
    """x, y with x·c1 + y·c2 = rhs (Cramer)."""
    det = _cross(c1, c2)
    return _cross(rhs, c2) / det, _cross(c1, rhs) / det


def _crank(O2, A0, u, w):
    """Crank pivot O2, design A0, turned by u (radians, from the design); rate w, α = 0."""
    a = _rot(u, A0 - O2)
    return O2 + a, w * _perp(a), -w * w * a


def four_bar(O2, A, B, O4, u, w, C=None, u0=0.0):
    """The four-bar O2–A–B–O4 of the drawing with its crank turned by u − u0 from the design
    position (both exact binary numbers, the difference taken exactly) at input rate w. Returns
    a dict: B, C (a coupler point) positions, velocities and accelerations, and θ, ω, α of the
    coupler and the rocker (angles relative to their design angles); None where it does not
    assemble."""
    O2, A0, B0, O4 = (_v(p) for p in (O2, A, B, O4))
    L3, L4 = mp.norm(B0 - A0), mp.norm(B0 - O4)
    side = mp.sign(_cross(O4 - A0, B0 - A0))
    u = mp.mpf(float(u)) - mp.mpf(float(u0))
    w = mp.mpf(float(w))
    Ap, vA, aA = _crank(O2, A0, u, w)
    d = O4 - Ap
    D = mp.norm(d)
    x = (L3 * L3 - L4 * L4 + D * D) / (2 * D)
    h2 = L3 * L3 - x * x
    if h2 < 0:
        return None
    e = d / D
    Bp = Ap + x * e + side * mp.sqrt(h2) * _perp(e)
    r3, r4 = Bp - Ap, Bp - O4
    # vA + ω3 ⊥r3 = ω4 ⊥r4
    w3, w4 = _solve2(_perp(r3), -_perp(r4), -vA)
    # aA + α3 ⊥r3 − ω3² r3 = α4 ⊥r4 − ω4² r4
    a3, a4 = _solve2(_perp(r3), -_perp(r4), -aA + w3 * w3 * r3 - w4 * w4 * r4)
    vB = w4 * _perp(r4)
    aB = a4 * _perp(r4) - w4 * w4 * r4
    out = dict(B=Bp, vB=vB, aB=aB,
               coupler=(mp.atan2(r3[1], r3[0]) - mp.atan2(B0[1] - A0[1], B0[0] - A0[0]), w3, a3),
               rocker=(mp.atan2(r4[1], r4[0]) - mp.atan2(B0[1] - O4[1], B0[0] - O4[0]), w4, a4))
    if C is not None:
        c = _rot(out["coupler"][0], _v(C) - A0)
        out["C"] = Ap + c
        out["vC"] = vA + w3 * _perp(c)
        out["aC"] = aA + a3 * _perp(c) - w3 * w3 * c
    return out


def fold_inputs(O2, A, B, O4):
    """The crank turns u (from the design) at which the four-bar stretches or folds (|A O4| =
    L3 + L4 or |L3 − L4|): its limit positions, where they exist."""
    O2, A0, B0, O4 = (_v(p) for p in (O2, A, B, O4))
    L2, L3, L4 = mp.norm(A0 - O2), mp.norm(B0 - A0), mp.norm(B0 - O4)
    g = O4 - O2
    G = mp.norm(g)
    a0 = mp.atan2(A0[1] - O2[1], A0[0] - O2[0])
    gang = mp.atan2(g[1], g[0])
    out = []
    for D in (L3 + L4, abs(L3 - L4)):
        # |O4 − O2 − a|² = D² with |a| = L2: cos(angle between a and g) = (G² + L2² − D²)/(2 G L2)
        c = (G * G + L2 * L2 - D * D) / (2 * G * L2)
        if abs(c) <= 1:
            for s in (1, -1):
                out.append(gang + s * mp.acos(c) - a0)
    return out
