"""Output safety and bounded cost (issue 10): every output that cannot be written is one line
naming the path; a file appears whole or not at all (full disk, Ctrl-C); long outputs are
estimated before they are solved, and streamed."""

import errno
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from linkwork.cli import streams
from linkwork.errors import OutputError
from linkwork.outputs import output_path, write_output_file

runner = CliRunner()

COMMANDS = {
    "analyze": ["analyze", "library:crank-rocker", "--at", "30", "--format", "csv"],
    "poles": ["poles", "library:crank-rocker"],
    "curvature": ["curvature", "library:crank-rocker", "--link", "coupler"],
    "draw": ["draw", "library:crank-rocker"],
    "plot": ["plot", "library:crank-rocker", "--point", "B"],
}


def run(*args):
    return runner.invoke(app, list(args))


def _one_line_error(r, path: str) -> None:
    assert r.exit_code == 2, r.output
    assert r.exception is None or isinstance(r.exception, SystemExit)
    lines = r.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: cannot write '{path}'"), r.output


@pytest.mark.parametrize("command", COMMANDS)
def test_missing_folder_is_one_line(command, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = "nodir/out.svg" if command in ("draw", "plot") else "nodir/out.txt"
    r = run(*COMMANDS[command], "-o", path)
    _one_line_error(r, path)
    assert "no directory 'nodir'" in r.output


@pytest.mark.parametrize("command", COMMANDS)
def test_folder_as_output_is_one_line(command, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = "adir.svg" if command in ("draw", "plot") else "adir.txt"  # a suffix each writes
    (tmp_path / path).mkdir()
    r = run(*COMMANDS[command], "-o", path)
    _one_line_error(r, path)
    assert "it is a directory" in r.output


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="needs /dev/full")
@pytest.mark.parametrize("command", ["analyze", "poles", "curvature"])
def test_full_device_is_one_line(command):
    r = run(*COMMANDS[command], "-o", "/dev/full")
    _one_line_error(r, "/dev/full")
    assert os.strerror(errno.ENOSPC) in r.output


def _leftovers(folder: Path) -> list[str]:
    return [p.name for p in folder.iterdir() if ".part" in p.name]


def test_full_disk_keeps_the_previous_output(tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("previous\n")

    def chunks():
        yield "a,b\n"
        yield "1,2\n"
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    with pytest.raises(OutputError, match="No space left on device"):
        write_output_file(target, chunks())
    assert target.read_text() == "previous\n" and _leftovers(tmp_path) == []


def test_interrupt_keeps_the_previous_output(tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("previous\n")

    def chunks():
        yield "a,b\n"
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_output_file(target, chunks())
    assert target.read_text() == "previous\n" and _leftovers(tmp_path) == []


def test_complete_output_replaces_and_keeps_permissions(tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("previous\n")
    target.chmod(0o640)
    write_output_file(target, iter(["x\n", "y\n"]))
    assert target.read_text() == "x\ny\n" and (target.stat().st_mode & 0o777) == 0o640
    with output_path(tmp_path / "new.bin") as p:
        p.write_bytes(b"\x00\x01")
    assert (tmp_path / "new.bin").read_bytes() == b"\x00\x01" and _leftovers(tmp_path) == []


def test_sigint_leaves_no_partial_file(tmp_path):
    """A real Ctrl-C while a long sweep is being written: the previous file stays, no part file."""
    target = tmp_path / "out.jsonl"
    target.write_text("previous\n")
    cmd = [sys.executable, "-c", "from linkwork.cli import app; app()", "analyze",
           "library:crank-rocker", "--sweep", "0:360:0.0005", "--format", "jsonl", "-o", str(target)]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 300  # a guard against a hang, not a timing assertion
        while not _leftovers(tmp_path):
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() < deadline
            time.sleep(0.05)
        proc.send_signal(signal.SIGINT)
        proc.communicate(timeout=300)
    finally:
        proc.kill()
    assert proc.returncode != 0
    assert target.read_text() == "previous\n" and _leftovers(tmp_path) == []


# ----------------------------------------------------------------------------- bounded cost
def test_size_is_estimated_before_solving(monkeypatch):
    r = run("analyze", "library:crank-rocker", "--sweep", "0:360:0.0001", "--format", "json")
    assert r.exit_code == 2 and "more than 1 GB" in r.output and "--force" in r.output
    monkeypatch.setattr(streams, "MAX_OUTPUT_BYTES", 10_000)
    r = run("analyze", "library:crank-rocker", "--sweep", "0:360:1", "--format", "csv")
    assert r.exit_code == 2 and "more than 10 kB" in r.output
    r = run("analyze", "library:crank-rocker", "--sweep", "0:360:1", "--format", "csv", "--force")
    assert r.exit_code == 0 and len(r.output.splitlines()) == 362


def test_estimate_is_close_to_the_written_size(tmp_path):
    mech = linkwork.load("library:crank-rocker")
    for fmt in ("csv", "jsonl", "json"):
        out = tmp_path / f"o.{fmt}"
        assert run("analyze", "library:crank-rocker", "--sweep", "0:350:10", "--format", fmt,
                   "-o", str(out)).exit_code == 0
        size = out.stat().st_size
        assert 0.7 * size < streams.estimate_bytes(mech, fmt, 36) < 1.3 * size


def test_long_table_is_refused(monkeypatch):
    monkeypatch.setattr(streams, "MAX_TABLE_ROWS", 20)
    r = run("analyze", "library:crank-rocker", "--sweep", "0:360:10")
    assert r.exit_code == 2 and "too long to read" in r.output


def test_streamed_chunks_equal_one_solution(monkeypatch):
    """Solved 7 samples at a time and written 3 rows at a time, the outputs hold what the library
    gives for the whole sweep at once."""
    monkeypatch.setattr(streams, "CHUNK", 7)
    monkeypatch.setattr(streams, "PIECE", 3)
    monkeypatch.setattr(streams, "PROGRESS_SAMPLES", 1)  # the bar drawn too
    mech = linkwork.load("library:crank-rocker")
    sol = linkwork.solve(mech, np.radians(np.arange(0, 361, 10.0)))
    ref = sol.to_pandas()
    r = run("analyze", "library:crank-rocker", "--sweep", "0:360:10", "--format", "csv")
    assert r.exit_code == 0
    from io import StringIO
    got = pd.read_csv(StringIO(r.stdout))  # the bar is on stderr
    units = ref.attrs["units"]  # the headers carry them: "B.vx [mm/s]"
    assert list(got.columns) == [f"{c} [{units[c]}]" if units[c] else c for c in ref.columns]
    got.columns = list(ref.columns)
    assert len(got) == 37
    num = [c for c in ref.columns if c != "status"]
    np.testing.assert_allclose(got[num].to_numpy(float), ref[num].to_numpy(float), rtol=1e-12, atol=1e-9)
    r = run("analyze", "library:crank-rocker", "--sweep", "0:360:10", "--format", "jsonl")
    lines = [json.loads(x) for x in r.stdout.splitlines()]
    doc = sol.to_document()
    assert len(lines) == 37
    for a, b in zip(lines, doc["samples"]):
        assert a["status"] == b["status"]
        assert a["points"]["B"]["velocity"] == pytest.approx(b["points"]["B"]["velocity"], rel=1e-12)
    r = run("analyze", "library:crank-rocker", "--sweep", "0:360:10", "--format", "json")
    d = json.loads(r.stdout)
    assert d["mechanism"] == doc["mechanism"] and d["units"] == doc["units"] and len(d["samples"]) == 37
    assert d["samples"][5]["links"]["coupler"]["omega"] == pytest.approx(
        doc["samples"][5]["links"]["coupler"]["omega"], rel=1e-12)
