"""Assembly branches across change points (German *Verzweigungslage*, the change position of a
four-bar whose pivots all fall on one line).

A closed-form RRR dyad chooses between its two assemblies by a sign: the side of AC on which
its hinge B lies, taken from the design drawing. At a limit position the dyad stretches out
(h², the squared distance of B from AC, crosses zero) and the input cannot go on. At a change
point h² only touches zero and the input goes on; the motion whose velocities stay continuous
(the one the real mechanism follows, carried by its inertia) crosses AC there, so the sign
flips. Keeping the design's sign would silently turn a parallelogram into an antiparallelogram
after the change point. The circle–line groups (RRP, rod in slot) choose the same way between
the two points where the rod's circle cuts the guided point's track; their change points are
where the circle touches the track without leaving it, as in the slider-crank whose rod is as
long as its crank. A dyad whose outer hinges A and C meet (the Galloway kite, Rosenauer §100:
crank as long as the frame, coupler as long as the rocker) flips too: the line AC turns over
there, and B keeps its place only on the other side of it.

For a mechanism with one driver, `branch_schedule` finds the change points of every such group
along the input once per mechanism, also below Newton-solved groups (whose poses along the scan
come from the continuation of the groups above, `continuation`): a scan of the input over its period (one turn, or two when
an upstream group flips an odd number of times per turn, so that the chain repeats only after
two), each touching minimum of h² refined by Brent's method and accepted when h vanishes there.
`Schedule.signs` then gives the sign at any input value: the design's sign times −1 for every
change point passed between the design input and the sample. Mechanisms with several drivers
keep the design's signs (their change points form curves in the input space).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import LinkworkWarning
from ..model import Mechanism
from .contact import rows
from .groups import GroupSolver, State, drawn_alike, input_coefficients
from .kept import Kept

BRANCHING = ("RRR", "RRP", "rod-in-slot")  # closed forms that choose between two assemblies
SCAN = 2048  # input samples per turn (or per 8 length scales of a prismatic input)
TOUCH = 1e-3  # relative discriminant (h²/L1²) below which a local minimum is refined
CHANGE = 1e-12  # … at the refined minimum below which it is a change point (h < 1e-6 L1)
MAX_TOUCHES = 16  # more touching minima per scan: a flat, degenerate h² (bounded cost)


@dataclass(frozen=True)
class Schedule:
    """The change points of one two-assembly group: its design sign, the input values where the sign flips,
    the period of the input (2π or 4π; None for a prismatic input) and the design input u0
    the flips are counted from."""

    sign: float
    change_points: tuple[float, ...]
    period: float | None
    u0: float

    def signs(self, u: np.ndarray) -> np.ndarray:
        """The group's sign at inputs u: flipped once per change point between u0 and u."""
        flips = np.zeros(u.shape, dtype=np.int64)
        for c in self.change_points:
            if self.period is None:
                flips += (u >= c).astype(np.int64) - int(self.u0 >= c)
            else:
                flips += (np.floor((u - c) / self.period)
                          - np.floor((self.u0 - c) / self.period)).astype(np.int64)
        return np.where(flips % 2 == 0, self.sign, -self.sign)

    def at(self, u: np.ndarray, lam: np.ndarray | None = None) -> np.ndarray:
        """The signs at inputs u (N, 1) (λ along a path is not needed: one driver)."""
        return self.signs(u[:, 0])


@dataclass(frozen=True)
class PathSchedule:
    """Several drivers: the change points of one two-assembly group as distances λ along the
    path of the inputs (`continuation.InputPath`: from the design input through the samples in
    their order), and its sign before the first of them."""

    sign: float
    change_points: tuple[float, ...]

    def signs(self, lam: np.ndarray) -> np.ndarray:
        """The group's sign at λ: flipped once per change point passed."""
        flips = np.searchsorted(np.asarray(self.change_points, dtype=float), lam, side="right")
        return np.where(flips % 2 == 0, self.sign, -self.sign)

    def at(self, u: np.ndarray, lam: np.ndarray) -> np.ndarray:
        return self.signs(lam)


def _poses(mech: Mechanism, N: int) -> np.ndarray:
    """Zero poses Q[0, n, row, (x, y, θ)] laid out as `solve` lays them out (the sample axis
    last in memory), so that the compiled kernels run the loops compiled for the solve rather
    than compiling another version (seconds) for another layout."""
    return np.zeros((1, len(rows(mech)), 3, N)).transpose(0, 3, 1, 2)


def placed(mech: Mechanism, solvers, u: np.ndarray, schedule: dict,
           guesses: dict | None = None) -> tuple[State, np.ndarray]:
    """Positions only of `solvers` (in the solution order) at inputs u (one driver), with the
    assembly signs of `schedule` (group → `Schedule`) and, for Newton groups, the starting
    values `guesses`; and the mask of the samples where every one of them assembles."""
    N = u.shape[0]
    state = State(mech, _poses(mech, N), input_coefficients(mech, u[:, None], None, None, None, 0),
                  branches={g: s.signs(u) for g, s in schedule.items()})
    ok = np.ones(N, dtype=bool)
    for s in solvers:
        ok &= (s.positions(state, (guesses or {}).get(s.group)) if s.kind == "generic"
               else s.positions(state))
    return state, ok


def _positions(mech: Mechanism, solvers: tuple[GroupSolver, ...], upto: GroupSolver,
               u: np.ndarray, branches: dict) -> State:
    """Positions of every group before and including `upto` at inputs u (one driver); NaN
    where a group cannot assemble (the closed forms leave finite values there). Newton groups
    upstream start from the continuation of these groups alone, with the change points found
    so far (all of them upstream of `upto`)."""
    from .continuation import continuation_guesses

    upstream = solvers[:solvers.index(upto) + 1]
    guesses = (continuation_guesses(mech, upstream, u[:, None], schedule=branches)
               if any(s.kind == "generic" for s in upstream) else {})
    state, ok = placed(mech, upstream, u, branches, guesses)
    if not ok.all():
        state.Q[:, ~ok] = np.nan
        state.forget_trig()
    return state


@lru_cache(maxsize=64)
def branch_schedule(mech: Mechanism) -> dict:
    """Group → `Schedule` for the two-assembly groups of a one-driver mechanism that have change
    points (groups not listed keep their design sign everywhere). A mechanism that follows
    another (`continuation.follow`: a drag's frames) whose every group the two draw alike
    (`groups.drawn_alike`: a tracer point moved) has that one's schedule: the scan would find
    the same numbers."""
    from .continuation import lineage
    from .solver import plan  # the solver imports this module

    solvers = plan(mech)
    if len(mech.drivers) != 1 or not any(s.kind in BRANCHING for s in solvers):
        return {}
    groups = tuple(s.group for s in solvers)
    previous = lineage(mech)
    kept = _schedules.get(previous) if previous is not None else None
    if kept is not None and kept[0] == groups and \
            all(drawn_alike(previous, mech, g) for g in groups):
        found, flagged = kept[1], kept[2]
        for s in solvers:
            if s.group in flagged:
                _warn_drawn_at_change(mech, s)
    else:
        found, flagged = _scan_schedule(mech, solvers)
    _schedules.put(mech, (groups, found, flagged))
    return found


#: mechanism -> (its groups, its schedule, the groups drawn at a change point), the last few
_schedules = Kept(8)


def _warn_drawn_at_change(mech: Mechanism, s: GroupSolver) -> None:
    warnings.warn(
        f"mechanism '{mech.name}': the drawing has the group {', '.join(s.group.links)} "
        "at a change or dead position (its pivots in line), so it does not define the "
        "assembly branch there; linkwork takes one side and follows it continuously",
        LinkworkWarning, stacklevel=3)


def _scan_schedule(mech: Mechanism, solvers) -> tuple[dict, set]:
    """`branch_schedule` found by scanning the input, and the groups the drawing has at a
    change point (warned of)."""
    flagged: set = set()
    d = mech.drivers[0]
    u0 = mech.driver_input_at_design(d)
    revolute = mech.joint(d.joint).kind == "revolute"
    found: dict = {}
    period = 2 * np.pi if revolute else None
    on_grid = _GridPlacement(mech, solvers)
    for k, s in enumerate(solvers):
        if s.kind not in BRANCHING:
            continue
        span = period if revolute else 8 * mech.length_scale
        n = SCAN * (int(round(span / (2 * np.pi))) if revolute else 1)
        grid = u0 - span / 2 + span * np.arange(n + 1) / n

        placed_at = _scan_once(lambda u: _positions(mech, solvers, s, u, found),
                               lambda u, k=k: on_grid.upto(k, u, found))

        def h2(u: np.ndarray) -> np.ndarray:
            return s.discriminant(placed_at(u))

        if abs(h2(np.array([u0]))[0]) < CHANGE:
            flagged.add(s.group)
            _warn_drawn_at_change(mech, s)
        def gap(u: np.ndarray) -> np.ndarray:
            return s.pivot_gap(placed_at(u))

        points: list[float] = []
        # where h² touches zero (a change point), and for a dyad where its outer hinges meet
        for fn in (h2, gap) if s.kind == "RRR" else (h2,):
            _touches(fn, grid, 0, points, span / n)
        if points:
            found[s.group] = Schedule(s.design_sign, tuple(sorted(points)), period, u0)
            if revolute and len(points) % 2 == 1:
                period *= 2  # downstream groups see the chain repeat after two turns
    return found, flagged


def chain_period(mech: Mechanism) -> float | None:
    """The input period after which the whole chain of a one-driver mechanism repeats: one turn
    (2π), or more where a group changes its assembly an odd number of times per period of its
    schedule (the Galloway kite: one fold per turn, the other sense of the kite on the second
    turn), so that it comes back to its design sign only after twice that; None for a prismatic
    input."""
    if len(mech.drivers) != 1 or mech.joint(mech.drivers[0].joint).kind != "revolute":
        return None
    period = 2 * np.pi
    for s in branch_schedule(mech).values():
        if s.period is not None:
            period = max(period, s.period * (2 if len(s.change_points) % 2 else 1))
    return period


def near_change_point(mech: Mechanism, u: np.ndarray, tol: float) -> np.ndarray:
    """Whether each input u (one driver) lies within `tol` of a change point of a group's
    schedule (where the chain goes on, though at a fold its pose is not defined by the pairs
    alone)."""
    near = np.zeros(u.shape, dtype=bool)
    for s in branch_schedule(mech).values():
        for c in s.change_points:
            d = u - c
            if s.period is not None:
                d = (d + s.period / 2) % s.period - s.period / 2
            near |= np.abs(d) <= tol
    return near


def _scan_once(place, grid=None):
    """`place` (inputs → a `State` with the groups placed), solved once for the scan's grid:
    a dyad's discriminant and pivot gap are read from the same poses (the refinements' few
    inputs are placed anew). `grid`: places the grid instead where it can (else None)."""
    kept: dict = {}

    def at(u: np.ndarray) -> State:
        if kept.get("u") is u:
            return kept["state"]
        big = not kept and u.size > 1  # the grid (the design check and refinements: one input)
        state = grid(u) if big and grid is not None else None
        if state is None:
            state = place(u)
        if big:
            kept["u"], kept["state"] = u, state
        return state

    return at


class _GridPlacement:
    """The groups placed on a one-driver scan's grid one after the other, for each
    two-assembly group's discriminant in turn: those placed for an earlier group's scan are
    kept for the next (not placed again for every group) while the grid and their assembly
    signs on it are the same (no change point found among them). The state handed out is
    `_positions`': the samples some group cannot assemble NaN. Each group is placed as
    `placed` places it, so the scan's numbers are the same."""

    def __init__(self, mech: Mechanism, solvers) -> None:
        self.mech, self.solvers = mech, solvers
        self.u = None

    def upto(self, k: int, u: np.ndarray, schedule: dict) -> State | None:
        """solvers[:k + 1] placed at inputs u with the assembly signs of `schedule`; None if a
        Newton-solved group is among them (its starting values come from a march)."""
        if any(t.kind == "generic" for t in self.solvers[:k + 1]):
            return None
        signs = {g: sc.signs(u) for g, sc in schedule.items()}

        def unchanged(g, old) -> bool:
            new = signs.get(g)
            return (new is None) == (old is None) and (new is None or np.array_equal(new, old))

        if not (self.u is not None and k + 1 >= self.n and np.array_equal(self.u, u)
                and all(unchanged(g, old) for g, old in self.used.items())):
            N = u.shape[0]
            self.u, self.n, self.used, self.ok = u, 0, {}, np.ones(N, dtype=bool)
            self.state = State(self.mech, _poses(self.mech, N),
                               input_coefficients(self.mech, u[:, None], None, None, None, 0))
        self.state.branches = signs
        for t in self.solvers[self.n:k + 1]:
            self.used[t.group] = signs.get(t.group)
            self.ok &= t.positions(self.state)
        self.n = k + 1
        st = self.state
        out = State(self.mech, st.Q.copy(), st.inputs, T=st.T.copy(), known=set(st.known),
                    branches=signs)
        if not self.ok.all():
            out.Q[:, ~self.ok] = np.nan
            out.forget_trig()
        return out


def _touches(fn, grid: np.ndarray, first: int, points: list, merge: float) -> None:
    """Append to `points` where `fn` (a discriminant or pivot gap along a parameter) touches
    zero: each local minimum of its values on `grid` (at index `first` or later) below
    `TOUCH`, refined by Brent's method between its neighbours and kept when below `CHANGE`
    (and not within `merge` of one found already)."""
    g = fn(grid)
    inner = np.arange(max(1, first), grid.size - 1)
    touch = inner[(g[inner] <= g[inner - 1]) & (g[inner] <= g[inner + 1])
                  & ((g[inner] < g[inner - 1]) | (g[inner] < g[inner + 1]))
                  & (g[inner] < TOUCH) & (g[inner - 1] > 0) & (g[inner + 1] > 0)]
    if len(touch) > MAX_TOUCHES:
        # h² flat and near zero along the scan (a degenerate drawing: the group stays at a
        # change position), its minima rounding noise: no change point is defined there
        return
    if len(touch):
        from scipy.optimize import minimize_scalar  # rarely needed; slow to import
    for i in touch:
        r = minimize_scalar(lambda x: float(fn(np.array([x]))[0]), method="bounded",
                            bounds=(grid[i - 1], grid[i + 1]),
                            options=dict(xatol=1e-13 * max(1.0, abs(grid[i]))))
        if r.fun < CHANGE and not any(abs(r.x - p) < merge for p in points):
            points.append(float(r.x))


def path_schedule(mech: Mechanism, solvers: tuple[GroupSolver, ...], values: np.ndarray,
                  start=None) -> tuple[dict, np.ndarray, object]:
    """Several drivers: the change points of every two-assembly group along the path of the
    inputs `values` (N, drivers) — from the design input (or from `start`, a
    `continuation.PathEnd`: an earlier solve's end) through the samples in their order — and
    the λ of each sample along it (NaN after a non-finite sample): group → `PathSchedule`,
    the samples' λ and the path (`continuation.InputPath`).

    The path is scanned on a grid (`SCAN` points per turn, every sample on it) and each
    touching minimum of the discriminant h² (and, of a dyad, of the gap of its outer hinges)
    refined, as for one driver. A path of several drivers touches a group's change points
    only where it runs along them — the five-bar whose second crank stands still while the
    first carries the dyad through its change position, or cranks coupled so that they do —
    and flips the group's assembly there as the real motion does. A path that crosses them
    leaves the group unreachable on the far side. Groups below a Newton-solved one keep the
    sign they start with (their scan would need a continuation of its own).

    A mechanism that follows another (`continuation.follow`: a drag's frames) along the same
    path takes that one's schedule of every group drawn alike by both, itself and all groups
    before it (`groups.drawn_alike`): the scan would find the same numbers."""
    from .continuation import InputPath, input_weights, lineage

    w = input_weights(mech)
    if start is None:
        head = np.array([mech.driver_input_at_design(d) for d in mech.drivers])[None] * w
        lam0, first_new = 0.0, 0
    elif start.previous is None:
        head, lam0, first_new = start.vertex[None], start.lam, 0
    else:
        head, lam0 = np.vstack([start.previous, start.vertex]), start.previous_lam
    path = InputPath(np.vstack([head, values * w]), start=lam0)
    lam_samples = np.full(values.shape[0], np.nan)
    on = path.vertex_of[len(head):]  # the samples on the path (before a non-finite one)
    lam_samples[:on.size] = path.knots[on]
    found: dict = {}
    if not any(s.kind in BRANCHING for s in solvers):
        return found, lam_samples, path
    groups = tuple(s.group for s in solvers)
    previous = lineage(mech) if start is None else None
    kept = _path_schedules.get(previous) if previous is not None else None
    if kept is not None and (kept[0] != groups or not np.array_equal(kept[1], path.knots)
                             or not np.array_equal(kept[2], path.vertices)):
        kept = None
    alike = kept is not None  # every group so far drawn alike by both
    grid, _ = path.grid(2 * np.pi / SCAN)
    if start is not None and start.previous is not None:
        first_new = int(np.flatnonzero(grid >= path.knots[1])[0])  # the earlier solve's end

    def inputs(lam: np.ndarray) -> np.ndarray:
        """Inputs at λ on the path (its vertices exactly at their knots)."""
        return path.at(lam) / w

    generic_above = False
    for s in solvers:
        generic_above |= s.kind == "generic"
        alike = alike and drawn_alike(previous, mech, s.group)
        if s.kind not in BRANCHING:
            continue
        if alike and s.group in kept[3]:
            found[s.group] = kept[3][s.group]
            continue
        before = start.schedules.get(s.group) if start is not None else None
        sign = s.design_sign if before is None else float(before.signs(np.array([lam0]))[0])
        points = [] if before is None else [c for c in before.change_points if c > lam0]
        if not generic_above and len(path.vertices) > 1:
            upstream = solvers[:solvers.index(s) + 1]

            def state(lam: np.ndarray) -> State:
                u = inputs(lam)
                st = State(mech, _poses(mech, lam.size),
                           input_coefficients(mech, u, None, None, None, 0),
                           branches={g: sc.signs(lam) for g, sc in found.items()})
                ok = np.ones(lam.size, dtype=bool)
                for t in upstream:
                    ok &= t.positions(st)
                if not ok.all():
                    st.Q[:, ~ok] = np.nan
                    st.forget_trig()
                return st

            merge = 2 * np.pi / SCAN
            new: list = []
            at = _scan_once(state)
            for fn in ((lambda x: s.discriminant(at(x))),
                       (lambda x: s.pivot_gap(at(x))))[:2 if s.kind == "RRR" else 1]:
                _touches(fn, grid, first_new, new, merge)
            points += [c for c in new if not any(abs(c - p) < merge for p in points)]
        found[s.group] = PathSchedule(sign, tuple(sorted(points)))
    if start is None and len(path.vertices) <= PATH_KEPT_VERTICES:
        _path_schedules.put(mech, (groups, path.knots, path.vertices, dict(found)))
    return found, lam_samples, path


#: mechanism -> (its groups, the knots and vertices of its last path from the design input,
#: the schedule along it), the last few; paths of a few vertices only (a drag's frames: one or
#: two), not a long batch's
_path_schedules = Kept(8)
PATH_KEPT_VERTICES = 64
