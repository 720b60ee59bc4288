"""`-o FILE`: the suffix chooses the format (for `analyze`: Parquet with its units in the
metadata, CSV, JSON, JSON Lines) unless --format is given, and a suffix contradicting --format,
or naming a format the command does not write, is refused rather than written as the wrong kind
of file — in every command that writes text."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app

runner = CliRunner()


def test_parquet_by_suffix_with_units(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    out = tmp_path / "m.parquet"
    r = runner.invoke(app, ["analyze", "library:crank-rocker", "--at", "30,60", "-o", str(out)])
    assert r.exit_code == 0, r.output
    t = pq.read_table(out)
    units = json.loads(t.schema.metadata[b"linkwork.units"])
    assert list(units) == t.column_names  # one unit (or "") per column
    assert (units["input"], units["A.x"], units["A.vx"], units["coupler.omega"]) == \
        ("rad", "mm", "mm/s", "rad/s")
    df = t.to_pandas()
    # the crank pin at 30° and 60° on its circle of radius 10 about O2 (the file's drawing)
    np.testing.assert_allclose(df["A.x"], 10 * np.cos(np.radians([30, 60])), atol=1e-12)
    np.testing.assert_allclose(df["input"], np.radians([30, 60]), atol=1e-15)
    whole = tmp_path / "w.parquet"
    assert runner.invoke(app, ["analyze", "library:crank-rocker", "-o", str(whole)]).exit_code == 0
    assert pq.read_table(whole).num_rows == len(linkwork.whole_motion(linkwork.load("library:crank-rocker")))


@pytest.mark.parametrize("suffix, check", [
    (".json", lambda t: json.loads(t)["mechanism"] == "Crank-rocker four-bar"),
    (".jsonl", lambda t: len(t.splitlines()) == 2 and json.loads(t.splitlines()[1])["status"] == "ok"),
    (".csv", lambda t: t.splitlines()[0].startswith("input [rad],status,")),
])
def test_text_format_by_suffix(tmp_path, suffix, check):
    out = tmp_path / f"m{suffix}"
    r = runner.invoke(app, ["analyze", "library:crank-rocker", "--at", "30,60", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert check(out.read_text())


@pytest.mark.parametrize("fmt, name, message", [
    ("csv", "m.parquet", "has the suffix of parquet, but --format is csv"),
    ("json", "m.csv", "has the suffix of csv, but --format is json"),
])
def test_contradicting_suffix_is_refused(tmp_path, fmt, name, message):
    out = tmp_path / name
    r = runner.invoke(app, ["analyze", "library:crank-rocker", "--at", "30", "--format", fmt, "-o", str(out)])
    assert r.exit_code == 2 and message in r.output
    assert not out.exists()


#: the commands that write text, with the arguments they need
TEXT_COMMANDS = {
    "analyze": ["library:crank-rocker", "--at", "30"],
    "poles": ["library:crank-rocker"],
    "curvature": ["library:crank-rocker", "--link", "coupler"],
    "structure": ["library:crank-rocker"],
    "plan": ["library:crank-rocker"],
    "forces": ["library:crank-rocker", "--at", "30"],
}


@pytest.mark.parametrize("command", list(TEXT_COMMANDS))
def test_json_by_suffix_in_every_command(tmp_path, command):
    out = tmp_path / "m.json"
    r = runner.invoke(app, [command, *TEXT_COMMANDS[command], "-o", str(out)])
    assert r.exit_code == 0, r.output
    doc = json.loads(out.read_text())
    assert "Crank-rocker" in json.dumps(doc) or "four-bar" in json.dumps(doc).lower()
    text = tmp_path / "m.txt"  # a suffix of no data format: the command's text
    r = runner.invoke(app, [command, *TEXT_COMMANDS[command], "-o", str(text)])
    assert r.exit_code == 0, r.output
    with pytest.raises(ValueError):
        json.loads(text.read_text())


@pytest.mark.parametrize("command", list(TEXT_COMMANDS))
@pytest.mark.parametrize("name", ["m.svg", "m.toml"])
def test_a_format_the_command_does_not_write_is_refused(tmp_path, command, name):
    out = tmp_path / name
    r = runner.invoke(app, [command, *TEXT_COMMANDS[command], "-o", str(out)])
    assert r.exit_code == 2 and "this command writes" in r.output and ".json" in r.output
    assert not out.exists()


def test_forces_csv_by_suffix_and_parquet_refused(tmp_path):
    out = tmp_path / "f.csv"
    r = runner.invoke(app, ["forces", *TEXT_COMMANDS["forces"], "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert out.read_text().startswith("input [rad],")
    r = runner.invoke(app, ["forces", *TEXT_COMMANDS["forces"], "-o", str(tmp_path / "f.parquet")])
    assert r.exit_code == 2 and ".csv" in r.output


@pytest.mark.parametrize("argv", [
    ["synth", "cognates", "library:crank-rocker", "--point", "C"],
    ["cam", "design", "--rise", "10:180:cycloidal", "--return", "10:180:cycloidal",
     "--follower", "knife"],
])
def test_mechanism_files_are_toml(tmp_path, argv):
    out = tmp_path / "m.json"
    r = runner.invoke(app, [*argv, "-o", str(out)])
    assert r.exit_code == 2 and ".toml" in r.output
    assert not out.exists()
