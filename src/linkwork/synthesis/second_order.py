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

**To the third order** (`order=3`): the new crank's constraint |A₃ − C₃| = const then holds
for the old motion to the third order only if A₃'s path has four-point contact with its
osculating circle, i.e. A₃ is a circling point (on the cubic of stationary curvature,
`instant.third_order`) and C₃ its centre of curvature (on the centre-point curve). On each ray
from the pole the cubic has one point besides the pole, ρ = −3(b·e)(Jb·e)/(L·e) (b the
acceleration of the pole point, L = ω j_P − 3ω̇ b − 3ω² Jb), so the chosen pivot fixes the ray
and is moved along it onto the centre-point curve: c = t (d·e)/((d·e) − t) with t = ρ. Both
cranks then keep the old coupler motion, and with the same input motion its position,
velocity, acceleration and jerk agree.

Both write a mechanism file drawn at the chosen input (its design position).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..model import Mechanism
from ._file import mechanism_file
from ._four_bar import _base, _coupler_point, _four_bar_at, _fresh
from .positions import SynthesisError

__all__ = ["DwellLinkage", "Substitution", "alt_dwell", "proell_substitution"]


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
    order: int = 2

    def mechanism(self):
        from ..io import load_text

        return load_text(self.text, source="Pröll substitution")


def proell_substitution(mech: Mechanism, at: float, pivot, *, replace: str = "input",
                        order: int = 2, name: str | None = None) -> Substitution:
    """Replace the input crank (or with `replace="output"` the rocker) of the four-bar `mech`
    at input `at` (radians) by a crank from the new fixed pivot `pivot` (x, y) to its conjugate
    point on the coupler: same pole, same inflection circle, the coupler's motion the same to
    second order. With `order=3` the pivot is moved along its ray from the pole onto the
    centre-point curve (module docstring): the motion is the same to the third order. The new
    file is drawn at `at`, driven at the new crank (input) or as before; the old fixed pivot
    stays drawn as a point of the frame."""
    from ..instant.curvature import instant

    if replace not in ("input", "output"):
        raise InputError(f"replace the 'input' crank or the 'output' rocker, not '{replace}'")
    if order not in (2, 3):
        raise InputError(f"order {order}: Pröll's substitution keeps the motion to order 2 or 3")
    fb = _four_bar_at(mech, at, order)
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
    if order == 3:
        c = _centre_point_on_ray(fb, e, de, scale)
        C3 = P + c * e
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
    kept = ("same pole and inflection circle" if order == 2 else
            "a circling point and its centre of curvature: the coupler motion kept to the third order")
    desc = (f"Pröll's substitution (Rosenauer §29) of the {replace} link of '{mech.name}' at input "
            f"{math.degrees(at):.6g}°: new pivot {c3}, its conjugate {a3} on the coupler ({kept}). "
            "Written by linkwork's synthesis.")
    text = mechanism_file(name=name or f"{mech.name}, Pröll substitution", description=desc,
                          length_unit=fb.unit, points=pts, links=links, joints=joints, driver=driver,
                          speed=_speed(mech))
    return Substitution(text, C3, A3, P, W, float(at), order)


def _centre_point_on_ray(fb, e: np.ndarray, de: float, scale: float) -> float:
    """The signed distance c from the pole along the world direction e of the centre of
    curvature of the circling point on that ray (module docstring)."""
    from ..instant.third_order import stationary_curvature

    cubic = stationary_curvature(fb.solution, fb.coupler)
    t3, rm = cubic.third, cubic.motion
    el = rm.to_local(rm.to_world(t3.P) + e[None, :]) - t3.P  # e in the coupler-relative frame
    b, L = t3.b[0], t3.L[0]
    Jb = np.array([-b[1], b[0]])
    den = float(L @ el[0])
    if abs(den) <= 1e-12 * np.hypot(*L):
        raise SynthesisError("the cubic of stationary curvature meets this ray only at infinity (its "
                             "asymptote's direction): choose a pivot in another direction")
    t = -3 * float(b @ el[0]) * float(Jb @ el[0]) / den
    if abs(t) <= 1e-9 * scale:
        raise SynthesisError("the circling point on this ray is the pole (the ray is the pole tangent or "
                             "normal): choose a pivot in another direction")
    if abs(de - t) <= 1e-12 * scale:
        raise SynthesisError("the circling point on this ray lies on the inflection circle (the Ball "
                             "point): its centre of curvature is at infinity, a slider, not built")
    return t * de / (de - t)
