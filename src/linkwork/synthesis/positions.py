"""Finite positions of a moving plane (*endlich benachbarte Lagen*, Pöschl ch. IX): the poles of
finite displacements, the pole triangle, image poles and the correspondence between circle
points (*Kreispunkte*) and centre points (*Mittelpunkte*) for two and three positions.

A position k of the moving plane Σ puts the point of Σ with coordinates z (complex, in Σ's own
frame) at Z = e^{iθ_k}·z + d_k in the fixed plane. The displacement from position i to position
j carries a fixed-plane point Z of Σ in position i to e^{iφ}(Z − d_i) + d_j with φ = θ_j − θ_i,
a rotation through φ about the pole P_ij (*Drehpol*, *Pol der endlichen Verschiebung*):

    P_ij = (d_j − e^{iφ} d_i) / (1 − e^{iφ}) = i (e^{−iφ/2} d_j − e^{iφ/2} d_i) / (2 sin(φ/2)),

written homogeneously as (i(e^{−iφ/2}d_j − e^{iφ/2}d_i), 2 sin(φ/2)): a pure translation
(φ = 0) has its pole at infinity, normal to the translation, with no division by a small number.

Pöschl writes the rotation as 2φ_ij; the half angles are the angles of the pole triangle
P₁₂P₁₃P₂₃ (Hamilton's composition of finite rotations, §57), and the homologous points D₁, D₂,
D₃ of one point of Σ are the mirror images of one image point 𝔇 in its three sides.

Circle point ↔ centre point: a point of Σ whose homologous positions lie on one circle is a
circle point, the circle's centre the centre point; a crank from that centre to that point
guides Σ through the positions. Since every displacement is an isometry,
|D_ik(Z) − M| = |Z − D_ik⁻¹(M)|: the circle points of a centre point M are the centre points
of M carried back by the inverted displacements, so one routine serves both directions.

Positions are numbered from 0 in the functions (P_ij is `pole(i, j)` with 0-based i, j) and
from 1 in reports, as in the literature.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..geometry import Circle, Line, Point, perpendicular_bisector, reflect

__all__ = ["Positions", "SynthesisError", "centre_points", "circle_points", "image_pole",
           "image_point", "pole_triangle"]


class SynthesisError(InputError):
    """A synthesis task without a solution (no real Burmester pair, a centre point off its
    curve) or with inconsistent data (positions that coincide, links of zero length)."""


def _c(xy) -> np.ndarray:
    a = np.asarray(xy, dtype=float)
    return a[..., 0] + 1j * a[..., 1]


def _xy(z) -> np.ndarray:
    z = np.asarray(z)
    return np.stack([z.real, z.imag], axis=-1)


def wrap(angle):
    """An angle reduced to (−π, π]."""
    return -np.remainder(-np.asarray(angle, dtype=float) + np.pi, 2 * np.pi) + np.pi


@dataclass(frozen=True, eq=False)
class Positions:
    """n prescribed positions of a moving plane: the angle θ_k of its frame and the place d_k
    of its origin in each (the pose (x, y, θ) of a coupler, say). Build with `from_poses` or
    `from_points`."""

    angle: np.ndarray  # (n,) radians
    origin: np.ndarray  # (n, 2)

    def __post_init__(self) -> None:
        th = np.array(self.angle, dtype=float).reshape(-1)
        d = np.array(self.origin, dtype=float).reshape(-1, 2)
        if th.shape[0] != d.shape[0]:
            raise InputError(f"{th.shape[0]} angles but {d.shape[0]} origins")
        if th.shape[0] < 2:
            raise InputError(f"give at least two positions, got {th.shape[0]}")
        if not (np.isfinite(th).all() and np.isfinite(d).all()):
            raise InputError("the positions must have finite coordinates and angles")
        scale = max(float(np.ptp(d, axis=0).max()), 1.0)
        for i in range(len(th)):
            for j in range(i):
                same = abs(wrap(th[i] - th[j])) <= 1e-12 and np.hypot(*(d[i] - d[j])) <= 1e-12 * scale
                if same:
                    raise SynthesisError(f"positions {j + 1} and {i + 1} coincide: their pole is undefined")
        for a in (th, d):
            a.flags.writeable = False
        object.__setattr__(self, "angle", th)
        object.__setattr__(self, "origin", d)

    # -------------------------------------------------------------------- construction
    @classmethod
    def from_poses(cls, poses) -> Positions:
        """From an (n, 3) array of poses (x, y, θ), θ in radians."""
        p = np.asarray(poses, dtype=float)
        if p.ndim != 2 or p.shape[1] != 3:
            raise InputError(f"poses: give an (n, 3) array of x, y, θ, got shape {p.shape}")
        return cls(p[:, 2], p[:, :2])

    @classmethod
    def from_points(cls, a, b) -> Positions:
        """From two points A_k, B_k of the plane in each position ((n, 2) each): the origin is
        at A, the frame's x-axis along AB. AB must keep its length (a rigid plane)."""
        A, B = (np.asarray(v, dtype=float) for v in (a, b))
        if A.shape != B.shape or A.ndim != 2 or A.shape[1] != 2:
            raise InputError("from_points: give two (n, 2) arrays of the same shape")
        v = B - A
        length = np.hypot(v[:, 0], v[:, 1])
        if (length == 0).any():
            raise SynthesisError("from_points: A and B coincide in a position")
        if np.ptp(length) > 1e-9 * length.max():
            raise SynthesisError(f"from_points: the length AB varies from {length.min():.9g} to "
                                 f"{length.max():.9g}: the points do not belong to one rigid plane")
        return cls(np.arctan2(v[:, 1], v[:, 0]), A)

    def __len__(self) -> int:
        return self.angle.shape[0]

    @property
    def poses(self) -> np.ndarray:
        """(n, 3): x, y, θ."""
        return np.column_stack([self.origin, self.angle])

    @property
    def size(self) -> float:
        """A length for tolerances: the spread of the origins (at least 1e-300)."""
        return max(float(np.ptp(self.origin, axis=0).max()), 1e-300)

    def subset(self, indices) -> Positions:
        idx = list(indices)
        return Positions(self.angle[idx], self.origin[idx])

    # -------------------------------------------------------------------- displacements
    def rotation(self, i: int, j: int) -> float:
        """The rotation angle θ_ij = θ_j − θ_i from position i to j, in (−π, π] (twice
        Pöschl's φ_ij)."""
        return float(wrap(self.angle[j] - self.angle[i]))

    def carry(self, xy, i: int, j: int) -> np.ndarray:
        """The fixed-plane points xy (..., 2) of Σ in position i, where they are in position j
        (their homologous points)."""
        phi = self.angle[j] - self.angle[i]
        z = np.exp(1j * phi) * (_c(xy) - _c(self.origin[i])) + _c(self.origin[j])
        return _xy(z)

    def homologous(self, xy, i: int = 0) -> np.ndarray:
        """(n, ..., 2): the point(s) xy of Σ in position i, in every position."""
        return np.stack([self.carry(xy, i, k) for k in range(len(self))])

    def pole(self, i: int, j: int) -> Point:
        """The pole P_ij of the displacement i → j (a point at infinity for a translation)."""
        phi = self.angle[j] - self.angle[i]
        di, dj = _c(self.origin[i]), _c(self.origin[j])
        h = np.exp(0.5j * phi)
        m = 1j * (dj / h - h * di)
        w = 2 * np.sin(phi / 2)
        if w == 0 and m == 0:
            raise SynthesisError(f"positions {i + 1} and {j + 1} coincide: their pole is undefined")
        return Point(np.array([m.real, m.imag, w]))

    def poles(self) -> dict[tuple[int, int], Point]:
        """Every pole P_ij, i < j."""
        n = len(self)
        return {(i, j): self.pole(i, j) for i in range(n) for j in range(i + 1, n)}


def pole_triangle(pos: Positions, i: int = 0, j: int = 1, k: int = 2):
    """The pole triangle (*Poldreieck*) of positions i, j, k: the poles (P_ij, P_ik, P_jk) and
    the half rotation angles (φ_ij, φ_ik, φ_jk) Pöschl writes the rotations as (2φ)."""
    poles = (pos.pole(i, j), pos.pole(i, k), pos.pole(j, k))
    halves = tuple(pos.rotation(a, b) / 2 for a, b in ((i, j), (i, k), (j, k)))
    return poles, halves


def image_pole(pos: Positions, j: int, k: int, ref: int = 0) -> Point:
    """The image pole P′_jk of P_jk in position `ref`: the point of Σ that is at P_jk in position
    j (and so in position k), drawn where it is in position `ref`. For three positions it is the
    mirror image of P_jk in the side P_ref,j P_ref,k of the pole triangle."""
    P = pos.pole(j, k)
    if P.is_infinite:
        raise SynthesisError(f"the pole P{j + 1}{k + 1} is at infinity (a translation): its image is too")
    return Point.from_xy(pos.carry(P.xy, j, ref))


def image_point(pos: Positions, circle_point, ref: int = 0) -> Point:
    """Pöschl's image point 𝔇 (§57) of a point D of Σ given in position `ref` of three
    positions: its mirror image in the side through P_ref of the pole triangle; the homologous
    points are the mirror images of 𝔇 in the three sides."""
    if len(pos) != 3:
        raise InputError("the image point belongs to three positions")
    a, b = [k for k in range(3) if k != ref]
    side = Line.through(pos.pole(min(ref, a), max(ref, a)), pos.pole(min(ref, b), max(ref, b)))
    return reflect(Point.from_xy(circle_point), side)


def _centre(points: np.ndarray) -> Point | Line:
    """The point equidistant from two (→ their perpendicular bisector, a Line) or three
    (→ the circumcentre; at infinity if they are collinear) points (k, 2)."""
    if points.shape[0] == 2:
        return perpendicular_bisector(Point.from_xy(points[0]), Point.from_xy(points[1]))
    circle = Circle.through(*(Point.from_xy(p) for p in points[:3]))
    return circle.centre


def centre_points(pos: Positions, circle_point, ref: int = 0) -> Point | Line:
    """The centre point(s) of the circle point given in position `ref`: two positions, the
    perpendicular bisector of D₁D₂ (a line through P₁₂); three, the centre of the circle through
    D₁, D₂, D₃ (a point, at infinity when they are collinear: a slider). For four or more
    positions the point must be a circle point of all of them (on the circle-point curve)."""
    D = pos.homologous(np.asarray(circle_point, dtype=float), ref)
    return _checked(pos, D, "circle point", "centre")


def circle_points(pos: Positions, centre, ref: int = 0) -> Point | Line:
    """The circle point(s), in position `ref`, of the centre point `centre`: the centre points
    of the centre carried back by the inverted displacements (see the module's docstring)."""
    M = np.asarray(centre, dtype=float)
    back = np.stack([pos.carry(M, k, ref) for k in range(len(pos))])
    return _checked(pos, back, "centre point", "circle")


def _checked(pos: Positions, pts: np.ndarray, given: str, wanted: str) -> Point | Line:
    if len(pos) <= 3:
        return _centre(pts)
    c = _centre(pts[:3])
    if c.is_infinite:
        line = Line.through(Point.from_xy(pts[0]), Point.from_xy(pts[1]))
        off = np.abs([line.signed_distance(Point.from_xy(p)) for p in pts[3:]])
    else:
        r = np.hypot(*(pts - c.xy).T)
        off = np.abs(r[3:] - r[0])
    if off.max() > 1e-9 * max(pos.size, float(np.abs(pts).max())):
        raise SynthesisError(f"the {given} is not a {given} of all {len(pos)} positions (its homologous "
                             f"points stray {off.max():.3g} from one {wanted}): choose it on the "
                             f"{given.split()[0]}-point curve")
    return c
