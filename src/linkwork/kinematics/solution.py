"""`Solution`: the motion of a mechanism at N samples, computed by `solve` (model/data split:
the `Mechanism` never changes, a `Solution` is arrays over it).

Stored are the link poses and their derivatives; points, links and pairs are read from them on
demand by name. All arrays have the sample axis first. Lengths are in the mechanism's unit,
angles in radians, time in seconds.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from functools import cached_property
from math import factorial

import numpy as np

from ..errors import ModelError
from ..model import CircularSlot, Gear, Mechanism, Prismatic, Slot
from . import contact, intermittent


_FACTORIALS = np.array([factorial(k) for k in range(8)], dtype=float)


class Status(enum.IntEnum):
    OK = 0  # forward error bound within `precision.TOLERANCE` (accelerations: `ACCELERATION_TOLERANCE`)
    SINGULAR = 1  # near a dead centre / change point: the bound is larger (the pose is given)
    UNREACHABLE = 2  # the chain cannot be assembled at this input

    def __str__(self) -> str:
        return self.name.lower()


def _perp(v: np.ndarray) -> np.ndarray:
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def _rot(theta: np.ndarray, s: np.ndarray) -> np.ndarray:
    c, sn = np.cos(theta), np.sin(theta)
    return np.stack([c * s[..., 0] - sn * s[..., 1], sn * s[..., 0] + c * s[..., 1]], axis=-1)


@dataclass(frozen=True)
class PointMotion:
    """Position, velocity, acceleration (and jerk when solved to third order), each (N, 2)."""

    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray | None
    jerk: np.ndarray | None = None


@dataclass(frozen=True)
class LinkMotion:
    """Angle of the link's reference line, angular velocity ω and acceleration α, each (N,)."""

    angle: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray | None
    jerk: np.ndarray | None = None


class Solution:
    """Kinematics of `mechanism` at N samples. Index a point, link or pair by name."""

    #: several drivers: where the solve left the path of its inputs, for `solve(..., resume=)`
    #: to go on from (`continuation.PathEnd`); None for one driver
    path_end = None

    def __init__(self, mechanism: Mechanism, inputs: np.ndarray, time: np.ndarray | None,
                 coefficients: np.ndarray, status: np.ndarray, condition: np.ndarray, *,
                 trig: tuple[np.ndarray, np.ndarray] | None = None,
                 errors: np.ndarray | None = None) -> None:
        """`coefficients` C[k, n, link, (x, y, θ)]: the Taylor coefficients q⁽ᵏ⁾/k! (k = 0 …
        order) of every link's pose in time, as the solver computes them (turned into
        derivatives per link on demand, not all at once); `trig`: (cos θ, sin θ) of every
        link, each (N, links), when the solver has them already (else computed on first use)."""
        self.mechanism = mechanism
        self.inputs = inputs  # (N, drivers)
        self.time = time
        self._C = coefficients
        self._C.setflags(write=False)
        self._cos_sin = trig
        self._trig_cache: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self._pose_cache: dict[int, np.ndarray] = {}
        self.status = status
        self.condition = condition
        # bound on each sample's forward error, relative to the natural scale (L, L·Ω, …) or
        # to the answer where that is larger (`precision`); NaN where unreachable
        self.errors = np.full(status.shape, np.nan) if errors is None else errors

    @classmethod
    def concatenate(cls, parts: list[Solution]) -> Solution:
        """One solution from consecutive solutions of the same mechanism (sample axis joined)."""
        first = parts[0]
        time = None if first.time is None else np.concatenate([p.time for p in parts])
        return cls(first.mechanism, np.concatenate([p.inputs for p in parts]), time,
                   np.concatenate([p._C for p in parts], axis=1),
                   np.concatenate([p.status for p in parts]),
                   np.concatenate([p.condition for p in parts]),
                   errors=np.concatenate([p.errors for p in parts]))

    def sample(self, n: int) -> Solution:
        """Sample `n` alone, as a solution of one sample with the same numbers (the solver's
        cos θ, sin θ kept, so that its points are the very same): the workbench draws a sample
        of a whole motion it keeps without solving it again."""
        n = range(len(self))[n]
        cut = slice(n, n + 1)  # copies: the whole motion's arrays stay as they are
        trig = None if self._cos_sin is None else (self._cos_sin[0][cut].copy(),
                                                   self._cos_sin[1][cut].copy())
        return Solution(self.mechanism, self.inputs[cut].copy(),
                        None if self.time is None else self.time[cut].copy(), self._C[:, cut].copy(),
                        self.status[cut].copy(), self.condition[cut].copy(), trig=trig,
                        errors=self.errors[cut].copy())

    # ------------------------------------------------------------------ basics
    def __len__(self) -> int:
        return self._C.shape[1]

    def __repr__(self) -> str:
        n_ok = int((self.status == Status.OK).sum())
        return (f"<Solution of '{self.mechanism.name}': {len(self)} samples, {n_ok} ok, "
                f"{int((self.status == Status.SINGULAR).sum())} singular, "
                f"{int((self.status == Status.UNREACHABLE).sum())} unreachable>")

    @property
    def order(self) -> int:
        return self._C.shape[0] - 1

    @property
    def input(self) -> np.ndarray:
        """The input values (N,) of a one-driver mechanism; (N, drivers) otherwise."""
        return self.inputs[:, 0] if self.inputs.shape[1] == 1 else self.inputs

    def pose_derivatives(self, link: str) -> np.ndarray:
        """(order+1, N, 3): derivatives of (x, y, θ) of `link`'s pose."""
        i = self._li(link)
        D = self._pose_cache.get(i)
        if D is None:
            D = self._C[:, :, i] * _FACTORIALS[: self.order + 1, None, None]
            D.setflags(write=False)
            self._pose_cache[i] = D
        return D

    def _li(self, link: str) -> int:
        try:
            return self.mechanism.link_index[link]
        except KeyError:
            raise ModelError(f"mechanism '{self.mechanism.name}' has no link '{link}'") from None

    # ------------------------------------------------------------------ points
    def _trig(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """cos θ, sin θ of link index i at every sample (the solver's, or computed once)."""
        t = self._trig_cache.get(i)
        if t is None:
            if self._cos_sin is not None:
                t = (self._cos_sin[0][:, i], self._cos_sin[1][:, i])
            else:
                th = self._C[0, :, i, 2]
                t = (np.cos(th), np.sin(th))
            self._trig_cache[i] = t
        return t

    def point_on(self, link: str, s) -> PointMotion:
        """Motion of the point with design coordinates `s` carried by `link` (s may be (2,) or
        (N, 2) to follow a moving material point of the link, e.g. a coincident point)."""
        s = np.asarray(s, dtype=float)
        i = self._li(link)
        N, K = len(self), self.order
        if i == self.mechanism.link_index[self.mechanism.frame] and s.ndim == 1 and \
                self._all_assembled:
            # a point of the frame stands still: its motion costs no memory
            zero = np.broadcast_to(0.0, (N, 2))
            K = min(K, 3)
            return PointMotion(np.broadcast_to(s, (N, 2)), *([zero] * K + [None] * (3 - K)))
        K = min(K, 3)  # a point's motion is given up to its jerk
        C = self._C[: K + 1, :, i]
        c, sn = self._trig(i)
        out = np.empty((K + 1, 2, N))  # out[k, x|y, n]; handed out as (N, 2) views
        sx, sy = (np.broadcast_to(s[..., j], (N,)) for j in (0, 1))
        from . import kernels  # numba loads on the first solve, not on import
        rows = [C[k, :, j] for k, j in ((0, 0), (0, 1), (1, 0), (1, 1), (1, 2), (2, 0), (2, 1),
                                        (2, 2))] if K == 2 else []
        if s.ndim == 1 and all(r.flags.c_contiguous for r in [c, sn, *rows]) and rows:
            # rows contiguous (the solver's layout): a loop whose rows are arrays of their own
            kernels.point_motion_2(c, sn, float(s[0]), float(s[1]), *rows, *out.reshape(6, N))
        else:
            kernels.point_motion(C, c, sn, sx, sy, out)
        out.setflags(write=False)  # like the rest of a solution
        return PointMotion(*([out[k].T for k in range(K + 1)] + [None] * (3 - K)))

    @cached_property
    def _all_assembled(self) -> bool:
        return bool((self.status != Status.UNREACHABLE).all())

    def point(self, name: str) -> PointMotion:
        mech = self.mechanism
        if name not in mech.points:
            raise ModelError(f"mechanism '{mech.name}' has no point '{name}'")
        return self.point_on(mech.point_owner[name], mech.points[name])

    def local(self, link: str, xy: np.ndarray) -> np.ndarray:
        """Design (link) coordinates of world points xy (N, 2) in `link` at each sample."""
        D = self.pose_derivatives(link)
        return _rot(-D[0, :, 2], xy - D[0, :, :2])

    # ------------------------------------------------------------------ links
    def reference_angle(self, link: str) -> float:
        """Design angle of the link's reference line (first point to the next distinct one)."""
        pts = [self.mechanism.points[p] for p in self.mechanism.link(link).points]
        for q in pts[1:]:
            d = q - pts[0]
            if np.hypot(*d) > 0:
                return float(np.arctan2(d[1], d[0]))
        return 0.0

    def link(self, name: str) -> LinkMotion:
        D = self.pose_derivatives(name)
        return LinkMotion(D[0, :, 2] + self.reference_angle(name), D[1, :, 2],
                          D[2, :, 2] if self.order >= 2 else None,
                          D[3, :, 2] if self.order >= 3 else None)

    # ------------------------------------------------------------------ pairs
    def joint(self, name: str) -> dict[str, np.ndarray]:
        """Relative motion in pair `name`: relative angle, ω and α of links[1] to links[0]; for
        sliding pairs the slide, sliding velocity and acceleration along the guide (scalar and
        vector) and the Coriolis acceleration 2ω×v_rel of the guiding link; for higher pairs the
        contact (`contact.report`: contact point, common normal, pressure angle, sliding)."""
        mech = self.mechanism
        j = mech.joint(name)
        if contact.is_higher(j):
            return contact.report(self, name)
        if intermittent.is_intermittent(j):
            return intermittent.report(self, name)
        if isinstance(j, Gear):
            c = self.link(j.carrier)
            w1, w2 = self.link(j.links[0]), self.link(j.links[1])
            return {"angle_1": w1.angle - c.angle, "angle_2": w2.angle - c.angle,
                    "omega_1": w1.omega - c.omega, "omega_2": w2.omega - c.omega}
        a, b = j.links
        la, lb = self.link(a), self.link(b)
        out = {"angle": lb.angle - la.angle - (self.reference_angle(b) - self.reference_angle(a)),
               "omega": lb.omega - la.omega}
        if self.order >= 2:
            out["alpha"] = lb.alpha - la.alpha
        if not isinstance(j, (Prismatic, Slot, CircularSlot)):
            return out
        pin = self.point_on(b, mech.points[j.point])
        # the point of the guiding link that coincides with the pin at each sample
        coinc = self.point_on(a, self.local(a, pin.position))
        v_rel = pin.velocity - coinc.velocity
        Da = self.pose_derivatives(a)
        w_a = Da[1, :, 2]
        out["velocity"] = v_rel
        if isinstance(j, CircularSlot):
            centre = self.point_on(a, mech.points[j.center]).position
            r = pin.position - centre
            r0 = mech.points[j.point] - mech.points[j.center]
            loc = self.local(a, pin.position) - mech.points[j.center]
            out["arc_angle"] = np.arctan2(loc[:, 1], loc[:, 0]) - np.arctan2(r0[1], r0[0])
            out["arc_rate"] = (r[:, 0] * v_rel[:, 1] - r[:, 1] * v_rel[:, 0]) / (r * r).sum(1)
        else:
            u = _rot(Da[0, :, 2], j.axis)
            out["slide"] = (self.local(a, pin.position) - mech.points[j.point]) @ j.axis
            out["sliding_velocity"] = (v_rel * u).sum(1)
        if self.order >= 2:
            cor = 2 * w_a[:, None] * _perp(v_rel)
            a_rel = pin.acceleration - coinc.acceleration - cor
            out["acceleration"] = a_rel
            out["coriolis"] = cor
            if not isinstance(j, CircularSlot):
                out["sliding_acceleration"] = (a_rel * u).sum(1)
        return out

    # ------------------------------------------------------------------ exports
    def to_pandas(self):
        """A wide DataFrame: one row per sample, columns like 'B.vx', 'coupler.omega'; their
        units in `DataFrame.attrs['units']`."""
        from .export import to_dataframe
        return to_dataframe(self)

    def to_csv(self, path, units: bool = False) -> None:
        """The wide table (`to_pandas`'s columns) as CSV, written whole or not at all; `units`:
        headers with their units, `name [unit]`."""
        from ..outputs import write_output_file
        from .export import csv_lines
        write_output_file(path, csv_lines(self, units=units))

    def to_parquet(self, path) -> None:
        """The wide table as Parquet, its columns' units in the metadata (`linkwork.units`)."""
        from .export import write_parquet
        write_parquet(self, path)

    def to_document(self) -> dict:
        """The JSON document of `linkwork analyze --format json`."""
        from .export import to_document
        return to_document(self)
