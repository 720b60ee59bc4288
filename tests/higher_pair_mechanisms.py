"""Mechanisms with higher pairs built in Python (no file format involved), shared by the tests of
the kinematics, the poles and the files: an eccentric disc cam with each follower, and a disc
rolling on a fixed circle led by a crank and rod."""

from __future__ import annotations

import numpy as np

from linkwork.geometry.profiles import CircleProfile
from linkwork.model import CamContact, Mechanism, Prismatic, Revolute, RollingContact

E, R, RHO = 10.0, 30.0, 5.0


def eccentric(follower: str, *, offset: float = 0.0, radius: float = RHO) -> Mechanism:
    """Disc of radius R about E = (e, 0) on a cam turning about O; a follower translating along
    the vertical line x = offset carries a roller (radius ρ), a knife edge, or a horizontal flat
    face touching the disc from above."""
    reach = (R + radius) if follower == "roller" else R
    if follower == "flat":
        C = np.array([offset, R])
    else:
        C = np.array([offset, np.sqrt(reach**2 - (offset - E) ** 2)])
    joint = CamContact("K", ("cam", "follower"), "disc", follower, point="C",
                       radius=radius if follower == "roller" else 0.0,
                       axis=np.array([1.0, 0.0]) if follower == "flat" else None)
    return Mechanism.build(
        name=f"eccentric, {follower}", points={"O": [0, 0], "E": [E, 0], "C": C, "F": [offset, -20.0]},
        links={"frame": ["O"], "cam": ["O", "E"], "follower": ["C", "F"]},
        joints=[Revolute("O", "O", ("frame", "cam")),
                Prismatic("F", "F", ("frame", "follower"), np.array([0.0, 1.0])), joint],
        drivers=[{"joint": "O"}], profiles={"disc": CircleProfile((E, 0.0), R)})



ROLL_R0, ROLL_R, ROLL_O2, ROLL_CRANK, ROLL_ROD = 40.0, 10.0, np.array([70.0, 0.0]), 15.0, 45.0


def rolling_disc() -> Mechanism:
    """A disc (radius r) rolling without slip on a fixed circle (radius R0) about O; its centre W
    is led by a rod AW from a crank O2A."""
    R0, r, O2, crank, rod = ROLL_R0, ROLL_R, ROLL_O2, ROLL_CRANK, ROLL_ROD
    A = O2 + [0.0, crank]
    d = np.hypot(*A)
    a = ((R0 + r) ** 2 - rod**2 + d * d) / (2 * d)
    ex = A / d
    W = a * ex + np.sqrt((R0 + r) ** 2 - a * a) * np.array([-ex[1], ex[0]])
    return Mechanism.build(
        name="rolling disc", points={"O": [0, 0], "O2": O2, "A": A, "W": W, "M": W + [r, 0]},
        links={"frame": ["O", "O2"], "crank": ["O2", "A"], "rod": ["A", "W"], "disc": ["W", "M"]},
        joints=[Revolute("O2", "O2", ("frame", "crank")), Revolute("A", "A", ("crank", "rod")),
                Revolute("W", "W", ("rod", "disc")),
                RollingContact("T", ("frame", "disc"), ("track", "rim"))],
        drivers=[{"joint": "O2"}],
        profiles={"track": CircleProfile((0.0, 0.0), R0), "rim": CircleProfile(tuple(W), r)})
