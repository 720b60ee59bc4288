"""Profiles made of straight lines and circular arcs, as the books draw cams (base circle,
flanks, nose arcs: *Kreisbogennocken*, *Tangentennocken*).

The parameter is the arc length from the start point. Derivatives are exact to any order: a
line's position is linear, an arc's k-th derivative is R·(σ/R)^k times the unit vector turned
by k quarter turns. At a join, `side=+1` (the default) evaluates the segment that starts there,
`side=-1` the segment that ends there; at the ends of an open path the only segment is taken.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .base import BaseProfile, ProfileError

_SENSES = {"ccw": 1, "cw": -1, 1: 1, -1: -1}


@dataclass(frozen=True)
class LineTo:
    """A straight segment from the current point to `point`."""

    point: tuple[float, float]


@dataclass(frozen=True)
class ArcTo:
    """A circular arc from the current point to `point`, either about `center` (the arc's radius
    is the start point's distance from it; the end point must lie on the same circle) or with
    `radius`: then the arc is the shorter one between the two points unless `large` is set.
    `sense` is +1 or "ccw" (counter-clockwise, the default) or -1 or "cw". An arc about a centre
    that ends where it starts is a full circle."""

    point: tuple[float, float]
    center: tuple[float, float] | None = None
    radius: float | None = None
    sense: int | str = 1
    large: bool = False


@dataclass(frozen=True)
class Joins:
    """The joins of a path, in order of the parameter (for a closed path the seam, u = 0, last):
    parameter, curvature on the segment ending and on the segment starting there, and the turn of
    the tangent (radians, positive counter-clockwise; non-zero at a corner)."""

    u: np.ndarray
    kappa_before: np.ndarray
    kappa_after: np.ndarray
    turn: np.ndarray


def _unit_angle(v: np.ndarray) -> float:
    return float(np.arctan2(v[1], v[0]))


class PathProfile(BaseProfile):
    """A profile of lines and circular arcs from `start` through `segments` (LineTo, ArcTo),
    open or `closed` (then the last segment must end at the start). The parameter is the arc
    length from the start, domain (0, length).

    End points given by the user are met to `tol` times the size of the figure; joins need not
    be tangent (see `joins()`; `smooth=True` refuses a corner larger than `angle_tol` radians).
    `breaks` are the joins where the curvature or the tangent jumps.
    """

    def __init__(self, start, segments, closed: bool = False, *, smooth: bool = False,
                 tol: float = 1e-9, angle_tol: float = 1e-6) -> None:
        start = np.asarray(start, dtype=float)
        if start.shape != (2,) or not np.all(np.isfinite(start)):
            raise ProfileError(f"a path needs a finite start point [x, y], got {start.tolist()}")
        segments = list(segments)
        if not segments:
            raise ProfileError("a path needs at least one segment")
        for i, s in enumerate(segments):
            if not isinstance(s, (LineTo, ArcTo)):
                raise ProfileError(f"segment {i}: not a LineTo or ArcTo but {type(s).__name__}", i)
        given = [start] + [np.asarray(s.point, dtype=float) for s in segments]
        for i, s in enumerate(segments):
            if given[i + 1].shape != (2,) or not np.all(np.isfinite(given[i + 1])):
                raise ProfileError(f"segment {i}: the end point must be a finite [x, y]", i)
        scale = max(1.0, max(float(np.max(np.abs(g))) for g in given))
        tol_abs = tol * scale
        rows = []
        current = start
        for i, seg in enumerate(segments):
            end = given[i + 1]
            if isinstance(seg, LineTo):
                rows.append(self._line(i, current, end, tol_abs))
            else:
                rows.append(self._arc(i, current, end, seg, tol_abs))
            current = end
        if closed and np.hypot(*(current - start)) > tol_abs:
            raise ProfileError(f"a closed path must end at its start {start.tolist()}, "
                               f"the last segment ends at {current.tolist()}", len(segments) - 1)
        self.closed = bool(closed)
        self.start = start
        self.segments = tuple(segments)
        kind, length, p0, t0, c, r, sig, th0 = (np.array(col) for col in zip(*rows))
        self._arc = kind.astype(bool)
        self._length = length.astype(float)
        self._s0 = np.concatenate([[0.0], np.cumsum(self._length)[:-1]])
        self._p0, self._t0, self._c = p0.reshape(-1, 2), t0.reshape(-1, 2), c.reshape(-1, 2)
        self._r, self._sig, self._th0 = r.astype(float), sig.astype(float), th0.astype(float)
        total = float(np.sum(self._length))
        self.domain = (0.0, total)
        self._joins = self._find_joins()
        if smooth:
            bad = np.flatnonzero(np.abs(self._joins.turn) > angle_tol)
            if bad.size:
                j = int(bad[0])
                seg = (j + 1) % len(segments)
                raise ProfileError(
                    f"segment {seg} starts with a corner of {np.degrees(self._joins.turn[j]):.6g}° "
                    f"against segment {seg - 1 if seg else len(segments) - 1} (smooth path required)", seg)
        jump = (np.abs(self._joins.kappa_after - self._joins.kappa_before)
                > 1e-12 * np.maximum(np.abs(self._joins.kappa_after), np.abs(self._joins.kappa_before)))
        self._breaks = np.sort(self._joins.u[jump | (np.abs(self._joins.turn) > 1e-12)])

    # -- construction ---------------------------------------------------------------------------

    @staticmethod
    def _line(i, p0, p1, tol_abs):
        d = p1 - p0
        length = float(np.hypot(*d))
        if length <= tol_abs:
            raise ProfileError(f"segment {i}: a line of zero length (it ends where it starts)", i)
        return (0, length, p0, d / length, np.zeros(2), np.inf, 0.0, 0.0)

    @staticmethod
    def _arc(i, p0, p1, seg: ArcTo, tol_abs):
        if seg.sense not in _SENSES or isinstance(seg.sense, bool):
            raise ProfileError(f"segment {i}: sense must be 'ccw' or 'cw', got {seg.sense!r}", i)
        sigma = _SENSES[seg.sense]
        chord = p1 - p0
        c_len = float(np.hypot(*chord))
        if (seg.center is None) == (seg.radius is None):
            raise ProfileError(f"segment {i}: an arc needs either its centre or its radius (one of them)", i)
        if seg.center is not None:
            if seg.large:
                raise ProfileError(f"segment {i}: 'large' applies to an arc given by its radius; "
                                   "an arc about a centre goes the way its sense says", i)
            center = np.asarray(seg.center, dtype=float)
            if center.shape != (2,) or not np.all(np.isfinite(center)):
                raise ProfileError(f"segment {i}: the centre must be a finite [x, y]", i)
            radius = float(np.hypot(*(p0 - center)))
            r_end = float(np.hypot(*(p1 - center)))
            if radius <= tol_abs:
                raise ProfileError(f"segment {i}: the arc starts at its centre (radius zero)", i)
            if abs(r_end - radius) > tol_abs:
                raise ProfileError(f"segment {i}: the end point is {r_end:.12g} from the centre but the "
                                   f"start point {radius:.12g}: not on one circle", i)
        else:
            radius = float(seg.radius)
            if not (np.isfinite(radius) and radius > 0):
                raise ProfileError(f"segment {i}: the radius must be positive and finite, got {seg.radius}", i)
            if c_len <= tol_abs:
                raise ProfileError(f"segment {i}: an arc given by its radius needs distinct end points "
                                   "(give the centre for a full circle)", i)
            if c_len > 2 * radius + tol_abs:
                raise ProfileError(f"segment {i}: the chord {c_len:.12g} is longer than the diameter "
                                   f"{2 * radius:.12g}", i)
            h = np.sqrt(max(radius**2 - c_len**2 / 4, 0.0))
            left = np.array([-chord[1], chord[0]]) / c_len
            # the shorter arc in the given sense has its centre on that side of the chord
            center = (p0 + p1) / 2 + sigma * (-1.0 if seg.large else 1.0) * h * left
        th0 = _unit_angle(p0 - center)
        sweep = float(np.mod(sigma * (_unit_angle(p1 - center) - th0), 2 * np.pi))
        if c_len <= tol_abs:
            sweep = 2 * np.pi
        return (1, radius * sweep, p0, np.zeros(2), center, radius, float(sigma), th0)

    def _find_joins(self) -> Joins:
        n = len(self._length)
        kappa = np.where(self._arc, self._sig / self._r, 0.0)
        th_end = self._th0 + self._sig * self._length / np.where(self._arc, self._r, 1.0)
        t_start = np.where(self._arc[:, None],
                           self._sig[:, None] * np.stack([-np.sin(self._th0), np.cos(self._th0)], -1), self._t0)
        t_end = np.where(self._arc[:, None],
                         self._sig[:, None] * np.stack([-np.sin(th_end), np.cos(th_end)], -1), self._t0)
        before = np.arange(n - 1) if not self.closed else np.r_[np.arange(n - 1), n - 1]
        after = before + 1
        after[after == n] = 0
        u = np.where(after == 0, 0.0, self._s0[after])
        a, b = t_end[before], t_start[after]
        turn = np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.sum(a * b, axis=-1))
        return Joins(u, kappa[before], kappa[after], turn)

    # -- the protocol ---------------------------------------------------------------------------

    @property
    def breaks(self) -> np.ndarray:
        return self._breaks

    def joins(self) -> Joins:
        """Every join (not only the breaks) with the curvature on each side and the tangent's turn."""
        return self._joins

    @property
    def segment_starts(self) -> np.ndarray:
        """Parameter (arc length) where each segment starts."""
        return self._s0

    def segment_index(self, u: np.ndarray, side: int = 1) -> np.ndarray:
        """Index of the segment that evaluates u (wrapped into the domain) on the given side."""
        r = self._wrap(np.asarray(u, dtype=float))[0]
        return self._locate(r, side)[0]

    def _locate(self, u: np.ndarray, side: int) -> tuple[np.ndarray, np.ndarray]:
        n = len(self._s0)
        i = np.searchsorted(self._s0, u, side="right" if side == 1 else "left") - 1
        local = u - self._s0[np.clip(i, 0, n - 1)]
        if self.closed:  # the seam seen from its left: the end of the last segment
            local = np.where(i < 0, self._length[-1], local)
            i = np.where(i < 0, n - 1, i)
        return np.clip(i, 0, n - 1), local

    def _eval(self, u: np.ndarray, order: int, side: int) -> np.ndarray:
        i, s = self._locate(u, side)
        arc = self._arc[i][..., None]
        radius = np.where(self._arc, self._r, 1.0)[i]
        sig = self._sig[i]
        theta = self._th0[i] + sig * s / radius
        out = np.zeros((order + 1,) + u.shape + (2,))
        for k in range(order + 1):
            ang = theta + k * np.pi / 2
            arc_k = (radius * (sig / radius) ** k)[..., None] * np.stack([np.cos(ang), np.sin(ang)], -1)
            if k == 0:
                arc_k = arc_k + self._c[i]
                line_k = self._p0[i] + s[..., None] * self._t0[i]
            elif k == 1:
                line_k = self._t0[i]
            else:
                line_k = 0.0
            out[k] = np.where(arc, arc_k, line_k)
        return out

    @property
    def length(self) -> float:
        return self.domain[1]

    def arc_length(self, u: np.ndarray) -> np.ndarray:
        """The parameter itself is the arc length (plus whole turns of a closed path)."""
        r, turns, inside = self._wrap(np.asarray(u, dtype=float))
        return np.where(inside, r + turns * self.domain[1], np.nan)

    def nearest(self, p: np.ndarray) -> np.ndarray:
        """Exact nearest point: the foot on each line, the radial point on each arc (or the
        nearer end of the segment), the nearest of all segments (a loop over segments)."""
        p = np.asarray(p, dtype=float)
        if p.shape[-1:] != (2,):
            raise ProfileError(f"nearest needs points of shape (..., 2), got {p.shape}")
        best_d = np.full(p.shape[:-1], np.inf)
        best_u = np.full(p.shape[:-1], np.nan)
        for i in range(len(self._s0)):
            length = self._length[i]
            seg = np.full(p.shape[:-1], i)
            if self._arc[i]:
                rel = p - self._c[i]
                local = self._r[i] * np.mod(
                    self._sig[i] * (np.arctan2(rel[..., 1], rel[..., 0]) - self._th0[i]), 2 * np.pi)
                # beyond the arc's ends: the nearer end point
                d_start = _dist(p, self._on_segment(seg, np.zeros(p.shape[:-1])))
                d_end = _dist(p, self._on_segment(seg, np.full(p.shape[:-1], length)))
                local = np.where(local > length, np.where(d_start <= d_end, 0.0, length), local)
            else:
                local = np.clip(np.sum((p - self._p0[i]) * self._t0[i], axis=-1), 0.0, length)
            d = _dist(p, self._on_segment(seg, local))
            take = d < best_d
            best_d = np.where(take, d, best_d)
            best_u = np.where(take, self._s0[i] + local, best_u)
        if self.closed:
            best_u = np.where(best_u >= self.domain[1], best_u - self.domain[1], best_u)
        return best_u

    def _on_segment(self, i: np.ndarray, s: np.ndarray) -> np.ndarray:
        radius = np.where(self._arc, self._r, 1.0)[i]
        theta = self._th0[i] + self._sig[i] * s / radius
        arc_pt = self._c[i] + radius[..., None] * np.stack([np.cos(theta), np.sin(theta)], -1)
        line_pt = self._p0[i] + s[..., None] * self._t0[i]
        return np.where(self._arc[i][..., None], arc_pt, line_pt)


def _dist(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    return np.hypot(p[..., 0] - q[..., 0], p[..., 1] - q[..., 1])
