"""`linkwork synth`: files that `analyze` runs through the prescribed positions (the coupler's
origin P and its angle read from the JSON output, compared with the positions written here by
hand), the Burmester four-bars of five positions of a closed-form four-bar, a function
generator meeting its precision points, and one clear message per mistake."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from four_bar_by_hand import generated
from linkwork.cli import app

runner = CliRunner()


def run(*args):
    return runner.invoke(app, [str(a) for a in args])


def pose_args(pos):
    out = []
    for x, y, t in pos.poses:
        out += ["--pose", f"{float(x)!r},{float(y)!r},{float(np.degrees(t))!r}"]
    return out


def analyze_at(path, degrees):
    r = run("analyze", path, "--at", ",".join(repr(float(d)) for d in degrees), "--format", "json")
    assert r.exit_code == 0, r.output
    return json.loads(r.output)["samples"]


def test_five_positions_write_files_that_analyze_runs_through_them(tmp_path):
    pos, A, B = generated([20, 50, 80, 110, 140])
    out, rep = tmp_path / "guide.toml", tmp_path / "guide.json"
    r = run("synth", "poses", *pose_args(pos), "-o", out, "--report", rep)
    assert r.exit_code == 0, r.output
    doc = json.loads(rep.read_text())
    assert len(doc["burmester"]["real"]) == 4 and doc["burmester"]["complex"] == 0
    first = doc["linkages"][0]
    assert first["input_pivot"] == pytest.approx([0, 0], abs=1e-9)
    assert first["output_pivot"] == pytest.approx([4, 0], abs=1e-9)
    for lk in doc["linkages"]:
        samples = analyze_at(lk["file"], lk["input_angles_deg"])
        for s, (x, y, t) in zip(samples, pos.poses):
            assert s["points"]["P"]["position"] == pytest.approx([x, y], abs=1e-9)
            # the crank by hand at 20°, 50°, …: P is the crank pin A in this set-up
        assert samples[1]["points"]["P"]["position"] == pytest.approx(A[1], abs=1e-9)


def test_three_positions_with_chosen_pivots(tmp_path):
    out = tmp_path / "three.toml"
    poses = [(0.0, 0.0, 0.0), (1.0, 0.4, 20.0), (1.8, 1.2, 45.0)]
    args = [a for p in poses for a in ("--pose", ",".join(map(str, p)))]
    r = run("synth", "poses", *args, "--centre", "0,-2", "--circle", "1,1", "-o", out, "--report", tmp_path / "r.json")
    assert r.exit_code == 0, r.output
    rep = json.loads((tmp_path / "r.json").read_text())
    samples = analyze_at(out, rep["linkages"][0]["input_angles_deg"])
    for s, (x, y, t) in zip(samples, poses):
        assert s["points"]["P"]["position"] == pytest.approx([x, y], abs=1e-9)
        d = np.subtract(s["points"]["Q"]["position"], s["points"]["P"]["position"])
        assert np.degrees(np.arctan2(d[1], d[0])) == pytest.approx(t, abs=1e-9)  # the plane's x-axis


def test_four_positions_slider(tmp_path):
    pos, A, B = generated([10, 45, 80, 120])
    out, rep = tmp_path / "slider.toml", tmp_path / "s.json"
    r = run("synth", "poses", *pose_args(pos), "--centre", "0,0", "--slider", "-o", out, "--report", rep)
    assert r.exit_code == 0, r.output
    doc = json.loads(rep.read_text())
    lk = doc["linkages"][0]
    assert lk["kind"] == "slider-crank"
    # the sampled centre-point curve: its points' circle points have four concyclic positions
    from linkwork.synthesis import circle_points
    from four_bar_by_hand import move
    pts = [p for p in doc["centre_point_curve"]["points"] if p is not None and np.hypot(*p) < 20]
    for M in pts[::40]:
        Z = circle_points(pos, M).xy
        r = [np.hypot(*(move(pos.poses[0], pos.poses[k], Z) - M)) for k in range(4)]
        assert np.ptp(r) < 1e-8 * max(r)
    for s, (x, y, t) in zip(analyze_at(out, lk["input_angles_deg"]), pos.poses):
        assert s["points"]["P"]["position"] == pytest.approx([x, y], abs=1e-9)


def test_function_generator(tmp_path):
    out, rep = tmp_path / "log.toml", tmp_path / "err.json"
    r = run("synth", "function", "--function", "log10(x)", "--x", "1:2", "--input-range", "30:120",
            "--output-range", "60:150", "-o", out, "--report", rep)
    assert r.exit_code == 0, r.output
    doc = json.loads(rep.read_text())
    xs = np.array(doc["precision_points"])
    phi = 30 + (xs - 1) * 90
    samples = analyze_at(out, phi)
    O4 = np.array([doc["lengths"]["frame"], 0.0])
    for s, x in zip(samples, xs):
        B = np.array(s["points"]["B"]["position"])
        v = np.sign(doc["lengths"]["output"]) * (B - O4)
        psi = np.degrees(np.arctan2(v[1], v[0])) % 360
        assert psi == pytest.approx(60 + 90 * np.log10(x) / np.log10(2), abs=1e-9)


@pytest.mark.parametrize("args, message", [
    (["poses", "--pose", "0,0,0", "--pose", "1,0,10", "-o", "x.toml"], "at least three positions"),
    (["poses", "--pose", "0,0", "--pose", "1,0,10", "--pose", "2,0,20", "-o", "x.toml"], "X,Y,ANGLE"),
    (["poses", "--pose", "0,0,0", "--pose", "1,0.4,20", "--pose", "1.8,1.2,45", "-o", "x.toml"], "give two pivots"),
    (["poses", "--pose", "0,0,0", "--pose", "1,0.4,20", "--pose", "1.8,1.2,45", "--pose", "2,2,60",
      "--centre", "0.1,0.2", "--centre", "3,3", "-o", "x.toml"], "centre-point curve"),
    (["function", "--function", "__import__('os')", "--x", "1:2", "--input-range", "0:90",
      "--output-range", "0:90", "-o", "x.toml"], "unknown function"),
    (["function", "--function", "x.real", "--x", "1:2", "--input-range", "0:90",
      "--output-range", "0:90", "-o", "x.toml"], "not allowed"),
    (["function", "--function", "y", "--x", "1:2", "--input-range", "0:90",
      "--output-range", "0:90", "-o", "x.toml"], "unknown name 'y'"),
    (["function", "--function", "x", "--x", "1:1", "--input-range", "0:90",
      "--output-range", "0:90", "-o", "x.toml"], "range of x"),
])
def test_mistakes_give_one_message(tmp_path, monkeypatch, args, message):
    monkeypatch.chdir(tmp_path)
    r = run("synth", *args)
    assert r.exit_code == 2
    assert message in r.output
    assert "Traceback" not in r.output


def test_dwell_and_substitute_commands(tmp_path):
    import linkwork
    from linkwork.kinematics import solve

    out = tmp_path / "dwell.toml"
    r = run("synth", "dwell", "library:crank-rocker", "--at", "60", "--point", "C", "-o", out)
    assert r.exit_code == 0, r.output
    six = linkwork.load(out)
    s = solve(six, [np.radians(60.0)], order=2)
    assert abs(s.link("output").omega[0]) < 1e-9 * 2 * np.pi
    sub = tmp_path / "sub.toml"
    r = run("synth", "substitute", "library:crank-rocker", "--at", "60", "--pivot", "5,-8", "-o", sub)
    assert r.exit_code == 0, r.output
    new, old = linkwork.load(sub), linkwork.load("library:crank-rocker")
    # at the design position the coupler point C is where the old four-bar has it at 60°
    assert np.allclose(new.points["C"], solve(old, [np.radians(60.0)], order=1).point("C").position[0], atol=1e-9)
    r = run("synth", "substitute", "library:crank-rocker", "--at", "60", "--pivot", "5,-8", "--replace", "frame",
            "-o", sub)
    assert r.exit_code == 2 and "replace" in r.output
