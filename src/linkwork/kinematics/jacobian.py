"""The constraint Jacobian of a whole mechanism at its design position.

Every pair's residuals (`constraints.joint_residuals`), optionally with the drivers', are
differentiated with respect to the poses (x, y, θ) of all moving links at once, by the same jets
with direction seeds that `groups.group_jacobian` uses for one group. At the design position
every link pose is (0, 0, 0), since each link's own coordinates coincide with the frame's there.

A higher pair's equations also contain its contact coordinates (`contact`), which belong to no
link: they are eliminated here. Of the pair's rows only the combinations that do not move the
contact coordinates are kept (the left null space of their columns): the cam's one equation
(the elements stay in touch) and the rolling pair's two. So the columns stay the link poses.

Its rank gives the real (instantaneous) mobility of the mechanism, whatever the counting rules
say; its row space tells which pair equations are redundant (over-closed chains, German
*übergeschlossen*, Latvian *pārāk slēgtas ķēdes*). `linkwork.structure.mobility` reads it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model import Joint, Mechanism
from ..topology import Group
from . import contact
from .constraints import joint_residuals
from .groups import State, _pose_fn, group_jacobian, least_squares, residual_and_jacobian

#: names of the residual equations of each pair kind, in the order `joint_residuals` returns them
EQUATIONS = {
    "revolute": ("x", "y"),
    "prismatic": ("normal", "angle"),
    "slot": ("normal",),
    "circular-slot": ("radius",),
    "gear": ("rolling",),
    "cam": ("contact",),
    "rolling": ("contact", "rolling"),
    "geneva": ("index",),
    "star-wheel": ("index",),
}

#: relative singular-value threshold below which a direction counts as free
RANK_TOL = 1e-9


@dataclass(frozen=True)
class DesignJacobian:
    """∂(constraint residuals)/∂(link poses) at the design position.

    `matrix` has one row per equation (`rows`: (joint, equation) pairs, drivers as
    (joint, "driver")) and one column per coordinate of a moving link (`columns`: (link, "x" |
    "y" | "θ")). `scaled` divides the angle columns by the mechanism's length scale, so that
    every entry is dimensionless and a rank decision with one relative tolerance is meaningful.
    """

    matrix: np.ndarray
    scaled: np.ndarray
    rows: tuple[tuple[str, str], ...]
    columns: tuple[tuple[str, str], ...]

    def rank(self, rows: np.ndarray | list[int] | None = None, tol: float = RANK_TOL) -> int:
        """Numerical rank of the (selected rows of the) scaled Jacobian."""
        m = self.scaled if rows is None else self.scaled[list(rows)]
        return numerical_rank(m, tol, reference=self.scaled)


def numerical_rank(m: np.ndarray, tol: float = RANK_TOL, *, reference: np.ndarray | None = None) -> int:
    """Rank of `m`: singular values above `tol` times the largest singular value of `reference`
    (default `m` itself), so that sub-matrices are judged by the same yardstick."""
    if m.size == 0:
        return 0
    ref = m if reference is None else reference
    top = np.linalg.norm(ref, 2) if ref.size else 0.0
    if top == 0.0:
        return 0
    s = np.linalg.svd(m, compute_uv=False)
    return int((s > tol * top).sum())


def equation_names(j: Joint) -> tuple[str, ...]:
    if j.kind == "rolling" and getattr(j, "carrier", None):
        return ("rolling",)  # on two pivots, as a gear pair: the pivots keep the wheels touching
    return EQUATIONS[j.kind]


def constraint_jacobian(mech: Mechanism, poses: np.ndarray | None = None, *, drivers: bool = False,
                        joints: tuple[str, ...] | None = None) -> DesignJacobian:
    """The Jacobian of all pair constraints (and, with `drivers`, the driver constraints) with
    respect to the poses of all moving links, at `poses` ((moving links, 3) array of x, y, θ in
    the order of `mech.moving_links`; default: the design position, all zero).

    `joints` selects and orders the pairs (default: all, in file order).
    """
    moving = mech.moving_links
    names = tuple(j.name for j in mech.joints) if joints is None else tuple(joints)
    drv = tuple(d.joint for d in mech.drivers) if drivers else ()
    higher = tuple(jn for jn in names if contact.is_higher(mech.joint(jn)))
    group = Group(links=moving + tuple(contact.row_name(mech.joint(jn)) for jn in higher),
                  joints=names, drivers=drv)
    state = _state(mech, poses)
    rows: list[tuple[str, str]] = []
    for jn in names:
        rows.extend((jn, eq) for eq in equation_names(mech.joint(jn)))
    rows.extend((d, "driver") for d in drv)
    cols = tuple((ln, c) for ln in moving for c in ("x", "y", "θ"))
    if not moving or not rows:
        J = np.zeros((len(rows), len(cols)))
    else:
        J = _eliminate_contacts(mech, names, group_jacobian(state, group)[0], len(moving))
    J = np.asarray(J, dtype=float).reshape(len(rows), len(cols))
    Js = J.copy()
    Js[:, 2::3] /= mech.length_scale
    return DesignJacobian(J, Js, tuple(rows), cols)


def _row_counts(mech: Mechanism, names: tuple[str, ...]) -> list[int]:
    """Rows each pair's `joint_residuals` returns."""
    return [contact.contact_row_count(mech.joint(jn)) if contact.is_higher(mech.joint(jn))
            else len(equation_names(mech.joint(jn))) for jn in names]


def _eliminate_contacts(mech: Mechanism, names: tuple[str, ...], J: np.ndarray, k: int) -> np.ndarray:
    """The Jacobian on the link poses alone: each higher pair's rows reduced to the
    combinations in which its contact coordinates do not appear."""
    out, at, c = [], 0, 0
    counts = _row_counts(mech, names)
    starts = dict(zip(names, np.cumsum([0] + counts[:-1])))
    for jn, n in zip(names, counts):
        block = J[at:at + n]
        j = mech.joint(jn)
        if contact.is_higher(j):
            Jc = block[:, 3 * (k + c):3 * (k + c) + 3]
            U = np.linalg.svd(Jc)[0]
            block = U[:, 3:].T @ block
            c += 1
            if getattr(j, "carrier", None):
                block = _rolling_on_pivots(mech, j, names, starts, J, block, k)
        out.append(block[:, :3 * k])
        at += n
    out.append(J[at:, :3 * k])  # the drivers
    return np.vstack(out)


def _rolling_on_pivots(mech: Mechanism, j, names, starts, J: np.ndarray, block: np.ndarray,
                       k: int) -> np.ndarray:
    """Of a rolling pair's two equations on the link poses, the one its wheels' pivots on the
    carrier do not already hold (they keep the wheels touching): the combination farthest from
    the pivot rows' span (the rolling), as a gear pair has one."""
    pivots = [jn for jn in names if mech.joint(jn).kind == "revolute"
              and set(mech.joint(jn).links) in ({j.carrier, j.links[0]}, {j.carrier, j.links[1]})]
    R = block[:, :3 * k]
    if pivots:
        P = np.vstack([J[starts[p]:starts[p] + 2, :3 * k] for p in pivots])
        _, sv, basis = np.linalg.svd(P, full_matrices=False)
        basis = basis[sv > 1e-12 * max(1.0, np.abs(P).max())]
        R = R - (R @ basis.T) @ basis
    w = np.linalg.svd(R)[0][:, 0]
    return w[None] @ block


def _close_contacts(mech: Mechanism, state: State) -> None:
    """Contact coordinates of every higher pair at the link poses in `state`: those that bring
    its elements closest (Gauss–Newton on the pair's rows, from the design contact)."""
    for j in mech.joints:
        if not contact.is_higher(j):
            continue
        g = Group(links=(contact.row_name(j),), joints=(j.name,), drivers=())
        i = state.li(contact.row_name(j))
        for _ in range(30):
            r, Jc = residual_and_jacobian(state, g)
            step = least_squares(Jc, -r)
            state.Q[0][:, i, :] += step
            if np.abs(step).max() <= 1e-15 * mech.length_scale:
                break


def design_jacobian(mech: Mechanism, *, drivers: bool = False,
                    joints: tuple[str, ...] | None = None) -> DesignJacobian:
    """`constraint_jacobian` at the design position."""
    return constraint_jacobian(mech, None, drivers=drivers, joints=joints)


def pair_residuals(mech: Mechanism, poses: np.ndarray) -> np.ndarray:
    """All pair residuals (length units, rows as in `constraint_jacobian`) at `poses`."""
    state = _state(mech, poses)
    _close_contacts(mech, state)
    pose = _pose_fn(state, (), None, 0)
    out: list[float] = []
    for j in mech.joints:
        res = np.array([float(np.ravel(r.c[0])[0]) for r in joint_residuals(mech, j, pose)])
        if contact.is_higher(j):
            # what the contact coordinates cannot close: the gap between the elements
            g = Group(links=(contact.row_name(j),), joints=(j.name,), drivers=())
            Jc = residual_and_jacobian(state, g)[1][0]
            if not (np.isfinite(Jc).all() and np.isfinite(res).all()):
                out.extend(np.full(res.size - 3, np.nan))  # poses far off: no gap to measure
                continue
            U = np.linalg.svd(Jc)[0]
            res = U[:, 3:].T @ res
        out.extend(res)
    return np.array(out)


def _state(mech: Mechanism, poses: np.ndarray | None) -> State:
    Q = np.zeros((2, 1, len(contact.rows(mech)), 3))
    if poses is not None:
        for ln, q in zip(mech.moving_links, np.asarray(poses, dtype=float).reshape(-1, 3)):
            Q[0, 0, mech.link_index[ln]] = q
    inputs = {d.joint: np.array([[mech.driver_input_at_design(d)], [0.0]]) for d in mech.drivers}
    return State(mech, Q, inputs)


__all__ = ["DesignJacobian", "EQUATIONS", "RANK_TOL", "constraint_jacobian", "design_jacobian",
           "equation_names", "numerical_rank", "pair_residuals"]
