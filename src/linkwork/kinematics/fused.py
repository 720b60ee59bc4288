"""The fused pass: one compiled walk through the whole solution order per block of samples,
for the mechanisms whose every group has a compiled closed form (revolute drivers on the frame,
RRR and RRP dyads: four-bars, slider-cranks, the Watt and Stephenson six-bars, Jansen's
linkage).

The per-group path (`solver.solve` with `groups.GroupSolver`) makes one pass over the batch per
group and kind of work (positions, rates, error bounds), each reading and writing the work
arrays of all samples again. Here the solution order is encoded once per mechanism as small
tables (`tables`: an opcode per group, its link indices and constants, which pivot is the
frame), and two loops of `kernels` walk them per sub-block of samples: `fused_positions`
(every group's positions) and `fused_rates` (every group's velocities, accelerations,
condition number and the forward error bounds of `precision`), each group's work a vectorised
block loop (`kernels._rrr_block_positions` …). Between the two, the links' angles are taken
with NumPy's vectorised arctan2 from the hinge vectors. The tables are data: one compiled
interpreter serves every mechanism.

The arithmetic is that of the per-group kernels (the same per-sample helpers), so the results
are the same to the last bit but for numba's contractions and the sign of zeros; the statuses,
condition numbers, error bounds and the polishing of samples near singular positions are those
of the per-group path (tests/kinematics/test_fused.py holds the two to each other), which stays
as the independent check. Measured (bench/README.md), the fused pass is 2.6–3× faster than
the per-group path; `designs.solve_designs` runs it too (a design's constants as a row of the
tables).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..model import Mechanism
from . import kernels
from .groups import UNRELIABLE_CONDITION, GroupSolver
from .precision import (_PLAIN, _STATUS_WEIGHTS, EPS, POLISH_LIMIT, TOLERANCE, coordinate_size,
                        polish)

@dataclass(frozen=True)
class Tables:
    """A mechanism's solution order for the fused loops (see `kernels.fused_positions`)."""

    #: (groups, 8) int64: opcode, link indices, sign row, hinge-vector row, and which pivot
    #: link is the frame (1: the first, A; 2: the second, C or the guide; 0: neither)
    ops: np.ndarray
    fl: np.ndarray  # (groups, 18) float64: the group's constants (`GroupSolver.fast`)
    #: in order: (hinge-vector row, link, φ): the link's angle is arctan2 of the row's vector
    #: less φ; (−1, block, guide): the block keeps the guide's angle (a guide on the frame:
    #: none, the loop has written the block's angle 0)
    angles: tuple
    vectors: int  # rows of hinge vectors
    signs: tuple  # per sign row: (group, design sign)


@lru_cache(maxsize=64)
def tables(mech: Mechanism, solvers: tuple[GroupSolver, ...]) -> Tables | None:
    """The tables of `mech` (its group solvers in solution order), or None when a group has no
    compiled closed form (Newton groups, cams, gears, prismatic drivers, a driver whose base
    is not the frame, higher pairs): such a mechanism takes the per-group path."""
    frame = mech.link_index[mech.frame]
    joints = {d.joint: i for i, d in enumerate(mech.drivers)}
    ops, fl, angles, signs = [], [], [], []
    vectors = 0
    for s in solvers:
        f = s.fast
        if f is None or (s.kind == "driver" and f["b"] != frame):
            return None
        o, c = np.full(8, -1, dtype=np.int64), np.zeros(18)
        if s.kind == "driver":
            o[:4] = kernels.DRIVER, f["b"], f["i"], joints[f["joint"]]
            c[:4] = *f["H"], f["u0"], f["cond"]
        elif s.kind == "RRR":
            o[:7] = kernels.RRR, f["iA"], f["iC"], f["i1"], f["i2"], len(signs), vectors
            c[:] = (*f["A"], *f["C"], f["diff"], f["L1sq"], f["tol"], f["branch"], *f["k1"],
                    *f["k2"], *f["BA"], *f["BC"], f["mid"], f["hd2"])
            angles += [(vectors, f["i1"], f["phi1"]), (vectors + 2, f["i2"], f["phi2"])]
            vectors += 4
        elif s.kind == "RRP":
            o[:7] = kernels.RRP, f["iA"], f["ig"], f["ir"], f["ib"], len(signs), vectors
            c[:14] = (*f["A"], *f["P"], *f["e0"], f["rsq"], f["tol"], s.design_sign, *f["k"],
                      *f["AP"], f["length"])
            angles.append((vectors, f["ir"], f["phi"]))
            if f["ig"] != frame:  # the block's angle is the guide's, known only after the loop
                angles.append((-1, f["ib"], f["ig"]))  # (on the frame: written in the loop)
            vectors += 2
        else:
            return None
        if s.kind != "driver":
            signs.append((s.group, s.design_sign))
            o[7] = 1 if o[1] == frame else 2 if o[2] == frame else 0
        ops.append(o)
        fl.append(c)
    return Tables(np.array(ops), np.array(fl), tuple(angles), vectors, tuple(signs))


def solve_blocks(mech: Mechanism, tab: Tables, solvers, Q: np.ndarray, T: np.ndarray,
                 inputs: dict, branches_in, assembled: np.ndarray, condition: np.ndarray,
                 errors: np.ndarray, status_errors: np.ndarray, can_polish: bool,
                 U: np.ndarray | None = None, start: int = 0, stop: int | None = None,
                 block: int = 1 << 17) -> bool:
    """Fill Q (Q[k, n, link, (x, y, θ)], order 2), T, and per sample `assembled`, `condition`,
    `errors`, `status_errors` (whatever they held before) as the per-group loop of
    `solver.solve` does, block by block: the samples start … stop − 1 (all by default) of these
    arrays (`designs.solve_designs`: one design's part of a batch of designs; U the stacked
    inputs, if at hand), `block` samples at
    a time (`solver.KERNEL_BLOCK`: the hinge vectors, assembly signs and error-bound work arrays
    are block-sized, not batch-sized; smaller blocks, which stay in the CPU's cache between the
    two passes, measured no faster). Returns whether a sample was polished (its poses
    rewritten, the frame's rows too)."""
    N = Q.shape[1] if stop is None else stop
    Qm = Q.transpose(0, 2, 3, 1)  # Qm[k, link, (x, y, θ), n]: the memory's order
    Q0 = Qm[0]
    if U is None:
        # (drivers, 3, N); one driver's coefficients as they are (no copy of the batch)
        U = inputs[mech.drivers[0].joint][None] if len(mech.drivers) == 1 else \
            np.stack([inputs[d.joint] for d in mech.drivers])
    per = np.array([mech.length_scale if mech.joint(d.joint).kind == "prismatic" else 1.0
                    for d in mech.drivers])
    B = max(1, min(N - start, block))
    R = np.empty((max(tab.vectors, 1), B))
    signs = np.empty((max(len(tab.signs), 1), B))
    fixed = np.empty(max(len(tab.signs), 1))
    E0 = np.empty(B)
    m, E = np.empty((3, B)), np.empty((3, B))
    L, m0 = mech.length_scale, coordinate_size(mech)
    polished = False
    for lo in range(start, N, B):
        hi = min(N, lo + B)
        sl, nb = slice(lo, hi), hi - lo
        given = branches_in(sl)
        for row, (group, design) in enumerate(tab.signs):
            if group in given:  # its change points: a sign per sample
                signs[row, :nb] = given[group]
                fixed[row] = np.nan
            else:  # the design's sign at every sample: a number, not a row of them
                fixed[row] = design
        kernels.fused_positions(assembled, tab.ops, tab.fl, Q0, T, U, signs, fixed, R, lo, hi)
        for row, i, phi in tab.angles:
            if row >= 0:  # in place: no temporary of the block's size
                np.arctan2(R[row + 1, :nb], R[row, :nb], out=Q0[i, 2, sl])
                Q0[i, 2, sl] -= phi
            else:  # a block turns with its guide
                Q0[i, 2, sl] = Q0[phi, 2, sl]
        ok = assembled[sl]
        Qb = Q[:, sl]
        if not ok.all():  # as `solver.solve`: NaN marks them
            Qb[:, ~ok] = np.nan
            T[:, :, sl][:, :, ~ok] = np.nan
        kernels.fused_rates(condition, tab.ops, tab.fl, Qm, T, U, per, L, EPS, m0,
                            UNRELIABLE_CONDITION, _PLAIN, _STATUS_WEIGHTS, errors, status_errors,
                            E0, m, E, lo, hi)
        if not ok.all():
            Qb[1:, ~ok] = np.nan
        err, serr, cond = errors[sl], status_errors[sl], condition[sl]
        # samples near a singular position: once more in extended precision (`precision`)
        sel = np.flatnonzero(ok & (serr > TOLERANCE) & (cond < POLISH_LIMIT)) \
            if can_polish and not serr.max(initial=0.0) <= TOLERANCE else np.zeros(0, dtype=int)
        if sel.size:
            polished = True
            e, se, c = polish(mech, solvers, Qb, T[:, :, sl],
                              {j: v[:, sl] for j, v in inputs.items()}, sel, E0[sel])
            done = np.isfinite(e)
            err[sel[done]], serr[sel[done]], cond[sel[done]] = e[done], se[done], c[done]
    return polished
