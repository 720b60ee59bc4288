"""Units in `analyze`'s files: the CSV headers read `name [unit]` and Parquet's metadata
(`linkwork.units`) holds the same unit for each column; the units mean what they say — the
velocity column is the time derivative of the position column in the header's units (finite
differences over the time column), lengths are in the file's unit, angles in radians — and
every column but the codes has one, across the library."""

from __future__ import annotations

import csv
import json
import re

import numpy as np
import pint
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from linkwork.io.library import library_names
from linkwork.kinematics.export import UNITLESS_JOINT_FIELDS, column_units, columns

runner = CliRunner()
ureg = pint.UnitRegistry()


def _csv(path) -> tuple[dict[str, str], dict[str, np.ndarray]]:
    """The CSV's units by column and its numeric columns, read with the csv module."""
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    units, values = {}, {}
    for k, head in enumerate(rows[0]):
        m = re.fullmatch(r"(.+?)(?: \[(.+)\])?", head)
        name, unit = m.group(1), m.group(2) or ""
        units[name] = unit
        try:
            values[name] = np.array([float(r[k]) if r[k] else np.nan for r in rows[1:]])
        except ValueError:
            pass  # the status words
    return units, values


def _write(tmp_path, mech: str, suffix: str, *args: str):
    out = tmp_path / f"m{suffix}"
    r = runner.invoke(app, ["analyze", mech, *args, "-o", str(out)])
    assert r.exit_code == 0, r.output
    return out


@pytest.mark.parametrize("mech", ["library:crank-rocker", "library:radial-roller-cam",
                                  "library:geneva-4", "library:crank-driven-wedge"])
def test_csv_and_parquet_carry_the_same_units(tmp_path, mech):
    pq = pytest.importorskip("pyarrow.parquet")
    units, _ = _csv(_write(tmp_path, mech, ".csv", "--sweep", "0:40:10"))
    t = pq.read_table(_write(tmp_path, mech, ".parquet", "--sweep", "0:40:10"))
    assert json.loads(t.schema.metadata[b"linkwork.units"]) == units
    assert list(units) == t.column_names


def test_rates_are_per_second_in_the_file_unit(tmp_path):
    """At 120 rpm, one degree of crank takes 1/720 s: the central difference of B.x over the
    time column is B.vx, both in the header's units (mm and mm/s); the link's angle difference
    over time is its ω in rad/s."""
    out = _write(tmp_path, "library:crank-rocker", ".csv", "--sweep", "0:20:0.5", "--speed", "120 rpm")
    units, v = _csv(out)
    assert (units["B.x"], units["B.vx"], units["B.ax"]) == ("mm", "mm/s", "mm/s^2")
    assert (units["input"], units["coupler.angle"], units["coupler.omega"]) == ("rad", "rad", "rad/s")
    t = (v["input"] - v["input"][0]) / (4 * np.pi)  # 120 rpm = 4π rad/s
    dt = t[2:] - t[:-2]
    np.testing.assert_allclose(dt, 2 * np.radians(0.5) / (4 * np.pi), rtol=1e-12)
    fd = (v["B.x"][2:] - v["B.x"][:-2]) / dt
    scale = np.abs(v["B.vx"]).max()
    np.testing.assert_allclose(fd, v["B.vx"][1:-1], atol=1e-3 * scale)
    fd = (v["B.vx"][2:] - v["B.vx"][:-2]) / dt
    np.testing.assert_allclose(fd, v["B.ax"][1:-1], atol=2e-3 * np.abs(v["B.ax"]).max())
    fd = (v["coupler.angle"][2:] - v["coupler.angle"][:-2]) / dt
    np.testing.assert_allclose(fd, v["coupler.omega"][1:-1], atol=1e-3 * np.abs(v["coupler.omega"]).max())


def test_lengths_in_the_file_unit_and_slider_inputs_in_length(tmp_path):
    """A file drawn in cm writes cm; a prismatic driver's input is a length (its slide)."""
    text = linkwork.io.library.library_text("crank-rocker")
    text = text.replace('units = { length = "mm" }', 'units = { length = "cm" }')
    assert 'length = "cm"' in text
    f = tmp_path / "cm.toml"
    f.write_text(text)
    units, _ = _csv(_write(tmp_path, str(f), ".csv", "--at", "30"))
    assert units["A.x"] == "cm" and units["A.vx"] == "cm/s" and units["input"] == "rad"
    units, _ = _csv(_write(tmp_path, "library:crank-slider", ".csv", "--at", "O2=30,slide=2"))
    assert units["input.O2"] == "rad" and units["input.slide"] == "mm"  # its slide
    units, _ = _csv(_write(tmp_path, "library:kley-governor", ".csv"))
    assert units["input"] == "mm"  # the sleeve's slide


@pytest.mark.parametrize("name", library_names())
def test_every_column_but_the_codes_has_a_unit_pint_reads(name):
    mech = linkwork.load(f"library:{name}")
    try:
        sol = linkwork.solve(mech)
    except linkwork.errors.LinkworkError:
        pytest.skip("does not solve at its design input")
    units = column_units(sol)
    assert list(units) == list(columns(sol))
    for col, unit in units.items():
        if col == "status" or col.split(".")[-1] in UNITLESS_JOINT_FIELDS:
            assert unit == "", col
            continue
        assert unit, f"{col} has no unit"
        q = ureg.parse_expression(unit)
        field = col.split(".")[-1] if col.split(".")[-1] not in "xy" or col.count(".") < 2 \
            else col.split(".")[-2]
        if field in ("x", "y", "slide"):
            assert q.dimensionality == ureg(mech.length_unit).dimensionality, col
        elif field in ("vx", "vy", "velocity", "sliding_velocity"):
            assert q.dimensionality == ureg("m/s").dimensionality, col
        elif field in ("ax", "ay", "acceleration", "coriolis"):
            assert q.dimensionality == ureg("m/s^2").dimensionality, col
        elif field.startswith(("angle", "omega", "alpha")):
            assert unit.startswith("rad"), col


def test_forces_csv_carries_units_that_make_the_power_balance(tmp_path):
    """`linkwork forces -o x.csv`: every header has a unit pint reads (or none, for codes), and
    the units are the right ones: the driver's power is its torque times the crank's angular
    velocity (60 rpm), in the units the headers state."""
    out = tmp_path / "f.csv"
    r = runner.invoke(app, ["forces", "library:crank-rocker", "--sweep", "0:360:30", "-o", str(out)])
    assert r.exit_code == 0, r.output
    units, values = _csv(out)
    for name, unit in units.items():
        if unit:
            ureg.Unit(unit)  # raises on a unit pint does not know
        else:
            assert name in ("status", "solved"), name
    mech = linkwork.load("library:crank-rocker")
    driver = mech.drivers[0].joint
    torque = values[f"{driver}.torque"] * ureg.Unit(units[f"{driver}.torque"])
    omega = 2 * np.pi * ureg.Unit("rad/s")  # 60 rpm
    power = values["driver_power"] * ureg.Unit(units["driver_power"])
    np.testing.assert_allclose((torque * omega).to(power.units).magnitude, power.magnitude,
                               rtol=1e-9, atol=1e-12)
    assert ureg.Unit(units["O2.fx"]).dimensionality == ureg.Unit("N").dimensionality
    assert units["input"] == "rad" and units["kinetic_energy"] == "J"
