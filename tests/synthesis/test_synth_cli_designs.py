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
