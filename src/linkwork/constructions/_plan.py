"""The engine behind the velocity and acceleration constructions of whole mechanisms.

Owns :class:`VelocityConstruction` (images of the points' velocities, built group by group in
the structural solution order: the polar velocity plan — *Geschwindigkeitsplan*, *polārais
ātrumu plāns* — or Rosenauer's rotated ("orthogonal", *gedrehte*) velocities on the mechanism
itself) and :class:`AccelerationConstruction` (the polar acceleration plan with normal,
tangential and Coriolis components). The public constructions are in
:mod:`.velocity_plan`, :mod:`.rotated_velocities` and :mod:`.acceleration_plan`.

Velocity images. In the polar plan the image of point X is x = o + v_X (o the plan's pole, the
plan drawn at the velocity scale). With rotated velocities the "image" is the tip of the velocity
turned by 90° clockwise and laid off at X at the scale kv: X' = X + kv·R(v_X). Both obey the same
rules, which are all a ruler needs:

* two points X, Y of one link: y − x ⟂ XY in the plan (x'Y' ∥ XY for rotated velocities:
  Rosenauer §38, Pöschl §27 — tips of a link's points lie on a line parallel to the link);
* a point sliding on a guide: its image and the image of the coincident point of the guide
  differ along the guide in the plan (perpendicular to it for rotated velocities);
* a point of the frame has the image o (X' = X).

Each group of the solution order (driver, RRR, RRP, RPR, rod in slot, slotted lever — the
dyads and one-link groups of :mod:`linkwork.structure`) gives its unknown images as the
intersection of two such lines. A link with two known images gives the image of any other of
its points by two more lines (the velocity image *Geschwindigkeitsbild* is similar to the link);
for a point on the line of the two it uses the link's angular velocity measured off the plan.

Accelerations: a_Y = a_X + ω²·YX (normal, towards X) + α ⟂ XY (tangential) for two points of
one link, and a_Y = a_{Y∈G} + a_rel (along the guide) + 2ω_G × v_rel (Coriolis) for a point
sliding on a guide link G. The normal and Coriolis components are laid off from the lengths
measured in the velocity plan (v²/l, 2ωv); the two unknown magnitudes come from intersecting
two lines, as in every textbook acceleration plan (Rosenauer ch. XIII, Pöschl §47–48).
"""

from __future__ import annotations

import numpy as np

from .construction import Builder, Role, pt
from ..errors import InputError
from ..geometry import Point
from ..kinematics import Solution
from ..kinematics.solver import plan as group_plan
from ..model import Mechanism, Revolute
from ..topology.constructibility import lower, upper  # the books' labels: B → b, O4 → o_4
from ._common import cross, dot, farthest_apart, norm, perp, rotate


def _meet(l1: np.ndarray, l2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Intersection (N,2) of lines given as (point (N,2), direction (N,2)) pairs; mask parallel."""
    (p, u), (q, v) = l1, l2
    den = cross(u, v)
    par = abs(den) <= 1e-12 * norm(u) * norm(v)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = cross(q - p, v) / den
        x = p + t[:, None] * u
    return np.where(par[:, None], np.nan, x), par


class _SlidingGroups:
    """The groups in which a link turns about a known hinge while one of its points slides on a
    guide: the rod in a slot and the RRP dyad (a point of the rod slides along the guide of a
    link G), the slotted lever and the RPR dyad (the lever carries the guide, the pin on it is
    known). In both constructions each is the same sequence — the two given images, one step,
    the intersection of the line about the hinge with the line along the guide, the images on
    the block — so it is written once here; a construction supplies the words of its steps
    (`SLIDING_STEPS`, `_sliding_words`), the intersection (`_sliding_image`) and what it keeps
    of the sliding (`_slid`). The walk through the groups (`_walk`) is theirs in common too."""

    SLIDING_STEPS: dict[str, str]
    #: the construction's name in messages, and the name of its dict of the rates (ω or α) it
    #: reads off two images of a link
    WHAT: str
    RATES: str

    def set_known(self, link: str, X: np.ndarray, image: np.ndarray, name: str) -> None:
        self.known.setdefault(link, []).append((X, image, name))
        self.images[(link, name)] = image
        if link in self._read_off:  # a further point: the rate is read off again (maybe farther apart)
            self._read_off.discard(link)
            getattr(self, self.RATES).pop(link, None)

    def two_known(self, link: str):
        """The two known images of ``link`` farthest apart (`farthest_apart`)."""
        known = self.known.get(link, [])
        if len(known) < 2:
            raise InputError(f"the {self.WHAT} has no two points of link '{link}' yet")
        i, j = farthest_apart([X for X, _, _ in known])
        return known[i], known[j]

    def _walk(self, groups, fallback, measured) -> None:
        """Each group in solution order by the construction's own step for its kind
        (`_g_<kind>`) or, without one, by `fallback(group, links solved so far)`; then the image
        of every remaining point and the measured rate (`measured`) of every link."""
        solved = {self.mech.frame}
        for gs in groups:
            fn = getattr(self, "_g_" + gs.kind.replace("-", "_"), None)
            if fn is not None:
                fn(gs)
            else:
                fallback(gs.group, solved)
            solved.update(gs.group.links)
        for link in self.mech.links:
            if link.name == self.mech.frame:
                continue
            for p in link.points:
                self.image(link.name, p)
            measured(link.name)

    def _other(self, j, link: str) -> str:
        return j.links[1] if j.links[0] == link else j.links[0]

    def _slid(self, joint, X: str, pin_img: np.ndarray, guide_img: np.ndarray) -> None:
        """Keep the sliding at X (the pin's image less the guide's); the acceleration plan takes
        it from its velocity plan instead."""

    def _axis(self, guide_link: str, axis) -> np.ndarray:
        th = self.sol.pose_derivatives(guide_link)[0, :, 2]
        a = rotate(th, np.broadcast_to(np.asarray(axis, float), (self.n, 2)))
        return a / norm(a)[:, None]

    def _g_rod_in_slot(self, gs) -> None:
        p = gs.parts
        G = p["line"].links[0]
        self._sliding_group(gs.kind, p["rod"], p["pivot"], p["line"], p["line"].point, G, G)

    def _g_RRP(self, gs) -> None:
        p = gs.parts
        G = p["guide"].links[0]
        self._sliding_group(gs.kind, p["rod"], p["pivot"], p["guide"], p["hinge"].point, G, G, p["block"])

    def _g_slotted_lever(self, gs) -> None:
        p = gs.parts
        line, lever = p["line"], p["lever"]
        self._sliding_group(gs.kind, lever, p["pivot"], line, line.point, lever, line.links[1])

    def _g_RPR(self, gs) -> None:
        p = gs.parts
        pin, lever, block = p["pin"], p["lever"], p["block"]
        self._sliding_group(gs.kind, lever, p["pivot"], p["guide"], pin.point, lever,
                            self._other(pin, block), block)

    def _sliding_group(self, kind: str, link: str, pivot, joint, X: str, guide: str, given: str,
                       block: str | None = None) -> None:
        """``link`` turns about the hinge ``pivot``; its point ``X`` slides along the axis of
        ``joint`` fixed in ``guide``. If ``guide`` is another link (rod), the given image at X is
        that of guide's coincident point and the constructed one is the rod's; if ``link`` is
        the guide itself (lever), the given image is the pin's on ``given`` and the constructed
        one is the lever's point under it (starred). A ``block`` (RRP, RPR) is hinged at X to
        the pin's side and turns with the guide."""
        on_guide = link == guide
        A, P = self.pos[pivot.point], self.pos[X]
        pivot_img = self.image(self._other(pivot, link), pivot.point)
        given_img = (self.image(given, X) if on_guide else
                     self.image(guide, f"{X}@{guide}", P, label=self.lbl(X) + "*"))
        axis = self._axis(guide, joint.axis)
        lab = self.lbl(X) + ("*" if on_guide else "")
        self.b.step(self.SLIDING_STEPS[kind].format(
            X=upper(X), P=upper(pivot.point), p=self.lbl(pivot.point), x=self.lbl(X), lab=lab,
            link=link, G=guide, block=block, **self._sliding_words(guide)))
        img = self._sliding_image(link, guide, joint, X, A, pivot_img, given_img, axis, lab)
        self.set_known(link, A, pivot_img, pivot.point)
        self.set_known(link, P, img, f"{X}@{link}" if on_guide else X)
        # images on the pin's side and on the guide at X: the sliding is their difference
        pin_img, guide_img = (given_img, img) if on_guide else (img, given_img)
        if block is not None:
            # the block moves like the guide link plus the common sliding
            shift = pin_img - guide_img
            self.set_known(block, P, pin_img, X)
            X2 = P + axis * self.mech.length_scale
            self.set_known(block, X2, self.image(guide, f"{X}+@{guide}", X2, draw=False) + shift, X + "+")
        self._slid(joint, X, pin_img, guide_img)


class VelocityConstruction(_SlidingGroups):
    """Velocity images of all points, group by group. ``mode`` is ``"plan"`` (polar velocity
    plan in the space ``velocity``) or ``"rotated"`` (rotated velocities on the mechanism, at
    ``kv`` mechanism lengths per velocity unit)."""

    WHAT, RATES = "velocity construction", "omega"

    def __init__(self, b: Builder, mech: Mechanism, sol: Solution, mode: str, kv: float = 1.0,
                 sense: int = -1) -> None:
        if mode not in ("plan", "rotated") or sense not in (1, -1):
            raise ValueError(mode)
        self.b, self.mech, self.sol, self.mode, self.kv = b, mech, sol, mode, kv
        self.sense = sense  # rotated velocities: +1 turned counter-clockwise, −1 clockwise
        self.n = len(sol)
        self.space = "velocity" if mode == "plan" else "mechanism"
        self.known: dict[str, list[tuple[np.ndarray, np.ndarray, str]]] = {}
        self.images: dict[tuple[str, str], np.ndarray] = {}  # (link, point name) -> image
        self.pos = {p: sol.point(p).position for p in mech.points}
        self.omega: dict[str, np.ndarray] = {mech.frame: np.zeros(self.n)}
        self._read_off: set[str] = set()  # the links whose ω was read off their images
        self.sliding: dict[str, np.ndarray] = {}  # joint -> relative velocity (N,2)
        if mode == "plan":
            self.o = np.zeros((self.n, 2))
            b.point("o", pt(self.o), Role.GIVEN, "o", space=self.space)

    # ------------------------------------------------------------------ the two modes
    def M(self, d: np.ndarray) -> np.ndarray:
        """Direction in the image of a velocity direction d (plan: d; rotated: d turned −90°)."""
        return d if self.mode == "plan" else self.sense * perp(d)

    def Minv(self, d: np.ndarray) -> np.ndarray:
        return d if self.mode == "plan" else -self.sense * perp(d)

    def base(self, X: np.ndarray) -> np.ndarray:
        return self.o if self.mode == "plan" else X

    def velocity(self, X: np.ndarray, image: np.ndarray) -> np.ndarray:
        """The velocity an image represents."""
        return self.Minv(image - self.base(X)) / self.kv

    def lbl(self, name: str) -> str:
        return lower(name) if self.mode == "plan" else upper(name) + "'"

    def rel_words(self) -> str:
        return "perpendicular" if self.mode == "plan" else "parallel"

    # ------------------------------------------------------------------ bookkeeping
    def _line(self, key: str, through: np.ndarray, direction: np.ndarray, *, role=Role.AUXILIARY) -> tuple:
        direction = np.where((norm(direction) == 0)[:, None], np.nan, direction)
        P = pt(through)
        Q = Point(np.concatenate([direction, np.zeros((self.n, 1))], axis=-1))
        self.b.join(key, P, Q, role, space=self.space)
        return (through, direction)

    def _point(self, key: str, xy: np.ndarray, label: str, role=Role.RESULT, lines=()) -> None:
        P = pt(xy)
        self.b.point(key, P, role, label, space=self.space)
        for k in lines:
            self.b.extend(k, P)
        if self.mode == "rotated":
            pass

    def measured_omega(self, link: str) -> np.ndarray:
        """ω of a link read off two of its images (with its sense)."""
        if link in self.omega:
            return self.omega[link]
        (X1, x1, _), (X2, x2, _) = self.two_known(link)
        d = X2 - X1
        dd = dot(d, d)
        self._read_off.add(link)
        if self.mode == "plan":
            w = cross(d, x2 - x1) / (self.kv * dd)
        else:
            w = -self.sense * (dot(x2 - x1, d) / dd - 1.0) / self.kv
        self.omega[link] = w
        return w

    def image(self, link: str, name: str, X: np.ndarray | None = None, *, label: str | None = None,
              draw: bool = True) -> np.ndarray:
        """Image of the point of ``link`` at ``X`` (named ``name``), constructing it if needed."""
        if (link, name) in self.images:
            return self.images[(link, name)]
        X = self.pos[name] if X is None else X
        if link == self.mech.frame:
            img = self.base(X)
            self.images[(link, name)] = img
            return img
        lab = label or self.lbl(name)
        (X1, x1, n1), (X2, x2, n2) = self.two_known(link)
        d1, d2 = X - X1, X - X2
        key = f"v.{link}.{name}"
        # fallback along the line of the two known points: ω measured off the plan
        w = self.measured_omega(link)
        along = x1 + self.kv * self.M(w[:, None] * perp(d1)) + (self.base(X) - self.base(X1))
        if draw:
            self.b.step(f"Image {lab} of {upper(name)} ({link}): through {self.lbl(n1)} draw the "
                        f"{self.rel_words()} to {upper(n1)}{upper(name)}, through {self.lbl(n2)} the "
                        f"{self.rel_words()} to {upper(n2)}{upper(name)}; they meet in {lab} "
                        "(the image of a link is similar to the link).")
            self._line(key + ".1", x1, self.M(perp(d1)))
            self._line(key + ".2", x2, self.M(perp(d2)))
        img, par = _meet((x1, self.M(perp(d1))), (x2, self.M(perp(d2))))
        img = np.where(par[:, None], along, img)
        # a point at the place of a known one has its image
        img = np.where((norm(d1) == 0)[:, None], x1, np.where((norm(d2) == 0)[:, None], x2, img))
        if draw:
            self._point(key, img, lab, lines=(key + ".1", key + ".2"))
        self.set_known(link, X, img, name)
        return img

    # ------------------------------------------------------------------ groups
    def run(self) -> None:
        from ._direct import draw_given, draw_group
        from ._inner_driver import velocity_images

        self.scripts = []
        given = bool(self.mech.given or getattr(self.sol, "given", ()))
        if given:
            # no driver: the whole chain from its given point velocities by Rosenauer's rule
            self.scripts.append(draw_given(self))
        # triads and larger groups, gears: Rosenauer's auxiliary points (`_direct`)
        def fallback(g, solved):
            if g.drivers and velocity_images(self, g, solved):  # driven from inside
                return
            self.scripts.append(draw_group(self, g.links, g.joints, solved, g.drivers))

        self._walk((() if given else group_plan(self.mech)), fallback, self.measured_omega)

    def _g_driver(self, gs) -> None:
        mech, sol = self.mech, self.sol
        (ln,) = gs.group.links
        d = next(d for d in mech.drivers if d.joint in gs.group.drivers)
        j = mech.joint(d.joint)
        if d.base != mech.frame:
            raise InputError("the velocity construction needs the driver to act against the frame")
        rate = sol.link(ln).omega if isinstance(j, Revolute) else None
        if isinstance(j, Revolute):
            O = self.pos[j.point]
            R = self.pos[d.reference]
            w = rate
            v = w[:, None] * perp(R - O)
            img = self.base(R) + self.kv * self.M(v)
            self.b.step(f"Given: the crank {upper(j.point)}{upper(d.reference)} turns at \u03c9; lay off "
                        f"v_{upper(d.reference)} = \u03c9\u00b7{upper(j.point)}{upper(d.reference)} "
                        f"perpendicular to the crank" + (" from o" if self.mode == "plan" else
                                                          " turned by 90\u00b0 along the crank") + ".")
            self.b.arrow(f"v.given.{d.reference}", pt(self.base(R)), pt(img), Role.GIVEN,
                         f"v_{upper(d.reference)}" if self.mode == "plan" else None, space=self.space)
            self._point(f"v.{ln}.{d.reference}", img, self.lbl(d.reference), Role.GIVEN)
            self.set_known(ln, O, self.base(O), j.point)
            self.set_known(ln, R, img, d.reference)
            self.omega[ln] = w
        else:
            # prismatic driver on the frame: the block translates with the given speed
            axis = rotate(np.zeros(self.n), np.broadcast_to(np.asarray(j.axis, float), (self.n, 2)))
            axis = axis / norm(axis)[:, None]
            # speed from the solution's input rate (given data)
            speed = dot(sol.point(j.point).velocity, axis)
            X = self.pos[j.point]
            img = self.base(X) + self.kv * self.M(speed[:, None] * axis)
            self.b.step(f"Given: the block slides at the speed v_{upper(j.point)} along its guide.")
            self.b.arrow(f"v.given.{j.point}", pt(self.base(X)), pt(img), Role.GIVEN,
                         f"v_{upper(j.point)}", space=self.space)
            self._point(f"v.{ln}.{j.point}", img, self.lbl(j.point), Role.GIVEN)
            self.set_known(ln, X, img, j.point)
            X2 = X + axis * self.mech.length_scale
            self.set_known(ln, X2, img + (self.base(X2) - self.base(X)), j.point + "*")
            self.omega[ln] = np.zeros(self.n)

    def _g_RRR(self, gs) -> None:
        p = gs.parts
        a, bj, c, l1, l2 = p["a"], p["b"], p["c"], p["l1"], p["l2"]
        K1, K2 = self._other(a, l1), self._other(c, l2)
        A, B, C = self.pos[a.point], self.pos[bj.point], self.pos[c.point]
        ia = self.image(K1, a.point)
        ic = self.image(K2, c.point)
        lab = self.lbl(bj.point)
        nA, nB, nC = upper(a.point), upper(bj.point), upper(c.point)
        self.b.step(f"Velocity of {nB} (dyad {l1}\u2013{l2}): v_{nB} = v_{nA} + v_{nB}{nA} = v_{nC} + "
                    f"v_{nB}{nC}. Through {self.lbl(a.point)} draw the {self.rel_words()} to {nA}{nB}, "
                    f"through {self.lbl(c.point)} the {self.rel_words()} to {nC}{nB}; they meet in {lab}.")
        key = f"v.{l1}.{bj.point}"
        self._line(key + ".1", ia, self.M(perp(B - A)))
        self._line(key + ".2", ic, self.M(perp(B - C)))
        img, par = _meet((ia, self.M(perp(B - A))), (ic, self.M(perp(B - C))))
        self.b.degenerate(par, f"the links {l1} and {l2} are stretched out or folded (dead centre): "
                               f"the two lines through {self.lbl(a.point)} and {self.lbl(c.point)} "
                               "are parallel, the velocity is undetermined")
        self._point(key, img, lab, lines=(key + ".1", key + ".2"))
        self.set_known(l1, A, ia, a.point)
        self.set_known(l1, B, img, bj.point)
        self.set_known(l2, C, ic, c.point)
        self.set_known(l2, B, img, bj.point)

    def _slide(self, key: str, X: np.ndarray, img_rel: np.ndarray, rel_dir: np.ndarray,
               img_g: np.ndarray, axis: np.ndarray, lab: str, what: str, role=Role.RESULT) -> np.ndarray:
        """Intersection of the line through img_rel along M(⟂rel_dir) with the sliding line
        through img_g along M(axis)."""
        self._line(key + ".1", img_rel, self.M(perp(rel_dir)))
        self._line(key + ".2", img_g, self.M(axis))
        img, par = _meet((img_rel, self.M(perp(rel_dir))), (img_g, self.M(axis)))
        self.b.degenerate(par, f"{what}: the guide is perpendicular to the link, so the velocity "
                               "is undetermined (dead centre)")
        self._point(key, img, lab, role, lines=(key + ".1", key + ".2"))
        return img

    # the sliding groups (rod in slot, slotted lever, RRP, RPR): `_SlidingGroups` builds them
    SLIDING_STEPS = {
        "rod-in-slot": "Velocity of {X} ({link}, sliding in the slot of {G}): v_{X} = v_{P} + "
                       "v_rel(\u27c2{P}{X}) = v_{X}*({G}) + v_slide(\u2225 slot). Through {p} draw the {rel} "
                       "to {P}{X}, through the image of the coincident point of {G} the {par} to the slot; "
                       "they meet in {lab}.",
        "RRP": "Velocity of {X} (block {block} on the guide of {G}): v_{X} = v_{P} + v_rel(\u27c2{P}{X}) = "
               "v_{X}*({G}) + v_slide(\u2225 guide). Through {p} draw the {rel} to {P}{X}, through {through} "
               "the {par} to the guide; they meet in {lab}.",
        "slotted-lever": "The point of the lever {link} under the pin {X}: v_{X} = v_{X}*({link}) + "
                         "v_slide(\u2225 slot), v_{X}* \u27c2 {P}{X}. Through {p} draw the {rel} to {P}{X}, "
                         "through {x} the {par} to the slot; they meet in {lab}.",
        "RPR": "The point of the lever {link} under the block's pin {X}: v_{X} = v_{X}*({link}) + "
               "v_slide(\u2225 {link}), v_{X}* \u27c2 {P}{X}; they meet in {lab}.",
    }

    def _sliding_words(self, guide: str) -> dict[str, str]:
        plan = self.mode == "plan"
        return {"rel": self.rel_words(), "par": "parallel" if plan else "perpendicular",
                "through": "o" if guide == self.mech.frame and plan else
                           f"the image of the coincident point of {guide}"}

    def _sliding_image(self, link, guide, joint, X, A, pivot_img, given_img, axis, lab) -> np.ndarray:
        what = f"{'lever' if link == guide else 'rod'} {link}"
        return self._slide(f"v.{link}.{X}", self.pos[X], pivot_img, self.pos[X] - A, given_img, axis, lab, what)

    def _slid(self, joint, X, pin_img, guide_img) -> None:
        self.sliding[joint.name] = self.velocity(self.pos[X], pin_img) - self.velocity(self.pos[X], guide_img)

    def _g_intermittent(self, gs) -> None:
        from ._intermittent import velocity_images
        velocity_images(self, gs)


class AccelerationConstruction(_SlidingGroups):
    """The polar acceleration plan (space ``acceleration``), built on a finished polar
    :class:`VelocityConstruction` ``vc`` (whose images give ω of every link and the sliding
    velocities)."""

    WHAT, RATES = "acceleration plan", "alpha"

    def __init__(self, b: Builder, vc: VelocityConstruction) -> None:
        self.b, self.vc = b, vc
        self.mech, self.sol, self.n = vc.mech, vc.sol, vc.n
        self.space = "acceleration"
        self.pos = vc.pos
        self.known: dict[str, list[tuple[np.ndarray, np.ndarray, str]]] = {}
        self.images: dict[tuple[str, str], np.ndarray] = {}
        self.alpha: dict[str, np.ndarray] = {self.mech.frame: np.zeros(self.n)}
        self._read_off: set[str] = set()  # the links whose α was read off their images
        self.coriolis: dict[str, np.ndarray] = {}
        self.o = np.zeros((self.n, 2))
        b.point("o'", pt(self.o), Role.GIVEN, "o'", space=self.space)

    def lbl(self, name: str) -> str:
        return lower(name) + "'"

    def w(self, link: str) -> np.ndarray:
        return self.vc.measured_omega(link)

    def _line(self, key, through, direction, role=Role.AUXILIARY):
        direction = np.where((norm(direction) == 0)[:, None], np.nan, direction)
        P = pt(through)
        Q = Point(np.concatenate([direction, np.zeros((self.n, 1))], axis=-1))
        self.b.join(key, P, Q, role, space=self.space)
        return (through, direction)

    def _component(self, key: str, start: np.ndarray, vec: np.ndarray, label: str | None,
                   kind: str = "acceleration") -> np.ndarray:
        end = start + vec
        self.b.arrow(key, pt(start), pt(end), Role.AUXILIARY, label, kind=kind, space=self.space)
        return end

    def measured_alpha(self, link: str) -> np.ndarray:
        if link in self.alpha:
            return self.alpha[link]
        (X1, x1, _), (X2, x2, _) = self.two_known(link)
        d = X2 - X1
        w = self.w(link)
        self._read_off.add(link)
        t = (x2 - x1) - (w * w)[:, None] * (X1 - X2)  # tangential part
        a = cross(d, t) / dot(d, d)
        self.alpha[link] = a
        return a

    def image(self, link: str, name: str, X: np.ndarray | None = None, *, draw: bool = True,
              label: str | None = None) -> np.ndarray:
        if (link, name) in self.images:
            return self.images[(link, name)]
        X = self.pos[name] if X is None else X
        if link == self.mech.frame:
            self.images[(link, name)] = self.o
            return self.o
        (X1, x1, n1), (X2, x2, n2) = self.two_known(link)
        w = self.w(link)
        lab = label or self.lbl(name)
        key = f"a.{link}.{name}"
        n1v = (w * w)[:, None] * (X1 - X)
        n2v = (w * w)[:, None] * (X2 - X)
        alpha = self.measured_alpha(link)
        along = x1 + n1v + alpha[:, None] * perp(X - X1)
        if draw:
            self.b.step(f"Acceleration image {lab} of {upper(name)} ({link}): from {self.lbl(n1)} lay off the "
                        f"normal component \u03c9\u00b2\u00b7{upper(name)}{upper(n1)} towards {upper(n1)} and "
                        f"draw the perpendicular to {upper(n1)}{upper(name)}; likewise from {self.lbl(n2)}; "
                        f"the perpendiculars meet in {lab}.")
            e1 = self._component(key + ".n1", x1, n1v, None)
            e2 = self._component(key + ".n2", x2, n2v, None)
            self._line(key + ".t1", e1, perp(X - X1))
            self._line(key + ".t2", e2, perp(X - X2))
        img, par = _meet((x1 + n1v, perp(X - X1)), (x2 + n2v, perp(X - X2)))
        img = np.where(par[:, None], along, img)
        img = np.where((norm(X - X1) == 0)[:, None], x1, np.where((norm(X - X2) == 0)[:, None], x2, img))
        if draw:
            self.b.point(key, pt(img), Role.RESULT, lab, space=self.space)
            self.b.extend(key + ".t1", pt(img))
            self.b.extend(key + ".t2", pt(img))
        self.set_known(link, X, img, name)
        return img

    def run(self) -> None:
        from ._direct import draw_given_acceleration, draw_group_acceleration
        from ._inner_driver import acceleration_images

        data = getattr(self.sol, "given", ()) or self.mech.given
        if data:
            # a chain driven by given point velocities: from their accelerations (paper 4)
            missing = [g for g in data if (g.acceleration if g.kind == "velocity" else g.curvature) is None]
            if not missing and self.sol.order < 2:
                raise InputError(f"the acceleration plan of '{self.mech.name}' needs its accelerations: "
                                 "the solution given was solved to velocities only (solve_given with "
                                 "order=2)")
            if missing:
                raise InputError(
                    f"the acceleration plan of '{self.mech.name}', a chain driven by given point "
                    "velocities, needs " + ", ".join(
                        f"the acceleration of {g.point}" if g.kind == "velocity" else
                        f"the curvature of the path of {g.point}" for g in missing)
                    + " (its file gives " + ("none" if len(missing) == len(data) else "not all")
                    + ": add acceleration = [x, y] to each [[given]] velocity, curvature to each "
                    "direction)")
            draw_given_acceleration(self)
            self._walk((), None, self.measured_alpha)
            return
        # the groups the velocity plan drew with auxiliary points: the same script on the plan
        # of relative normal accelerations (`_direct`)
        def fallback(g, solved):
            if not (g.drivers and acceleration_images(self, g, solved)):
                draw_group_acceleration(self, g.links, g.joints, solved, g.drivers)

        self._walk(group_plan(self.mech), fallback, self.measured_alpha)

    def _g_driver(self, gs) -> None:
        mech, sol = self.mech, self.sol
        (ln,) = gs.group.links
        d = next(d for d in mech.drivers if d.joint in gs.group.drivers)
        j = mech.joint(d.joint)
        if isinstance(j, Revolute):
            O, R = self.pos[j.point], self.pos[d.reference]
            w = self.w(ln)
            alpha = sol.link(ln).alpha  # given: the input's angular acceleration
            nR = (w * w)[:, None] * (O - R)
            tR = alpha[:, None] * perp(R - O)
            self.b.step(f"Given: the crank's angular acceleration \u03b1; from o' lay off the normal "
                        f"component \u03c9\u00b2\u00b7{upper(d.reference)}{upper(j.point)} (towards "
                        f"{upper(j.point)}) and the tangential component \u03b1\u00b7{upper(j.point)}"
                        f"{upper(d.reference)}: their sum is {self.lbl(d.reference)}.")
            e = self._component(f"a.given.n.{d.reference}", self.o, nR, f"a^n_{upper(d.reference)}")
            img = self._component(f"a.given.t.{d.reference}", e, tR, None)
            self.b.point(f"a.{ln}.{d.reference}", pt(img), Role.GIVEN, self.lbl(d.reference), space=self.space)
            self.set_known(ln, O, self.o, j.point)
            self.set_known(ln, R, img, d.reference)
            self.alpha[ln] = alpha
        else:
            axis = np.broadcast_to(np.asarray(j.axis, float) / np.linalg.norm(j.axis), (self.n, 2))
            acc = dot(sol.point(j.point).acceleration, axis)
            X = self.pos[j.point]
            img = self.o + acc[:, None] * axis
            self.b.step("Given: the block's acceleration along its guide.")
            self.b.arrow(f"a.given.{j.point}", pt(self.o), pt(img), Role.GIVEN, f"a_{upper(j.point)}",
                         kind="acceleration", space=self.space)
            self.set_known(ln, X, img, j.point)
            X2 = X + axis * self.mech.length_scale
            self.set_known(ln, X2, img, j.point + "*")
            self.alpha[ln] = np.zeros(self.n)

    def _g_RRR(self, gs) -> None:
        p = gs.parts
        a, bj, c, l1, l2 = p["a"], p["b"], p["c"], p["l1"], p["l2"]
        K1, K2 = self._other(a, l1), self._other(c, l2)
        A, B, C = self.pos[a.point], self.pos[bj.point], self.pos[c.point]
        ia, ic = self.image(K1, a.point), self.image(K2, c.point)
        w1, w2 = self.w(l1), self.w(l2)
        n1 = (w1 * w1)[:, None] * (A - B)
        n2 = (w2 * w2)[:, None] * (C - B)
        nA, nB, nC = upper(a.point), upper(bj.point), upper(c.point)
        lab = self.lbl(bj.point)
        self.b.step(f"Acceleration of {nB}: a_{nB} = a_{nA} + a^n_{nB}{nA} + a^t_{nB}{nA} = a_{nC} + a^n_{nB}{nC} + "
                    f"a^t_{nB}{nC}. From {self.lbl(a.point)} lay off a^n_{nB}{nA} = \u03c9\u00b2_{l1}\u00b7{nB}{nA} "
                    f"(= ({lower(a.point)}{lower(bj.point)})\u00b2/{nA}{nB}, towards {nA}), from {self.lbl(c.point)} "
                    f"a^n_{nB}{nC} (towards {nC}); the perpendiculars to {nA}{nB} and {nC}{nB} through their ends "
                    f"meet in {lab}.")
        key = f"a.{l1}.{bj.point}"
        e1 = self._component(key + ".n1", ia, n1, f"a^n_{nB}{nA}")
        e2 = self._component(key + ".n2", ic, n2, f"a^n_{nB}{nC}")
        self._line(key + ".t1", e1, perp(B - A))
        self._line(key + ".t2", e2, perp(B - C))
        img, par = _meet((e1, perp(B - A)), (e2, perp(B - C)))
        self.b.point(key, pt(img), Role.RESULT, lab, space=self.space)
        self.b.extend(key + ".t1", pt(img))
        self.b.extend(key + ".t2", pt(img))
        self.set_known(l1, A, ia, a.point)
        self.set_known(l1, B, img, bj.point)
        self.set_known(l2, C, ic, c.point)
        self.set_known(l2, B, img, bj.point)

    def _slide(self, key, X, ia, A, img_g, cor, axis, w_rel_link, lab) -> np.ndarray:
        """a_X = a_A + ω²·XA + t(⟂AX) = a_{X∈G} + Coriolis + s(∥ axis)."""
        n = (w_rel_link * w_rel_link)[:, None] * (A - X)
        e1 = self._component(key + ".n", ia, n, None)
        self._line(key + ".t", e1, perp(X - A))
        e2 = self._component(key + ".cor", img_g, cor, "a_cor", kind="coriolis") if np.any(cor) else img_g
        self._line(key + ".s", e2, axis)
        img, par = _meet((e1, perp(X - A)), (e2, axis))
        self.b.point(key, pt(img), Role.RESULT, lab, space=self.space)
        self.b.extend(key + ".t", pt(img))
        self.b.extend(key + ".s", pt(img))
        return img

    # the sliding groups (rod in slot, slotted lever, RRP, RPR): `_SlidingGroups` builds them
    SLIDING_STEPS = {
        "rod-in-slot": "Acceleration of {X}: a = a_{P} + a^n + a^t(\u27c2{P}{X}) = a*({G}) + "
                       "2\u03c9_{G}\u00d7v_rel (Coriolis) + a_rel(\u2225 slot); the two lines meet in {lab}.",
        "RRP": "Acceleration of {X}: a_{X} = a_{P} + a^n + a^t(\u27c2{P}{X}) = a*({G}){coriolis} + "
               "a_rel(\u2225 guide); the lines meet in {lab}.",
        "slotted-lever": "The lever's point under the pin {X}: a_{X} = a* + 2\u03c9_{link}\u00d7v_rel "
                         "(Coriolis) + a_rel(\u2225 slot), a* = a_{P} + a^n + a^t(\u27c2{P}{X}): from {x} "
                         "take away the Coriolis component and draw the parallel to the slot.",
        "RPR": "The lever's point under the pin {X}: a_{X} = a* + 2\u03c9_{link}\u00d7v_rel (Coriolis) + "
               "a_rel(\u2225 {link}).",
    }

    def _g_intermittent(self, gs) -> None:
        from ._intermittent import acceleration_images
        acceleration_images(self, gs)

    def _sliding_words(self, guide: str) -> dict[str, str]:
        # a guide on the frame does not turn: no Coriolis component to name
        return {"coriolis": " + 2\u03c9\u00d7v_rel (Coriolis)" if guide != self.mech.frame else ""}

    def _sliding_image(self, link, guide, joint, X, A, pivot_img, given_img, axis, lab) -> np.ndarray:
        """With the Coriolis component 2ω_G × v_rel of the guide link G: added to the image of G's
        coincident point for a rod, taken away from the pin's image for a lever."""
        cor = 2 * self.w(guide)[:, None] * perp(self.vc.sliding[joint.name])
        self.coriolis[joint.name] = cor
        return self._slide(f"a.{link}.{X}", self.pos[X], pivot_img, A, given_img,
                           -cor if link == guide else cor, axis, self.w(link), lab)
