"""Drawing scales (*Maßstäbe*, *mērogi*) as the books use them.

Owns :class:`Scale` (how much of a quantity one millimetre of paper represents: the length scale
*Längenmaßstab* M_l, the velocity scale *Geschwindigkeitsmaßstab* M_v, the acceleration scale
*Beschleunigungsmaßstab* M_a, each with its unit), :class:`Scales` (the three together, with the
factors that turn a velocity or an acceleration into a length on the mechanism drawing), the
"nice" rounding of scales (1, 2, 2.5, 5 × 10^k) and the automatic choice that fits a drawing on a
sheet. Scales can always be set by hand instead.

Rosenauer warns that his constructions mix lengths, velocities and accelerations "in drawing
units" (tg δ = ω, "choose the velocity scale so that the orthogonal velocity of A equals AC_a").
Here the mixing is explicit: ``Scales.kv`` is the mechanism length that represents a unit of
velocity (seconds), ``Scales.ka`` the one for accelerations (s²); with :meth:`Scales.rosenauer`
the velocity scale is chosen so that the rotated velocity of a crank pin is the crank itself
(kv = 1/ω) and the acceleration scale is the associated one (ka = kv², *zugeordneter Maßstab*).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..errors import InputError

NICE = (1.0, 2.0, 2.5, 5.0)

#: A4 landscape, with 10 mm margins: the default sheet
SHEET_MM = (277.0, 190.0)


def nice_ceil(x: float) -> float:
    """The smallest 'nice' number (1, 2, 2.5 or 5 times a power of ten) that is >= x."""
    if not math.isfinite(x) or x <= 0:
        return 1.0
    e = math.floor(math.log10(x))
    for k in (e - 1, e, e + 1):
        for m in NICE:
            v = m * 10.0**k
            if v >= x * (1 - 1e-12):
                return v
    return 10.0 ** (e + 1)


def _num(v: float) -> str:
    return f"{v:.6g}"


@dataclass(frozen=True)
class Scale:
    """1 mm of paper represents ``per_mm`` ``unit`` of ``quantity``."""

    quantity: str  # "length", "velocity", "acceleration", "force"
    unit: str
    per_mm: float

    def __post_init__(self) -> None:
        if not (math.isfinite(self.per_mm) and self.per_mm > 0):
            raise InputError(f"the {self.quantity} scale must be a positive number of {self.unit} "
                             f"per mm, got {self.per_mm!r}")

    @property
    def symbol(self) -> str:
        return {"length": "M_l", "velocity": "M_v", "acceleration": "M_a", "force": "M_F"}.get(self.quantity, "M")

    def to_paper(self, value):
        """Millimetres of paper for ``value`` (in ``unit``)."""
        return value / self.per_mm

    def text(self) -> str:
        """The legend line, e.g. ``M_v: 1 mm ≙ 20 mm/s``."""
        return f"{self.symbol}: 1 mm \u2259 {_num(self.per_mm)} {self.unit}"


@dataclass(frozen=True)
class Scales:
    """The length, velocity and acceleration scales of one drawing."""

    length: Scale
    velocity: Scale | None = None
    acceleration: Scale | None = None

    @property
    def kv(self) -> float:
        """Mechanism length that represents one velocity unit on the mechanism drawing [s]."""
        if self.velocity is None:
            raise InputError("no velocity scale has been set")
        return self.length.per_mm / self.velocity.per_mm

    @property
    def ka(self) -> float:
        """Mechanism length that represents one acceleration unit on the mechanism drawing [s²]."""
        if self.acceleration is None:
            raise InputError("no acceleration scale has been set")
        return self.length.per_mm / self.acceleration.per_mm

    def with_(self, **kw) -> Scales:
        return replace(self, **kw)

    def lines(self) -> list[str]:
        return [s.text() for s in (self.length, self.velocity, self.acceleration) if s is not None]

    # ------------------------------------------------------------------ choosing scales
    @classmethod
    def auto(cls, length_unit: str, extent: float, *, vmax: float | None = None,
             amax: float | None = None, paper_mm: float = 180.0, vector_mm: float = 30.0,
             length: float | None = None, velocity: float | None = None,
             acceleration: float | None = None) -> Scales:
        """Scales that fit a figure of ``extent`` (mechanism units) into ``paper_mm`` millimetres
        and draw the largest velocity/acceleration (``vmax``, ``amax``) about ``vector_mm`` long,
        rounded to nice values. Any of ``length``, ``velocity``, ``acceleration`` (units per mm)
        given by hand is used as it is."""
        ls = Scale("length", length_unit, length or nice_ceil(extent / paper_mm))
        vs = as_ = None
        if velocity is not None or vmax is not None:
            vs = Scale("velocity", f"{length_unit}/s", velocity or nice_ceil((vmax or 1.0) / vector_mm))
        if acceleration is not None or amax is not None:
            as_ = Scale("acceleration", f"{length_unit}/s\u00b2",
                        acceleration or nice_ceil((amax or 1.0) / vector_mm))
        return cls(ls, vs, as_)

    @classmethod
    def rosenauer(cls, length: Scale, omega: float) -> Scales:
        """Rosenauer's choice: a crank turning at ``omega`` has its rotated velocity drawn as the
        crank itself (kv = 1/|ω|) and its centripetal acceleration too (ka = kv²)."""
        w = abs(omega)
        if not w > 0:
            raise InputError("Rosenauer's scales need a non-zero crank angular velocity")
        u = length.unit
        return cls(length, Scale("velocity", f"{u}/s", length.per_mm * w),
                   Scale("acceleration", f"{u}/s\u00b2", length.per_mm * w * w))
