"""`solve_designs`: D designs of one mechanism × N inputs in one batch (the design sweeps'
solver): the designs' dimensions become per-design rows of the fused pass's tables (`fused`), so
that a sweep is array work, not a Python loop over designs."""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from . import kernels
from .fused import solve_blocks, tables


def solve_designs(mechs, inputs, *, velocities=None, accelerations=None,
                  compiled: bool | None = None) -> list:
    """Solutions of D designs of one mechanism (the same links, pairs and one driver; other
    dimensions, e.g. `sweeps.designs.apply` of each design's parameter values) at the same N
    inputs, as `solve(mech, inputs, …)` gives each: one batch of D·N samples, the designs'
    dimensions the per-design rows of the fused tables, solved into one pose array (each
    `Solution` a view of its part). Each design keeps its own assembly branch across its own
    change points (`branches.branch_schedule`). Designs the fused pass does not take (another
    solution order, a group without a compiled closed form, several drivers) are solved one
    by one with `solve`, with the same result.

    Plain numbers or quantities as for `solve` (the first design's units)."""
    from .branches import branch_schedule
    from .groups import input_coefficients
    from .precision import polishable
    from .solver import KERNEL_BLOCK, _as_2d, _plain_numbers, _pose_array, _solution, plan, solve

    mechs = list(mechs)
    if not mechs:
        return []
    first = mechs[0]
    plans = [plan(m) for m in mechs]  # once per design (more designs than plan's cache holds)
    tabs = [tables(m, p) if len(m.drivers) == 1 else None for m, p in zip(mechs, plans)]
    same = all(t is not None and t.ops.shape == tabs[0].ops.shape and
               (t.ops == tabs[0].ops).all() and m.link_names == first.link_names and
               m.length_unit == first.length_unit for t, m in zip(tabs, mechs))
    if not same:
        return [solve(m, inputs, velocities=velocities, accelerations=accelerations,
                      compiled=compiled) for m in mechs]
    inputs, _, velocities, accelerations, _, _ = _plain_numbers(
        first, inputs, None, velocities, accelerations, None, None)
    if inputs is None:
        raise InputError("solve_designs: give the inputs (one value per sample)")
    values = _as_2d(inputs, 1, "inputs")
    N, D = values.shape[0], len(mechs)
    velocities, accelerations = (_as_2d(a, 1, name, rows=N) for a, name in (
        (velocities, "velocities"), (accelerations, "accelerations")))
    n_links = len(first.link_names)
    Q = _pose_array(2, D * N, n_links, first.link_index[first.frame])
    T = np.empty((n_links, 2, D * N))
    T[first.link_index[first.frame], 0], T[first.link_index[first.frame], 1] = 1.0, 0.0
    joint = first.drivers[0].joint
    coef = np.empty((1, 3, D * N))  # the inputs' Taylor coefficients, design after design
    for d, m in enumerate(mechs):
        coef[0, :, d * N:(d + 1) * N] = input_coefficients(m, values, velocities, accelerations,
                                                           None, 2)[m.drivers[0].joint]
    inputs_all = {joint: coef[0]}
    assembled = np.ones(D * N, dtype=bool)
    condition, errors, status_errors = np.ones(D * N), np.zeros(D * N), np.zeros(D * N)
    out = []
    if compiled is None and D * N > kernels.INTERPRETED_UP_TO:
        # a batch that loads the compiled loops anyway: every design's branch scan (2 049
        # inputs, interpreted on its own) takes them too, some 100 ms less per design
        compiled = True
    with kernels.compiled_loops(compiled):
        for d, (m, tab, solvers) in enumerate(zip(mechs, tabs, plans)):
            lo = d * N
            schedules = branch_schedule(m)

            def branches_in(sl: slice, lo=lo, schedules=schedules) -> dict:
                return {g: sch.signs(values[sl.start - lo:sl.stop - lo, 0])
                        for g, sch in schedules.items()}
            solve_blocks(m, tab, solvers, Q, T, inputs_all, branches_in, assembled, condition,
                         errors, status_errors, polishable(m), U=coef, start=lo, stop=lo + N,
                         block=KERNEL_BLOCK)
    for d, m in enumerate(mechs):
        sl = slice(d * N, (d + 1) * N)
        out.append(_solution(m, values, None, Q[:, sl], T[:, :, sl], assembled[sl],
                             condition[sl], errors[sl], status_errors[sl]))
    return out
