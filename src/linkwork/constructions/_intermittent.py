"""The velocity and acceleration plans of an intermittent pair (Geneva wheel, star wheel), for
:mod:`._plan`'s walk through the groups.

Owns :func:`velocity_images` and :func:`acceleration_images`: the wheel's second image after the
image of its pivot C, in the phase each sample is in (the pair's phase is the position's given
datum, read off the drive's schedule at the driver's angle):

* a pin B of the driver on a radial slot of the wheel (Geneva engaged; star-wheel entry and
  exit): "analysed exactly like the slotted crank" (Pöschl §25a). The wheel's point B* under the
  pin turns about C, v_B* ⟂ CB, and the pin slides along the slot, v_B − v_B* ∥ CB; for the
  accelerations a_B = a_B* + 2ω_wheel × v_rel (Coriolis) + a_rel (∥ slot), a_B* = a_C +
  ω²·BC + a^t (⟂ CB);
* the pin gear of a star wheel (*Triebstockverzahnung*, Pöschl §25b): the pitch circles (r about
  the driver's pivot M, D − r about C) roll at the pitch point T on MC, so the wheel's point at T
  has the driver's velocity, and the accelerations of the two points at T differ along MC only
  (the rolling circles' contact points have equal tangential accelerations);
* the rest (*Rast*, the locking arc holds the wheel): the wheel does not turn relative to the
  carrier, whose images it takes.
"""

from __future__ import annotations

import numpy as np

from ..model import Revolute
from ..model.intermittent import DWELL, GEAR, PHASES, SLOT_PHASES, indexing_schedule
from ..topology.constructibility import lower, pitch_point_name, upper
from ._common import norm, perp

#: the Pöschl section of each drive
_SOURCE = {"geneva": "Geneva wheel, Pöschl §25a", "star-wheel": "star wheel, Pöschl §25b"}


class PairPhases:
    """What the plans need of the pair at each sample: driver, wheel, carrier and their pivots;
    the phase; on a slot the pin (its position), in the pin gear the pitch point T."""

    def __init__(self, mech, sol, pos, j) -> None:
        self.j, self.name = j, j.name
        self.driver, self.wheel, self.carrier = j.links[0], j.links[1], j.carrier
        self.M, self.C = (next(r.point for r in mech.joints if isinstance(r, Revolute)
                               and set(r.links) == {ln, j.carrier}) for ln in j.links)
        sch = indexing_schedule(mech, j)
        rep = sol.joint(j.name)
        self.kind = np.asarray(rep["phase"])
        _, _, idx = sch.locate(np.asarray(rep["driver_angle"], float))
        n = len(sol)
        pins = np.array([p.pin or "" for p in sch.phases], dtype=object)[idx]
        radius = np.array([p.radius for p in sch.phases])[idx]
        self.slot = np.isin(self.kind, SLOT_PHASES)
        self.gear = self.kind == GEAR
        self.dwell = self.kind == DWELL
        self.pins = [p for p in sch.pins if np.any(self.slot & (pins == p))]
        self.pin_of = {p: self.slot & (pins == p) for p in self.pins}
        Mx, Cx = pos[self.M], pos[self.C]
        self.B = np.full((n, 2), np.nan)
        for p, on in self.pin_of.items():
            self.B[on] = pos[p][on]
        self.T_name = pitch_point_name(mech, j)
        D = norm(Cx - Mx)
        with np.errstate(invalid="ignore", divide="ignore"):
            T = Mx + (radius / D)[:, None] * (Cx - Mx)
        self.T = np.where(self.gear[:, None], T, np.nan)
        self.r = radius
        # at rest: a point of the wheel other than its pivot (or one a length away)
        other = [p for p in mech.link(self.wheel).points if p != self.C]
        self.R_name = other[0] if other else f"{self.C}+"
        R = pos[other[0]] if other else Cx + np.array([mech.length_scale, 0.0])
        self.R = np.where(self.dwell[:, None], R, np.nan)
        # the wheel's second point, named after the one phase the samples are in
        one = [k for k, m in (("slot", self.slot), ("gear", self.gear), ("dwell", self.dwell)) if m.any()]
        if one == ["slot"] and len(self.pins) == 1:
            self.second = self.pins[0] + "*"
        elif one == ["gear"]:
            self.second = self.T_name
        elif one == ["dwell"]:
            self.second = self.R_name
        else:
            self.second = f"{self.wheel}*"
        self.X2 = np.where(self.slot[:, None], self.B, np.where(self.gear[:, None], self.T, self.R))
        with np.errstate(invalid="ignore", divide="ignore"):
            self.axis = (self.B - Cx) / norm(self.B - Cx)[:, None]  # the slot's, radial
        self.source = _SOURCE.get(j.kind, j.kind)

    def at_pins(self, n: int, value) -> np.ndarray:
        """``value(pin)`` (N, 2) of the pin on the slot at each sample (NaN off the slots)."""
        out = np.full((n, 2), np.nan)
        for q, on in self.pin_of.items():
            out = np.where(on[:, None], value(q), out)
        return out

    def pin_words(self) -> str:
        return ", ".join(upper(p) for p in self.pins)

    def phases_named(self) -> str:
        return ", ".join(dict.fromkeys(PHASES[k] for k in self.kind if k >= 0))


def _mask(on: np.ndarray, a: np.ndarray) -> np.ndarray:
    return np.where(on[:, None], a, np.nan)


def _select(n: int, *parts) -> np.ndarray:
    """The per-sample value of the phase each sample is in (NaN where none)."""
    out = np.full((n, 2), np.nan)
    for on, v in parts:
        out = np.where(on[:, None], v, out)
    return out


def velocity_images(vc, gs) -> None:
    """The wheel's images in a `VelocityConstruction` (polar plan or rotated velocities)."""
    p = PairPhases(vc.mech, vc.sol, vc.pos, gs.parts["pair"])
    n, C, W, Dr = vc.n, vc.pos[p.C], p.wheel, p.driver
    c = vc.image(p.carrier, p.C)
    plan = vc.mode == "plan"
    parts = []
    if p.slot.any():
        B = p.B
        pin_img = p.at_pins(n, lambda q: vc.image(Dr, q))
        lab = (vc.lbl(p.pins[0]) if len(p.pins) == 1 else "b") + "*"
        pins = p.pin_words()
        vc.b.step(
            f"The pin {pins} of {Dr} runs in a radial slot of the wheel {W} ({p.source}: as in the "
            f"slotted crank). The wheel's point {pins}* under the pin turns about {upper(p.C)}: "
            f"v* \u27c2 {upper(p.C)}{pins}; the pin slides along the slot: v_{pins} \u2212 v* \u2225 "
            f"{upper(p.C)}{pins}. Through {vc.lbl(p.C)} draw the {vc.rel_words()} to "
            f"{upper(p.C)}{pins}, through the pin's image the {'parallel' if plan else 'perpendicular'} "
            f"to the slot; they meet in {lab}.")
        img = vc._slide(f"v.{W}.{p.name}.slot", B, _mask(p.slot, c), B - C, pin_img, p.axis, lab,
                        f"wheel {W}")
        parts.append((p.slot, img))
    if p.gear.any():
        T = p.T
        t = p.T_name
        img = vc.image(Dr, t, T)  # the driver's point at T, drawn first
        vc.b.step(
            f"Pin gear of the star wheel {W} ({p.source}): the pitch circles about "
            f"{upper(p.M)} and {upper(p.C)} roll at the pitch point {upper(t)} on "
            f"{upper(p.M)}{upper(p.C)} ({upper(p.M)}{upper(t)} = r, the pins' pitch radius), the "
            f"wheel's and the driver's relative pole: the wheel's point at {upper(t)} has the "
            f"velocity of the driver's point there: the wheel's image at {upper(t)} is {vc.lbl(t)}.")
        vc._point(f"v.{W}.{p.name}.gear", _mask(p.gear, img), vc.lbl(t))
        parts.append((p.gear, img))
    if p.dwell.any():
        R = p.R
        vc.b.step(f"The wheel {W} rests (its locking arc holds it on {p.carrier}): it does not turn "
                  f"relative to {p.carrier}, its points' images are {p.carrier}'s: "
                  f"{vc.lbl(p.R_name)} = the image of {p.carrier}'s point at {upper(p.R_name)}.")
        img = vc.image(p.carrier, f"{p.R_name}@{p.carrier}", R, draw=False)
        parts.append((p.dwell, img))
    vc.set_known(W, C, c, p.C)
    vc.set_known(W, p.X2, _select(n, *parts), p.second)


def acceleration_images(ac, gs) -> None:
    """The wheel's acceleration images in an `AccelerationConstruction` (its velocity plan
    drawn)."""
    vc = ac.vc
    p = PairPhases(ac.mech, ac.sol, ac.pos, gs.parts["pair"])
    n, C, W, Dr = ac.n, ac.pos[p.C], p.wheel, p.driver
    c = ac.image(p.carrier, p.C)
    w = ac.w(W)
    parts = []
    if p.slot.any():
        B = p.B
        pin_img = p.at_pins(n, lambda q: ac.image(Dr, q))
        v_pin = p.at_pins(n, lambda q: vc.velocity(vc.pos[q], vc.images[(Dr, q)]))
        v_rel = v_pin - vc.velocity(p.X2, vc.images[(W, p.second)])
        cor = 2 * w[:, None] * perp(v_rel)
        pins = p.pin_words()
        lab = (ac.lbl(p.pins[0]) if len(p.pins) == 1 else "b'") + "*"
        ac.b.step(
            f"The wheel's point {pins}* under the pin ({p.source}): a_{pins} = a* + "
            f"2\u03c9_{W}\u00d7v_rel (Coriolis, v_rel from the velocity plan) + a_rel (\u2225 slot), "
            f"a* = a_{upper(p.C)} + \u03c9\u00b2\u00b7{pins}{upper(p.C)} + a^t (\u27c2 "
            f"{upper(p.C)}{pins}): from {ac.lbl(p.C)} lay off the normal component towards "
            f"{upper(p.C)} and draw the perpendicular to {upper(p.C)}{pins}; from the pin's image "
            f"take away the Coriolis component and draw the parallel to the slot; they meet in {lab}.")
        img = ac._slide(f"a.{W}.{p.name}.slot", B, _mask(p.slot, c), C, pin_img, -cor, p.axis, w, lab)
        parts.append((p.slot, img))
    if p.gear.any():
        T, t = p.T, p.T_name
        t_driver = ac.image(Dr, t, T)
        ac.b.step(
            f"Pin gear ({p.source}): the wheel's and the driver's points at the pitch point "
            f"{upper(t)} have equal tangential accelerations (the pitch circles roll), so they "
            f"differ along {upper(p.M)}{upper(p.C)}. From {ac.lbl(p.C)} lay off "
            f"\u03c9\u00b2\u00b7{upper(t)}{upper(p.C)} towards {upper(p.C)} and draw the "
            f"perpendicular to {upper(p.C)}{upper(t)}; through the driver's {ac.lbl(t)} draw the "
            f"parallel to {upper(p.M)}{upper(p.C)}; they meet in the wheel's {ac.lbl(t)}.")
        with np.errstate(invalid="ignore", divide="ignore"):
            axis = (C - T) / norm(C - T)[:, None]
        img = ac._slide(f"a.{W}.{p.name}.gear", T, _mask(p.gear, c), C, t_driver, np.zeros((n, 2)),
                        axis, w, lower(t) + "'")
        parts.append((p.gear, img))
    if p.dwell.any():
        ac.b.step(f"The wheel {W} rests on {p.carrier}: its acceleration images are {p.carrier}'s.")
        parts.append((p.dwell, ac.image(p.carrier, f"{p.R_name}@{p.carrier}", p.R, draw=False)))
    ac.set_known(W, C, c, p.C)
    ac.set_known(W, p.X2, _select(n, *parts), p.second)
