"""The force layer (`draw --show forces`): every pair's reaction drawn at the force scale, read
back from the figure and from the SVG, equals the kinetostatics reaction (the forces module is
checked on its own against the PMKS reference data in tests/forces)."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from typer.testing import CliRunner

from linkwork.cli import app
from linkwork.drawing import scene_figure
from linkwork.drawing.force_layers import draw_forces
from linkwork.drawing.layers import Scene
from linkwork.errors import InputError
from linkwork.forces import kinetostatics
from linkwork.io import load_dynamics
from linkwork.kinematics import solve

NS = "{http://www.w3.org/2000/svg}"
runner = CliRunner()


def _figure(spec="library:crank-rocker", deg=50.0):
    dyn = load_dynamics(spec)
    mech = dyn.mechanism
    sc = Scene(mech, solve(mech, np.radians([[deg]])))
    fig = scene_figure(sc, ["mechanism"])
    fa, scale = draw_forces(fig, sc, dyn)
    # the reference: the analysis on its own, not the one the layer drew
    ref = kinetostatics(dyn, solve(mech, np.radians([[deg]])))
    return sc, fig, scale, ref


@pytest.mark.parametrize("spec,deg", [("library:crank-rocker", 0.0), ("library:crank-rocker", 50.0),
                                      ("library:crank-rocker", 200.0),
                                      ("library:slider-crank-centric", 50.0)])
def test_drawn_reactions_are_the_kinetostatic_ones(spec, deg):
    sc, fig, scale, ref = _figure(spec, deg)
    kF = sc.scales.length.per_mm / scale.per_mm
    arrows = {p.ident[len("force-"):]: p.data for p in fig.prims if p.kind == "arrow"
              and p.ident and p.ident.startswith("force-")}
    assert set(arrows) == set(ref.reactions)
    for name, r in ref.reactions.items():
        tail, head = arrows[name]["tail"], arrows[name]["head"]
        np.testing.assert_allclose(tail, r.point[0], rtol=1e-9, atol=1e-9 * sc.mech.length_scale)
        np.testing.assert_allclose((head - tail) / kF, r.force[0], rtol=1e-9,
                                   atol=1e-9 * np.abs(r.force[0]).max())


def test_reactions_read_back_from_the_svg():
    """Through the figure's scales: paper mm × M_F is newtons. The SVG writes coordinates to
    0.001 mm, so the read-back agrees to that rounding (the 1e-9 check is on the figure)."""
    sc, fig, scale, ref = _figure()
    root = ET.fromstring(fig.to_svg())
    tf = fig.transforms()["mechanism"]
    by_id = {g.get("id"): g for g in root.iter(f"{NS}g")}
    for name, r in ref.reactions.items():
        g = by_id[f"force-{name}"]
        line = g.find(f"{NS}line")
        tail = np.array([float(line.get("x1")), float(line.get("y1"))])
        head = np.array([float(v) for v in g.find(f"{NS}polygon").get("points").split()[0].split(",")])
        # paper (y down) → world
        world_tail = np.array([tf["lo"][0] + (tail[0] - tf["origin"][0]) * tf["per_mm"],
                               tf["hi"][1] - (tail[1] - tf["origin"][1]) * tf["per_mm"]])
        force = (head - tail) * np.array([1.0, -1.0]) * scale.per_mm
        rounding = 1.5e-3  # mm: two coordinates each rounded to 0.0005 mm, and a margin
        np.testing.assert_allclose(world_tail, r.point[0], atol=rounding * tf["per_mm"])
        np.testing.assert_allclose(force, r.force[0], atol=rounding * scale.per_mm)
        # the arrows are long enough on paper for that rounding to be small
        assert np.linalg.norm(r.force[0]) / scale.per_mm > 1.0 or np.linalg.norm(r.force[0]) < \
            0.05 * max(np.linalg.norm(x.force[0]) for x in ref.reactions.values())
    assert by_id["scale-force"] is not None


def test_force_scale_is_nice_and_fits():
    sc, fig, scale, ref = _figure()
    fmax = max(float(r.magnitude[0]) for r in ref.reactions.values())
    longest = fmax / scale.per_mm  # mm of paper
    assert longest <= 0.3 * sc.extent() / sc.scales.length.per_mm * (1 + 1e-12)
    m = scale.per_mm / 10.0 ** np.floor(np.log10(scale.per_mm))
    assert any(np.isclose(m, n) for n in (1.0, 2.0, 2.5, 5.0))
    assert scale.text().startswith("M_F: 1 mm")


def test_driver_torque_is_shown():
    sc, fig, scale, ref = _figure()
    e = float(ref.efforts["O2"][0])
    assert any(t.startswith("driver O2: torque") and f"{e:.6g}" in t for t in fig.legend)
    assert any(p.ident == "effort-O2" for p in fig.prims)


def test_missing_mass_data_is_an_input_error_naming_the_links():
    dyn = load_dynamics("library:double-crank")
    mech = dyn.mechanism
    sc = Scene(mech, solve(mech, np.radians([[30.0]])))
    fig = scene_figure(sc, ["mechanism"])
    with pytest.raises(InputError, match="no mass data for link"):
        draw_forces(fig, sc, dyn)


def test_cli_draw_show_forces(tmp_path):
    out = tmp_path / "f.svg"
    res = runner.invoke(app, ["draw", "library:crank-rocker", "--at", "50", "--show",
                              "mechanism,forces", "-o", str(out)])
    assert res.exit_code == 0, res.output
    root = ET.fromstring(out.read_text())
    ids = {g.get("id") for g in root.iter(f"{NS}g")}
    assert {"force-O2", "force-A", "force-B", "force-O4", "scale-force"} <= ids
    res = runner.invoke(app, ["draw", "library:crank-rocker", "--show", "mechanism,forces",
                              "--construction", "velocity-plan", "--steps", "-o", str(tmp_path / "s.svg")])
    assert res.exit_code == 0, res.output
    assert 'id="force-O4"' in (tmp_path / "s-01.svg").read_text()
    res = runner.invoke(app, ["draw", "library:double-crank", "--show", "forces", "-o",
                              str(tmp_path / "g.svg")])
    assert res.exit_code != 0
    assert "no mass data for link" in res.output and "crank" in res.output
