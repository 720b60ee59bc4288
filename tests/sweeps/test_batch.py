"""A sweep's chunk of designs in one batch (`kinematics.designs.whole_motions`, `solve_designs`,
`sweeps.metrics.evaluate_designs`) against the same designs solved and reduced one by one
(`motion.whole_motion` / `solve` and `metrics.evaluate`, `run_designs(batch=False)`), a second
path through the code: the same rows to rounding, on grids whose designs change Grashof class,
turn into rockers (each its own input range, its own number of samples), cannot be built or
placed, and a mechanism with two drivers. The metrics' values themselves are held to closed
forms in test_sweeps.py, which runs the batched path."""

from __future__ import annotations

import math

import numpy as np
import pytest

from linkwork import sweeps

CR = "library:crank-rocker"  # O2 (0, 0), A (0, 10), B (30, 30), O4 (40, 0)
CR_METRICS = ["grashof", "transmission-min:B", "transmission-max:B", "time-ratio:B", "input-range",
              "stroke:C", "straightness:C", "circularity:C", "max-speed:C", "max-acceleration:B",
              "coupler.omega:rms", "C.x:range", "rocker.angle:min"]


def rows_of(p, batch: bool, compiled: bool = False):
    return sweeps.run_designs(p.spec, p.params, p.designs, p.metrics, p.inputs, p.text,
                              p.base_dir, compiled, batch=batch)


def assert_same_rows(batched, alone, rtol=1e-9):
    assert len(batched) == len(alone)
    for b, a in zip(batched, alone):
        assert len(b) == len(a)
        for x, y in zip(b, a):
            if isinstance(y, str):
                assert x == y
            elif math.isnan(y):
                assert math.isnan(x), (b, a)
            else:
                assert x == pytest.approx(y, rel=rtol, abs=1e-9), (b, a)


@pytest.mark.parametrize("compiled", [False, True])
def test_a_crank_rocker_grid_in_one_batch_equals_design_by_design(compiled):
    """The crank from 5 to 35 (crank-rockers, then past s + l = p + q non-Grashof double
    rockers with their own input ranges), lengths that cannot be built (≤ 0), and the rocker
    pivot moved onto B (a rocker of zero length: the design cannot be placed)."""
    p = sweeps.plan(CR, ["O2-A=-5:35:5", "O4.x=30:40:10", "O4.y=0:30:30"], CR_METRICS)
    alone = rows_of(p, batch=False, compiled=compiled)
    assert_same_rows(rows_of(p, batch=True, compiled=compiled), alone)
    status = [r[-1] for r in alone]
    grashof = {r[0] for r in alone}
    assert any(s.startswith("error: parameter O2-A: a length must be positive") for s in status)
    assert any("'rocker': all its points coincide" in s for s in status)
    assert {"Grashof crank-rocker", "non-Grashof double rocker"} <= grashof
    ranges = [r[4] for r in alone if r[-1] == "ok"]
    assert any(v == pytest.approx(360.0) for v in ranges) and any(v < 359 for v in ranges)


def test_slider_cranks_a_two_driver_five_bar_and_given_inputs_in_one_batch():
    """A slider-crank whose rod gets shorter than its crank (a rocking crank: limit positions of
    a sliding-block chain), the README's five-bar with its two drivers (time laws, a path
    through the inputs), and a sweep at given inputs where long cranks cannot reach."""
    cases = [
        sweeps.plan("library:slider-crank-offset", ["O-A=10:70:20", "A-B=30:60:15"],
                    ["grashof", "stroke:B", "time-ratio:B", "max-speed:B", "input-range"]),
        sweeps.plan("library:five-bar", ["O5.x=20:120:25", "C.y=60:80:20"],
                    ["transmission-min:C", "C.x:range", "max-speed:C", "coupler_a.alpha:max"]),
        sweeps.plan(CR, ["O2-A=8:30:4"], ["A.y:max", "transmission-min:B"],
                    inputs=np.radians(np.arange(0.0, 360.0, 7.0))),
        # the long cranks cannot reach the frame line beyond O2 at all: no sample ok
        sweeps.plan(CR, ["O2-A=20:35:5"], ["A.y:max", "transmission-min:B", "time-ratio:B",
                                           "stroke:C", "input-range"],
                    inputs=np.radians([175.0, 180.0, 185.0])),
    ]
    for p in cases:
        alone = rows_of(p, batch=False)
        assert_same_rows(rows_of(p, batch=True), alone)
        if p.inputs is not None and len(p.inputs) == 3:
            assert [r[-1] for r in alone] == ["ok"] + ["unreachable"] * 3
        elif p.inputs is not None:  # some inputs unreachable for the long cranks
            assert any(r[-2] < 1 for r in alone)


def test_a_resumed_batched_sweep_on_a_dask_cluster_equals_design_by_design(tmp_path):
    distributed = pytest.importorskip("distributed")
    p = sweeps.plan(CR, ["O2-A=-5:35:10", "O4.y=0:30:30"], ["grashof", "transmission-min:B",
                                                            "input-range"])
    alone = rows_of(p, batch=False)
    side = tmp_path / "b.resume.jsonl"
    first = sweeps.execute(p, workers=1, chunk=3, resume=side)
    lines = side.read_text().splitlines()
    side.write_text("\n".join(lines[:2]) + "\n")  # one chunk kept
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        again = sweeps.execute(p, scheduler=cluster.scheduler_address, chunk=3, resume=side)
    rows = [r[2:] for r in again]
    assert_same_rows(rows, alone)
    assert_same_rows(again, first, rtol=1e-15)  # what the resume file kept
