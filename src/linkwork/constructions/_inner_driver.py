"""A group driven from inside: the double slider (*Kreuzschieber*, the elliptic trammel or
ellipsograph) turned at a hinge between its rod and one of its blocks, for :mod:`._plan`.

Owns :func:`velocity_images` and :func:`acceleration_images`. Two blocks S₁, S₂ slide on guides
of links G₁, G₂ solved before (the frame's two guides in the ellipsograph) and are hinged at A
and B to the rod AB; the input turns the rod against its block. Each block turns with its guide,
so the rod's angular velocity ω = ω_G + the input's rate is given, and with it the relative
velocity v_BA = ω·AB ⟂ AB (and the relative acceleration a_BA = α·AB ⟂ AB + ω²·BA towards A,
α = α_G + the input's angular acceleration). The velocity plan is then the textbook triangle: a
lies on the line through the image a* of G₁'s point at A along guide 1, b = a + v_BA on the line
through b* along guide 2, so the second line moved back by v_BA cuts the first in a (Rosenauer
§40–42, Pöschl §47: a velocity polygon with one known side). The acceleration plan is the same
triangle with a_BA for v_BA and the Coriolis components 2ω_G × v_rel at the guides (Pöschl
§47–48).
"""

from __future__ import annotations

import numpy as np

from ..model import Prismatic, Revolute
from ..topology.constructibility import upper
from ._common import perp
from .construction import Role


class _DoubleSlider:
    """The parts, or `ok` False where the group is no double slider driven at a rod's hinge."""

    def __init__(self, con, group, solved: set[str]) -> None:
        mech = con.mech
        self.ok = False
        if len(group.links) != 3 or len(group.drivers) != 1:
            return
        d = next(d for d in mech.drivers if d.joint == group.drivers[0])
        joints = [mech.joint(n) for n in group.joints]
        links = set(group.links)
        slides = [j for j in joints if isinstance(j, Prismatic)]
        hinges = [j for j in joints if isinstance(j, Revolute)]
        if len(slides) != 2 or len(hinges) != 2 or len(joints) != 4:
            return
        blocks = {}
        for s in slides:
            G, S = s.links
            if G in links and S not in links:
                G, S = S, G
            if G not in solved or S not in links:
                return
            blocks[S] = (s, G)
        rods = links - set(blocks)
        if len(rods) != 1 or len(blocks) != 2:
            return
        (rod,) = rods
        ends = {}
        for h in hinges:
            S = next((ln for ln in h.links if ln in blocks), None)
            if S is None or rod not in h.links or S in ends:
                return
            ends[S] = h.point
        j = mech.joint(d.joint)
        if not isinstance(j, Revolute) or {d.driven, d.base} != set(j.links) or rod not in j.links:
            return
        first = d.base if d.driven == rod else d.driven  # the block the rod turns against
        second = next(S for S in blocks if S != first)
        self.mech, self.rod, self.driver = mech, rod, d
        self.S = (first, second)
        self.A, self.B = ends[first], ends[second]
        self.slide = (blocks[first][0], blocks[second][0])
        self.G = (blocks[first][1], blocks[second][1])
        # the input's rate: the rod against its block (given data, as a crank's ω)
        sign = 1.0 if d.driven == rod else -1.0
        sol = con.sol
        self.rate = sign * (sol.link(d.driven).omega - sol.link(d.base).omega)
        self.rate2 = sign * (sol.link(d.driven).alpha - sol.link(d.base).alpha) if sol.order >= 2 else None
        self.ok = True

    def axis(self, con, k: int) -> np.ndarray:
        return con._axis(self.G[k], self.slide[k].axis)

    def words(self) -> dict[str, str]:
        (S1, S2), (P1, P2) = self.S, self.slide
        G1 = self.G[0]
        turns = (f"{S1} slides on the frame and does not turn" if G1 == self.mech.frame else
                 f"{S1} turns with {G1}")
        return dict(A=upper(self.A), B=upper(self.B), R=self.rod, S1=S1, S2=S2, P1=P1.name,
                    P2=P2.name, turns=turns, J=upper(self.driver.joint))


def _blocks(con, ds, imgs, guide_imgs) -> None:
    """The rod's and the blocks' images: each block moves like its guide plus the sliding."""
    mech = con.mech
    for k, (S, X) in enumerate(zip(ds.S, (ds.A, ds.B))):
        P = con.pos[X]
        con.set_known(ds.rod, P, imgs[k], X)
        con.set_known(S, P, imgs[k], X)
        X2 = P + ds.axis(con, k) * mech.length_scale
        g2 = con.image(ds.G[k], f"{X}+@{ds.G[k]}", X2, draw=False)
        con.set_known(S, X2, g2 + (imgs[k] - guide_imgs[k]), X + "+")


def velocity_images(vc, group, solved: set[str]) -> bool:
    """Draw the group's images in the `VelocityConstruction` ``vc``; False if it is no double
    slider driven at a rod's hinge (the caller then refuses, naming the driver)."""
    ds = _DoubleSlider(vc, group, solved)
    if not ds.ok:
        return False
    A, B = vc.pos[ds.A], vc.pos[ds.B]
    w = vc.measured_omega(ds.G[0]) + ds.rate
    sa = vc.image(ds.G[0], f"{ds.A}@{ds.G[0]}", A, draw=False)
    sb = vc.image(ds.G[1], f"{ds.B}@{ds.G[1]}", B, draw=False)
    rel = (vc.base(B) - vc.base(A)) + vc.kv * vc.M(w[:, None] * perp(B - A))
    e1, e2 = ds.axis(vc, 0), ds.axis(vc, 1)
    plan = vc.mode == "plan"
    a, b = vc.lbl(ds.A), vc.lbl(ds.B)
    par = "parallel" if plan else "perpendicular"
    vc.b.step("Double slider (elliptic trammel) driven at the hinge {J}: {turns}, so the rod {R} "
              "turns at \u03c9 = the input's rate + \u03c9_{S1} and v_{B}{A} = \u03c9\u00b7{A}{B} "
              "\u27c2 {A}{B} is known. v_{A} = v_{A}* + v_slide (\u2225 {P1}), v_{B} = v_{A} + v_{B}{A} = "
              "v_{B}* + v_slide (\u2225 {P2}): lay off v_{B}{A} ({rel} to {A}{B}); through the image of "
              "{A}* draw the {par} to {P1}, through the image of {B}* moved back by v_{B}{A} the {par} "
              "to {P2}; they meet in {a}, and {b} = {a} + v_{B}{A}.".format(
                  rel=vc.rel_words(), par=par, a=a, b=b, **ds.words()))
    key = f"v.{ds.rod}.{ds.A}"
    vc._line(key + ".1", sa, vc.M(e1))
    vc._line(key + ".2", sb - rel, vc.M(e2))
    from ._plan import _meet
    ia, bad = _meet((sa, vc.M(e1)), (sb - rel, vc.M(e2)))
    vc.b.degenerate(bad & ~vc.b.bad, f"the guides {ds.slide[0].name} and {ds.slide[1].name} are "
                    "parallel: the blocks' velocities are undetermined")
    vc._point(key, ia, a, lines=(key + ".1", key + ".2"))
    ib = ia + rel
    vc.b.arrow(key + ".rel", _pt(ia), _pt(ib), Role.AUXILIARY, f"v_{upper(ds.B)}{upper(ds.A)}", space=vc.space)
    vc._point(f"v.{ds.rod}.{ds.B}", ib, b, lines=(key + ".2",))
    _blocks(vc, ds, (ia, ib), (sa, sb))
    for k, (X, img, g) in enumerate(((ds.A, ia, sa), (ds.B, ib, sb))):
        vc.sliding[ds.slide[k].name] = vc.velocity(vc.pos[X], img) - vc.velocity(vc.pos[X], g)
    return True


def acceleration_images(ac, group, solved: set[str]) -> bool:
    """The same triangle on accelerations in the `AccelerationConstruction` ``ac``."""
    ds = _DoubleSlider(ac, group, solved)
    if not ds.ok:
        return False
    vc = ac.vc
    A, B = ac.pos[ds.A], ac.pos[ds.B]
    w = vc.measured_omega(ds.rod)
    alpha = ac.measured_alpha(ds.G[0]) + ds.rate2
    rel = alpha[:, None] * perp(B - A) + (w * w)[:, None] * (A - B)
    ends = []
    for k, X in enumerate((ds.A, ds.B)):
        G = ds.G[k]
        g = ac.image(G, f"{X}@{G}", ac.pos[X], draw=False)
        cor = 2 * ac.w(G)[:, None] * perp(vc.sliding[ds.slide[k].name])
        ac.coriolis[ds.slide[k].name] = cor
        ends.append((g, cor))
    (ga, ca), (gb, cb) = ends
    e1, e2 = ds.axis(ac, 0), ds.axis(ac, 1)
    a, b = ac.lbl(ds.A), ac.lbl(ds.B)
    ac.b.step("Accelerations of the double slider: the rod turns at \u03c9 (from the velocity plan) "
              "with \u03b1 = the input's angular acceleration + \u03b1_{S1}, so a_{B}{A} = "
              "\u03b1\u00b7{A}{B} (\u27c2 {A}{B}) + \u03c9\u00b2\u00b7{B}{A} (towards {A}) is known. "
              "a_{A} = a_{A}* + 2\u03c9\u00d7v_rel (Coriolis) + a_rel (\u2225 {P1}), a_{B} = a_{A} + "
              "a_{B}{A} = a_{B}* + Coriolis + a_rel (\u2225 {P2}): through the end of {A}*'s "
              "acceleration and Coriolis component draw the parallel to {P1}; through {B}*'s moved "
              "back by a_{B}{A} the parallel to {P2}; they meet in {a}, and {b} = {a} + "
              "a_{B}{A}.".format(a=a, b=b, **ds.words()))
    key = f"a.{ds.rod}.{ds.A}"
    s1 = ac._component(key + ".cor1", ga, ca, "a_cor", kind="coriolis") if np.any(ca) else ga
    s2 = ac._component(key + ".cor2", gb, cb, "a_cor", kind="coriolis") if np.any(cb) else gb
    ac._line(key + ".1", s1, e1)
    ac._line(key + ".2", s2 - rel, e2)
    from ._plan import _meet
    ia, bad = _meet((s1, e1), (s2 - rel, e2))
    ac.b.degenerate(bad & ~ac.b.bad, f"the guides {ds.slide[0].name} and {ds.slide[1].name} are "
                    "parallel: the blocks' accelerations are undetermined")
    ib = ia + rel
    ac.b.point(key, _pt(ia), label=a, space=ac.space)
    ac.b.extend(key + ".1", _pt(ia))
    ac.b.extend(key + ".2", _pt(ia))
    ac._component(key + ".rel", ia, rel, f"a_{upper(ds.B)}{upper(ds.A)}")
    ac.b.point(f"a.{ds.rod}.{ds.B}", _pt(ib), label=b, space=ac.space)
    _blocks(ac, ds, (ia, ib), (ga, gb))
    return True


def _pt(xy):
    from .construction import pt
    return pt(xy)
