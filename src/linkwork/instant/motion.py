"""Relative motion of one link with respect to another: the base of everything in `instant`.

Owns `RelativeMotion` (the pose of link i in the own coordinates of link j, with its exact time
derivatives, taken from the core engine's solution, never by differencing) and the small
homogeneous-coordinate helpers the other modules share (mapping points, vectors and
generalised circles from link j's coordinates to the drawing at each sample). The vector
helpers `perp` (J, the quarter turn), `cross`, `dot`, `norm` are the geometry layer's.

Link j's coordinates coincide with the frame's in the design position (see
`linkwork.model.mechanism`), so for `relative_to = frame` the relative motion *is* the absolute
motion. Rosenauer §62, §71: the relative motion of plane i with respect to plane j is again a
plane motion, with ω_ij = ω_i − ω_j and τ_ij = τ_i − τ_j; all of curvature theory applies to it.

Derivatives are computed with complex numbers: a pose (x, y, θ) places design point s at
z = (x + iy) + e^{iθ}s, and the n-th derivative of e^{iθ} follows from E' = iθ'E by Leibniz's
rule, to any order the solution carries.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import comb

import numpy as np

from ..errors import InputError, ModelError
from ..geometry import Circle, Point, Vector
from ..geometry._base import cross2 as cross, dot, norm, rot90 as perp  # noqa: F401 (shared here)
from ..kinematics import Solution

#: default relative tolerance for deciding that an instantaneous quantity is at infinity
#: (a pole farther than length_scale / TOL is a translation pole, exactly at infinity)
TOL = 1e-9


def rotate(theta: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Vectors v (..., 2) turned by the angles theta (...)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def _c(xy: np.ndarray) -> np.ndarray:
    return xy[..., 0] + 1j * xy[..., 1]


def _xy(z: np.ndarray) -> np.ndarray:
    return np.stack([z.real, z.imag], axis=-1)


def exp_derivatives(theta: np.ndarray, sign: float = 1.0) -> np.ndarray:
    """Derivatives (K+1, N) of e^{i·sign·θ(t)} from θ's derivatives (K+1, N)."""
    K = theta.shape[0] - 1
    E = np.empty(theta.shape, dtype=complex)
    E[0] = np.exp(1j * sign * theta[0])
    for n in range(1, K + 1):
        E[n] = 1j * sign * sum(comb(n - 1, k) * theta[k + 1] * E[n - 1 - k] for k in range(n))
    return E


def leibniz(f: np.ndarray, g: np.ndarray) -> np.ndarray:
    """Derivatives of the product f·g from the derivatives of f and g (first axis)."""
    K = f.shape[0] - 1
    return np.stack([sum(comb(n, k) * f[k] * g[n - k] for k in range(n + 1)) for n in range(K + 1)])


@dataclass(frozen=True)
class RelativeMotion:
    """The motion of `link` relative to `relative_to`, at N samples.

    `derivatives[k, n]` is the k-th time derivative of (x, y, θ): the pose of `link` expressed in
    the own (design) coordinates of `relative_to`. `base[n]` is the pose of `relative_to` in
    the frame, used to draw relative quantities on the mechanism at each sample. `reference`
    are design coordinates of a point of `link` near its points (well-conditioned origin for
    the formulas); `scale` is the mechanism's characteristic length.
    """

    link: str
    relative_to: str
    derivatives: np.ndarray
    base: np.ndarray
    reference: np.ndarray
    scale: float

    @property
    def order(self) -> int:
        return self.derivatives.shape[0] - 1

    def __len__(self) -> int:
        return self.derivatives.shape[1]

    def require(self, order: int, what: str) -> None:
        if self.order < order:
            need = {1: "velocities", 2: "accelerations", 3: "jerks", 4: "fourth derivatives"}[order]
            raise InputError(f"{what} needs {need}: solve the mechanism with order={order} "
                             f"(this solution has order {self.order})")

    @property
    def omega(self) -> np.ndarray:
        """Relative angular velocity ω_ij (N,)."""
        return self.derivatives[1, :, 2]

    def angle_derivatives(self) -> np.ndarray:
        return self.derivatives[:, :, 2]

    def point(self, s) -> np.ndarray:
        """Derivatives (K+1, N, 2) of the material point with design coordinates `s` ((2,) or
        (N, 2)) of `link`, in the coordinates of `relative_to`."""
        s = _c(np.asarray(s, dtype=float))
        E = exp_derivatives(self.angle_derivatives())
        z = _c(self.derivatives[..., :2]) + E * s
        return _xy(z)

    # ------------------------------------------------------------------ to the drawing
    def to_world(self, xy: np.ndarray) -> np.ndarray:
        """Frame coordinates (N, 2) of points given in `relative_to`'s coordinates."""
        return _xy(_c(self.base[:, :2]) + np.exp(1j * self.base[:, 2]) * _c(xy))

    def to_local(self, xy: np.ndarray) -> np.ndarray:
        """`relative_to`'s coordinates (N, 2) of frame points xy (the inverse of `to_world`)."""
        return _xy(np.exp(-1j * self.base[:, 2]) * (_c(np.asarray(xy, dtype=float)) - _c(self.base[:, :2])))

    def rotate_to_world(self, v: np.ndarray) -> np.ndarray:
        """Frame components (N, 2) of vectors given in `relative_to`'s axes."""
        return _xy(np.exp(1j * self.base[:, 2]) * _c(v))

    def homogeneous_to_world(self, h: np.ndarray) -> np.ndarray:
        """Homogeneous (N, 3) points in `relative_to`'s coordinates to the frame's."""
        xy = self.rotate_to_world(h[:, :2]) + h[:, 2:3] * self.base[:, :2]
        return np.concatenate([xy, h[:, 2:3]], axis=1)

    def point_to_world(self, h: np.ndarray) -> Point:
        return make_point(self.homogeneous_to_world(h))

    def vector_to_world(self, v: np.ndarray) -> Vector:
        return Vector(self.rotate_to_world(v))

    def circle_to_world(self, centre: np.ndarray, radius: np.ndarray, line: np.ndarray,
                        normal: np.ndarray, through: np.ndarray) -> Circle:
        """Circles (N,) given in `relative_to`'s coordinates, as `Circle`s in the frame: proper
        circles (centre, radius) where ~line, straight lines (a normal vector and a point
        through which they pass, radius inf) where line; NaN items where undefined."""
        with np.errstate(divide="ignore", invalid="ignore"):
            ex = np.array([1.0, 0.0])
            anchor = np.where(line[:, None], self.to_world(through),
                              self.to_world(centre) - radius[:, None] * ex)
            nw = self.rotate_to_world(normal / norm(normal)[:, None])
            nrm = np.where(line[:, None], nw, ex)
            rad = np.where(line, np.inf, radius)
        bad = ~np.isfinite(anchor).all(axis=1) | ~np.isfinite(nrm).all(axis=1) | np.isnan(rad)
        anchor[bad], nrm[bad], rad[bad] = np.nan, np.nan, np.nan
        return Circle(Point.from_xy(anchor), Vector(nrm), rad)


def make_point(h: np.ndarray) -> Point:
    """A `Point` from homogeneous rows; rows (0, 0, 0) or with NaN become undefined (NaN)."""
    h = np.array(h, dtype=float)
    bad = ~np.isfinite(h).all(axis=-1) | (h == 0).all(axis=-1)
    h[bad] = np.nan
    return Point(h)


def link_reference(solution: Solution, link: str) -> np.ndarray:
    """Design coordinates of the centroid of `link`'s points (of the mechanism if it has none)."""
    mech = solution.mechanism
    names = mech.link(link).points or tuple(mech.points)
    return np.mean([mech.points[p] for p in names], axis=0)


def relative_motion(solution: Solution, link: str, relative_to: str | None = None) -> RelativeMotion:
    """The motion of `link` relative to `relative_to` (the frame by default) at every sample.

    Both links' pose derivatives come from the core engine; the relative pose is
    z_rel = e^{−iθ_j}(z_i − z_j), θ_rel = θ_i − θ_j, differentiated exactly by Leibniz's rule.
    """
    mech = solution.mechanism
    j = mech.frame if relative_to is None else relative_to
    for name in (link, j):
        if name not in mech.link_index:
            raise ModelError(f"mechanism '{mech.name}' has no link '{name}' "
                             f"(links: {', '.join(mech.link_names)})")
    if link == j:
        raise InputError(f"the motion of link '{link}' relative to itself is rest; "
                         "choose two different links")
    Di, Dj = solution.pose_derivatives(link), solution.pose_derivatives(j)
    E = exp_derivatives(Dj[..., 2], sign=-1.0)
    z = leibniz(E, _c(Di[..., :2]) - _c(Dj[..., :2]))
    rel = np.concatenate([_xy(z), (Di[..., 2] - Dj[..., 2])[..., None]], axis=-1)
    return RelativeMotion(link, j, rel, np.array(Dj[0]), link_reference(solution, link),
                          mech.length_scale)
