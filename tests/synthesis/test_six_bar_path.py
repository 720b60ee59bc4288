"""Six-bar path generation (`linkwork.synthesis.six_bar_path`): points sampled by the engine
from the library's Watt I and Stephenson III six-bars (a tracer added on the dyad's first
link) must be met: the engine, solving the written file at the crank angles found, puts the
tracer on them to 1e-9 of their size. Points off every six-bar curve get a least-squares
answer whose reported error is the engine's distance."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from linkwork.errors import InputError
from linkwork.io import load_text
from linkwork.kinematics import solve
from linkwork.synthesis.six_bar_path import six_bar_path_generator

LIB = Path(__file__).resolve().parents[2] / "src" / "linkwork" / "library"


def known(kind):
    if kind == "stephenson":
        txt = (LIB / "stephenson-iii-six-bar.toml").read_text()
        txt = txt.replace('O6 = [90, 60]', 'O6 = [90, 60]\nP = [60, 90]').replace(
            'link_ef = ["E", "F"]', 'link_ef = ["E", "F", "P"]')
    else:
        txt = (LIB / "watt-i-six-bar.toml").read_text()
        txt = txt.replace('E  = [-4.82595577806281, 48.9539459509657]',
                          'E  = [-4.82595577806281, 48.9539459509657]\nP = [-20, 40]').replace(
            'link_ce = ["C", "E"]', 'link_ce = ["C", "E", "P"]')
    assert "P = " in txt
    return load_text(txt, source=kind)


def sampled(kind, n):
    m = known(kind)
    th = m.driver_input_at_design(m.drivers[0]) + np.radians(np.linspace(0, 300, n))
    sol = solve(m, th, order=1)
    assert (sol.status == 0).all()
    return sol.point("P").position, th


@pytest.mark.parametrize("kind", ["watt", "stephenson"])
@pytest.mark.parametrize("timing", [False, True])
def test_sampled_points_of_a_known_six_bar_are_met(kind, timing):
    T, th = sampled(kind, 6)
    gen = six_bar_path_generator(T, kind, timing=(th - th[0]) if timing else None)
    size = np.ptp(T, axis=0).max()
    assert gen.error <= 1e-9 * size
    # the written file, solved again here at the angles found
    mech = load_text(gen.text, source="generated")
    assert len(mech.links) == 6 and len(mech.joints) == 7
    P = solve(mech, gen.angles, order=1).point("P").position
    assert np.hypot(*(P - T).T).max() <= 1e-9 * size
    assert gen.engine_error <= 1e-9 * size
    if timing:
        assert np.allclose(np.diff(gen.angles), np.diff(th), atol=1e-12)


def test_least_squares_beyond_exact():
    # eighteen points of a five-lobed curve: more conditions (36) than unknowns (33)
    phi = np.linspace(0, 2 * np.pi, 18, endpoint=False)
    T = np.column_stack([np.cos(phi) * (1 + 0.3 * np.cos(5 * phi)), np.sin(phi)]) * 50
    gen = six_bar_path_generator(T, "stephenson", starts=2)
    mech = load_text(gen.text, source="generated")
    P = solve(mech, gen.angles, order=1).point("P").position
    assert gen.engine_error == pytest.approx(np.hypot(*(P - T).T).max(), rel=1e-9)
    assert gen.engine_error == pytest.approx(gen.error, rel=1e-6)


def test_bad_requests_are_refused():
    with pytest.raises(InputError, match="choose one of"):
        six_bar_path_generator(np.eye(3, 2), "jansen")
    with pytest.raises(InputError, match="at least three"):
        six_bar_path_generator(np.zeros((2, 2)))
    with pytest.raises(InputError, match="timing"):
        six_bar_path_generator(np.random.default_rng(1).normal(size=(4, 2)), timing=[0, 1])
