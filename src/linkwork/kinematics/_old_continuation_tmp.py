"""Newton starting values for the groups without a closed form, by continuation.

From the design position the input is marched along a coarse grid (`CONTINUATION_STEP`), each
point's Newton solve starting from the previous one's poses, so that every generic group stays
on the assembly branch of the design; the samples then get their guesses by interpolation.
"""

from __future__ import annotations

import numpy as np

from ..model import Mechanism
from .groups import State, input_coefficients

CONTINUATION_STEP = np.radians(2.0)


def continuation_guesses(mech: Mechanism, solvers, values: np.ndarray) -> dict:
    """Newton starting poses of the generic groups at every sample, by continuation."""
    design = np.array([mech.driver_input_at_design(d) for d in mech.drivers])
    if values.shape[1] == 1:
        lo, hi = min(values[:, 0].min(), design[0]), max(values[:, 0].max(), design[0])
        step = CONTINUATION_STEP if not _prismatic(mech) else 0.01 * mech.length_scale
        up = np.append(np.arange(design[0], hi, step), hi)
        down = np.append(np.arange(design[0], lo, -step), lo)
        branches = [_march(mech, solvers, up[:, None]), _march(mech, solvers, down[:, None])]
        guesses = {}
        for s in solvers:
            if s.kind != "generic":
                continue
            g = np.full((values.shape[0], s.group.size, 3), np.nan)
            for path, poses in zip((up, down), branches):
                sel = (values[:, 0] >= path.min()) & (values[:, 0] <= path.max())
                order = np.argsort(path)
                P = poses[s.group][order]
                for k in range(s.group.size):
                    for c in range(3):
                        g[sel, k, c] = np.interp(values[sel, 0], path[order], P[:, k, c])
            guesses[s.group] = g
        return guesses
    # several drivers: march through the samples in their order
    path = np.vstack([design[None], values])
    poses = _march(mech, solvers, path)
    return {s.group: poses[s.group][1:] for s in solvers if s.kind == "generic"}


def _prismatic(mech: Mechanism) -> bool:
    return mech.joint(mech.drivers[0].joint).kind == "prismatic"


def _march(mech: Mechanism, solvers, path: np.ndarray) -> dict:
    """Solve positions along `path` (M, drivers) one point after another, each Newton solve
    starting from the previous point's poses; stops where the chain cannot assemble."""
    M = path.shape[0]
    out = {s.group: np.full((M, s.group.size, 3), np.nan) for s in solvers if s.kind == "generic"}
    prev = {g: np.zeros((1, g.size, 3)) for g in out}
    for m in range(M):
        state = State(mech, np.zeros((2, 1, len(mech.links), 3)),
                      input_coefficients(mech, path[m:m + 1], None, None, None, 1))
        ok = True
        for s in solvers:
            ok = ok and bool(s.positions(state, prev.get(s.group))[0])
            if not ok:
                break
            if s.group in out:
                q = state.Q[0][0, [state.li(ln) for ln in s.group.links]]
                out[s.group][m] = q
                prev[s.group] = q[None]
        if not ok:
            break
    return out
