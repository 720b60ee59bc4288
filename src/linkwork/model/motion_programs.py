"""Follower motion programs of cams (*Bewegungsgesetze*, *Bewegungsplan*): rise, dwell and
return segments over the cam angle, each following a standard motion law.

A motion law is a normalised transition S(x) from S(0) = 0 to S(1) = 1 over x in [0, 1]
(x the fraction of the segment's cam angle); a segment of lift L over the cam angle β gives
s(φ) = s_start ± L·S((φ − φ_start)/β) and s⁽ᵏ⁾(φ) = ±L·S⁽ᵏ⁾(x)/βᵏ. Every law here is piecewise a
polynomial plus one sine, so its derivatives of every order are exact (the cam profiles that
`disc_cams` builds from them need as many as the kinematics asks for).

The laws (names as written in files and on the command line; VDI 2143 names in brackets):

- `uniform`: constant velocity, S = x (*Gerade*); the velocity jumps at both ends.
- `harmonic`: simple harmonic, S = (1 − cos πx)/2 (*einfache Sinuslinie*); the acceleration
  jumps at the ends. Cv = π/2, Ca = π²/2.
- `cycloidal`: S = x − sin(2πx)/2π (*geneigte Sinuslinie*). Cv = 2, Ca = 2π, Cj = 4π².
- `3-4-5`: S = 10x³ − 15x⁴ + 6x⁵ (*Polynom 5. Grades*). Cv = 15/8, Ca = 10/√3.
- `4-5-6-7`: S = 35x⁴ − 84x⁵ + 70x⁶ − 20x⁷; the jerk too is zero at the ends.
- `modified-trapezoid`: the acceleration rises along a quarter sine over x in [0, 1/8], stays
  constant to 3/8, turns along a half sine to its negative over [3/8, 5/8], … (Neklutin;
  *modifiziertes Beschleunigungstrapez*). Ca = 8π/(2 + π) ≈ 4.888, Cv = 2.
- `modified-sine`: a quarter sine of period 1/2 over [0, 1/8], a sine of period 3/2 over
  [1/8, 7/8], a quarter sine again to the end (*modifizierte Sinuslinie*).
  Ca = 4π²/(π + 4) ≈ 5.528, Cv = 4π/(π + 4) ≈ 1.760.
- `parabolic`: Pöschl's constant acceleration (*Parabelgesetz*, *konstante Beschleunigung*):
  S = 2x² to x = 1/2, then 1 − 2(1 − x)², so that on the second half the velocity is
  V√(1 − y/h) of the remaining lift (Pöschl §19, eq. 55). Cv = 2, Ca = 4; the acceleration
  jumps at the ends and in the middle.

Peak factors Cv = max S′, Ca = max |S″|, Cj = max |S‴| are taken inside the pieces: where the
acceleration jumps the jerk is an impulse, which `MotionProgram.joins` reports, never smooths.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..errors import ModelError

TWO_PI = 2.0 * np.pi


class CamDesignError(ModelError):
    """A cam design or motion program that cannot be built; `index` is the segment the message
    names (None when it concerns the whole design), `key` the design's parameter."""

    def __init__(self, message: str, index: int | None = None, key: str | None = None) -> None:
        super().__init__(message)
        self.index, self.key = index, key


# ---------------------------------------------------------------------------- laws
@dataclass(frozen=True)
class _Piece:
    """S(x) = Σ_j p_j t^j + amp·sin(ω t + phase), t = x − x0, on [x0, x1]."""

    x0: float
    x1: float
    poly: tuple[float, ...]
    amp: float = 0.0
    omega: float = 0.0
    phase: float = 0.0

    def derivative(self, x: np.ndarray, k: int) -> np.ndarray:
        t = x - self.x0
        c = np.polynomial.polynomial.polyder(np.asarray(self.poly, dtype=float), k) if k else np.asarray(self.poly)
        out = np.polynomial.polynomial.polyval(t, c) if len(c) else np.zeros_like(t)
        if self.amp:
            out = out + self.amp * self.omega**k * np.sin(self.omega * t + self.phase + k * np.pi / 2)
        return np.broadcast_to(out, np.shape(x)).astype(float)


def _from_acceleration(pieces: list[tuple[float, float, float, float, float, float]]) -> tuple[_Piece, ...]:
    """Integrate an acceleration given piecewise as k + B·sin(ω t + φ) (t from the piece's
    start) twice from rest at S = 0, and scale the result to S(1) = 1:
    S = S₀ + B sin φ/ω² + (v₀ + B cos φ/ω)·t + k t²/2 − (B/ω²)·sin(ω t + φ)."""
    out, v0, s0 = [], 0.0, 0.0
    for x0, x1, k, B, w, ph in pieces:
        trig = B != 0.0
        p0 = s0 + (B * np.sin(ph) / w**2 if trig else 0.0)
        p1 = v0 + (B * np.cos(ph) / w if trig else 0.0)
        piece = _Piece(x0, x1, (p0, p1, k / 2), -B / w**2 if trig else 0.0, w if trig else 0.0, ph)
        out.append(piece)
        h = np.array(x1)
        v0, s0 = float(piece.derivative(h, 1)), float(piece.derivative(h, 0))
    return tuple(_Piece(p.x0, p.x1, tuple(c / s0 for c in p.poly), p.amp / s0, p.omega, p.phase) for p in out)


def _law_pieces(name: str) -> tuple[_Piece, ...]:
    pi = np.pi
    if name == "uniform":
        return (_Piece(0.0, 1.0, (0.0, 1.0)),)
    if name == "harmonic":
        return (_Piece(0.0, 1.0, (0.5,), -0.5, pi, pi / 2),)
    if name == "cycloidal":
        return (_Piece(0.0, 1.0, (0.0, 1.0), -1 / (2 * pi), 2 * pi, 0.0),)
    if name == "3-4-5":
        return (_Piece(0.0, 1.0, (0, 0, 0, 10, -15, 6)),)
    if name == "4-5-6-7":
        return (_Piece(0.0, 1.0, (0, 0, 0, 0, 35, -84, 70, -20)),)
    w = 4 * pi
    if name == "modified-trapezoid":
        return _from_acceleration([(0, 1 / 8, 0, 1, w, 0), (1 / 8, 3 / 8, 1, 0, 0, 0),
                                   (3 / 8, 5 / 8, 0, 1, w, pi / 2), (5 / 8, 7 / 8, -1, 0, 0, 0),
                                   (7 / 8, 1, 0, -1, w, pi / 2)])
    if name == "modified-sine":
        return _from_acceleration([(0, 1 / 8, 0, 1, w, 0), (1 / 8, 7 / 8, 0, 1, w / 3, pi / 2),
                                   (7 / 8, 1, 0, -1, w, pi / 2)])
    if name == "parabolic":
        return _from_acceleration([(0, 0.5, 1, 0, 0, 0), (0.5, 1, -1, 0, 0, 0)])
    raise KeyError(name)  # pragma: no cover - names are checked by `law`


LAWS = ("uniform", "harmonic", "cycloidal", "3-4-5", "4-5-6-7", "modified-trapezoid",
        "modified-sine", "parabolic")
#: other names accepted for the laws
ALIASES = {"constant-velocity": "uniform", "simple-harmonic": "harmonic", "cycloid": "cycloidal",
           "constant-acceleration": "parabolic", "345": "3-4-5", "4567": "4-5-6-7",
           "polynomial-345": "3-4-5", "polynomial-4567": "4-5-6-7"}


@dataclass(frozen=True)
class MotionLawShape:
    """A normalised motion law S(x), x in [0, 1], with derivatives of any order; `breaks` are
    the inner joins of its pieces (where some derivative jumps or is only piecewise smooth)."""

    name: str
    pieces: tuple[_Piece, ...] = field(repr=False)

    @property
    def breaks(self) -> np.ndarray:
        return np.array([p.x0 for p in self.pieces[1:]])

    def derivatives(self, x: np.ndarray, order: int, side: int = 1) -> np.ndarray:
        """(order + 1, *x.shape): S, S′, …, S⁽ᵒʳᵈᵉʳ⁾ at x in [0, 1]; at an inner break, the piece
        that starts there (side=+1) or ends there (side=−1)."""
        x = np.asarray(x, dtype=float)
        out = np.empty((order + 1,) + x.shape)
        starts = np.array([p.x0 for p in self.pieces])
        for b in starts[1:]:  # a join reached through rounding (φ scaled by the segment) is the join
            x = np.where(np.abs(x - b) <= 1e-13, b, x)
        i = np.searchsorted(starts, x, side="right" if side > 0 else "left") - 1
        i = np.clip(i, 0, len(self.pieces) - 1)
        for n, piece in enumerate(self.pieces):
            m = i == n
            if not m.any():
                continue
            xm = x[m]
            for k in range(order + 1):
                out[k][m] = piece.derivative(xm, k)
        return out

    @cached_property
    def peaks(self) -> tuple[float, float, float]:
        """(Cv, Ca, Cj): the largest |S′|, |S″|, |S‴| inside the pieces, each maximum refined by
        Newton's method on the next derivative from the best of a dense sample."""
        best = [0.0, 0.0, 0.0]
        for p in self.pieces:
            x = np.linspace(p.x0, p.x1, 4001)
            for k in (1, 2, 3):
                v = np.abs(p.derivative(x, k))
                j = int(np.argmax(v))
                xs, val = x[j], v[j]
                if p.x0 < xs < p.x1:
                    for _ in range(30):
                        d1, d2 = float(p.derivative(np.array(xs), k + 1)), float(p.derivative(np.array(xs), k + 2))
                        if d2 == 0.0:
                            break
                        xs = min(max(xs - d1 / d2, p.x0), p.x1)
                    val = max(val, abs(float(p.derivative(np.array(xs), k))))
                best[k - 1] = max(best[k - 1], val)
        return tuple(float(b) for b in best)


def law(name: str) -> MotionLawShape:
    """The motion law called `name` (one of `LAWS` or an alias); CamDesignError otherwise."""
    key = ALIASES.get(str(name).strip().lower(), str(name).strip().lower())
    if key not in LAWS:
        raise CamDesignError(f"unknown motion law '{name}' (one of {', '.join(LAWS)})")
    return _LAW_CACHE.setdefault(key, MotionLawShape(key, _law_pieces(key)))


_LAW_CACHE: dict[str, MotionLawShape] = {}


# ---------------------------------------------------------------------------- program
KINDS = ("rise", "dwell", "return")


@dataclass(frozen=True)
class Segment:
    """One part of a motion program: a `rise` or `return` of `lift` over the cam angle `extent`
    (radians) following `law`, or a `dwell` (*Rast*) over `extent`. The lift is a length for a
    translating follower, an angle (radians) for an oscillating one."""

    kind: str
    extent: float
    lift: float = 0.0
    law: str | None = None


@dataclass(frozen=True)
class Join:
    """Where two pieces of the program meet (a segment join or a join inside a law): the cam
    angle and the jumps s⁽ᵏ⁾(φ⁺) − s⁽ᵏ⁾(φ⁻) of the derivatives k = 1…4 (velocity, acceleration,
    jerk, snap per radian of cam angle); a jump below 1e-9 of its scale is written as 0."""

    angle: float
    jumps: tuple[float, float, float, float]
    segment: int

    @property
    def first_jump(self) -> int | None:
        """The lowest order whose derivative jumps here (1: velocity, 2: acceleration, …), None
        if the program is C⁴ here."""
        for k, j in enumerate(self.jumps, start=1):
            if j != 0.0:
                return k
        return None


class MotionProgram:
    """Follower lift s(φ) over one turn of the cam, from segments that fill exactly 360°
    (φ in radians, periodic). The lift is measured from its lowest value in the turn (the base
    circle), so `s` ≥ 0 and its minimum is 0."""

    def __init__(self, segments) -> None:
        segs = tuple(segments)
        if not segs:
            raise CamDesignError("a motion program needs at least one segment")
        for i, s in enumerate(segs):
            if not isinstance(s, Segment):
                raise CamDesignError(f"segment {i + 1} is not a Segment", i)
            if s.kind not in KINDS:
                raise CamDesignError(f"segment {i + 1}: kind must be one of {', '.join(KINDS)}, got '{s.kind}'", i)
            if not (np.isfinite(s.extent) and s.extent > 0):
                raise CamDesignError(f"segment {i + 1} ({s.kind}): its cam angle must be positive, "
                                     f"got {np.degrees(s.extent):.6g}°", i)
            if s.kind != "dwell":
                if not (np.isfinite(s.lift) and s.lift > 0):
                    raise CamDesignError(f"segment {i + 1} ({s.kind}): the lift must be positive, got {s.lift}", i)
                try:
                    law(s.law if s.law is not None else "")
                except CamDesignError as exc:
                    raise CamDesignError(f"segment {i + 1} ({s.kind}): {exc}", i) from None
        total = float(sum(s.extent for s in segs))
        if abs(total - TWO_PI) > 1e-9 * TWO_PI:
            raise CamDesignError(f"the segments cover {np.degrees(total):.9g}° of cam angle; they must "
                                 f"fill one turn, 360°")
        rises = sum(s.lift for s in segs if s.kind == "rise")
        returns = sum(s.lift for s in segs if s.kind == "return")
        if abs(rises - returns) > 1e-9 * max(rises, returns, 1e-300):
            raise CamDesignError(f"the follower must end the turn where it starts: the rises total "
                                 f"{rises:.9g} but the returns {returns:.9g}")
        self.segments = segs
        ext = np.array([s.extent for s in segs])
        self.starts = np.concatenate([[0.0], np.cumsum(ext)[:-1]])
        self.ends = np.append(self.starts[1:], TWO_PI)
        sign = np.array([{"rise": 1.0, "dwell": 0.0, "return": -1.0}[s.kind] for s in segs])
        step = sign * np.array([s.lift for s in segs])
        level = np.concatenate([[0.0], np.cumsum(step)[:-1]])
        self.levels = level - level.min()  # lift at each segment's start
        self._sign = sign
        self._laws = tuple(law(s.law) if s.kind != "dwell" else None for s in segs)

    @property
    def max_lift(self) -> float:
        return float(max(self.levels.max(), (self.levels + self._sign * [s.lift for s in self.segments]).max()))

    def __repr__(self) -> str:
        return "MotionProgram(" + ", ".join(
            f"{s.kind} {np.degrees(s.extent):g}°" + (f" {s.lift:g} {s.law}" if s.kind != "dwell" else "")
            for s in self.segments) + ")"

    @cached_property
    def breaks(self) -> np.ndarray:
        """Cam angles of every join (segment joins, including 0, and the joins inside laws)."""
        out = list(self.starts)
        for s, lw, a, b in zip(self.segments, self._laws, self.starts, self.ends):
            if lw is not None:
                out.extend(a + (b - a) * lw.breaks)
        return np.unique(np.array(out))

    def _locate(self, phi: np.ndarray, side: int) -> tuple[np.ndarray, np.ndarray]:
        """(segment index, angle inside [0, 2π)) for each φ, the join taken by `side`."""
        r = np.mod(phi, TWO_PI)
        r = np.where(r >= TWO_PI, 0.0, r)
        if side > 0:
            i = np.searchsorted(self.starts, r, side="right") - 1
        else:
            i = np.searchsorted(self.starts, r, side="left") - 1
            r = np.where(i < 0, TWO_PI, r)  # φ = 0 from below: the end of the last segment
            i = np.where(i < 0, len(self.segments) - 1, i)
        return np.clip(i, 0, len(self.segments) - 1), r

    def derivatives(self, phi: np.ndarray, order: int, side: int = 1) -> np.ndarray:
        """(order + 1, *phi.shape): s, ds/dφ, …, dᵒʳᵈᵉʳs/dφᵒʳᵈᵉʳ; at a join, of the piece that
        starts there (side=+1) or ends there (side=−1)."""
        phi = np.asarray(phi, dtype=float)
        shape = phi.shape
        phi = phi.reshape(-1)
        out = np.zeros((order + 1,) + phi.shape)
        i, r = self._locate(phi, side)
        for n, (seg, lw) in enumerate(zip(self.segments, self._laws)):
            m = i == n
            if not m.any():
                continue
            out[0][m] = self.levels[n]
            if lw is None:
                continue
            beta = self.ends[n] - self.starts[n]
            x = np.clip((r[m] - self.starts[n]) / beta, 0.0, 1.0)
            S = lw.derivatives(x, order, side)
            for k in range(order + 1):
                out[k][m] += self._sign[n] * seg.lift * S[k] / beta**k
        bad = ~np.isfinite(phi)
        if bad.any():
            out[:, bad] = np.nan
        return out.reshape((order + 1,) + shape)

    def joins(self) -> list[Join]:
        """Every join with the jumps of velocity, acceleration, jerk and snap there."""
        u = self.breaks
        after, before = self.derivatives(u, 4, 1), self.derivatives(u, 4, -1)
        i, _ = self._locate(u, 1)
        out = []
        for n, a in enumerate(u):
            jumps = []
            for k in range(1, 5):
                # the scale of the k-th derivative on the two segments meeting here
                scale = max(self._scale(int(i[n]), k), self._scale(int(i[n]) - 1, k))
                j = float(after[k, n] - before[k, n])
                jumps.append(0.0 if abs(j) <= 1e-9 * scale else j)
            out.append(Join(float(a), tuple(jumps), int(i[n])))
        return out

    def _scale(self, n: int, k: int) -> float:
        seg = self.segments[n % len(self.segments)]
        lift = seg.lift if seg.kind != "dwell" else self.max_lift
        return max(lift, 1e-300) / seg.extent**k

    def peaks(self) -> tuple[float, float, float]:
        """The largest |s′|, |s″|, |s‴| (per radian of cam angle) over the turn, inside the
        pieces: Σ over segments of L·C/βᵏ with each law's peak factors."""
        best = [0.0, 0.0, 0.0]
        for seg, lw in zip(self.segments, self._laws):
            if lw is None:
                continue
            for k, c in enumerate(lw.peaks):
                best[k] = max(best[k], seg.lift * c / seg.extent ** (k + 1))
        return tuple(float(b) for b in best)

