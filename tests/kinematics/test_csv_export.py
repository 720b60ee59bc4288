"""The CSV of a solution, written without pandas (`export.csv_lines`), is the text pandas'
`to_csv` writes from the same table (`to_pandas`): pandas is the second method."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.kinematics.export import csv_lines


def _cases():
    yield "whole motion", "crank-rocker", lambda m: linkwork.whole_motion(m)
    yield "unreachable samples", "double-rocker", lambda m: linkwork.solve(m, np.radians(np.arange(0, 360, 7.0)))
    yield "times", "crank-rocker", lambda m: linkwork.solve(m, times=np.linspace(0, 1, 11))
    yield "cam contact fields", "radial-roller-cam", lambda m: linkwork.whole_motion(m)
    yield "intermittent", "geneva-4", lambda m: linkwork.whole_motion(m)
    yield "one sample", "jansen-linkage", lambda m: linkwork.solve(m)


@pytest.mark.parametrize("case, name, make", list(_cases()), ids=[c[0] for c in _cases()])
@pytest.mark.parametrize("piece", [3, 4096])
def test_csv_equals_pandas(case, name, make, piece):
    sol = make(linkwork.load(f"library:{name}"))
    assert "".join(csv_lines(sol, True, piece)) == sol.to_pandas().to_csv(index=False)
    body = "".join(csv_lines(sol, False, piece))
    assert body == sol.to_pandas().to_csv(index=False, header=False)


def test_to_csv_writes_the_same_file(tmp_path):
    sol = linkwork.whole_motion(linkwork.load("library:crank-rocker"))
    sol.to_csv(tmp_path / "m.csv")
    assert (tmp_path / "m.csv").read_text() == sol.to_pandas().to_csv(index=False)
