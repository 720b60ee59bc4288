"""The cam follower group, solved in its own two unknowns.

The commonest group with a higher pair is a follower on one lower pair — a hinge (oscillating
follower, *Schwinghebel*) or a guide (translating follower, *Stößel*) on a link already placed —
touching the profile of another placed link with a roller, a knife edge or a flat face. The
generic path solves it in the six coordinates of its rows (the follower's pose, the contact
row) with the Jacobian from jets in six directions. Here the group is written in what is really
unknown: the follower's angle or slide q and the contact parameter u, two equations

- roller (radius ρ) or knife edge (ρ = 0) at C: (C − c)·t = 0 and t × (C − c) = ±ρ|t|;
- flat face through P along e: e × (c − P) = 0 and t × e = 0;

(c the profile point, t = c′(u) turned with the cam), solved by Newton's method with their
partial derivatives written out (2×2, Cramer's rule, every sample at once), and the rates by
2×2 solves of the same equations evaluated on jets. The same geometry as `contact.residuals`,
so the generic path remains its independent check in the tests.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model import CamContact, Mechanism, Prismatic, Revolute
from ..topology import Group
from . import contact
from .jet import Jet

MAX_ITERATIONS = 50


@dataclass(frozen=True)
class CamFollower:
    """follower: the group's link; base: the placed link carrying its hinge or guide; cam: the
    placed link carrying the profile. `hinge` is the follower's pivot (design coordinates) or
    None for a guide, whose direction `axis` (design, unit) the slide q runs along with sign
    `sense`."""

    follower: str
    base: str
    cam: str
    pair: CamContact
    hinge: np.ndarray | None
    axis: np.ndarray | None
    sense: float


def recognise(mech: Mechanism, group: Group) -> CamFollower | None:
    """The group as a cam follower, or None (the generic path then solves it)."""
    if group.size != 1 or group.drivers or group.wedge_pairs or len(group.joints) != 2:
        return None
    return _follower(mech, group.links[0], [mech.joint(j) for j in group.joints])


def of_pair(mech: Mechanism, pair: CamContact) -> CamFollower | None:
    """The follower of cam pair `pair` if it is held by nothing but one hinge or guide."""
    f = pair.links[1]
    joints = [j for j in mech.joints if f in getattr(j, "links", ())]
    if any(d.driven == f for d in mech.drivers):
        return None
    return _follower(mech, f, joints)


def _follower(mech: Mechanism, f: str, joints: list) -> CamFollower | None:
    cams = [j for j in joints if isinstance(j, CamContact)]
    lower = [j for j in joints if isinstance(j, (Revolute, Prismatic))]
    if len(cams) != 1 or len(lower) != 1 or len(joints) != 2:
        return None
    k, low = cams[0], lower[0]
    if k.follower not in ("roller", "knife", "flat") or k.links[1] != f or k.links[0] == f:
        return None
    base = low.links[0] if low.links[1] == f else low.links[1]
    if isinstance(low, Revolute):
        return CamFollower(f, base, k.links[0], k, np.asarray(mech.points[low.point], float), None, 1.0)
    return CamFollower(f, base, k.links[0], k, None, np.asarray(low.axis, float),
                       1.0 if low.links[1] == f else -1.0)


def motion_direction(cf: CamFollower, sol, point: np.ndarray) -> np.ndarray:
    """(N, 2) unit direction in which the follower's point at `point` (frame coordinates, per
    sample) moves when the follower moves forwards (its angle or slide growing): defined in a
    dwell too, where the point's velocity is zero and gives no direction."""
    pose = sol.pose_derivatives(cf.base)[0]
    c, s = np.cos(pose[:, 2]), np.sin(pose[:, 2])
    if cf.hinge is None:
        a = cf.axis * cf.sense
        d = np.stack([c * a[0] - s * a[1], s * a[0] + c * a[1]], axis=1)
    else:
        h = cf.hinge
        r = point - (pose[:, :2] + np.stack([c * h[0] - s * h[1], s * h[0] + c * h[1]], axis=1))
        d = np.stack([-r[:, 1], r[:, 0]], axis=1)
    return d / np.hypot(d[:, 0], d[:, 1])[:, None]


# ---------------------------------------------------------------------------- plain arrays
def _rot(c, s, v):
    return c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


def _pose(state, link: str, sel=None):
    """x, y, cos θ, sin θ of `link` at the samples (those indexed by `sel`, if given)."""
    q = state.Q[0, :, state.li(link)]
    c, s = state.cs(state.li(link))
    if sel is None:
        return q[:, 0], q[:, 1], c, s
    return q[sel, 0], q[sel, 1], c[sel], s[sel]


def _follower_point(cf: CamFollower, state, q, p: np.ndarray, sel=None):
    """World position of design point p of the follower and its derivative by q."""
    bx, by, bc, bs = _pose(state, cf.base, sel)
    if cf.hinge is not None:
        hx, hy = _rot(bc, bs, cf.hinge)
        c, s = np.cos(q), np.sin(q)
        rx, ry = _rot(c, s, p - cf.hinge)
        return bx + hx + rx, by + hy + ry, -ry, rx
    ax, ay = _rot(bc, bs, cf.axis * cf.sense)
    px, py = _rot(bc, bs, p)
    return bx + px + q * ax, by + py + q * ay, ax, ay


def _equations(cf: CamFollower, mech: Mechanism, state, q, u, d, D=None, sel=None):
    """The two equations and their partial derivatives by q and u (each (N,)), and the weights
    that turn each equation into a length (as the generic rows are) and a profile parameter
    into a length along the profile (|c′|). With `sel`, at those samples only (q and u given
    there)."""
    j = cf.pair
    if D is None:  # else given: the profile's derivatives at u, to order 2 at least
        D = mech.profiles[j.profile].derivatives(u, 2)
    ax_, ay_, ac, as_ = _pose(state, cf.cam, sel)
    cx, cy = _rot(ac, as_, D[0])
    cx, cy = cx + ax_, cy + ay_
    tx, ty = _rot(ac, as_, D[1])
    kx, ky = _rot(ac, as_, D[2])
    if j.follower in ("roller", "knife"):
        Cx, Cy, dCx, dCy = _follower_point(cf, state, q, mech.points[j.point], sel)
        dx, dy = Cx - cx, Cy - cy
        nt = np.hypot(tx, ty)
        g1 = dx * tx + dy * ty
        g1u = -(tx * tx + ty * ty) + dx * kx + dy * ky
        g1q = dCx * tx + dCy * ty
        sr = d.sign * j.radius
        g2 = _cross(tx, ty, dx, dy) - sr * nt
        g2u = _cross(kx, ky, dx, dy) - sr * (tx * kx + ty * ky) / nt
        g2q = _cross(tx, ty, dCx, dCy)
        return g1, g2, g1q, g1u, g2q, g2u, (1.0 / nt, 1.0 / nt, nt)
    Px, Py, dPx, dPy = _follower_point(cf, state, q, mech.points[j.point], sel)
    if cf.hinge is not None:
        c, s = np.cos(q), np.sin(q)
        ex, ey = _rot(c, s, j.axis)
        dex, dey = -ey, ex
    else:
        bc, bs = _pose(state, cf.base, sel)[2:]
        ex, ey = _rot(bc, bs, j.axis)
        dex = dey = np.zeros_like(ex)
    g1 = _cross(ex, ey, cx - Px, cy - Py)
    g1u = _cross(ex, ey, tx, ty)
    g1q = _cross(dex, dey, cx - Px, cy - Py) - _cross(ex, ey, dPx, dPy)
    g2 = _cross(tx, ty, ex, ey)
    g2u = _cross(kx, ky, ex, ey)
    g2q = _cross(tx, ty, dex, dey)
    nt = np.hypot(tx, ty)
    return g1, g2, g1q, g1u, g2q, g2u, (np.ones_like(nt), mech.length_scale / nt, nt)


def _start(cf: CamFollower, state, guess: np.ndarray, u0: float):
    """q and u from a Newton starting guess of the generic rows (follower pose, contact row)."""
    u = guess[:, 1, 0] + u0
    if cf.hinge is not None:
        return guess[:, 0, 2].copy(), u
    bx, by, bc, bs = _pose(state, cf.base)
    # the follower's origin is the base's, shifted along the guide by q
    ax, ay = _rot(bc, bs, cf.axis * cf.sense)
    return (guess[:, 0, 0] - bx) * ax + (guess[:, 0, 1] - by) * ay, u


def positions(cf: CamFollower, state, guess: np.ndarray | None, tol: float, reseat: bool = True
              ) -> tuple[np.ndarray, np.ndarray]:
    """Place the follower and the contact row in Q[0] (Newton from `guess`, the generic
    rows' starting poses); return the samples that converged and the residual (a length) of
    the equations at the poses placed (the backward error of the estimate in `precision`).

    A roller can reach the end of the contact it follows: bridging a hollow of the profile it
    touches it at two places, and past that the contact followed on would have it cut into
    the profile (`contact.interference` marks such samples unreachable). Where the roller
    stands then, the other touching is the profile's point nearest its centre (deepest in
    it): the contact is sought again from there (`reseat`), so the motion is picked up where
    the roller can be, and stays unreachable only where it can touch nowhere."""
    mech = state.mech
    d = contact._design(mech, cf.pair.name)
    N = state.Q.shape[1]
    fi, ri = state.li(cf.follower), state.li(contact.row_name(cf.pair))
    if guess is None:
        guess = np.zeros((N, 2, 3))
    if reseat and cf.pair.follower in ("roller", "knife"):
        lost = ~np.isfinite(guess).all(axis=(1, 2))
        if lost.any():  # beyond where the continuation got: contacts sought over the profile
            guess = guess.copy()
            guess[lost] = _seeds(cf, state, guess, lost, d)
    q, u = _start(cf, state, guess, d.u0)
    active = np.isfinite(q) & np.isfinite(u)
    q, u = np.where(active, q, 0.0), np.where(active, u, d.u0)
    converged = np.zeros(N, dtype=bool)
    polished = np.zeros(N, dtype=bool)
    span = 1.0 if cf.hinge is not None else mech.length_scale  # the largest step of q
    prof = mech.profiles[cf.pair.profile]
    u_span = (prof.domain[1] - prof.domain[0]) / 8 if np.isfinite(prof.domain).all() else np.inf
    # Newton's method on every sample while many are still to do, then on those left only. The
    # evaluations expected to be a sample's last (few samples still unconverged) take the
    # profile's derivatives to the order the rates need, kept so that the rates reuse them.
    rates_order = max(2, state.order + 1)
    few = max(N // 8, 1)
    err = np.full(N, np.nan)
    kept, fresh = None, np.zeros(N, dtype=bool)
    sel, high = None, False
    for it in range(MAX_ITERATIONS):
        here = slice(None) if sel is None else sel
        qs, us = (q, u) if sel is None else (q[sel], u[sel])
        D = prof.derivatives(us, rates_order if high else 2)
        ev = _equations(cf, mech, state, qs, us, d, D, sel)
        g1, g2, g1q, g1u, g2q, g2u, (w1, w2, _) = ev
        with np.errstate(invalid="ignore", divide="ignore"):
            err[here] = np.maximum(np.abs(g1) * w1, np.abs(g2) * w2)
        if high:
            if kept is None:
                kept = (np.full((rates_order + 1, N, 2), np.nan),
                        [np.full(N, np.nan) for _ in range(9)])
            kept[0][:, here] = D
            for a_, b_ in zip(kept[1], ev[:6] + ev[6]):
                a_[here] = b_
        fresh[here] = high
        if it == 0:
            active &= np.isfinite(err)
        converged = active & (err <= tol)
        todo = active & ~(converged & polished)
        if not todo.any():
            break  # err is the residual at the final q, u
        high = np.count_nonzero(active & ~converged) <= few
        polished |= converged  # one more step after convergence leaves only rounding
        t = todo[here]
        with np.errstate(invalid="ignore", divide="ignore"):
            det = g1q * g2u - g1u * g2q
            dq = (g1u * g2 - g2u * g1) / det
            du = (g2q * g1 - g1q * g2) / det
        # damped as the generic path: at most a radian (a length) of q, an eighth of the profile
        damp = np.minimum(1.0, np.minimum(span / np.maximum(np.abs(dq), 1e-300),
                                          u_span / np.maximum(np.abs(du), 1e-300)))
        ok_step = t & np.isfinite(dq) & np.isfinite(du)
        active[here] &= ~(t & ~ok_step)
        q[here] = np.where(ok_step, qs + damp * dq, qs)
        u[here] = np.where(ok_step, us + damp * du, us)
        todo &= active
        idx = np.flatnonzero(todo)
        sel = idx if idx.size <= few else None
    else:
        g1, g2, *_, (w1, w2, _) = _equations(cf, mech, state, q, u, d)
        with np.errstate(invalid="ignore", divide="ignore"):
            err = np.maximum(np.abs(g1) * w1, np.abs(g2) * w2)
        fresh[:] = False
    q = np.where(converged, q, np.nan)
    u = np.where(converged, u, np.nan)
    _write_pose(cf, state, Jet(q[None]), fi)
    state.Q[0, :, ri, 0] = u - d.u0
    state.Q[0, :, ri, 1:] = np.where(converged, 0.0, np.nan)[:, None]
    if reseat and cf.pair.follower == "roller" and not contact._convex_outside(mech, cf.pair.name):
        cut = _cuts(cf, state, converged)
        if cut.any():
            u_near = contact.nearest_on_profile(mech, cf.pair.profile, _centre_on_cam(cf, state))[0]
            guess = state.Q[0][:, [fi, ri]].copy()
            guess[cut, 1, 0] = u_near[cut] - d.u0
            return positions(cf, state, guess, tol, reseat=False)
    state.contacts.pop(cf.pair.name, None)
    if kept is not None and fresh[converged].all():
        # with the poses written, to tell whether they are still the ones
        ev = tuple(kept[1][:6]) + (tuple(kept[1][6:]),)
        state.contacts[cf.pair.name] = (state.Q[0, :, [fi, ri]].copy(), q, u, kept[0], ev)
    return converged, np.where(converged, err, np.nan)


SEED_SAMPLES = 1024  # profile points tried per sample when the contact is sought afresh


def _seeds(cf: CamFollower, state, guess: np.ndarray, lost: np.ndarray, d) -> np.ndarray:
    """Starting guesses (generic rows) at the samples `lost`, which the continuation did not
    reach (it stops where the contact it follows ends, as a roller bridging a hollow): every
    place on the profile where the roller's centre (the knife's tip) would lie on the
    follower's path (its guide's line, its hinge's circle) is a candidate; those at which the
    roller would overlap the profile elsewhere are dropped, and of the others the one nearest
    to the follower's position at the nearest reached input is taken. NaN where there is none."""
    mech = state.mech
    j = cf.pair
    prof = mech.profiles[j.profile]
    out = np.full((int(lost.sum()), 2, 3), np.nan)
    lo, hi = prof.domain
    if not (np.isfinite(lo) and np.isfinite(hi)):
        return out
    us = np.linspace(lo, hi, SEED_SAMPLES + (0 if prof.closed else 1), endpoint=not prof.closed)
    D = prof.derivatives(us, 1)
    nl = np.stack([-D[1][:, 1], D[1][:, 0]], axis=1) / np.hypot(*D[1].T)[:, None]
    centres = D[0] + d.sign * j.radius * nl  # in the cam's coordinates
    idx = np.flatnonzero(lost)
    ax, ay, ac, as_ = (v[idx] for v in _pose(state, cf.cam))
    wx = ax[:, None] + ac[:, None] * centres[:, 0] - as_[:, None] * centres[:, 1]
    wy = ay[:, None] + as_[:, None] * centres[:, 0] + ac[:, None] * centres[:, 1]
    bx, by, bc, bs = (v[idx] for v in _pose(state, cf.base))
    p = np.asarray(mech.points[j.point], float)
    if cf.hinge is None:  # the guide's line: C(q) = B + Rb·p + q·Rb·a
        a = cf.axis * cf.sense
        ex, ey = (bc * a[0] - bs * a[1])[:, None], (bs * a[0] + bc * a[1])[:, None]
        ox, oy = (bx + bc * p[0] - bs * p[1])[:, None], (by + bs * p[0] + bc * p[1])[:, None]
        f = (wx - ox) * ey - (wy - oy) * ex
        qs = (wx - ox) * ex + (wy - oy) * ey
    else:  # the hinge's circle
        hx, hy = (bx + bc * cf.hinge[0] - bs * cf.hinge[1])[:, None], \
            (by + bs * cf.hinge[0] + bc * cf.hinge[1])[:, None]
        v = p - cf.hinge
        f = np.hypot(wx - hx, wy - hy) - np.hypot(*v)
        qs = np.arctan2(wy - hy, wx - hx) - np.arctan2(v[1], v[0])
    nxt = np.roll(np.arange(us.size), -1) if prof.closed else np.arange(1, us.size + 1).clip(max=us.size - 1)
    with np.errstate(invalid="ignore"):
        cross = (np.sign(f) != np.sign(f[:, nxt])) & np.isfinite(f) & np.isfinite(f[:, nxt])
    if not prof.closed:
        cross[:, -1] = False
    n, i = np.nonzero(cross)
    if n.size == 0:
        return out
    k = nxt[i]
    w = f[n, i] / (f[n, i] - f[n, k])
    span = np.where(k > i, us[k] - us[i], us[k] + (hi - lo) - us[i])
    uc = us[i] + w * span
    qc = qs[n, i] + w * (qs[n, k] - qs[n, i] if cf.hinge is None
                         else np.angle(np.exp(1j * (qs[n, k] - qs[n, i]))))
    if j.follower == "roller":  # a candidate overlapping the profile elsewhere is no contact
        cx = centres[i] + w[:, None] * (centres[k] - centres[i])
        _, gap = contact.nearest_on_profile(mech, j.profile, cx)
        keep = gap >= j.radius * (1 - 1e-3)
        n, uc, qc = n[keep], uc[keep], qc[keep]
        if n.size == 0:
            return out
    # the follower's position at the nearest reached input (the design's without any)
    reached = ~lost & np.isfinite(guess).all(axis=(1, 2))
    x = np.column_stack([c[0] for c in state.inputs.values()])
    q_ref = np.zeros(idx.size)
    if reached.any():
        r_idx = np.flatnonzero(reached)
        near = r_idx[np.argmin(np.abs(x[idx][:, None, :] - x[r_idx][None]).sum(axis=2), axis=1)]
        q_ref = _start(cf, state, guess[near], d.u0)[0] if cf.hinge is not None else \
            _start_at(cf, state, guess, near, d.u0)
    score = np.abs(qc - q_ref[n]) if cf.hinge is None else np.abs(np.angle(np.exp(1j * (qc - q_ref[n]))))
    order = np.lexsort((score, n))
    first = order[np.unique(n[order], return_index=True)[1]]
    m = n[first]
    out[m] = 0.0
    if cf.hinge is None:  # the follower's origin, slid along the guide (as `_start` reads it)
        out[m, 0, 0] = bx[m] + qc[first] * ex[m, 0]
        out[m, 0, 1] = by[m] + qc[first] * ey[m, 0]
    else:
        out[m, 0, 2] = qc[first]
    out[m, 1, 0] = uc[first] - d.u0
    return out


def _start_at(cf: CamFollower, state, guess: np.ndarray, rows: np.ndarray, u0: float) -> np.ndarray:
    """A guide's slide q of the guesses at the sample indices `rows` (their base's poses)."""
    bx, by, bc, bs = (v[rows] for v in _pose(state, cf.base))
    a = cf.axis * cf.sense
    ax, ay = bc * a[0] - bs * a[1], bs * a[0] + bc * a[1]
    return (guess[rows, 0, 0] - bx) * ax + (guess[rows, 0, 1] - by) * ay


def _centre_on_cam(cf: CamFollower, state) -> np.ndarray:
    """(N, 2) the roller's centre (as placed in Q[0]) in the cam's coordinates."""
    fx, fy, fc, fs = _pose(state, cf.follower)
    ax, ay, ac, as_ = _pose(state, cf.cam)
    p = np.asarray(state.mech.points[cf.pair.point], float)
    x, y = fx + fc * p[0] - fs * p[1] - ax, fy + fs * p[0] + fc * p[1] - ay
    return np.stack([ac * x + as_ * y, -as_ * x + ac * y], axis=1)


def _cuts(cf: CamFollower, state, converged: np.ndarray) -> np.ndarray:
    """Samples at which the placed roller overlaps its profile somewhere (another touching)."""
    _, gap = contact.nearest_on_profile(state.mech, cf.pair.profile, _centre_on_cam(cf, state))
    with np.errstate(invalid="ignore"):
        return converged & (gap < cf.pair.radius - 1e-9 * state.mech.length_scale)


def _write_pose(cf: CamFollower, state, q: Jet, fi: int) -> None:
    """The follower's pose coefficients (orders 0 … q.order) from the jet of q."""
    K = q.order
    if cf.base == state.mech.frame and cf.hinge is None:  # the frame's pose is zero
        a = cf.axis * cf.sense
        state.Q[: K + 1, :, fi, 0] = q.c * a[0]
        state.Q[: K + 1, :, fi, 1] = q.c * a[1]
        state.Q[: K + 1, :, fi, 2] = 0.0
        state.forget_trig([fi])
        return
    b = state.Q[: K + 1, :, state.li(cf.base)]
    bx, by, bth = Jet(b[..., 0]), Jet(b[..., 1]), Jet(b[..., 2])
    bc, bs = bth.cos_sin()
    if cf.hinge is not None:
        hx, hy = bc * cf.hinge[0] - bs * cf.hinge[1], bs * cf.hinge[0] + bc * cf.hinge[1]
        c, s = q.cos_sin()
        x = bx + hx - (c * cf.hinge[0] - s * cf.hinge[1])
        y = by + hy - (s * cf.hinge[0] + c * cf.hinge[1])
        th = q
    else:
        a = cf.axis * cf.sense
        x = bx + q * (bc * a[0] - bs * a[1])
        y = by + q * (bs * a[0] + bc * a[1])
        th = bth
    state.Q[: K + 1, :, fi, 0] = x.c
    state.Q[: K + 1, :, fi, 1] = y.c
    state.Q[: K + 1, :, fi, 2] = th.c
    state.forget_trig([fi])


def _equations_on_jets(cf: CamFollower, state, q: Jet, u: Jet, D: np.ndarray) -> tuple[Jet, Jet]:
    """The two equations on jets (the cam's and base's poses from Q, q and u given; D: the
    profile's derivatives at u's value, of order q.order + 1 at least)."""
    mech = state.mech
    j = cf.pair
    d = contact._design(mech, j.name)
    K = q.order

    def pose(link):
        p = state.Q[: K + 1, :, state.li(link)]
        th = Jet(p[..., 2])
        c, s = th.cos_sin()
        return Jet(p[..., 0]), Jet(p[..., 1]), c, s

    def rot(c, s, vx, vy):
        return c * vx - s * vy, s * vx + c * vy

    ax_, ay_, ac, as_ = pose(cf.cam)
    c, t = u.compose(D[: K + 1]), u.compose(D[1: K + 2])
    px, py, tx0, ty0 = Jet(c.c[..., 0]), Jet(c.c[..., 1]), Jet(t.c[..., 0]), Jet(t.c[..., 1])
    cx, cy = rot(ac, as_, px, py)
    cx, cy = cx + ax_, cy + ay_
    tx, ty = rot(ac, as_, tx0, ty0)
    bx, by, bc, bs = pose(cf.base)

    def follower_point(p):
        if cf.hinge is not None:
            hx, hy = rot(bc, bs, cf.hinge[0], cf.hinge[1])
            c, s = q.cos_sin()
            rx, ry = rot(c, s, p[0] - cf.hinge[0], p[1] - cf.hinge[1])
            return bx + hx + rx, by + hy + ry
        a = cf.axis * cf.sense
        px_, py_ = rot(bc, bs, p[0], p[1])
        ax, ay = rot(bc, bs, a[0], a[1])
        return bx + px_ + q * ax, by + py_ + q * ay

    if j.follower in ("roller", "knife"):
        Cx, Cy = follower_point(mech.points[j.point])
        dx, dy = Cx - cx, Cy - cy
        g1 = dx * tx + dy * ty
        g2 = tx * dy - ty * dx
        if j.radius:
            g2 = g2 - (tx * tx + ty * ty).sqrt() * (d.sign * j.radius)
        return g1, g2
    Px, Py = follower_point(mech.points[j.point])
    if cf.hinge is not None:
        c, s = q.cos_sin()
        ex, ey = rot(c, s, j.axis[0], j.axis[1])
    else:
        ex, ey = rot(bc, bs, j.axis[0], j.axis[1])
    return ex * (cy - Py) - ey * (cx - Px), tx * ey - ty * ex


def _turn(v):
    """J·v: v turned a quarter turn counter-clockwise."""
    return -v[1], v[0]


def _add(*terms):
    """Σ of (weight, vector) pairs, vectors as (x, y) arrays; a weight None is 1, a vector None
    is zero (a part of the motion that is not there, as the rates of a still base)."""
    x = y = None
    for w, v in terms:
        if v is None:
            continue
        vx, vy = (v[0], v[1]) if w is None else (w * v[0], w * v[1])
        x, y = (vx, vy) if x is None else (x + vx, y + vy)
    return None if x is None else (x, y)


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


class _Rates:
    """The follower's rates to order 2 with the right-hand sides written out.

    The two equations do not change when both elements are turned together, so they are
    written in the cam's own coordinates: the follower's point (roller centre, knife tip or a
    point of the face) becomes d(t) = R(−θ_cam)(C − A) and a face's direction e(t) likewise,
    while the profile point p(u) and its tangent p′(u) are the profile's own. The Taylor
    coefficients of d and e follow from the base's and the cam's pose coefficients; those of
    p(u(t)) from u's (Faà di Bruno to order 2). r_k is the k-th coefficient of the equations
    with q_k = u_k = 0 (they enter linearly, through the Jacobian). The jets of
    `_equations_on_jets` give the same numbers (and the orders above 2)."""

    def __init__(self, cf: CamFollower, state, q0, D, sign: float):
        mech = state.mech
        self.cf, self.D, self.sign = cf, D, sign
        j = cf.pair
        Qa = state.Q[:, :, state.li(cf.cam)]
        Qb = state.Q[:, :, state.li(cf.base)]
        self.Qa, self.Qb = Qa, Qb
        self.still = cf.base == mech.frame  # (its rates are zero)
        self.ca, self.sa = state.cs(state.li(cf.cam))
        bc, bs = state.cs(state.li(cf.base))
        self.flat = j.follower == "flat"
        p = np.asarray(mech.points[j.point], float)
        # the follower's point C (world, order 0), ∂C/∂q, and the parts that the base's motion
        # turns: Rb·(vector) for the hinge's or the guide's offset
        if cf.hinge is not None:
            self.rbh = _rot(bc, bs, cf.hinge)            # R_b·h
            c, s = np.cos(q0), np.sin(q0)
            self.rqv = _rot(c, s, p - cf.hinge)         # R_q·(p − h)
            self.dC = _turn(self.rqv)
            C0 = _add((None, self.rbh), (None, self.rqv))
            if self.flat:
                self.ew = _rot(c, s, j.axis)            # the face turns with q
        else:
            a = cf.axis * cf.sense
            self.rba = _rot(bc, bs, a)                   # R_b·a
            self.w = _add((None, _rot(bc, bs, p)), (q0, self.rba))  # R_b·(p + q0 a)
            self.dC, C0 = self.rba, self.w
            if self.flat:
                self.ew = _rot(bc, bs, j.axis)           # the face turns with the base
        self.dq = self._in_cam(self.dC)                  # ∂d/∂q
        self.Y0 = self._in_cam((C0[0] + Qb[0, :, 0] - Qa[0, :, 0], C0[1] + Qb[0, :, 1] - Qa[0, :, 1]))
        if self.flat:
            self.E0 = self._in_cam(self.ew)
            self.dE = self._in_cam(_turn(self.ew)) if cf.hinge is not None else None

    def _in_cam(self, v):
        """R(−θ_cam)·v at the samples' cam angles (None stays None)."""
        if v is None:
            return None
        return self.ca * v[0] + self.sa * v[1], -self.sa * v[0] + self.ca * v[1]

    def _point(self, k: int, q1):
        """C_k (world) with q_k = 0 (k = 1, 2; q1 given for k = 2); None if zero."""
        hinge = self.cf.hinge is not None
        if self.still:
            return _add((-0.5 * q1 * q1, self.rqv)) if hinge and k == 2 else None
        b = self.Qb
        t1 = b[1, :, 2]
        bk = (b[k, :, 0], b[k, :, 1])
        if hinge:
            if k == 1:
                return _add((None, bk), (t1, _turn(self.rbh)))
            return _add((None, bk), (b[2, :, 2], _turn(self.rbh)), (-0.5 * t1 * t1, self.rbh),
                        (-0.5 * q1 * q1, self.rqv))
        if k == 1:
            return _add((None, bk), (t1, _turn(self.w)))
        return _add((None, bk), (b[2, :, 2], _turn(self.w)), (-0.5 * t1 * t1, self.w),
                    (q1 * t1, _turn(self.rba)))

    def _face(self, k: int, q1):
        """e_k (world) of the face with q_k = 0; None if zero."""
        if self.cf.hinge is not None:  # turning with q
            return None if k == 1 else _add((-0.5 * q1 * q1, self.ew))
        if self.still:
            return None
        th1 = self.Qb[1, :, 2]
        if k == 1:
            return _add((th1, _turn(self.ew)))
        return _add((self.Qb[2, :, 2], _turn(self.ew)), (-0.5 * th1 * th1, self.ew))

    def _cam_coeffs(self, Y0, Y1, Y2=None, second=False):
        """d_1 (and d_2) of d = R(−θ_cam)·X from the coefficients Y_k = R(−θ_cam,0)·X_k."""
        t1 = self.Qa[1, :, 2]
        d1 = _add((None, Y1), (-t1, _turn(Y0)))
        if not second:
            return d1, None
        t2 = self.Qa[2, :, 2]
        d2 = _add((None, Y2), (-t1, None if Y1 is None else _turn(Y1)), (-t2, _turn(Y0)),
                  (-0.5 * t1 * t1, Y0))
        return d1, d2

    def _minus_cam_origin(self, C, k: int):
        """R(−θ_cam,0)·(C_k − A_k)."""
        a = self.Qa
        Ak = (a[k, :, 0], a[k, :, 1])
        return self._in_cam((-Ak[0], -Ak[1]) if C is None else (C[0] - Ak[0], C[1] - Ak[1]))

    def rhs(self, k: int, q1=None, u1=None):
        """(r1, r2): the k-th coefficients of the two equations with q_k = u_k = 0."""
        D = self.D
        P0, P1, P2 = (D[0, :, 0], D[0, :, 1]), (D[1, :, 0], D[1, :, 1]), (D[2, :, 0], D[2, :, 1])
        Y1 = self._minus_cam_origin(self._point(1, q1), 1)
        if k == 2:
            Y1 = _add((None, Y1), (q1, self.dq))
            Y2 = self._minus_cam_origin(self._point(2, q1), 2)
            d1, d2 = self._cam_coeffs(self.Y0, Y1, Y2, True)
            P3 = (D[3, :, 0], D[3, :, 1])
            t1 = (P2[0] * u1, P2[1] * u1)
            h = 0.5 * u1 * u1
            t2 = (P3[0] * h, P3[1] * h)
        else:
            d1, _ = self._cam_coeffs(self.Y0, Y1)
        if not self.flat:
            if k == 1:
                return _dot(d1, P1), _cross(*P1, *d1)
            e0 = (self.Y0[0] - P0[0], self.Y0[1] - P0[1])
            e1 = (d1[0] - u1 * P1[0], d1[1] - u1 * P1[1])
            e2 = (d2[0] - h * P2[0], d2[1] - h * P2[1])
            r1 = _dot(e2, P1) + _dot(e1, t1) + _dot(e0, t2)
            r2 = _cross(*P1, *e2) + _cross(*t1, *e1) + _cross(*t2, *e0)
            j = self.cf.pair
            if j.radius:
                n0 = np.hypot(*P1)
                n1 = _dot(P1, t1) / n0
                n2 = (2 * _dot(P1, t2) + _dot(t1, t1) - n1 * n1) / (2 * n0)
                r2 = r2 - self.sign * j.radius * n2
            return r1, r2
        # flat face: g1 = e × (p − P), g2 = p′ × e, in the cam's coordinates
        f0 = (P0[0] - self.Y0[0], P0[1] - self.Y0[1])
        E1 = self._in_cam(self._face(1, q1))
        if k == 1:
            e1, _ = self._cam_coeffs(self.E0, E1)
            return _cross(*e1, *f0) - _cross(*self.E0, *d1), _cross(*P1, *e1)
        E1 = _add((None, E1), (q1, self.dE))
        E2 = self._in_cam(self._face(2, q1))
        e1, e2 = self._cam_coeffs(self.E0, E1, E2, True)
        f1 = (u1 * P1[0] - d1[0], u1 * P1[1] - d1[1])
        f2 = (h * P2[0] - d2[0], h * P2[1] - d2[1])
        r1 = _cross(*e2, *f0) + _cross(*e1, *f1) + _cross(*self.E0, *f2)
        r2 = _cross(*P1, *e2) + _cross(*t1, *e1) + _cross(*t2, *self.E0)
        return r1, r2


def derivatives(cf: CamFollower, state, ok: np.ndarray, unreliable: float) -> np.ndarray:
    """Rates of q and u order by order from J·(q_k, u_k) = −r_k (the equations' k-th
    coefficients with q_k = u_k = 0: written out to order 2, `_Rates`, on jets above); the
    follower's pose and the contact row's coefficients from them. Returns the condition number
    of the scaled 2×2 Jacobian (rows in lengths, columns per unit length of q and of the
    profile)."""
    mech = state.mech
    d = contact._design(mech, cf.pair.name)
    fi, ri = state.li(cf.follower), state.li(contact.row_name(cf.pair))
    K, N = state.order, state.Q.shape[1]
    q0 = state.Q[0, :, fi, 2] if cf.hinge is not None else _start(
        cf, state, state.Q[0][:, [fi, ri]], d.u0)[0]
    u0 = state.Q[0, :, ri, 0] + d.u0
    last = state.contacts.pop(cf.pair.name, None)
    if (last is not None and last[3].shape[0] >= K + 2
            and not ((last[0] != state.Q[0, :, [fi, ri]]) & ok[None, :, None]).any()):
        # Newton's last evaluation, at the poses still in Q (its own q and u, which the poses
        # were written from: a guide's slide read back from them differs by rounding)
        q0, u0, D, ev = last[1:]
    else:
        D = mech.profiles[cf.pair.profile].derivatives(u0, max(K + 1, 2))  # once for every order
        ev = _equations(cf, mech, state, q0, u0, d, D)
    g1, g2, g1q, g1u, g2q, g2u, (w1, w2, nt) = ev
    det = g1q * g2u - g1u * g2q
    # scaled Jacobian: rows in lengths, the u column per length along the profile, a hinge's
    # q column per radian over the mechanism's size (as the generic path scales angles)
    L = mech.length_scale if cf.hinge is not None else 1.0
    m = np.stack([g1q * w1 / L, g1u * w1 / nt, g2q * w2 / L, g2u * w2 / nt], axis=-1)
    fro2 = np.einsum("ij,ij->i", m, m)
    dets = np.abs(m[:, 0] * m[:, 3] - m[:, 1] * m[:, 2])
    with np.errstate(invalid="ignore", divide="ignore"):
        cond = (fro2 + np.sqrt(np.maximum(fro2 * fro2 - 4 * dets * dets, 0.0))) / (2 * dets)
    good = ok & np.isfinite(cond) & (cond < unreliable)
    cond = np.where(ok & np.isfinite(cond), cond, np.inf)
    qc = np.zeros((K + 1, N))  # zeros: the jets of order k > 2 need q_k = u_k = 0
    uc = np.zeros((K + 1, N))
    qc[0], uc[0] = q0, u0
    rates = _Rates(cf, state, q0, D, d.sign) if K >= 1 else None
    with np.errstate(invalid="ignore", divide="ignore"):
        inv = np.where(good, 1.0 / det, np.nan)
        for k in range(1, K + 1):
            if k <= 2:
                r1, r2 = rates.rhs(k, qc[1] if k == 2 else None, uc[1] if k == 2 else None)
            else:
                r1, r2 = _equations_on_jets(cf, state, Jet(qc[: k + 1]), Jet(uc[: k + 1]), D)
                r1, r2 = r1.c[k], r2.c[k]
            qc[k] = (g1u * r2 - g2u * r1) * inv
            uc[k] = (g2q * r1 - g1q * r2) * inv
    _write_pose(cf, state, Jet(qc), fi)
    state.Q[1:, :, ri, 0] = uc[1:]
    state.Q[1:, :, ri, 1:] = np.where(good, 0.0, np.nan)[None, :, None]
    return cond
