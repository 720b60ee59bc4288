"""Higher pairs (*höhere Elementenpaare*, Latvian *augstākie pāri*): contact along profiles.

`CamContact` keeps a profile carried by `links[0]` touching a follower element of `links[1]`: a
roller (circle about a follower point), a knife edge (the point itself), a flat face (a line of
the follower) or a second profile. It removes one freedom (h = 1): the contact point slides and
may roll, as on a disc cam (*Kurvenscheibe*, *Steuernocken*), a rolling lever
(*Wälzhebel*, Latvian *slīdsvira*) or the flanks of two teeth.

`RollingContact` keeps two profiles touching *and* rolling on each other without slip: it
removes two freedoms (a self-closed higher pair, counted h = 2 by Rosenauer §110), as a wheel on
a track, the wheel and lever of the Proell–Schwabe gear, or the two centrodes of a motion.

Like every pair, both are defined by the design drawing: the profiles are given in drawing
coordinates (which are their links' coordinates) and must touch there. The contact's place on
each profile at the design position (`design_contact`) and the side on which the follower lies
follow from the drawing, as the assembly branch of a dyad does.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from ..errors import ModelError
from ..geometry.profiles import Profile

if TYPE_CHECKING:  # pragma: no cover
    from .mechanism import Mechanism

FOLLOWERS = ("roller", "knife", "flat", "profile")
#: how far apart the elements may be drawn at the design position, relative to the drawing
CONTACT_TOL = 1e-6


@dataclass(frozen=True)
class CamContact:
    """Profile `profile` of `links[0]` touches the follower element of `links[1]`.

    `follower`: 'roller' (circle of `radius` about `point`), 'knife' (the point `point`), 'flat'
    (the line through `point` with direction `axis`) or 'profile' (the profile `mate` carried by
    `links[1]`)."""

    name: str
    links: tuple[str, str]
    profile: str
    follower: str
    point: str | None = None
    radius: float = 0.0
    axis: np.ndarray | None = None
    mate: str | None = None
    kind = "cam"


@dataclass(frozen=True)
class RollingContact:
    """Profiles `profiles[0]` of `links[0]` and `profiles[1]` of `links[1]` touch and roll on
    each other without slip (equal arc lengths pass the contact on both).

    `carrier`: the link on which both are hinged, as non-circular gears on their axles
    (*unrunde Räder*). Their pivots then keep the wheels touching, so, like a gear pair, the
    pair removes one freedom (the rolling), not two; its touching equations stay (they fix the
    contact's place) and repeat the pivots' consistently. `Mechanism.build` finds the carrier
    when both links are hinged to one link."""

    name: str
    links: tuple[str, str]
    profiles: tuple[str, str]
    carrier: str | None = None
    kind = "rolling"

    @property
    def constraints(self) -> int:
        """Freedoms the pair removes: 1 on two pivots of one carrier, else 2 (self-closed)."""
        return 1 if self.carrier else 2


HigherPair = CamContact | RollingContact


@dataclass(frozen=True)
class DesignContact:
    """Where a higher pair touches in the design drawing: the parameters u0 (on the profile of
    links[0]) and v0 (on the follower's profile, or along the flat face from its point), the
    contact point, the unit common normal (pointing from links[0]'s profile towards the
    follower's side) and the side `sign` of a roller or face (+1: on the left of the profile's
    direction of increasing u)."""

    u0: float
    v0: float
    point: np.ndarray
    normal: np.ndarray
    sign: float


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _unit_normal(t: np.ndarray) -> np.ndarray:
    n = np.array([-t[1], t[0]])
    return n / np.hypot(*n)


def _refine_foot(profile: Profile, p: np.ndarray, u: float) -> float:
    """Parameter of the foot of the perpendicular from p on the profile, by Newton's method on
    (p − c(u))·c′(u) = 0 from u."""
    for _ in range(50):
        d = profile.derivatives(np.array(u), 2)
        g = float(np.dot(p - d[0], d[1]))
        dg = float(np.dot(p - d[0], d[2]) - np.dot(d[1], d[1]))
        if dg == 0.0:
            break
        step = g / dg
        u -= step
        if abs(step) <= 1e-15 * max(1.0, abs(u)):
            break
    return u


def _samples(profile: Profile, n: int = 2048) -> np.ndarray:
    lo, hi = profile.domain
    return np.linspace(lo, hi, n, endpoint=not profile.closed)


def design_contact(mech: "Mechanism", pair: HigherPair) -> DesignContact:
    """The contact of `pair` in the design drawing; `ModelError` if its elements do not touch."""
    prof = mech.profiles[pair.profile if isinstance(pair, CamContact) else pair.profiles[0]]
    tol = CONTACT_TOL * mech.length_scale
    what = f"{pair.kind} pair '{pair.name}'"
    if isinstance(pair, CamContact) and pair.follower in ("roller", "knife"):
        C = mech.points[pair.point]
        u = _refine_foot(prof, C, float(prof.nearest(C)))
        d = prof.derivatives(np.array(u), 1)
        n = _unit_normal(d[1])
        dist = float(np.dot(C - d[0], n))
        gap = abs(abs(dist) - pair.radius) if pair.follower == "roller" else float(np.hypot(*(C - d[0])))
        if not np.isfinite(gap) or gap > tol:
            raise ModelError(
                f"{what}: the {pair.follower} at '{pair.point}' does not touch profile "
                f"'{pair.profile}' in the drawing (gap {gap:.6g} {mech.length_unit}); draw the "
                f"follower touching the profile")
        sign = 1.0 if dist >= 0 else -1.0
        if pair.follower == "knife":
            # the tip lies on the profile: the follower is outside a closed profile (the
            # left normal points out of a clockwise one), else on the side of its other points
            if prof.closed:
                c = prof.derivatives(_samples(prof), 0)[0]
                area2 = float(np.sum(c[:, 0] * np.roll(c[:, 1], -1) - c[:, 1] * np.roll(c[:, 0], -1)))
                sign = 1.0 if area2 < 0 else -1.0
            else:
                others = [mech.points[p] for p in mech.link(pair.links[1]).points if p != pair.point]
                side = float(np.dot(np.mean(others, axis=0) - d[0], n)) if others else 0.0
                sign = -1.0 if side < 0 else 1.0
        return DesignContact(u, 0.0, d[0], sign * n, sign)
    if isinstance(pair, CamContact) and pair.follower == "flat":
        P = mech.points[pair.point]
        e = pair.axis
        n_face = np.array([-e[1], e[0]])
        us = _samples(prof)
        c = prof.derivatives(us, 0)[0]
        h = (c - P) @ n_face
        i = int(np.nanargmin(np.abs(h)))
        u = float(us[i])
        for _ in range(50):  # Newton on c′(u)·n = 0: the profile's tangent along the face
            d = prof.derivatives(np.array(u), 2)
            g, dg = float(d[1] @ n_face), float(d[2] @ n_face)
            if dg == 0.0:
                break
            u -= g / dg
            if abs(g / dg) <= 1e-15 * max(1.0, abs(u)):
                break
        d = prof.derivatives(np.array(u), 1)
        gap = abs(float((d[0] - P) @ n_face))
        parallel = abs(_cross(d[1], e)) / np.hypot(*d[1])
        if not np.isfinite(gap) or gap > tol or parallel > 1e-6:
            raise ModelError(f"{what}: the flat face through '{pair.point}' does not touch profile "
                             f"'{pair.profile}' in the drawing (gap {gap:.6g} {mech.length_unit}); "
                             "draw the face tangent to the profile")
        # the profile lies on the side of the face opposite to the follower's normal
        side = 1.0 if np.nanmedian(h) <= 0 else -1.0
        return DesignContact(u, float((d[0] - P) @ e), d[0], side * n_face, side)
    # two profiles (cam contact of two curves, or rolling)
    mate = mech.profiles[pair.mate if isinstance(pair, CamContact) else pair.profiles[1]]
    vs = _samples(mate)
    pts = mate.derivatives(vs, 0)[0]
    us = prof.nearest(pts)
    foot = prof.derivatives(us, 0)[0]
    i = int(np.nanargmin(np.hypot(*(pts - foot).T)))
    v, u = float(vs[i]), float(us[i])
    for _ in range(50):  # Newton on c1(u) = c2(v)
        d1, d2 = prof.derivatives(np.array(u), 1), mate.derivatives(np.array(v), 1)
        r = d2[0] - d1[0]
        J = np.column_stack([-d1[1], d2[1]])
        if abs(np.linalg.det(J)) < 1e-300:
            break  # tangent curves: the meeting point is found to √ε only, refined below
        du, dv = np.linalg.solve(J, -r)
        u, v = u + du, v + dv
        if np.hypot(du, dv) <= 1e-15 * max(1.0, abs(u), abs(v)):
            break
    d1, d2 = prof.derivatives(np.array(u), 1), mate.derivatives(np.array(v), 1)
    gap = float(np.hypot(*(d2[0] - d1[0])))
    t1, t2 = d1[1] / np.hypot(*d1[1]), d2[1] / np.hypot(*d2[1])
    names = (pair.profile, pair.mate) if isinstance(pair, CamContact) else pair.profiles
    if not np.isfinite(gap) or gap > tol or abs(_cross(t1, t2)) > 1e-5:
        raise ModelError(f"{what}: profiles '{names[0]}' and '{names[1]}' do not touch in the "
                         f"drawing (gap {gap:.6g} {mech.length_unit}, tangents "
                         f"{np.degrees(np.arcsin(min(1.0, abs(_cross(t1, t2))))):.3g}° "
                         "apart); draw them tangent")
    # which side of profile 1 the mate's body lies on: its curvature centre's side, or the
    # side its points leave to
    n = _unit_normal(d1[1])
    probe = mate.derivatives(np.array(vs), 0)[0]
    side = 1.0 if np.nanmedian((probe - d1[0]) @ n) >= 0 else -1.0
    return DesignContact(u, v, d1[0], side * n, side)


def validate_higher_pair(mech: "Mechanism", pair: HigherPair) -> None:
    """References and the design contact of a higher pair (called by `Mechanism._validate`)."""
    what = f"{pair.kind} pair '{pair.name}'"
    names = (pair.profile, pair.mate) if isinstance(pair, CamContact) else pair.profiles
    if isinstance(pair, CamContact):
        if pair.follower not in FOLLOWERS:
            raise ModelError(f"{what}: follower must be one of {', '.join(FOLLOWERS)}, got "
                             f"'{pair.follower}'")
        if pair.follower == "profile":
            if pair.mate is None:
                raise ModelError(f"{what}: a 'profile' follower needs `mate`, the follower's "
                                 "profile")
        else:
            names = (pair.profile,)
            if pair.point is None or pair.point not in mech.points:
                raise ModelError(f"{what}: the {pair.follower} needs `point`, a point of link "
                                 f"'{pair.links[1]}' (got {pair.point!r})")
            if pair.point not in mech.link(pair.links[1]).points:
                raise ModelError(f"{what}: point '{pair.point}' is not carried by the follower "
                                 f"link '{pair.links[1]}' (list it under [links])")
        if pair.follower == "roller" and not (np.isfinite(pair.radius) and pair.radius > 0):
            raise ModelError(f"{what}: a roller needs a positive radius, got {pair.radius}")
        if pair.follower == "flat" and pair.axis is None:
            raise ModelError(f"{what}: a flat face needs `axis`, its direction")
    if isinstance(pair, RollingContact) and pair.carrier is not None:
        if pair.carrier not in mech.link_names or pair.carrier in pair.links:
            raise ModelError(f"{what}: carrier '{pair.carrier}' must be a third link, on which "
                             "both wheels are hinged")
        if with_pivot_carrier(replace(pair, carrier=None), mech.joints).carrier != pair.carrier:
            raise ModelError(f"{what}: links '{pair.links[0]}' and '{pair.links[1]}' are not both "
                             f"hinged to the carrier '{pair.carrier}'")
    for name in names:
        if name not in mech.profiles:
            known = ", ".join(sorted(mech.profiles)) or "none"
            raise ModelError(f"{what}: there is no profile '{name}' in [profiles] (defined: "
                             f"{known})")
    design_contact(mech, pair)


def with_pivot_carrier(pair: RollingContact, joints) -> RollingContact:
    """`pair` with its carrier set when both its links are hinged to one third link."""
    if pair.carrier is not None:
        return pair
    hinged: dict[str, set[str]] = {}
    for j in joints:
        if getattr(j, "kind", None) == "revolute":
            a, b = j.links
            hinged.setdefault(a, set()).add(b)
            hinged.setdefault(b, set()).add(a)
    common = hinged.get(pair.links[0], set()) & hinged.get(pair.links[1], set())
    return replace(pair, carrier=sorted(common)[0]) if len(common) == 1 else pair
