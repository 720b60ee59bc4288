"""`designs.solve_designs`: D designs × N inputs in one batch give, design by design, the
solution `solve` gives each design on its own (statuses, poses, rates, condition numbers,
error bounds), designs that cannot assemble at some inputs and designs past a change of their
Grashof type included; `designs.whole_motions` gives each design's `whole_motion` (its limit
positions and change points searched for all designs at once), errors isolated per design."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.errors import InputError, LinkworkError
from linkwork.kinematics import designs as KD, kernels
from linkwork.kinematics.branches import branch_schedule
from linkwork.kinematics.designs import solve_designs, whole_motions
from linkwork.kinematics.motion import whole_motion
from linkwork.kinematics.solution import Status
from linkwork.sweeps import designs as D

CASES = {
    # the crank-rocker's crank from short (a crank-rocker) to long (past Grashof's limit:
    # unreachable over part of the turn), and its rocker pivot moved
    "crank-rocker": (["O2-A", "O4.x"], [(10.0, 0.0), (14.0, 1.5), (20.0, -2.0), (30.0, 3.0),
                                        (35.0, 0.0)]),
    "slider-crank-offset": (["O-A", "A-B"], [(10.0, 50.0), (20.0, 45.0), (30.0, 40.0),
                                             (60.0, 40.0)]),
    "jansen-linkage": (["O-A"], [(10.0,), (15.0,), (18.0,), (25.0,)]),
}


@pytest.mark.parametrize("name", sorted(CASES))
@pytest.mark.parametrize("compiled", [True, False])
def test_designs_in_one_batch_are_each_design_solved_alone(name, compiled):
    base = linkwork.load(f"library:{name}")
    names, rows = CASES[name]
    params = [D.parameter(base, n) for n in names]
    mechs = []
    for row in rows:
        v = list(row)
        if names[-1].endswith(".x"):  # an offset from the drawn coordinate
            v[-1] += params[-1].value(base)
        mechs.append(D.apply(base, params, v))
    u = mech_u = base.driver_input_at_design(base.drivers[0]) + np.linspace(-np.pi, np.pi, 721)
    sols = solve_designs(mechs, u, velocities=2.0, compiled=compiled)
    assert len(sols) == len(mechs)
    seen = set()
    for m, s in zip(mechs, sols):
        alone = linkwork.solve(m, mech_u, velocities=2.0, compiled=compiled)
        np.testing.assert_array_equal(s.status, alone.status)
        seen |= set(s.status.tolist())
        np.testing.assert_array_equal(np.isnan(s._C), np.isnan(alone._C))
        L = m.length_scale
        a, b = np.nan_to_num(s._C), np.nan_to_num(alone._C)
        assert (np.abs(a - b) / np.maximum(np.abs(b), L)).max() <= 1e-13
        np.testing.assert_allclose(s.condition, alone.condition, rtol=1e-12)
        np.testing.assert_allclose(s.errors, alone.errors, rtol=1e-9)
        for p in m.points:  # the points read from a design's part of the batch
            np.testing.assert_allclose(s.point(p).acceleration, alone.point(p).acceleration,
                                       rtol=1e-12, atol=1e-12 * L)
    if name == "crank-rocker":
        assert Status.UNREACHABLE in seen and Status.OK in seen


def test_other_structures_are_solved_one_by_one():
    """Designs the fused pass does not take (a Newton group) or of different structures: each
    by `solve`, the same answers."""
    mechs = [linkwork.load("library:alt-ten-link"), linkwork.load("library:crank-rocker")]
    u = np.linspace(0.0, 1.0, 5)
    for m, s in zip(mechs, solve_designs(mechs, u)):
        alone = linkwork.solve(m, u)
        np.testing.assert_array_equal(s.status, alone.status)
        np.testing.assert_array_equal(s._C, alone._C)
    assert solve_designs([], u) == []


def test_a_large_batch_of_designs_runs_compiled(monkeypatch):
    """The batch's size (designs × inputs) chooses the compiled loops, as in `solve`."""
    base = linkwork.load("library:crank-rocker")
    prm = [D.parameter(base, "O2-A")]
    mechs = [D.apply(base, prm, [v]) for v in np.linspace(8.0, 12.0, 3)]
    ran = []
    real = kernels._compiled
    monkeypatch.setattr(kernels, "_compiled", lambda: ran.append(1) or real())
    monkeypatch.setattr(kernels, "INTERPRETED_UP_TO", 1000)
    solve_designs(mechs, np.linspace(0.0, 6.0, 400))
    assert ran


def test_whole_motions_are_each_designs_whole_motion_with_errors_isolated():
    """Crank and rocker designs, a slider-crank and the two-driver five-bar, a chain without a
    driver and a Newton-solved chain in one call: each the `whole_motion` of its own (samples,
    statuses, poses), the chain without a driver its error in its place, not raised."""
    base = linkwork.load("library:crank-rocker")
    prm = [D.parameter(base, "O2-A")]
    mechs = [D.apply(base, prm, [a]) for a in (10.0, 30.0, 20.0)]
    mechs += [linkwork.load("library:slider-crank-offset"), linkwork.load("library:five-bar"),
              linkwork.load("library:rosenauer-free-triad"), linkwork.load("library:double-rocker")]
    sols = whole_motions(mechs, compiled=False, isolate=True)
    for m, s in zip(mechs, sols):
        try:
            alone = whole_motion(m)
        except LinkworkError as exc:
            assert isinstance(s, LinkworkError) and str(s) == str(exc)
            continue
        np.testing.assert_array_equal(s.inputs, alone.inputs)
        np.testing.assert_array_equal(s.status, alone.status)
        np.testing.assert_allclose(np.nan_to_num(s._C), np.nan_to_num(alone._C), rtol=0,
                                   atol=1e-12 * m.length_scale)
    assert isinstance(sols[5], InputError) and "has no driver" in str(sols[5])
    assert len(sols[1]) != len(sols[0])  # a rocker's own input range
    with pytest.raises(InputError, match="has no driver"):
        whole_motions(mechs, compiled=False)


def test_solve_designs_per_design_inputs_drivers_and_solution_orders():
    """Inputs of each design's own length, designs of another solution order (a slider-crank
    among four-bars: the same number of links, other tables) in the same batch, the five-bar's
    two drivers per sample; each the `solve` of its own. A bad input of one design is its error,
    the others are solved."""
    cr, sc, fb = (linkwork.load(f"library:{n}") for n in ("crank-rocker", "slider-crank-offset",
                                                           "five-bar"))
    mechs = [cr, sc, cr, fb]
    u = [np.linspace(0.0, 6.0, 50), np.linspace(1.0, 2.0, 7), np.linspace(-1.0, 0.0, 3),
         np.column_stack([np.linspace(0.5, 1.5, 20), np.linspace(1.4, 0.9, 20)])]
    v = [2.0, None, np.linspace(1.0, 3.0, 3), None]
    sols = solve_designs(mechs, u, velocities=v, per_design=True, compiled=False)
    for m, s, ui, vi in zip(mechs, sols, u, v):
        alone = linkwork.solve(m, ui, velocities=vi, compiled=False)
        np.testing.assert_array_equal(s.status, alone.status)
        np.testing.assert_array_equal(s._C, alone._C)
    bad = solve_designs([cr, sc], [np.zeros(3), np.zeros((3, 2))], per_design=True, isolate=True)
    assert isinstance(bad[1], InputError) and "1 driver(s), got 2" in str(bad[1])
    assert len(bad[0]) == 3
    with pytest.raises(InputError, match="2 inputs for 3 designs"):
        solve_designs([cr, cr, cr], u[:2], per_design=True)



def test_the_batched_branch_scan_leaves_change_points_to_branch_schedule():
    """Designs whose batched scans meet no touching minimum are those for which
    `branch_schedule` finds no change point; the parallelogram and antiparallelogram (change
    points half a turn apart), the Galloway kite (its fold) and a crank-rocker drawn on
    Grashof's limit (s + l = p + q: a change point) are left to it, and their whole motions
    (the kite's over two turns) are each design's own."""
    base = linkwork.load("library:crank-rocker")
    prm = [D.parameter(base, "O2-A")]
    # crank a (A at (0, a)), coupler |AB| = √(30² + (30 − a)²), rocker |O4B| = √1000, frame 40:
    # s + l = p + q between a = 20 and 25, found here by bisection on the lengths alone
    def excess(a):
        L = sorted([40.0, a, np.hypot(30.0, 30.0 - a), np.hypot(10.0, 30.0)])
        return L[0] + L[3] - L[1] - L[2]
    lo, hi = 20.0, 25.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if excess(mid) < 0 else (lo, mid)
    mechs = [D.apply(base, prm, [a]) for a in (8.0, 12.0, 25.0, lo)]
    mechs += [linkwork.load(f"library:{n}") for n in ("parallelogram", "antiparallelogram",
                                                       "galloway-kite", "watt-i-six-bar",
                                                       "jansen-linkage")]
    search = []
    for k, m in enumerate(mechs):
        solvers, tab = KD._fused(m)
        search.append(KD._Search(k, m, solvers, tab, m.driver_input_at_design(m.drivers[0]),
                                 False, {}))
    with kernels.compiled_loops(False):
        clear = KD._no_change_points(search)
    has = [bool(branch_schedule(m)) for m in mechs]
    assert has == [False, False, False, True, True, True, True, False, False]
    assert clear == [not h for h in has]
    for m, s in zip(mechs, whole_motions(mechs, compiled=False)):
        alone = whole_motion(m)
        np.testing.assert_array_equal(s.inputs, alone.inputs)
        np.testing.assert_array_equal(s.status, alone.status)
        np.testing.assert_allclose(np.nan_to_num(s._C), np.nan_to_num(alone._C), rtol=0,
                                   atol=1e-12 * m.length_scale)
