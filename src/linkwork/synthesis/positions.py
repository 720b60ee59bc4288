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
from ..geometry import Line, Point, reflect

__all__ = ["Positions", "SynthesisError", "centre_points", "circle_points", "dyad_forms", "image_pole",
           "image_point", "mate", "normalised", "pole_triangle", "wrap"]


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
    """An angle reduced to (−π, π] (NaN stays NaN: an unreachable sample)."""
    with np.errstate(invalid="ignore"):
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


def dyad_forms(pos: Positions, ref: int = 0) -> np.ndarray:
    """(n − 1, 3, 3): for every position k ≠ ref the bilinear form B_k with

        Ẑᵀ B_k M̂ = (|Z_k − M|² − |Z − M|²) / 2,

    Ẑ = (x, y, 1) the point of Σ drawn in position `ref`, Z_k its homologous point in position
    k, M̂ = (m_x, m_y, 1) a fixed point. Neither |Z|² nor |M|² survives the difference, so the
    condition "Z stays on a circle about M" is bilinear: for a chosen centre point the rows
    B_k M̂ are lines that the circle point lies on (two positions: the line itself; three: their
    meet), and for a chosen circle point the rows Ẑᵀ B_k are lines through the centre point.
    Homogeneous M̂ = (u_x, u_y, 0) is a centre at infinity (the circle a straight line normal to
    u: a slider). With Z_k = c Z + e (c = e^{iθ_ref,k}):
    (|Z_k − M|² − |Z − M|²)/2 = Re(Z c ē) − Re(Z (c − 1) M̄) − Re(e M̄) + |e|²/2."""
    out = []
    d_ref = _c(pos.origin[ref])
    for k in range(len(pos)):
        if k == ref:
            continue
        c = np.exp(1j * (pos.angle[k] - pos.angle[ref]))
        e = _c(pos.origin[k]) - c * d_ref
        g, h = c * np.conj(e), c - 1
        out.append([[-h.real, -h.imag, g.real],
                    [h.imag, -h.real, -g.imag],
                    [-e.real, -e.imag, abs(e) ** 2 / 2]])
    return np.array(out)


def normalised(pos: Positions) -> tuple[Positions, np.ndarray, float]:
    """The positions moved and scaled so that their origins spread over about a unit square
    about 0 (the forms' entries are then of one size), with the centre and scale used."""
    c = pos.origin.mean(axis=0)
    s = pos.size
    return Positions(pos.angle, (pos.origin - c) / s), c, s


def _homogeneous(p, centre: np.ndarray, scale: float) -> np.ndarray:
    """A point (Point, or x, y) in the normalised frame, homogeneous with unit norm."""
    P = p if isinstance(p, Point) else Point.from_xy(np.asarray(p, dtype=float))
    if P.shape != ():
        raise InputError("give one point")
    v = P.coords.copy()
    if v[2] == 1:
        v[:2] = (v[:2] - centre) / scale
    return v / np.linalg.norm(v)


def _from_homogeneous(v: np.ndarray, centre: np.ndarray, scale: float) -> Point:
    v = np.asarray(v, dtype=float)
    if v[2] != 0 and np.isfinite(v[:2] / v[2]).all() and abs(v[2]) > 1e-13 * np.abs(v[:2]).max(initial=0):
        return Point.from_xy(v[:2] / v[2] * scale + centre)
    return Point.at_infinity(v[:2])


def mate(pos: Positions, given, of: str, ref: int = 0) -> Point | Line:
    """The circle point of a centre point (`of="centre"`), or the centre point of a circle point
    (`of="circle"`, the point drawn in position `ref`), as a homogeneous Point (at infinity for
    a slider) — for two positions the Line of all of them. Four or more positions: the point
    must lie on its curve, else `SynthesisError`."""
    unit, c, s = normalised(pos)
    B = dyad_forms(unit, ref)
    v = _homogeneous(given, c, s)
    rows = B @ v if of == "centre" else np.einsum("i,kij->kj", v, B)
    if len(pos) == 2:
        r = rows[0]
        if np.hypot(r[0], r[1]) <= 1e-14 * abs(r[2]):
            raise SynthesisError(f"the {of} point is the pole P12: every point is its mate")
        return _line_back(r, c, s)
    rows = rows / np.linalg.norm(rows, axis=1, keepdims=True).clip(1e-300)
    _, sv, vt = np.linalg.svd(rows)
    if len(pos) > 3 and sv[-1] > 1e-9 * sv[0]:
        curve = "centre" if of == "centre" else "circle"
        raise SynthesisError(f"the {of} point is not a {of} point of all {len(pos)} positions (off "
                             f"the {curve}-point curve by {sv[-1] / sv[0]:.3g}, relative)")
    if len(pos) == 3 and sv[1] <= 1e-12 * sv[0]:
        raise SynthesisError(f"the {of} point lies on a pole line: its mate is not unique")
    return _from_homogeneous(vt[-1], c, s)


def _line_back(r: np.ndarray, c: np.ndarray, s: float) -> Line:
    """The line r·(x̂, ŷ, 1) = 0 of the normalised frame in the user's coordinates
    (x̂ = (x − c)/s)."""
    return Line(np.array([r[0] / s, r[1] / s, r[2] - (r[0] * c[0] + r[1] * c[1]) / s]))


def centre_points(pos: Positions, circle_point, ref: int = 0) -> Point | Line:
    """The centre point of the circle point given in position `ref`: two positions, the
    perpendicular bisector of D₁D₂ (a line through P₁₂); three, the centre of the circle through
    D₁, D₂, D₃ (at infinity when they are collinear: a slider); four or more, the point must be
    a circle point of all of them (on the circle-point curve)."""
    return mate(pos, circle_point, "circle", ref)


def circle_points(pos: Positions, centre, ref: int = 0) -> Point | Line:
    """The circle point(s), drawn in position `ref`, of the centre point `centre` (the mirror
    task: see `mate`)."""
    return mate(pos, centre, "centre", ref)
