"""How far each sample of a solve can be from the exact answer, and polishing where that is
too far.

Near a dead centre or a change point (German *Totlage*, *Verzweigungslage*) a group's
Jacobian J is nearly singular. Rounding the positions (or stopping Newton's method) leaves
them off by about κ·ε·L, κ the condition number of the scaled J; the velocities, solved with
that J, then carry κ times the error of J, so about κ²·ε relative, the accelerations at a
change point κ³·ε. An `ok` that only asked for κ < 1e8 let a rocker's ω be 22 % wrong.

`ErrorBudget` carries a first-order forward error bound through the groups in solution order
(`kernels.propagate_errors`: each group amplifies the error of what it hangs on and of its own
residual by its κ). Its result per sample, `Solution.errors`, is the bound on the error of every
pose coefficient relative to the larger of the mechanism's natural scale (L, L·Ω, L·Ω², … with
Ω the inputs' rate) and the size of the answer itself at that order, for the positions,
velocities and accelerations (jerks and snaps, when asked for, carry one more factor κ per
order and are not covered). A sample is `ok` when it is at most `TOLERANCE`.

Samples above it are solved once more in extended precision (`polish`: NumPy's long double,
ε ≈ 1.1e-19 on x86-64; where the platform's long double is the double, polishing gains
nothing and the bound says so): every group by Newton's method from the double answer, the
residuals on long-double jets, the linear solves in double refined by long-double residuals;
the rates likewise. What is still above the tolerance stays `singular`, its pose returned.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..model import Mechanism
from .groups import (UNRELIABLE_CONDITION, GroupSolver, backward_error, State, _scaled, least_squares,
                     rate_residuals, residual_and_jacobian)

#: the largest forward error (relative to the natural scale, or to the answer where that is
#: larger) of an `ok` sample's positions and velocities
TOLERANCE = 1e-9
#: ... and of its accelerations. The bound grows like κ³ε for them (κ²ε for velocities): held to
#: 1e-9 it called samples of ordinary mechanisms (κ ≈ 150) singular whose accelerations are
#: right to 1e-13; at 1e-7 a sample is `ok` up to κ ≈ 700 and its accelerations carry 7 digits
ACCELERATION_TOLERANCE = 1e-7
#: per order (positions, velocities, accelerations): the weight that turns its bound into the
#: positions' tolerance, so that one comparison with TOLERANCE decides the status
_STATUS_WEIGHTS = np.array([1.0, 1.0, TOLERANCE / ACCELERATION_TOLERANCE])
_PLAIN = np.ones(3)
#: above this condition number Newton's method in long double is not tried: from the double
#: answer, off by κ·ε, it converges only while κ²·ε is well below 1
POLISH_LIMIT = 1e7
EPS = float(np.finfo(float).eps)
EPS_LONG = float(np.finfo(np.longdouble).eps)
NEWTON_STEPS = 8
REFINEMENTS = 3


@lru_cache(maxsize=64)
def coordinate_size(mech: Mechanism) -> float:
    """The drawing's coordinates over L (at least 1): rounding in the constraints is ε times
    the coordinates, not ε times L, when the drawing lies far from its origin."""
    xy = np.array(list(mech.points.values()))
    return max(1.0, float(np.abs(xy).max(initial=0.0)) / mech.length_scale)


def rate_scale(mech: Mechanism, inputs: dict) -> np.ndarray:
    """Ω per sample: the inputs' rate (rad/s; a slide's in L/s), the k-th Taylor coefficients
    counted as Ω^k; 1 where the inputs stand still (every rate is zero then)."""
    from . import kernels

    C = np.stack([np.asarray(inputs[d.joint], dtype=np.float64) for d in mech.drivers])
    per = np.array([mech.length_scale if mech.joint(d.joint).kind == "prismatic" else 1.0
                    for d in mech.drivers])
    out = np.empty(C.shape[2])
    kernels.rate_scales(C, per, out)
    return out


class ErrorBudget:
    """The running forward error bounds of a solve (one block of samples)."""

    def __init__(self, mech: Mechanism, state: State, eps: float = EPS) -> None:
        K, N = state.order, state.Q.shape[1]
        self.mech, self.eps = mech, eps
        self.E = np.zeros((K + 1, N))
        self.m = np.zeros((K + 1, N))
        self.m[0] = coordinate_size(mech)  # the sizes start at the drawing's coordinates
        self.omega = rate_scale(mech, state.inputs)

    def add(self, state: State, solver: GroupSolver, kappa: np.ndarray) -> None:
        """Account for one group just solved (poses and rates in state.Q) with condition
        numbers κ."""
        from . import kernels

        links = np.array([state.li(ln) for ln in solver.group.links], dtype=np.int64)
        Qm = state.Qm
        if Qm.dtype != np.float64:
            Qm = Qm.astype(np.float64)
        rho = state.residuals.get(solver.group)  # None: a closed form, exact but for rounding
        rho = np.zeros(0) if rho is None else np.ascontiguousarray(rho, dtype=np.float64)
        kernels.propagate_errors(Qm, links, self.mech.length_scale, self.omega,
                                 np.ascontiguousarray(kappa, dtype=np.float64), rho, self.m,
                                 self.E, self.eps)

    def relative(self, out: np.ndarray | None = None, *, for_status: bool = False) -> np.ndarray:
        """The bound per sample: each order's error over the larger of its natural scale and the
        answer's size, the largest of them; the storing in double adds ε. `for_status`: the
        accelerations' bound scaled by TOLERANCE/ACCELERATION_TOLERANCE (compare with
        TOLERANCE)."""
        from . import kernels

        out = np.empty(self.E.shape[1]) if out is None else out
        kernels.relative_errors(self.E, self.m, EPS, _STATUS_WEIGHTS if for_status else _PLAIN, out)
        return out


#: pairs whose equations run on long-double jets throughout (the contact equations of higher
#: pairs evaluate their profiles in double; intermittent pairs switch phases)
POLISHABLE_PAIRS = frozenset({"revolute", "prismatic", "slot", "circular-slot", "gear"})


def polishable(mech: Mechanism) -> bool:
    """Every group can be polished in long double (`POLISHABLE_PAIRS` only)."""
    return all(j.kind in POLISHABLE_PAIRS for j in mech.joints)


def polish(mech: Mechanism, solvers, Q: np.ndarray, T: np.ndarray, inputs: dict,
           sel: np.ndarray, bound: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Solve the samples `sel` (indices into the block) again in long double, starting from
    their double answers in Q, whose positions are off by at most `bound` (in L, from the double
    solve's `ErrorBudget`); write the results (rounded to double) into Q and T. Returns the new
    error bounds (plain and for the status, `ErrorBudget.relative`) and condition numbers of
    those samples (inf where Newton's method does not settle next to the double answer, which
    then stays).

    The bound is `ErrorBudget`'s with the long double's ε: safe, though at a change point it
    can be a thousand times the actual error. (Comparing with the same Newton solve in double,
    scaled by the ratio of the two ε, is no safe estimate: near the x-axis, say, the double
    solve's rounding can be as small as the long double's, and the comparison then says
    nothing.)"""
    Ql, cond, good, budget = _newton(mech, solvers, Q[:, sel], inputs, sel, bound, np.longdouble)
    err, status_err = budget.relative(), budget.relative(for_status=True)
    err[~good] = status_err[~good] = np.inf
    keep = sel[good]
    Q[:, keep] = Ql[:, good].astype(float)
    th = Ql[0][good][..., 2]  # (n, rows)
    T[:, 0, keep] = np.cos(th).astype(float).T
    T[:, 1, keep] = np.sin(th).astype(float).T
    return err, status_err, cond


def _newton(mech: Mechanism, solvers, Qd: np.ndarray, inputs: dict, sel: np.ndarray,
            bound: np.ndarray, dtype) -> tuple[np.ndarray, np.ndarray, np.ndarray, ErrorBudget]:
    """Every group of the samples `sel` by Newton's method in `dtype` from the double answers
    Qd, then their rates (linear solves in double refined by residuals in `dtype`). Returns the
    poses' Taylor coefficients, the condition numbers, whether Newton's method settled next to
    the double answer, and the error budget of the solve."""
    n = sel.size
    K = Qd.shape[0] - 1
    L = mech.length_scale
    P = coordinate_size(mech)
    eps = float(np.finfo(dtype).eps)
    Ql = Qd.astype(dtype)
    state = State(mech, Ql, {j: c[:, sel].astype(dtype) for j, c in inputs.items()})
    budget = ErrorBudget(mech, state, eps)
    cond = np.ones(n)
    good = np.ones(n, dtype=bool)
    for s in solvers:
        g = s.group
        idx = [state.li(ln) for ln in g.links]
        start = Qd[0][:, idx].astype(float)
        for _ in range(NEWTON_STEPS):
            r, J = residual_and_jacobian(state, g)
            res = np.abs(r).max(axis=1, initial=0.0).astype(float)
            todo = ~(res <= 4 * eps * P * L)  # each sample steps on its own, batch or not
            if not todo.any():
                break
            step = least_squares(J[todo].astype(float), -r[todo].astype(float))
            q = Ql[0][:, idx]
            q[todo] += step.reshape(-1, g.size, 3)
            Ql[0][:, idx] = q
        else:
            r, J = residual_and_jacobian(state, g)
            res = np.abs(r).max(axis=1, initial=0.0).astype(float)
        Jd = J.astype(float)
        kappa = np.full(n, np.inf)
        finite = np.isfinite(Jd).all(axis=(1, 2))
        if finite.any():
            kappa[finite] = np.linalg.cond(_scaled(Jd[finite], L, g.links))
        # Newton's method settled next to the double answer (not on another branch), to far
        # below what the double answer's bound allowed
        moved = np.abs(Ql[0][:, idx].astype(float) - start)
        moved[..., 2] *= L
        drift = moved.max(axis=(1, 2), initial=0.0)
        good &= finite & (res <= 1e3 * EPS * P * L) & (drift <= (10 * bound + 1e3 * EPS * P) * L)
        state.residuals[g] = backward_error(mech, res, eps)
        usable = kappa < UNRELIABLE_CONDITION
        for k in range(1, K + 1):
            b = -rate_residuals(state, g, k)
            x = np.full(b.shape[:1] + Jd.shape[2:], np.nan, dtype=dtype)
            if usable.any():
                Ju, bu = Jd[usable], b[usable]
                xu = least_squares(Ju, bu.astype(float)).astype(dtype)
                for _ in range(REFINEMENTS):  # iterative refinement with residuals in dtype
                    rr = bu - np.einsum("nij,nj->ni", J[usable], xu)
                    xu += least_squares(Ju, rr.astype(float))
                x[usable] = xu
            Ql[k][:, idx] = x.reshape(n, g.size, 3)
        cond = np.maximum(cond, kappa)
        budget.add(state, s, kappa)
    return Ql, cond, good, budget
