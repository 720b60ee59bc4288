"""The plots show the engine's numbers: the data of every line is the solution's."""

import numpy as np
import pytest

import linkwork
from linkwork.drawing.plots import motion_plot, path_coordinate, vs_plot


def test_motion_plot_data_is_the_solution():
    mech = linkwork.load("library:crank-rocker")
    sol = linkwork.whole_motion(mech)
    fig = motion_plot(mech, points=["C"], links=["rocker"], quantity="acceleration", solution=sol)
    ax_pts, ax_links = fig.axes
    lines = {ln.get_label(): ln.get_ydata() for ln in ax_pts.get_lines()}
    a = sol.point("C").acceleration
    np.testing.assert_array_equal(lines[r"$a_{\mathrm{C},x}$"], a[:, 0])
    np.testing.assert_array_equal(lines[r"|$a_{\mathrm{C}}$|"], np.linalg.norm(a, axis=1))
    (alpha,) = [ln.get_ydata() for ln in ax_links.get_lines()]
    np.testing.assert_array_equal(alpha, sol.link("rocker").alpha)
    np.testing.assert_allclose(ax_pts.get_lines()[0].get_xdata(), np.degrees(sol.inputs[:, 0]))


def test_vs_diagram_of_a_slider_is_displacement_and_velocity():
    mech = linkwork.load("library:slider-crank-centric")
    sol = linkwork.solve(mech, np.radians(np.arange(0, 361, 1.0)))  # dead centres at 0° and 180°
    fig = vs_plot(mech, "B", solution=sol)
    (line,) = fig.axes[0].get_lines()[:1]
    s, v = line.get_xdata(), line.get_ydata()
    x = sol.point("B").position[:, 0]
    np.testing.assert_allclose(np.ptp(s), 100.0, rtol=1e-9)  # stroke 2r
    np.testing.assert_allclose(abs(v), abs(sol.point("B").velocity[:, 0]), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(s - s.mean(), (x - x.mean()) * np.sign(np.dot(s - s.mean(), x - x.mean())),
                               atol=1e-9)


def test_path_coordinate_of_a_curve_is_arc_length():
    t = np.linspace(0, np.pi, 2001)
    pos = np.stack([np.cos(t), np.sin(t)], 1) * 3.0
    vel = np.stack([-np.sin(t), np.cos(t)], 1) * 3.0
    s, v, straight = path_coordinate(pos, vel)
    assert not straight
    assert s[-1] == pytest.approx(3 * np.pi, rel=1e-6)
    np.testing.assert_allclose(v, 3.0, rtol=1e-9)


def test_plot_needs_something_to_plot():
    with pytest.raises(linkwork.LinkworkError):
        motion_plot(linkwork.load("library:crank-rocker"))


def test_graphical_motion_diagrams_match_the_engine():
    # Pöschl's chord polygons of the s–t and v–t lines against the engine's velocity and
    # tangential acceleration (at the chords' middles; chord error O(h²))
    from linkwork.drawing.plots import graphical_motion
    from linkwork.kinematics import whole_motion

    mech = linkwork.load("library:slider-crank-centric")
    sol = whole_motion(mech)
    fig = graphical_motion(mech, "B", chords=72, solution=sol)
    t = sol.time if sol.time is not None else None
    ax_v, ax_a = fig.axes[1], fig.axes[2]
    (eng_v, chords_v), (eng_a, chords_a) = ax_v.get_lines()[:2], ax_a.get_lines()[:2]
    for eng, ch in ((eng_v, chords_v), (eng_a, chords_a)):
        te, ye = eng.get_data()
        tc, yc = ch.get_data()
        want = np.interp(tc, te, ye)
        assert np.max(np.abs(yc - want)) < 0.02 * np.max(np.abs(ye))
    # the engine's velocity line is the point's velocity along the line of stroke
    v = sol.point("B").velocity
    assert np.allclose(np.abs(eng_v.get_data()[1]), np.linalg.norm(v, axis=1), rtol=1e-9, atol=1e-9)
    assert t is None or len(t) == len(v)


def test_cli_plot_diagrams(tmp_path):
    from typer.testing import CliRunner

    from linkwork.cli import app
    runner = CliRunner()
    out = tmp_path / "d.png"
    r = runner.invoke(app, ["plot", "library:slider-crank-centric", "--point", "B", "--diagrams", "-o", str(out)])
    assert r.exit_code == 0, r.output
    assert out.stat().st_size > 1000
    r = runner.invoke(app, ["plot", "library:slider-crank-centric", "--diagrams", "-o", str(out)])
    assert r.exit_code != 0 and "--diagrams needs --point" in r.output
