"""Higher pairs in the solver: contact coordinates, their constraint equations, and the contact
report (contact points, common normal, pressure angle, sliding).

Where a higher pair touches is not a property of either link: it is the parameter u of the
contact on the profile of links[0], and v on the follower's element (a second profile, the flat
face). The solver treats these as coordinates of their own, solved with the link poses of the
pair's group: every higher pair adds one *contact row* `@NAME` to the pose array
Q[k, n, row, 3] after the links, holding (u − u0, v − v0, 0), zero in the design drawing as every
link pose is. Its equations are written once at position level on jets like every other pair's
(the profile's derivatives enter by Taylor composition, `Jet.compose`), so velocities,
accelerations, jerks and snaps through the pair are exact:

- roller (radius ρ) and knife edge (ρ = 0) at C: the tangential and normal components of
  C − c(u) are 0 and ±ρ (2 rows, unknown u);
- flat face through P along e: c(u) lies on the face, c′(u) is parallel to e (2 rows, unknown u;
  the contact's place along the face is reported, not solved);
- two profiles: c₂(v) = c₁(u) and c′₁ ∥ c′₂ (3 rows, unknowns u, v);
- rolling: as two profiles, and the arc lengths rolled off both are equal (4 rows).

A contact row's unused coordinates get trivial rows (held at zero), so each group's system
stays square and its condition number meaningful.
"""

from __future__ import annotations

from functools import lru_cache
from types import MappingProxyType
from typing import Mapping

import numpy as np

from ..geometry.profiles import curvature
from ..model import CamContact, Mechanism, RollingContact, design_contact
from .jet import Jet

PREFIX = "@"


def is_higher(j) -> bool:
    return isinstance(j, (CamContact, RollingContact))


def row_name(pair) -> str:
    return PREFIX + pair.name


@lru_cache(maxsize=256)
def rows(mech: Mechanism) -> tuple[str, ...]:
    """Rows of the pose array: the links, then one contact row per higher pair."""
    return mech.link_names + tuple(row_name(j) for j in mech.joints if is_higher(j))


@lru_cache(maxsize=256)
def row_index(mech: Mechanism) -> Mapping[str, int]:
    return MappingProxyType({n: i for i, n in enumerate(rows(mech))})


@lru_cache(maxsize=256)
def _design(mech: Mechanism, name: str):
    from .continuation import lineage  # (it imports this module)

    # a drag's frame (`continuation.follow`) that draws the pair as the frame before it: the
    # same contact, not searched for on the profiles again (milliseconds)
    previous = lineage(mech)
    if previous is not None and _contact_alike(previous, mech, name):
        return _design(previous, name)
    return design_contact(mech, mech.joint(name))


def _contact_alike(a: Mechanism, b: Mechanism, name: str) -> bool:
    """Whether two mechanisms draw the higher pair `name` alike, so that its design contact is
    the same: the same pair and profile objects, the same length scale (the contact's
    tolerance) and the same coordinates of every point of its two links (a roller's or knife's
    centre, a flat face's point, a knife's side)."""
    pair = a.joint(name)
    if pair is not b.joint(name) or a.length_scale != b.length_scale or \
            any(a.profiles.get(k) is not b.profiles.get(k) for k in a.profiles):
        return False
    return all(a.link(ln).points == b.link(ln).points and
               all(a.points[p].tolist() == b.points[p].tolist() for p in a.link(ln).points)
               for ln in pair.links)


@lru_cache(maxsize=256)
def rolling_sense(mech: Mechanism, name: str) -> float:
    """+1 when the two profiles' parameters run the same way at the contact (arc lengths grow
    together as they roll), −1 when they run against each other."""
    j = mech.joint(name)
    d = _design(mech, name)
    t1 = mech.profiles[j.profiles[0]].derivatives(np.array(d.u0), 1)[1]
    t2 = mech.profiles[j.profiles[1]].derivatives(np.array(d.v0), 1)[1]
    return 1.0 if float(t1 @ t2) >= 0 else -1.0


def _once(u0: np.ndarray) -> np.ndarray:
    """The parameter values to evaluate a profile at: a Jacobian's jets repeat each sample's
    value along their last axis (one column per direction), so evaluate one column and let
    `Jet.compose` broadcast it (the profile is the costliest part of a contact's rows)."""
    if u0.ndim >= 2 and u0.shape[-1] > 1 and (u0 == u0[..., :1]).all():
        return u0[..., :1]
    return u0


def _curve(profile, u: Jet, order: int) -> tuple[Jet, Jet, Jet, Jet]:
    """Jets of c(u) and c′(u) (x and y each) for the parameter jet u."""
    D = profile.derivatives(_once(u.c[0]), order + 1)
    c = u.compose(D[: order + 1])
    t = u.compose(D[1: order + 2])
    return Jet(c.c[..., 0]), Jet(c.c[..., 1]), Jet(t.c[..., 0]), Jet(t.c[..., 1])


def _arc_length(profile, u: Jet, order: int) -> Jet:
    """Jet of the arc length s(u): s(u₀) from the profile, its u-derivatives from |c′(u)|."""
    # c, c′, …, c⁽ᵒʳᵈᵉʳ⁾ (at least c′: an order-0 jet, positions only, still has a value)
    D = profile.derivatives(_once(u.c[0]), max(order, 1))[: order + 1 if order else 2]
    # |c′(u₀ + δ)| as a series in δ, then s⁽ᵐ⁺¹⁾(u₀) = m!·(its m-th coefficient)
    tx = Jet.from_derivatives(D[1:, ..., 0])
    ty = Jet.from_derivatives(D[1:, ..., 1])
    speed = (tx * tx + ty * ty).sqrt()
    derivs = np.empty((order + 1,) + D.shape[1:-1])
    derivs[0] = profile.arc_length(_once(u.c[0]))
    for m in range(order):
        derivs[m + 1] = speed.derivative(m)
    return u.compose(derivs)


def residuals(mech: Mechanism, j, pose, point, rotate) -> list[Jet]:
    """Constraint rows of higher pair `j` (lengths), on the jets `pose(row)` gives; `point` and
    `rotate` map design coordinates and directions of a link into the frame."""
    d = _design(mech, j.name)
    q = pose(row_name(j))
    order = q[0].order
    L = mech.length_scale
    u = q[0] + d.u0
    a, b = j.links
    prof = mech.profiles[j.profile if isinstance(j, CamContact) else j.profiles[0]]
    cx, cy, tx, ty = _curve(prof, u, order)
    cwx, cwy = point(pose, a, (cx, cy))
    twx, twy = rotate(pose, a, (tx, ty))
    inv = (tx * tx + ty * ty).sqrt().reciprocal()
    trivial_w = q[2] * L
    follower = j.follower if isinstance(j, CamContact) else "rolling"
    if follower in ("roller", "knife"):
        Cx, Cy = point(pose, b, mech.points[j.point])
        dx, dy = Cx - cwx, Cy - cwy
        along = (dx * twx + dy * twy) * inv
        across = (twx * dy - twy * dx) * inv - d.sign * j.radius
        return [along, across, q[1] * 1.0, trivial_w]
    if follower == "flat":
        P = mech.points[j.point]
        Px, Py = point(pose, b, P)
        ex, ey = rotate(pose, b, j.axis)
        on_face = (cwx - Px) * (-ey) + (cwy - Py) * ex
        parallel = (twx * ey - twy * ex) * inv * L
        return [on_face, parallel, q[1] * 1.0, trivial_w]
    mate = mech.profiles[j.mate if isinstance(j, CamContact) else j.profiles[1]]
    v = q[1] + d.v0
    mx, my, sx, sy = _curve(mate, v, order)
    mwx, mwy = point(pose, b, (mx, my))
    swx, swy = rotate(pose, b, (sx, sy))
    dx, dy = mwx - cwx, mwy - cwy
    rows_ = [(dx * twx + dy * twy) * inv, (twx * dy - twy * dx) * inv,
             (twx * swy - twy * swx) * inv * (sx * sx + sy * sy).sqrt().reciprocal() * L]
    if follower == "rolling":
        s1 = _arc_length(prof, u, order)
        s2 = _arc_length(mate, v, order)
        s10 = float(prof.arc_length(np.array(d.u0)))
        s20 = float(mate.arc_length(np.array(d.v0)))
        rows_.append((s1 - s10) - (s2 - s20) * rolling_sense(mech, j.name))
    rows_.append(trivial_w)
    return rows_


def _side(profile, u0: float, normal: np.ndarray) -> float:
    """+1 where `normal` (the common normal of the drawing, towards the follower) lies on the
    left of the profile's direction at u0, −1 on its right."""
    t = profile.derivatives(np.array(u0), 1)[1]
    return float(np.sign(np.array([-t[1], t[0]]) @ normal))


def _concavities(mech: Mechanism, j, u: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """How much each element bends towards the other at the contact (1/length; positive where
    it is hollow towards the other body): links[0]'s profile at u, the follower's element at v.
    Curvature does not change with the links' poses, and the sides are those of the drawing."""
    d = _design(mech, j.name)
    prof = mech.profiles[j.profile if isinstance(j, CamContact) else j.profiles[0]]
    k1 = _side(prof, d.u0, d.normal) * np.asarray(curvature(prof, u))
    follower = j.follower if isinstance(j, CamContact) else "rolling"
    if follower == "roller":
        return k1, np.full_like(k1, -1.0 / j.radius)
    if follower == "flat":
        return k1, np.zeros_like(k1)
    if follower == "knife":
        return k1, np.full_like(k1, -np.inf)
    mate = mech.profiles[j.mate if isinstance(j, CamContact) else j.profiles[1]]
    return k1, -_side(mate, d.v0, d.normal) * np.asarray(curvature(mate, v))


@lru_cache(maxsize=256)
def _outline(mech: Mechanism, name: str):
    """A fine polygon through the profile `name` and its KD-tree (for the search of a second,
    deeper touching), or None for a profile of infinite extent."""
    prof = mech.profiles[name]
    lo, hi = prof.domain
    if not (np.isfinite(lo) and np.isfinite(hi)):
        return None
    u = np.linspace(lo, hi, 4096, endpoint=not prof.closed)
    pts = prof.derivatives(u, 0)[0]
    keep = np.all(np.isfinite(pts), axis=1)
    from scipy.spatial import cKDTree  # SciPy loads when first needed
    return u[keep], pts[keep], cKDTree(pts[keep])


def _roller_cuts_elsewhere(mech: Mechanism, j, poses: np.ndarray) -> np.ndarray:
    """Samples at which the roller of cam pair `j` overlaps its profile somewhere: the profile's
    point nearest to the roller's centre (a KD-tree over a fine polygon, refined by Newton's
    method) is nearer than the radius. For a true contact that nearest point is the contact."""
    index = mech.link_index
    a, b = poses[:, index[j.links[0]]], poses[:, index[j.links[1]]]
    C = _rotate(b[:, 2], np.asarray(mech.points[j.point])[None, :]) + b[:, :2]
    local = _rotate(-a[:, 2], C - a[:, :2])  # the roller's centre in the cam's coordinates
    _, gap = nearest_on_profile(mech, j.profile, local)
    with np.errstate(invalid="ignore"):
        return gap < j.radius - 1e-9 * mech.length_scale


def nearest_on_profile(mech: Mechanism, name: str, local: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray]:
    """The parameter (N,) of the point of profile `name` nearest to each point of `local`
    (N, 2; the profile's own coordinates) and the distance to it: a KD-tree over a fine polygon,
    refined by Newton's method on (c(u) − p)·c′(u) = 0. NaN where a point is not finite or the
    profile has no finite extent."""
    N = local.shape[0]
    u_out, gap_out = np.full(N, np.nan), np.full(N, np.nan)
    outline = _outline(mech, name)
    finite = np.all(np.isfinite(local), axis=1)
    if outline is None or not finite.any():
        return u_out, gap_out
    us, _, tree = outline
    q = local[finite]
    _, k = tree.query(q)
    prof = mech.profiles[name]
    u = us[k]
    for _ in range(4):  # Newton on (c(u) − q)·c′(u) = 0, from the nearest vertex
        d = prof.derivatives(u, 2)
        r = d[0] - q
        fp = np.einsum("ij,ij->i", d[1], d[1]) + np.einsum("ij,ij->i", r, d[2])
        with np.errstate(divide="ignore", invalid="ignore"):
            u = u - np.where(fp > 0, np.einsum("ij,ij->i", r, d[1]) / fp, 0.0)
        if not prof.closed:
            u = np.clip(u, *prof.domain)
    u_out[finite] = u
    gap_out[finite] = np.hypot(*(prof.derivatives(u, 0)[0] - q).T)
    return u_out, gap_out


@lru_cache(maxsize=256)
def _convex_outside(mech: Mechanism, name: str) -> bool:
    """A roller or flat face outside a convex closed profile (the common disc cam) can touch it
    nowhere but at the contact: the common tangent separates them. Convex: the curvature,
    on both sides of every join, bends away from the follower all round, and the tangent turns
    once."""
    j = mech.joint(name)
    if not (isinstance(j, CamContact) and j.follower in ("roller", "flat")):
        return False
    prof = mech.profiles[j.profile]
    if not prof.closed or not np.isfinite(prof.domain).all():
        return False
    d = _design(mech, name)
    towards = _side(prof, d.u0, d.normal)
    u = np.linspace(prof.domain[0], prof.domain[1], 4096, endpoint=False)
    breaks = np.asarray(prof.breaks, dtype=float)
    k = np.concatenate([curvature(prof, u), curvature(prof, breaks, side=-1),
                        curvature(prof, breaks, side=1)])
    if not (np.all(np.isfinite(k)) and np.all(towards * k <= 0.0)):
        return False
    t = prof.derivatives(u, 1)[1]
    heading = np.unwrap(np.arctan2(t[:, 1], t[:, 0]))
    last = np.angle(np.exp(1j * (heading[0] - heading[-1])))  # from the last sample round to the first
    return abs(abs(heading[-1] - heading[0] + last) - 2 * np.pi) < 1e-6


def interference(mech: Mechanism, poses: np.ndarray) -> np.ndarray:
    """Samples (N,) at which some higher pair's elements would cut into each other: next to the
    contact (a roller larger than the hollow of the profile it sits in — the undercut cam —, a
    flat face on a hollow flank, two profiles hollow towards each other beyond their touching),
    or, for a roller, anywhere along the profile (the roller bridging a hollow touches it at
    two places; the contact followed on past that is not where the roller can be). Such a
    contact solves the pair's equations but is not a place the follower can be: the solver
    marks those samples unreachable. `poses` (N, rows, 3) is the pose array of the solve
    (links, then contact rows holding u − u0, v − v0)."""
    bad = np.zeros(poses.shape[0], dtype=bool)
    index = row_index(mech)
    for j in mech.joints:
        if not is_higher(j) or (isinstance(j, CamContact) and j.follower == "knife"):
            continue
        if _convex_outside(mech, j.name):
            continue
        d = _design(mech, j.name)
        r = index[row_name(j)]
        with np.errstate(invalid="ignore"):
            k1, k2 = _concavities(mech, j, poses[:, r, 0] + d.u0, poses[:, r, 1] + d.v0)
            bad |= k1 + k2 > 1e-9 * (np.abs(k1) + np.abs(k2))
        if isinstance(j, CamContact) and j.follower == "roller":
            bad |= _roller_cuts_elsewhere(mech, j, poses)
    return bad


def contact_row_count(j) -> int:
    """Equations of a higher pair's contact row (its 3 coordinates plus the freedoms it removes)."""
    return 3 + (2 if isinstance(j, RollingContact) else 1)


def design_offsets(mech: Mechanism, name: str) -> tuple[float, float]:
    d = _design(mech, name)
    return d.u0, d.v0


# ---------------------------------------------------------------------------- the report
def _unit(v: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore", divide="ignore"):
        return v / np.hypot(v[:, 0], v[:, 1])[:, None]


def _perp(v: np.ndarray) -> np.ndarray:
    return np.stack([-v[:, 1], v[:, 0]], axis=1)


def _rotate(theta: np.ndarray, v: np.ndarray) -> np.ndarray:
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def report(sol, name: str) -> dict[str, np.ndarray]:
    """The contact of higher pair `name` at every sample (arrays, sample axis first):

    `u`, `v`: contact parameters on the profile of links[0] and on the follower's element (the
    mate profile; the place along a flat face from its point; 0 for a roller or knife);
    `point`: the contact point; `point_on_profile`, `point_on_follower`: the same point in the
    coordinates of links[0] and of links[1] (where it lies on each element); `normal`: the unit common normal, from links[0]'s profile
    towards the follower; `curvature`: the signed curvature of links[0]'s profile at the contact
    (positive where it turns left with increasing u); `profile_speed` and `follower_speed`: how
    fast the contact point runs along each element, relative to the link carrying it;
    `sliding_velocity`: the follower's material point at the contact relative to the profile's,
    along the common tangent (zero for rolling); `roller_spin` (rollers): the angular velocity
    relative to the follower with which a roller turning freely rolls without slip;
    `pressure_angle`: between the common normal (the line of action of the contact force) and
    the direction in which the follower's point (a roller's centre or knife tip, else the
    contact point) moves, in [0, π/2]: for a follower held by one hinge or guide the direction
    its pair allows (defined in dwells too), otherwise its velocity's.
    """
    mech = sol.mechanism
    j = mech.joint(name)
    d = _design(mech, name)
    row = row_index(mech)[row_name(j)]
    C = sol._C
    u = C[0, :, row, 0] + d.u0
    u_dot = C[1, :, row, 0]
    a, b = j.links
    prof = mech.profiles[j.profile if isinstance(j, CamContact) else j.profiles[0]]
    D = prof.derivatives(u, 2)
    Pa = sol.pose_derivatives(a)
    th_a, w_a = Pa[0, :, 2], Pa[1, :, 2]
    point = Pa[0, :, :2] + _rotate(th_a, D[0])
    t_local = D[1]
    speed = np.hypot(t_local[:, 0], t_local[:, 1])
    tangent = _unit(_rotate(th_a, t_local))
    kappa = (t_local[:, 0] * D[2][:, 1] - t_local[:, 1] * D[2][:, 0]) / speed**3
    normal = _perp(tangent) * d.sign if not (isinstance(j, CamContact) and j.follower == "flat") \
        else _perp(tangent) * np.sign(np.einsum("ij,ij->i", _perp(tangent), _normal_flat(sol, j, d)))[:, None]
    out = {"u": u, "point": point, "point_on_profile": D[0], "point_on_follower": sol.local(b, point),
           "normal": normal, "curvature": kappa, "profile_speed": speed * u_dot}
    # velocities of the two links' material points at the contact
    vb_point = sol.point_on(b, sol.local(b, point)).velocity
    va_point = sol.point_on(a, sol.local(a, point)).velocity
    out["sliding_velocity"] = np.einsum("ij,ij->i", vb_point - va_point, tangent)
    follower = j.follower if isinstance(j, CamContact) else "rolling"
    w_b = sol.pose_derivatives(b)[1, :, 2]
    if follower in ("roller", "knife"):
        out["v"] = np.zeros_like(u)
        # the normal turns with links[0] and with the contact's run along the profile
        turn = w_a + kappa * speed * u_dot
        out["follower_speed"] = j.radius * (turn - w_b) * d.sign
        if follower == "roller":
            out["roller_spin"] = -(out["sliding_velocity"]) / j.radius
        v_f = sol.point(j.point).velocity
    elif follower == "flat":
        Pw = sol.point(j.point)
        ew = _rotate(sol.pose_derivatives(b)[0, :, 2], j.axis)
        lam = np.einsum("ij,ij->i", point - Pw.position, ew)
        out["v"] = lam
        # d/dt of (contact − P)·e in the follower: the contact point's speed along the face
        rel = va_point + tangent * (speed * u_dot)[:, None] - Pw.velocity
        out["follower_speed"] = np.einsum("ij,ij->i", rel, ew) - w_b * np.einsum(
            "ij,ij->i", point - Pw.position, _perp(ew))
        v_f = vb_point
    else:
        mate = mech.profiles[j.mate if isinstance(j, CamContact) else j.profiles[1]]
        v = C[0, :, row, 1] + d.v0
        out["v"] = v
        out["follower_speed"] = np.hypot(*mate.derivatives(v, 1)[1].T) * C[1, :, row, 1]
        v_f = vb_point
    # the direction the follower's point moves in: from the follower's own hinge or guide where
    # it has only that (so also in a dwell, where its velocity is zero), else its velocity
    from .cam_group import motion_direction, of_pair
    cf = of_pair(mech, j) if isinstance(j, CamContact) else None
    if cf is not None:
        v_f = motion_direction(cf, sol, sol.point(j.point).position if follower in ("roller", "knife")
                               else point)
    with np.errstate(invalid="ignore", divide="ignore"):
        cos_a = np.abs(np.einsum("ij,ij->i", normal, v_f)) / np.hypot(v_f[:, 0], v_f[:, 1])
    out["pressure_angle"] = np.arccos(np.clip(cos_a, 0.0, 1.0))
    return out


def _normal_flat(sol, j, d) -> np.ndarray:
    """The face's normal towards the follower, in the frame, at every sample."""
    return _rotate(sol.pose_derivatives(j.links[1])[0, :, 2], d.normal[None, :])
