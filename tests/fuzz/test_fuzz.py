"""Fuzzing the boundary (issue 10): mutated library files and random command-line arguments end
in a result or a linkwork error, never another exception, a hang or a wrong `ok` sample.

Kept short for the suite (about half a minute); tools/fuzz.py runs the same harness over ten
thousand cases and more."""

import random

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from fuzz_harness import Outcome, cli_args, library_texts, mutate, run_cli_case, run_file_case, warm_up

TEXTS = library_texts()
NAMES = sorted(TEXTS)
FUZZ = settings(max_examples=60, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow])


@pytest.fixture(scope="module", autouse=True)
def _compiled():
    warm_up()


def _assert_fine(outcome: Outcome, case) -> None:
    assert outcome.kind in ("result", "user-error"), f"{outcome.kind}: {outcome.cause}\n{outcome.detail}\n{case}"


@FUZZ
@given(name=st.sampled_from(NAMES), rng=st.randoms(use_true_random=False))
def test_mutated_library_files(name, rng):
    data, mutations = mutate(TEXTS[name], rng)
    _assert_fine(run_file_case(data, rng), (name, mutations))


@FUZZ
@given(rng=st.randoms(use_true_random=False))
def test_random_command_lines(rng):
    args = cli_args(rng, NAMES)
    _assert_fine(run_cli_case(args), args)


@pytest.mark.parametrize("name", NAMES)
def test_every_library_file_as_shipped_passes_the_checks(name):
    """The harness's own check: unmutated files solve with every ok sample closed."""
    out = run_file_case(TEXTS[name].encode(), random.Random(0))
    assert out.kind == "result", (out.cause, out.detail)


def test_tiny_rocker_is_not_ok_with_an_open_pair():
    """Found by tools/fuzz.py (seed 5, case 405): a rocker of 1e-6 mm in a 50 mm drawing was
    reported ok with its pair B open by 7.6 mm, until the honest statuses of issue 10."""
    import numpy as np

    import linkwork
    from fuzz_harness import check_ok_samples
    mech = linkwork.load_text(TEXTS["crank-rocker"].replace("O4 = [40, 0]", "O4 = [30.000001, 30]"))
    u0 = mech.driver_input_at_design(mech.drivers[0])
    sol = linkwork.solve(mech, u0 + np.linspace(-np.pi, np.pi, 13))
    assert check_ok_samples(sol) is None


def test_runaway_structure_step_is_not_a_linalg_crash():
    """Found by tools/fuzz.py (seed 12, case 999): the Proell–Schwabe gear with P58 drawn
    1e-12 from P38. The structure report's finite step (Gauss–Newton) ran away to NaN poses
    and the cam's gap took an SVD of NaN (LinAlgError); it now ends as a step that does not
    close."""
    from fuzz_harness import _POINT

    text = TEXTS["proell-schwabe-valve-gear"]
    pts = {m.group(1): m for m in _POINT.finditer(text)}
    m, o = pts["P58"], pts["P38"]
    x, y = float(o.group(2)) + 1e-12, float(o.group(3)) - 1e-12
    data = (text[:m.start(2)] + repr(x) + ", " + repr(y) + text[m.end(3):]).encode()
    _assert_fine(run_file_case(data, random.Random(0)), "P58 -> P38 + 1e-12")


def test_change_point_scans_run_the_solves_compiled_loops():
    """Found by tools/fuzz.py (seed 12, case 41, the Holst mechanism): a change-point scan of
    more than INTERPRETED_UP_TO samples laid its poses out otherwise than `solve`, so numba
    compiled the dyad's loop once more (seconds, inside a case: a hang, and an alarm in the
    middle of the compiler broke the loop for the cases after). The scans now lay poses out as
    the solve does: no new compiled version."""
    import numpy as np

    import linkwork
    from linkwork.kinematics import branches, kernels, solver

    mech = linkwork.load("library:parallelogram")
    solvers = solver.plan(mech)
    n = kernels.INTERPRETED_UP_TO + 1
    u = np.linspace(0.0, 4 * np.pi, n)
    sol = linkwork.solve(mech, u)  # the solve's versions (compiled by warm_up already)
    rrr = kernels._compiled()["rrr_positions"]
    before = list(rrr.signatures)
    dyad = next(s for s in solvers if s.kind == "RRR")
    state = branches._positions(mech, solvers, dyad, u, branches.branch_schedule(mech))
    assert list(rrr.signatures) == before
    # (and the scan places the dyad where the solve does)
    np.testing.assert_allclose(state.Q[0][:, mech.link_index["coupler"], 2],
                               sol.link("coupler").angle, atol=1e-12)


def test_flat_discriminant_is_no_string_of_change_points(monkeypatch):
    """Found by tools/fuzz.py (seed 11, case 7775, 74 s): the Whitworth quick return with the
    rod hinged to the frame at C, D and T moved far off. A group then sits at a change position
    all along: its h² is flat, and every scan point was taken for a touching minimum and refined
    (2 047 Brent searches). A flat h² defines no change point: a handful of refinements at
    most, and the case ends in a result or a linkwork error."""
    import scipy.optimize

    text = TEXTS["whitworth-quick-return"]
    for old, new in (("D  = [62.648257205314, -20]", "D  = [62.648257205314, 3.0e5]"),
                     ("T  = [92.648257205314, -30]", "T  = [7.544162531321938e-10, -19.99999999996065]"),
                     ('C     = { type = "revolute", links = ["lever", "rod"] }',
                      'C     = { type = "revolute", links = ["frame", "rod"] }')):
        assert old in text
        text = text.replace(old, new)
    searches = []
    brent = scipy.optimize.minimize_scalar
    monkeypatch.setattr(scipy.optimize, "minimize_scalar",
                        lambda *a, **k: (searches.append(1), brent(*a, **k))[1])
    _assert_fine(run_file_case(text.encode(), random.Random(0)), "whitworth, rod on the frame")
    assert len(searches) <= 4 * 16
