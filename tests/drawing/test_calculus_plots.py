"""Pöschl's plans and the v–s constructions as drawn: what the figures read off agrees with the
engine (and the engine with finite differences, tests/constructions/test_motion_calculus.py)."""

import numpy as np
import pytest
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app
from linkwork.drawing.calculus_plots import plans_figure, vs_steps
from linkwork.errors import InputError


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    import matplotlib.pyplot as plt
    plt.close("all")


@pytest.mark.parametrize("name,point", [("crank-rocker", "C"), ("slider-crank-offset", "B"),
                                        ("jansen-linkage", "F")])
def test_plans_tangents_match_the_engine(name, point):
    mech = linkwork.load(f"library:{name}")
    sol = linkwork.whole_motion(mech, order=3)
    fig, check = plans_figure(mech, point, solution=sol)
    # 1° samples: the drawn tangent (circle through three tips) is within a fraction of a degree
    assert check.tangent_v_vs_acceleration_deg < 0.05
    assert check.tangent_b_vs_jerk_deg < 1.0
    a = sol.point(point).acceleration
    np.testing.assert_allclose(check.acceleration_read, check.acceleration, atol=2e-3 * np.max(np.abs(a)))
    # three panels, each the plan as drawn: the tips are the engine's vectors at the panel's scale
    assert len(fig.axes) == 3
    v = sol.point(point).velocity
    xy = fig.axes[1].get_lines()[0].get_xydata()
    scale = float(fig.axes[1].get_title().split("=")[1].split()[0])
    np.testing.assert_allclose(xy * scale, v, rtol=1e-12, atol=1e-9 * np.max(np.abs(v)))


def test_subnormal_steps_read_the_engine_acceleration():
    mech = linkwork.load("library:slider-crank-centric")
    figs, texts, (got, exact) = vs_steps(mech, "B", "subnormal", at=0.7)
    assert len(figs) == len(texts) == 5
    assert got == pytest.approx(exact, rel=1e-3)
    # every step on a sheet of the same size, so that the drawing does not jump when paging
    assert len({tuple(f.get_size_inches()) for f in figs}) == 1
    assert len({tuple(np.round(f.axes[0].get_position().bounds, 9)) for f in figs}) == 1


def test_time_from_the_vs_line_is_the_engine_time():
    mech = linkwork.load("library:slider-crank-offset")
    figs, texts, (t, exact) = vs_steps(mech, "B", "time", strips=10)
    np.testing.assert_allclose(t, exact, rtol=2e-3, atol=1e-4 * exact[-1])
    assert len({tuple(f.get_size_inches()) for f in figs}) == 1


SLIDER_CRANK = """
name = "slider-crank"
units = { length = "mm" }
[points]
O = [0, 0]
crank_pin = [0, 50]
piston_pin = [193.64916731037084, 0]
[links]
frame = ["O"]
crank = ["O", "crank_pin"]
rod = ["crank_pin", "piston_pin"]
block = ["piston_pin"]
[joints]
O = { type = "revolute", links = ["frame", "crank"] }
crank_pin = { type = "revolute", links = ["crank", "rod"] }
piston_pin = { type = "revolute", links = ["rod", "block"] }
guide = { type = "prismatic", links = ["frame", "block"], axis = [1, 0], point = "piston_pin" }
[driver]
joint = "O"
speed = "1 rad/s"
"""


def test_user_names_are_printed_as_written_in_calculus_figures(tmp_path):
    # `piston_pin` keeps its underscore (mathtext would set "pin" as a subscript of "piston")
    from linkwork.io.files import load_text
    mech = load_text(SLIDER_CRANK)
    figs, _, _ = vs_steps(mech, "piston_pin", "subnormal")
    labels = [t.get_text() for t in figs[-1].axes[0].texts]
    assert r"$v_{\mathrm{piston\_pin}}$" in labels
    figs[-1].savefig(tmp_path / "x.png")  # the label parses and renders
    fig, _ = plans_figure(mech, "crank_pin", solution=linkwork.whole_motion(mech, order=3))
    assert "crank_pin" in fig._suptitle.get_text()
    from linkwork.drawing.plots import motion_plot
    fig = motion_plot(mech, points=["piston_pin"], links=["rod"])
    labels = [ln.get_label() for ax in fig.axes for ln in ax.get_lines()]
    assert r"$v_{\mathrm{piston\_pin},x}$" in labels and r"$\omega_{\mathrm{rod}}$" in labels
    fig.savefig(tmp_path / "y.png")


def test_bad_requests_are_refused():
    mech = linkwork.load("library:slider-crank-centric")
    with pytest.raises(InputError, match="fraction"):
        vs_steps(mech, "B", "subnormal", at=1.5)
    with pytest.raises(InputError, match="'subnormal' or 'time'"):
        vs_steps(mech, "B", "area")
    with pytest.raises(InputError, match="no point"):
        plans_figure(mech, "Z")
    with pytest.raises(InputError, match="order 3"):
        plans_figure(mech, "B", solution=linkwork.whole_motion(mech))


def test_cli_plans_and_steps(tmp_path):
    runner = CliRunner()
    out = tmp_path / "p.png"
    r = runner.invoke(app, ["plot", "library:crank-rocker", "--point", "C", "--plans", "--at", "30", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert "tangent of the v-plan" in r.output and out.stat().st_size > 1000
    out = tmp_path / "s.png"
    r = runner.invoke(app, ["plot", "library:slider-crank-centric", "--point", "B", "--vs", "--construction",
                            "subnormal", "--steps", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert sorted(p.name for p in tmp_path.glob("s-*.png")) == [f"s-0{k}.png" for k in range(1, 6)]
    r = runner.invoke(app, ["plot", "library:slider-crank-centric", "--point", "B", "--steps", "-o", str(out)])
    assert r.exit_code != 0 and "--vs" in r.output
    out = tmp_path / "d.png"
    r = runner.invoke(app, ["plot", "library:slider-crank-centric", "--point", "B", "--diagrams", "--steps",
                            "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert sorted(p.name for p in tmp_path.glob("d-*.png")) == [f"d-0{k}.png" for k in range(1, 6)]


def test_graphical_differentiation_steps_read_the_engine_velocity():
    # the chord's slope is the mean velocity over the chord: at the chord's middle it differs
    # from the engine's v by O(h²) (12 chords over a stroke: under 1 % of the largest speed)
    from linkwork.drawing.calculus_plots import differentiation_steps
    mech = linkwork.load("library:slider-crank-offset")
    figs, texts, (v, exact) = differentiation_steps(mech, "B", chords=12)
    assert len(figs) == 5 and len({tuple(f.get_size_inches()) for f in figs}) == 1
    assert np.max(np.abs(v - exact)) < 0.01 * np.max(np.abs(exact))
    figs, _, (v, exact) = differentiation_steps(mech, "B", chords=48)
    assert np.max(np.abs(v - exact)) < 0.001 * np.max(np.abs(exact))  # finer chords, O(h²)


@pytest.mark.parametrize("strips", [3, 12])
def test_graphical_integration_steps_read_the_engine_velocity(strips):
    """Integration by mean ordinates keeps each strip's area, so the chord polygon's corners are
    v at the strip boundaries whatever the number of strips (unlike the chords of the
    differentiation, which are only O(h²) close): the a–t line integrated from v₀ meets the
    engine's own velocity there, up to the quadrature of the sampled a–t line."""
    from linkwork.drawing.calculus_plots import integration_steps
    mech = linkwork.load("library:slider-crank-offset")
    figs, texts, (v, exact) = integration_steps(mech, "B", strips=strips)
    assert len(figs) == len(texts) == 5 and len({tuple(f.get_size_inches()) for f in figs}) == 1
    assert len(v) == strips + 1
    assert np.max(np.abs(v - exact)) < 1e-4 * np.max(np.abs(exact))


def test_plot_draws_the_integration_step_by_step(tmp_path):
    out = tmp_path / "int.png"
    res = CliRunner().invoke(app, ["plot", "library:slider-crank-offset", "--point", "B", "--diagrams",
                                   "--construction", "integration", "--steps", "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert "mean ordinate" in res.output and (tmp_path / "int-05.png").exists()
    res = CliRunner().invoke(app, ["plot", "library:slider-crank-offset", "--point", "B", "--diagrams",
                                   "--construction", "subnormal", "-o", str(out)])
    assert res.exit_code != 0 and "differentiation or integration" in res.output
