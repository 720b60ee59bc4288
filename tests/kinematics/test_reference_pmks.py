"""Conformance: the four PMKS/MATLAB reference cases reproduced at every sample.

Expectations are the independent MATLAB series in ../shared/reference; the library files only
restate each case's drawing (case.json). Tolerance: 1e-6 of the case's characteristic length
(times ω or ω² for velocities and accelerations).
"""

import csv
import json

import numpy as np
import pytest

import linkwork

CASES = {
    "teaching_four_bar": "pmks-teaching-four-bar",
    "teaching_slider_crank": "pmks-teaching-slider-crank",
    "slider_crank_tracer": "pmks-slider-crank-tracer",
    "stephenson_iii_example_2": "pmks-stephenson-iii",
}


def _table(path):
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0] if k != "sample_id"}


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request, reference_root):
    root = reference_root / request.param
    meta = json.loads((root / "case.json").read_text())
    samples = {}
    with open(root / "matlab" / "samples.csv") as fh:
        rows = list(csv.DictReader(fh))
    samples["input"] = np.array([float(r["input_angle_rad"]) for r in rows])
    samples["direction"] = np.array([float(r["input_direction"]) for r in rows])
    mech = linkwork.load(f"library:{CASES[request.param]}")
    speed = meta["input"]["speed_rad_s"]
    sol = linkwork.solve(mech, samples["input"], velocities=speed * samples["direction"])
    return root, meta, sol, speed


def test_every_sample_assembles(case):
    _, _, sol, _ = case
    assert (sol.status == linkwork.Status.OK).all()


def test_points_positions_velocities_accelerations(case):
    root, meta, sol, w = case
    L = meta["characteristic_length"]
    files = list((root / "matlab" / "joints").glob("*.csv")) + list((root / "matlab" / "points").glob("*.csv"))
    assert files
    for f in files:
        ref = _table(f)
        m = sol.point(f.stem)
        np.testing.assert_allclose(m.position, np.c_[ref["x"], ref["y"]], rtol=0, atol=1e-6 * L, err_msg=f.stem)
        np.testing.assert_allclose(m.velocity, np.c_[ref["vx"], ref["vy"]], rtol=0, atol=1e-6 * L * w, err_msg=f.stem)
        np.testing.assert_allclose(m.acceleration, np.c_[ref["ax"], ref["ay"]], rtol=0, atol=1e-6 * L * w * w,
                                   err_msg=f.stem)


def test_link_angles_omega_alpha(case):
    root, meta, sol, w = case
    for f in (root / "matlab" / "links").glob("*.csv"):
        ref = _table(f)
        m = sol.link(f.stem)
        delta = np.angle(np.exp(1j * (m.angle - m.angle[0] - ref["theta_delta_rad"])))
        np.testing.assert_allclose(delta, 0, atol=1e-9, err_msg=f.stem)
        np.testing.assert_allclose(m.omega, ref["omega_rad_s"], rtol=0, atol=1e-7 * w, err_msg=f.stem)
        np.testing.assert_allclose(m.alpha, ref["alpha_rad_s2"], rtol=0, atol=1e-7 * w * w, err_msg=f.stem)
