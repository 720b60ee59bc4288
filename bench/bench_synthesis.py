"""Motion generation, linkwork vs pylinkage: the same 3-, 4- and 5-position problems.

The positions are those of the coupler of a four-bar written out in closed form
(tests/synthesis/four_bar_by_hand.py: pivots (0, 0) and (4, 0), crank 1.5, coupler 3.5, rocker
3), so an exact solution exists for every count. Each library synthesizes four-bars through
them the way a user would call it:

- pylinkage 1.3: `pylinkage.synthesis.motion_generation(poses, require_grashof=False)` (its
  defaults otherwise: up to 10 solutions). With five positions it usually filters every
  candidate out; then its Burmester candidates (`compute_circle_point_curve`, a grid search
  accepting 1 % radius error, and `select_compatible_dyads`) are measured as well.
- linkwork: three and four positions, the dyads of two chosen centre points (the generating
  pivots; pylinkage is given them too, as `ground_pivot_a`, `ground_pivot_d`); four,
  `four_position_linkages` (pairs of points along the centre-point curve); five,
  `burmester_points` and `linkages` (the quartic's roots).

The error of every linkage is measured the same way for both: the two dyads (fixed pivot and
moving pivot in position 1) become a linkwork four-bar, which linkwork's engine solves at the
input angles of the positions; the coupler's pose against the prescribed one, the larger of
the position error (relative to the positions' spread) and the angle error (rad)
(`Linkage.check().pose_error`). Reported: the best error, how many linkages meet the positions to
1e-9, and the worst (large where the positions lie on both assemblies: a circuit defect).

    uv run --group bench python bench/bench_synthesis.py [--repeats 5]
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np
from rich.console import Console
from rich.table import Table

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "synthesis"))
from four_bar_by_hand import O2, O4, generated  # noqa: E402

from linkwork.geometry import Point  # noqa: E402
from linkwork.synthesis import burmester_points, dyad, linkages  # noqa: E402
from linkwork.synthesis.burmester import Dyad  # noqa: E402
from linkwork.synthesis.linkages import Linkage, four_position_linkages  # noqa: E402

try:
    from pylinkage.synthesis import Pose, motion_generation
    from pylinkage.synthesis.burmester import compute_circle_point_curve, select_compatible_dyads
except ImportError:  # pragma: no cover
    sys.exit("pylinkage is not installed: run `uv run --group bench python bench/bench_synthesis.py`")

PROBLEMS = {3: [10, 45, 80], 4: [10, 45, 80, 120], 5: [20, 50, 80, 110, 140]}


def timed(f, repeats: int):
    out, times = None, []
    for _ in range(repeats):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return out, statistics.median(times)


def engine_error(pos, centre_a, circle_a, centre_b, circle_b) -> float:
    """The pose error of the four-bar of two dyads (points in position 1), solved by linkwork."""
    try:
        lk = Linkage(Dyad(Point.from_xy(np.asarray(centre_a, float)), Point.from_xy(np.asarray(circle_a, float)), pos),
                     Dyad(Point.from_xy(np.asarray(centre_b, float)), Point.from_xy(np.asarray(circle_b, float)), pos))
        return float(lk.check.pose_error)
    except Exception:  # noqa: BLE001  (a degenerate candidate: no four-bar at all)
        return math.inf


def span(errors) -> str:
    """Best error, how many linkages meet the positions to 1e-9, worst error (a circuit defect:
    the engine assembles the chain the other way at some position)."""
    e = list(errors)
    if not e:
        return "—"
    exact = sum(x <= 1e-9 for x in e)
    return f"{min(e):.1e} | {exact}/{len(e)} | {max(e):.1e}"


def pylinkage_rows(pos, repeats):
    poses = [Pose(float(x), float(y), float(t)) for x, y, t in pos.poses]
    res, dt = timed(lambda: motion_generation(poses, require_grashof=False), repeats)
    errs = [engine_error(pos, s.ground_pivot_a, s.crank_pivot_b, s.ground_pivot_d, s.coupler_pivot_c)
            for s in res.raw_solutions]
    rows = [("pylinkage motion_generation", dt, len(errs), span(errs))]
    if len(pos) < 5:  # like for like with linkwork's chosen centre points
        pivots = dict(ground_pivot_a=tuple(map(float, O2)), ground_pivot_d=tuple(map(float, O4)))
        res, dt = timed(lambda: motion_generation(poses, require_grashof=False, **pivots), repeats)
        errs = [engine_error(pos, s.ground_pivot_a, s.crank_pivot_b, s.ground_pivot_d, s.coupler_pivot_c)
                for s in res.raw_solutions]
        rows.append(("pylinkage motion_generation, pivots given", dt, len(errs), span(errs)))
    if len(pos) == 5 and not errs:
        def candidates():
            return select_compatible_dyads(compute_circle_point_curve(poses))
        pairs, dt2 = timed(candidates, repeats)
        def xy(z):
            return (z.real, z.imag)
        errs2 = [engine_error(pos, xy(a.center_point), xy(a.circle_point), xy(b.center_point), xy(b.circle_point))
                 for a, b in pairs]
        rows.append(("pylinkage Burmester candidates", dt2, len(errs2), span(errs2)))
    return rows


def linkwork_rows(pos, repeats):
    n = len(pos)
    rows = []

    def chosen():
        return [Linkage(dyad(pos, O2), dyad(pos, O4))]
    if n < 5:
        rows.append(("linkwork dyads of 2 chosen centre points", chosen))
    if n == 4:
        rows.append(("linkwork four_position_linkages", lambda: four_position_linkages(pos)))
    if n == 5:
        rows.append(("linkwork burmester_points + linkages", lambda: linkages(burmester_points(pos).dyads)))
    return [_linkwork_row(pos, what, run, repeats) for what, run in rows]


def _linkwork_row(pos, what, run, repeats):
    found, dt = timed(run, repeats)
    errs = [engine_error(pos, lk.input.centre.xy, lk.input.circle.xy, lk.output.centre.xy, lk.output.circle.xy)
            if not (lk.input.is_slider or lk.output.is_slider) else float(lk.check.pose_error) for lk in found]
    return (what, dt, len(errs), span(errs))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    t = Table(title="motion generation: time (median) and engine pose error of the linkages returned")
    for col in ("positions", "method", "time", "linkages", "pose error: best | ≤ 1e-9 | worst"):
        t.add_column(col)
    for n, degrees in PROBLEMS.items():
        pos = generated(degrees)[0]
        for what, dt, count, errs in linkwork_rows(pos, args.repeats) + pylinkage_rows(pos, args.repeats):
            t.add_row(str(n), what, f"{dt * 1e3:.1f} ms", str(count), errs)
    Console().print(t)


if __name__ == "__main__":
    main()
