"""The equivalent linkage of a higher pair (*Ersatzgetriebe*, Rosenauer §121 Method II, Pöschl
§43, §49): at each position, the two profiles in contact are replaced by their osculating
circles, and the higher pair by lower pairs through the two centres of curvature C₁, C₂ on the
common normal.

- A cam pair (sliding contact) becomes a coupler C₁C₂ hinged to the profile's link at C₁ and
  to the follower at C₂ ('RR': the four-bar of Rosenauer's Fig. 325, the slider-crank of an
  eccentric with a roller). A centre at infinity (a flat face, a straight flank) becomes a
  slider: a block hinged at the finite centre that slides along the straight element ('RP':
  block hinged to links[0] at C₁ sliding on the follower's face, the Scotch yoke of a flat
  face; 'PR': block hinged to the follower at C₂ sliding along the profile's straight piece).
  Both straight ('PP') has no such linkage (Pöschl's caveat for straight lines).
- A rolling pair (no slip, h = 2) becomes a carrier C₁C₂ on which the two osculating circles
  roll as a gear pair (external or internal), or, where one profile is straight at the contact,
  a rack on the carrier.

The substitute has the same velocities and accelerations as the higher pair at that position
(the four-bar "has the same motion as the higher pair in three infinitely close positions",
Rosenauer §121), not the same jerks; it changes from position to position unless both profiles
are circles. `equivalent_linkage` gives the substitute at every sample (batch), and
`equivalent_mechanism` builds it at one sample as a `Mechanism` (drawn at that position), so it
can be solved by the engine like any other (`solve_equivalent`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import InputError, ModelError
from ..geometry import Point
from ..kinematics import Solution, Status, solve
from ..kinematics.contact import is_higher
from ..model import (CamContact, CircularSlot, Gear, Mechanism, Prismatic, Revolute, RollingContact,
                     Slot)
from .curvature import _higher_pair, element_centres
from .motion import TOL, dot, perp, relative_motion, rotate

#: the substitutes of one higher pair (letters: the pair at C₁ on links[0], then at C₂ on links[1])
KINDS = {
    "RR": "a coupler C₁C₂ hinged at both centres of curvature",
    "RP": "a block hinged at C₁ sliding along the follower's straight element",
    "PR": "a block hinged to the follower at C₂ sliding along the profile's straight piece",
    "PP": "none: both elements are straight at the contact",
}

#: textbook names by (links[0] on the frame, links[1] on the frame, substitute)
_NAMES = {
    ("R", "R", "RR"): "four-bar (Gelenkviereck)",
    ("R", "P", "RR"): "slider-crank (Schubkurbel)",
    ("P", "R", "RR"): "slider-crank (Schubkurbel)",
    ("R", "P", "RP"): "Scotch yoke (Kreuzschleife)",
    ("P", "R", "PR"): "Scotch yoke (Kreuzschleife)",
    ("R", "R", "RP"): "slotted crank (Kurbelschleife)",
    ("R", "R", "PR"): "slotted crank (Kurbelschleife)",
}


@dataclass(frozen=True)
class EquivalentLinkage:
    """The substitute of higher pair `pair` between `links` at N samples.

    contact, normal (N, 2): the contact point and the unit common normal (from links[0]'s
    profile towards the follower); tangent (N, 2): the common tangent, the direction of a
    substitute slider. centres: C₁ (on links[0]) and C₂ (on links[1]), `Point`s of shape (N,),
    at infinity along the normal where an element is straight. radii (N, 2): the signed
    distances (C₁ − X)·n and (C₂ − X)·n from the contact X along the normal (inf at infinity).
    coupler (N,): the length |C₁C₂| of the substitute coupler (inf where a centre is at infinity).
    kind (N,): 'RR', 'RP', 'PR' or 'PP' (see `KINDS`), '' where undefined. rolling: the pair
    rolls without slip (the substitute carries a gear pair of the osculating circles)."""

    pair: str
    links: tuple[str, str]
    rolling: bool
    contact: np.ndarray
    normal: np.ndarray
    tangent: np.ndarray
    centres: tuple[Point, Point]
    radii: np.ndarray
    coupler: np.ndarray
    kind: np.ndarray

    def __len__(self) -> int:
        return len(self.kind)

    def name(self, mechanism: Mechanism, index: int = 0) -> str:
        """The textbook name of the substitute mechanism at sample `index` where the two links
        are each pivoted or guided on the frame ('four-bar', 'slider-crank', 'Scotch yoke',
        'slotted crank'), else 'equivalent linkage'; with 'gears' for a rolling pair."""
        if self.rolling:
            return "gear pair on a carrier (equivalent rolling circles)"
        key = (*(_on_frame(mechanism, ln) for ln in self.links), str(self.kind[index]))
        return _NAMES.get(key, "equivalent linkage")


def _on_frame(mech: Mechanism, link: str) -> str | None:
    for j in mech.joints:
        if set(j.links) == {link, mech.frame}:
            if isinstance(j, Revolute):
                return "R"
            if isinstance(j, Prismatic):
                return "P"
    return None


def equivalent_linkage(solution: Solution, pair: str, *, tol: float = TOL) -> EquivalentLinkage:
    """The equivalent linkage of higher pair `pair` at every sample of `solution` (positions
    suffice): the curvature centres of both elements at the contact (`element_centres`), the
    coupler between them and the kind of substitute."""
    j = _higher_pair(solution, pair)
    rep = solution.joint(pair)
    X, n = rep["point"], rep["normal"]
    C1, C2 = element_centres(solution, pair, tol=tol)
    radii = np.empty((len(solution), 2))
    for i, C in enumerate((C1, C2)):
        with np.errstate(invalid="ignore"):
            radii[:, i] = np.where(C.is_infinite, np.inf, dot(C.xy - X, n))
    bad = ~np.isfinite(X).all(axis=1) | np.isnan(C1.coords).any(axis=1) | np.isnan(C2.coords).any(axis=1)
    radii[bad] = np.nan
    with np.errstate(invalid="ignore"):
        coupler = np.abs(radii[:, 1] - radii[:, 0])
    coupler[np.isinf(radii).any(axis=1)] = np.inf
    letters = np.where(np.isinf(radii), "P", "R")
    kind = np.char.add(letters[:, 0], letters[:, 1])
    kind[bad] = ""
    return EquivalentLinkage(pair, tuple(j.links), isinstance(j, RollingContact), X, n, perp(n),
                             (C1, C2), radii, coupler, kind)


# ---------------------------------------------------------------------------- one position
class _Placed:
    """A profile carried into the drawing of another position: c(u) turned by `theta` and moved
    by `offset` (the pose of its link there), so that it is given in the new design
    coordinates. Parameters, arc lengths and breaks stay those of the original."""

    def __init__(self, profile, theta: float, offset: np.ndarray) -> None:
        self.profile = profile
        self.closed = profile.closed
        self.domain = profile.domain
        self._theta = float(theta)
        self._offset = np.asarray(offset, dtype=float)

    @property
    def breaks(self) -> np.ndarray:
        return self.profile.breaks

    def derivatives(self, u: np.ndarray, order: int, side: int = 1) -> np.ndarray:
        D = self.profile.derivatives(u, order, side) if side != 1 else self.profile.derivatives(u, order)
        out = rotate(np.full(D.shape[:-1], self._theta), D)
        out[0] = out[0] + self._offset
        return out

    def arc_length(self, u: np.ndarray) -> np.ndarray:
        return self.profile.arc_length(u)

    def nearest(self, p: np.ndarray) -> np.ndarray:
        p = np.asarray(p, dtype=float)
        return self.profile.nearest(rotate(np.full(p.shape[:-1], -self._theta), p - self._offset))


def _fresh(name: str, taken) -> str:
    while name in taken:
        name += "'"
    return name


def _sample(solution: Solution, index: int) -> int:
    N = len(solution)
    if not -N <= index < N:
        raise InputError(f"sample {index} is out of range: the solution has {N} samples")
    index %= N
    if solution.status[index] == Status.UNREACHABLE:
        raise InputError(f"the mechanism '{solution.mechanism.name}' is not assembled at sample "
                         f"{index}: there is no equivalent linkage there")
    return index


def equivalent_mechanism(solution: Solution, index: int = 0, pairs=None, *,
                         tol: float = TOL) -> Mechanism:
    """The mechanism with the higher pairs `pairs` (default: all of them) replaced by their
    equivalent linkages at sample `index`, drawn in that position (its design drawing is the
    solution's drawing at that sample; the drivers and their joints are kept, so its design
    input is the sample's input). New points, links and pairs are named after the pair:
    'NAME.C1', 'NAME.C2' (the centres, unless the link has a point there already: a roller's
    centre, a knife's tip), 'NAME.coupler' (the coupler, block or carrier),
    'NAME.R1', 'NAME.R2' (hinges), 'NAME.P' (slider), 'NAME.G' (gears)."""
    mech = solution.mechanism
    n = _sample(solution, index)
    higher = [j.name for j in mech.joints if is_higher(j)]
    chosen = list(higher if pairs is None else ([pairs] if isinstance(pairs, str) else pairs))
    for name in chosen:
        _higher_pair(solution, name)
    if not chosen:
        raise ModelError(f"mechanism '{mech.name}' has no higher pair to replace")
    theta = {ln: float(solution.pose_derivatives(ln)[0, n, 2]) for ln in mech.link_names}
    offset = {ln: solution.pose_derivatives(ln)[0, n, :2] for ln in mech.link_names}
    points = {p: solution.point(p).position[n] for p in mech.points}
    links = {ln.name: list(ln.points) for ln in mech.links}
    joints, profiles = [], {}
    taken = set(points) | set(links) | {j.name for j in mech.joints}

    def place(name: str, link: str) -> None:
        profiles.setdefault(name, _Placed(mech.profiles[name], theta[link], offset[link]))

    for j in mech.joints:
        if j.name in chosen:
            eq = equivalent_linkage(solution, j.name, tol=tol)
            joints += _substitute(eq, n, points, links, taken, mech.length_scale)
        elif isinstance(j, (Prismatic, Slot)):
            joints.append(replace(j, axis=rotate(np.array(theta[j.links[0]]), np.asarray(j.axis, float))))
        elif isinstance(j, CamContact):
            place(j.profile, j.links[0])
            if j.mate is not None:
                place(j.mate, j.links[1])
            axis = None if j.axis is None else rotate(np.array(theta[j.links[1]]), np.asarray(j.axis, float))
            joints.append(replace(j, axis=axis))
        elif isinstance(j, RollingContact):
            place(j.profiles[0], j.links[0])
            place(j.profiles[1], j.links[1])
            joints.append(j)
        else:
            assert isinstance(j, (Revolute, CircularSlot, Gear))
            joints.append(j)
    return Mechanism.build(name=f"{mech.name}: equivalent linkage", points=points, links=links,
                           joints=joints, drivers=list(mech.drivers), frame=mech.frame,
                           length_unit=mech.length_unit, description=mech.description,
                           profiles=profiles)


def _substitute(eq: EquivalentLinkage, n: int, points: dict, links: dict, taken: set,
                scale: float) -> list:
    """The lower pairs (and the new link and points) replacing one higher pair at sample n."""
    a, b = eq.links
    kind = str(eq.kind[n])
    what = f"{'rolling' if eq.rolling else 'cam'} pair '{eq.pair}'"
    if kind == "PP":
        raise ModelError(f"{what}: both elements are straight at the contact of sample {n}; no "
                         "linkage of lower pairs replaces it there")
    if kind == "":
        raise ModelError(f"{what}: the contact is undefined at sample {n}")
    names = {k: _fresh(f"{eq.pair}.{k}", taken) for k in ("C1", "C2", "X", "coupler", "R1", "R2", "P", "G")}
    taken.update(names.values())
    cpl = names["coupler"]
    links[cpl] = []
    out: list = []
    hinge_points: list[str] = []
    t = eq.tangent[n]
    for i, (link, C) in enumerate(((a, eq.centres[0]), (b, eq.centres[1]))):
        if not C.is_finite[n]:
            continue
        # a point the link has there already (a roller's centre, a knife's tip, a wheel's hub)
        # is the hinge: two names at one place would be a link of zero length
        at = [p for p in links[link] if np.hypot(*(points[p] - C.xy[n])) <= 1e-9 * scale]
        c = at[0] if at else names[f"C{i + 1}"]
        if not at:
            points[c] = C.xy[n]
            links[link].append(c)
        links[cpl].append(c)
        out.append(Revolute(names[f"R{i + 1}"], c, (link, cpl) if i == 0 else (cpl, link)))
        hinge_points.append(c)
    r1, r2 = eq.radii[n]
    if not eq.rolling:
        if kind == "RP":  # the block at C₁ slides along the follower's face, fixed in links[1]
            out.append(Prismatic(names["P"], hinge_points[0], (b, cpl), t))
        elif kind == "PR":  # the block at C₂ slides along the profile's straight piece
            out.append(Prismatic(names["P"], hinge_points[0], (a, cpl), t))
        return out
    if kind == "RR":  # the osculating circles roll on each other as pitch circles
        sense = "external" if r1 * r2 < 0 else "internal"
        out.append(Gear(names["G"], (a, b), cpl, (abs(r1), abs(r2)), sense))
        return out
    # one element straight: it is a rack sliding on the carrier, the other the pinion
    pinion, rack, r = (b, a, abs(r2)) if kind == "PR" else (a, b, abs(r1))
    x = names["X"]
    points[x] = eq.contact[n]
    links[rack].append(x)
    links[cpl].append(x)
    out.append(Prismatic(names["P"], x, (cpl, rack), t))
    out.append(Gear(names["G"], (pinion, rack), cpl, (r, np.inf), "rack", point=x))
    return out


def driver_rates(solution: Solution, index: int) -> np.ndarray:
    """(order + 1, drivers) the drivers' inputs at sample `index` measured from that position
    (0) and their time derivatives (velocities, accelerations, …), read from the motion of the
    driven link relative to its base: the angle for a revolute driver, the slide along the
    axis for a prismatic one."""
    mech = solution.mechanism
    out = np.zeros((solution.order + 1, len(mech.drivers)))
    for i, d in enumerate(mech.drivers):
        rm = relative_motion(solution, d.driven, d.base).derivatives[:, index]
        j = mech.joint(d.joint)
        out[1:, i] = (rm[1:, :2] @ np.asarray(j.axis, float)) if isinstance(j, Prismatic) else rm[1:, 2]
    return out


def solve_equivalent(solution: Solution, index: int = 0, pairs=None, *, tol: float = TOL) -> Solution:
    """The equivalent mechanism at sample `index` (`equivalent_mechanism`) solved in its drawn
    position with the drivers' speeds and accelerations of that sample: one sample, to
    accelerations (the order to which it is equivalent)."""
    n = _sample(solution, index)
    eq = equivalent_mechanism(solution, n, pairs, tol=tol)
    rates = driver_rates(solution, n)
    values = [[eq.driver_input_at_design(d) for d in eq.drivers]]
    acc = rates[2:3] if solution.order >= 2 else None
    return solve(eq, values, velocities=rates[1:2], accelerations=acc, order=min(2, solution.order))
