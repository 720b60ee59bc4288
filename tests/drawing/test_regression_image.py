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
    else:
        raise KeyError(name)
    return fig.save(tmp_path / f"{name}.png", dpi=DPI)


def grey(path: Path) -> np.ndarray:
    return np.asarray(PIL.open(path).convert("L"), dtype=np.int16)


@pytest.mark.parametrize("name", ["klein-centric-40", "crank-rocker-plans-230"])
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
