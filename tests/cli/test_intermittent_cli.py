"""The command line on Geneva and star wheels: analyze (table, JSON with the pair's phase and
slot), draw with every layer, poles, structure and plot run without error."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from linkwork.cli import app

runner = CliRunner()

LAYERS = "mechanism,paths,velocities,accelerations,poles,pole-lines,centrodes,inflection,return,bresse,gamma"


def run(*args):
    r = runner.invoke(app, list(args))
    assert r.exit_code == 0, r.output
    return r


def test_analyze_reports_phase_and_slot():
    doc = json.loads(run("analyze", "library:geneva-4", "--at", "0,100", "--format", "json").output)
    engaged, locked = (s["joints"]["pin"] for s in doc["samples"])
    assert engaged["phase"] == 1 and engaged["slot"] == 0
    assert engaged["ratio"] == pytest.approx(-1 / (np.sqrt(2) - 1), rel=1e-12)
    assert locked["phase"] == 0 and locked["slot"] == -1 and locked["omega"] == 0.0


@pytest.mark.parametrize("name", ["geneva-4", "geneva-6", "star-wheel"])
@pytest.mark.parametrize("at", ["0", "100", "200"])
def test_draw_every_layer(name, at, tmp_path):
    out = tmp_path / "m.svg"
    run("draw", f"library:{name}", "--at", at, "--show", LAYERS, "-o", str(out))
    assert out.read_text().startswith("<svg") or "<svg" in out.read_text()


@pytest.mark.parametrize("name", ["geneva-4", "star-wheel"])
def test_poles_structure_plot(name, tmp_path):
    run("poles", f"library:{name}", "--at", "30")
    run("poles", f"library:{name}", "--at", "180")
    r = run("structure", f"library:{name}")
    assert "constrained motion" in r.output
    wheel = "cross" if name == "geneva-4" else "star"
    run("plot", f"library:{name}", "--link", wheel, "-o", str(tmp_path / "p.svg"))
    run("analyze", f"library:{name}")


def test_analyze_table_lists_entry_and_exit_with_the_acceleration_jump():
    """60 rpm: ω = 2π/s; the 4-slot wheel jumps to ω²·tan 45° at entry (and from it at exit)."""
    out = run("analyze", "library:geneva-4").output
    assert "advances 90° per driver turn and rests 75% of it" in out
    jump = f"{(2 * np.pi) ** 2:.6g}"
    entry = next(line for line in out.splitlines() if "dwell → engaged" in line)
    exit_ = next(line for line in out.splitlines() if "engaged → dwell" in line)
    assert "315.0000" in entry and f"-{jump}" in entry
    assert "45.0000" in exit_ and jump in exit_
