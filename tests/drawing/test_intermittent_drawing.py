"""Geneva and star wheels drawn simply: the wheel's radial slots turn with it, and the pin sits
in the drawn slot between its foot (D − r from C) and the rim where it entered."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.drawing import scene_at, scene_figure
from linkwork.model import indexing_schedule


@pytest.mark.parametrize("name,n", [("geneva-4", 4), ("geneva-6", 6)])
def test_geneva_slots_carry_the_pin(name, n):
    mech = linkwork.load(f"library:{name}")
    j = mech.joint("pin")
    lines = indexing_schedule(mech, j).slot_lines()
    assert len(lines) == n
    angles = np.sort(np.mod([a for a, _, _ in lines], 2 * np.pi))
    np.testing.assert_allclose(np.diff(angles), 2 * np.pi / n, atol=1e-12)  # equally spaced
    C, M, B = (mech.points[p] for p in ("C", "M", "B"))
    D, r = np.hypot(*(C - M)), np.hypot(*(B - M))
    for _, inner, outer in lines:
        assert inner == pytest.approx(D - r)
        assert outer == pytest.approx(D * np.cos(np.pi / n))  # Pöschl's cross radius a
    wheel = j.links[1]
    for deg in (-30.0, 0.0, 25.0):
        sol = linkwork.solve(mech, [np.radians(deg)])
        pin = sol.local(wheel, sol.point("B").position)[0] - C
        bearing, dist = np.arctan2(pin[1], pin[0]), np.hypot(*pin)
        off = [abs(np.angle(np.exp(1j * (bearing - a)))) for a, _, _ in lines]
        k = int(np.argmin(off))
        assert off[k] < 1e-12 and lines[k][1] - 1e-9 <= dist <= lines[k][2] + 1e-9


def test_star_wheel_draws_its_entry_and_exit_slots():
    mech = linkwork.load("library:star-wheel")
    lines = indexing_schedule(mech, mech.joint("index")).slot_lines()
    assert len(lines) == 8  # two groups, an entry and an exit slot each, twice round the wheel
    svg = scene_figure(scene_at(mech, np.radians(80.0)), ["mechanism"]).to_svg()
    assert "joint-index" in svg
