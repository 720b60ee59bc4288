"""`linkwork poles` and `linkwork curvature`: documented output, seed numbers through the command
line, and one clear message (exit status 2, no traceback) for each user mistake."""

import json

import numpy as np
import pytest
import typer
from typer.testing import CliRunner

from linkwork.cli.instant_cmd import register

import instant_mechanisms as im

runner = CliRunner()


@pytest.fixture(scope="module")
def app():
    a = typer.Typer()

    @a.callback()
    def main() -> None:  # a group, so that commands are addressed by name
        pass

    register(a)
    return a


@pytest.fixture()
def slider_crank(tmp_path):
    f = tmp_path / "sc.toml"
    f.write_text(im.slider_crank(1.0, 3.0, 0.0, np.radians(60)))
    return str(f)


def test_poles_table_with_schedule(app):
    r = runner.invoke(app, ["poles", "library:crank-rocker", "--at", "30,45", "--schedule"])
    assert r.exit_code == 0, r.output
    assert "P13 = P12P23 ∩ P14P34" in r.output and "P24 = P12P14 ∩ P23P34" in r.output
    assert "6 poles" in r.output and "4 pole lines" in r.output
    assert "1 = frame, 2 = crank, 3 = coupler, 4 = rocker" in r.output


def test_poles_json_at_infinity(app, slider_crank):
    r = runner.invoke(app, ["poles", slider_crank, "--at", "60", "--format", "json", "--schedule"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    assert doc["pole_count"] == 6 and doc["pole_line_count"] == 4
    assert doc["unreachable_by_three_pole_theorem"] == []
    assert "P14 = ∞ normal to the guide of guide" in doc["schedule"]
    (s,) = doc["samples"]
    rows = {p["label"]: p for p in s["poles"]}
    slider = rows["P14"]
    assert slider["pole"]["at_infinity"] and abs(slider["pole"]["direction"][1]) == pytest.approx(1)
    assert slider["three_pole_theorem"]["at_infinity"]
    assert rows["P13"]["pole"]["x"] == pytest.approx(3.37228, abs=1e-5)  # digest 001a E.2
    assert max(p["discrepancy"] for p in s["poles"]) < 1e-9
    assert s["pole_lines_max_residual"] < 1e-9
    assert "1e+" not in r.output  # no large numbers standing for infinity


def test_curvature_json_seed_numbers(app, slider_crank):
    r = runner.invoke(app, ["curvature", slider_crank, "--link", "rod", "--point", "B", "--point", "0.5,0.866",
                            "--at", "60", "--format", "json"])
    assert r.exit_code == 0, r.output
    (s,) = json.loads(r.output)["samples"]
    # Rosenauer §26 via the digest's worked case: W₀ = (−64, 0), D = 67.625
    assert s["inflection_pole"] == {"x": pytest.approx(-64.0, abs=1e-6), "y": pytest.approx(0.0, abs=1e-9)}
    assert s["diameter"] == pytest.approx(67.625, abs=1e-3)
    assert s["inflection_circle"]["radius"] == pytest.approx(s["diameter"] / 2)
    assert s["return_circle"]["radius"] == pytest.approx(s["diameter"] / 2)
    assert s["fixed_centrode_radius"] is not None and s["moving_centrode_radius"] is not None
    B = s["curvature_centres"]["B"]
    assert B["centre"]["at_infinity"] and B["radius"] is None  # a straight path
    A = s["curvature_centres"]["0.5,0.866"]
    assert A["centre"]["x"] == pytest.approx(0, abs=1e-3) and A["radius"] == pytest.approx(1, abs=1e-3)
    for key in ("pole", "pole_velocity", "acceleration_pole", "tangential_pole", "bresse_circle"):
        assert s[key] is not None


def test_curvature_table_relative(app):
    r = runner.invoke(app, ["curvature", "library:crank-rocker", "--link", "coupler",
                            "--relative-to", "rocker", "--point", "C", "--at", "30"])
    assert r.exit_code == 0, r.output
    for word in ("coupler relative to rocker", "inflection circle", "return circle", "Bresse circle",
                 "acceleration pole Γ", "R′ (fixed centrode)", "curvature centre of C"):
        assert word in r.output


@pytest.mark.parametrize("args,message", [
    (["curvature", "library:crank-rocker", "--link", "nope", "--at", "30"], "no link 'nope'"),
    (["curvature", "library:crank-rocker", "--link", "coupler", "--relative-to", "coupler"], "relative to itself"),
    (["curvature", "library:crank-rocker", "--link", "coupler", "--point", "Z9"], "--point 'Z9'"),
    (["poles", "library:crank-rocker", "--at", "abc"], "abc"),
    (["poles", "library:no-such-thing"], "no-such-thing"),
    (["poles", "/nonexistent/file.toml"], "no mechanism file"),
])
def test_user_mistakes(app, args, message):
    r = runner.invoke(app, args)
    assert r.exit_code == 2
    out = r.output + (r.stderr if hasattr(r, "stderr") else "")
    assert message in out
    assert "Traceback" not in out
