"""Designs from a four-bar's curvature theory: Alt's dwell linkage (Pöschl §37) and Pröll's
substitution of a crank (Rosenauer §29).

**Alt's dwell linkage** (*Rastgetriebe nach H. Alt*). A coupler point C moves, near the chosen
input, on the osculating circle of its path about the centre of curvature K_C. A dyad C–K–E
with |CK| = ρ_C and a new frame pivot E keeps K at rest while C runs along that circle: the
output rocker E–K dwells there, its angular velocity and acceleration zero at the chosen input
(second order); a point C of the cubic of stationary curvature (circling points,
`instant.third_order.stationary_curvature`) makes the jerk vanish as well (third order).

**Pröll's substitution** (*Pröll, Regler*, Rosenauer §29): a crank A₀–A of the four-bar is
replaced by another, C₃–A₃, whose fixed pivot C₃ is chosen freely and whose moving pivot A₃ on
the coupler is C₃'s conjugate point by Euler–Savary (A₃ the point whose path has its centre of
curvature at C₃). The new four-bar has the same pole and inflection circle in this position, so
every coupler point's path has the same tangent and curvature: the coupler motion is the same
to second order. On the ray from the pole P through C₃ (unit e, |PC₃| = c, d = W − P with W the
inflection pole) Euler–Savary C = P − (d·r)/(|r|² − d·r)·r solved for r = t·e gives
t = c (d·e)/(c + d·e).

Both write a mechanism file drawn at the chosen input (its design position).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..model import Mechanism
from ._file import mechanism_file
from .positions import SynthesisError

__all__ = ["DwellLinkage", "Substitution", "alt_dwell", "proell_substitution"]


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


@dataclass(frozen=True)
class DwellLinkage:
    """Alt's six-bar: the four-bar, the dwell link C–K (length ρ_C) and the output rocker K–E."""

    text: str
    coupler_point: np.ndarray  # C where it is at the dwell
    centre: np.ndarray  # K_C, the centre of curvature of C's path
    pivot: np.ndarray  # E
    radius: float  # ρ_C
    input: float  # the input of the dwell (the file's design input)
    output_link: str

    def mechanism(self):
        from ..io import load_text

        return load_text(self.text, source="dwell linkage")


def alt_dwell(mech: Mechanism, at: float, point, *, pivot=None, name: str | None = None) -> DwellLinkage:
    """Alt's dwell linkage from the four-bar `mech` at input `at` (radians) and the coupler
    point `point` (a name or design coordinates): the six-bar's file, drawn at `at`. The output
    pivot E defaults to the point that puts the output rocker at right angles to the dwell link,
    as long as it (the best transmission at the dwell)."""
    from ..instant.curvature import curvature_centre

    fb = _four_bar_at(mech, at, 3)
    cname, design, C = _coupler_point(fb, mech, point)
    pc = curvature_centre(fb.solution, fb.coupler, design)
    K = pc.centre
    if not K.is_finite[0] or not np.isfinite(pc.radius[0]) or pc.radius[0] == 0:
        raise SynthesisError("the coupler point's path has no finite centre of curvature there (an "
                             "inflection or a cusp): choose another point or input")
    Kxy = K.xy[0]
    rho = float(pc.radius[0])
    if pivot is None:
        u = (Kxy - C) / rho
        E = Kxy + rho * np.array([-u[1], u[0]])
    else:
        E = np.asarray(pivot, dtype=float)
        if E.shape != (2,) or np.hypot(*(E - Kxy)) <= 1e-9 * rho:
            raise InputError("the output pivot must be a point x, y away from the centre of curvature")
    pts, links, joints = _base(fb)
    if cname == "C":
        cname = _fresh("C", pts)
        pts[cname] = C
        links[fb.coupler].append(cname)
    kname, ename = _fresh("K", pts), _fresh("E", pts)
    pts[kname], pts[ename] = Kxy, E
    dwell, out = _fresh("dwell_link", links), _fresh("output", links)
    links[fb.frame].append(ename)
    links[dwell] = [cname, kname]
    links[out] = [kname, ename]
    joints[_fresh(cname, joints)] = ("revolute", (fb.coupler, dwell), f'point = "{cname}"')
    joints[kname] = ("revolute", (dwell, out), "")
    joints[ename] = ("revolute", (out, fb.frame), "")
    drv = mech.drivers[0]
    desc = (f"Alt's dwell linkage (Pöschl §37) from '{mech.name}' at input {math.degrees(at):.6g}°: "
            f"the dwell link {cname}–{kname} is the radius of curvature ({rho:.6g}) of {cname}'s path, "
            f"the output {out} rests at this input. Written by linkwork's synthesis.")
    speed = _speed(mech)
    text = mechanism_file(name=name or f"{mech.name} with Alt's dwell", description=desc,
                          length_unit=fb.unit, points=pts, links=links, joints=joints,
                          driver=drv.joint, speed=speed)
    return DwellLinkage(text, C, Kxy, E, rho, float(at), out)


def _speed(mech: Mechanism) -> str:
    law = mech.drivers[0].law
    w = getattr(law, "speed", 1.0)
    return f"{float(w)!r} rad/s"


@dataclass(frozen=True)
class Substitution:
    """Pröll's substitution: the new crank C₃–A₃ in place of the old one."""

    text: str
    pivot: np.ndarray  # C₃
    moving_pivot: np.ndarray  # A₃, where it is at the input
    pole: np.ndarray
    inflection_pole: np.ndarray
    input: float

    def mechanism(self):
        from ..io import load_text

        return load_text(self.text, source="Pröll substitution")


def proell_substitution(mech: Mechanism, at: float, pivot, *, replace: str = "input",
                        name: str | None = None) -> Substitution:
    """Replace the input crank (or with `replace="output"` the rocker) of the four-bar `mech`
    at input `at` (radians) by a crank from the new fixed pivot `pivot` (x, y) to its conjugate
    point on the coupler: same pole, same inflection circle, the coupler's motion the same to
    second order. The new file is drawn at `at`, driven at the new crank (input) or as before;
    the old fixed pivot stays drawn as a point of the frame."""
    from ..instant.curvature import instant

    if replace not in ("input", "output"):
        raise InputError(f"replace the 'input' crank or the 'output' rocker, not '{replace}'")
    fb = _four_bar_at(mech, at, 2)
    ins = instant(fb.solution, fb.coupler)
    if ins.translating[0]:
        raise SynthesisError("the coupler translates at this input: its pole is at infinity")
    P, W = ins.pole.xy[0], ins.inflection_pole.xy[0]
    C3 = np.asarray(pivot, dtype=float)
    if C3.shape != (2,) or not np.isfinite(C3).all():
        raise InputError("give the new fixed pivot as x, y")
    v = C3 - P
    c = float(np.hypot(*v))
    scale = max(np.hypot(*(fb.B0 - fb.A0)), 1e-300)
    if c <= 1e-9 * scale:
        raise SynthesisError("the new pivot is the pole: its conjugate is not defined")
    e = v / c
    de = float(np.dot(W - P, e))
    if abs(c + de) <= 1e-12 * scale:
        raise SynthesisError("the new pivot lies on the return circle: its conjugate is at infinity "
                             "(a slider, not built)")
    t = c * de / (c + de)
    if abs(t) <= 1e-9 * scale:
        raise SynthesisError("the new pivot's conjugate is the pole (the pivot lies on the pole "
                             "tangent): the new crank would have no length")
    A3 = P + t * e
    pts, links, joints = _base(fb)
    n = fb.names
    a3, c3 = _fresh("A3", pts), _fresh("C3", pts)
    pts[a3], pts[c3] = A3, C3
    links[fb.coupler].append(a3)
    links[fb.frame].append(c3)
    driver = mech.drivers[0].joint
    if replace == "input":
        links[fb.crank] = [c3, a3]
        del joints[n["A0"]], joints[n["A"]]
        joints[c3] = ("revolute", (fb.frame, fb.crank), "")
        joints[a3] = ("revolute", (fb.crank, fb.coupler), "")
        driver = c3
    else:
        links[fb.rocker] = [a3, c3]
        del joints[n["B"]], joints[n["B0"]]
        joints[a3] = ("revolute", (fb.coupler, fb.rocker), "")
        joints[c3] = ("revolute", (fb.rocker, fb.frame), "")
    desc = (f"Pröll's substitution (Rosenauer §29) of the {replace} link of '{mech.name}' at input "
            f"{math.degrees(at):.6g}°: new pivot {c3}, its conjugate {a3} on the coupler (same pole and "
            "inflection circle). Written by linkwork's synthesis.")
    text = mechanism_file(name=name or f"{mech.name}, Pröll substitution", description=desc,
                          length_unit=fb.unit, points=pts, links=links, joints=joints, driver=driver,
                          speed=_speed(mech))
    return Substitution(text, C3, A3, P, W, float(at))
