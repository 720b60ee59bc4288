"""`linkwork forces`: the JSON and CSV outputs carry the kinetostatics (checked against the
reference and closed forms elsewhere: here against the library's Stephenson III reference
torque and the static slider-crank's virtual work), the table, the plot, and user mistakes
as one message with exit status 2."""

import csv
import io
import json

import numpy as np
import pytest
from typer.testing import CliRunner

import pmks_cases as P
from linkwork.cli import app

runner = CliRunner()


def run(*args):
    return runner.invoke(app, list(args))


def test_json_matches_the_reference_torque():
    ref = P.table(P.ROOT / "stephenson_iii_example_2" / "newton_gravity.csv")
    # the first three reference samples, in degrees, turning counter-clockwise at 10 rpm
    at = ",".join(repr(float(np.degrees(a))) for a in ref["input_angle_rad"][:3])
    r = run("forces", "library:pmks-stephenson-iii", "--at", at, "--format", "json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    assert doc["inertia"] is True and doc["samples"] == 3
    np.testing.assert_allclose(doc["columns"]["A.torque"], ref["input_torque"][:3], rtol=1e-9)
    assert max(doc["columns"]["power_residual_relative"]) < 1e-12


def test_static_csv_of_the_slider_crank(tmp_path):
    out = tmp_path / "f.csv"
    r = run("forces", "library:slider-crank-centric", "--sweep", "10:350:20", "--static", "-o", str(out))
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(io.StringIO(out.read_text())))
    assert len(rows) == 18
    # statics of the file's masses alone, without gravity or loads: nothing to hold
    assert all(float(row["O.torque [N*m]"]) == 0 for row in rows)
    assert {"guide.normal [N]", "guide.couple [N*m]", "B.fx [N]", "frame.moment [N*m]"} <= set(rows[0])


def test_table_and_plot(tmp_path):
    png = tmp_path / "torque.png"
    r = run("forces", "library:crank-rocker", "--plot", str(png))
    assert r.exit_code == 0, r.output
    assert "samples solved: 361 of 361" in r.output
    assert png.read_bytes()[:4] == b"\x89PNG"
    r = run("forces", "library:crank-rocker", "--at", "30")
    assert r.exit_code == 0 and "coupler → rocker" in r.output and "by virtual work" in r.output


def test_missing_mass_data_is_one_message():
    r = run("forces", "library:double-rocker")
    assert r.exit_code == 2
    assert "no mass data for link" in r.output and "Traceback" not in r.output
    r = run("forces", "library:double-rocker", "--static")
    assert r.exit_code == 0, r.output


def test_bad_plot_suffix():
    r = run("forces", "library:crank-rocker", "--at", "10", "--plot", "x.txt")
    assert r.exit_code == 2 and ".png" in r.output


def test_flywheel_of_the_free_slider_crank():
    # without loads the torque that keeps ω constant stores and returns the kinetic energy
    # ½·J(φ)·ω²: its work swings by ½·ω²·(J_max − J_min), and its mean is zero
    r = run("forces", "library:slider-crank-centric", "--flywheel", "0.02", "--format", "json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    fw, J = doc["flywheel"], np.array(doc["columns"]["reduced_inertia"])
    w = 120 * 2 * np.pi / 60
    assert fw["mean_speed"] == pytest.approx(w, rel=1e-12)
    assert abs(fw["mean_torque"]) < 1e-12
    assert fw["energy_fluctuation"] == pytest.approx(0.5 * w**2 * (J.max() - J.min()), rel=1e-3)
    assert fw["inertia"] == pytest.approx(fw["energy_fluctuation"] / (0.02 * w**2), rel=1e-12)
    r = run("forces", "library:slider-crank-centric", "--at", "30", "--flywheel", "0.02")
    assert r.exit_code == 2 and "whole motion" in r.output
