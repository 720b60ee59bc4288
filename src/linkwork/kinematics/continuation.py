"""Newton starting values for the groups without a closed form, by continuation.

The input is marched from the design position by predictor–corrector continuation with adaptive
step control, so that every generic group stays on the assembly branch of the design:

- predictor: Euler's, along the tangent dq/dλ of the solution path (the poses' velocities at
  unit input rate, from the groups' velocity equations);
- corrector: Newton's method on each generic group, which gives up as soon as its iterates stop
  contracting (the prediction then lies outside the basin of the nearby solution);
- step control: a step is accepted when every group assembled and the poses changed smoothly:
  the corrected poses lie close to the predicted ones, and the prediction back from the new
  point along its tangent comes close to the old one (each within a quarter of the predicted
  change). Otherwise the step is halved, down to a floor; after two successes in a row it is
  doubled again, up to `CONTINUATION_STEP`. The predicted change of the poses per step is
  bounded as well (`MAX_POSE_CHANGE`), so that fast swings are resolved in pose space.

A fixed step jumps to the other assembly branch where the solution swings fast (a slotted lever
whose slot passes close to its pivot, a dyad near its dead centre); the adaptive step shrinks
there instead. At a limit position (a turning point of the path, where |dq/dλ| grows like
1/√(λ* − λ)) the step closes in on λ*, extrapolated from the growth of the tangent, and the
march ends within `MIN_STEP` of it.

One driver: the march runs upwards and downwards from the design value. Its steps do not depend
on the range asked for (the march goes on until it has passed it), so the marched points — poses
and tangents — are kept per mechanism and extended when a later solve asks for more, and every
solve gets the same starting values whether the march was kept or not: the limits, the grid and
the samples of a whole motion march once. The samples get their starting values by cubic
Hermite interpolation of the marched poses and tangents. Several drivers: the march goes through
the samples in their order, subdividing adaptively between them.

A drag in the workbench solves a new mechanism for every frame: the same structure, slightly
other dimensions. `solve(..., previous=)` starts its march from the previous frame's
(`_carry`): the accepted points are solved again for the new dimensions all at once, from the
old poses, and taken in order for as long as each step passes the tests a march's step must
pass (a contracting corrector, the step bound, smooth both ways). A change of assembly branch
fails them as it fails a march, and from there the march goes on as it does after a rejected
step, across to the failed point; the old points beyond are then offered again from the
marched one, each step checked the same way (a step the old march passed only just can fail
by a hair for the new dimensions, and the rest of the old march still serves); `carried(mech)`
says how much of the old march was taken and where it was not. Starting values
from a carried march differ from a fresh one's at the level of the march's accuracy, so the
solutions agree to rounding, not bit for bit.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass
from functools import wraps
from threading import Lock, RLock

import numpy as np

from ..errors import SolveError
from ..model import Mechanism
from . import groups
from .contact import PREFIX, row_index
from .groups import State, input_coefficients

CONTINUATION_STEP = np.radians(2.0)  # largest step of a revolute input (prismatic: 1 % of L)
MIN_STEP = 2.0 ** -36                # smallest step, relative to the largest (≈ 5e-13 rad)
MAX_POSE_CHANGE = 0.1                # largest predicted change of any pose per step, in L (θ·L)
PREDICTOR_TOLERANCE = 0.25           # largest corrector distance, relative to the predicted change
SLACK = 1e-4                         # ... plus this, in L: the curvature allowed where dq/dλ ≈ 0
CONTRACTION = 0.5                    # each Newton step must be at most this times the one before
CORRECTOR_ITERATIONS = 12
STEP_TOL = 1e-6                      # a Newton step this small (in L) ends the corrector
FOLD_APPROACH = 0.9                  # fraction of the distance to a limit position ahead
CACHE_SIZE = 32
MAX_ATTEMPTS = 2000                  # steps (accepted or not) per lane and march, plus 4 per
                                     # sample of several drivers: bounded cost
CRAWL_WINDOW = 100                   # attempts over which a lane's progress is measured
CRAWL_MARGIN = 10                    # ... and how much faster it might still get
SCAN_PER_SEGMENT = 2048              # grid points per turn of a path scanned for change points
PERIOD_TURNS = 4                     # turns of a revolute input searched for the motion's period

# (mechanism, its group solvers) -> {+1: lane upwards, -1: lane downwards}. Both are compared
# by identity, so a new Mechanism or a new plan (`solver.plan`) starts a new march.
_marches: OrderedDict = OrderedDict()


@dataclass(frozen=True)
class PathEnd:
    """Where a solve of several drivers left the path of its inputs, for a later solve to go on
    from (`solve(..., resume=)`, the chunks of a streamed output) as if both had been one:
    the last sample's input (in the march's metric, `input_weights`) and its λ along the path,
    the vertex before it and its λ (the last segment, where a change point at the end may only
    show from the next samples), the two-assembly groups' `branches.PathSchedule` and, when
    there are Newton-solved groups, the march's tail (`LaneTail`)."""

    vertex: np.ndarray
    lam: float
    previous: np.ndarray | None
    previous_lam: float
    schedules: dict
    tail: "LaneTail | None"


@dataclass(frozen=True)
class LaneTail:
    """The last two accepted points of a march (λ, poses, tangents), the direction it arrived
    at the last one along, the generic groups' Jacobians there, and its step control."""

    lam: tuple
    P: tuple
    T: tuple
    arrive: np.ndarray
    jacobians: dict
    h: float
    halved: bool


def input_weights(mech: Mechanism) -> np.ndarray:
    """λ, the distance marched in input space, counts a slide of 1 % of L like a turn of
    CONTINUATION_STEP, so that one largest step serves revolute and prismatic inputs (and
    mixtures of them, with several drivers): the factor of each driver's input."""
    return np.array([CONTINUATION_STEP / (0.01 * mech.length_scale)
                     if mech.joint(d.joint).kind == "prismatic" else 1.0 for d in mech.drivers])


def _serialized(fn):
    """One march at a time: the marches kept per mechanism are extended in place, and a server
    solves in several threads."""
    @wraps(fn)
    def run(*args, **kwargs):
        with _marching:
            return fn(*args, **kwargs)
    return run


_marching = RLock()  # re-entered: a march may find change points, which march upstream groups


def marching() -> bool:
    """Whether another thread is marching now: a march here would wait until it is done."""
    if _marching.acquire(blocking=False):
        _marching.release()
        return False
    return True


@_serialized
def continuation_guesses(mech: Mechanism, solvers, values: np.ndarray,
                         schedule: dict | None = None, *, start: PathEnd | None = None,
                         ends: dict | None = None, previous: Mechanism | None = None) -> dict:
    """Newton starting poses (N, k, 3) of every generic group at the samples `values`
    (N, drivers), by continuation from the design position; NaN where the march does not reach
    (the branch of the design cannot be assembled there). `schedule`: the closed-form groups'
    change points (`branches.branch_schedule`, or for several drivers
    `branches.path_schedule`; found from these solvers when not given). Several drivers: the
    march goes on from `start` (an earlier solve's end) instead of the design position, and
    its tail is put in ends["tail"] when `ends` is given. `previous`: a mechanism of the same
    structure solved before (the last frame of a drag); a march `mech` does not have yet starts
    from that one's, carried over (`_carry`; how far: `carried(mech)`)."""
    gen = _Generic(mech, solvers, schedule)
    design = np.array([mech.driver_input_at_design(d) for d in mech.drivers])
    if previous is None:
        with _lock:
            previous = _lineage.get(mech)
    if values.shape[1] == 1:
        lam = (values[:, 0] - design[0]) * gen.weights[0]
        finite = np.isfinite(lam)
        # as far as these samples need, unless they lie farther than half a turn (then the
        # period is looked for, on marches of several turns)
        need = None if np.abs(lam[finite]).max(initial=0.0) > np.pi else \
            {+1: lam[finite].max(initial=0.0), -1: -lam[finite].min(initial=0.0)}
        lanes = _one_driver_lanes(mech, solvers, gen, design, previous, need)
        turns = None
        if mech.joint(mech.drivers[0].joint).kind == "revolute" and \
                np.abs(lam[finite]).max(initial=0.0) > np.pi:
            found = _period(mech, solvers, gen, lanes)
            if found is not None:  # inputs far out: the same poses some periods nearer
                period, advance = found
                # only the samples beyond half a period: the others keep their own λ, so
                # that a sample's answer does not depend on the others in its batch
                far = finite & (np.abs(lam) > period / 2)
                near = np.where(far, np.mod(lam + period / 2, period) - period / 2, lam)
                turns = np.where(far, np.round((lam - near) / period), 0.0)
                lam = near
        reach = {+1: lam[finite].max(initial=0.0), -1: -lam[finite].min(initial=0.0)}
        _march(mech, solvers, gen, list(lanes.values()), reach)
        g = np.full((values.shape[0], gen.size, 3), np.nan)
        up, down = finite & (lam >= 0), finite & (lam < 0)
        g[up] = lanes[+1].interpolate(lam[up])
        g[down] = lanes[-1].interpolate(-lam[down])
        if turns is not None:  # the links' angles as turned through the periods left out (a
            # contact parameter stays within its lap: the profile repeats, and a parameter of
            # 1e8 would leave no digits for Newton's method)
            g[..., 2] += turns[:, None] * advance[:, 2]
        return gen.split(g)
    # several drivers: march through the samples in their order
    if start is None:
        lane = _Lane(gen, np.vstack([design[None] * gen.weights, values * gen.weights]))
        if previous is not None:
            old = _paths.get(previous)
            _note(mech, _compatible(previous, mech) or (
                "the previous mechanism's march is not kept" if old is None else
                _carry(mech, solvers, gen, [(old, lane, _path_map(old, lane))])))
    else:
        lane = _Lane(gen, np.vstack([start.vertex[None], values * gen.weights]), start=start.lam)
        lane.resume(mech, solvers, gen, start.tail)
    _march(mech, solvers, gen, [lane], {lane.sense: lane.knots[-1]})
    with _lock:
        _paths[mech] = lane
        while len(_paths) > PATHS_KEPT:
            _paths.popitem(last=False)
    if ends is not None:
        ends["tail"] = lane.tail()
    return gen.split(lane.at_vertices()[1:])


@_serialized
def march_limit(mech: Mechanism, solvers, sense: int, span: float) -> float | None:
    """The input value at which the march of the design's branch stops on one side (`sense`
    +1: upwards, −1: downwards) — a limit position, closed in on to `MIN_STEP` by the step
    halving — or None when it gets farther than `span` from the design value. One driver."""
    gen = _Generic(mech, solvers)
    design = np.array([mech.driver_input_at_design(d) for d in mech.drivers])
    lane = _one_driver_lanes(mech, solvers, gen, design)[sense]
    target = span * gen.weights[0]
    _march(mech, solvers, gen, [lane], {sense: target})
    end = lane.lam[-1] if lane.lam else 0.0
    if not lane.stopped or end >= target:
        return None
    return float(design[0] + sense * end / gen.weights[0])


@_serialized
def march_period(mech: Mechanism, solvers) -> float | None:
    """The period of the design branch's motion in a revolute input (`_period`: the marches
    upwards and downwards meet after 1 … `PERIOD_TURNS` turns), or None when a march stops at a
    limit position first (or they do not meet). One driver. Its marches to ±half a period are
    kept, and the samples of a whole motion need them (`continuation_guesses` reduces samples
    beyond half a period into one), so deciding whether the input turns fully costs no march
    that the solve would not make anyway."""
    gen = _Generic(mech, solvers)
    design = np.array([mech.driver_input_at_design(d) for d in mech.drivers])
    found = _period(mech, solvers, gen, _one_driver_lanes(mech, solvers, gen, design))
    return None if found is None else found[0]


def _period(mech: Mechanism, solvers, gen: "_Generic", lanes: dict) -> tuple | None:
    """The period of the Newton-solved groups' motion in a revolute input: the first of 1 …
    `PERIOD_TURNS` turns P for which the marches upwards and downwards meet, the poses at
    +P/2 and −P/2 alike (angles modulo a turn; the marches to ±P/2 are what the samples
    reduced into one period need anyway), and the angles (G,) the links turn through in a
    period; None (no period within them, or a march stops at a limit position)."""
    for turns in range(1, PERIOD_TURNS + 1):
        half = np.pi * turns
        _march(mech, solvers, gen, [lanes[+1], lanes[-1]], {+1: half, -1: half})
        ends = []
        for lane in (lanes[+1], lanes[-1]):
            if lane.stopped and (not lane.lam or lane.lam[-1] < half):
                return None
            ends.append(lane.interpolate(np.array([half]))[0])
        d = ends[0] - ends[1]
        lap = np.where(gen.laps > 0, gen.laps, 1.0)
        advance = np.where(gen.laps > 0, lap * np.round(d / lap), 0.0)
        d = d - advance
        d[:, 2] *= gen.L
        if np.abs(d).max(initial=0.0) <= 1e-6 * gen.L:
            return 2 * half, advance
    return None


def _laps(mech: Mechanism, row: str) -> tuple[float, float, float]:
    """(x, y, θ) of a link: a turn in θ; (u, v, ·) of a higher pair's contact row: the period of
    each closed profile it runs on (0: not periodic)."""
    if not row.startswith(PREFIX):
        return (0.0, 0.0, 2 * np.pi)
    j = mech.joint(row[len(PREFIX):])
    names = ((j.profile, j.mate) if j.kind == "cam" else tuple(j.profiles))

    def lap(name):
        p = mech.profiles.get(name) if name else None
        return float(p.domain[1] - p.domain[0]) if p is not None and p.closed else 0.0

    return (lap(names[0]), lap(names[1]) if len(names) > 1 else 0.0, 0.0)


def _one_driver_lanes(mech: Mechanism, solvers, gen: "_Generic", design: np.ndarray,
                      previous: Mechanism | None = None, need: dict | None = None) -> dict:
    """The two marches of a one-driver mechanism, from the cache or new: new ones carried over
    from those of `previous` (`_carry`), as far as `need` says (λ per sense; None: all)."""
    key = (mech, tuple(solvers))
    lanes = _marches.get(key)
    if lanes is None:
        origin = design * gen.weights
        lanes = {s: _Lane(gen, np.vstack([origin, origin + s]), sense=s, ray=True)
                 for s in (+1, -1)}
        if previous is not None:  # its march of the same groups (the same solvers, else
            # one whose Newton groups are these: a march of the groups upstream of a change point)
            groups = [s.group for s in solvers]
            generic = [s.group for s in solvers if s.kind == "generic"]
            kept = [(k, v) for k, v in list(_marches.items()) if k[0] is previous and
                    [s.group for s in k[1] if s.kind == "generic"] == generic]
            old = next((v for k, v in kept if [s.group for s in k[1]] == groups),
                       kept[0][1] if kept else None)
            _note(mech, _compatible(previous, mech) or (
                "the previous mechanism's march is not kept" if old is None else
                _carry(mech, solvers, gen, [(old[s], lanes[s], _ray_map(need, s)) for s in (+1, -1)])))
        _marches[key] = lanes
        while len(_marches) > CACHE_SIZE:
            _marches.popitem(last=False)
    else:
        _marches.move_to_end(key)
    return lanes


# ---------------------------------------------------------------------------- carrying over
@dataclass(frozen=True)
class Carried:
    """How the march of a mechanism began from that of a previous one of the same structure
    (`solve(..., previous=)`, the frames of a drag): `carried` of the `points` accepted points
    offered were taken over; `failed_at` is the input (one value per driver) of the first one
    that was not and `reason` says why (None, None: all of them). From there the march went on
    as a march from the design position goes on after a rejected step, across `gaps` stretches
    after which the old march's points were taken up again (`resumed` of them)."""

    carried: int
    points: int
    failed_at: tuple | None = None
    reason: str | None = None
    gaps: int = 0     # stretches marched across where a carried step failed ...
    resumed: int = 0  # ... and the points carried over after them

    def __str__(self) -> str:
        if self.reason is None:
            return f"continued from the previous mechanism ({self.carried} points)"
        at = "" if self.failed_at is None else \
            " at input " + ", ".join(f"{v:.6g}" for v in self.failed_at)
        again = "" if not self.resumed else \
            f"; taken up again after {self.gaps} stretch{'es' if self.gaps > 1 else ''} marched"
        return (f"marched again from the design position's branch{at}: {self.reason} "
                f"({self.carried} of {self.points} points carried over{again})")


#: mechanism -> the `Carried` of its march; mechanism -> its last march of several drivers;
_carried: OrderedDict = OrderedDict()
_paths: OrderedDict = OrderedDict()
_lineage: OrderedDict = OrderedDict()  # mechanism -> the one it follows (`follow`)
PATHS_KEPT = 4
#: a carried step may be this much longer than the step bound the march keeps to
#: (`MAX_POSE_CHANGE`): the poses' speed differs a little from the previous mechanism's
CARRY_STEP_SLACK = 1.5
#: where a carried step fails, the lane marches across to the failed point and the old march's
#: points beyond are offered again: at most this many times per lane and carry
MAX_GAPS = 8
_lock = Lock()


def follow(mech: Mechanism, previous: Mechanism) -> None:
    """Let every march of `mech` it does not have yet (the solve's, the change points' scans',
    the whole motion's) start from the corresponding march of `previous`, a mechanism of the
    same structure solved before (a drag's previous frame), carried over (`_carry`)."""
    with _lock:
        _lineage[mech] = previous
        while len(_lineage) > CACHE_SIZE:
            _lineage.popitem(last=False)


def lineage(mech: Mechanism) -> Mechanism | None:
    """The mechanism `mech` follows (`follow`), if any."""
    with _lock:
        return _lineage.get(mech)


def carried(mech: Mechanism) -> Carried | None:
    """How the march of `mech` began from a previous mechanism's (None: it was not asked to)."""
    with _lock:
        return _carried.get(mech)


def _note(mech: Mechanism, what) -> None:
    with _lock:
        _carried[mech] = what if isinstance(what, Carried) else Carried(0, 0, None, what)
        while len(_carried) > CACHE_SIZE:
            _carried.popitem(last=False)


def _compatible(previous: Mechanism, mech: Mechanism) -> str | None:
    """Why the march of `previous` cannot be carried over to `mech` (None: it can)."""
    from ..topology import structure_key
    if structure_key(previous) != structure_key(mech):
        return "the previous mechanism has another structure"
    return None


def _ray_map(need: dict | None, sense: int):
    """One driver: λ is the same along the new ray (counted from the new design value); the
    points beyond `need` are left (the first one past it kept, so the lane covers it)."""
    def to_new(lam: np.ndarray) -> np.ndarray:
        if need is None or lam.size == 0:
            return lam
        past = np.flatnonzero(lam >= need[sense])
        return lam[:past[0] + 1] if past.size else lam
    return to_new


def _path_map(old: "InputPath", new: "InputPath"):
    """Several drivers: a point a fraction f along the old path's segment k goes to the same
    fraction of the new path's segment k (vertices to vertices exactly); paths of another
    number of vertices map nothing."""
    def to_new(lam: np.ndarray) -> np.ndarray:
        if len(old.vertices) != len(new.vertices):
            return lam[:0]
        if len(old.vertices) < 2:  # the design input only
            return np.full(min(lam.size, 1), new.knots[0])
        seg = np.clip(np.searchsorted(old.knots, lam, side="right") - 1, 0, len(old.knots) - 2)
        f = (lam - old.knots[seg]) / (old.knots[seg + 1] - old.knots[seg])
        out = new.knots[seg] + f * (new.knots[seg + 1] - new.knots[seg])
        at = np.searchsorted(old.knots, lam)
        hit = (at < old.knots.size) & (old.knots[np.minimum(at, old.knots.size - 1)] == lam)
        out[hit] = new.knots[at[hit]]
        return out[:np.searchsorted(out, new.knots[len(new.vertices) - 1], side="right")]
    return to_new


def _carry(mech: Mechanism, solvers, gen: "_Generic", lanes: list) -> Carried:
    """Carry earlier marches over to `mech` (the same structure, other dimensions): `lanes` are
    (old lane, new lane, old λ → new λ). Each old point is solved for `mech` from its poses at
    once (one batched corrector, as a march's attempt), and the new lane takes the results in
    order for as long as every step passes the march's own tests: converged with contracting
    Newton steps, within the step bound, smooth both ways (`_smooth`). A step onto another
    assembly branch fails them as it fails a march, and the lane then goes on from the last
    point taken as a march does after a rejected step. The design position (λ = 0, every pose
    zero) is each lane's first point, so a carried lane is a march of `mech`'s own branch.
    Points the map leaves (beyond what the samples need) stay pending: a march that later
    needs them carries them first (`_carry_ahead`)."""
    offered = []
    for old, new, to_new in lanes:
        lam = to_new(np.asarray(old.lam, dtype=float))
        offered.append((old, new, lam, old.P[:lam.size], lam.size))
    return _carry_points(mech, solvers, gen, offered)


def _carry_ahead(mech: Mechanism, solvers, gen: "_Generic", lanes: list, reach: dict) -> None:
    """Before a march goes on: lanes with points of an earlier march still pending (`_carry`)
    take them first, as far as `reach` needs."""
    todo = []
    for ln in lanes:
        if ln.pending is None or ln.stopped or ln.reached(reach[ln.sense]):
            continue
        old, start = ln.pending
        if ln.lam:  # (a march across a gap may have gone past some of them)
            start += int(np.searchsorted(np.asarray(old.lam[start:]), ln.lam[-1], side="right"))
        lam = np.asarray(old.lam[start:], dtype=float)
        past = np.flatnonzero(lam >= reach[ln.sense])
        m = int(past[0]) + 1 if past.size else lam.size
        todo.append((old, ln, lam[:m], old.P[start:start + m], start + m))
    if todo:
        more = _carry_points(mech, solvers, gen, todo)
        with _lock:
            was = _carried.get(mech)
        if was is not None and was.reason is None:
            _note(mech, Carried(was.carried + more.carried, was.points + more.points,
                                more.failed_at, more.reason, more.gaps, more.resumed))


def _carry_points(mech: Mechanism, solvers, gen: "_Generic", lanes: list) -> Carried:
    """`_carry` of (old lane, new lane, new λ, old poses, index in the old lane after them)."""
    from .branches import branch_schedule  # imports the solver, which imports this module

    rows = [(n, float(x), P) for n, (_, _, lam, Ps, _) in enumerate(lanes) for x, P in zip(lam, Ps)]
    if not rows:
        return Carried(0, 0, None, "the previous mechanism's march has no points to offer")
    schedule = gen.schedule
    if schedule is None:
        schedule = branch_schedule(mech) if len(mech.drivers) == 1 else {}
    lams = np.array([r[1] for r in rows])
    lane_of = np.array([r[0] for r in rows])
    u, arrive, leave = (np.empty((lams.size, gen.weights.size)) for _ in range(3))
    for n, (_, new, _, _, _) in enumerate(lanes):
        on = lane_of == n
        u[on] = new.at(lams[on]) / gen.weights
        arrive[on] = new.directions(lams[on], True) / gen.weights
        leave[on] = new.directions(lams[on], False) / gen.weights
    pred = np.array([r[2] for r in rows])
    ok, q, t_arrive, t_leave, jacobians = _attempt(mech, solvers, gen, schedule, u, lams,
                                                   arrive, leave, pred)
    taken, failed, gaps, resumed = 0, None, 0, 0
    for n, (old, new, _, _, after) in enumerate(lanes):
        idx = np.flatnonzero(lane_of == n)
        new.pending = None
        pos, crossed = 0, 0  # the first row not yet taken; gaps marched across in this lane
        while pos < idx.size:
            sub = idx[pos:]
            why = _carry_faults(gen, new, lams[sub], q[sub], t_leave[sub], t_arrive[sub], ok[sub])
            bad = np.flatnonzero(why != None)  # noqa: E711 (an object array, compared elementwise)
            k = int(bad[0]) if bad.size else sub.size
            if bad.size and failed is None:
                failed = (tuple(float(v) for v in u[sub[k]]), why[k])
            for i in sub[:k]:
                new._append(float(lams[i]), q[i].copy(), t_leave[i].copy())
            if k:
                new.started = True
                last = sub[k - 1]
                new.last = (arrive[last], {g: J[last:last + 1].copy() for g, J in jacobians.items()})
                taken += k
                resumed += k if crossed else 0
            if k == sub.size or not new.lam:
                pos = idx.size
                break
            # as a march goes on after a rejected step: the step halved ...
            new.h = (lams[sub[k]] - new.lam[-1]) / 2
            new.halved = True
            new.stopped = new.h < MIN_STEP * CONTINUATION_STEP
            if new.stopped or crossed == MAX_GAPS:
                pos += k
                break
            # ... and marched across the gap to the failed point's λ; then the points beyond
            # the march's last one are offered again, each step checked as before (the first
            # from the marched point): a step the march passed only just, made for the old
            # dimensions, fails by a hair for the new ones, and the rest of the old march
            # still serves (a march of its own costs milliseconds per step)
            _march(mech, solvers, gen, [new], {new.sense: float(lams[sub[k]])})
            crossed += 1
            pos += int(np.searchsorted(lams[sub], new.lam[-1], side="right"))
            if new.stopped:  # a limit position before the failed point: the march ends there
                pos = min(pos, idx.size - 1)
                break
        gaps += crossed
        if not new.lam:
            continue
        if pos < idx.size:  # left as a march after a rejected step (set above)
            continue
        if after < len(old.lam):  # more to take when a march needs them
            new.pending = (old, after)
            new.h = min(new.lam[-1] - new.lam[-2], CONTINUATION_STEP) if len(new.lam) > 1 \
                else CONTINUATION_STEP
            new.halved = False
        elif old.stopped:  # the old march ended at its limit position; this one may go on
            new.h = min(new.lam[-1] - new.lam[-2], CONTINUATION_STEP) if len(new.lam) > 1 \
                else CONTINUATION_STEP
            new.halved = True
        else:
            new.h, new.halved = old.h, old.halved
    return Carried(taken, len(rows), *(failed or (None, None)), gaps, resumed)


def _carry_faults(gen: "_Generic", new: "_Lane", lams: np.ndarray, q: np.ndarray,
                  t_leave: np.ndarray, t_arrive: np.ndarray, ok: np.ndarray) -> np.ndarray:
    """Why each carried point (its λ, poses, tangents leaving and arriving, whether it
    converged) may not be taken as the lane's next step after the point before it (the first:
    after the lane's last point, or as its design position): None where it may. Every step's
    tests at once (each needs its two ends only): converged, not longer than the bound the
    march keeps to, smooth both ways."""
    head = bool(new.lam)
    L = np.concatenate([new.lam[-1:], lams])
    Q = np.concatenate([np.array(new.P[-1:]).reshape(-1, gen.size, 3), q])
    TL = np.concatenate([np.array(new.T[-1:]).reshape(-1, gen.size, 3), t_leave])
    h = L[1:] - L[:-1]
    tn = gen.norm(TL[:-1])
    known = np.isfinite(tn) & (tn > 0)
    bound = np.where(known, np.maximum(MAX_POSE_CHANGE * gen.L / np.where(known, tn, 1.0),
                                       MIN_STEP * CONTINUATION_STEP), np.inf)
    tangent = np.isfinite(TL[:-1]).all(axis=(1, 2))[:, None, None]
    pred = np.where(tangent, Q[:-1] + h[:, None, None] * TL[:-1], Q[:-1])
    arriving = t_arrive if head else t_arrive[1:]
    why = np.full(lams.size, None, dtype=object)
    stepped = why[0 if head else 1:]  # the rows a step arrives at (a view)
    stepped[~_smooth(gen, Q[:-1], pred, Q[1:], h, arriving)] = (
        "the poses do not follow on smoothly there (another assembly branch, or a fast swing)")
    stepped[h > CARRY_STEP_SLACK * bound] = "the poses move faster there than the previous step allows"
    if not head and lams[0] != new.knots[0]:
        why[0] = "the previous march does not start at the design position"
    why[~ok] = "the previous poses do not converge there (no assembly near them)"
    return why


class _Generic:
    """What a march carries: the links of the generic groups, stacked as the rows of (G, 3)
    pose arrays, and the input metric."""

    def __init__(self, mech: Mechanism, solvers, schedule: dict | None = None) -> None:
        self.schedule = schedule
        self.solvers = [s for s in solvers if s.kind == "generic"]
        self.last = max((i for i, s in enumerate(solvers) if s.kind == "generic"), default=-1)
        # the closed-form groups ahead of every Newton-solved one depend on the inputs alone
        self.first = min((i for i, s in enumerate(solvers) if s.kind == "generic"), default=0)
        self.slices, start = {}, 0
        for s in self.solvers:
            self.slices[s.group] = slice(start, start + s.group.size)
            start += s.group.size
        self.size = start
        self.links = [row_index(mech)[ln] for s in self.solvers for ln in s.group.links]
        self.L = mech.length_scale
        # what each coordinate may gain over a period of the motion and still be the same pose:
        # a turn of an angle, a lap of a closed profile for a contact parameter
        self.laps = np.array([_laps(mech, ln) for s in self.solvers for ln in s.group.links]
                             ).reshape(-1, 3)
        self.weights = input_weights(mech)

    def norm(self, q: np.ndarray) -> np.ndarray:
        """Max-norm of pose arrays (..., G, 3) in lengths: angles times L."""
        a = np.abs(q)
        return np.maximum(a[..., :2].max(axis=(-1, -2), initial=0.0),
                          self.L * a[..., 2].max(axis=-1, initial=0.0))

    def split(self, g: np.ndarray) -> dict:
        return {s.group: g[:, self.slices[s.group]] for s in self.solvers}


class InputPath:
    """A polyline of inputs (in the march's metric: `_Generic.weights`) parametrised by the
    distance λ travelled along it from its first vertex, whose λ is `start` (a path continued
    from an earlier solve keeps counting: its knots are the same numbers as those of the path
    solved in one piece). Repeated vertices count once; vertices after a non-finite one are not
    on it (nothing can be followed past that)."""

    def __init__(self, vertices: np.ndarray, *, ray: bool = False, start: float = 0.0) -> None:
        bad = np.flatnonzero(~np.isfinite(vertices).all(axis=1))
        n = vertices.shape[0] if bad.size == 0 else int(bad[0])
        self.n_given = vertices.shape[0]
        d = np.diff(vertices[:n], axis=0)
        keep = np.concatenate([[True], np.abs(d).max(axis=1) > 0])[:n]  # repeats: one vertex
        self.vertex_of = np.cumsum(keep) - 1  # vertex index of every given (finite) vertex
        v = vertices[:n][keep]
        d = np.diff(v, axis=0)
        length = np.sqrt((d * d).sum(axis=1))
        self.vertices = v
        # a lone vertex: no direction to go, the tangent is taken along the first input
        self.dirs = d / length[:, None] if d.shape[0] else np.eye(1, v.shape[1])
        if ray:  # one driver: a ray from the design value, marched as far as asked
            length = np.full(1, np.inf)
        # summed one after the other (as np.cumsum does), from the start's λ
        self.knots = np.cumsum(np.concatenate([[start], length]))
        self.empty = n == 0

    def point(self, lam: float) -> np.ndarray:
        """Input at λ (a vertex exactly, at its knot)."""
        return self.at(np.array([lam]))[0]

    def at(self, lam: np.ndarray) -> np.ndarray:
        """Inputs (M, drivers) at λ ≥ the first knot (vertices exactly at their knots)."""
        j = np.searchsorted(self.knots, lam)
        seg = np.clip(j - 1, 0, len(self.dirs) - 1)
        out = self.vertices[seg] + (lam - self.knots[seg])[:, None] * self.dirs[seg]
        hit = (j < len(self.vertices)) & (self.knots[np.minimum(j, self.knots.size - 1)] == lam)
        out[hit] = self.vertices[j[hit]]
        return out

    def direction(self, lam: float, arriving: bool) -> np.ndarray:
        """Unit direction (in λ) of the segment a step arrives at λ along, or leaves λ along
        (they differ at a sample of several drivers)."""
        return self.directions(np.array([lam]), arriving)[0]

    def directions(self, lam: np.ndarray, arriving: bool) -> np.ndarray:
        """`direction` at each λ (M, drivers)."""
        seg = np.searchsorted(self.knots, lam, side="left" if arriving else "right") - 1
        return self.dirs[np.clip(seg, 0, len(self.dirs) - 1)]

    def grid(self, spacing: float) -> tuple[np.ndarray, np.ndarray]:
        """λ of points along the path at most `spacing` apart, every vertex among them, and the
        segment of each (the last vertex: the last segment). The same numbers for a segment
        whichever path it is part of."""
        nseg = len(self.vertices) - 1
        if nseg <= 0:
            return self.knots[:1].copy(), np.zeros(1, dtype=int)
        length = np.diff(self.knots)
        # a segment longer than a few turns is scanned more coarsely: bounded cost
        n = np.clip(np.ceil(length / spacing), 1, 8 * SCAN_PER_SEGMENT).astype(int)
        seg = np.repeat(np.arange(nseg), n)
        k = np.arange(seg.size) - np.repeat(np.cumsum(n) - n, n)
        lam = self.knots[seg] + length[seg] * (k / n[seg])
        return np.append(lam, self.knots[-1]), np.append(seg, nseg - 1)


class _Lane(InputPath):
    """One march along a polyline of inputs from the design position (its first vertex),
    parametrised by the distance λ travelled in input space. Keeps every accepted point: λ,
    the generic poses and their tangents d/dλ."""

    def __init__(self, gen: _Generic, vertices: np.ndarray, *, sense: int = 1,
                 ray: bool = False, start: float = 0.0) -> None:
        super().__init__(vertices, ray=ray, start=start)
        self.size = gen.size  # generic links: the poses' rows, also when nothing was marched
        self.sense = sense
        self.h = CONTINUATION_STEP
        self.halved = False
        self.stopped = self.empty
        self.started = False
        self.lam: list[float] = []
        self.P: list[np.ndarray] = []
        self.T: list[np.ndarray] = []
        self._arrays = None
        self.last = None  # (arriving direction, {group: Jacobian}) of the last accepted point
        self.pending = None  # (an earlier march, the index of its next point to carry over)
        self._ahead = None  # `_Ahead` of a path of several drivers, made when first wanted
        self.ray = ray

    def ahead(self, mech: Mechanism, solvers, gen: _Generic, schedule: dict,
              lams: np.ndarray) -> tuple | None:
        """The closed-form groups ahead of the Newton-solved ones at λ `lams`, if all are
        vertices of this path of several drivers (`_Ahead`), else None."""
        if self.ray or gen.first == 0:
            return None
        if self._ahead is None:
            self._ahead = _Ahead(mech, solvers, gen, schedule, self)
        return self._ahead.at(lams)

    # ------------------------------------------------------------------ going on
    def tail(self) -> LaneTail | None:
        """What a later march needs to go on from this one's last point (None: it stopped
        before its last vertex, or never started)."""
        if self.stopped or not self.lam or self.lam[-1] != self.knots[-1] or self.last is None:
            return None
        return LaneTail(tuple(self.lam[-2:]), tuple(self.P[-2:]), tuple(self.T[-2:]),
                        self.last[0], self.last[1], self.h, self.halved)

    def resume(self, mech: Mechanism, solvers, gen: _Generic, tail: LaneTail | None) -> None:
        """Go on from an earlier march's `tail` at this path's first vertex: its points and
        step control taken over, the tangent at the last point recomputed along the direction
        this path leaves it in, as the march in one piece computes it (`_attempt` with the
        poses and Jacobians it had there)."""
        if tail is None:
            self.stopped = True  # the earlier march did not get there
            return
        self.started = True
        self.lam, self.P, self.T = list(tail.lam), list(tail.P), list(tail.T)
        self.h, self.halved = tail.h, tail.halved
        lam = np.array([self.knots[0]])
        leave = self.direction(self.knots[0], False)[None] / gen.weights
        schedule = gen.schedule or {}
        ok, _, _, t_leave, _ = _attempt(mech, solvers, gen, schedule, self.vertices[:1] / gen.weights,
                                        lam, tail.arrive[None], leave, None,
                                        fixed=(self.P[-1][None], tail.jacobians))
        self.T[-1] = t_leave[0].copy()
        self.last = (tail.arrive, tail.jacobians)

    # ------------------------------------------------------------------ stepping
    def proposal(self, gen: _Generic) -> tuple[float, float, np.ndarray]:
        """(step, λ, predicted poses) of the next attempt."""
        if not self.started:
            return 0.0, 0.0, np.zeros((gen.size, 3))  # the design position: poses all zero
        lam, q, t = self.lam[-1], self.P[-1], self.T[-1]
        h = self.h
        tn = gen.norm(t)
        if np.isfinite(tn) and tn > 0:  # bound the predicted change of the poses
            h = min(h, max(MAX_POSE_CHANGE * gen.L / tn, MIN_STEP * CONTINUATION_STEP))
        if len(self.lam) >= 2:  # a limit position ahead: close in on it
            g1, g0 = gen.norm(t), gen.norm(self.T[-2])
            lam0 = self.lam[-2]
            # near a turning point of the path |dq/dλ|⁻² falls linearly to zero at it. Poses
            # that hardly move (a change of less than SLACK over a largest step) turn at no
            # limit position: a tangent growing from 1e-12 is a degenerate drawing's branch
            # crossing, which the steps would close in on forever
            if np.isfinite(g0) and np.isfinite(g1) and g1 > g0 > 0 and \
                    g1 * CONTINUATION_STEP > SLACK * gen.L:
                fold = lam + (lam - lam0) * g0 ** 2 / (g1 ** 2 - g0 ** 2)
                h = min(h, max(FOLD_APPROACH * (fold - lam), MIN_STEP * CONTINUATION_STEP))
        nxt = self.knots[np.searchsorted(self.knots, lam, side="right")]
        to = lam + h
        if h >= nxt - lam:  # land on the next sample exactly
            h, to = nxt - lam, nxt
        pred = q + h * t if np.isfinite(t).all() else q.copy()
        return h, to, pred

    def settle(self, gen: _Generic, h: float, lam: float, pred: np.ndarray, ok: bool,
               q: np.ndarray, t: np.ndarray, t_leave: np.ndarray) -> None:
        """Accept or reject the attempt at λ, adapt the step. `t` is the tangent along the
        step, `t_leave` the one along the next (they differ where several drivers turn)."""
        if not self.started:
            self.started = True
            if ok:
                self._append(lam, q, t_leave)
            else:
                self.stopped = True  # the design position itself does not assemble
            return
        if ok and _smooth(gen, self.P[-1], pred, q, h, t):
            self._append(lam, q, t_leave)
            # grow after two successes in a row: right after a halving the step that just
            # failed would be tried again (and fail again, closing in on a limit position)
            self.h = h if self.halved else min(2 * h, CONTINUATION_STEP)
            self.halved = False
        else:
            self.h = h / 2
            self.halved = True
            if self.h < MIN_STEP * CONTINUATION_STEP:
                self.stopped = True  # a limit position (or a passage no step gets across)

    def _append(self, lam: float, q: np.ndarray, t: np.ndarray) -> None:
        self.lam.append(lam)
        self.P.append(q)
        self.T.append(t)
        self._arrays = None

    def reached(self, target: float) -> bool:
        return self.stopped or (self.started and bool(self.lam) and self.lam[-1] >= target)

    # ------------------------------------------------------------------ reading
    def arrays(self):
        if self._arrays is None:
            self._arrays = (np.array(self.lam), np.array(self.P), np.array(self.T))
        return self._arrays

    def interpolate(self, lam: np.ndarray) -> np.ndarray:
        """Poses (N, G, 3) at λ ≥ 0 by cubic Hermite interpolation of the marched poses and
        tangents (linear on a span whose tangents are unknown: singular ends); NaN beyond the
        last marched point."""
        G = self.size
        out = np.full((lam.size, G, 3), np.nan)
        if not self.P or lam.size == 0:
            return out
        K, P, T = self.arrays()
        # a limit position at the march's end, computed back from λ: up to rounding beyond it
        end = K[-1] * (1 + 1e-12) + 1e-15
        lam = np.where((lam > K[-1]) & (lam <= end), K[-1], lam)
        inside = lam <= K[-1]
        if K.size == 1:
            out[inside] = P[0]
            return out
        x = lam[inside]
        i = np.clip(np.searchsorted(K, x, side="right") - 1, 0, K.size - 2)
        H = (K[i + 1] - K[i])[:, None, None]
        s = ((x - K[i]) / H[:, 0, 0])[:, None, None]
        P0, P1, T0, T1 = P[i], P[i + 1], T[i], T[i + 1]
        hermite = ((1 + 2 * s) * (1 - s) ** 2 * P0 + s * (1 - s) ** 2 * H * T0
                   + s * s * (3 - 2 * s) * P1 + s * s * (s - 1) * H * T1)
        linear = P0 + s * (P1 - P0)
        known = (np.isfinite(T0) & np.isfinite(T1)).all(axis=(1, 2))[:, None, None]
        out[inside] = np.where(known, hermite, linear)
        return out

    def at_vertices(self) -> np.ndarray:
        """Poses (V, G, 3) at the given vertices (NaN where the march did not get)."""
        out = np.full((self.n_given, self.size, 3), np.nan)
        if self.P:
            K, P, _ = self.arrays()
            j = np.searchsorted(K, self.knots)
            hit = j < K.size
            hit[hit] = K[j[hit]] == self.knots[hit]
            marched = np.full((self.knots.size,) + P.shape[1:], np.nan)
            marched[hit] = P[j[hit]]
            out[:self.vertex_of.size] = marched[self.vertex_of]
        return out


def _march(mech: Mechanism, solvers: tuple, gen: _Generic, lanes: list[_Lane], reach: dict) -> None:
    """Advance the lanes (together: one batched solve per round) until each has passed
    reach[lane.sense] or stopped. Every attempt solves all groups in order at the proposed
    input — the generic ones by `_correct` from the predicted poses — then their velocities at
    unit input rate along the lane: the tangent for the next prediction."""
    from .branches import branch_schedule  # imports the solver, which imports this module

    _carry_ahead(mech, solvers, gen, lanes, reach)
    # (a path through many samples: a few more attempts for each)
    allowed = {id(ln): MAX_ATTEMPTS + 4 * max(0, len(ln.knots) - 2) for ln in lanes}
    budget = dict(allowed)
    # λ reached after each attempt, per lane: a lane that crawls at a pace that cannot reach its
    # target within the budget is stopped early (each attempt of a higher pair costs
    # milliseconds, so the budget alone would take seconds to run out)
    trail: dict = {id(ln): [] for ln in lanes}
    # closed-form groups take the assembly the real motion takes across change points, as in
    # `solve` (a parallelogram under an over-closing crank stays a parallelogram)
    schedule = gen.schedule
    if schedule is None:
        schedule = branch_schedule(mech) if len(mech.drivers) == 1 else {}
    while True:
        todo = [ln for ln in lanes if not ln.reached(reach[ln.sense])]
        if not todo:
            return
        for ln in todo:
            budget[id(ln)] -= 1
            if budget[id(ln)] < 0 or _crawls(trail[id(ln)], budget[id(ln)], reach[ln.sense]):
                at = ln.point(ln.lam[-1]) / gen.weights if ln.lam else ln.vertices[0] / gen.weights
                took = "took" if budget[id(ln)] < 0 else "would take more than"
                raise SolveError(
                    f"mechanism '{mech.name}': following the design's assembly branch {took} "
                    f"{allowed[id(ln)]} continuation steps and got only to input "
                    f"{', '.join(f'{v:.6g}' for v in at)} (the poses change too fast to follow "
                    "there: nearly parallel guides, or a group close to a singular position all "
                    "along); ask for inputs nearer the design position or redraw the mechanism")
        props = [ln.proposal(gen) for ln in todo]
        lams = np.array([p[1] for p in props])
        u = np.array([ln.point(p[1]) for ln, p in zip(todo, props)]) / gen.weights
        # input rates per unit λ: the tangents dq/dλ come out as velocities
        arrive = np.array([ln.direction(p[1], True) for ln, p in zip(todo, props)]) / gen.weights
        leave = np.array([ln.direction(p[1], False) for ln, p in zip(todo, props)]) / gen.weights
        pred = np.array([p[2] for p in props])
        known = todo[0].ahead(mech, solvers, gen, schedule, lams) if len(todo) == 1 else None
        ok, q, t_arrive, t_leave, jacobians = _attempt(mech, solvers, gen, schedule, u, lams,
                                                       arrive, leave, pred, known=known)
        for k, (ln, (h, lam, p)) in enumerate(zip(todo, props)):
            n = len(ln.lam)
            ln.settle(gen, h, lam, p, bool(ok[k]), q[k].copy(), t_arrive[k].copy(),
                      t_leave[k].copy())
            if len(ln.lam) > n:  # accepted: what a later solve needs to go on from here
                ln.last = (arrive[k], {g: J[k:k + 1].copy() for g, J in jacobians.items()})
            trail[id(ln)].append(ln.lam[-1] if ln.lam else 0.0)


def _attempt(mech: Mechanism, solvers, gen: _Generic, schedule: dict, u: np.ndarray,
             lams: np.ndarray, arrive: np.ndarray, leave: np.ndarray, pred: np.ndarray,
             fixed: tuple | None = None, known: tuple | None = None) -> tuple:
    """One round of the march: all groups solved in order at the inputs u (N, drivers) at λ
    `lams` — the generic ones by `_correct` from `pred`, or, with `fixed` = (poses, {group:
    Jacobian}), set to known poses — then the tangents at unit input rate along the direction
    arriving and leaving. (ok, generic poses, tangents arriving, leaving, Jacobians).
    `known`: the closed-form groups ahead of the first generic one, solved at these samples
    before (`_Ahead.at`), taken instead of solved again."""
    N = u.shape[0]
    # second order, so that the driver and RRR dyads take their closed-form velocities
    state = _march_state(mech, u, arrive, lams, schedule)
    ok = np.ones(N, dtype=bool)
    jacobians = {}
    start = 0
    if known is not None:
        rows, Q, T, ok_known, _ = known
        state.Q[:, :, rows] = Q
        state.T[rows] = T
        state.placed(*rows)
        ok &= ok_known
        start = gen.first
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for s in solvers[start:]:
            if s.kind != "generic":
                ok &= s.positions(state)
            elif fixed is None:
                conv, jacobians[s.group] = _correct(state, s, pred[:, gen.slices[s.group]])
                ok &= conv
            else:  # as `_correct` leaves a converged sample
                idx = [state.li(ln) for ln in s.group.links]
                state.Q[0][:, idx, :] = fixed[0][:, gen.slices[s.group]]
                state.forget_trig(idx)
                jacobians[s.group] = fixed[1][s.group]
        t_arrive = t_leave = np.full((N, gen.size, 3), np.nan)
        if ok.any():  # (all failed: nothing to settle with them)
            t_arrive = t_leave = _tangents(state, solvers, gen, jacobians, ok, start)
            if not np.allclose(arrive, leave, rtol=1e-12, atol=0.0):  # a sample turns
                for i, d in enumerate(mech.drivers):
                    state.inputs[d.joint][1] = leave[:, i]
                if known is not None:
                    state.Q[1:, :, known[0]] = known[4]
                t_leave = _tangents(state, solvers, gen, jacobians, ok, start)
    return ok, state.Q[0][:, gen.links], t_arrive, t_leave, jacobians


def _smooth(gen: _Generic, q0: np.ndarray, pred: np.ndarray, q: np.ndarray, h,
            t: np.ndarray) -> np.ndarray:
    """Whether a step of λ-length `h` from poses `q0` to `q` changed the poses smoothly: the
    predictions from both ends along their tangents (`pred` from q0, back from q along its
    tangent `t` arriving) come close to the other end. A step into a fast swing, or onto another
    assembly branch, fails the one from the new end. One step (poses (G, 3)) or several at once
    (a leading axis, `h` one per step)."""
    h = np.asarray(h, dtype=float)[..., None, None]
    slack = SLACK * gen.L
    forward = gen.norm(q - pred) <= PREDICTOR_TOLERANCE * gen.norm(pred - q0) + slack
    back = q - h * t
    with np.errstate(invalid="ignore"):
        backward = gen.norm(back - q0) <= PREDICTOR_TOLERANCE * gen.norm(h * t) + slack
    # no tangent at q: singular there, the step is judged by the prediction from q0 alone
    return forward & (~np.isfinite(back).all(axis=(-1, -2)) | backward)


def _crawls(trail: list, left: int, target: float) -> bool:
    """Whether a lane that has advanced along `trail` (λ after each attempt) would still be
    short of `target` after its `left` attempts at `CRAWL_MARGIN` times the pace of its last
    `CRAWL_WINDOW` ones.
    A narrow passage slows a lane only briefly (the step grows again, doubling every other
    attempt, once it is through), so a window of that length measures a pace that lasts."""
    if len(trail) < CRAWL_WINDOW:
        return False
    pace = (trail[-1] - trail[-CRAWL_WINDOW]) / CRAWL_WINDOW
    return trail[-1] + CRAWL_MARGIN * pace * left < target


def _march_state(mech: Mechanism, u: np.ndarray, rates: np.ndarray, lams: np.ndarray,
                 schedule: dict) -> State:
    """The work arrays of an attempt at the inputs u (N, drivers), λ `lams`, to second order
    with input rates `rates` (the sample axis last in memory, as `solve` lays out Q for the
    compiled kernels), the closed-form groups on their scheduled assemblies."""
    n_links = len(row_index(mech))  # links and contact rows
    return State(mech, np.zeros((3, n_links, 3, u.shape[0])).transpose(0, 3, 1, 2),
                 input_coefficients(mech, u, rates, None, None, 2),
                 branches={g: sch.at(u, lams) for g, sch in schedule.items()})


class _Ahead:
    """The closed-form groups ahead of the first Newton-solved one, solved once at every vertex
    of a path of several drivers (one batch), where most attempts of its march land: their
    poses (with cos θ, sin θ) and their rates along the segments arriving at and leaving each
    vertex. Each sample is solved as an attempt solves it (the same operations, sample by
    sample), so taking them changes no digit of the march."""

    def __init__(self, mech: Mechanism, solvers, gen: _Generic, schedule: dict,
                 path: "InputPath") -> None:
        V = len(path.vertices)
        self.lams = path.knots[:V]
        u = path.vertices / gen.weights
        arrive = path.directions(self.lams, True) / gen.weights
        leave = path.directions(self.lams, False) / gen.weights
        state = _march_state(mech, u, arrive, self.lams, schedule)
        ahead = solvers[:gen.first]
        self.ok = np.ones(V, dtype=bool)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            for s in ahead:
                self.ok &= s.positions(state)
            for s in ahead:
                s.derivatives(state, self.ok)
            self.rows = sorted({state.li(ln) for s in ahead for ln in s.group.links})
            self.Q = state.Q[:, :, self.rows].copy()
            self.T = state.T[self.rows].copy()
            for i, d in enumerate(mech.drivers):
                state.inputs[d.joint][1] = leave[:, i]
            for s in ahead:
                s.derivatives(state, self.ok)
            self.Q_leave = state.Q[1:, :, self.rows].copy()

    def at(self, lams: np.ndarray) -> tuple | None:
        """(rows, Q, T, ok, Q[1:] leaving) at λ `lams`, all vertices (else None)."""
        j = np.searchsorted(self.lams, lams)
        if not (j < self.lams.size).all() or (self.lams[np.minimum(j, self.lams.size - 1)] != lams).any():
            return None
        return self.rows, self.Q[:, j], self.T[:, :, j], self.ok[j], self.Q_leave[:, j]


def _tangents(state: State, solvers, gen: _Generic, jacobians: dict, ok: np.ndarray,
              start: int = 0) -> np.ndarray:
    """Velocities (N, G, 3) of the generic groups' links at the state's input rates, from the
    velocities of all groups up to the last generic one (from `start`: those before it are
    in Q already)."""
    for s in solvers[start:gen.last + 1]:
        if s.kind == "generic":
            _tangent(state, s, jacobians[s.group], ok)
        else:
            s.derivatives(state, ok)
    return state.Q[1][:, gen.links]


def _correct(state: State, solver, guess: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on one generic group from the predicted poses `guess` (N, k, 3); fills
    the group's poses in Q[0] (NaN where it failed). Returns the convergence mask and the last
    Jacobian (at the final poses, or one Newton step before them; with the columns of the known
    links and inputs after the group's own where a pair table gave it).

    An iteration whose step is not at most `CONTRACTION` times the one before fails the sample:
    near a regular solution Newton's method contracts fast, so slow or growing steps mean that
    the prediction is too far away, and the continuation step is to be halved rather than the
    iteration pursued (possibly towards the other branch)."""
    group = solver.group
    idx = [state.li(ln) for ln in group.links]
    L = state.mech.length_scale
    tol = groups.NEWTON_TOL * L
    N = guess.shape[0]
    q = guess.copy()
    alive = np.isfinite(q).all(axis=(1, 2)) & np.isfinite(state.Q[0]).all(axis=(1, 2))
    q[~alive] = 0.0
    converged = np.zeros(N, dtype=bool)
    last = np.full(N, np.inf)
    J = None
    m = 3 * group.size
    for _ in range(CORRECTOR_ITERATIONS):
        state.Q[0][:, idx, :] = q
        # (a pair table's Jacobian with all its columns: the tangent's rates take them)
        r, Jall = groups.residual_and_jacobian(state, group, all_columns=True)
        Jq = Jall[:, :, :m]
        # a sample converged by a small step keeps the Jacobian a step before, as when the
        # batch's evaluations end with it: its answer does not depend on the others in the batch
        fresh = alive & ~converged
        converged |= alive & (np.abs(r).max(axis=1) <= tol)
        if J is None:
            J = np.full(Jall.shape, np.nan)
        J[fresh] = Jall[fresh]
        todo = alive & ~converged
        if not todo.any():
            break
        step = groups.least_squares(Jq[todo], -r[todo])
        step = step.reshape(-1, group.size, 3)
        size = np.maximum(np.abs(step[..., :2]).max(axis=(1, 2)),
                          L * np.abs(step[..., 2]).max(axis=1))
        before = last[todo]
        # steps at rounding level carry no information on contraction
        failing = ~np.isfinite(size) | ((size > CONTRACTION * before) & (size > 1e3 * tol))
        rows = np.flatnonzero(todo)
        alive[rows[failing]] = False
        q[todo] += step
        last[todo] = size
        # a small step after a contracting one leaves an error of the order of its square
        # (quadratic convergence): close enough for a starting value and a tangent, and it
        # saves the evaluation that would confirm it
        converged[rows[~failing & np.isfinite(before) & (size <= STEP_TOL * L)]] = True
        if not (alive & ~converged).any():
            break  # (the Jacobian stays the one a step before: enough for the tangent)
    converged &= alive
    state.Q[0][:, idx, :] = np.where(converged[:, None, None], q, np.nan)
    state.forget_trig(idx)
    return converged, J


def _tangent(state: State, solver, J: np.ndarray, ok: np.ndarray) -> None:
    """Velocities of the group's links in Q[1] (the path's tangent at the state's input rates):
    J·q̇ = −ṙ, where ṙ is the constraints' rate with the group held still (the first-order
    jets of the residuals with the unknown velocities zero), J the corrector's last Jacobian."""
    group = solver.group
    idx = [state.li(ln) for ln in group.links]
    m = 3 * group.size
    # the corrector's Jacobian is at the poses in Q[0]: its other columns give the rates
    r = groups.rate_residuals(state, group, 1, jacobian=J)
    J = J[:, :, :m]
    good = ok & np.isfinite(J).all(axis=(1, 2))
    v = np.full((r.shape[0], m), np.nan)
    if good.any():
        v[good] = groups.least_squares(J[good], -r[good])
    state.Q[1][:, idx, :] = v.reshape(-1, group.size, 3)
