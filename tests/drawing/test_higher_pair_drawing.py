"""Drawings of mechanisms with higher pairs: the profiles carried by their links, the roller and
the flat face (mechanism layer), the contact and its common normal (`contact`), the equivalent
linkage dashed (`equivalent`), from the API and from `linkwork draw` on mechanism files.

The drawn geometry is checked against the model, not against itself: the cam outline turned
back by the cam's angle lies on the profile, the roller circle about the roller's centre, the
contact point on both elements."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from higher_pair_mechanisms import eccentric
from linkwork.cli import app
from linkwork.drawing import LAYERS, Scene, scene_figure
from linkwork.drawing.higher_layers import outlines
from spline_cams import RHO, cam_file, cam_mechanism, rolling_ellipses, rolling_ellipses_file, spline_cam

runner = CliRunner()


def ids(svg: str) -> dict[str, ET.Element]:
    root = ET.fromstring(svg.encode("utf-8"))
    return {e.get("id"): e for e in root.iter() if e.get("id")}


def scene(mech, at_deg: float) -> Scene:
    x0 = mech.driver_input_at_design(mech.drivers[0])
    return Scene(mech, linkwork.solve(mech, [x0 + np.radians(at_deg)]))


def test_cam_outline_and_roller_are_carried_by_their_links():
    prof = spline_cam(0)
    mech = cam_mechanism(prof, "roller")
    sc = scene(mech, 70.0)
    drawn = dict((k, xy) for k, xy, _ in outlines(sc))
    cam = drawn["profile-K-cam"]
    th = sc.theta("cam")
    back = cam @ np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])  # turned by −θ
    foot = prof.derivatives(prof.nearest(back), 0)[0]
    np.testing.assert_allclose(back, foot, atol=1e-9 * mech.length_scale)
    roller = drawn["roller-K"]
    np.testing.assert_allclose(np.hypot(*(roller - sc.pos("C")).T), RHO, atol=1e-12)
    # the contact lies on the drawn cam (to the polyline's chord height) and on the roller
    X = sc.sol.joint("K")["point"][0]
    assert np.min(np.hypot(*(cam - X).T)) < 0.5 * prof.domain[1] / 720
    assert abs(np.hypot(*(X - sc.pos("C"))) - RHO) < 1e-9


@pytest.mark.parametrize("build,kind", [(lambda: cam_mechanism(spline_cam(1), "roller"), "coupler"),
                                        (lambda: eccentric("flat"), "slider"),
                                        (rolling_ellipses, "coupler")], ids=["roller", "flat", "rolling"])
def test_contact_and_equivalent_layers(build, kind):
    mech = build()
    sc = scene(mech, 10.0)
    fig = scene_figure(sc, ["mechanism", "contact", "equivalent"])
    svg = fig.to_svg()
    found = ids(svg)
    name = next(j.name for j in mech.joints if j.kind in ("cam", "rolling"))
    for key in (f"normal-{name}", f"contact-{name}", f"equivalent-{kind}-{name}", "layer-contact",
                "layer-equivalent"):
        assert key in found, key
    assert any(k.startswith(f"profile-{name}-") for k in found)
    # the substitute is dashed
    assert "stroke-dasharray" in ET.tostring(found["layer-equivalent"]).decode()
    assert any("equivalent linkage" in n for n in fig.legend)
    if mech.name == "eccentric, flat":
        assert f"face-{name}" in found and any("Scotch yoke" in n for n in fig.legend)
    if mech.name == "rolling ellipses":
        assert f"equivalent-circle-{name}-1" in found and f"equivalent-circle-{name}-2" in found


def test_layers_on_a_mechanism_without_higher_pairs_say_so():
    mech = linkwork.load("library:crank-rocker")
    sc = Scene(mech, linkwork.solve(mech, [0.5]))
    fig = scene_figure(sc, ["mechanism", "contact", "equivalent"])
    assert "contact: the mechanism has no higher pair" in fig.legend
    assert "contact" in LAYERS and "equivalent" in LAYERS


@pytest.mark.parametrize("which", ["roller", "flat", "knife", "ellipses"])
def test_draw_command_on_cam_files(which, tmp_path):
    path = tmp_path / f"{which}.toml"
    path.write_text(rolling_ellipses_file() if which == "ellipses" else cam_file(2, which))
    out = tmp_path / f"{which}.svg"
    every = [x for x in LAYERS if x != "construction"]
    res = runner.invoke(app, ["draw", str(path), "--at", "125" if which == "ellipses" else "40",
                              "--show", ",".join(every), "-o", str(out)])
    assert res.exit_code == 0, res.output
    found = ids(out.read_text())
    assert "layer-equivalent" in found and "layer-contact" in found
    assert any(k.startswith("profile-") for k in found)
    png = tmp_path / f"{which}.png"
    res = runner.invoke(app, ["draw", str(path), "--show", "mechanism,equivalent", "-o", str(png)])
    assert res.exit_code == 0 and png.stat().st_size > 1000, res.output


@pytest.mark.parametrize("name", ["radial-roller-cam", "flat-faced-cam", "oscillating-roller-cam",
                                  "elliptical-gears", "rolling-lever-valve-gear", "poeschl-arc-cam"])
def test_library_cams_draw_every_layer(name):
    mech = linkwork.load(f"library:{name}")
    sc = scene(mech, 37.0)
    fig = scene_figure(sc, [x for x in LAYERS if x != "construction"])
    found = ids(fig.to_svg())
    pair = next(j.name for j in mech.joints if j.kind in ("cam", "rolling"))
    assert f"normal-{pair}" in found and any(k.startswith(f"profile-{pair}-") for k in found)
    assert any(k.startswith(f"equivalent-") for k in found)
