"""The drawing layer's caches and vectorised writing change nothing: a drawing is the same text
drawn cold (a fresh process), twice in a row, or after other mechanisms; a drag frame (a point
moved) is drawn where the point now is; the vectorised pieces agree with the plain one-by-one
versions they replace."""

import json
import re
import subprocess
import sys

import numpy as np
import pytest

import linkwork
from linkwork.drawing import Scene, scene_figure
from linkwork.drawing import symbols as sym
from linkwork.drawing.instant_layers import schedule_of
from linkwork.drawing.svg import _inside_counts
from linkwork.instant import pole_schedule
from linkwork.kinematics import solve_at
from linkwork.web.sources import moved

#: (library mechanism, layers), drawn as the workbench draws a drag frame (no whole motion)
CASES = [("crank-rocker", ["mechanism"]),
         ("crank-rocker", ["mechanism", "velocities", "accelerations", "poles", "pole-lines"]),
         ("heusinger-valve-gear", ["mechanism", "poles", "inflection", "return", "bresse", "gamma"]),
         ("slider-crank-offset", ["mechanism", "velocities", "pole-lines"])]
OTHERS = ["jansen-linkage", "geneva-4", "radial-roller-cam", "watt-i-six-bar"]


def frame(mech, layers, motion=False):
    sc = Scene(mech, solve_at(mech))
    if not motion:
        sc.motion = None
    return scene_figure(sc, layers).svg_and_transforms()


COLD = """
import json, sys, warnings
warnings.simplefilter("ignore")
sys.path.insert(0, {tests!r})
from test_drawing_caches import CASES, frame
import linkwork
print(json.dumps([frame(linkwork.load("library:" + name), layers) for name, layers in CASES]))
"""


@pytest.fixture(scope="module")
def cold():
    """Each case's (SVG, transforms) drawn first thing in a fresh process: every cache empty."""
    from pathlib import Path
    code = COLD.format(tests=str(Path(__file__).parent))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return [(svg, tfs) for svg, tfs in json.loads(out.stdout)]


def test_a_drawing_is_the_same_cold_warm_and_after_other_mechanisms(cold):
    for (name, layers), (svg, tfs) in zip(CASES, cold):
        mech = linkwork.load(f"library:{name}")
        first = frame(mech, layers)
        again = frame(mech, layers)
        for other in OTHERS:  # other labels, styles, structures through the caches
            frame(linkwork.load(f"library:{other}"), ["mechanism", "poles", "pole-lines"])
        after = frame(linkwork.load(f"library:{name}"), layers)
        for got in (first, again, after):
            assert got[0] == svg, f"{name} {layers}: the SVG differs from the cold drawing"
            assert json.loads(json.dumps(got[1])) == tfs


def _dot(svg: str, ident: str) -> np.ndarray:
    m = re.search(rf'<circle id="{ident}" cx="([-0-9.]+)" cy="([-0-9.]+)"', svg)
    assert m, ident
    return np.array([float(m.group(1)), float(m.group(2))])


def test_a_drag_frame_draws_the_moved_point_where_it_now_is():
    base = linkwork.load("library:crank-rocker")
    before, _ = frame(base, ["mechanism"])
    c = base.points["C"] + np.array([3.0, -2.0])
    svg, tfs = frame(moved(base, {"C": tuple(c)}), ["mechanism"])
    assert svg != before
    # the coupler point's dot at the paper point of its new design position (the transform's
    # formula, rounded to the 3 decimals written)
    t = tfs["mechanism"]
    want = [t["origin"][0] + (c[0] - t["lo"][0]) / t["per_mm"],
            t["origin"][1] + (t["hi"][1] - c[1]) / t["per_mm"]]
    np.testing.assert_allclose(_dot(svg, "point-C"), want, atol=6e-4)
    # drawn twice, the moved frame is the same text
    assert frame(moved(base, {"C": tuple(c)}), ["mechanism"])[0] == svg


def test_the_pole_schedule_of_a_drag_frame_is_its_own():
    base = linkwork.load("library:heusinger-valve-gear")
    drag = moved(base, {"P45": tuple(base.points["P45"] + 4.0)})
    assert schedule_of(drag) == pole_schedule(drag)
    # another structure with the same kind of chain gets its own schedule
    for name in ("crank-rocker", "double-rocker", "jansen-linkage"):
        mech = linkwork.load(f"library:{name}")
        assert schedule_of(mech) == pole_schedule(mech)


def test_counting_points_in_boxes_agrees_with_testing_every_pair():
    rng = np.random.default_rng(7)
    for _ in range(60):
        pts = rng.normal(0.0, 30.0, (rng.integers(1, 800), 2))
        corner = rng.normal(0.0, 40.0, (rng.integers(1, 120), 2))
        boxes = np.concatenate([corner, corner + rng.uniform(0.0, 9.0, corner.shape)], axis=1)
        k = min(len(pts), len(boxes)) // 2  # points on the boxes' edges count
        pts[:k] = boxes[:k, [0, 3]]
        inside = ((pts[None, :, 0] >= boxes[:, None, 0]) & (pts[None, :, 0] <= boxes[:, None, 2])
                  & (pts[None, :, 1] >= boxes[:, None, 1]) & (pts[None, :, 1] <= boxes[:, None, 3]))
        np.testing.assert_array_equal(_inside_counts(pts, boxes), inside.sum(axis=1))


def test_a_polyline_is_resampled_as_its_segments_one_by_one():
    rng = np.random.default_rng(3)
    # segments a whole number of steps long too (where the count could round either way)
    exact = np.cumsum(np.array([[0.0, 0.0], [0.6, 0.0], [0.0, 1.2], [1.8, 0.0], [0.36, 0.48]]), axis=0)
    for xy in [exact, rng.normal(0, 10, (40, 2)), np.array([[1.0, 2.0], [1.0, 2.0]])]:
        for step in (0.6, 0.8):
            one_by_one = np.concatenate([sym._samples(a, b, step) for a, b in zip(xy[:-1], xy[1:])])
            np.testing.assert_array_equal(sym.resample(xy, step), one_by_one)


def test_numbers_are_written_alike_one_by_one_and_all_at_once():
    values = np.array([0.0, -0.0, 0.0004, -0.0004, 0.0005, 1.2345, -1.2355, 12.5, 999999.9996,
                       1e6, -1e6, 2.5e7, np.inf, -np.inf, np.nan, 1 / 3])
    assert sym._fs(values) == [sym._f(v) for v in values]
    assert sym._f(-0.0004) == "-0" and sym._f(12.5) == "12.5" and sym._f(1e6) == "1000000.0"
