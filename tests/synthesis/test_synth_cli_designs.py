"""`linkwork synth straight-line|straightness|six-bar-path`: files that `analyze` runs as designed
(Hart's tracer on one line x = const read from analyze's JSON; Watt's tracer through the middle
and on the line of the coupler), and one clear message per mistake."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from linkwork.cli import app

runner = CliRunner()


def run(*args):
    return runner.invoke(app, [str(a) for a in args])


def analyze_at(path, degrees):
    r = run("analyze", path, "--at", ",".join(repr(float(d)) for d in degrees), "--format", "json")
    assert r.exit_code == 0, r.output
    return json.loads(r.output)["samples"]


def test_hart_command_writes_a_six_bar_whose_tracer_runs_straight(tmp_path):
    out, rep = tmp_path / "hart.toml", tmp_path / "hart.json"
    r = run("synth", "straight-line", "hart", "--mechanism", "library:crank-rocker", "-o", out, "--report", rep)
    assert r.exit_code == 0, r.output
    samples = analyze_at(out, np.arange(0, 360, 15))
    xs = [s["points"]["Q"]["position"][0] for s in samples]
    assert np.ptp(xs) <= 1e-9 * 100
    doc = json.loads(rep.read_text())
    assert doc["straightness"]["deviation"] <= 1e-9 * doc["straightness"]["stroke"]


def test_watt_command_and_straightness_command(tmp_path):
    out, rep = tmp_path / "watt.toml", tmp_path / "watt.json"
    r = run("synth", "straight-line", "watt", "--stroke", "20", "--arm", "50", "--coupler", "20", "-o", out,
            "--report", rep)
    assert r.exit_code == 0, r.output
    s = analyze_at(out, [0.0])[0]
    assert s["points"]["Q"]["position"] == pytest.approx([0.0, 0.0], abs=1e-12)
    doc = json.loads(rep.read_text())
    assert doc["lengths"]["arm"] == 50 and doc["lengths"]["coupler"] == 20
    r = run("synth", "straightness", out, "--point", "Q", "--stroke", "20")
    assert r.exit_code == 0, r.output
    assert f"{doc['straightness']['deviation']:.3g}" in r.output


@pytest.mark.parametrize("args, message", [
    (["straight-line", "sarrus", "--stroke", "1", "-o", "x.toml"], "choose one of"),
    (["straight-line", "watt", "-o", "x.toml"], "--stroke"),
    (["straight-line", "watt", "--stroke", "10", "--arm", "3", "-o", "x.toml"], "two of"),
    (["straight-line", "hart", "-o", "x.toml"], "--mechanism"),
    (["straight-line", "ball-point", "--mechanism", "library:crank-rocker", "-o", "x.toml"], "--at"),
    (["straightness", "library:crank-rocker", "--point", "C", "--stroke", "1000"], "too long"),
])
def test_mistakes_give_one_message(tmp_path, monkeypatch, args, message):
    monkeypatch.chdir(tmp_path)
    r = run("synth", *args)
    assert r.exit_code == 2, r.output
    assert message in r.output
    assert "Traceback" not in r.output


def test_substitute_to_third_order(tmp_path):
    out = tmp_path / "sub.toml"
    r = run("synth", "substitute", "library:crank-rocker", "--at", "60", "--pivot", "30,-10", "--replace",
            "output", "--order", "3", "-o", out)
    assert r.exit_code == 0, r.output
    old, new = analyze_at("library:crank-rocker", [60.0])[0], analyze_at(out, [60.0])[0]
    for q in ("position", "velocity", "acceleration"):
        assert new["points"]["C"][q] == pytest.approx(old["points"]["C"][q], abs=1e-9 * 40 * 40)
    r = run("synth", "substitute", "library:crank-rocker", "--at", "60", "--pivot", "30,-10", "--order", "4",
            "-o", out)
    assert r.exit_code == 2 and "order 2 or 3" in r.output


def test_six_bar_path_command(tmp_path):
    from test_six_bar_path import sampled

    T, th = sampled("watt", 5)
    out = tmp_path / "six.toml"
    args = [a for p in T for a in ("--point", f"{float(p[0])!r},{float(p[1])!r}")]
    r = run("synth", "six-bar-path", "--kind", "watt", *args, "--timing",
            ",".join(repr(float(np.degrees(t - th[0]))) for t in th), "-o", out)
    assert r.exit_code == 0, r.output
    import linkwork

    mech = linkwork.load(out)
    # the file is drawn at the first target: its tracer is there
    assert np.allclose(mech.points["P"], T[0], atol=1e-9 * 50)
    r = run("synth", "six-bar-path", "--kind", "klann", *args, "-o", out)
    assert r.exit_code == 2 and "choose one of" in r.output


def test_poles_command_draws_the_steps(tmp_path):
    out = tmp_path / "hamilton.svg"
    r = run("synth", "poles", "--pose", "0,0,0", "--pose", "1,0.4,20", "--pose", "1.8,1.2,45", "--steps", "-o", out)
    assert r.exit_code == 0, r.output
    files = sorted(tmp_path.glob("hamilton-*.svg"))
    assert len(files) == 8
    assert "P_13" in r.output and "relative error" in r.output
    r = run("synth", "poles", "--pose", "0,0,0", "--pose", "1,0,0", "--pose", "2,0,0", "-o", out)
    assert r.exit_code == 2 and "translation" in r.output
