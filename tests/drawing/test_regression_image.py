"""A rendered PNG of a reference drawing, compared with the baseline image that was looked at
and kept (tests/drawing/baseline/). Set LINKWORK_UPDATE_BASELINE=1 to rewrite the baselines after
an intended change of the drawings (and look at them before committing)."""

import os
from pathlib import Path

import numpy as np
import pytest

import linkwork
from linkwork.constructions import construct
from linkwork.drawing import Scene, scene_figure

PIL = pytest.importorskip("PIL.Image")
BASELINE = Path(__file__).parent / "baseline"
DPI = 100

#: tolerance: at most this fraction of the pixels may differ by more than 64 grey levels
#: (fonts and antialiasing vary a little between cairo versions)
MAX_CHANGED = 0.01


def render(name: str, tmp_path: Path) -> Path:
    if name == "klein-centric-40":
        mech = linkwork.load("library:slider-crank-centric")
        sol = linkwork.solve(mech, np.radians([40.0]))
        fig = scene_figure(Scene(mech, sol), ["mechanism"], construction=construct("klein", mech, sol))
    elif name == "crank-rocker-plans-230":
        mech = linkwork.load("library:crank-rocker")
        sol = linkwork.solve(mech, np.radians([230.0]))
        fig = scene_figure(Scene(mech, sol), ["mechanism"], construction=construct("acceleration-plan", mech, sol))
    elif name == "crank-rocker-inset-30":
        # issue 16's worst offender, with the circles drawn whole in an inset at their own scale
        mech = linkwork.load("library:crank-rocker")
        sol = linkwork.solve(mech, np.radians([30.0]))
        fig = scene_figure(Scene(mech, sol), ["mechanism", "poles", "pole-lines", "centrodes", "inflection",
                                              "return", "bresse", "gamma"], frame="inset")
    elif name == "jansen-poles-0":
        # issue 16: Jansen's pole labels crowded near O (placement against lines, points, labels)
        mech = linkwork.load("library:jansen-linkage")
        sol = linkwork.solve(mech, np.radians([0.0]))
        fig = scene_figure(Scene(mech, sol), ["mechanism", "poles"])
    elif name in ("plans-crank-rocker-C-30", "vs-time-slider-crank-offset"):
        from linkwork.drawing.calculus_plots import plans_figure, vs_steps
        from linkwork.drawing.plots import save
        if name.startswith("plans"):
            fig, _ = plans_figure(linkwork.load("library:crank-rocker"), "C", at=np.radians(30.0))
        else:
            fig = vs_steps(linkwork.load("library:slider-crank-offset"), "B", "time")[0][-1]
        return save(fig, tmp_path / f"{name}.png", dpi=70)
    else:
        raise KeyError(name)
    return fig.save(tmp_path / f"{name}.png", dpi=DPI)


def grey(path: Path) -> np.ndarray:
    return np.asarray(PIL.open(path).convert("L"), dtype=np.int16)


@pytest.mark.parametrize("name", ["klein-centric-40", "crank-rocker-plans-230", "crank-rocker-inset-30",
                                  "plans-crank-rocker-C-30", "vs-time-slider-crank-offset", "jansen-poles-0"])
def test_reference_drawing(name, tmp_path):
    png = render(name, tmp_path)
    base = BASELINE / f"{name}.png"
    if os.environ.get("LINKWORK_UPDATE_BASELINE") == "1":
        base.write_bytes(png.read_bytes())
    if not base.exists():
        pytest.fail(f"no baseline {base}; render it with LINKWORK_UPDATE_BASELINE=1, look at it, commit it")
    a, b = grey(png), grey(base)
    assert a.shape == b.shape, f"size changed: {a.shape} vs baseline {b.shape}"
    changed = np.mean(np.abs(a - b) > 64)
    assert changed <= MAX_CHANGED, f"{changed:.2%} of the pixels differ from the baseline {base}"
