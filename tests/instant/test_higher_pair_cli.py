"""`linkwork analyze`, `poles` and `curvature` on mechanism files with higher pairs: a roller, a
knife edge and a flat face on random spline cams, and an ellipse rolling on an ellipse.

What the commands print is checked against geometry the test computes itself from the file's
profiles: the contact point at the roller's radius from its centre, the relative pole on the
common normal, the centre of curvature of the roller centre's path relative to the cam at the
cam's own curvature centre (Euler–Savary through the contact, Pöschl §38), and the centrode
radii of a rolling wheel equal to the ellipses' radii of curvature at the contact (closed form
of the ellipse)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from spline_cams import RHO, ROLL_E1, ROLL_E2, cam_file, rolling_ellipses_file

runner = CliRunner()
SEED = 3


def write(tmp_path, which: str):
    path = tmp_path / f"{which}.toml"
    path.write_text(rolling_ellipses_file() if which == "ellipses" else cam_file(SEED, which))
    return path


def run(*args) -> str:
    res = runner.invoke(app, [str(a) for a in args])
    assert res.exit_code == 0, res.output
    return res.output


def contact(path, at: str) -> list[dict]:
    doc = json.loads(run("analyze", path, "--at", at, "--format", "json"))
    return doc["samples"]


@pytest.mark.parametrize("which", ["roller", "knife", "flat", "ellipses"])
def test_analyze_table_json_csv_and_whole_motion(which, tmp_path):
    path = write(tmp_path, which)
    pair = "T" if which == "ellipses" else "K"
    at = "120,130" if which == "ellipses" else "10,75,200"
    assert "ω" in run("analyze", path, "--at", at)
    csv = run("analyze", path, "--at", at, "--format", "csv").splitlines()
    # headers carry their units, `name [unit]`
    assert f"{pair}.pressure_angle [rad]" in csv[0].split(",") and len(csv) == 1 + len(at.split(","))
    for s in contact(path, at):
        assert s["status"] == "ok" and set(s["joints"][pair]) >= {"point", "normal", "sliding_velocity"}
    whole = json.loads(run("analyze", path, "--format", "json"))
    assert len(whole["samples"]) > 100


def test_analyze_reports_a_contact_on_both_elements(tmp_path):
    path = write(tmp_path, "roller")
    for s in contact(path, "10,75,200,333"):
        X = np.array(s["joints"]["K"]["point"])
        C = np.array(s["points"]["C"]["position"])
        n = np.array(s["joints"]["K"]["normal"])
        np.testing.assert_allclose(C - X, RHO * n, atol=1e-9)


@pytest.mark.parametrize("which", ["roller", "knife", "flat"])
def test_poles_on_a_cam_file(which, tmp_path):
    path = write(tmp_path, which)
    text = run("poles", path, "--at", "30", "--schedule")
    assert "P23 = n(K) ∩ P12P13" in text
    doc = json.loads(run("poles", path, "--at", "30,140,260", "--format", "json"))
    samples = contact(path, "30,140,260")
    for k, s in enumerate(doc["samples"]):
        rows = {r["label"]: r for r in s["poles"]}
        assert max(r["discrepancy"] for r in rows.values()) < 1e-9
        P = np.array([rows["P23"]["pole"]["x"], rows["P23"]["pole"]["y"]])
        X = np.array(samples[k]["joints"]["K"]["point"])
        n = np.array(samples[k]["joints"]["K"]["normal"])
        d = P - X
        assert abs(d[0] * n[1] - d[1] * n[0]) < 1e-9 * 100  # P23 on the common normal


def test_curvature_of_the_roller_path_on_the_cam(tmp_path):
    """The roller's centre describes on the cam the offset of its profile: the centre of
    curvature of that path is the cam's curvature centre at the contact."""
    path = write(tmp_path, "roller")
    mech = linkwork.load(path)
    prof = mech.profiles["cam"]
    at = "25,110,290"
    doc = json.loads(run("curvature", path, "--link", "follower", "--relative-to", "cam",
                         "--point", "C", "--at", at, "--format", "json"))
    for s, a in zip(doc["samples"], contact(path, at)):
        u = a["joints"]["K"]["u"]
        c, d1, d2 = prof.derivatives(np.array(u), 2)
        cr = d1[0] * d2[1] - d1[1] * d2[0]
        centre_local = c + (d1 @ d1) / cr * np.array([-d1[1], d1[0]])  # in the cam's design frame
        th = a["links"]["cam"]["angle"] - np.arctan2(mech.points["A"][1], mech.points["A"][0])
        R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
        want = R @ centre_local
        got = s["curvature_centres"]["C"]["centre"]
        np.testing.assert_allclose([got["x"], got["y"]], want, atol=1e-8 * 100)
    assert "curvature centre of C" in run("curvature", path, "--link", "follower", "--relative-to",
                                          "cam", "--point", "C", "--at", "25")


def test_curvature_of_a_rolling_ellipse_gives_the_profiles_as_centrodes(tmp_path):
    """Rolling without slip: the centrodes of the wheel are the two ellipses; their radii at the
    contact, ρ = (a² sin² t + b² cos² t)^{3/2}/(ab) at the eccentric anomaly t."""
    path = write(tmp_path, "ellipses")
    at = "110,125,140"
    doc = json.loads(run("curvature", path, "--link", "wheel", "--at", at, "--format", "json"))
    for s, a in zip(doc["samples"], contact(path, at)):
        rep = a["joints"]["T"]
        for (ax, bx), t, key in ((ROLL_E1, rep["u"], "fixed_centrode_radius"),
                                 (ROLL_E2, rep["v"], "moving_centrode_radius")):
            rho = (ax**2 * np.sin(t) ** 2 + bx**2 * np.cos(t) ** 2) ** 1.5 / (ax * bx)
            assert abs(abs(s[key]) - rho) < 1e-8 * rho, key
        # the pole of the wheel is the contact point
        np.testing.assert_allclose([s["pole"]["x"], s["pole"]["y"]], rep["point"], atol=1e-9 * 100)
