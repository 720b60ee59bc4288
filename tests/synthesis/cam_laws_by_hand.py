"""The standard cam motion laws written out by hand, piece by piece, from their definitions (the
expectations of the cam tests; nothing here comes from linkwork).

Each function returns S, S′, S″, S‴ at x in [0, 1] (S(0) = 0, S(1) = 1). The modified laws are
integrated by hand from their acceleration (sine quarters and halves, constants):

modified sine, a = C·sin 4πx on [0, 1/8], C·cos(4π(x − 1/8)/3) on [1/8, 7/8],
−C·cos 4π(x − 7/8) on [7/8, 1]; integrating twice from rest gives S(1) = C(1/4π + 1/π²), so
C = 4π²/(π + 4).

modified trapezoid, a = C·sin 4πx on [0, 1/8], C on [1/8, 3/8], C·cos 4π(x − 3/8) on
[3/8, 1/2], and antisymmetric about x = 1/2; S(1/2) = C(1/8π + 1/16) = 1/2 gives
C = 8π/(2 + π).
"""

from __future__ import annotations

import numpy as np

PI = np.pi


def uniform(x):
    z = np.zeros_like(x)
    return x, np.ones_like(x), z, z


def harmonic(x):
    return ((1 - np.cos(PI * x)) / 2, PI / 2 * np.sin(PI * x), PI**2 / 2 * np.cos(PI * x),
            -PI**3 / 2 * np.sin(PI * x))


def cycloidal(x):
    w = 2 * PI
    return x - np.sin(w * x) / w, 1 - np.cos(w * x), w * np.sin(w * x), w * w * np.cos(w * x)


def poly345(x):
    return (10 * x**3 - 15 * x**4 + 6 * x**5, 30 * x**2 - 60 * x**3 + 30 * x**4,
            60 * x - 180 * x**2 + 120 * x**3, 60 - 360 * x + 360 * x**2)


def poly4567(x):
    return (35 * x**4 - 84 * x**5 + 70 * x**6 - 20 * x**7,
            140 * x**3 - 420 * x**4 + 420 * x**5 - 140 * x**6,
            420 * x**2 - 1680 * x**3 + 2100 * x**4 - 840 * x**5,
            840 * x - 5040 * x**2 + 8400 * x**3 - 4200 * x**4)


def parabolic(x):
    first = x < 0.5
    return (np.where(first, 2 * x * x, 1 - 2 * (1 - x) ** 2), np.where(first, 4 * x, 4 * (1 - x)),
            np.where(first, 4.0, -4.0), np.zeros_like(x))


_S18 = 1 / (32 * PI) - 1 / (16 * PI**2)  # S(1/8)/C of both modified laws


def modified_sine(x):
    C, w = 4 * PI**2 / (PI + 4), 4 * PI
    s78 = _S18 + 3 / (16 * PI) + 9 / (8 * PI**2)
    t2, t3 = x - 1 / 8, x - 7 / 8
    p1, p3 = x <= 1 / 8, x >= 7 / 8
    S = np.where(p1, x / w - np.sin(w * x) / w**2,
                 np.where(p3, s78 + t3 / w + (np.cos(w * t3) - 1) / w**2,
                          _S18 + t2 / w - 9 / w**2 * (np.cos(w * t2 / 3) - 1)))
    S1 = np.where(p1, (1 - np.cos(w * x)) / w,
                  np.where(p3, (1 - np.sin(w * t3)) / w, (1 + 3 * np.sin(w * t2 / 3)) / w))
    S2 = np.where(p1, np.sin(w * x), np.where(p3, -np.cos(w * t3), np.cos(w * t2 / 3)))
    S3 = np.where(p1, w * np.cos(w * x), np.where(p3, w * np.sin(w * t3), -w / 3 * np.sin(w * t2 / 3)))
    return C * S, C * S1, C * S2, C * S3


def _trapezoid_half(x):
    w = 4 * PI
    s38 = _S18 + 1 / (16 * PI) + 1 / 32
    t2, t3 = x - 1 / 8, x - 3 / 8
    p1, p3 = x <= 1 / 8, x >= 3 / 8
    S = np.where(p1, x / w - np.sin(w * x) / w**2,
                 np.where(p3, s38 + (1 / w + 1 / 4) * t3 + (1 - np.cos(w * t3)) / w**2,
                          _S18 + t2 / w + t2 * t2 / 2))
    S1 = np.where(p1, (1 - np.cos(w * x)) / w, np.where(p3, 1 / w + 1 / 4 + np.sin(w * t3) / w, 1 / w + t2))
    S2 = np.where(p1, np.sin(w * x), np.where(p3, np.cos(w * t3), 1.0))
    S3 = np.where(p1, w * np.cos(w * x), np.where(p3, -w * np.sin(w * t3), 0.0))
    return S, S1, S2, S3


def modified_trapezoid(x):
    C = 8 * PI / (2 + PI)
    first = x <= 0.5
    a = _trapezoid_half(np.where(first, x, 0.0))
    b = _trapezoid_half(np.where(first, 0.0, 1 - x))
    return (C * np.where(first, a[0], 1 / C - b[0]), C * np.where(first, a[1], b[1]),
            C * np.where(first, a[2], -b[2]), C * np.where(first, a[3], b[3]))


BY_HAND = {"uniform": uniform, "harmonic": harmonic, "cycloidal": cycloidal, "3-4-5": poly345,
           "4-5-6-7": poly4567, "parabolic": parabolic, "modified-sine": modified_sine,
           "modified-trapezoid": modified_trapezoid}


def program_by_hand(segments, phi):
    """s, s′, s″, s‴ (per radian) of a list of (kind, extent in degrees, lift, law) segments
    that starts at lift 0, at cam angles φ (radians, inside one turn)."""
    out = [np.zeros_like(phi) for _ in range(4)]
    start, level = 0.0, 0.0
    for kind, extent, lift, law in segments:
        a, b = np.radians(start), np.radians(start + extent)
        m = (phi >= a) & (phi < b)
        beta = b - a
        if kind == "dwell":
            out[0][m] = level
        else:
            sign = 1.0 if kind == "rise" else -1.0
            S = BY_HAND[law]((phi[m] - a) / beta)
            out[0][m] = level + sign * lift * S[0]
            for k in (1, 2, 3):
                out[k][m] = sign * lift * S[k] / beta**k
            level += sign * lift
        start += extent
    return out
