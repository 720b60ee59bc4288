"""Disc cams designed from a motion program (*Kurvenscheibe* from its *Bewegungsplan*): the
pitch curve and the profile as profiles of `geometry.profiles`, with derivatives of every order.

The cam turns counter-clockwise about its centre O by the cam angle φ (the driver's angle); the
follower's lift s(φ) is the `MotionProgram`. By kinematic inversion (the cam held, the frame
turned back by −φ) every curve is written in the cam's own coordinates, which at φ = 0 are the
drawing's, as complex numbers about O:

- roller or knife edge at C(φ) in the frame: the pitch curve (*Mittelpunktsbahn* of the roller)
  is c(φ) = e^{−iφ}·C(φ); a knife edge's profile is the pitch curve, a roller's the pitch curve
  offset towards the cam by its radius (`OffsetProfile`).
  Translating follower (line of motion along e = e^{iγ}, `offset` ε to the right of it):
  C = ε·(−ie) + (s₀ + s)·e, s₀ = √(R₀² − ε²), R₀ = base radius (+ roller radius).
  Oscillating follower (pivot A, arm ℓ): C = A + ℓ·e^{iψ}, ψ = ψ₀ + σ·s; at s = 0 the roller
  lies on the circle R₀ (ψ₀ from the triangle O–A–C), and σ makes the lift carry it away
  from O.
- flat face: the face is the line X·ν = p in the frame, with unit normal ν = e^{iθ₀} towards the
  follower; its envelope (*Hüllkurve*) in the cam's coordinates, with θ = the normal's angle
  there (θ = γ − φ translating, ψ − φ oscillating), is x = e^{iθ}(p + i·p′/θ′), whose radius
  of curvature is p + d²p/dθ². Translating: p = R_b + s (the face perpendicular to the line
  of motion). Oscillating: the face is a line of the lever at distance `face_offset` f from
  the pivot, p = A·ν − f, ν = e^{iψ}.

The parameter of every curve is φ itself: a roller's or knife's contact in the engine sits at
u = φ. Derivatives come from truncated Taylor series (`geometry.profiles.taylor`), exact to any
order; at the program's joins `side` picks the segment.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from math import factorial

import numpy as np

from ..geometry.profiles import OffsetProfile, ParametricProfile, Profile, taylor
from .motion_programs import TWO_PI, CamDesignError, MotionProgram

FOLLOWER_KINDS = ("roller", "knife", "flat")
MOTIONS = ("translating", "oscillating")


def _finite(value, what: str, key: str, positive: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise CamDesignError(f"{what} must be a number, got {value!r}", key=key) from None
    if not np.isfinite(v) or (positive and v <= 0):
        raise CamDesignError(f"{what} must be {'positive and ' if positive else ''}finite, got {value}", key=key)
    return v


@dataclass(frozen=True, eq=False)
class DiscCam:
    """A disc cam turning counter-clockwise about `center`, designed for `program`.

    follower: 'roller' (radius `roller_radius`), 'knife' or 'flat'; motion: 'translating'
    (line of motion at angle `direction` (radians), `offset` to the right of the cam centre as
    seen along it) or 'oscillating' (lever pivoted at `pivot`, roller or knife at `arm` from
    it, a flat face at `face_offset` from it; `side`: the follower lies 'left' or 'right' of
    the line from the cam centre to the pivot). The lifts of an oscillating follower's program
    are angles (radians). `base_radius` is the smallest radius of the profile (the base circle,
    *Grundkreis*)."""

    program: MotionProgram
    follower: str
    base_radius: float
    roller_radius: float = 0.0
    motion: str = "translating"
    offset: float = 0.0
    direction: float = np.pi / 2
    pivot: tuple[float, float] | None = None
    arm: float | None = None
    face_offset: float = 0.0
    side: str = "left"
    center: tuple[float, float] = (0.0, 0.0)
    _geometry: dict = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.program, MotionProgram):
            raise CamDesignError("a cam needs a MotionProgram")
        if self.follower not in FOLLOWER_KINDS:
            raise CamDesignError(f"follower must be one of {', '.join(FOLLOWER_KINDS)}, got '{self.follower}'",
                                 key="follower")
        if self.motion not in MOTIONS:
            raise CamDesignError(f"motion must be one of {', '.join(MOTIONS)}, got '{self.motion}'", key="motion")
        rb = _finite(self.base_radius, "the base radius", "base_radius", positive=True)
        rho = 0.0
        if self.follower == "roller":
            rho = _finite(self.roller_radius, "a roller's radius", "roller_radius", positive=True)
        center = np.asarray(self.center, dtype=float)
        if center.shape != (2,) or not np.all(np.isfinite(center)):
            raise CamDesignError(f"the cam centre must be a finite [x, y], got {self.center}", key="center")
        g = self._geometry
        g["R0"] = rb + rho  # radius of the prime circle (the pitch curve's smallest)
        joins = [j for j in self.program.joins() if j.jumps[0] != 0.0]
        if self.follower == "flat" and joins:
            raise CamDesignError(
                f"a flat face cannot follow a jump of velocity (at {np.degrees(joins[0].angle):.6g}° of cam "
                "angle): its contact would leap along the face; use a law that starts and ends at rest "
                "(not 'uniform') or a roller or knife follower", index=joins[0].segment)
        if self.motion == "translating":
            eps = _finite(self.offset, "the offset", "offset")
            gam = _finite(self.direction, "the direction", "direction")
            g["e"] = np.exp(1j * gam)
            if self.follower != "flat":
                if abs(eps) >= g["R0"]:
                    raise CamDesignError(
                        f"the offset {eps:g} must be smaller than the radius {g['R0']:g} of the "
                        f"{'prime' if rho else 'base'} circle, or the follower's line misses it", key="offset")
                g["s0"] = float(np.sqrt(g["R0"] ** 2 - eps**2))
        else:
            if self.pivot is None:
                raise CamDesignError("an oscillating follower needs `pivot`, the lever's fixed pivot", key="pivot")
            piv = np.asarray(self.pivot, dtype=float)
            if piv.shape != (2,) or not np.all(np.isfinite(piv)):
                raise CamDesignError(f"the pivot must be a finite [x, y], got {self.pivot}", key="pivot")
            if self.side not in ("left", "right"):
                raise CamDesignError(f"side must be 'left' or 'right', got '{self.side}'", key="side")
            A = complex(*(piv - center))
            d = abs(A)
            g["A"], sense = A, (1.0 if self.side == "left" else -1.0)
            if self.follower == "flat":
                f = _finite(self.face_offset, "the face offset", "face_offset")
                cos_d = (rb + f) / d if d > 0 else np.inf
                if not abs(cos_d) < 1:
                    raise CamDesignError(
                        f"the pivot lies {d:g} from the cam centre: a face {f:g} from it cannot touch the "
                        f"base circle of radius {rb:g} (move the pivot out, or change the face offset)", key="pivot")
            else:
                ell = _finite(self.arm, "the arm", "arm", positive=True)
                cos_d = (g["R0"] ** 2 - d * d - ell * ell) / (2 * d * ell) if d > 0 else np.inf
                if not abs(cos_d) < 1:
                    raise CamDesignError(
                        f"an arm of {ell:g} about the pivot at {d:g} from the cam centre cannot reach the "
                        f"{'prime' if rho else 'base'} circle of radius {g['R0']:g}", key="arm")
            delta = float(np.arccos(cos_d))
            g["psi0"] = float(np.angle(A)) + sense * delta
            # the lift carries the roller away from O (a flat face: moves its line away from O)
            g["sigma"] = -sense
            if self.follower == "flat" and self.program.peaks()[0] >= 1.0:
                raise CamDesignError(
                    "an oscillating flat face must turn slower than the cam (|dψ/dφ| < 1); this program "
                    f"reaches {self.program.peaks()[0]:.4g}", key="segments")

    # -- the follower ------------------------------------------------------------------------
    @property
    def prime_radius(self) -> float:
        """Radius of the prime circle: the base radius plus a roller's radius."""
        return self._geometry["R0"]

    @property
    def rocker_start(self) -> float:
        """ψ₀: the lever's angle (of the arm, or of the face's normal) at lift 0."""
        return self._geometry["psi0"]

    @property
    def rocker_sense(self) -> float:
        """σ: ψ = ψ₀ + σ·s."""
        return self._geometry["sigma"]

    @property
    def pivot_vector(self) -> complex:
        """The oscillating lever's pivot seen from the cam centre (complex)."""
        return self._geometry["A"]

    @property
    def line_vector(self) -> complex:
        """The translating follower's direction of lift e (complex, unit)."""
        return self._geometry["e"]

    def element_point(self, phi: np.ndarray, order: int = 1, side: int = 1) -> np.ndarray:
        """(order + 1, *phi.shape) complex: the roller centre or knife tip C(φ) in the frame,
        about the cam centre, and its derivatives with respect to the cam angle."""
        return taylor.to_derivatives(self._frame_point_series(self._lift_series(np.asarray(phi, dtype=float), order, side)))

    def face_line(self, phi: np.ndarray, order: int = 1, side: int = 1) -> tuple[np.ndarray, np.ndarray]:
        """(θ, p), each (order + 1, *phi.shape), with derivatives: a flat face's line X·e^{iθ} = p
        in the cam's coordinates (about the cam centre) at cam angle φ."""
        phi = np.asarray(phi, dtype=float)
        theta, p = self._face_series(phi, self._lift_series(phi, order, side))
        return taylor.to_derivatives(theta), taylor.to_derivatives(p)

    def follower_motion(self, phi: np.ndarray, order: int, side: int = 1) -> np.ndarray:
        """(order + 1, *phi.shape): the follower's displacement along its line of motion from
        its lowest position (translating) or its lever angle ψ (oscillating) and their
        derivatives with respect to the cam angle."""
        s = self.program.derivatives(phi, order, side)
        if self.motion == "translating":
            return s
        out = self.rocker_sense * s
        out[0] += self.rocker_start
        return out

    def _lift_series(self, phi: np.ndarray, order: int, side: int) -> np.ndarray:
        return taylor.from_derivatives(self.program.derivatives(phi, order, side))

    def _rocker_series(self, s: np.ndarray) -> np.ndarray:
        psi = self.rocker_sense * s
        psi[0] = psi[0] + self.rocker_start
        return psi

    def _frame_point_series(self, s: np.ndarray) -> np.ndarray:
        """Series of C(φ) (complex, about the cam centre): the roller centre or knife tip."""
        g = self._geometry
        if self.motion == "translating":
            e = g["e"]
            C = s.astype(complex) * e
            C[0] = C[0] + self.offset * (-1j * e) + g["s0"] * e
            return C
        return _shift(self.arm * taylor.expi(self._rocker_series(s)), g["A"])

    @staticmethod
    def _turn_back(phi: np.ndarray, n: int) -> np.ndarray:
        """Series of e^{−iφ} to n coefficients."""
        base = np.exp(-1j * phi)
        return np.stack([(-1j) ** k / factorial(k) * base for k in range(n)])

    def _pitch(self, u: np.ndarray, order: int, side: int = 1) -> np.ndarray:
        s = self._lift_series(u, order, side)
        c = taylor.mul(self._turn_back(u, order + 1), self._frame_point_series(s))
        return self._out(c)

    def _flat(self, u: np.ndarray, order: int, side: int = 1) -> np.ndarray:
        s = self._lift_series(u, order + 1, side)
        theta, p = self._face_series(u, s)
        dtheta = _deriv(theta)
        dp = _deriv(p)
        q = taylor.mul(dp, taylor.power(dtheta, -1.0))
        x = taylor.mul(taylor.expi(theta[: order + 1]), p[: order + 1] + 1j * q)
        return self._out(x)

    def _face_series(self, u: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Series of θ (the face normal's angle in the cam's coordinates) and of p (the face's
        distance from the cam centre)."""
        if self.motion == "translating":
            theta = np.zeros_like(s)
            theta[0] = self.direction - u
            if s.shape[0] > 1:
                theta[1] = -1.0
            p = s.copy()
            p[0] = p[0] + self.base_radius
            return theta, p
        psi = self._rocker_series(s)
        theta = psi.copy()
        theta[0] = theta[0] - u
        if s.shape[0] > 1:
            theta[1] = theta[1] - 1.0
        e = taylor.expi(psi)
        A = self._geometry["A"]
        p = (np.conj(A) * e).real
        p[0] = p[0] - self.face_offset
        return theta, p

    def _out(self, z: np.ndarray) -> np.ndarray:
        d = taylor.to_derivatives(z)
        out = np.stack([d.real, d.imag], axis=-1)
        out[0, ..., 0] += self.center[0]
        out[0, ..., 1] += self.center[1]
        return out

    # -- profiles --------------------------------------------------------------------------
    @cached_property
    def pitch_curve(self) -> Profile:
        """The pitch curve (the path of the roller centre or knife tip in the cam's
        coordinates), parameter φ; for a flat face, the profile itself."""
        if self.follower == "flat":
            return self.profile
        return ParametricProfile(self._pitch, (0.0, TWO_PI), closed=True, breaks=self.program.breaks,
                                 sided=True, pieces=128)

    @cached_property
    def profile(self) -> Profile:
        """The cam's working profile, parameter φ (the cam angle at which it touches)."""
        if self.follower == "flat":
            return ParametricProfile(self._flat, (0.0, TWO_PI), closed=True, breaks=self.program.breaks,
                                     sided=True, pieces=128)
        if self.follower == "knife":
            return self.pitch_curve
        # the pitch curve runs clockwise (the frame turns back by −φ): the cam is on its right
        return OffsetProfile(self.pitch_curve, self.roller_radius)

    # -- the drawing at φ = 0 -------------------------------------------------------------------
    def follower_point(self) -> np.ndarray:
        """The roller centre or knife tip at φ = 0; for a flat face, the foot of the
        perpendicular from the cam centre on the face."""
        if self.follower == "flat":
            nu, p = self.face_normal(), self.face_distance(0.0)
            return np.asarray(self.center) + p * nu
        C = self._frame_point_series(self._lift_series(np.array(0.0), 0, 1))[0]
        return np.asarray(self.center) + np.array([C.real, C.imag])

    def face_normal(self, phi: float = 0.0) -> np.ndarray:
        """The flat face's unit normal in the frame (towards the follower) at cam angle φ."""
        if self.motion == "translating":
            a = self.direction
        else:
            a = float(self.follower_motion(np.array(phi), 0)[0])
        return np.array([np.cos(a), np.sin(a)])

    def face_distance(self, phi: float = 0.0) -> float:
        s = self._lift_series(np.array(phi), 0, 1)
        return float(self._face_series(np.array(phi), s)[1][0])

    def line_of_motion(self) -> np.ndarray:
        """The translating follower's unit direction of lift."""
        return np.array([np.cos(self.direction), np.sin(self.direction)])


def _deriv(a: np.ndarray) -> np.ndarray:
    """Series of f′ from the series of f (one coefficient shorter)."""
    k = np.arange(1, a.shape[0]).reshape((-1,) + (1,) * (a.ndim - 1))
    return a[1:] * k


def _shift(a: np.ndarray, c: complex) -> np.ndarray:
    a = a.copy()
    a[0] = a[0] + c
    return a
