"""Rosenauer's direct velocity construction carried out on the drawing, for the groups the
dyad constructions of :mod:`._plan` do not handle (triads, the Heusinger six-link group, chains
without four-bar loops, the Römer mechanism's gears and coupler, cam and rolling contacts), and
the same script on accelerations.

Owns :func:`draw_group` and :func:`draw_group_acceleration`: the steps of a
:class:`linkwork.topology.constructibility.VelocityScript` (the auxiliary points Q, R, … where two
link lines meet, each image where two plan lines meet, points on a line of two images divided in
the drawing's ratio, images copied along a sliding pair) performed at every sample with the
drafting table of a :class:`._plan.VelocityConstruction`, in either of its modes: the polar plan
(plan lines ⟂ the mechanism lines) or rotated velocities (tips on lines ∥ the mechanism lines,
Rosenauer's own form). The script is planned on the drawing's geometry (`drawing_geometry`), so
that lines parallel only at this position are chosen around where the rules allow.

* `ScriptDrawer`: the direct construction; `TrialDrawer`: false position, with one trial (rows
  through o, Rosenauer's binary driver) or two (a binary link left out, its check fixes the rows);
* `AccelerationDrawer`: the plan of relative normal accelerations (paper 4) in the books'
  chained layout (two images of a hinge where a loop does not close), transferred across
  hinges, slides (Coriolis), curved slots, gears and rolling contacts (the relative pole's
  acceleration) and cam contacts (the equivalent link between the centres of curvature);
  `AccelerationTrialDrawer`: the same after a false-position velocity plan (two trial α*);
  `TriangleDrawer`: a triad by the inscribed perpendicular-similar triangle (paper 4).

Each image is handed back to the construction, which checks every point, auxiliary points
included, against the engine.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..model import Gear, Prismatic, Slot
from ..topology.constructibility import (POLE, Chain, MechLine, VelocityScript, lower,
                                          plan_velocities, upper)
from ._common import dot, norm, perp
from .construction import Role

_SOURCE = "Rosenauer 1937, papers 1, 2, 7 (auxiliary points, projection theorem across a joint)"


class ScriptDrawer:
    """Performs a velocity script on the images of ``vc`` (a `VelocityConstruction`)."""

    prefix = "v"

    def __init__(self, vc, script: VelocityScript, solved: set[str]) -> None:
        self.vc, self.s, self.solved = vc, script, solved
        self.mech = vc.mech
        self.pos = dict(vc.pos)
        self.chain = Chain.from_mechanism(vc.mech)
        self.aux = {a.name: a for a in script.aux}
        for pair, g1, g2, t, c1, c2 in self.chain.meshes:
            self.pos[t] = self._pitch_point(self.mech.joint(pair), c1, c2)
        for pair, _, _, k in self.chain.contacts + self.chain.rolls:
            self.pos[k] = np.asarray(vc.sol.joint(pair)["point"], float)

    # ---------------------------------------------------------------- drawing geometry
    def _pitch_point(self, gear: Gear, c1: str, c2: str) -> np.ndarray:
        r1, r2 = gear.radii
        k = r1 / (r1 + r2) if gear.gear_kind == "external" else r1 / (r1 - r2)
        return self.pos[c1] + k * (self.pos[c2] - self.pos[c1])

    def where(self, name: str) -> np.ndarray:
        if name not in self.pos:
            a = self.aux[name]
            (p, u), (q, v) = (self.line(ln) for ln in a.lines)
            from ._plan import _meet
            x, par = _meet((p, u), (q, v))
            self.vc.b.degenerate(par & ~self.vc.b.bad, f"the lines {a.lines[0].text()} and "
                                 f"{a.lines[1].text()} are parallel: the auxiliary point {name} lies at infinity")
            self.pos[name] = x
        return self.pos[name]

    def line(self, line: MechLine) -> tuple[np.ndarray, np.ndarray]:
        """(point, direction) of a mechanism line at every sample."""
        if line.kind == "join":
            p, q = (self.where(n) for n in line.points)
            return p, q - p
        if line.kind == "normal":
            j = self.mech.joint(line.pair)
            if not isinstance(j, (Prismatic, Slot)):
                raise InputError(f"pair {line.pair} has no guide")
            return self.where(line.points[0]), perp(self.vc._axis(j.links[0], j.axis))
        if line.kind == "contact":
            return self.where(line.points[0]), np.asarray(self.vc.sol.joint(line.pair)["normal"], float)
        if line.kind == "direction":
            # the normal to the given direction of motion at the point (its pole lies on it)
            return self.where(line.points[0]), perp(self.given(line.points[0]).direction)
        raise InputError(f"the direct construction does not know the line {line.text()}")

    def given(self, point: str):
        """The given datum of ``point`` at every sample (from the solve, or the mechanism's)."""
        data = getattr(self.vc.sol, "given", ()) or self.mech.given
        g = next((g for g in data if g.point == point), None)
        if g is None:
            raise InputError(f"no velocity or direction of {point} is given")
        n = self.vc.n
        if g.kind == "velocity":
            return type(g)(g.point, np.broadcast_to(g.velocity, (n, 2)), link=g.link)
        return type(g)(g.point, np.broadcast_to(g.direction, (n, 2)), link=g.link)

    # ---------------------------------------------------------------- images
    def img(self, key: tuple[str, str]) -> np.ndarray:
        if key[0] == POLE:  # a given direction's line starts at o (at the point, rotated)
            return self.vc.base(self.where(key[1]))
        keys = (key,) + tuple(self.s.shared.get(key, ()))
        for k in keys:
            if k in self.vc.images:
                return self.vc.images[k]
        # a point of a link solved before (or of the frame): its image from the link's own
        for ln, p in keys:
            if ln in self.solved:
                return self.vc.image(ln, p, self.where(p), label=self.s.labels.get(key))
        raise InputError(f"the direct construction reached the image of {key[1]} ({key[0]}) "
                         "before it was drawn")

    def keep(self, ln: str, p: str, image: np.ndarray) -> None:
        for key in ((ln, p),) + tuple(self.s.shared.get((ln, p), ())):
            if key not in self.vc.images:
                self.vc.set_known(key[0], self.where(key[1]), image, key[1])

    def plan_line(self, pl, key: str) -> tuple[np.ndarray, np.ndarray]:
        p, d = self.line(pl.line)
        through = self.img(pl.anchor)
        direction = self.vc.M(perp(d))
        self.vc._line(key, through, direction)
        return through, direction

    def partner_image(self, partner: str, point: str) -> np.ndarray:
        return self.vc.image(partner, f"{point}@{partner}", self.where(point), draw=False)

    def show(self, key: str, st, image: np.ndarray, lab: str, lines=()) -> None:
        self.vc._point(key, image, lab, lines=lines)

    def text(self, st) -> str:
        if getattr(self.vc, "mode", "plan") == "rotated":
            # the script is written for the polar plan; on the mechanism the tips X' of the
            # rotated velocities lie on the parallels where the plan has the perpendiculars
            return (st.text + "  [rotated velocities: x is the tip X', a line \u27c2 XY in the plan "
                    "is the parallel to XY through the tip]")
        return st.text

    def _one(self, st) -> None:
        """Draw one step of the script."""
        from ._plan import _meet
        vc = self.vc
        key = f"{self.prefix}.direct.{st.link}.{st.point}"
        lab = self.s.labels.get((st.link, st.point), st.point)
        # images of earlier links that the step starts from are drawn first, in their own steps
        for pl in st.lines:
            if pl.anchor[0] != POLE:  # a given direction's line starts at the pole
                self.img(pl.anchor)
        for n in st.base:
            self.img((st.link, n))
        vc.b.step(self.text(st))
        if st.aux is not None and self.prefix in ("v", "v.trial", "v.trial1"):  # drawn once
            Q = self.where(st.point)
            for i, ln in enumerate(st.aux.lines):
                p, d = self.line(ln)
                vc.b.segment(f"{key}.aux{i}", _pt(p), _pt(Q), kind="line")
            vc.b.point(f"{key}.pos", _pt(Q), label=st.point)
        if st.kind == "meet":
            (p1, d1), (p2, d2) = (self.plan_line(pl, f"{key}.{i}") for i, pl in enumerate(st.lines))
            image, par = _meet((p1, d1), (p2, d2))
            own = self._own_figure(st)
            if own is not None:
                # both lines start at images of the link's own points: the image is the point of
                # the figure similar to the link (the lines pass through it), which stays
                # determined where they cross at a small angle or run parallel
                image = np.where(own[1][:, None], _similar(own[0], self.where(st.point)), image)
                par = par & ~own[1]
                if np.any(_sine(d1, d2) < 0.05):
                    a, b2 = (self.s.labels.get(pl.anchor, pl.anchor[1]) for pl in st.lines)
                    vc.b.step(f"The two lines of {lab} cross at a small angle (or run parallel) "
                              f"in some positions: {lab} is drawn as the point of the figure over "
                              f"{lower(a)}{lower(b2)} similar to {st.link} (the image of a link is "
                              "similar to it); the lines pass through it.")
            vc.b.degenerate(par & ~vc.b.bad, f"step '{st.text}': the two lines are parallel here, "
                            "the image is undetermined")
            self.show(key, st, image, lab, (f"{key}.0", f"{key}.1"))
        elif st.kind == "divide":
            # the image divides xy as P divides XY: the similar triangle over xy (exact also
            # where P lies only nearly on XY)
            image = _similar([(self.where(n), self.img((st.link, n))) for n in st.base],
                             self.where(st.point))
            self.show(key, st, image, lab)
        elif st.kind == "given":
            X = self.where(st.point)
            image = vc.base(X) + vc.kv * vc.M(self.given(st.point).velocity)
            vc.b.arrow(f"{key}.given", _pt(vc.base(X)), _pt(image), Role.GIVEN,
                       f"v_{st.point}" if vc.mode == "plan" else None, space=vc.space)
            vc._point(key, image, lab, Role.GIVEN)
        elif st.kind == "copy":
            (X,) = st.base
            x = self.img((st.link, X))
            image = x + (self.partner_image(st.partner, st.point) - self.partner_image(st.partner, X))
            self.show(key, st, image, lab)
        else:
            raise InputError(f"the direct construction cannot perform a '{st.kind}' step here")
        self.keep(st.link, st.point, image)

    def _own_figure(self, st):
        """For a meet step whose two lines both start at images of points of the step's own
        link (no pair crossed): those two (point, image) pairs and the samples where the points
        are apart, else None. The lines are then x − a ⟂ XA and x − b ⟂ XB, the similar figure."""
        if any(pl.anchor[0] != st.link or pl.via for pl in st.lines):
            return None
        own = [(self.where(pl.anchor[1]), self.img(pl.anchor)) for pl in st.lines]
        apart = norm(own[1][0] - own[0][0]) > 0
        return own, apart

    def run(self, links: set[str]) -> None:
        vc = self.vc
        for k, st in enumerate(self.s.steps):
            if st.link not in links:
                continue
            self._one(st)
        # the group's links take their hinges' images from the links solved before
        for ln in links:
            for p in self.chain.links[ln]:
                if (ln, p) not in vc.images:
                    try:
                        self.keep(ln, p, self.img((ln, p)))
                    except InputError:
                        pass
            if len(vc.known.get(ln, [])) == 1:
                self._second_image(ln)

    def _second_image(self, ln: str) -> None:
        """A link known by one point that turns with a partner across a sliding pair (a block,
        a translating follower): a second image for reading off ω, copied from the partner."""
        vc = self.vc
        (X, x, name), = vc.known[ln]
        for pair, G, S, _ in self.chain.slides:
            partner = G if S == ln else S if G == ln else None
            if partner is None or not (partner == self.mech.frame or len(vc.known.get(partner, [])) >= 2):
                continue
            X2 = X + np.array([self.mech.length_scale, 0.0])
            gx = vc.image(partner, f"{name}@{partner}", X, draw=False)
            g2 = vc.image(partner, f"{name}+@{partner}", X2, draw=False)
            vc.set_known(ln, X2, x + (g2 - gx), name + "+")
            return


def _pt(xy):
    from .construction import pt
    return pt(xy)


#: the pairs the direct construction knows (a gear pair: external or internal wheels)
KNOWN_PAIRS = ("revolute", "prismatic", "slot", "circular-slot", "gear", "cam", "rolling")


class TrialDrawer(ScriptDrawer):
    """False position (*ähnliche Punktreihen*): the script of the whole chain drawn from a trial
    rate of another crank (Rosenauer 1937 paper 7, remark on a binary driver), then every image
    moved along its ray from o in the ratio of the given driver's true to trial velocity. The
    velocities are proportional to the input rate, so the rows of trial images pass through o
    and one trial fixes the ratio."""

    prefix = "v.trial"

    def __init__(self, vc, script: VelocityScript, solved: set[str]) -> None:
        super().__init__(vc, script, solved)
        self.T: dict[tuple[str, str], np.ndarray] = {}

    def img(self, key: tuple[str, str]) -> np.ndarray:
        for k in (key,) + tuple(self.s.shared.get(key, ())):
            if k in self.T:
                return self.T[k]
            if k[0] == self.mech.frame:
                return self.vc.base(self.where(k[1]))
        raise InputError(f"the trial construction reached {key[1]} ({key[0]}) before it was drawn")

    def keep(self, ln: str, p: str, image: np.ndarray) -> None:
        for key in ((ln, p),) + tuple(self.s.shared.get((ln, p), ())):
            self.T.setdefault(key, image)

    def at(self, link: str, X: np.ndarray) -> np.ndarray:
        """The trial image of the point of ``link`` at X (the link's image is similar to it)."""
        if link == self.mech.frame:
            return self.vc.base(X)
        return _similar([(self.where(p), v) for (ln, p), v in self.T.items() if ln == link][:2], X)

    def partner_image(self, partner: str, point: str) -> np.ndarray:
        return self.at(partner, self.where(point))

    star = "*"

    def show(self, key: str, st, image: np.ndarray, lab: str, lines=()) -> None:
        self.vc.b.point(key, _pt(image), label=lab + self.star, space=self.vc.space)
        for k in lines:
            self.vc.b.extend(k, _pt(image))

    def text(self, st) -> str:
        return self.heading + super().text(st)

    def run(self, links: set[str]) -> None:
        self.heading = ""
        if self.s.check is not None:
            self._run_two(links)
            return
        vc = self.vc
        t_link, t_pivot, t_ref = self.s.trial
        d_link, d_pivot, d_ref = self.s.scale_by
        true_ref = vc.image(d_link, d_ref)
        for st in self.s.steps:
            if st.kind == "driver":
                vc.b.step(st.text)
                self._trial_driver(st, 1.0)
            elif st.kind == "scale":
                self._scale(st, links, true_ref, self.img((d_link, d_ref)))
            else:
                self._one(st)

    def _trial_driver(self, st, sign: float) -> None:
        """The trial crank's pin: as fast as the given driver's (a readable drawing), or as the
        given point it turns about, times ``sign`` (the second trial turns the other way)."""
        vc = self.vc
        t_link, t_pivot, t_ref = self.s.trial
        O, R = self.where(t_pivot), self.where(t_ref)
        pivot = self.img((t_link, t_pivot))  # a frame pivot: o; a given point: its image
        if self.s.scale_by is not None:
            d_link, d_pivot, d_ref = self.s.scale_by
            speed = np.linalg.norm(vc.velocity(self.where(d_ref), vc.image(d_link, d_ref)), axis=-1)
        else:
            speed = np.linalg.norm(vc.velocity(O, pivot), axis=-1)
        speed = np.where(speed > 0, speed, 1.0)
        w = sign * speed / np.linalg.norm(R - O, axis=-1)
        image = pivot + (vc.base(R) - vc.base(O)) + vc.kv * vc.M(w[:, None] * perp(R - O))
        self.keep(t_link, t_pivot, pivot)
        self.keep(t_link, t_ref, image)
        self.show(f"{self.prefix}.{t_link}.{t_ref}", st, image, self.s.labels.get((t_link, t_ref), t_ref))

    def _true_driver(self) -> None:
        d_link, d_pivot, d_ref = self.s.scale_by
        self.keep(d_link, d_pivot, self.vc.base(self.where(d_pivot)))
        self.keep(d_link, d_ref, self.vc.image(d_link, d_ref))

    def _check(self) -> np.ndarray:
        """The left-out link's condition (m − k)·KM at the trial images (zero when true)."""
        cut, K, LK, M, LM = self.s.check
        PK, PM = self.where(K), self.where(M)
        vk = self.vc.velocity(PK, self.img((LK, K)))
        vm = self.vc.velocity(PM, self.img((LM, M)))
        return dot(vm - vk, PM - PK)

    def _run_two(self, links: set[str]) -> None:
        """Two trials: the script drawn for two trial rates, then every image put at the
        point of its row where the left-out link's check holds."""
        vc = self.vc
        rows, checks = [], []
        for k, sign in enumerate((1.0, -1.0)):
            self.T, self.star = {}, "*" * (k + 1)
            self.prefix = f"v.trial{k + 1}"
            self.heading = ("first trial: ", "second trial: ")[k]
            for st in self.s.steps:
                if st.kind == "driver" and st.link == self.s.trial[0]:
                    vc.b.step(self.heading + st.text)
                    self._trial_driver(st, sign)
                elif st.kind == "driver":
                    self._true_driver()
                elif st.kind != "check":
                    self._one(st)
            rows.append(self.T)
            checks.append(self._check())
        self.heading = ""
        self._interpolate(links, rows, checks, lambda ln, p, x, src: vc.set_known(ln, self.where(p), x, p))

    def _interpolate(self, links, rows, checks, keep) -> None:
        """Similar point rows: t where the check c₁ + t·(c₂ − c₁) vanishes (a vector check by
        least squares), and every image x = x* + t·(x** − x*)."""
        b = self.vc.b if hasattr(self.vc, "b") else self.ac.b
        st = self.s.steps[-1]
        b.step(st.text)
        c1, c2 = (np.asarray(c, float) for c in checks)
        dc = c2 - c1
        if c1.ndim == 2:
            den = dot(dc, dc)
            with np.errstate(divide="ignore", invalid="ignore"):
                t = -dot(c1, dc) / den
        else:
            den = dc * dc
            with np.errstate(divide="ignore", invalid="ignore"):
                t = -c1 / dc
        flat = den <= 1e-24 * np.maximum(1.0, np.max(den))
        b.degenerate(flat & ~b.bad, "false position: the check does not change between the two trials "
                                    "here (the rows do not cross the true locus)")
        self.rows_t = t
        done: set[str] = set()
        cut = self.s.check[0] if self.s.check is not None else None
        chain_pts = [(ln, q) for ln in links if ln in self.chain.links and ln != cut
                     for q in self.chain.links[ln]]
        for ln, p in dict.fromkeys(chain_pts + list(rows[0])):
            x1, x2 = self._row_images(rows, (ln, p))
            x = x1 + t[:, None] * (x2 - x1)
            lab = self.s.labels.get((ln, p), p)
            if lab not in done and lab != "o":
                done.add(lab)
                key = f"{self.prefix[:1]}.rows.{ln}.{p}"
                self._row(key, x1, x2, x, lab)
            if ln in links:
                keep(ln, p, x, ln)
            if cut is not None and cut in links and (ln, p) in ((self.s.check[2], self.s.check[1]),
                                                                (self.s.check[4], self.s.check[3])):
                keep(cut, p, x, ln)  # the left-out link takes its ends' accelerations

    def _row_images(self, rows, key):
        out = []
        for row in rows:
            self.T = row
            out.append(self.img(key))
        return out

    def _row(self, key: str, x1, x2, x, lab: str) -> None:
        vc = self.vc
        vc._line(key, x1, x2 - x1)
        vc._point(key + ".pt", x, lab, lines=(key,))

    def _scale(self, st, links: set[str], true_ref: np.ndarray, trial_ref: np.ndarray) -> None:
        vc = self.vc
        vc.b.step(st.text)
        base = vc.base(self.where(st.point))
        k = dot(true_ref - base, trial_ref - base) / dot(trial_ref - base, trial_ref - base)
        keys = [(ln, p) for ln in links for p in self.chain.links[ln]] + list(self.T)
        drawn: set[str] = set()
        for ln, p in dict.fromkeys(keys):
            if ln not in links or (ln, p) in vc.images:
                continue
            t = self.img((ln, p))
            b = vc.base(self.where(p))
            image = b + k[:, None] * (t - b)
            lab = self.s.labels.get((ln, p), p)
            if lab not in drawn and lab != "o":  # a hinge's image once; the frame's stay at o
                drawn.add(lab)
                key = f"{self.prefix}.scaled.{ln}.{p}"
                vc._line(key + ".ray", b, t - b)
                vc._point(key, image, lab, lines=(key + ".ray",))
            vc.set_known(ln, self.where(p), image, p)


def drawing_geometry(vc, chain: Chain) -> dict:
    """The drawing's points and the directions of the guides' and contacts' normals at every
    sample, for the planner's choice of lines (`plan_velocities` with ``geometry``)."""
    geo: dict = dict(vc.pos)
    mech = vc.mech
    for pair, g1, g2, t, c1, c2 in chain.meshes:
        r1, r2 = mech.joint(pair).radii
        k = r1 / (r1 + r2) if mech.joint(pair).gear_kind == "external" else r1 / (r1 - r2)
        geo[t] = geo[c1] + k * (geo[c2] - geo[c1])
    for pair, a, b, k in chain.contacts + chain.rolls:
        rep = vc.sol.joint(pair)
        geo[k] = np.asarray(rep["point"], float)
        geo[("contact", pair)] = np.asarray(rep["normal"], float)
    for j in mech.joints:
        if isinstance(j, (Prismatic, Slot)):
            geo[("normal", j.name)] = perp(vc._axis(j.links[0], j.axis))
    return geo


def _scripts(vc, chain: Chain, links, solved):
    """The group's script and the whole chain's, planned on the drawing's geometry."""
    geo = drawing_geometry(vc, chain)
    sub = chain.restricted(solved | set(links), solved)
    return plan_velocities(sub, geo), (lambda: plan_velocities(chain, geo))


def _report_coincidences(b, script) -> None:
    for text in script.coincidences:
        b.step("Note on the drawing: " + text)


def draw_group(vc, links: tuple[str, ...], joints: tuple[str, ...], solved: set[str],
               drivers: tuple[str, ...] = ()) -> VelocityScript:
    """Construct the images of the group ``links`` on the links ``solved`` before it by
    Rosenauer's rule; raise `InputError` where it does not reach them (similar point rows
    would be needed) or the group has pairs the rule does not know. Where the rules leave a
    choice of lines, those crossing at the widest angle in this drawing are taken."""
    chain = Chain.from_mechanism(vc.mech)
    # the solver's own (virtual) links of a cam group are no links of the chain
    links = tuple(ln for ln in links if ln in chain.links)
    solved = {ln for ln in solved if ln in chain.links}
    script, whole = _scripts(vc, chain, links, solved)
    missing = [ln for ln in links if ln in script.unreached]
    if missing and not script.unsupported:
        # false position: the whole chain from a trial driver, scaled to the given one
        full = whole()
        if full.trial is not None and full.complete:
            TrialDrawer(vc, full, solved).run(set(links))
            return full
    bad = [f"{j.name} ({j.kind})" for j in (vc.mech.joint(n) for n in joints)
           if j.kind not in KNOWN_PAIRS or getattr(j, "gear_kind", "external") == "rack"]
    bad += [f"driver {d} (inside the group, between moving links)" for d in drivers]
    if missing or bad:
        why = (f"not handled: {', '.join(bad)}" if bad else
               f"{script.verdict()}")
        raise InputError(f"the direct velocity construction of the group {', '.join(links)}: {why}")
    _report_coincidences(vc.b, script)
    ScriptDrawer(vc, script, solved).run(set(links))
    return script


def draw_given(vc) -> VelocityScript:
    """The velocity construction of a chain driven by given point velocities and directions (a
    free or open chain, Rosenauer 1937 paper 2): the whole chain from its given data by
    Rosenauer's rule, or by false position with two trials where the rule does not reach every
    link (`TrialDrawer`)."""
    script = plan_velocities(Chain.from_mechanism(vc.mech, getattr(vc.sol, "given", None) or None))
    if script.by_two_trials:
        # Rosenauer's rule fails (the Dreispann with v_A, v_B): similar point rows, two trials
        TrialDrawer(vc, script, {vc.mech.frame}).run(set(vc.mech.moving_links))
        return script
    if not script.direct:
        raise InputError(f"the velocity construction of '{vc.mech.name}' from its given point "
                         f"velocities: {script.verdict()}")
    ScriptDrawer(vc, script, {vc.mech.frame}).run(set(vc.mech.moving_links))
    return script


def draw_given_acceleration(ac) -> VelocityScript:
    """The accelerations of a chain driven by given point velocities and accelerations (and
    the curvatures of given directions' paths): its velocity script (`draw_given`) performed on
    the plan of relative normal accelerations (Rosenauer 1937, paper 4, Ex. III: the free triad
    from j_K, j_L, j_M), by false position where the velocities needed it."""
    script = ac.vc.scripts[0]
    links = set(ac.mech.moving_links)
    solved = {ac.mech.frame}
    if script.by_two_trials:
        AccelerationTrialDrawer(ac, script, solved).run(links)
        return script
    chain = Chain.from_mechanism(ac.mech, getattr(ac.sol, "given", None) or None)
    triad = _triad(chain, links, solved)
    drawer = TriangleDrawer(ac, script, solved) if triad is not None else AccelerationDrawer(ac, script, solved)
    if triad is not None:
        # the given accelerations first, then the inscribed triangle (paper 4, Ex. III)
        for st in script.steps:
            if st.kind == "given":
                drawer._one(st)
        if drawer.draw(links, *triad):
            return script
    AccelerationDrawer.run(drawer, links)
    return script


class AccelerationDrawer(ScriptDrawer):
    """The same script performed on accelerations: Rosenauer's plan of relative normal
    accelerations (1937, paper 4; digest 000 §2.5), in the books' chained layout.

    Every link L has its figure in the plan of relative normal accelerations, x_L(X) = c_L +
    ω_L²·X: homothetic to the link with factor ω_L² (within a link x_L(Y) − x_L(X) = ω_L²·XY,
    the relative normal accelerations laid off one after another). The offsets c_L are chained
    across the pairs of a spanning tree from the frame (whose images are all o'), so each hinge of
    the tree has one image; a hinge that closes a loop has two, j and j′, because the plan does
    not close around the loop (Σ ω_i²·ΔX_i ≠ 0; paper 4, Ex. V: l and l′, k and k′). The
    construction works with the end E_L(X) = x_L(X) + a(X) of the acceleration laid off at the
    plan point; within a link E_L(Y) − E_L(X) = α_L·J(Y − X) ⟂ XY, so the velocity script carries
    over line by line. Where a line crosses a pair into the next link the end is *transferred*:
    the acceleration of a hinge is common, so E moves by the difference of its two plan images;
    a sliding pair adds the Coriolis acceleration 2ω × v_rel (its sliding acceleration lies
    along the plan line); a rolling contact (a gear pair, rolling profiles) adds the acceleration
    of the relative pole's point, ω_rel²·ρ₁ρ₂/(ρ₁ + ρ₂) along the normal (paper 8's pole
    acceleration j_p = ω·V_p); a cam contact crosses by its equivalent lower pairs, the link
    C₁C₂ between the profiles' centres of curvature (paper 8; Rosenauer §121). The acceleration
    read off is a(X) = E_L(X) − x_L(X)."""

    prefix = "a"

    def __init__(self, ac, script: VelocityScript, solved: set[str]) -> None:
        super().__init__(ac, script, solved)
        self.ac, self.vcv = ac, ac.vc
        self.E: dict[tuple[str, str], np.ndarray] = {}
        self.c = self._offsets()
        self.twice: dict[str, tuple[str, str]] = {}

    def _edges(self):
        """(point, link, link) of every pair, for the chaining of the plan."""
        ch = self.chain
        yield from ch.hinges
        for _, g1, g2, t, _, _ in ch.meshes:
            yield t, g1, g2
        for pair, a, b, k in ch.rolls + ch.contacts:
            yield k, a, b
        for e in ch.slides + ch.slots + ch.arcs:
            yield e[3], e[1], e[2]

    def _offsets(self) -> dict[str, np.ndarray]:
        """c_L chained from the frame over a spanning tree of the pairs (breadth first)."""
        zero = np.zeros((self.ac.n, 2))
        c = {self.mech.frame: zero}
        self.tree: set[tuple[str, str, str]] = set()
        edges = list(self._edges())
        # a free chain has no pair with the frame: its plan starts at its first link's o'
        for seed in [self.mech.frame] + list(self.chain.links):
            c.setdefault(seed, zero)
            grown = True
            while grown:
                grown = False
                for P, a, b in edges:
                    for L, T in ((a, b), (b, a)):
                        if L in c and T not in c:
                            c[T] = c[L] + (self.w2(L) - self.w2(T)) * self.where(P)
                            self.tree.add((P, L, T))
                            grown = True
        return c

    def w2(self, link: str) -> np.ndarray:
        return (self.vcv.measured_omega(link) ** 2)[:, None]

    def normal(self, link: str, P: np.ndarray) -> np.ndarray:
        """The point of link's figure in the plan of relative normal accelerations."""
        return self.w2(link) * P + self.c.get(link, 0.0)

    def _v(self, link: str, name: str) -> np.ndarray:
        vc = self.vcv
        X = self.where(name)
        return vc.velocity(X, vc.image(link, f"{name}@{link}" if (link, name) not in vc.images else name,
                                       X, draw=False))

    def _pair_point(self, x: str) -> str:
        """The point at which the pair (or hinge) ``x`` is crossed."""
        for e in self.chain.slides + self.chain.slots + self.chain.arcs + self.chain.contacts:
            if e[0] == x:
                return e[3]
        return x

    def _pair_jump(self, L: str, T: str, x: str) -> np.ndarray:
        """a_T − a_L at the crossing x (a hinge point or a pair's name), less what lies along the
        plan line drawn there (a sliding acceleration, the tangential part at a cam contact)."""
        pairs = {e[0]: e for e in self.chain.slides + self.chain.slots}
        arcs = {e[0]: e for e in self.chain.arcs}
        if x in pairs or x in arcs:
            pair, G, S, X = (pairs.get(x) or arcs[x])[:4]
            v_rel = self._v(S, X) - self._v(G, X)
            jump = 2 * self.vcv.measured_omega(G)[:, None] * perp(v_rel)  # Coriolis
            if x in arcs:
                # along the arc about the guide's centre C: the normal part v_rel²/r towards C
                r = self.where(arcs[x][4]) - self.where(X)
                jump = jump + (dot(v_rel, v_rel) / dot(r, r))[:, None] * r
            return jump if T == S else -jump
        for pair, A, B, K in self.chain.contacts:
            if x == pair and {L, T} == {A, B}:
                return self._contact_jump(pair, A, B, K, rolling=False, sign=1.0 if T == B else -1.0)
        for pair, A, B, K in self.chain.rolls:
            if x == K and {L, T} == {A, B}:
                return self._contact_jump(pair, A, B, K, rolling=True, sign=1.0 if T == B else -1.0)
        for pair, g1, g2, t, c1, c2 in self.chain.meshes:
            if x == t and {L, T} == {g1, g2}:
                return self._mesh_jump(pair, g1, g2, t, c1, c2, 1.0 if T == g2 else -1.0)
        return np.zeros((self.ac.n, 2))

    def _normal_jump(self, n, s1, s2, w1, w2, v_s) -> np.ndarray:
        """(a₂ − a₁)·n at a contact of two elements with signed radii s1, s2 along n (inf:
        straight, 0: a point) on links turning at w1, w2 and sliding at v_s = (v₂ − v₁)·J n: the
        equivalent link C₁C₂ (its ω_c from the velocities, then ω_c²·C₂C₁ projected), written
        with the curvatures κ = 1/s so that straight elements (sliders) need no case."""
        with np.errstate(divide="ignore", invalid="ignore"):
            k1, k2 = 1.0 / s1, 1.0 / s2
            wr = w2 - w1
            gen = (-wr * wr - v_s * v_s * k1 * k2 - 2 * v_s * (w2 * k1 - w1 * k2)) / (k1 - k2)
            # a point element (knife edge): the limits κ → ∞
            gen = np.where(np.isinf(k2), v_s * v_s * k1 - 2 * v_s * w1, gen)
            gen = np.where(np.isinf(k1), -v_s * v_s * k2 - 2 * v_s * w2, gen)
        return gen[:, None] * n

    def _contact_jump(self, pair: str, A: str, B: str, K: str, rolling: bool, sign: float) -> np.ndarray:
        from ..instant.equivalent import equivalent_linkage
        eq = self._eq.get(pair) if hasattr(self, "_eq") else None
        if eq is None:
            eq = equivalent_linkage(self.vcv.sol, pair)
            self.__dict__.setdefault("_eq", {})[pair] = eq
        n = eq.normal
        v_s = np.zeros(self.ac.n) if rolling else dot(self._v(B, K) - self._v(A, K), perp(n))
        wA, wB = self.vcv.measured_omega(A), self.vcv.measured_omega(B)
        j = self._normal_jump(n, eq.radii[:, 0], eq.radii[:, 1], wA, wB, v_s)
        bad = (eq.radii[:, 0] == eq.radii[:, 1]) | np.isnan(eq.radii).any(axis=1)
        self.ac.b.degenerate(bad & ~self.ac.b.bad, f"the contact {pair}: both elements have the same "
                             "centre of curvature here (no equivalent link)")
        return sign * j

    def _mesh_jump(self, pair, g1, g2, t, c1, c2, sign) -> np.ndarray:
        """A gear pair: the pitch circles roll (a rolling contact with centres c1, c2)."""
        Pt = self.where(t)
        n = self.where(c2) - Pt
        r2 = norm(n)
        n = n / r2[:, None]
        s1 = dot(self.where(c1) - Pt, n)
        j = self._normal_jump(n, s1, r2, self.vcv.measured_omega(g1), self.vcv.measured_omega(g2),
                              np.zeros(self.ac.n))
        return sign * j

    def transfer(self, L: str, T: str, x: str) -> np.ndarray:
        """E_T − E_L at the crossing x: the two plan images of the point, and the pair's jump."""
        P = self.where(self._pair_point(x))
        return self.normal(T, P) - self.normal(L, P) + self._pair_jump(L, T, x)

    def img(self, key: tuple[str, str]) -> np.ndarray:
        if key in self.E:
            return self.E[key]
        keys = (key,) + tuple(self.s.shared.get(key, ()))
        for k in keys[1:]:
            if k in self.E:
                return self.E[k] + self.transfer(k[0], key[0], key[1])
        for ln, p in keys:
            if ln in self.solved:
                X = self.where(p)
                a = self.ac.image(ln, p, X)
                self.E[(ln, p)] = a + self.normal(ln, X)
                return self.E[(ln, p)] + (self.transfer(ln, key[0], p) if ln != key[0] else 0.0)
        raise InputError(f"the direct construction reached the acceleration of {key[1]} ({key[0]}) "
                         "before it was drawn")

    def keep(self, ln: str, p: str, image: np.ndarray) -> None:
        self.E.setdefault((ln, p), image)
        if (ln, p) not in self.ac.images:
            self.ac.set_known(ln, self.where(p), image - self.normal(ln, self.where(p)), p)

    def datum(self, point: str):
        """The given condition at ``point`` as the solve took it (acceleration, curvature)."""
        data = getattr(self.vcv.sol, "given", ()) or self.mech.given
        return next(g for g in data if g.point == point)

    def _one(self, st) -> None:
        self._step = st
        if st.kind != "given":
            super()._one(st)
            return
        if (st.link, st.point) in self.E:  # drawn before an inscribed triangle was tried
            return
        # a given velocity's point: its given acceleration, laid off at its plan point
        ac = self.ac
        X = self.where(st.point)
        acc = np.broadcast_to(np.asarray(self.datum(st.point).acceleration, float), (ac.n, 2))
        x = self.normal(st.link, X)
        key = f"{self.prefix}.given.{st.link}.{st.point}"
        ac.b.step(f"given: the acceleration a_{upper(st.point)}, laid off at {lower(st.point)} in the "
                  "plan of relative normal accelerations")
        ac.b.point(key + ".plan", _pt(x), label=lower(st.point), space="acceleration")
        ac.b.arrow(key, _pt(x), _pt(x + acc), Role.GIVEN, f"a_{upper(st.point)}", kind="acceleration",
                   space="acceleration")
        ac.b.point(key + ".acc", _pt(acc), Role.GIVEN, ac.lbl(st.point), space="acceleration")
        self.keep(st.link, st.point, x + acc)

    def _pole_anchor(self, pl) -> np.ndarray:
        """A given direction of motion at X: the acceleration's normal component is κ·v² (the
        path's curvature κ, to the left of the direction), its tangential one unknown, so the
        ends lie on the parallel to the direction through x + κ·v²·n."""
        X = pl.anchor[1]
        L = pl.via[0][0] if pl.via else self._step.link
        g = self.datum(X)
        if g.curvature is None:
            raise InputError(f"the acceleration plan needs the curvature of the path of {X} (its "
                             "velocity's direction is given, its acceleration's normal component is "
                             "not)")
        e = np.broadcast_to(np.asarray(g.direction, float), (self.ac.n, 2))
        e = e / norm(e)[:, None]
        v = self._v(L, X)
        kappa = np.broadcast_to(np.asarray(g.curvature, float), (self.ac.n,))
        return self.normal(L, self.where(X)) + (kappa * dot(v, v))[:, None] * perp(e)

    def plan_line(self, pl, key: str) -> tuple[np.ndarray, np.ndarray]:
        p, d = self.line(pl.line)
        through = self._pole_anchor(pl) if pl.anchor[0] == POLE else self.img(pl.anchor)
        for L, T, x in pl.via:
            through = through + self.transfer(L, T, x)
        direction = perp(d)
        self.ac._line(key, through, direction)
        return through, direction

    def partner_image(self, partner: str, point: str) -> np.ndarray:
        X = self.where(point)
        return self.ac.image(partner, f"{point}@{partner}", X, draw=False) + self.normal(partner, X)

    def show(self, key: str, st, image: np.ndarray, lab: str, lines=()) -> None:
        b, ac = self.ac.b, self.ac
        P = self.where(st.point)
        x = self.normal(st.link, P)
        acc = image - x
        b.point(key + ".plan", _pt(x), label=lab, space="acceleration")
        b.arrow(key + ".laid", _pt(x), _pt(image), kind="acceleration", space="acceleration")
        for k in lines:
            b.extend(k, _pt(image))
        b.point(key, _pt(acc), Role.RESULT, ac.lbl(st.point), space="acceleration")

    def text(self, st) -> str:
        return ("Accelerations, the same lines through the ends of the accelerations laid off at the "
                "plan of relative normal accelerations (ends transferred across each pair): "
                + st.text + f"; the acceleration of {st.point} runs from its plan point to the end"
                + "".join(f"; the line \u2225 v_{upper(pl.anchor[1])} runs through the end of the normal "
                          f"component \u03ba\u00b7v_{upper(pl.anchor[1])}\u00b2 (\u03ba the given curvature "
                          f"of {upper(pl.anchor[1])}'s path) laid off at {lower(pl.anchor[1])}"
                          for pl in st.lines if pl.anchor[0] == POLE))

    def run(self, links: set[str]) -> None:
        super().run(links)
        self._second_images(links)

    def _second_images(self, links: set[str]) -> None:
        """Hinges that close a loop: two images j, j′ in the plan; the acceleration found at one
        is laid off again at the other (the transfer rule)."""
        b = self.ac.b
        for P, L, T in self.chain.hinges:
            if not ({L, T} & links) or (P, L, T) in self.tree or (P, T, L) in self.tree \
                    or f"a.twice.{P}.1" in b.elements:  # drawn with its other link's group
                continue
            if L == self.mech.frame or T == self.mech.frame:
                continue
            X = self.where(P)
            x1, x2 = self.normal(L, X), self.normal(T, X)
            a = self.ac.image(L, P, X, draw=False) if (L, P) in self.ac.images else \
                self.ac.image(T, P, X, draw=False)
            b.step(f"The plan of relative normal accelerations does not close at {upper(P)}: it has the "
                   f"two images {lower(P)} (in {L}) and {lower(P)}\u2032 (in {T}); the acceleration of "
                   f"{upper(P)} found at one image is transferred to the other (laid off there again).")
            key = f"a.twice.{P}"
            b.point(key + ".1", _pt(x1), label=lower(P), space="acceleration")
            b.point(key + ".2", _pt(x2), label=lower(P) + "\u2032", space="acceleration")
            b.arrow(key + ".a1", _pt(x1), _pt(x1 + a), kind="acceleration", space="acceleration")
            b.arrow(key + ".a2", _pt(x2), _pt(x2 + a), kind="acceleration", space="acceleration")
            self.twice[P] = (L, T)


def draw_group_acceleration(ac, links: tuple[str, ...], joints: tuple[str, ...], solved: set[str],
                            drivers: tuple[str, ...] = ()) -> VelocityScript:
    """The accelerations of the group ``links`` by the plan of relative normal accelerations,
    along the same script as the velocities (`draw_group`)."""
    chain = Chain.from_mechanism(ac.mech)
    links = tuple(ln for ln in links if ln in chain.links)
    solved = {ln for ln in solved if ln in chain.links}
    script, whole = _scripts(ac.vc, chain, links, solved)
    triad = _triad(chain, links, solved)
    if triad is not None and script.complete and script.trial is None:
        if TriangleDrawer(ac, script, solved).draw(set(links), *triad):
            return script
        # the locus lines cross badly in this drawing: the auxiliary points' script instead
    if not script.complete:
        full = whole()
        if full.trial is not None and full.complete:
            AccelerationTrialDrawer(ac, full, {ac.mech.frame}).run(set(links))
            return full
        raise InputError(f"the acceleration plan of the group {', '.join(links)}: {script.verdict()}")
    AccelerationDrawer(ac, script, solved).run(set(links))
    return script


class AccelerationTrialDrawer(AccelerationDrawer):
    """False position on the plan of relative normal accelerations (paper 4 with the classical
    similar point rows): the velocity plan is known, so every ω and hence every relative normal
    and Coriolis term is known, and the accelerations are affine in the trial crank's angular
    acceleration α*. The script is drawn for two trial values; the ends of the accelerations
    then lie on rows x*x** (which, unlike the velocities' rows, do not pass through o'), and the
    check — the given driver's acceleration (one-trial velocity scripts) or the left-out link's
    km ⟂ KM — picks the point of every row."""

    def __init__(self, ac, script: VelocityScript, solved: set[str]) -> None:
        super().__init__(ac, script, solved)
        self.star, self.heading = "*", ""

    # the trial ends live only in self.E until the rows are solved
    def keep(self, ln: str, p: str, image: np.ndarray) -> None:
        self.E.setdefault((ln, p), image)

    def text(self, st) -> str:
        return self.heading + super().text(st)

    def partner_image(self, partner: str, point: str) -> np.ndarray:
        # the ends of a link's accelerations form a figure similar to the link (turned 90°,
        # scaled by α): found from two ends already drawn
        own = [(self.where(p), v) for (ln, p), v in self.E.items() if ln == partner][:2]
        return _similar(own, self.where(point))

    def show(self, key: str, st, image: np.ndarray, lab: str, lines=()) -> None:
        b = self.ac.b
        b.point(key, _pt(image), label=self.ac.lbl(st.point) + self.star, space="acceleration")
        for k in lines:
            b.extend(k, _pt(image))

    def _trial_driver(self, sign: float) -> None:
        t_link, t_pivot, t_ref = self.s.trial
        O, R = self.where(t_pivot), self.where(t_ref)
        w2 = self.w2(t_link)
        # the trial rates: of the order of the crank's ω² (any two distinct values would do)
        size = w2[:, 0] + np.where(w2[:, 0] == 0, 1.0, 0.0)
        if self.s.scale_by is not None:
            size = size + abs(self.ac.measured_alpha(self.s.scale_by[0]))
        if t_pivot in self.chain.given:
            pivot = self.img((t_link, t_pivot))  # a given point's end, drawn before
        else:  # a frame pivot: no acceleration
            pivot = self.normal(t_link, O)
            self.keep(t_link, t_pivot, pivot)
        # within a link the ends differ by α·J(R − O)
        end = pivot + (sign * size)[:, None] * perp(R - O)
        self.keep(t_link, t_ref, end)
        b = self.ac.b
        b.point(f"{self.prefix}.{t_link}.{t_ref}", _pt(end), label=self.ac.lbl(t_ref) + self.star,
                space="acceleration")

    def _true_end(self) -> np.ndarray:
        d_link, d_pivot, d_ref = self.s.scale_by
        R = self.where(d_ref)
        return self.ac.image(d_link, d_ref, R) + self.normal(d_link, R)

    def _check(self) -> np.ndarray:
        if self.s.check is None:  # the given driver's end
            d_link, _, d_ref = self.s.scale_by
            return self.img((d_link, d_ref)) - self._true_end()
        cut, K, LK, M, LM = self.s.check
        PK, PM = self.where(K), self.where(M)
        ek = self.img((LK, K)) + self.transfer(LK, cut, K)
        em = self.img((LM, M)) + self.transfer(LM, cut, M)
        return dot(em - ek, PM - PK)

    def run(self, links: set[str]) -> None:
        ac = self.ac
        t_link = self.s.trial[0]
        rows, checks = [], []
        for k, sign in enumerate((1.0, -1.0)):
            self.E, self.star = {}, "*" * (k + 1)
            self.prefix = f"a.trial{k + 1}"
            self.heading = ("first trial (accelerations): ", "second trial (accelerations): ")[k]
            for st in self.s.steps:
                if st.kind == "driver" and st.link == t_link:
                    ac.b.step(self.heading + "an arbitrary angular acceleration α* of the trial crank "
                              f"{t_link}: " + st.text)
                    self._trial_driver(sign)
                elif st.kind == "driver":
                    d_link, d_pivot, d_ref = self.s.scale_by
                    self.keep(d_link, d_pivot, self.normal(d_link, self.where(d_pivot)))
                    self.keep(d_link, d_ref, self._true_end())
                elif st.kind not in ("check", "scale"):
                    self._one(st)
            rows.append(self.E)
            checks.append(self._check())
        self.heading, self.star = "", ""
        self.prefix = "a"

        def keep(ln, p, end, src):
            if (ln, p) not in ac.images:
                ac.set_known(ln, self.where(p), end - self.normal(src, self.where(p)), p)
        TrialDrawer._interpolate(self, links, rows, checks, keep)

    def _row_images(self, rows, key):
        out = []
        for row in rows:
            self.E = row
            out.append(self.img(key))
        return out

    def _row(self, key: str, x1, x2, x, lab: str) -> None:
        ac = self.ac
        ac._line(key, x1, x2 - x1)
        ac.b.point(key + ".pt", _pt(x), label=None, space="acceleration")
        ac.b.extend(key, _pt(x))


def _sine(u, v) -> np.ndarray:
    """|sin| of the angle between two directions at every sample (NaN where one vanishes)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) / (norm(u) * norm(v))


def _similar(own, X: np.ndarray) -> np.ndarray:
    """The point of a figure similar to a link at the link's point X, from two pairs
    (link point, figure point): a similarity is complex-affine."""
    (X1, x1), (X2, x2) = own
    z = lambda a: a[:, 0] + 1j * a[:, 1]  # noqa: E731
    with np.errstate(invalid="ignore", divide="ignore"):  # NaN rows: unassembled samples
        w = z(x1) + (z(x2) - z(x1)) / (z(X2) - z(X1)) * (z(X) - z(X1))
    return np.stack([w.real, w.imag], axis=-1)


def _triad(chain: Chain, links, solved):
    """A group of one link T and three binary links, each hinged to T at one end and to a link
    solved before at the other (Rosenauer 1937 paper 4, Ex. III and V: the triad ABC with AK, BL,
    CM): (T, [(point of T, binary link, its other end, the solved link there)] * 3), else None."""
    links = set(links)
    for T in links:
        rest = links - {T}
        if len(rest) != 3:
            continue
        arms = []
        for B in (ln for ln in chain.links if ln in rest):  # the chain's order: stable labels
            pts = list(dict.fromkeys(chain.links[B]))
            if len(pts) != 2:
                break
            at_T = [p for p in pts if any(h == (p, B, T) or h == (p, T, B) for h in chain.hinges)]
            if len(at_T) != 1:
                break
            X = at_T[0]
            Y = pts[1] if pts[0] == X else pts[0]
            K = next((a if b == B else b for q, a, b in chain.hinges
                      if q == Y and B in (a, b) and (a if b == B else b) in solved), None)
            if K is None and Y in chain.given:
                K = B  # a free end with its given velocity and acceleration (paper 4, Ex. III)
            if K is None:
                break
            arms.append((X, B, Y, K))
        else:
            if len({a[0] for a in arms}) == 3:
                return T, arms
    return None


class TriangleDrawer(AccelerationDrawer):
    """Paper 4's solution for a triad (digest 000 §2.8; Ex. III, V): the ends of the
    accelerations of the three points A, B, C of the link T lie on three locus lines α, β, γ
    (through the transferred ends of the accelerations of K, L, M, perpendicular to KA, LB, MC),
    and form a triangle whose sides are perpendicular to those of ABC. Any such trial triangle
    A′B′C′ with B′ on β and C′ on γ is homothetic to the true one from Q = β ∩ γ, so QA′ cuts α
    in the true A₁, and parallels to A′B′, A′C′ give B₁, C₁. Where A, B, C are collinear (paper
    5, Ex. III) A′ divides B′C′ as A divides BC. Of the three corners Q is taken where the two
    locus lines cross at the widest angle in this drawing (a runtime choice: lines nearly parallel
    at this position are avoided)."""

    @staticmethod
    def _sine(u, v) -> float:
        s = _sine(u, v)
        s = s[~np.isnan(s)]
        return float(s.min()) if s.size else 1.0

    def _solve(self, loci, order) -> dict:
        """The trial triangle and the true one for one labelling (``order``: the corner on the
        ray from Q first, then the two whose locus lines meet in Q)."""
        (X1, t1, d1), (X2, t2, d2), (X3, t3, d3) = (loci[i] for i in order)
        P1, P2, P3 = (self.where(x) for x in (X1, X2, X3))
        Q, par = _meet_lines((t2, d2), (t3, d3))
        size = norm(t2 - t3) + norm(t1 - t2) + 1.0
        base = np.where(par[:, None], t2, Q)
        B2 = base + (size / norm(d2))[:, None] * d2
        side = perp(P3 - P2)
        C3, _ = _meet_lines((t3, d3), (B2, side))
        e23 = P3 - P2
        lam = dot(P1 - P2, e23) / dot(e23, e23)
        straight = norm(P1 - (P2 + lam[:, None] * e23)) <= 1e-9 * norm(e23)
        A1t, _ = _meet_lines((B2, perp(P1 - P2)), (C3, perp(P1 - P3)))
        A1t = np.where(straight[:, None], B2 + lam[:, None] * (C3 - B2), A1t)
        start = np.where(par[:, None], A1t, Q)
        ray = np.where(par[:, None], d2, A1t - Q)
        A1, bad = _meet_lines((start, ray), (t1, d1))
        B1, _ = _meet_lines((t2, d2), (A1, B2 - A1t))
        C1, _ = _meet_lines((t3, d3), (A1, C3 - A1t))
        score = min(self._sine(d2, d3) if not par.all() else 1.0, self._sine(d3, side),
                    self._sine(ray, d1), self._sine(d2, B2 - A1t), self._sine(d3, C3 - A1t))
        return dict(order=order, X=(X1, X2, X3), Q=Q, par=par, B2=B2, C3=C3, A1t=A1t, start=start,
                    ray=ray, A1=A1, B1=B1, C1=C1, bad=bad, score=score)

    def draw(self, links: set[str], T: str, arms) -> bool:
        """Draw the triangle if some labelling avoids the drawing's coincidences (True), else
        leave everything undrawn (False: the caller takes the auxiliary points' script)."""
        ac = self.ac
        b = ac.b
        names = "\u03b1\u03b2\u03b3"
        loci = []
        for i, (X, B, Y, K) in enumerate(arms):
            through = self.img((K, Y)) + self.transfer(K, B, Y) + self.transfer(B, T, X)
            loci.append((X, through, perp(self.where(X) - self.where(Y))))
        orders = [[k, i2, 3 - k - i2] for k in range(3) for i2 in range(3) if i2 != k]
        best = max((self._solve(loci, o) for o in orders), key=lambda r: r["score"])
        if best["score"] < 1e-3:
            return False
        b.step("Locus lines (paper 4): through the ends of the accelerations of "
               + ", ".join(upper(Y) for X, B, Y, K in arms) + " (laid off at their images in the plan "
               "of relative normal accelerations, transferred into " + T + ") draw the perpendiculars to "
               + ", ".join(f"{upper(Y)}{upper(X)}" for X, B, Y, K in arms) + ": "
               + ", ".join(f"{names[i]}\u2013{names[i]}" for i in range(3)) + ".")
        for X, through, d in loci:
            ac._line(f"a.locus.{X}", through, d)
        order = best["order"]
        X1, X2, X3 = best["X"]
        b.step(f"Inscribed triangle: Q = {names[order[1]]} \u2229 {names[order[2]]}; a trial "
               f"{upper(X2)}\u2032 on {names[order[1]]}, {upper(X3)}\u2032 on {names[order[2]]} with "
               f"{upper(X2)}\u2032{upper(X3)}\u2032 \u27c2 {upper(X2)}{upper(X3)}, and {upper(X1)}\u2032 "
               f"from the sides \u27c2 {upper(X2)}{upper(X1)}, {upper(X3)}{upper(X1)} (collinear points: "
               f"dividing {upper(X2)}\u2032{upper(X3)}\u2032 as {upper(X1)} divides {upper(X2)}{upper(X3)}); "
               f"Q{upper(X1)}\u2032 cuts {names[order[0]]} in {upper(X1)}\u2081, the parallels to the trial's "
               f"sides give {upper(X2)}\u2081 and {upper(X3)}\u2081 (Q at infinity: a translation).")
        b.degenerate(best["bad"] & ~b.bad, f"the trial ray meets the locus line of {upper(X1)} at infinity here")
        B2, C3, A1t = best["B2"], best["C3"], best["A1t"]
        A1, B1, C1, par = best["A1"], best["B1"], best["C1"], best["par"]
        ac._line("a.tri.QA", best["start"], best["ray"])
        for nm, xy in ((X2 + "'", B2), (X3 + "'", C3), (X1 + "'", A1t)):
            b.point(f"a.tri.trial.{nm}", _pt(xy), label=upper(nm[:-1]) + "\u2032", space="acceleration")
        b.polygon("a.tri.trial", [_pt(A1t), _pt(B2), _pt(C3)], Role.AUXILIARY, space="acceleration")
        b.polygon("a.tri.result", [_pt(A1), _pt(B1), _pt(C1)], Role.RESULT, space="acceleration")
        if not par.all():
            b.point("a.tri.Q", _pt(np.where(par[:, None], np.nan, best["Q"])), label="Q", space="acceleration")
        ends = {X1: A1, X2: B1, X3: C1}
        for X, B, Y, K in arms:
            E = ends[X]
            self.show(f"a.tri.{T}.{X}", _Pt(X, T), E, lower(X))
            self.keep(T, X, E)
            self.keep(B, X, E + self.transfer(T, B, X))
            self.keep(B, Y, self.img((K, Y)) + self.transfer(K, B, Y))
        for ln in links:
            if len(self.ac.known.get(ln, [])) < 2:
                raise InputError(f"the triad construction left {ln} with fewer than two points")
        self._second_images(links)
        return True


class _Pt:
    """What `show` needs of a step: the point and its link."""

    def __init__(self, point: str, link: str) -> None:
        self.point, self.link = point, link


def _meet_lines(l1, l2):
    from ._plan import _meet
    return _meet(l1, l2)
