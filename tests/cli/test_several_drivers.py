"""`--at`, `--sweep` and `--speed` for mechanisms with several drivers: one value list per named
driver (`--at O2=30,60 --at O5=80,70`), lock-step samples, units per driver. The numbers the
command line reports are checked against closed forms and against the Python API (`solve`),
which is given the inputs directly, without any of the command line's parsing."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from mechanism_texts import joint, mechanism_text, revolute, two_crank_five_bar_text

runner = CliRunner()

# Two cranks on the frame, O2 (|O2A| = 10) and O5 (|O5B| = 15), joined by the dyad A–P–B:
# two freedoms (3·4 − 2·5), both driven.
FIVE_BAR = two_crank_five_bar_text(units="mm")


def crank_and_slider_text(unit: str) -> str:
    """A crank (revolute driver O2, |O2A| = 10) and a block sliding on the frame along x
    (prismatic driver `slide`, input = displacement of S from its design position), joined by
    A–P–S; lengths in `unit`."""
    return mechanism_text(
        name="crank and slider driving a dyad", units=unit,
        points={"O2": (0, 0), "A": (0, 10), "P": (25, 30), "S": (40, 0)},
        links={"frame": ["O2"], "crank": ["O2", "A"], "upper": ["A", "P"], "rod": ["P", "S"],
               "block": ["S"]},
        joints=[revolute("O2", "frame", "crank"), revolute("A", "crank", "upper"),
                revolute("P", "upper", "rod"), revolute("S", "rod", "block"),
                joint("slide", "prismatic", "frame", "block", axis=[1, 0], point="S")],
        driver=("O2", "slide"), speed=("1 rad/s", 3))


@pytest.fixture
def five_bar(tmp_path):
    f = tmp_path / "five-bar.toml"
    f.write_text(FIVE_BAR)
    return str(f)


def crank_and_slider(tmp_path, unit="mm"):
    f = tmp_path / f"crank-slider-{unit}.toml"
    f.write_text(crank_and_slider_text(unit))
    return str(f)


def run(*args):
    return runner.invoke(app, [str(a) for a in args])


def inputs(doc):
    return np.array([s["input"] for s in doc["samples"]])


def analyze_json(*args):
    r = run("analyze", *args, "--format", "json")
    assert r.exit_code == 0, r.output
    return json.loads(r.output)


def dyad_point(A, B, ra, rb):
    """The point at distance ra from A and rb from B, to the left of A→B (the design branch of
    both test mechanisms: the cross product (B − A) × (P − A) is positive at design)."""
    A, B = np.asarray(A, float), np.asarray(B, float)
    d = np.linalg.norm(B - A)
    u = (B - A) / d
    a = (ra**2 - rb**2 + d**2) / (2 * d)
    h = np.sqrt(ra**2 - a**2)
    return A + a * u + h * np.array([-u[1], u[0]])


def five_bar_P(phi2, phi5):
    A = 10 * np.array([np.cos(phi2), np.sin(phi2)])
    B = np.array([40, 0]) + 15 * np.array([np.cos(phi5), np.sin(phi5)])
    return dyad_point(A, B, np.hypot(20, 20), np.hypot(20, 15))


def assert_same_as_api(doc, sol):
    """Every point's position, velocity and acceleration and every link's ω, α of the command's
    JSON equal the API's solution (sample by sample)."""
    assert len(doc["samples"]) == len(sol)
    for n, s in enumerate(doc["samples"]):
        assert s["input"] == pytest.approx(sol.inputs[n], abs=1e-12)
        for p, m in s["points"].items():
            ref = sol.point(p)
            assert m["position"] == pytest.approx(ref.position[n], abs=1e-9)
            assert m["velocity"] == pytest.approx(ref.velocity[n], abs=1e-9)
            assert m["acceleration"] == pytest.approx(ref.acceleration[n], abs=1e-9)
        for ln, m in s["links"].items():
            assert m["omega"] == pytest.approx(sol.link(ln).omega[n], abs=1e-9)
            assert m["alpha"] == pytest.approx(sol.link(ln).alpha[n], abs=1e-9)


# ---------------------------------------------------------------------------- --at
def test_at_one_list_per_driver_matches_closed_form_and_api(five_bar):
    doc = analyze_json(five_bar, "--at", "O2=30,60", "--at", "O5=80,70")
    assert doc["drivers"] == ["O2", "O5"]
    phi = np.radians([[30, 80], [60, 70]])
    for s, (p2, p5) in zip(doc["samples"], phi):
        assert s["status"] == "ok"
        assert s["input"] == pytest.approx([p2, p5])
        assert s["points"]["A"]["position"] == pytest.approx(10 * np.array([np.cos(p2), np.sin(p2)]))
        assert s["points"]["B"]["position"] == pytest.approx([40 + 15 * np.cos(p5), 15 * np.sin(p5)])
        assert s["points"]["P"]["position"] == pytest.approx(five_bar_P(p2, p5), abs=1e-9)
        # each crank turns at its file's speed
        assert s["links"]["crank2"]["omega"] == pytest.approx(2.0)
        assert s["links"]["crank5"]["omega"] == pytest.approx(-1.0)
    mech = linkwork.load(five_bar)
    assert_same_as_api(doc, linkwork.solve(mech, phi))


@pytest.mark.parametrize("at", [
    ["O2=30,60,O5=80,70"],                  # one option, a name starts each driver's list
    ["O2=30,O5=80", "O2=60,O5=70"],         # one option per sample
    ["O5=80,70", "O2=30,60"],               # drivers in any order
    ["O2=30deg,1.0471975511965976rad", "O5=80,70°"],
])
def test_at_spellings_are_equivalent(five_bar, at):
    ref = analyze_json(five_bar, "--at", "O2=30,60", "--at", "O5=80,70")
    args = [x for a in at for x in ("--at", a)]
    doc = analyze_json(five_bar, *args)
    assert inputs(doc) == pytest.approx(inputs(ref))
    assert doc["samples"][1]["points"]["P"]["position"] == pytest.approx(
        ref["samples"][1]["points"]["P"]["position"])


def test_a_driver_with_one_value_is_held(five_bar):
    doc = analyze_json(five_bar, "--at", "O2=30,60,90", "--at", "O5=80")
    assert inputs(doc) == pytest.approx(np.radians([[30, 80], [60, 80], [90, 80]]))


def test_units_per_driver_revolute_degrees_prismatic_file_unit(tmp_path):
    # the file is in cm: a bare slide value is in cm, 5mm is converted; the crank takes degrees
    # by default and radians when written
    f = crank_and_slider(tmp_path, "cm")
    doc = analyze_json(f, "--at", "O2=1.2rad,90", "--at", "slide=5mm,2")
    assert inputs(doc) == pytest.approx(np.array([[1.2, 0.5], [np.pi / 2, 2.0]]))
    mech = linkwork.load(f)
    for s, (phi, x) in zip(doc["samples"], [(1.2, 0.5), (np.pi / 2, 2.0)]):
        A = 10 * np.array([np.cos(phi), np.sin(phi)])
        S = np.array([40 + x, 0])
        assert s["points"]["S"]["position"] == pytest.approx(S)
        assert s["points"]["P"]["position"] == pytest.approx(
            dyad_point(A, S, np.hypot(25, 20), np.hypot(15, 30)), abs=1e-9)
        # the block slides at the file's 3 cm/s, the crank turns at 1 rad/s
        assert s["points"]["S"]["velocity"] == pytest.approx([3, 0])
        assert s["links"]["crank"]["omega"] == pytest.approx(1.0)
    assert_same_as_api(doc, linkwork.solve(mech, [[1.2, 0.5], [np.pi / 2, 2.0]]))


def test_times_drive_every_driver_through_its_law(tmp_path):
    f = crank_and_slider(tmp_path)
    doc = analyze_json(f, "--at", "0.5s,1s")
    assert [s["time"] for s in doc["samples"]] == pytest.approx([0.5, 1.0])
    assert_same_as_api(doc, linkwork.solve(linkwork.load(f), times=[0.5, 1.0]))


# ---------------------------------------------------------------------------- --sweep
def test_sweeps_run_in_lock_step(five_bar):
    doc = analyze_json(five_bar, "--sweep", "O2=0:90:30", "--sweep", "O5=90:60:-10")
    phi = np.radians([[0, 90], [30, 80], [60, 70], [90, 60]])
    assert inputs(doc) == pytest.approx(phi)
    for s, (p2, p5) in zip(doc["samples"], phi):
        assert s["points"]["P"]["position"] == pytest.approx(five_bar_P(p2, p5), abs=1e-9)
    assert_same_as_api(doc, linkwork.solve(linkwork.load(five_bar), phi))


def test_sweep_one_driver_and_hold_the_other(tmp_path):
    f = crank_and_slider(tmp_path)
    out = tmp_path / "m.csv"
    r = run("analyze", f, "--sweep", "slide=0:1cm:2.5", "--at", "O2=90", "--format", "csv", "-o", out)
    assert r.exit_code == 0, r.output
    import pandas as pd
    df = pd.read_csv(out)
    assert list(df["input.slide [mm]"]) == pytest.approx([0, 2.5, 5, 7.5, 10])
    assert list(df["input.O2 [rad]"]) == pytest.approx([np.pi / 2] * 5)
    assert list(df["S.x [mm]"]) == pytest.approx([40, 42.5, 45, 47.5, 50])


def test_tables_name_the_drivers(five_bar, tmp_path):
    r = run("analyze", five_bar, "--at", "O2=30,O5=80")
    assert r.exit_code == 0, r.output
    assert "input O2 30.000°, O5 80.000°" in r.output
    r = run("analyze", crank_and_slider(tmp_path), "--sweep", "O2=0:40:10", "--at", "slide=2")
    assert r.exit_code == 0, r.output
    assert "input O2" in r.output and "input slide" in r.output and "2 mm" in r.output


# ---------------------------------------------------------------------------- --speed
def test_speed_per_driver_and_the_others_keep_the_file(tmp_path):
    f = crank_and_slider(tmp_path, "cm")
    mech = linkwork.load(f)
    at = ("--at", "O2=30,120", "--at", "slide=1")
    inputs = [[np.radians(30), 1.0], [np.radians(120), 1.0]]
    doc = analyze_json(f, *at, "--speed", "O2=60rpm", "--speed", "slide=20mm/s")
    assert doc["samples"][0]["links"]["crank"]["omega"] == pytest.approx(2 * np.pi)
    assert doc["samples"][0]["points"]["S"]["velocity"] == pytest.approx([2.0, 0])
    assert_same_as_api(doc, linkwork.solve(mech, inputs, velocities=[[2 * np.pi, 2.0]] * 2))
    # only the slide's speed given (a bare number: cm/s): the crank keeps its 1 rad/s
    doc = analyze_json(f, *at, "--speed", "slide=-4")
    assert_same_as_api(doc, linkwork.solve(mech, inputs, velocities=[[1.0, -4.0]] * 2))


# ---------------------------------------------------------------------------- one driver
def test_one_driver_may_be_named_and_unnamed_forms_are_unchanged():
    a = analyze_json("library:crank-rocker", "--at", "O2=30,45")
    b = analyze_json("library:crank-rocker", "--at", "30,45")
    assert inputs(a) == pytest.approx(np.radians([30, 45]))
    assert a["samples"] == b["samples"]
    c = analyze_json("library:crank-rocker", "--sweep", "O2=30:45:15", "--speed", "O2=120rpm")
    d = analyze_json("library:crank-rocker", "--sweep", "30:45:15", "--speed", "120 rpm")
    assert c["samples"] == d["samples"] and c["samples"][0]["input"] == pytest.approx(np.radians(30))


# ---------------------------------------------------------------------------- other commands
def test_poles_and_draw_take_the_same_syntax(five_bar, tmp_path):
    r = run("poles", five_bar, "--at", "O2=30", "--at", "O5=80", "--format", "json")
    assert r.exit_code == 0, r.output
    assert "O2" in run("poles", five_bar, "--at", "O2=30,O5=80").output
    out = tmp_path / "five.svg"
    r = run("draw", five_bar, "--at", "O2=30", "--at", "O5=80", "-o", out)
    assert r.exit_code == 0, r.output
    assert out.read_text().startswith("<")


# ---------------------------------------------------------------------------- mistakes
FIVE = "FIVE"
MIXED = "MIXED"
ONE = "library:crank-rocker"


@pytest.mark.parametrize("mech, args, message", [
    (FIVE, ["--at", "O3=30", "--at", "O5=10"], "--at O3: mechanism 'five-bar with two cranks' has no driver 'O3'; the drivers are O2, O5"),
    (FIVE, ["--at", "A=30", "--at", "O5=10"], "--at A: joint 'A' is not a driver; the drivers are O2, O5"),
    (FIVE, ["--sweep", "O9=0:10:1", "--at", "O5=10"], "--sweep O9: mechanism 'five-bar with two cranks' has no driver 'O9'"),
    (FIVE, ["--at", "=30"], "--at: a value has '=' but no driver name before it"),
    (FIVE, ["--at", "O2=30"], "no value for driver O5: every driver needs its values"),
    (FIVE, ["--at", "O2=30,60", "--at", "O5=1,2,3"], "need the same number of values: O2 has 2, O5 has 3"),
    (FIVE, ["--sweep", "O2=0:10:1", "--sweep", "O5=0:20:1"], "need the same number of values: O2 has 11, O5 has 21"),
    (FIVE, ["--at", "O2=30", "--at", "O5=10mm"], "--at O5: '10mm': driver O5 is revolute, give an angle"),
    (MIXED, ["--at", "slide=5deg", "--at", "O2=1"], "--at slide: '5deg': driver slide is prismatic, give a length (default mm)"),
    (MIXED, ["--sweep", "slide=0:1kg:1", "--at", "O2=1"], "--sweep slide: '1kg': driver slide is prismatic"),
    (FIVE, ["--at", "O2=ten", "--at", "O5=1"], "--at O2: cannot read"),
    (FIVE, ["--at", "O2=", "--at", "O5=1"], "--at O2: empty value for driver O2"),
    (FIVE, ["--at", "30"], "has 2 drivers (O2, O5): name the driver of each value"),
    (FIVE, ["--sweep", "0:10:1"], "has 2 drivers (O2, O5): name the driver of each value"),
    (FIVE, ["--at", "10mm"], "has 2 drivers (O2, O5): name the driver of each value"),
    (FIVE, ["--at", "0.5s,10"], "has 2 drivers (O2, O5): name the driver of each value"),
    (FIVE, ["--at", "30", "--at", "O5=3"], "name the driver of every value or of none"),
    (FIVE, ["--at", "O2=0.5s", "--at", "O5=1"], "--at O2: a time drives every driver at once through its law"),
    (FIVE, ["--sweep", "O2=0:10:1", "--at", "O2=40", "--at", "O5=1"], "driver O2 is given twice"),
    (FIVE, ["--sweep", "O2=0:10:1,20:30:1", "--at", "O5=1"], "--sweep O2: one START:STOP:STEP per driver"),
    (FIVE, ["--sweep", "O2=0:10", "--at", "O5=1"], "--sweep O2 '0:10': write START:STOP:STEP"),
    (FIVE, ["--sweep", "O2=0:10:0", "--at", "O5=1"], "--sweep O2: the step must not be zero"),
    (FIVE, ["--sweep", "O2=0:10:-1", "--at", "O5=1"], "--sweep O2: the step goes away from STOP"),
    (FIVE, ["--sweep", "O2=0s:1s:0.5s", "--at", "O5=1"], "--sweep O2: a time drives every driver"),
    (FIVE, ["--at", "O2=1,O5=2", "--speed", "3rpm"], "has 2 drivers (O2, O5): name the driver of each speed"),
    (FIVE, ["--at", "O2=1,O5=2", "--speed", "O9=3rpm"], "--speed O9: mechanism 'five-bar with two cranks' has no driver 'O9'"),
    (FIVE, ["--at", "O2=1,O5=2", "--speed", "O2=3kg"], "speed of driver O2 '3kg' has unit 'kilogram'"),
    (MIXED, ["--at", "O2=1,slide=2", "--speed", "slide=3rpm"], "speed of driver slide '3rpm' has unit 'revolutions_per_minute', which cannot be converted to 'mm/s'"),
    (FIVE, ["--at", "O2=1,O5=2", "--speed", "O2=1,O2=2"], "--speed O2: driver O2 is given twice"),
    (FIVE, ["--at", "O2=1,O5=2", "--speed", "1,O2=2"], "--speed: name the driver of every speed or of none"),
    (FIVE, ["--at", "0.5s", "--speed", "O2=1"], "--speed sets the input speed at input values"),
    (FIVE, ["--speed", "O2=1"], "--speed with several drivers needs --at or --sweep"),
    (ONE, ["--sweep", "0:10:1", "--sweep", "20:30:1"], "--sweep is given more than once"),
    (ONE, ["--speed", "1", "--speed", "2"], "--speed takes one speed"),
    (ONE, ["--at", "0.5s", "--speed", "1"], "--speed sets the input speed at input values"),
    (ONE, ["--at", "O4=30"], "--at O4: joint 'O4' is not a driver; the drivers are O2"),
])
def test_mistakes_name_the_driver_and_the_reason(five_bar, tmp_path, mech, args, message):
    path = {FIVE: five_bar, MIXED: crank_and_slider(tmp_path), ONE: ONE}[mech]
    r = run("analyze", path, *args)
    assert r.exit_code == 2, r.output
    assert message in r.output
    assert "Traceback" not in r.output and isinstance(r.exception, SystemExit)


def test_draw_and_poles_mistakes(five_bar, tmp_path):
    r = run("draw", five_bar, "--at", "O2=30,40", "--at", "O5=80", "-o", tmp_path / "x.svg")
    assert r.exit_code == 2 and "draw takes one position, got 2" in r.output
    r = run("poles", five_bar, "--at", "O2=30")
    assert r.exit_code == 2 and "no value for driver O5" in r.output
