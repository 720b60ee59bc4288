"""`solve`: positions, velocities and accelerations of a mechanism for N inputs at once.

The solution order comes from `linkwork.topology.solution_order`; each group is solved for the
whole batch by `groups.GroupSolver`. Groups without a closed form get their Newton starting
values from `continuation` (a short sequential march on a coarse grid from the design position,
then one batched Newton solve at the samples).
"""

from __future__ import annotations

import sys
import threading
import warnings
from functools import lru_cache

import numpy as np

from ..errors import InputError, LinkworkWarning, StructureError
from ..model import ConstantSpeed, Mechanism, Prismatic
from ..topology import solution_order
from .branches import branch_schedule, path_schedule
from . import fused, kernels
from .contact import interference, rows
from .continuation import PathEnd, continuation_guesses, follow, lineage
from .groups import GroupSolver, State, input_coefficients
from .kept import Kept
from .precision import POLISH_LIMIT, TOLERANCE, ErrorBudget, polish, polishable
from .solution import Solution, Status

BLOCK = 8192  # samples per block when every group has a closed form
#: samples per block of the compiled kernels: a batch of this size or smaller is one block (a
#: block is no faster in the kernels, whose loops hold nothing but registers); larger batches
#: are cut so that the work arrays (error bounds, hinge vectors, branch signs) stay this size,
#: not the batch's (ten million samples of a four-bar: 3.7 GB of answer, a gigabyte less at
#: the peak)
KERNEL_BLOCK = 1 << 17
#: mechanisms whose every group has a compiled closed form take the fused pass (`fused`); off,
#: they take the per-group path (the tests compare the two)
FUSED = True


@lru_cache(maxsize=64)
def plan(mech: Mechanism) -> tuple[GroupSolver, ...]:
    """The group solvers of `mech` in solution order (computed once per mechanism); an
    over-closed chain is ordered by `overclosed` (its redundant links last, least squares).
    A mechanism that follows another (`continuation.follow`: a drag's frames) takes over the
    constants of the groups the two draw alike (`groups.drawn_alike`)."""
    try:
        order = solution_order(mech)
    except StructureError as exc:
        if not str(exc).startswith("over-constrained"):
            raise
        from .overclosed import overclosed_order
        order = overclosed_order(mech, exc)
    previous = lineage(mech)
    kept = _plans.get(previous) if previous is not None else None
    like = {s.group: s for s in kept} if kept is not None else {}
    out = tuple(GroupSolver(mech, g, like[g]) if g in like else GroupSolver(mech, g) for g in order)
    _plans.put(mech, out)
    return out


#: the last plans made, for the next frame of a drag to take constants from (`plan`)
_plans = Kept(8)


#: pose arrays of this many bytes and more (up to `SPARE_UP_TO`) are taken from the memory of
#: the last one once no solution refers to it any more (`_pose_memory`): below it, the C
#: library's allocator keeps freed memory for the next request itself; above it, it hands the
#: memory back to the system, and a new array of that size is paid again page by page (first
#: touches: a fifth of the time of a Jansen linkage's solve in a loop of solves). Not lower:
#: from 16 MB (a four-bar's 100 000 samples, 27 MB, kept as the spare) the four-bar's solve
#: in a loop took 2.5 times as long, measured: the allocator, no longer given back a freed
#: array that large, does not raise its threshold for fresh memory from the system above the
#: other arrays' sizes, and each of them is paid page by page again.
SPARE_FROM = 1 << 25
SPARE_UP_TO = 1 << 29  # … not beyond: a batch of millions keeps no gigabytes alive
#: the spare buffer, and (shape, frame) of the pose array in it whose frame rows are known to be
#: zero (None: not known)
_SPARE: list = [None, None]
_SPARE_LOCK = threading.Lock()


def _pose_memory(size: int, key=None) -> tuple[np.ndarray, bool]:
    """`size` float64s: the spare buffer of the last large pose array when no one refers to it
    (no `Solution` alive: its only references are the slot and this call), else fresh memory,
    which then becomes the spare; and whether it is the spare with the frame rows of `key`
    zero (until marked again, they are not known to be)."""
    if not SPARE_FROM <= 8 * size <= SPARE_UP_TO:
        return np.empty(size), False
    with _SPARE_LOCK:
        buf, zero = _SPARE
        _SPARE[1] = None
        # references: the slot, `buf` and getrefcount's argument
        if buf is not None and size <= buf.size <= 2 * size and sys.getrefcount(buf) == 3:
            return buf[:size], key is not None and zero == key
        _raise_mmap_threshold()
        _SPARE[0] = np.empty(size)
        return _SPARE[0], False


#: glibc serves requests above its mmap threshold with fresh pages from the system (paid page
#: by page on first touch) and raises that threshold to the size of such a block when it is
#: freed, up to 32 MiB. The spare is never freed, so without a freed block of its own a process
#: whose first large array is the spare kept every other large array of each solve (cos θ,
#: sin θ, the points) above the threshold: 1 600 page faults and 60 % more time per solve and
#: read of Jansen's linkage in a loop, measured. A block just under the limit, never touched,
#: costs one mmap and munmap.
_MMAP_RAISE = 30 << 20


def _raise_mmap_threshold() -> None:
    np.empty(_MMAP_RAISE // 8)


def _pose_array(order: int, N: int, n_links: int, frame: int) -> np.ndarray:
    """Q[k, n, link, (x, y, θ)], stored with the sample axis last in memory, so that every
    Q[k, :, link, c] the group solvers and `Solution` work on is contiguous (a C-ordered array
    would make each of them a strided walk over all of Q[k]). The frame's rows are zero (set
    here unless the spare memory holds them zero already, `_frame_rows_kept`); every other
    link's rows are written by the group that solves it (not zeroed first: on large batches
    that pass over memory is a noticeable part of the solve)."""
    shape = (order + 1, n_links, 3, N)
    mem, zero = _pose_memory(int(np.prod(shape)), (shape, frame))
    Q = mem.reshape(shape)
    if not zero:
        Q[:, frame] = 0.0
    return Q.transpose(0, 3, 1, 2)


def _frame_rows_kept(Q: np.ndarray, frame: int) -> None:
    """Note that the pose array Q (of `_pose_array`) leaves the solve with its frame rows as
    they were made, zero: when its memory is lent again as the spare for a pose array of the
    same shape and frame, they need not be written again (7 MB of a four-bar's 100 000
    samples). Only for solves in which nothing else writes them (no NaN of unassembled
    samples, no polish)."""
    shape = (Q.shape[0], Q.shape[2], Q.shape[3], Q.shape[1])
    with _SPARE_LOCK:
        buf = _SPARE[0]
        if buf is not None and Q.size <= buf.size and \
                Q.__array_interface__["data"][0] == buf.__array_interface__["data"][0]:
            _SPARE[1] = (shape, frame)


def _finish_block(state: State) -> None:
    """Hand a solved block over to `Solution`: cos θ and sin θ of every link in state.T (most
    of them written by the group solvers already)."""
    for i in range(state.T.shape[0]):
        state.cs(i)


def _as_2d(a, n_drivers: int, name: str, rows: int | None = None) -> np.ndarray | None:
    """`a` as (samples, drivers); with `rows`, one row (the same for every sample) or `rows`."""
    if a is None:
        return None
    arr = np.asarray(a, dtype=float)
    if arr.ndim == 0:
        arr = arr[None]
    if arr.ndim == 1:
        arr = arr[:, None] if n_drivers == 1 else arr[None, :]
    if arr.shape[1] != n_drivers:
        raise InputError(f"{name}: the mechanism has {n_drivers} driver(s), got {arr.shape[1]} "
                         "values per sample")
    if rows is not None and arr.shape[0] not in (1, rows):
        raise InputError(f"{name}: {arr.shape[0]} samples for {rows} inputs (give one per input, "
                         "or one for all)")
    return arr


def _plain_numbers(mech: Mechanism, inputs, times, *rates) -> tuple:
    """The arguments of `solve` with pint quantities converted to radians or the file's length
    unit (per second to the k-th power for the k-th rate) and seconds."""
    from ..units import column_magnitudes

    base = [mech.length_unit if isinstance(mech.joint(d.joint), Prismatic)
            else "rad" for d in mech.drivers]
    names = [f"driver '{d.joint}'" for d in mech.drivers]
    out = [column_magnitudes(inputs, base, "inputs", names),
           column_magnitudes(times, ["s"], "times", ["the time"])]
    for k, (a, what) in enumerate(zip(rates, ("velocities", "accelerations", "jerks", "snaps")),
                                  start=1):
        out.append(column_magnitudes(a, [f"{u} / s ** {k}" for u in base], what, names))
    return tuple(out)


def driver_samples(mech: Mechanism, inputs=None, times=None, velocities=None,
                   accelerations=None, jerks=None, snaps=None) -> tuple:
    """`solve`'s arguments as numbers per sample: (times or None, values, velocities,
    accelerations, jerks, snaps), each (N, drivers) or None where not given — at `times`, each
    driver's law (a constant speed from the design input), else the inputs (the design
    position when none are given) with their rates."""
    nd = len(mech.drivers)
    inputs, times, velocities, accelerations, jerks, snaps = _plain_numbers(
        mech, inputs, times, velocities, accelerations, jerks, snaps)
    if times is not None:
        t = np.atleast_1d(np.asarray(times, dtype=float))
        laws = np.stack([d.law.derivatives(t) for d in mech.drivers], axis=-1)  # (5, N, nd)
        for i, d in enumerate(mech.drivers):
            if isinstance(d.law, ConstantSpeed):
                laws[0, :, i] += mech.driver_input_at_design(d)
        return (t, *laws)
    if inputs is None:
        inputs = [[mech.driver_input_at_design(d) for d in mech.drivers]]
    values = _as_2d(inputs, nd, "inputs")
    if all(a is None for a in (velocities, accelerations, jerks, snaps)):
        velocities, accelerations, jerks, snaps = _law_rates(mech, values)
    return (None, values, *(_as_2d(a, nd, name, rows=values.shape[0]) for a, name in (
        (velocities, "velocities"), (accelerations, "accelerations"), (jerks, "jerks"),
        (snaps, "snaps"))))


def _law_rates(mech: Mechanism, values: np.ndarray) -> tuple:
    """The rates of drivers that follow a motion law of time, at input values: the law's at
    the time it takes the sample's value (`MotionLaw.time_of`), which every such driver must
    reach at one time. Where none is (a law that goes back, a value outside its span, drivers
    whose laws reach their values at different times) the rates are not known: NaN, and a
    warning naming the drivers. Laws of one speed at every time (constant speeds, linear laws,
    laws that stand still) need no time: their speed holds at any value."""
    if all(isinstance(d.law, ConstantSpeed) for d in mech.drivers):
        return None, None, None, None
    uniform = [d.law.speed if isinstance(d.law, ConstantSpeed) else d.law.uniform_speed
               for d in mech.drivers]
    moving = [i for i, v in enumerate(uniform) if v is None]
    N, nd = values.shape
    rates = np.zeros((4, N, nd))
    for i, v in enumerate(uniform):
        if v is not None:
            rates[0, :, i] = v
    if not moving:
        return tuple(rates)
    ts = np.stack([mech.drivers[i].law.time_of(values[:, i]) for i in moving], axis=-1)
    span = max(mech.drivers[i].law.duration for i in moving)
    known = np.all(np.isfinite(ts), axis=1) & \
        (np.ptp(ts, axis=1) <= 1e-9 * span if len(moving) > 1 else True)
    for k, i in enumerate(moving):
        rates[:, :, i] = mech.drivers[i].law.derivatives(np.nan_to_num(ts[:, k]))[1:5]
    if not known.all():
        rates[:, ~known] = np.nan
        names = ", ".join(f"'{mech.drivers[i].joint}'" for i in moving)
        warnings.warn(
            f"mechanism '{mech.name}': " + (
                f"driver {names} follows a motion law of time, and at {int((~known).sum())} "
                f"of {N} input values the law does not take the value at exactly one time"
                if len(moving) == 1 else
                f"drivers {names} follow motion laws of time, and at {int((~known).sum())} of "
                f"{N} input values their laws do not take the values at exactly one common "
                "time") +
            ": the rates there are not known (NaN); solve at times, or give the rates",
            LinkworkWarning, stacklevel=4)
    return tuple(rates)


def solve(mech: Mechanism, inputs=None, *, times=None, velocities=None, accelerations=None,
          jerks=None, snaps=None, order: int = 2, resume: PathEnd | None = None,
          previous: Mechanism | None = None, compiled: bool | None = None) -> Solution:
    """Solve `mech` at the given input values (shape (N,) for one driver, (N, drivers) else) or
    at `times` (each driver's law evaluated at those times).

    Plain numbers are radians for revolute inputs and the file's length unit for prismatic
    ones (seconds for `times`, per second and per second squared … for the rates); pint
    quantities (`linkwork.units.Q_([0, 30], "deg")`, `Q_(2, "rad/s")`) are converted to those,
    and a quantity of the wrong kind (a length for a revolute driver) is an `InputError`
    naming the driver. Several drivers of different kinds: one quantity per driver. Input speeds
    default to each driver's constant speed; give `velocities`/`accelerations` arrays to
    override them (for example the reversed speed of a rocker's return sweep).
    `order` = 3 also computes jerks, `order` = 4 the fourth derivatives (snaps) of the link
    poses, which curvature theory of higher order (Burmester points) needs; `jerks` and `snaps`
    give the inputs' third and fourth derivatives (default 0).

    Several drivers: the inputs are followed as a path, from the design input through the
    samples in their order — the Newton-solved groups by continuation, the two-assembly groups
    across the change points the path touches (`branches.path_schedule`). The solution's
    `path_end` is where it left off: `resume=` that in the next solve goes on from there
    instead of from the design input, so that samples solved in chunks are solved as in one
    piece. (One driver: every sample is solved on its own; `path_end` is None.)

    `previous`: a mechanism of the same structure solved before, with other dimensions (the
    last frame of a drag): the Newton-solved groups' march starts from its march, checked step
    by step (`continuation.follow`; what was taken: `continuation.carried(mech)`).

    `compiled`: run the numba-compiled loops (True), their interpreted source (False: no numba
    import, for a few samples), or choose by the batch's size (None; see
    `kernels.compiled_loops`, which sets the same choice for a whole block of calls).
    """
    if compiled is not None:
        with kernels.compiled_loops(compiled):
            return solve(mech, inputs, times=times, velocities=velocities,
                         accelerations=accelerations, jerks=jerks, snaps=snaps, order=order,
                         resume=resume, previous=previous)
    if order not in (1, 2, 3, 4):
        raise InputError("order must be 1 (velocities), 2 (accelerations), 3 (jerks) or 4 "
                         "(snaps)")
    if mech.given and not mech.drivers:
        # a free or open chain moves by its given point velocities at its drawn position only
        raise InputError(f"mechanism '{mech.name}' is driven by given point velocities "
                         "([[given]]), not by drivers: it has no inputs to solve at; use "
                         "kinematics.point_inputs.solve_given (as `linkwork analyze` does)")
    nd = len(mech.drivers)
    t, values, velocities, accelerations, jerks, snaps = driver_samples(
        mech, inputs, times, velocities, accelerations, jerks, snaps)
    N = values.shape[0]
    if previous is not None:  # every march of mech from here on, the change points' scans too
        follow(mech, previous)
    solvers = plan(mech)
    frame = mech.link_index[mech.frame]
    n_rows = len(rows(mech))  # the links, then the contact coordinates of higher pairs
    Q = _pose_array(order, N, n_rows, frame)
    inputs = input_coefficients(mech, values, velocities, accelerations, jerks, order, snaps)
    generic = any(s.kind == "generic" for s in solvers)
    path_end = None
    if nd == 1:
        schedules = branch_schedule(mech)

        def branches_in(sl: slice) -> dict:  # the signs of a block only (no N-long temporaries)
            return {g: sch.signs(values[sl, 0]) for g, sch in schedules.items()}
        guesses = continuation_guesses(mech, solvers, values) if generic else {}
    else:  # a path through the samples
        schedules, lam, path = path_schedule(mech, solvers, values, resume)
        branches = {g: sch.signs(lam) for g, sch in schedules.items()}

        def branches_in(sl: slice) -> dict:
            return {g: b[sl] for g, b in branches.items()}
        ends: dict = {}
        guesses = continuation_guesses(mech, solvers, values, schedules, start=resume,
                                       ends=ends) if generic else {}
        if np.isfinite(values).all() and len(path.vertices) > 0:
            end = path.knots[len(path.vertices) - 1]
            prev = len(path.vertices) >= 2
            path_end = PathEnd(
                path.vertices[-1], float(end), path.vertices[-2] if prev else None,
                float(path.knots[len(path.vertices) - 2]) if prev else float(end),
                schedules, ends.get("tail") if generic else None)
    tab = fused.tables(mech, solvers) if FUSED and order == 2 and not generic and \
        n_rows == len(mech.link_names) else None
    # the fused pass writes every sample of these itself (no pass over them beforehand);
    # status_errors: the errors with the accelerations weighted to their own tolerance
    fill = tab is None
    assembled = np.ones(N, dtype=bool) if fill else np.empty(N, dtype=bool)
    condition = np.ones(N) if fill else np.empty(N)
    errors, status_errors = (np.zeros(N), np.zeros(N)) if fill else (np.empty(N), np.empty(N))
    T = np.empty((n_rows, 2, N))  # cos θ, sin θ of every link, rows contiguous
    T[frame, 0], T[frame, 1] = 1.0, 0.0
    # Closed-form groups in NumPy work sample by sample, so the samples are solved in blocks
    # whose temporaries stay in the CPU cache (same operations per sample, same results); the
    # compiled kernels (positions at any order, rates at order 2) have few temporaries, kept to
    # KERNEL_BLOCK samples; the Newton path wants one batch.
    compiled = order == 2 and all(s.compiled for s in solvers)
    block = max(N, 1) if generic else KERNEL_BLOCK if compiled else BLOCK
    can_polish = polishable(mech)
    if tab is not None:  # one compiled pass through the solution order per sample
        polished = fused.solve_blocks(mech, tab, solvers, Q, T, inputs, branches_in, assembled,
                                      condition, errors, status_errors, can_polish,
                                      block=KERNEL_BLOCK)
        if not polished and assembled.all():
            _frame_rows_kept(Q, frame)
    else:
        for lo in range(0, N, block):
            sl = slice(lo, lo + block)
            state = State(mech, Q[:, sl], {j: c[:, sl] for j, c in inputs.items()}, T=T[:, :, sl],
                          known={frame}, branches=branches_in(sl))
            ok = assembled[sl]  # a view: updated in place
            for s in solvers:
                g = guesses.get(s.group)
                ok &= s.positions(state, None if g is None else g[sl])
            if not ok.all():
                # NaN marks them; the other samples keep their cos θ, sin θ (not recomputed: a
                # sample's answer does not depend on the others in its batch)
                state.Q[:, ~ok] = np.nan
                state.T[:, :, ~ok] = np.nan
                state.rots.clear()
            cond = condition[sl]
            budget = state.budget = ErrorBudget(mech, state)
            for s in solvers:
                np.maximum(cond, s.derivatives(state, ok), out=cond)
            if not ok.all():
                state.Q[1:, ~ok] = np.nan
            _finish_block(state)
            err = budget.relative(errors[sl])
            serr = budget.relative(status_errors[sl], for_status=True)
            # samples near a singular position: once more in extended precision
            sel = np.flatnonzero(ok & (serr > TOLERANCE) & (cond < POLISH_LIMIT)) if can_polish \
                else np.zeros(0, dtype=int)
            if sel.size:
                e, se, c = polish(mech, solvers, state.Q, state.T, state.inputs, sel, budget.E[0, sel])
                done = np.isfinite(e)  # else the double answer stays, with its bound
                err[sel[done]], serr[sel[done]], cond[sel[done]] = e[done], se[done], c[done]
    if n_rows > len(mech.link_names):  # higher pairs: a contact cut into is no contact
        cut = interference(mech, Q[0])
        if cut.any():
            Q[:, cut] = np.nan
            T[:, :, cut] = np.nan
            assembled &= ~cut
    sol = _solution(mech, values, t, Q, T, assembled, condition, errors, status_errors)
    sol.path_end = path_end
    return sol


def _solution(mech: Mechanism, values, t, Q, T, assembled, condition, errors,
              status_errors) -> Solution:
    """The `Solution` of a solved batch: the status per sample from its error bound (in
    place: no N-long temporaries beyond the masks), NaN where it did not assemble."""
    status = np.full(len(assembled), Status.OK, dtype=np.int8)
    status[status_errors > TOLERANCE] = Status.SINGULAR
    unassembled = ~assembled
    status[unassembled] = Status.UNREACHABLE
    condition[unassembled] = np.nan
    errors[unassembled] = np.nan
    return Solution(mech, values, t, Q, status, condition, trig=(T[:, 0].T, T[:, 1].T),
                    errors=errors)
