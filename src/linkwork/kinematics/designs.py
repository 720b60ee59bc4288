"""Many designs of one mechanism in one batch (the design sweeps' solver): `solve_designs` solves
D designs at their inputs, `whole_motions` runs each design through its whole motion
(`motion.whole_motion`: a crank's turn, a rocker between its limit positions), so that a sweep
is array work, not a Python loop over designs.

The designs' samples are laid out one after another in one pose array; the fused pass (`fused`)
walks each design's part with that design's tables (its dimensions are the tables' constants),
so designs of different dimensions, and even of different solution orders, share one batch. A
design's answer is the one `solve` / `whole_motion` give it alone (to rounding: the same
arithmetic, with sums over another batch). Designs the fused pass does not take (a Newton-solved
group, a cam or gear, no driver) are solved one by one with `solve` / `whole_motion`; with
`isolate=True` a design that fails (it cannot be planned, has no limit position, …) gets its
error in place of its solution and the others go on.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, LinkworkError
from ..model import ConstantSpeed, Mechanism
from . import kernels
from .fused import Tables, solve_blocks, tables

#: bisection steps per batch of the limit search over designs (every midpoint those steps may
#: visit solved at once, as `motion.bisect_brackets` does three at a time for one design): 31 samples per limit and
#: batch, twelve batches for the sixty steps, each batch one pass over all designs
TREE = 5
#: designs per batch of `whole_motions`: a design's plan, tables and change points are cached
#: per mechanism (`solver.plan`, `branches.branch_schedule`: 64 mechanisms each), and its
#: whole motion needs them several times, so more designs at a time would compute them again
WHOLE_BATCH = 32


def _one_by_one(isolate: bool, fn, *args, **kwargs):
    """`fn(*args, **kwargs)`, or with `isolate` the `LinkworkError` it raises."""
    try:
        return fn(*args, **kwargs)
    except LinkworkError as exc:
        if not isolate:
            raise
        return exc


@dataclass
class _Design:
    """A design prepared for the fused batch: its tables, samples and assembly branches."""

    mech: Mechanism
    solvers: tuple
    tab: Tables
    values: np.ndarray  # (N, drivers)
    t: np.ndarray | None
    coef: np.ndarray  # (drivers, 3, N): the inputs' Taylor coefficients
    signs_at: object  # slice of the design's samples → {group: assembly signs}


def _fused(mech: Mechanism):
    """(solvers, tables) of a design the fused pass takes, else None."""
    from .contact import rows
    from .solver import plan

    if not mech.drivers or len(rows(mech)) != len(mech.link_names):
        return None
    solvers = plan(mech)
    tab = tables(mech, solvers)
    return None if tab is None else (solvers, tab)


def _prepare(mech: Mechanism, inputs, times, velocities, accelerations,
             schedule: dict | None = None) -> _Design | None:
    """A design's samples as `solve` takes them (plain numbers or quantities; `times`: each
    driver's law at those times), with its tables and branches; None when the fused pass
    does not take it; `schedule`: its change points, if known (one driver)."""
    from .branches import branch_schedule, path_schedule
    from .groups import input_coefficients
    from .solver import driver_samples

    fused = _fused(mech)
    if fused is None:
        return None
    solvers, tab = fused
    nd = len(mech.drivers)
    t, values, velocities, accelerations, _, _ = driver_samples(
        mech, inputs, times, velocities, accelerations)
    c = input_coefficients(mech, values, velocities, accelerations, None, 2)
    coef = np.stack([c[d.joint] for d in mech.drivers])
    if nd == 1:
        schedules = branch_schedule(mech) if schedule is None else schedule

        def signs_at(sl: slice) -> dict:
            return {g: sch.signs(values[sl, 0]) for g, sch in schedules.items()}
    else:  # several drivers: a path through the samples (`solve`)
        schedules, lam, _ = path_schedule(mech, solvers, values)

        def signs_at(sl: slice) -> dict:
            return {g: sch.signs(lam[sl]) for g, sch in schedules.items()}
    return _Design(mech, solvers, tab, values, t, coef, signs_at)


def solve_designs(mechs, inputs=None, *, times=None, velocities=None, accelerations=None,
                  per_design: bool = False, compiled: bool | None = None,
                  isolate: bool = False, schedules: list | None = None) -> list:
    """Solutions of D designs of one mechanism (e.g. `sweeps.designs.apply` of each design's
    parameter values), as `solve(mech, inputs, times=…, velocities=…, accelerations=…)` gives
    each (order 2): one batch of all designs' samples, each `Solution` a view of its part.
    The same inputs for every design, or with `per_design` one entry per design in each of
    `inputs`, `times`, `velocities`, `accelerations` (sequences of D; None entries as in
    `solve`, so some designs may be given inputs and others times), each of its own length.
    Several drivers are followed as a path through the samples, as `solve` does; each design
    keeps its own assembly branch across its own change points (`branches`).

    Designs the fused pass does not take, or whose number of links, frame or drivers differ
    from the batch's, are solved one by one with `solve`, with the same result. `isolate`:
    a design that fails gets its `LinkworkError` in its place in the list, the others are
    solved. Plain numbers or quantities as for `solve`. `schedules`: per design its
    `branches.branch_schedule` where known already (one driver; None: found here)."""
    from .solver import KERNEL_BLOCK, _pose_array, _solution, solve
    from .precision import polishable

    mechs = list(mechs)
    D = len(mechs)
    if per_design:
        for a, name in ((inputs, "inputs"), (times, "times"), (velocities, "velocities"),
                        (accelerations, "accelerations")):
            if a is not None and len(a) != D:
                raise InputError(f"solve_designs: {len(a)} {name} for {D} designs (per_design: "
                                 "one entry per design)")

    def arg(a, d: int):
        return a[d] if per_design and a is not None else a

    out: list = [None] * D
    batch: list[tuple[int, _Design]] = []
    for d, m in enumerate(mechs):
        args = dict(inputs=arg(inputs, d), times=arg(times, d), velocities=arg(velocities, d),
                    accelerations=arg(accelerations, d))
        prep = _one_by_one(isolate, _prepare, m, args["inputs"], args["times"],
                           args["velocities"], args["accelerations"],
                           None if schedules is None else schedules[d])
        if isinstance(prep, LinkworkError):
            out[d] = prep
            continue
        first = batch[0][1].mech if batch else m
        if prep is None or len(m.link_names) != len(first.link_names) or \
                m.link_index[m.frame] != first.link_index[first.frame] or \
                len(m.drivers) != len(first.drivers):
            out[d] = _one_by_one(isolate, solve, m, args["inputs"], times=args["times"],
                                 velocities=args["velocities"],
                                 accelerations=args["accelerations"], compiled=compiled)
            continue
        batch.append((d, prep))
    if not batch:
        return out
    first = batch[0][1].mech
    sizes = [p.values.shape[0] for _, p in batch]
    starts = np.concatenate([[0], np.cumsum(sizes)])
    S, n_links, frame = int(starts[-1]), len(first.link_names), first.link_index[first.frame]
    Q = _pose_array(2, S, n_links, frame)
    T = np.empty((n_links, 2, S))
    T[frame, 0], T[frame, 1] = 1.0, 0.0
    coef = np.empty((len(first.drivers), 3, S))  # the inputs' Taylor coefficients, by design
    for (_, p), lo, hi in zip(batch, starts[:-1], starts[1:]):
        coef[:, :, lo:hi] = p.coef
    assembled = np.ones(S, dtype=bool)
    condition, errors, status_errors = np.ones(S), np.zeros(S), np.zeros(S)
    if compiled is None and S > kernels.INTERPRETED_UP_TO:
        # a batch that loads the compiled loops anyway: every design's branch scan (2 049
        # inputs, interpreted on its own) takes them too, some 100 ms less per design
        compiled = True
    with kernels.compiled_loops(compiled):
        for (_, p), lo, hi in zip(batch, starts[:-1], starts[1:]):
            def branches_in(sl: slice, lo=int(lo), p=p) -> dict:
                return p.signs_at(slice(sl.start - lo, sl.stop - lo))
            inputs_all = {d.joint: coef[i] for i, d in enumerate(p.mech.drivers)}
            solve_blocks(p.mech, p.tab, p.solvers, Q, T, inputs_all, branches_in, assembled,
                         condition, errors, status_errors, polishable(p.mech), U=coef,
                         start=int(lo), stop=int(hi), block=KERNEL_BLOCK)
    for (d, p), lo, hi in zip(batch, starts[:-1], starts[1:]):
        sl = slice(int(lo), int(hi))
        out[d] = _solution(p.mech, p.values, p.t, Q[:, sl], T[:, :, sl], assembled[sl],
                           condition[sl], errors[sl], status_errors[sl])
    return out


# ------------------------------------------------------------------------ whole motions
@dataclass
class _Search:
    """A one-driver design whose limit positions the batched search finds."""

    index: int
    mech: Mechanism
    solvers: tuple
    tab: Tables
    u0: float
    prismatic: bool
    schedule: dict  # `branches.branch_schedule` (empty until known)


def _placed(designs: list[_Search], us: list[np.ndarray], groups: list[int] | None = None):
    """Positions only of each design at its inputs, in one batch (the fused pass's first loop,
    design by design over its part): the first `groups[k]` groups of design k in the solution
    order (all by default), with the design's assembly branches. Returns per design whether
    every one of them assembles, and the poses: (Q0[link, (x, y, θ), sample] — θ not set —,
    T[link, (cos θ, sin θ), sample], the designs' first samples)."""
    sizes = [u.size for u in us]
    starts = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
    S, B = int(starts[-1]), max(max(sizes, default=1), 1)
    L = max(len(s.mech.link_names) for s in designs)
    Q0 = np.zeros((L, 3, S))  # the frame's rows stay zero
    T = np.zeros((L, 2, S))
    U = np.zeros((1, 3, S))
    ok = np.ones(S, dtype=bool)
    R = np.empty((max(max(s.tab.vectors for s in designs), 1), B))
    signs = np.empty((max(max(len(s.tab.signs) for s in designs), 1), B))
    nan = np.full(signs.shape[0], np.nan)  # every sign row read (`kernels.fused_positions`)
    for k, (s, u, lo, hi) in enumerate(zip(designs, us, starts[:-1], starts[1:])):
        T[s.mech.link_index[s.mech.frame], 0, lo:hi] = 1.0
        U[0, 0, lo:hi] = u
        given = {g: sch.signs(u) for g, sch in s.schedule.items()}
        for row, (group, design) in enumerate(s.tab.signs):
            signs[row, :hi - lo] = given.get(group, design)
        g = len(s.tab.ops) if groups is None else groups[k]
        kernels.fused_positions(ok, s.tab.ops[:g], s.tab.fl[:g], Q0, T, U, signs, nan, R,
                                int(lo), int(hi))
    return [ok[lo:hi] for lo, hi in zip(starts[:-1], starts[1:])], (Q0, T, starts)


def _assembles(designs: list[_Search], us: list[np.ndarray]) -> list[np.ndarray]:
    """`motion._assembles` of each design at its inputs, all in one batch: positions only,
    with the design's assembly branches, an input within `motion.CHANGE_POINT_TOL` of a change
    point counting as assembling."""
    from .branches import near_change_point
    from .motion import CHANGE_POINT_TOL

    out = []
    for s, u, a in zip(designs, us, _placed(designs, us)[0]):
        a = a.copy()
        if s.schedule and not a.all():  # a change point is passed, not a limit
            scale = 1.0 if not s.prismatic else s.mech.length_scale
            a |= near_change_point(s.mech, u, CHANGE_POINT_TOL * scale)
        out.append(a)
    return out


class _Touches(Exception):
    """A branch scan met a touching minimum: the design's change points need `branch_schedule`."""


def _no_change_points(designs: list[_Search]) -> list[bool]:
    """Per design (closed-form groups), whether `branches.branch_schedule` surely finds no change
    point: its scans of every dyad's discriminant h² and pivot gap over the input's period
    (the same grid, the design's signs, as long as none is found), taken for all designs in
    one batch, meet no touching minimum (`branches._touches`, which would refine it) and the
    design is not drawn at one (which `branch_schedule` warns of). False: ask
    `branch_schedule`, as for circle–line groups (whose scans this does not take)."""
    from .branches import BRANCHING, CHANGE, SCAN, _touches
    from .groups import State

    out = [False] * len(designs)
    todo = [k for k, s in enumerate(designs)
            if all(g.kind in ("driver", "RRR") for g in s.solvers)
            and any(g.kind in BRANCHING for g in s.solvers)]
    if not todo:
        return out
    designs = [designs[k] for k in todo]
    grids = []
    for s in designs:
        span = 8 * s.mech.length_scale if s.prismatic else 2 * np.pi
        grid = s.u0 - span / 2 + span * np.arange(SCAN + 1) / SCAN
        grids.append(np.append(grid, s.u0))  # the design input last
    dyads = [[i for i, g in enumerate(s.solvers) if g.kind == "RRR"] for s in designs]
    clear = np.ones(len(designs), dtype=bool)
    for j in range(max(len(d) for d in dyads)):
        # the positions up to and including each design's j-th dyad: NaN where any fails
        oks, (Q0, T, starts) = _placed(designs, grids, [d[j] + 1 if j < len(d) else 0
                                                        for d in dyads])
        for k, (s, grid, ok) in enumerate(zip(designs, grids, oks)):
            if j >= len(dyads[k]) or not clear[k]:
                continue
            lo, hi = starts[k], starts[k + 1]
            L = len(s.mech.link_names)
            Q = Q0[:L, :, lo:hi].copy()[None].transpose(0, 3, 1, 2)
            Q[:, ~ok] = np.nan
            state = State(s.mech, Q, {}, T=np.where(ok, T[:L, :, lo:hi], np.nan),
                          known=set(range(L)))
            dyad = s.solvers[dyads[k][j]]
            h2 = dyad.discriminant(state)
            if abs(h2[-1]) < CHANGE:  # drawn at a change or dead position
                clear[k] = False
                continue
            scan = grid[:-1]
            for g in (h2[:-1], dyad.pivot_gap(state)[:-1]):
                def scanned(u: np.ndarray, g=g, scan=scan) -> np.ndarray:
                    if u is scan:
                        return g
                    raise _Touches  # a minimum to refine
                try:
                    _touches(scanned, scan, 0, [], 0.0)
                except _Touches:
                    clear[k] = False
                    break
    for k, c in zip(todo, clear):
        out[k] = bool(c)
    return out


def _first_failures(designs: list[_Search], grids: list[np.ndarray], sign: float) -> list:
    """Per design, the index of the first offset of its grid at which u0 + sign·offset does
    not assemble (None if all do): `motion._first_failure`, all of the grid at once."""
    oks = _assembles(designs, [s.u0 + sign * g for s, g in zip(designs, grids)])
    return [None if a.all() else int(np.argmin(a)) for a in oks]


def _limits(designs: list[_Search]) -> list:
    """`motion.input_limits` of each design (closed-form groups, one driver), the scans and
    bisections of all designs batched: per design (lower, upper), None for a crank, or
    False where the search needs what only `input_limits` says (no limit on a side, or none
    at the design position itself: the design goes one by one, to its error or answer)."""
    from .motion import bisect_brackets

    spans = [4 * s.mech.length_scale if s.prismatic else 2 * np.pi for s in designs]
    grids = [np.linspace(0.0, span, 1441) for span in spans]
    up = _first_failures(designs, grids, +1.0)
    out: list = [None] * len(designs)
    need = [k for k, s in enumerate(designs) if s.prismatic or up[k] is not None]
    if not need:
        return out
    down = dict(zip(need, _first_failures([designs[k] for k in need], [grids[k] for k in need],
                                          -1.0)))
    brackets = []  # (design, sign, index of the first failure)
    for k in need:
        if up[k] in (None, 0) or down[k] in (None, 0):
            out[k] = False
        else:
            brackets += [(k, -1.0, down[k]), (k, 1.0, up[k])]
    if not brackets:
        return out
    sub = sorted({k for k, *_ in brackets})
    at = {k: i for i, k in enumerate(sub)}
    owner = np.array([at[k] for k, *_ in brackets])
    sign = np.array([b[1] for b in brackets])
    u0 = np.array([designs[k].u0 for k, *_ in brackets])
    lo = np.array([grids[k][j - 1] for k, _, j in brackets])
    hi = np.array([grids[k][j] for k, _, j in brackets])
    mine = [np.flatnonzero(owner == k) for k in range(len(sub))]

    def assembles(offsets: np.ndarray) -> np.ndarray:  # every design's brackets in one pass
        u = u0[:, None] + sign[:, None] * offsets
        ok = np.empty(offsets.shape, dtype=bool)
        for p, a in zip(mine, _assembles([designs[k] for k in sub], [u[p].ravel() for p in mine])):
            ok[p] = a.reshape(len(p), -1)
        return ok
    offset = bisect_brackets(assembles, lo, hi, TREE)
    limit = u0 + sign * offset
    for p in range(0, len(brackets), 2):
        out[brackets[p][0]] = (float(limit[p]), float(limit[p + 1]))
    return out


def whole_motions(mechs, *, compiled: bool | None = None, isolate: bool = False) -> list:
    """`motion.whole_motion(mech)` (order 2, the default step) of every design, in one batch:
    the limit positions of the designs that do not turn fully searched for all designs at once
    (the scan of `motion.input_limits` and its bisection, the same limits), then every design's
    samples solved by one `solve_designs` call. Designs driven by time laws (several drivers,
    or a law with a duration) are solved at their laws' 361 times in the same batch; designs
    the fused pass does not take go one by one through `whole_motion`. `isolate` as for
    `solve_designs`."""
    from .motion import motion_inputs, whole_motion

    mechs = list(mechs)
    if len(mechs) > WHOLE_BATCH:
        return [s for i in range(0, len(mechs), WHOLE_BATCH) for s in whole_motions(
            mechs[i:i + WHOLE_BATCH], compiled=compiled, isolate=isolate)]
    out: list = [None] * len(mechs)
    inputs, velocities, times, schedules = {}, {}, {}, {}
    search: list[_Search] = []
    alone = []
    with kernels.compiled_loops(compiled):
        for k, m in enumerate(mechs):
            try:
                fused = _fused(m)
                if fused is None:
                    alone.append(k)
                    continue
                laws = [d.law for d in m.drivers]
                if len(laws) > 1 or not isinstance(laws[0], ConstantSpeed):
                    if not all(law.duration for law in laws):
                        alone.append(k)  # to whole_motion's error
                    else:
                        times[k] = np.linspace(0.0, min(law.duration for law in laws), 361)
                    continue
                d = m.drivers[0]
                search.append(_Search(k, m, *fused, m.driver_input_at_design(d),
                                      m.joint(d.joint).kind == "prismatic", {}))
            except LinkworkError as exc:
                if not isolate:
                    raise
                out[k] = exc
        # the change points: none, as the batched scans show for most designs, or
        # `branch_schedule`'s (Brent's method on each touching minimum)
        from .branches import branch_schedule
        for s, clear in zip(list(search), _no_change_points(search) if search else []):
            try:
                s.schedule = {} if clear else branch_schedule(s.mech)
            except LinkworkError:
                search.remove(s)
                alone.append(s.index)  # to whole_motion's error
        limits = _limits(search) if search else []
        for s, lim in zip(search, limits):
            if lim is False:
                alone.append(s.index)
            else:
                inputs[s.index], velocities[s.index] = motion_inputs(
                    s.mech, lim, period=None if s.schedule else 2 * np.pi)
                schedules[s.index] = s.schedule
        for k in sorted(alone):
            out[k] = _one_by_one(isolate, whole_motion, mechs[k], order=2)
        batch = sorted(set(inputs) | set(times))
        sols = solve_designs([mechs[k] for k in batch], [inputs.get(k) for k in batch],
                             times=[times.get(k) for k in batch],
                             velocities=[velocities.get(k) for k in batch], per_design=True,
                             compiled=compiled, isolate=isolate,
                             schedules=[schedules.get(k) for k in batch])
    for k, s in zip(batch, sols):
        out[k] = s
    return out
