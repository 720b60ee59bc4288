"""A four-bar written out in closed form (circle intersection), to generate prescribed positions
of its coupler independently of linkwork, and a displacement by rotation matrices."""

from __future__ import annotations

import numpy as np

from linkwork.synthesis.positions import Positions

O2, O4 = np.array([0.0, 0.0]), np.array([4.0, 0.0])
A_LEN, B_LEN, C_LEN = 1.5, 3.5, 3.0


def four_bar(theta, O2=O2, O4=O4, a=A_LEN, b=B_LEN, c=C_LEN):
    """Crank pin A and rocker pin B of the four-bar O2 A B O4 at crank angles theta (one
    assembly: B left of A → O4)."""
    A = O2 + a * np.column_stack([np.cos(theta), np.sin(theta)])
    v = O4 - A
    d = np.hypot(v[:, 0], v[:, 1])
    u = v / d[:, None]
    x = (b * b - c * c + d * d) / (2 * d)
    h = np.sqrt(b * b - x * x)
    B = A + x[:, None] * u + h[:, None] * np.column_stack([-u[:, 1], u[:, 0]])
    return A, B


def generated(degrees):
    A, B = four_bar(np.radians(degrees))
    return Positions.from_points(A, B), A, B


def move(pose_i, pose_j, X):
    def R(t):
        return np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])
    return R(pose_j[2]) @ (R(pose_i[2]).T @ (np.asarray(X) - pose_i[:2])) + pose_j[:2]
