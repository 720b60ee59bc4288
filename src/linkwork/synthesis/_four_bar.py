"""A four-bar of revolute pairs read from a `Mechanism` (by Grashof's loop roles) and drawn at one
input: what the designs built on a given four-bar (dwell, substitution, cognates) start from."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..model import Mechanism
from .positions import SynthesisError


@dataclass(frozen=True)
class _FourBar:
    """A four-bar of revolute pairs drawn at one input: its links' names by role, the fixed
    and moving pivots and every coupler point, where they are at that input."""

    frame: str
    crank: str
    coupler: str
    rocker: str
    A0: np.ndarray
    A: np.ndarray
    B: np.ndarray
    B0: np.ndarray
    coupler_points: dict  # name -> xy at the input (A and B among them)
    names: dict  # role -> point name of A0, A, B, B0
    unit: str
    solution: object


def _four_bar_at(mech: Mechanism, at: float, order: int) -> _FourBar:
    from ..kinematics import Status, solve
    from ..structure.grashof import loops

    found = [r for r in loops(mech) if r.chain == "four-bar"]
    if len(mech.links) != 4 or not found or len(mech.drivers) != 1:
        raise InputError(f"mechanism '{mech.name}': give a four-bar of revolute pairs with one driver")
    roles = found[0].links
    if mech.drivers[0].driven != roles["input"]:
        raise InputError(f"mechanism '{mech.name}': drive the four-bar at a frame pivot")

    def hinge(a, b):
        for j in mech.joints:
            if set(j.links) == {a, b}:
                return j.point
        raise InputError(f"mechanism '{mech.name}': no hinge between {a} and {b}")
    names = {"A0": hinge(roles["frame"], roles["input"]), "A": hinge(roles["input"], roles["coupler"]),
             "B": hinge(roles["coupler"], roles["output"]), "B0": hinge(roles["output"], roles["frame"])}
    sol = solve(mech, [float(at)], order=order)
    if sol.status[0] == Status.UNREACHABLE:
        raise SynthesisError(f"mechanism '{mech.name}' cannot be assembled at input {math.degrees(at):g}°")
    cp = {p: sol.point(p).position[0].copy() for p in mech.link(roles["coupler"]).points}
    return _FourBar(roles["frame"], roles["input"], roles["coupler"], roles["output"],
                    np.asarray(mech.points[names["A0"]], dtype=float), cp[names["A"]], cp[names["B"]],
                    np.asarray(mech.points[names["B0"]], dtype=float), cp, names, mech.length_unit, sol)


def _coupler_point(fb: _FourBar, mech: Mechanism, point) -> tuple[str, np.ndarray, np.ndarray]:
    """The coupler point's name, its design coordinates and where it is at the input."""
    if isinstance(point, str):
        if point not in fb.coupler_points:
            raise InputError(f"'{point}' is not a point of the coupler '{fb.coupler}'")
        return point, np.asarray(mech.points[point], dtype=float), fb.coupler_points[point]
    s = np.asarray(point, dtype=float)
    if s.shape != (2,) or not np.isfinite(s).all():
        raise InputError("give the coupler point as a name or as design coordinates x, y")
    return "C", s, fb.solution.point_on(fb.coupler, s).position[0].copy()


def _base(fb: _FourBar) -> tuple[dict, dict, dict]:
    n = fb.names
    pts = {n["A0"]: fb.A0, n["B0"]: fb.B0, **fb.coupler_points}
    links = {fb.frame: [n["A0"], n["B0"]], fb.crank: [n["A0"], n["A"]],
             fb.coupler: list(fb.coupler_points), fb.rocker: [n["B"], n["B0"]]}
    joints = {n["A0"]: ("revolute", (fb.frame, fb.crank), ""), n["A"]: ("revolute", (fb.crank, fb.coupler), ""),
              n["B"]: ("revolute", (fb.coupler, fb.rocker), ""), n["B0"]: ("revolute", (fb.rocker, fb.frame), "")}
    return pts, links, joints


def _fresh(name: str, taken) -> str:
    k, out = 1, name
    while out in taken:
        k += 1
        out = f"{name}{k}"
    return out
