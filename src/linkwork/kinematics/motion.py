"""The whole motion of a one-input mechanism, as the real mechanism runs through it.

An input that can turn fully is sampled over one period of the chain: one turn, or two where a
group changes its assembly an odd number of times per turn (the Galloway kite, whose crank
passes the fold where its pin meets the rocker's pivot once per turn and runs the other sense of
the kite on the second turn), since only then does the chain come back to its design position.
A change point is no limit: the chain runs through it (at a fold the sample exactly on it is
marked unreachable by `solve`, its pose not being defined by the pairs). An input that cannot
(a rocker, a slider)
is driven from the design position to its limit position, back to the other limit and forward
to the design position again, on the assembly branch of the design, with the input speed
reversed on the way back (as in the Stephenson III reference sweeps). Limit positions are found
by bisection to machine precision (with Newton-solved groups: where the continuation of the
design's branch stops, to ~1e-12) and included as samples. Whether the chain assembles is a
matter of positions alone, so the limit search solves positions only (no rates, no error
bounds), and its bisection steps are taken a few at a time in one batch.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..model import ConstantSpeed, Mechanism
from .branches import branch_schedule, chain_period, near_change_point, placed
from .contact import interference, rows
from .continuation import march_limit, march_period
from .solution import Solution
from .solver import plan, solve

BISECTIONS = 60
# bisection steps per batch (their 2^DEPTH − 1 possible midpoints solved at once): a position
# solve costs some 50 µs per call and 9 µs per sample (the interpreted kernels), so three steps
# (7 samples) per call are cheapest
DEPTH = 3
FIRST_CHUNK = 64  # samples of the limit scan solved first; each further chunk twice as many
# inputs this close to a change point (radians, or length scales) count as assembling: a fold
# fails to assemble only within rounding of it, and the chain goes on beyond it
CHANGE_POINT_TOL = 1e-9


def _assembles(mech: Mechanism, solvers, u: np.ndarray) -> np.ndarray:
    """Where the mechanism assembles at inputs u (one driver, closed-form groups): positions
    only, with the assembly branches and the contact check of `solve`, whose status is
    unreachable exactly where this is False (its rates and error bounds do not decide it)."""
    schedule = branch_schedule(mech)
    state, ok = placed(mech, solvers, u, schedule)
    if len(rows(mech)) > len(mech.link_names):  # higher pairs: a contact cut into is no contact
        state.Q[0, ~ok] = np.nan
        ok &= ~interference(mech, state.Q[0])
    if schedule and not ok.all():  # a change point is passed, not a limit
        scale = 1.0 if mech.joint(mech.drivers[0].joint).kind == "revolute" else mech.length_scale
        ok |= near_change_point(mech, u, CHANGE_POINT_TOL * scale)
    return ok


def _first_failure(mech: Mechanism, solvers, u0: float, sign: float,
                   grid: np.ndarray) -> int | None:
    """Index of the first offset on `grid` at which u0 + sign·offset does not assemble (None if
    all do), solved in chunks outwards from the design position, each twice the last, so that a
    rocker's scan stops soon after its limit."""
    start, size = 0, FIRST_CHUNK
    while start < grid.size:
        ok = _assembles(mech, solvers, u0 + sign * grid[start:start + size])
        if not ok.all():
            return start + int(np.argmin(ok))
        start, size = start + size, 2 * size
    return None


def bisect_brackets(assembles, lo: np.ndarray, hi: np.ndarray, depth: int = DEPTH) -> np.ndarray:
    """`BISECTIONS` steps of bisection of every bracket p of offsets (lo[p] assembles, hi[p]
    does not), all at once: the same midpoints in the same floating-point arithmetic as one
    step at a time, so the same limits to the last bit; but `depth` steps per batch: every
    midpoint those steps may visit (a full binary tree, level by level) is asked of
    `assembles(offsets (P, M)) → (P, M) bool` at once, then the tree is walked."""
    lo, hi = np.atleast_1d(np.asarray(lo, float)), np.atleast_1d(np.asarray(hi, float))
    P = lo.size
    rows = np.arange(P)
    steps = BISECTIONS
    while steps > 0:
        d = min(depth, steps)
        # level k of the tree holds the 2^k brackets that k steps can leave
        los, his, mids = [lo[:, None]], [hi[:, None]], []
        for k in range(d):
            m = 0.5 * (los[k] + his[k])
            mids.append(m)
            if k + 1 < d:  # left child, right child
                los.append(np.stack([los[k], m], axis=2).reshape(P, -1))
                his.append(np.stack([m, his[k]], axis=2).reshape(P, -1))
        flat = np.concatenate(mids, axis=1)
        ok = assembles(flat)
        node, start = np.zeros(P, dtype=int), 0
        for k in range(d):
            i = start + node
            good, at = ok[rows, i], flat[rows, i]
            lo, hi = np.where(good, at, lo), np.where(good, hi, at)
            node = 2 * node + good
            start += 2 ** k
        steps -= d
    return lo


def input_limits(mech: Mechanism, *, resolution: float | None = None) -> tuple[float, float] | None:
    """(lower, upper) limits of the single input around the design value, or None when a
    revolute input can turn fully."""
    d = mech.drivers[0]
    prismatic = mech.joint(d.joint).kind == "prismatic"
    u0 = mech.driver_input_at_design(d)
    span = 4 * mech.length_scale if prismatic else 2 * np.pi
    solvers = plan(mech)
    if any(s.kind == "generic" for s in solvers):
        return _march_limits(mech, solvers, u0, span, prismatic)
    n = 1441
    res = resolution or span / (n - 1)
    grid = np.linspace(0.0, span, max(n, int(span / res) + 1))
    up = _first_failure(mech, solvers, u0, +1.0, grid)
    if not prismatic and up is None:
        return None  # a crank: the lower side is not needed
    down = _first_failure(mech, solvers, u0, -1.0, grid)
    limits = []
    for sign, k in ((-1.0, down), (1.0, up)):
        if k is None:
            raise InputError(f"driver '{d.joint}': no limit position within ±{span:g} of the design "
                             "position; give --sweep explicitly")
        offset = bisect_brackets(lambda x: _assembles(mech, solvers, u0 + sign * x.ravel())[None],
                                 grid[k - 1], grid[k])
        limits.append(u0 + sign * offset[0])
    return limits[0], limits[1]


def _march_limits(mech: Mechanism, solvers, u0: float, span: float,
                  prismatic: bool) -> tuple[float, float] | None:
    """`input_limits` of a mechanism with Newton-solved groups: where the continuation of the
    design's branch stops. Its step control closes in on a limit position to ~1e-12 (where
    Newton's residual tolerance blurs the turning point), which is where bisection on `solve`
    ends too, since solve's Newton starts from that march and finds nothing beyond it; but the
    bisection would take sixty solves next to the turning point, where Newton's method converges
    slowly. A revolute input turns fully where the marches upwards and downwards meet at half a
    turn (or a few turns) each way: those are the marches the whole motion's samples beyond
    half a turn are solved from, so the limit search marches nothing the solve does not."""
    d = mech.drivers[0]
    if not prismatic and march_period(mech, solvers) is not None:
        return None  # the marches to ±half a turn meet: a crank (and the solve needs them)
    upper = march_limit(mech, solvers, +1, span)
    if upper is None and not prismatic:
        return None
    lower = march_limit(mech, solvers, -1, span)
    if lower is None or upper is None:
        raise InputError(f"driver '{d.joint}': no limit position within ±{span:g} of the design "
                         "position; give --sweep explicitly")
    return lower, upper


def whole_motion(mech: Mechanism, *, step: float | None = None, speed: float | None = None,
                 order: int = 2) -> Solution:
    """Solve the whole motion. `step` is the input increment (radians or length unit; default
    1° or 1/200 of the stroke); `speed` overrides the driver's constant speed."""
    if not mech.drivers:
        raise InputError(f"mechanism '{mech.name}' has no driver: a chain driven by given point "
                         "velocities is solved at its drawn position only (point_inputs.solve_given)")
    if len(mech.drivers) != 1:
        laws = [d.law for d in mech.drivers]
        if all(law.duration for law in laws):
            t = np.linspace(0.0, min(law.duration for law in laws), 361)
            return solve(mech, times=t, order=order)
        raise InputError("the whole motion of a mechanism with several drivers needs a time law "
                         "with a duration for every driver; give inputs explicitly")
    d = mech.drivers[0]
    if not isinstance(d.law, ConstantSpeed) and speed is None:
        return solve(mech, times=np.linspace(0.0, d.law.duration, 361), order=order)
    u, w = motion_inputs(mech, input_limits(mech), step=step, speed=speed)
    return solve(mech, u, velocities=w, order=order)


def motion_inputs(mech: Mechanism, limits, *, step: float | None = None,
                  speed: float | None = None, period: float | None = None) -> tuple:
    """The inputs and input speeds of the whole motion of a one-driver mechanism whose
    `input_limits` are `limits`: a crank over the chain's period (`period`, or
    `branches.chain_period`), a rocker from the design position to its upper limit, back to
    the lower and forward to the design position, its speed reversed on the way back; `step`
    1° or 1/200 of a slider's stroke, `speed` the driver's constant speed unless given."""
    d = mech.drivers[0]
    u0 = mech.driver_input_at_design(d)
    speed = d.law.speed if speed is None else speed
    if limits is None:
        h = step or np.radians(1.0)
        turn = chain_period(mech) if period is None else period
        n = int(round(turn / h))
        u = u0 + np.sign(speed or 1.0) * np.linspace(0.0, turn, n + 1)
        return u, np.full(u.shape, speed)
    lo, hi = limits
    h = step or (np.radians(1.0) if mech.joint(d.joint).kind == "revolute" else (hi - lo) / 200)

    def leg(a: float, b: float) -> np.ndarray:
        n = max(1, int(np.ceil(abs(b - a) / h - 1e-9)))
        return a + np.sign(b - a) * np.minimum(np.arange(n + 1) * h, abs(b - a))

    first, back, last = leg(u0, hi), leg(hi, lo), leg(lo, u0)
    u = np.concatenate([first, back[1:], last[1:]])
    sign = np.concatenate([np.ones(first.size), -np.ones(back.size - 1), np.ones(last.size - 1)])
    return u, abs(speed) * sign
