"""The command line: outputs in the documented shape, and one clear message per user mistake."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from linkwork.cli import app

runner = CliRunner()


def run(*args):
    return runner.invoke(app, list(args))


def test_analyze_json_document_shape():
    r = run("analyze", "library:crank-rocker", "--at", "30,1.2rad", "--format", "json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    assert doc["mechanism"] == "Crank-rocker four-bar"
    assert doc["units"]["length"] == "mm"
    s0, s1 = doc["samples"]
    assert s0["input"] == pytest.approx(np.radians(30)) and s1["input"] == pytest.approx(1.2)
    assert s0["status"] == "ok" and s0["condition"] >= 1
    # crank pin A: |OA| = 10 mm at 60 rpm -> |v| = 10·2π mm/s, |a| = 10·(2π)² mm/s²
    a = s0["points"]["A"]
    assert np.hypot(*a["velocity"]) == pytest.approx(20 * np.pi)
    assert np.hypot(*a["acceleration"]) == pytest.approx(10 * (2 * np.pi) ** 2)
    assert a["position"] == pytest.approx([10 * np.cos(np.radians(30)), 10 * np.sin(np.radians(30))])
    assert set(s0["links"]) == {"crank", "coupler", "rocker"}
    assert set(s0["links"]["coupler"]) == {"angle", "omega", "alpha"}
    assert s0["joints"]["A"]["omega"] is not None


def test_analyze_whole_motion_csv(tmp_path):
    out = tmp_path / "m.csv"
    r = run("analyze", "library:crank-rocker", "--format", "csv", "-o", str(out))
    assert r.exit_code == 0, r.output
    lines = out.read_text().splitlines()
    assert len(lines) == 1 + 361  # one turn in 1° steps, both ends included
    assert "B.vx" in lines[0] and "coupler.omega" in lines[0]


def test_analyze_sweep_and_speed():
    r = run("analyze", "library:crank-rocker", "--sweep", "0:90:45", "--speed", "120 rpm", "--format", "json")
    doc = json.loads(r.output)
    assert [s["input"] for s in doc["samples"]] == pytest.approx(np.radians([0, 45, 90]))
    assert doc["samples"][0]["links"]["crank"]["omega"] == pytest.approx(4 * np.pi)


def test_analyze_table_runs():
    r = run("analyze", "library:crank-rocker", "--at", "10")
    assert r.exit_code == 0 and "coupler" in r.output


def test_library_lists_and_prints():
    r = run("library")
    assert r.exit_code == 0 and "crank-rocker" in r.output
    r = run("library", "crank-rocker")
    assert r.exit_code == 0 and "[joints]" in r.output


@pytest.mark.parametrize("args, message", [
    (("analyze", "library:nosuch"), "no mechanism 'nosuch'"),
    (("analyze", "/no/such/file.toml"), "no mechanism file"),
    (("analyze", "library:crank-rocker", "--at", "ten"), "cannot read"),
    (("analyze", "library:crank-rocker", "--at", "10 mm"), "give an angle"),
    (("analyze", "library:crank-rocker", "--sweep", "0:10"), "START:STOP:STEP"),
    (("analyze", "library:crank-rocker", "--sweep", "0:10:0"), "must not be zero"),
    (("analyze", "library:crank-rocker", "--sweep", "0:10:-1"), "away from STOP"),
    (("analyze", "library:crank-rocker", "--at", "1", "--sweep", "0:1:1"), "either --at or --sweep"),
    (("analyze", "library:crank-rocker", "--speed", "3 kg"), "speed"),
    (("library", "nosuch"), "no mechanism 'nosuch'"),
])
def test_user_mistakes_exit_nonzero_with_one_message(args, message):
    r = runner.invoke(app, list(args))
    assert r.exit_code == 2
    assert message in r.output
    assert "Traceback" not in r.output


def test_bad_file_message_names_key(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text('name = "x"\npoints = { A = [0, 0] }\nlinks = { frame = ["A"] }\njoints = {}\n'
                 '[driver]\njoint = "A"\nsped = "1 rpm"\n')
    r = run("analyze", str(f))
    assert r.exit_code == 2 and "driver.sped" in r.output and "Traceback" not in r.output


def test_drawing_at_a_change_point_prints_one_warning_line(tmp_path):
    from mechanism_texts import four_bar_text

    f = tmp_path / "flat.toml"
    f.write_text(four_bar_text(name="flat parallelogram (CLI warning test)", O2=(0, 0),
                               A=(20, 0), B=(60, 0), O4=(40, 0), speed="1 rad/s"))
    r = run("analyze", str(f), "--at", "30", "--format", "json")
    assert r.exit_code == 0, r.output
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("warning: mechanism 'flat parallelogram")
    assert "coupler, rocker" in lines[0] and "Traceback" not in r.output
