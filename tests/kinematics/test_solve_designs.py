"""`designs.solve_designs`: D designs × N inputs in one batch give, design by design, the
solution `solve` gives each design on its own (statuses, poses, rates, condition numbers,
error bounds), designs that cannot assemble at some inputs and designs past a change of their
Grashof type included."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.kinematics import kernels
from linkwork.kinematics.designs import solve_designs
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
