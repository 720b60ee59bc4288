"""Coupler cognates (Roberts–Chebyshev theorem): the two other four-bars whose coupler point
traces the same coupler curve.

With the crank r₂ = A − A₀, coupler r₃ = B − A, rocker r₄ = B − B₀ and the coupler point
C = A + λ·r₃ (λ complex: the shape of the coupler triangle ABC), the third fixed pivot is
O_C = A₀ + λ(B₀ − A₀) (triangle A₀B₀O_C similar to ABC), and

    C = A₀ + λr₃ + r₂           = O_C + λr₄ + (1 − λ)r₂     (cognate 1: pivots A₀, O_C)
    C = B₀ + (λ − 1)r₃ + r₄     = O_C + (1 − λ)r₂ + λr₄     (cognate 2: pivots B₀, O_C)

each vector turning with the link of the original whose vector it is multiplied from: in
cognate 1 the link A₀–A₁ (A₁ = A₀ + λr₃) turns with the original coupler, its coupler A₁–C–D
(D = C − (1 − λ)r₂) with the crank, its rocker D–O_C with the rocker; in cognate 2 the link
B₀–E (E = B₀ + (λ − 1)r₃) with the coupler, the coupler E–C–F (F = C − λr₄) with the rocker,
the link F–O_C with the crank. Cognate 1 is driven at A₀, cognate 2 at O_C (its link there turns
with the original crank, so it runs in step with the original).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model import Mechanism
from ._file import mechanism_file
from ._four_bar import _coupler_point, _four_bar_at

__all__ = ["Cognates", "cognates"]


@dataclass(frozen=True)
class Cognates:
    """The two cognates' mechanism files and the third fixed pivot."""

    first: str  # pivots A0 and OC, driven at A0
    second: str  # pivots B0 and OC, driven at OC (in step with the original crank)
    third_pivot: np.ndarray


def _c(p) -> complex:
    return complex(p[0], p[1])


def _xy(z: complex) -> np.ndarray:
    return np.array([z.real, z.imag])


def cognates(mech: Mechanism, point, *, name: str | None = None) -> Cognates:
    """The Roberts–Chebyshev cognates of the four-bar `mech` for its coupler point `point` (a
    name or design coordinates), drawn in the original's design position."""
    at = mech.driver_input_at_design(mech.drivers[0])
    fb = _four_bar_at(mech, at, 1)
    _, _, C = _coupler_point(fb, mech, point)
    A0, A, B, B0, Cz = (_c(v) for v in (fb.A0, fb.A, fb.B, fb.B0, C))
    r2, r3, r4 = A - A0, B - A, B - B0
    lam = (Cz - A) / r3
    OC = A0 + lam * (B0 - A0)
    A1, D = A0 + lam * r3, Cz - (1 - lam) * r2
    E, F = B0 + (lam - 1) * r3, Cz - lam * r4
    base = name or mech.name

    def four_bar(k: int, pivots: tuple[str, str], pins: tuple[str, str], pts: dict, note: str) -> str:
        (p, q), (u, v) = pivots, pins
        return mechanism_file(
            name=f"{base}, cognate {k}", length_unit=fb.unit, speed="1 rad/s", driver=p,
            description=f"Roberts–Chebyshev cognate of '{mech.name}' on pivots {p} and {q}: its coupler "
                        f"point C traces the same curve{note}. Written by linkwork's synthesis.",
            points={name_: _xy(z) for name_, z in pts.items()},
            links={"frame": [p, q], "crank": [p, u], "coupler": [u, "C", v], "rocker": [v, q]},
            joints={p: ("revolute", ("frame", "crank"), ""), u: ("revolute", ("crank", "coupler"), ""),
                    v: ("revolute", ("coupler", "rocker"), ""), q: ("revolute", ("rocker", "frame"), "")})

    first = four_bar(1, ("A0", "OC"), ("A1", "D"), {"A0": A0, "OC": OC, "A1": A1, "C": Cz, "D": D}, "")
    second = four_bar(2, ("OC", "B0"), ("F", "E"), {"OC": OC, "B0": B0, "F": F, "C": Cz, "E": E},
                      ", in step with the original's crank")
    return Cognates(first, second, _xy(OC))
