"""`analyze -o FILE`: the suffix chooses the format (Parquet with its units in the metadata,
CSV, JSON, JSON Lines) unless --format is given, and a suffix contradicting --format is refused
rather than written as the wrong kind of file."""

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
    assert json.loads(t.schema.metadata[b"linkwork.units"]) == {"length": "mm", "angle": "rad", "time": "s"}
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
    (".csv", lambda t: t.splitlines()[0].startswith("input,status")),
])
def test_text_format_by_suffix(tmp_path, suffix, check):
    out = tmp_path / f"m{suffix}"
    r = runner.invoke(app, ["analyze", "library:crank-rocker", "--at", "30,60", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert check(out.read_text())


@pytest.mark.parametrize("fmt, name, message", [
    ("csv", "m.parquet", "writes Parquet; drop --format csv"),
    ("json", "m.csv", "has the suffix of csv, but --format is json"),
])
def test_contradicting_suffix_is_refused(tmp_path, fmt, name, message):
    out = tmp_path / name
    r = runner.invoke(app, ["analyze", "library:crank-rocker", "--at", "30", "--format", fmt, "-o", str(out)])
    assert r.exit_code == 2 and message in r.output
    assert not out.exists()
