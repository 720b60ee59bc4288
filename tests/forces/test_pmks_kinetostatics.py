"""Conformance: the PMKS kinetostatics reference (MATLAB Newton–Euler solver, re-solved
independently in the pack) reproduced at every sample to 1e-9 relative, with linkwork's own
kinematics: joint reactions (the pack's metric: max |ΔR| / max |R| over a sample's joint
components) and input torque (|ΔT| / |T|). Mechanisms, masses and loads come from each
case.json alone (`pmks_cases`)."""

import numpy as np
import pytest

import pmks_cases as P
from linkwork.forces import kinetostatics

SCENARIOS = [(cid, scen) for cid in P.CASES
             for scen in ("newton_gravity", "newton_no_gravity", "static_gravity", "static_no_gravity",
                          "newton_no_gravity.derived")
             if (P.ROOT / cid / f"{scen}.csv").exists()]


@pytest.fixture(scope="module", params=SCENARIOS, ids=lambda s: f"{s[0]}-{s[1]}")
def analysis(request):
    cid, scen = request.param
    if not P.ROOT.is_dir():
        pytest.fail(f"the reference suite is missing: {P.ROOT}")
    meta, dyn = P.dynamics(cid, gravity="no_gravity" not in scen)
    _, sol = P.motion(meta, dyn.mechanism, cid)
    ref = P.table(P.ROOT / cid / f"{scen}.csv")
    return meta, ref, kinetostatics(dyn, sol, inertia=scen.startswith("newton"))


def test_scenarios_found():
    # the three cases, the six-bars with static runs too, the derived no-gravity four-bar
    assert len(SCENARIOS) == 10


def test_input_torque(analysis):
    _, ref, fa = analysis
    assert fa.solved.all()
    T = ref["input_torque"]
    assert np.max(np.abs(fa.efforts["A"] - T) / np.abs(T)) < 1e-9


def test_joint_reactions(analysis):
    meta, ref, fa = analysis
    comps = np.stack([ref[k] for k in ref if k.endswith(("_fx", "_fy"))], axis=1)
    scale = np.abs(comps).max(axis=1)
    for j in meta["joints"]:
        jn = j["id"]
        R = fa.reactions[jn].force
        err = np.abs(R - np.c_[ref[f"{jn}_fx"], ref[f"{jn}_fy"]]).max(axis=1) / scale
        assert err.max() < 1e-9, jn


def test_power_balance_and_virtual_work(analysis):
    _, _, fa = analysis
    assert np.max(np.abs(fa.power_residual) / fa.power_scale) < 1e-9
    assert np.max(np.abs(fa.virtual_work["A"] - fa.efforts["A"]) / np.abs(fa.efforts["A"])) < 1e-9
