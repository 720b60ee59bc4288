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
from .groups import GroupSolver, State, input_coefficients

BRANCHING = ("RRR", "RRP", "rod-in-slot")  # closed forms that choose between two assemblies
SCAN = 2048  # input samples per turn (or per 8 length scales of a prismatic input)
TOUCH = 1e-3  # relative discriminant (h²/L1²) below which a local minimum is refined
CHANGE = 1e-12  # … at the refined minimum below which it is a change point (h < 1e-6 L1)


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


def _positions(mech: Mechanism, solvers: tuple[GroupSolver, ...], upto: GroupSolver,
               u: np.ndarray, branches: dict) -> State:
    """Positions of every group before and including `upto` at inputs u (one driver); NaN
    where a group cannot assemble (the closed forms leave finite values there). Newton groups
    upstream start from the continuation of these groups alone, with the change points found
    so far (all of them upstream of `upto`)."""
    from .continuation import continuation_guesses

    N = u.shape[0]
    Q = np.zeros((1, N, len(rows(mech)), 3))
    state = State(mech, Q, input_coefficients(mech, u[:, None], None, None, None, 0),
                  branches={g: s.signs(u) for g, s in branches.items()})
    upstream = solvers[:solvers.index(upto) + 1]
    guesses = (continuation_guesses(mech, upstream, u[:, None], schedule=branches)
               if any(s.kind == "generic" for s in upstream) else {})
    ok = np.ones(N, dtype=bool)
    for s in upstream:
        ok &= s.positions(state, guesses.get(s.group)) if s.kind == "generic" else s.positions(state)
    if not ok.all():
        state.Q[:, ~ok] = np.nan
        state.forget_trig()
    return state


@lru_cache(maxsize=64)
def branch_schedule(mech: Mechanism) -> dict:
    """Group → `Schedule` for the two-assembly groups of a one-driver mechanism that have change
    points (groups not listed keep their design sign everywhere)."""
    from .solver import plan  # the solver imports this module

    solvers = plan(mech)
    if len(mech.drivers) != 1 or not any(s.kind in BRANCHING for s in solvers):
        return {}
    d = mech.drivers[0]
    u0 = mech.driver_input_at_design(d)
    revolute = mech.joint(d.joint).kind == "revolute"
    found: dict = {}
    period = 2 * np.pi if revolute else None
    for k, s in enumerate(solvers):
        if s.kind not in BRANCHING:
            continue
        span = period if revolute else 8 * mech.length_scale
        n = SCAN * (int(round(span / (2 * np.pi))) if revolute else 1)
        grid = u0 - span / 2 + span * np.arange(n + 1) / n

        def h2(u: np.ndarray) -> np.ndarray:
            return s.discriminant(_positions(mech, solvers, s, u, found))

        if abs(h2(np.array([u0]))[0]) < CHANGE:
            warnings.warn(
                f"mechanism '{mech.name}': the drawing has the group {', '.join(s.group.links)} "
                "at a change or dead position (its pivots in line), so it does not define the "
                "assembly branch there; linkwork takes one side and follows it continuously",
                LinkworkWarning, stacklevel=2)
        def gap(u: np.ndarray) -> np.ndarray:
            return s.pivot_gap(_positions(mech, solvers, s, u, found))

        points: list[float] = []
        # where h² touches zero (a change point), and for a dyad where its outer hinges meet
        for fn in (h2, gap) if s.kind == "RRR" else (h2,):
            g = fn(grid)
            inner = np.arange(1, n)
            touch = inner[(g[inner] <= g[inner - 1]) & (g[inner] <= g[inner + 1])
                          & (g[inner] < TOUCH) & (g[inner - 1] > 0) & (g[inner + 1] > 0)]
            if len(touch):
                from scipy.optimize import minimize_scalar  # rarely needed; slow to import
            for i in touch:
                r = minimize_scalar(lambda x: float(fn(np.array([x]))[0]), method="bounded",
                                    bounds=(grid[i - 1], grid[i + 1]),
                                    options=dict(xatol=1e-13 * max(1.0, abs(grid[i]))))
                if r.fun < CHANGE and not any(abs(r.x - p) < span / n for p in points):
                    points.append(float(r.x))
        if points:
            found[s.group] = Schedule(s.design_sign, tuple(sorted(points)), period, u0)
            if revolute and len(points) % 2 == 1:
                period *= 2  # downstream groups see the chain repeat after two turns
    return found
