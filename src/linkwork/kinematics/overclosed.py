"""Over-closed chains (*übergeschlossen*, *pārāk slēgtas ķēdes*): a solution order for chains
whose pairs repeat each other.

The triple parallel crank, Roberval's balance and the pantograph with its braces move only
thanks to special dimensions: some of their pair equations follow from the others (Rosenauer
§101). `topology.solution_order` counts freedoms and so refuses them as over-constrained. Here
the redundancy is read from the constraint Jacobian at the design position
(`jacobian.constraint_jacobian`): when the pairs leave exactly the drivers' freedoms (real
mobility = drivers) and the drivers fix every link, the chain is consistent at first order.
Then the fewest links whose removal (with their pairs) leaves a chain `solution_order` accepts
are set aside: the rest is solved as usual, and the links set aside form one last group with
more equations than unknowns, solved by Gauss–Newton (least squares), whose residual vanishes
where the redundancy is consistent. A warning names the redundant pairs.

A chain whose redundancy holds only at first order (a third crank parallel to the others but
of another length) closes at the design position and nowhere else: the last group is solved a
small step of the input away, and a pair that stays open there refuses the chain, named.
"""

from __future__ import annotations

import dataclasses
import warnings
from itertools import combinations

import numpy as np

from ..errors import LinkworkWarning, StructureError
from ..model import Mechanism
from ..topology import Group, solution_order
from .contact import rows
from .groups import GroupSolver, State, input_coefficients, least_squares, residual_and_jacobian
from .jacobian import RANK_TOL, constraint_jacobian, equation_names, numerical_rank

MAX_SET_ASIDE = 3  # links set aside at most (the pantograph with both braces needs two)
STEP = 1e-3        # the input step (rad, or L for a slide) of the finite consistency check
CLOSED = 1e-9      # largest residual (in L) of a closed pair there


def overclosed_order(mech: Mechanism, error: StructureError) -> tuple[Group, ...]:
    """The groups of an over-closed mechanism (see the module's docstring), or `error` raised
    again when the chain is not consistently over-closed."""
    J = constraint_jacobian(mech, drivers=True)
    k = len(mech.moving_links)
    n_pairs = len(J.rows) - len(mech.drivers)
    pairs_rank = numerical_rank(J.scaled[:n_pairs], RANK_TOL, reference=J.scaled)
    if 3 * k - pairs_rank != len(mech.drivers) or numerical_rank(J.scaled, RANK_TOL) != 3 * k:
        if 3 * k - pairs_rank < len(mech.drivers):
            rigid = [jn for jn, _ in J.rows[:n_pairs]]
            raise StructureError(
                f"over-constrained: the pairs of mechanism '{mech.name}' leave "
                f"{3 * k - pairs_rank} freedom{'s' if 3 * k - pairs_rank != 1 else ''} for "
                f"{len(mech.drivers)} driver{'s' if len(mech.drivers) != 1 else ''}: "
                f"{_dependent_text(J, n_pairs, rigid)} cannot all hold while it moves") from error
        raise error
    drivers = {d.driven for d in mech.drivers} | {d.base for d in mech.drivers}
    candidates = [ln for ln in reversed(mech.moving_links) if ln not in drivers]
    for size in range(1, MAX_SET_ASIDE + 1):
        for aside in combinations(candidates, size):
            base = _without(mech, set(aside))
            if base is None:
                continue
            try:
                groups = solution_order(base)
            except StructureError:
                continue
            pairs = tuple(j.name for j in mech.joints if set(j.links) & set(aside))
            last = Group(links=tuple(ln for ln in mech.link_names if ln in aside), joints=pairs,
                         drivers=())
            order = tuple(groups) + (last,)
            _check_finite(mech, order, last)
            warnings.warn(
                f"mechanism '{mech.name}' is over-closed (übergeschlossen): the pairs "
                f"{', '.join(pairs)} of {', '.join(last.links)} repeat what the others impose "
                f"({n_pairs - pairs_rank} redundant equation"
                f"{'s' if n_pairs - pairs_rank != 1 else ''}); solved in the least-squares sense, "
                "their residual checked at every sample", LinkworkWarning, stacklevel=4)
            return order
    raise error


def _dependent_text(J, n_pairs: int, names: list[str]) -> str:
    """The pairs taking part in a dependency of the pair rows (left null space), named."""
    P = J.scaled[:n_pairs]
    U, sv, _ = np.linalg.svd(P, full_matrices=True)
    r = int((sv > RANK_TOL * sv.max(initial=0.0)).sum())
    null = U[:, r:]
    support = np.abs(null).max(axis=1) > 1e-8 if null.size else np.zeros(n_pairs, dtype=bool)
    dep = list(dict.fromkeys(J.rows[i][0] for i in np.flatnonzero(support))) or names
    return "the pairs " + ", ".join(dep)


def _without(mech: Mechanism, aside: set[str]) -> Mechanism | None:
    """`mech` without the links `aside` and their pairs (None if a driver needs them)."""
    joints = tuple(j for j in mech.joints if not set(j.links) & aside
                   and getattr(j, "carrier", None) not in aside)
    if any(d.joint not in {j.name for j in joints} for d in mech.drivers):
        return None
    return dataclasses.replace(mech, links=tuple(ln for ln in mech.links if ln.name not in aside),
                               joints=joints)


def _check_finite(mech: Mechanism, order: tuple[Group, ...], last: Group) -> None:
    """Solve the order a small input step either side of the design; the set-aside group must
    close there (consistent redundancy), else the pair that stays most open is named."""
    solvers = [GroupSolver(mech, g) for g in order]
    design = np.array([[mech.driver_input_at_design(d) for d in mech.drivers]])
    scale = np.array([mech.length_scale if mech.joint(d.joint).kind == "prismatic" else 1.0
                      for d in mech.drivers])
    u = np.vstack([design, design + STEP * scale, design - STEP * scale])
    N = u.shape[0]
    state = State(mech, np.zeros((1, N, len(rows(mech)), 3)),
                  input_coefficients(mech, u, None, None, None, 0))
    L = mech.length_scale
    for s in solvers[:-1]:
        if s.kind == "generic":
            return  # Newton groups want continuation: the samples' own residuals will tell
        s.positions(state)
    # the set-aside links from their design poses (zero): Gauss–Newton on the group alone
    idx = [state.li(ln) for ln in last.links]
    for _ in range(30):
        r, Jq = residual_and_jacobian(state, last)
        state.Q[0][:, idx] += least_squares(Jq, -r).reshape(N, last.size, 3)
    r, _ = residual_and_jacobian(state, last)
    res = np.abs(r).max(axis=1)
    if (res <= CLOSED * L).all():
        return
    bad = int(np.argmax(res))
    names = [jn for jn in last.joints for _ in range(len(equation_names(mech.joint(jn))))]
    worst = names[int(np.argmax(np.abs(r[bad])))]
    raise StructureError(
        f"over-constrained: mechanism '{mech.name}' closes its pairs {', '.join(last.joints)} at "
        f"the design position only (its redundancy holds to first order, not along the motion): "
        f"a step of {STEP:g} in the input leaves pair {worst} open by {res[bad]:.3g} "
        f"({res[bad] / L:.2g} L); give the over-closing links dimensions that repeat the others "
        "(equal parallel cranks) or remove one of them")
