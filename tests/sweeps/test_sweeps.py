"""Design sweeps: every metric against a closed form of the swept designs, computed here from
the designs' drawings (cosine rule for the crank-rocker's transmission angle and its rocker's
dead centres, Grashof's inequality on the drawn lengths, Pöschl's quick-return time ratio, the
crank pin's circle), never from the solver; and the runner's contracts (parallel = serial, a
resumed sweep = a fresh one, random samples reproducible, units in the files, clear errors)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork import sweeps
from linkwork.cli import app
from linkwork.errors import InputError

CR = "library:crank-rocker"  # O2 (0, 0), A (0, 10), B (30, 30), O4 (40, 0)


def frame(p, rows):
    return sweeps.to_frame(p, rows)


def four_bar_lengths(o4x, a):
    """Frame d, crank a, coupler b, rocker c of the crank-rocker with O4 at (o4x, 0) and A at
    (0, a) (the parameter O2-A moves A along O2A)."""
    A, B, O4 = np.array([0.0, a]), np.array([30.0, 30.0]), np.array([o4x, 0.0])
    return o4x, a, float(np.linalg.norm(B - A)), float(np.linalg.norm(B - O4))


def test_transmission_angle_extremes_of_crank_rockers_by_the_cosine_rule():
    """Over the crank's turn the transmission angle μ at B is extreme where the crank lies on the
    frame line: cos μ = (b² + c² − (d ∓ a)²)/(2bc). The whole motion samples those positions
    (1° steps from the drawn 90°)."""
    p = sweeps.plan(CR, ["O4.x=36:44:4", "O2-A=8:12:2"], ["transmission-min:B", "transmission-max:B", "grashof"])
    df = frame(p, sweeps.execute(p, workers=1))
    for _, r in df.iterrows():
        d, a, b, c = four_bar_lengths(r["O4.x"], r["O2-A"])
        lo = math.degrees(math.acos((b * b + c * c - (d - a) ** 2) / (2 * b * c)))
        hi = math.degrees(math.acos((b * b + c * c - (d + a) ** 2) / (2 * b * c)))
        assert r["grashof"] == "Grashof crank-rocker"
        assert r["transmission-min:B"] == pytest.approx(lo, abs=1e-9)
        assert r["transmission-max:B"] == pytest.approx(hi, abs=1e-9)


def test_grashof_class_changes_where_s_plus_l_passes_p_plus_q():
    """Lengthening the crank (O2-A) past s + l = p + q turns the crank-rocker into a non-Grashof
    chain whose input no longer turns fully (input range < 360°)."""
    p = sweeps.plan(CR, ["O2-A=5:35:5"], ["grashof", "input-range"])
    df = frame(p, sweeps.execute(p, workers=1))
    for _, r in df.iterrows():
        L = sorted(four_bar_lengths(40.0, r["O2-A"]))
        grashof = L[0] + L[3] < L[1] + L[2]
        assert r["grashof"].startswith("Grashof" if grashof else "non-Grashof"), (r["O2-A"], L)
        assert (r["input-range"] == pytest.approx(360.0)) == grashof
    assert set(df["grashof"].str.split().str[0]) == {"Grashof", "non-Grashof"}


def test_time_ratio_of_the_rocker_from_its_dead_centres():
    """The rocker reverses where crank and coupler are in line (|O2B| = b ± a); the crank arcs
    between those two positions give the time ratio (π + δ)/(π − δ)."""
    p = sweeps.plan(CR, ["O4.x=36:44:4"], ["time-ratio:B"])
    df = frame(p, sweeps.execute(p, workers=1))
    for _, r in df.iterrows():
        d, a, b, c = four_bar_lengths(r["O4.x"], 10.0)
        ang = lambda f: math.acos((d * d + f * f - c * c) / (2 * d * f))  # angle B O2 O4, B above
        t_ext, t_fold = ang(b + a), ang(b - a) + math.pi
        arc = (t_fold - t_ext) % (2 * math.pi)
        assert r["time-ratio:B"] == pytest.approx(max(arc, 2 * math.pi - arc) / min(arc, 2 * math.pi - arc),
                                                  rel=1e-4)  # reversals interpolated between 1° samples


def test_quick_return_time_ratio_against_poeschl():
    """Pöschl §24b: the slotted lever shaper's slide E has the time ratio
    (π + 2 asin(r/d))/(π − 2 asin(r/d)), r = AB = 40 the crank and d = AC the frame. The lever's
    pivot C is moved along the slot's line (B-C, so the slot still passes through C) and d
    taken from the new drawing."""
    name = "library:poeschl-quick-return-shaper"
    m = linkwork.load(name)
    A, B, C = (np.array(m.points[k]) for k in "ABC")
    p = sweeps.plan(name, ["B-C=90:130:20"], ["time-ratio:E", "stroke:E"])
    df = frame(p, sweeps.execute(p, workers=1))
    for _, r in df.iterrows():
        C_new = B + r["B-C"] * (C - B) / np.linalg.norm(C - B)
        s = math.asin(40 / np.linalg.norm(C_new - A))
        assert r["time-ratio:E"] == pytest.approx((math.pi + 2 * s) / (math.pi - 2 * s), rel=1e-4)
    assert (np.diff(df["stroke:E"]) < 0).all()  # a longer frame swings the lever less


def test_circularity_straightness_stroke_and_reductions():
    """The crank pin runs on a circle of radius |O2A| (circularity 0, stroke 2·|O2A|, speed ω·r at
    60 rpm); the elliptic straight-line's B runs on a line (straightness 0) of length 2·AB."""
    p = sweeps.plan(CR, ["O2-A=8:12:2"], ["circularity:A", "stroke:A", "A.speed:max", "crank.omega:rms",
                                          "A.x:range", "straightness:C"])
    df = frame(p, sweeps.execute(p, workers=1))
    r = df["O2-A"].to_numpy()
    np.testing.assert_allclose(df["circularity:A"], 0.0, atol=1e-9)
    np.testing.assert_allclose(df["stroke:A"], 2 * r, rtol=1e-6)  # the 1° samples reach both ends
    np.testing.assert_allclose(df["A.speed:max"], 2 * np.pi * r, rtol=1e-12)
    np.testing.assert_allclose(df["crank.omega:rms"], 360.0, rtol=1e-12)
    np.testing.assert_allclose(df["A.x:range"], 2 * r, rtol=1e-12)
    assert (df["straightness:C"] > 1).all()  # a coupler curve, far from straight
    q = sweeps.plan("library:elliptic-straight-line", ["O.x=0:0:1"], ["straightness:B", "stroke:B"])
    e = frame(q, sweeps.execute(q, workers=1)).iloc[0]
    assert e["straightness:B"] == pytest.approx(0.0, abs=1e-9)
    # the dead centres at ±90° (B at ±AB) are singular samples, left out: the stroke ends at ±89°
    assert e["stroke:B"] == pytest.approx(200.0 * math.sin(math.radians(89)), rel=1e-12)


def test_inputs_instead_of_the_whole_motion():
    p = sweeps.plan(CR, ["O2-A=10:10:1"], ["A.y:max", "A.y:min"], inputs=np.radians([0.0, 30.0]))
    r = frame(p, sweeps.execute(p, workers=1)).iloc[0]
    assert (r["A.y:min"], r["A.y:max"]) == pytest.approx((0.0, 5.0), abs=1e-12)


def test_parallel_equals_serial_and_resume_equals_fresh(tmp_path):
    p = sweeps.plan(CR, ["O4.x=36:44:2", "C.y=20:30:5"], ["transmission-min:B", "straightness:C", "grashof"])
    serial = sweeps.execute(p, workers=1, chunk=4)
    assert sweeps.execute(p, workers=2, chunk=4) == serial
    side = tmp_path / "s.resume.jsonl"
    calls = []
    sweeps.execute(p, workers=1, chunk=4, resume=side, progress=lambda d, n: calls.append(d))
    lines = side.read_text().splitlines()
    side.write_text("\n".join(lines[:3]) + "\n" + lines[3][:10])  # cut off after two chunks, mid-line
    resumed_from = []
    again = sweeps.execute(p, workers=1, chunk=4, resume=side, progress=lambda d, n: resumed_from.append(d))
    assert again == serial
    assert resumed_from[0] == 8 and calls[-1] == len(p.designs) == 15
    other = sweeps.plan(CR, ["O4.x=36:44:2"], ["grashof"])
    with pytest.raises(InputError, match="belongs to another sweep"):
        sweeps.execute(other, workers=1, chunk=4, resume=side)


def test_random_samples_are_reproducible_and_inside_the_box():
    a = sweeps.plan(CR, ["O4.x=35:45", "C.y=20:30"], ["grashof"], samples=50, seed=3)
    b = sweeps.plan(CR, ["O4.x=35:45", "C.y=20:30"], ["grashof"], samples=50, seed=3)
    np.testing.assert_array_equal(a.designs, b.designs)
    assert a.designs.shape == (50, 2)
    assert (a.designs[:, 0] >= 35).all() and (a.designs[:, 0] <= 45).all()
    assert (a.designs[:, 1] >= 20).all() and (a.designs[:, 1] <= 30).all()


def test_design_parameters_move_only_what_they_name():
    m = linkwork.load(CR)
    q = sweeps.apply(m, [sweeps.parameter(m, "A-B"), sweeps.parameter(m, "O4.y")], [50.0, 3.0])
    A = np.array(m.points["A"])
    assert np.linalg.norm(np.array(q.points["B"]) - A) == pytest.approx(50.0)
    u, v = np.array(q.points["B"]) - A, np.array(m.points["B"]) - A
    assert u[0] * v[1] - u[1] * v[0] == pytest.approx(0.0, abs=1e-9) and u @ v > 0
    assert tuple(q.points["O4"]) == (40.0, 3.0)
    assert tuple(q.points["C"]) == tuple(m.points["C"])


@pytest.mark.parametrize("vary, metric, message", [
    (["Q.x=1:2:1"], ["grashof"], "no point 'Q'"),
    (["A.z=1:2:1"], ["grashof"], "name a coordinate"),
    (["O2-A=1:5:-1"], ["grashof"], "does not lead"),
    (["O4.x=1:2:1"], ["transmission-min:O2x"], "not a revolute joint"),
    (["O4.x=1:2:1"], ["stroke"], "needs a point"),
    (["O4.x=1:2:1"], ["C.jerk:max"], "unknown metric"),
    (["O4.x=1:2:1", "O4.x=3:4:1"], ["grashof"], "twice"),
    ([], ["grashof"], "at least one --vary"),
])
def test_bad_arguments_are_refused_with_one_message(vary, metric, message):
    with pytest.raises(InputError, match=message):
        sweeps.plan(CR, vary, metric)


def test_a_design_that_cannot_be_built_is_marked_not_fatal():
    p = sweeps.plan(CR, ["O2-A=-5:10:15"], ["grashof", "transmission-min:B"])
    df = frame(p, sweeps.execute(p, workers=1))
    assert df["status"].iloc[0].startswith("error: parameter O2-A: a length must be positive")
    assert math.isnan(df["transmission-min:B"].iloc[0]) and df["status"].iloc[1] == "ok"


def test_cli_writes_csv_and_parquet_with_units(tmp_path):
    runner = CliRunner()
    out = tmp_path / "s.csv"
    r = runner.invoke(app, ["sweep", CR, "--vary", "O4.x=36:40:4", "--metric", "transmission-min:B",
                            "--metric", "grashof", "--workers", "1", "-o", str(out)])
    assert r.exit_code == 0, r.output
    head = out.read_text().splitlines()[0]
    assert head == "O4.x [mm],transmission-min:B [deg],grashof,ok [fraction of samples],status"
    assert not (tmp_path / "s.csv.resume.jsonl").exists()
    pq = pytest.importorskip("pyarrow.parquet")
    out = tmp_path / "s.parquet"
    r = runner.invoke(app, ["sweep", CR, "--samples", "3", "--vary", "O4.x=36:40", "--metric",
                            "max-speed:C", "--workers", "1", "-o", str(out)])
    assert r.exit_code == 0, r.output
    t = pq.read_table(out)
    assert json.loads(t.schema.metadata[b"linkwork.units"])["max-speed:C"] == "mm/s"
    assert t.num_rows == 3
    r = runner.invoke(app, ["sweep", CR, "--vary", "O4.x=36:40:4", "--metric", "grashof", "-o", "x.txt"])
    assert r.exit_code == 2 and "write .csv or .parquet" in r.output


def test_dask_cluster_path_equals_the_local_one(tmp_path):
    """The distributed path on an in-process LocalCluster (dask.distributed): the same rows as
    the serial run, by address and by client, and resumable like the local one."""
    distributed = pytest.importorskip("distributed")
    p = sweeps.plan(CR, ["O4.x=36:44:4", "O2-A=9:11:2"], ["transmission-min:B", "grashof", "time-ratio:B"])
    serial = sweeps.execute(p, workers=1)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        assert sweeps.execute(p, scheduler=cluster.scheduler_address, chunk=2) == serial
        with distributed.Client(cluster, set_as_default=False) as client:
            side = tmp_path / "d.resume.jsonl"
            assert sweeps.execute(p, scheduler=client, chunk=2, resume=side) == serial
            assert len(side.read_text().splitlines()) == 1 + 3


def test_unreachable_scheduler_is_a_clear_error():
    pytest.importorskip("distributed")
    p = sweeps.plan(CR, ["O4.x=36:36:1"], ["grashof"])
    with pytest.raises(InputError, match="cannot reach the Dask scheduler at tcp://127.0.0.1:9"):
        sweeps.execute(p, scheduler="tcp://127.0.0.1:9")


def test_parameters_named_in_the_file(tmp_path):
    """crank-rocker.toml names crank = "O2-A" and frame = "O2-O4": sweeping by those names is
    sweeping the distances; a [parameters] entry naming an unknown point is refused on loading,
    with its key and line."""
    by_name = sweeps.plan(CR, ["crank=8:12:2", "frame=38:42:4"], ["transmission-min:B"])
    by_expr = sweeps.plan(CR, ["O2-A=8:12:2", "O2-O4=38:42:4"], ["transmission-min:B"])
    assert [p.name for p in by_name.params] == ["crank", "frame"]
    assert [r[2:] for r in sweeps.execute(by_name, workers=1)] == [r[2:] for r in sweeps.execute(by_expr, workers=1)]
    with pytest.raises(InputError, match=r"parameter of the file's \[parameters\] \(coupler, crank, frame, rocker\)"):
        sweeps.plan(CR, ["crankk=1:2:1"], ["grashof"])
    from linkwork.errors import MechanismFileError
    text = linkwork.io.files.resolve(CR)[1].replace('rocker  = "O4-B"', 'rocker  = "O4-X"')
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    with pytest.raises(MechanismFileError, match=r"bad.toml:\d+, key 'parameters.rocker': parameter 'rocker' "
                                                 r"names point 'X', which is not in \[points\]"):
        linkwork.load(str(bad))


def test_direction_parameters_turn_a_point_about_another():
    """`O2-A.angle` turns the crank pin about O2 (radius kept); swept over the circle, the crank
    of length 10 stays a crank (Grashof) while the coupler |AB| follows the cosine rule."""
    m = linkwork.load(CR)
    prm = sweeps.parameter(m, "O2-A.angle")
    assert prm.value(m) == pytest.approx(90.0)
    q = sweeps.apply(m, [prm], [30.0])
    np.testing.assert_allclose(q.points["A"], [10 * np.cos(np.radians(30)), 10 * np.sin(np.radians(30))])
    p = sweeps.plan(CR, ["O2-A.angle=0:180:60"], ["A.y:max", "grashof"], inputs=np.radians([0.0]))
    df = frame(p, sweeps.execute(p, workers=1))
    # the crank is turned back to 0° by the input; its drawn angle does not matter for A,
    # but the coupler length |AB| = |(30, 30) − 10·(cos φ, sin φ)| does for the class
    for _, r in df.iterrows():
        phi = math.radians(r["O2-A.angle"])
        b = math.hypot(30 - 10 * math.cos(phi), 30 - 10 * math.sin(phi))
        L = sorted([40.0, 10.0, b, math.hypot(10, 30)])
        assert r["grashof"].startswith("Grashof" if L[0] + L[3] < L[1] + L[2] else "non-Grashof")
        assert r["A.y:max"] == pytest.approx(0.0, abs=1e-12)


def test_a_sweep_on_the_compiled_loops_gives_the_same_rows(monkeypatch):
    """A sweep with enough designs per process runs the compiled loops (loaded once): its rows
    are those of the interpreted loops to rounding (numba fuses multiply-adds), and the
    threshold of the solves around it is as it was."""
    from linkwork.kinematics import kernels
    from linkwork.sweeps import run as R

    p = sweeps.plan("library:crank-rocker", ["O4.x=38:42:2", "O2-A=9:11:2"],
                    ["transmission-min:B", "max-speed:C", "time-ratio:B"])
    threshold = kernels.INTERPRETED_UP_TO
    monkeypatch.setattr(R, "COMPILED_FROM", 10 ** 9)
    plain = sweeps.execute(p, workers=1)
    monkeypatch.setattr(R, "COMPILED_FROM", 1)
    fast = sweeps.execute(p, workers=1)
    assert kernels.INTERPRETED_UP_TO == threshold
    assert [r[-1] for r in fast] == [r[-1] for r in plain]
    np.testing.assert_allclose(np.array([r[:-1] for r in fast], float),
                               np.array([r[:-1] for r in plain], float), rtol=1e-9)
