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


def _flanks(fig) -> dict[str, np.ndarray]:
    return {p.ident: p.data["xy"] for p in fig.prims if p.ident and p.ident.startswith("flank-index-")}


@pytest.mark.parametrize("deg", [80.0, 200.0])
def test_star_wheel_draws_its_tooth_flanks(deg):
    """The flanks drawn with the wheel are where the model's pins drive it: turned back into
    the wheel's drawing they are epicycloids (a point of the driver's pitch circle, radius r,
    rolling on the wheel's, D − r), the normal at each point passes through the pitch point
    (the law of gearing), and the solved pins run along them."""
    mech = linkwork.load("library:star-wheel")
    j = mech.joint("index")
    sch = indexing_schedule(mech, j)
    sc = scene_at(mech, np.radians(deg))
    fig = scene_figure(sc, ["mechanism"])
    drawn = _flanks(fig)
    # per driver turn: 2 flanks of the 3-pin group, 1 of the 2-pin group; twice round the wheel
    assert len(drawn) == 6
    th = sc.theta("star")
    C = sc.sol.point("C").position[0]
    M, D = mech.points["M"], 100.0
    by_radius = {60.0: 0, 50.0: 0}
    for xy in drawn.values():
        local = (xy - C) @ np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
        rho = np.hypot(*local.T)
        # from the pitch circle's foot outwards: D − r at the start fixes r
        r = D - rho[0]
        assert min(abs(r - 60.0), abs(r - 50.0)) < 1e-9
        by_radius[round(r)] += 1
        R = D - r
        # epicycloid, with t the wheel's rolling angle: ρ² = D² + r² − 2Dr·cos(R t/r) and the
        # polar angle from the foot ±(atan2 of (R + r)e^{it} − r e^{iDt/r})
        t = np.arccos(np.clip((D * D + r * r - rho**2) / (2 * D * r), -1, 1)) * r / R
        z = (R + r) * np.exp(1j * t) - r * np.exp(1j * D * t / r)
        polar = np.unwrap(np.arctan2(local[:, 1], local[:, 0]))
        turn = polar - polar[0]
        want = np.angle(z)
        sign = np.sign(turn[-1]) if turn[-1] else 1.0
        np.testing.assert_allclose(turn, sign * want, atol=1e-9)
    assert by_radius == {60.0: 4, 50.0: 2}
    # while the pins drive the wheel as a pin gear (the solver's phase), one of them is on a
    # drawn flank: the model's motion runs along what is drawn
    sol = linkwork.solve(mech, np.linspace(0, 2 * np.pi, 721))
    gear = sol.joint("index")["phase"] == 3
    assert gear.sum() > 20
    back = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    polys = [(xy - C) @ back + mech.points["C"] for xy in drawn.values()]
    pts = np.vstack(polys)
    chord = max(np.hypot(*np.diff(p, axis=0).T).max() for p in polys)
    near = np.full(int(gear.sum()), np.inf)
    for p in ("A1", "A2", "A3", "B1", "B2"):
        local = sol.local("star", sol.point(p).position)[gear]
        d = np.hypot(local[:, None, 0] - pts[None, :, 0], local[:, None, 1] - pts[None, :, 1])
        near = np.minimum(near, d.min(axis=1))
    assert np.all(near <= chord)


def test_geneva_wheel_has_no_tooth_flanks():
    mech = linkwork.load("library:geneva-4")
    assert indexing_schedule(mech, mech.joint("pin")).flanks() == ()
    fig = scene_figure(scene_at(mech, 0.3), ["mechanism"])
    assert not [p for p in fig.prims if p.ident and p.ident.startswith("flank-")]
