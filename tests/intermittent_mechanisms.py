"""Geneva wheels built in Python (no file format involved), shared by the tests of the
kinematics, the poles, the structure and the files, and the closed form they are checked
against."""

from __future__ import annotations

import numpy as np

from linkwork.model import GenevaPair, Mechanism, Revolute

D = 100.0


def geneva(n: int, r: float | None = None, *, at: float = 0.0, centre: float = D) -> Mechanism:
    """Disc about M = (0, 0) with a pin B at radius r (default D·sin(π/n), shock-free), drawn at
    angle `at` from the line of centres; the wheel of n slots about C = (centre, 0); W marks a
    point of the wheel."""
    r = centre * np.sin(np.pi / n) if r is None else r
    return Mechanism.build(
        name=f"Geneva {n}", points={"M": [0, 0], "C": [centre, 0], "B": [r * np.cos(at), r * np.sin(at)],
                                    "W": [centre, 0.3 * centre]},
        links={"frame": ["M", "C"], "disc": ["M", "B"], "wheel": ["C", "W"]},
        joints=[Revolute("M", "M", ("frame", "disc")), Revolute("C", "C", ("frame", "wheel")),
                GenevaPair("G", ("disc", "wheel"), "B", n)],
        drivers=[{"joint": "M"}])


def tan_formula(phi, lam: float):
    """The wheel's turn from mid-engagement, against the driver's sense, at driver angle φ from
    the line of centres: tan ψ = λ sin φ/(1 − λ cos φ), λ = r/D (the slotted crank's formula,
    Pöschl §25a: the Geneva wheel is analysed like the slotted crank, §24)."""
    return np.arctan(lam * np.sin(phi) / (1.0 - lam * np.cos(phi)))
