"""A chain driven by given point velocities: free (frameless) and open chains at their drawn
position (Rosenauer 1937, paper 2: the plan of a free chain from v_A and v_B, of a triad from
v_K, v_L, v_M, of a serial chain from v_A, v_D and the directions of motion of B and C).

At the drawn position every link's pose is (0, 0, 0) (its own coordinates coincide with the
frame's), so the rates are linear: the pairs' equations J_p·q̇ = 0 leave the chain's velocity
states q̇ = N·z (N a basis of their null space, its dimension m the chain's mobility there), and
the given data (`model.given`) state m more equations J_c·q̇ = b. Accelerations solve the same
rows with the right-hand sides of the equations' second time derivatives, taken from jets
(`kinematics.jet`) of the constraints as `kinematics.constraints` writes them.

The count is checked against the rank, not against Grübler's formula (an over-closed chain
moves although the formula says it cannot): fewer conditions than degrees of freedom, or more,
is a `StructureError` naming the shortfall or the conditions that are too many; a square system
that is singular at this position (the triad whose three binary links' lines meet in a point)
is one too, naming the conditions that fail together and the motion they leave free.

`solve_given` returns a `Solution` (`GivenSolution`, with the conditions it solved) whose
samples are the N given velocity sets (sample axis first), so that points, poles (`instant`)
and the velocity constructions read it as any other.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..errors import StructureError
from ..model import Mechanism
from ..model.given import GivenDirection, GivenVelocity, batch_size, condition_count, normalized
from . import contact, intermittent
from .constraints import joint_residuals, point
from .jacobian import RANK_TOL
from .jet import Jet
from .solution import Solution, Status

#: a sample whose velocities may be off by more than this (relative, κ·ε) is `singular`
TOLERANCE = 1e-9
_EPS = float(np.finfo(float).eps)


class GivenSolution(Solution):
    """A `Solution` of a chain driven by given point data, at its drawn position; ``given``: the
    conditions solved, with their values broadcast to the N samples."""

    given: tuple = ()


def _pose_fn(mech: Mechanism, C: np.ndarray):
    """pose(link) → (x, y, θ, cos θ, sin θ) jets from Taylor coefficients C[k, batch, moving
    link, (x, y, θ)] of the moving links (the frame at rest)."""
    index = {ln: i for i, ln in enumerate(mech.moving_links)}
    shape = C.shape[:2]
    zero = Jet(np.zeros(shape))
    one = Jet.constant(1.0, shape[0] - 1, like=np.zeros(shape[1]))
    cache: dict[str, tuple] = {}

    def pose(ln: str):
        if ln == mech.frame:
            return zero, zero, zero, one, zero
        if ln not in cache:
            i = index[ln]
            x, y, th = (Jet(C[:, :, i, c]) for c in range(3))
            cache[ln] = (x, y, th, *th.cos_sin())
        return cache[ln]

    return pose


def _rows(mech: Mechanism, given, C: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pairs' residual jets and the given points' position jets at the poses C:
    (pairs (K+1, rows, batch), points (K+1, given, 2, batch))."""
    pose = _pose_fn(mech, C)
    pairs = [r.c for j in mech.joints for r in joint_residuals(mech, j, pose)]
    pts = [np.stack([c.c for c in point(pose, g.link, mech.points[g.point])], axis=1) for g in given]
    K1, B = C.shape[:2]
    P = np.stack(pairs, axis=1) if pairs else np.zeros((K1, 0, B))
    Q = np.stack(pts, axis=1) if pts else np.zeros((K1, 0, 2, B))
    return P, Q


def _jacobians(mech: Mechanism, given) -> tuple[np.ndarray, np.ndarray]:
    """∂(pair residuals)/∂q (rows × 3k) and ∂(given points)/∂q (given × 2 × 3k) at the drawn
    position, from first-order jets seeded with the unit vectors of the 3k coordinates."""
    k = len(mech.moving_links)
    C = np.zeros((2, 3 * k, k, 3))
    C[1].reshape(3 * k, 3 * k)[:] = np.eye(3 * k)
    P, Q = _rows(mech, given, C)
    return P[1], Q[1]


def _refuse_pairs(mech: Mechanism) -> None:
    for j in mech.joints:
        if contact.is_higher(j) or intermittent.is_intermittent(j):
            raise StructureError(f"pair '{j.name}' ({j.kind}): the solve from given point velocities "
                                 "takes lower pairs and gears only (a higher pair's contact "
                                 "coordinates are not eliminated here)")


def _broadcast(given, n: int) -> tuple:
    out = []
    for g in given:
        if isinstance(g, GivenVelocity):
            acc = None if g.acceleration is None else np.broadcast_to(g.acceleration, (n, 2))
            out.append(replace(g, velocity=np.broadcast_to(g.velocity, (n, 2)), acceleration=acc))
        else:
            d = np.broadcast_to(g.direction, (n, 2))
            k = None if g.curvature is None else np.broadcast_to(g.curvature, (n,))
            out.append(replace(g, direction=d / np.hypot(d[:, 0], d[:, 1])[:, None], curvature=k))
    return tuple(out)


def _normal(d: np.ndarray) -> np.ndarray:
    """The left normal of unit directions d (N, 2)."""
    return np.stack([-d[:, 1], d[:, 0]], axis=-1)


def _condition_rows(given, Jq: np.ndarray, n: int) -> tuple[np.ndarray, list[tuple[int, str]]]:
    """The conditions' rows (N, c, 3k) on the rates and which condition each row is."""
    rows, owner = [], []
    for i, g in enumerate(given):
        if isinstance(g, GivenVelocity):
            rows.extend(np.broadcast_to(Jq[i, a], (n, Jq.shape[-1])) for a in (0, 1))
            owner.extend([(i, "x"), (i, "y")])
        else:
            nrm = _normal(g.direction)
            rows.append(nrm @ Jq[i])
            owner.append((i, "normal"))
    return np.stack(rows, axis=1), owner


def _right_hand_sides(given, n: int) -> np.ndarray:
    out = []
    for g in given:
        if isinstance(g, GivenVelocity):
            out.extend((g.velocity[:, 0], g.velocity[:, 1]))
        else:
            out.append(np.zeros(n))
    return np.stack(out, axis=1)


def _null_space(Js: np.ndarray) -> tuple[np.ndarray, int]:
    """An orthonormal basis (3k × m) of the null space of the scaled pair rows, and their rank."""
    ncol = Js.shape[1]
    if Js.shape[0] == 0:
        return np.eye(ncol), 0
    _, s, Vt = np.linalg.svd(Js)
    top = s[0] if s.size else 0.0
    rank = int((s > RANK_TOL * top).sum()) if top > 0 else 0
    return Vt[rank:].T, rank


def _names(given, which) -> str:
    parts = list(dict.fromkeys(given[i].describe() for i in which))
    return ", ".join(parts[:-1]) + (" and " if len(parts) > 1 else "") + parts[-1]


def _dependent(M: np.ndarray) -> list[int]:
    """Rows of M that take part in a linear dependency (the support of its left null space)."""
    U, s, _ = np.linalg.svd(M)
    top = s[0] if s.size else 0.0
    r = int((s > RANK_TOL * top).sum()) if top > 0 else 0
    null = U[:, r:]
    return [int(i) for i in np.flatnonzero(np.abs(null).max(axis=1) > 1e-8)] if null.size else []


def _free_motion(mech: Mechanism, q: np.ndarray) -> str:
    """Words for a velocity state q (3k, scaled) the given data do not see: which links move,
    about which pole."""
    L = mech.length_scale
    big = np.abs(q).max()
    words = []
    for i, ln in enumerate(mech.moving_links):
        vx, vy, w = q[3 * i], q[3 * i + 1], q[3 * i + 2] / L
        if max(abs(vx), abs(vy), abs(w) * L) <= 1e-6 * big:
            continue
        if abs(w) * L <= 1e-9 * big:
            words.append(f"{ln} translates")
        else:
            P = np.array([-vy, vx]) / w  # where (vx, vy) + ω·J·X vanishes
            words.append(f"{ln} turns about ({P[0]:.4g}, {P[1]:.4g})")
    shown = words[:6] + (["…"] if len(words) > 6 else [])
    return "; ".join(shown) if shown else "no link moves"


def check_count(mech: Mechanism, given=None) -> int:
    """The chain's mobility at its drawn position, checked against the number of conditions
    ``given`` (default: the mechanism's own) state; `StructureError` when they differ."""
    given = mech.given if given is None else normalized(mech, given, alone=False)
    _refuse_pairs(mech)
    Jp, Jq = _jacobians(mech, given)
    return _count(mech, given, Jp, Jq)[1]


def _count(mech: Mechanism, given, Jp: np.ndarray, Jq: np.ndarray):
    L = mech.length_scale
    scale = np.tile([1.0, 1.0, 1.0 / L], len(mech.moving_links))  # θ columns in length units
    Nn, rank = _null_space(Jp * scale)
    m = Nn.shape[1]
    c = condition_count(given)
    if not given:
        raise StructureError(f"mechanism '{mech.name}' has no given point velocities (and the "
                             "solve from them needs some)")
    if c < m:
        raise StructureError(
            f"under-determined: {m - c} more condition{'s' if m - c > 1 else ''} needed — the chain "
            f"'{mech.name}' has {m} degrees of freedom at its drawn position and the given data "
            f"({_names(given, range(len(given)))}) state {c}; give further point velocities or "
            "directions")
    if c > m:
        one = _broadcast(given, 1)
        rows, owner = _condition_rows(one, Jq, 1)
        M = (rows[0] * scale) @ Nn
        extra = [owner[i][0] for i in _dependent(M)] or list(range(len(given)))
        # consistent (one motion satisfies them all, at the first sample) or contradictory
        b = _right_hand_sides(one, 1)[0]
        z = np.linalg.lstsq(M, b, rcond=None)[0] if m else np.zeros(0)
        off = float(np.linalg.norm(M @ z - b)) if m else float(np.linalg.norm(b))
        how = ("contradict each other: no motion of the chain has them all (two points of one link, "
               "for one, must have equal velocity components along the line joining them)"
               if off > 1e-9 * max(float(np.linalg.norm(b)), 1e-300) else
               f"say {c - m} time{'s' if c - m > 1 else ''} what the others fix already")
        raise StructureError(
            f"over-determined: {c - m} condition{'s' if c - m > 1 else ''} too many — the chain "
            f"'{mech.name}' has {m} degrees of freedom at its drawn position, the given data state "
            f"{c}: {_names(given, extra)} {how} (drop {c - m} condition{'s' if c - m > 1 else ''})")
    return Nn, m, scale


def solve_given(mech: Mechanism, given=None, *, order: int | None = None) -> GivenSolution:
    """Solve the chain ``mech`` at its drawn position from given point data: ``given`` (a
    sequence of `GivenVelocity` / `GivenDirection`, values (2,) or batches (N, 2); default: the
    mechanism's own, from its file's [[given]]). ``order`` 1: velocities; 2: also accelerations
    (each condition then needs its acceleration, or its path's curvature); default: 2 where the
    data allow it. Given explicitly, the conditions replace the mechanism's drivers (an open
    chain on its frame driven by point velocities instead of its crank)."""
    given = mech.given if given is None else normalized(mech, given, alone=False)
    _refuse_pairs(mech)
    has_acc = all((g.acceleration if isinstance(g, GivenVelocity) else g.curvature) is not None
                  for g in given)
    if order is None:
        order = 2 if has_acc and given else 1
    if order not in (1, 2):
        raise StructureError(f"order {order}: the solve from given point data gives velocities (1) "
                             "and accelerations (2)")
    if order == 2 and not has_acc:
        missing = [g for g in given if (g.acceleration if isinstance(g, GivenVelocity) else g.curvature) is None]
        raise StructureError("the accelerations need " + ", ".join(
            f"the acceleration of {g.point}" if isinstance(g, GivenVelocity) else
            f"the curvature of the path of {g.point} (0 for a straight guide)" for g in missing))
    Jp, Jq = _jacobians(mech, given)
    Nn, m, scale = _count(mech, given, Jp, Jq)
    n = batch_size(given)
    given = _broadcast(given, n)
    rows, owner = _condition_rows(given, Jq, n)
    M = (rows * scale) @ Nn  # (N, m, m)
    s = np.linalg.svd(M, compute_uv=False)
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = np.where(s[:, -1] > 0, s[:, 0] / s[:, -1], np.inf)
    singular = ~(s[:, -1] > RANK_TOL * s[:, 0])
    if singular.all():
        i = 0
        dep = sorted({owner[r][0] for r in _dependent(M[i])})
        _, _, Vt = np.linalg.svd(M[i])
        free = Nn @ Vt[-1]
        raise StructureError(
            f"singular at the drawn position: {_names(given, dep or range(len(given)))} do not fix "
            f"the chain '{mech.name}' there — with them held, one motion stays free ({_free_motion(mech, free)})"
            + (f"; all {n} samples" if n > 1 else ""))
    b = _right_hand_sides(given, n)
    Ms = np.where(singular[:, None, None], np.eye(m), M)
    z = np.linalg.solve(Ms, b[..., None])[..., 0]
    qd = (z @ Nn.T) * scale  # the rates (N, 3k): θ̇ = (L·θ̇)/L
    qd[singular] = np.nan
    k = len(mech.moving_links)
    C = np.zeros((order + 1, n, len(mech.links), 3))
    moving = [mech.link_index[ln] for ln in mech.moving_links]
    C[1][:, moving] = qd.reshape(n, k, 3)
    if order == 2:
        C[2][:, moving] = _accelerations(mech, given, Jp, Jq, Nn, scale, Ms, qd, owner).reshape(n, k, 3) / 2
    status = np.where(singular, Status.SINGULAR,
                      np.where(kappa * _EPS > TOLERANCE, Status.SINGULAR, Status.OK)).astype(np.int8)
    sol = GivenSolution(mech, np.zeros((n, 0)), None, C, status, kappa, errors=kappa * _EPS)
    sol.given = given
    return sol


def _accelerations(mech, given, Jp, Jq, Nn, scale, Ms, qd, owner) -> np.ndarray:
    """q̈ (N, 3k) from the given accelerations (points) and path curvatures (directions): the
    same rows as the rates, right-hand sides from the second-order jets at q̇ with q̈ = 0."""
    n, k = qd.shape[0], len(mech.moving_links)
    C = np.zeros((3, n, k, 3))
    C[1] = np.nan_to_num(qd).reshape(n, k, 3)
    P, Q = _rows(mech, given, C)
    quad_p = 2 * P[2].T  # (N, rows): J_p·q̈ + quad = 0
    quad_q = 2 * np.moveaxis(Q[2], -1, 0)  # (N, given, 2)
    vel_q = np.moveaxis(Q[1], -1, 0)
    # a particular solution of the pairs' rows, then the conditions on the rest
    pinv = np.linalg.pinv(Jp * scale)
    qp = (-quad_p @ pinv.T) * scale
    rhs = []
    for i, g in enumerate(given):
        if isinstance(g, GivenVelocity):
            want = g.acceleration - quad_q[:, i] - qp @ Jq[i].T
            rhs.extend((want[:, 0], want[:, 1]))
        else:
            nrm = _normal(g.direction)
            v2 = (vel_q[:, i] ** 2).sum(1)
            rhs.append(g.curvature * v2 - (nrm * (quad_q[:, i] + qp @ Jq[i].T)).sum(1))
    z = np.linalg.solve(Ms, np.stack(rhs, axis=1)[..., None])[..., 0]
    return qp + (z @ Nn.T) * scale
