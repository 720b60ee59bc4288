"""Roberts–Chebyshev cognates (`linkwork.synthesis.cognates`), checked by the engine: the second
cognate, driven at the third pivot in step with the original crank (its crank vector is
(1 − λ)·r₂), puts its coupler point where the original puts C at every sample of a turn; the
first cognate, moved through its whole motion, puts C where the original does at the crank
angle read off its own coupler (whose side A₁C is the original crank vector r₂)."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.io import load_text
from linkwork.kinematics import solve, whole_motion
from linkwork.synthesis.cognates import cognates


@pytest.mark.parametrize("library, point", [("crank-rocker", "C"), ("crank-rocker", [22.0, 8.0]),
                                            ("double-crank", None)])
def test_cognates_trace_the_same_coupler_curve(library, point):
    m = linkwork.load(f"library:{library}")
    if point is None:  # a point of the coupler off its line
        coupler = [lk for lk in m.links if lk.name == "coupler"][0]
        a, b = (np.asarray(m.points[p]) for p in coupler.points[:2])
        point = (a + b) / 2 + 0.3 * np.array([-(b - a)[1], (b - a)[0]])
    cg = cognates(m, point)
    design = np.asarray(point if not isinstance(point, str) else m.points[point], dtype=float)
    th = np.linspace(0, 2 * np.pi, 361)
    orig = solve(m, th, order=1)
    C = orig.point_on("coupler", design).position
    ok = orig.status != 2
    size = float(np.ptp(np.array(list(m.points.values())), axis=0).max())
    # the second cognate in step with the crank
    lam = (complex(*design) - complex(*m.points["A"])) / (complex(*m.points["B"]) - complex(*m.points["A"]))
    s2 = solve(load_text(cg.second), th + np.angle(1 - lam), order=1)
    assert np.nanmax(np.hypot(*(s2.point("C").position[ok] - C[ok]).T)) < 1e-9 * size
    # the first cognate through its own motion
    first = load_text(cg.first)
    s1 = whole_motion(first, step=np.radians(2.0), order=1)
    good = s1.status != 2
    Cc, A1 = s1.point("C").position[good], s1.point("A1").position[good]
    crank = np.arctan2(*(Cc - A1).T[::-1])  # A1→C is the original crank vector r2
    o = solve(m, crank, order=1)
    assert np.nanmax(np.hypot(*(o.point_on("coupler", design).position - Cc).T)) < 1e-9 * size
