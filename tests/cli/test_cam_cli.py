"""`linkwork cam design`: the segments in the order written, a mechanism file that `analyze`
runs with the law's numbers (checked against the closed form by hand), the report, and one
clear message per mistake."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app

runner = CliRunner()


def run(*args):
    return runner.invoke(app, [str(a) for a in args])


def test_design_writes_a_file_that_analyze_runs(tmp_path):
    out, rep = tmp_path / "cam.toml", tmp_path / "cam.png"
    r = run("cam", "design", "--rise", "20:120:cycloidal", "--dwell", "60", "--return", "20:120:3-4-5",
            "--dwell", "60", "--follower", "roller", "--radius", 8, "--base-radius", 40, "--offset", 5,
            "--speed", "300 rpm", "-o", out, "--report", rep)
    assert r.exit_code == 0, r.output
    assert "engine vs law" in r.output and "cusps" in r.output
    assert rep.stat().st_size > 10_000
    # analyze at 30°: cycloidal rise, x = 1/4: s = 20(1/4 − 1/2π), v = ω·(20/β)(1 − cos π/2)
    r = run("analyze", out, "--at", "30", "--format", "json")
    assert r.exit_code == 0, r.output
    C = json.loads(r.output)["samples"][0]["points"]["C"]
    w, beta = 300 * 2 * np.pi / 60, np.radians(120)
    y0 = np.sqrt(48.0**2 - 5.0**2)
    assert C["position"] == pytest.approx([5.0, y0 + 20 * (0.25 - 1 / (2 * np.pi))], abs=1e-9)
    assert C["velocity"] == pytest.approx([0.0, w * 20 / beta], abs=1e-9)
    assert C["acceleration"] == pytest.approx([0.0, w**2 * 20 / beta**2 * 2 * np.pi], abs=1e-7)


def test_segments_are_taken_in_the_order_written(tmp_path):
    """A dwell first, then the rise: the follower rests over the first 90°."""
    out = tmp_path / "cam.toml"
    r = run("cam", "design", "--dwell", "90", "--rise", "10:90:harmonic", "--dwell", "90",
            "--return", "10:90:harmonic", "--follower", "knife", "--base-radius", 30, "-o", out)
    assert r.exit_code == 0, r.output
    mech = linkwork.load(out)
    sol = linkwork.solve(mech, np.radians([45.0, 135.0, 225.0]))
    y = sol.point("C").position[:, 1] - 30.0
    assert y == pytest.approx([0.0, 5.0, 10.0], abs=1e-9)


def test_smallest_base_circle_for_a_pressure_angle(tmp_path):
    """Centric translating roller, harmonic rise and return: tan α = s′/(R₀ + s); the command's
    base circle gives a largest pressure angle of exactly 30° (by a dense check by hand)."""
    out = tmp_path / "cam.toml"
    r = run("cam", "design", "--rise", "30:150:harmonic", "--return", "30:150:harmonic", "--dwell", "60",
            "--follower", "roller", "--radius", 10, "--max-pressure-angle", 30, "-o", out)
    assert r.exit_code == 0, r.output
    text = out.read_text()
    base = float(text.split("base_radius = ")[1].split("\n")[0])
    x = np.linspace(0, 1, 200001)
    beta = np.radians(150)
    s, s1 = 15 * (1 - np.cos(np.pi * x)), 15 * np.pi / beta * np.sin(np.pi * x)
    alpha = np.arctan(s1 / (base + 10 + s))
    assert np.degrees(alpha.max()) == pytest.approx(30.0, abs=1e-6)


def test_oscillating_follower(tmp_path):
    out = tmp_path / "osc.toml"
    r = run("cam", "design", "--rise", "15:100:modified-sine", "--dwell", "50", "--return", "15:150:modified-trapezoid",
            "--dwell", "60", "--motion", "oscillating", "--pivot", "90,20", "--arm", "70", "--follower", "roller",
            "--radius", 6, "--base-radius", 30, "-o", out)
    assert r.exit_code == 0, r.output
    sol = linkwork.solve(linkwork.load(out), np.radians([100.0 + 25.0]))  # in the outer dwell
    turn = np.degrees(abs(sol.pose_derivatives("follower")[0, 0, 2]))
    assert turn == pytest.approx(15.0, abs=1e-9)


def test_undercut_is_warned(tmp_path):
    r = run("cam", "design", "--dwell", "60", "--rise", "30:60:harmonic", "--return", "30:60:harmonic",
            "--dwell", "180", "--follower", "flat", "--base-radius", 20, "-o", tmp_path / "f.toml")
    assert r.exit_code == 0, r.output
    assert "warning" in r.output and "undercut" in r.output


@pytest.mark.parametrize("args,message", [
    (["--rise", "20:120:cycloidal", "--return", "20:120:cycloidal", "--dwell", "100", "--follower", "knife",
      "--base-radius", "20"], "cover 340°"),
    (["--rise", "20:120:cycloidl", "--return", "20:120:cycloidal", "--dwell", "120", "--follower", "knife",
      "--base-radius", "20"], "segment 1 .*unknown motion law 'cycloidl'"),
    (["--rise", "20:120", "--return", "20:120:cycloidal", "--dwell", "120", "--base-radius", "20"],
     "--rise 20:120 .*LIFT:ANGLE:LAW"),
    (["--rise", "20:180:uniform", "--return", "20:180:cycloidal", "--follower", "flat", "--base-radius", "20"],
     "flat face cannot follow a jump of velocity"),
    (["--rise", "20:180:cycloidal", "--return", "20:180:cycloidal", "--base-radius", "20"], "needs --radius"),
    (["--rise", "20:180:cycloidal", "--return", "20:180:cycloidal", "--follower", "knife"], "give --base-radius"),
    (["--rise", "20:180:cycloidal", "--return", "20:180:cycloidal", "--follower", "knife", "--base-radius", "20",
      "--motion", "oscillating", "--arm", "40"], "needs --pivot"),
])
def test_mistakes_get_one_clear_message(tmp_path, args, message):
    r = run("cam", "design", *args, "-o", tmp_path / "x.toml")
    assert r.exit_code == 2
    assert "error:" in r.output
    assert re.search(message, r.output.replace("\n", " ")), r.output
