"""Several drivers: the inputs are a path (from the design input through the samples in their
order). Two-assembly groups flip where the path touches their change points, and a solve in
chunks (`resume=`, the streamed outputs) equals the solve in one piece sample for sample.

The five-bar here is drawn so that, with its second crank standing still, the loop through the
first crank is a parallelogram: O2 = (0, 0), A = (0, 10) on crank 2, C = (40, 15) on crank 5
(pivot O5 = (40, 0)), P = A + C: |AP| = |O2C| and |PC| = |O2A|. While crank 5 stands, P stays
at A + C (a parallelogram through its change points, where A passes the line O2C); keeping the
drawing's side would fold it into the antiparallelogram there. Expected values are this
closed form; where crank 5 moves too, they are the circle–circle point nearest to the one
extrapolated from the samples before (the motion is smooth), both points computed here.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork import Status
from linkwork.kinematics import solver
from mechanism_texts import hinged_loop_text, two_crank_five_bar_text

O2, A0, C0, O5 = np.array([0.0, 0.0]), np.array([0.0, 10.0]), np.array([40.0, 15.0]), np.array([40.0, 0.0])
P0 = A0 + C0

PARALLEL_FIVE_BAR = hinged_loop_text(
    name="five-bar, a parallelogram while crank 5 stands",
    hinges={"O2": tuple(O2), "A": tuple(A0), "P": tuple(P0), "C": tuple(C0), "O5": tuple(O5)},
    links=("frame", "crank2", "left", "right", "crank5"),
    link_points={"right": ["C", "P"], "crank5": ["O5", "C"]},
    driver=("O2", "O5"), speed=("1 rad/s", "0 rad/s"))


def _rot(v, t):
    c, s = np.cos(t), np.sin(t)
    return np.stack([c * v[0] - s * v[1], s * v[0] + c * v[1]], axis=-1)


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _crank_points(turn1, turn2):
    return _rot(A0 - O2, turn1) + O2, _rot(C0 - O5, turn2) + O5


def _both_assemblies(A, C):
    """The two points P with |AP| = |A0P0| and |CP| = |C0P0|."""
    r1, r2 = np.hypot(*(P0 - A0)), np.hypot(*(P0 - C0))
    D = C - A
    d = np.hypot(D[:, 0], D[:, 1])
    along = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    h = np.sqrt(np.maximum(r1 * r1 - along * along, 0.0))
    e = D / d[:, None]
    n = np.stack([-e[:, 1], e[:, 0]], axis=-1)
    foot = A + along[:, None] * e
    return foot + h[:, None] * n, foot - h[:, None] * n


def _followed(turns, start):
    """P along the path of input turns (N, 2) from `start`, smoothly: at each sample the point
    nearer to the one extrapolated from the two before (where the two assemblies cross, at a
    change point, the nearer point alone could be either). A fine path."""
    A, C = _crank_points(turns[:, 0], turns[:, 1])
    p, q = _both_assemblies(A, C)
    out = np.empty_like(p)
    for k in range(len(p)):
        guess = start if k == 0 else out[0] if k == 1 else 2 * out[k - 1] - out[k - 2]
        out[k] = p[k] if np.hypot(*(p[k] - guess)) <= np.hypot(*(q[k] - guess)) else q[k]
    return out


@pytest.fixture
def five_bar():
    mech = linkwork.load_text(PARALLEL_FIVE_BAR)
    assert [s.kind for s in solver.plan(mech)] == ["driver", "driver", "RRR"]
    return mech


def _design(mech):
    return np.array([mech.driver_input_at_design(d) for d in mech.drivers])


def test_parallelogram_of_a_five_bar_passes_its_change_points(five_bar):
    """Crank 2 turned a whole turn both ways, crank 5 standing: the change points at A on the
    line O2C (20.6° and 200.6° from the x-axis, crank 2 turned by −69.4° and +110.6°) are
    passed, and P stays at A + C throughout."""
    turn1 = np.radians(np.concatenate([np.arange(0, 361, 5.0), np.arange(355, -361, -5.0)]))
    turns = np.column_stack([turn1, np.zeros_like(turn1)])
    sol = linkwork.solve(five_bar, _design(five_bar) + turns, velocities=[[1.0, 0.0]])
    assert (sol.status != Status.UNREACHABLE).all()
    A, C = _crank_points(turns[:, 0], turns[:, 1])
    np.testing.assert_allclose(sol.point("P").position, A + C, atol=1e-9)
    # the motion is continuous: the parallelogram's P moves with A's velocity
    np.testing.assert_allclose(sol.point("P").velocity, sol.point("A").velocity, atol=1e-9)


def test_a_path_that_leaves_the_change_point_goes_on_the_branch_it_took(five_bar):
    """Crank 2 past the change point with crank 5 standing, then both moving: P follows the
    circle–circle point the motion runs on smoothly (computed along the same path, finely)."""
    leg1 = np.column_stack([np.radians(np.arange(0, -121, -1.0)), np.zeros(121)])
    leg2 = leg1[-1] + np.column_stack([np.radians(np.arange(1, 41, 1.0)), np.radians(np.arange(1, 41, 1.0)) * -0.5])
    turns = np.vstack([leg1, leg2])
    sol = linkwork.solve(five_bar, _design(five_bar) + turns)
    assert (sol.status != Status.UNREACHABLE).all()
    expected = _followed(turns, P0)
    np.testing.assert_allclose(sol.point("P").position, expected, atol=1e-9)
    # the design's side all along would give the other point past the change point
    keep = np.sign(_cross(C0 - A0, P0 - A0))
    A, C = _crank_points(turns[:, 0], turns[:, 1])
    side = np.sign(_cross(C - A, sol.point("P").position - A))
    assert (side[-40:] == -keep).all()


def test_a_path_passing_near_a_change_point_does_not_flip(five_bar):
    """Crank 5 turned by −1° before crank 2 sweeps: the loop is no parallelogram, A passes the
    line O2C off the change position (|AC| stays above |AP| − |PC|), and P stays on the side of
    AC it is drawn on."""
    leg1 = np.column_stack([np.zeros(10), np.radians(np.linspace(-0.1, -1.0, 10))])
    leg2 = np.column_stack([np.radians(np.arange(-1, -121, -1.0)), np.full(120, np.radians(-1.0))])
    turns = np.vstack([leg1, leg2])
    sol = linkwork.solve(five_bar, _design(five_bar) + turns)
    assert (sol.status != Status.UNREACHABLE).all()
    A, C = _crank_points(turns[:, 0], turns[:, 1])
    left, right = _both_assemblies(A, C)  # left of A→C: the drawing's side (P0 = A0 + C0)
    assert _cross(C0 - A0, P0 - A0) > 0
    np.testing.assert_allclose(sol.point("P").position, left, atol=1e-9)


# ---------------------------------------------------------------------------- in chunks
def _chunked(mech, values, sizes, **kw):
    sols, end, i = [], None, 0
    for n in sizes:
        sols.append(linkwork.solve(mech, values[i:i + n], resume=end, **kw))
        end, i = sols[-1].path_end, i + n
    assert i == len(values)
    return sols


def _assert_same(whole, parts, mech):
    for name in mech.points:
        got = np.vstack([p.point(name).position for p in parts])
        np.testing.assert_array_equal(got, whole.point(name).position, err_msg=name)
        got = np.vstack([p.point(name).velocity for p in parts])
        np.testing.assert_array_equal(got, whole.point(name).velocity, err_msg=name)
    np.testing.assert_array_equal(np.concatenate([p.status for p in parts]), whole.status)


def test_chunks_flip_where_the_one_piece_solve_flips(five_bar):
    """The parallelogram's path in chunks of 7 (a change point inside a chunk and one exactly
    at a chunk's last sample: crank 2 at −69.44°, the touching point is found from the next
    chunk) gives the one-piece solve bit for bit."""
    c = np.arctan2(15.0, 40.0) - np.pi / 2  # crank 2's turn to the change point
    turn1 = np.concatenate([np.linspace(0.0, c, 14), c + np.radians(np.arange(-3, -181, -3.0))])
    values = _design(five_bar) + np.column_stack([turn1, np.zeros_like(turn1)])
    whole = linkwork.solve(five_bar, values)
    parts = _chunked(five_bar, values, [7, 7, 7, 7, 7, 7, 7, 7, 7, 10, len(values) - 73])
    _assert_same(whole, parts, five_bar)
    A, C = _crank_points(turn1, 0.0 * turn1)
    np.testing.assert_allclose(whole.point("P").position, A + C, atol=1e-6)


def test_chunks_continue_the_march_of_newton_groups(newton):
    """The five-bar's dyad by Newton's method, samples far apart in random order: the march
    through them in chunks of 1–9 samples goes on where the chunk before ended, and gives the
    one-piece solve bit for bit."""
    mech = linkwork.load_text(two_crank_five_bar_text())
    assert {s.kind for s in solver.plan(mech)} == {"driver", "generic"}
    rng = np.random.default_rng(3)
    values = _design(mech) + rng.uniform(-0.6, 0.6, (60, 2))
    whole = linkwork.solve(mech, values)
    assert (whole.status == Status.OK).all()
    sizes = [1, 9, 2, 5, 8, 3, 7, 4, 6, 15]
    parts = _chunked(linkwork.load_text(two_crank_five_bar_text()), values, sizes)
    _assert_same(whole, parts, mech)


def test_streamed_analyze_of_a_five_bar_equals_one_solve(monkeypatch, tmp_path):
    """`analyze --sweep` of the parallelogram five-bar through its change point, solved 5
    samples at a time, writes the same text as solved in one chunk; past the change point P is
    at A + C (the parallelogram), which a restart from the design per chunk would lose."""
    from io import StringIO

    import pandas as pd
    from typer.testing import CliRunner

    from linkwork.cli import app, streams

    f = tmp_path / "five-bar.toml"
    f.write_text(PARALLEL_FIVE_BAR)
    mech = linkwork.load(f)
    d = np.degrees(_design(mech))
    args = ["analyze", str(f), "--sweep", f"O2={d[0]}:{d[0] - 180}:-4", "--sweep",
            f"O5={d[1]}:{d[1]}:1", "--format", "csv"]
    out = {}
    for chunk in (5, 1000):
        monkeypatch.setattr(streams, "CHUNK", chunk)
        r = CliRunner().invoke(app, args)
        assert r.exit_code == 0, r.output
        out[chunk] = r.stdout
    assert out[5] == out[1000]
    got = pd.read_csv(StringIO(out[5]))
    assert len(got) == 46
    sol = linkwork.solve(mech, np.radians(np.column_stack([d[0] - 4.0 * np.arange(46), np.full(46, d[1])])))
    A, C = sol.point("A").position, sol.point("C").position
    P = got[["P.x [mm]", "P.y [mm]"]].to_numpy(float)  # headers with their units
    np.testing.assert_allclose(P, A + C, atol=1e-6)


@pytest.mark.parametrize("name", ["roemer-mechanism", "crank-driven-wedge", "jansen-linkage"])
def test_one_driver_chunks_equal_the_one_piece_solve(name):
    """One driver: every sample is solved on its own (its change points counted from the
    design input, its Newton start interpolated from the kept march, reduced by the period
    only when beyond half of it), so chunks of 9 — some within half a turn, some beyond — give
    the one-piece solve bit for bit, and `path_end` is None."""
    mech = linkwork.load(f"library:{name}")
    values = _design(mech)[0] + np.radians(np.arange(-30, 400, 7.0))
    whole = linkwork.solve(mech, values)
    parts = [linkwork.solve(mech, values[i:i + 9]) for i in range(0, len(values), 9)]
    _assert_same(whole, parts, mech)
    np.testing.assert_array_equal(np.concatenate([p.errors for p in parts]), whole.errors)
    assert whole.path_end is None
