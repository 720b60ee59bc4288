"""Over-closed chains solved (`linkwork.kinematics.overclosed`): the triple parallel crank,
Roberval's balance and the braced pantograph move by their special dimensions; their redundant
pairs are set aside, solved by least squares and reported. Inconsistent ones are refused with
the pair named.

Expectations by hand: three equal parallel cranks keep the coupler translating, every crank at
the input's angle (Rosenauer §101, Fig. 287); Roberval's beams are two parallelograms on one
post, so both beams turn alike and the pans stay upright; the braces of the pantograph are
parallel to its sides, so the braced pantograph moves as the unbraced one.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import linkwork
from linkwork import Status
from linkwork.errors import LinkworkWarning, StructureError
from mechanism_texts import TRIPLE_PARALLEL_CRANKS

sys.path.insert(0, str(Path(__file__).parents[1] / "structure"))
from test_mobility import ROBERVAL, _pantograph  # noqa: E402


def _angles(deg):
    return np.radians(np.asarray(deg, dtype=float))


def test_triple_parallel_cranks_move_as_a_parallelogram():
    mech = linkwork.load_text(TRIPLE_PARALLEL_CRANKS)
    u0 = mech.driver_input_at_design(mech.drivers[0])
    u = u0 + _angles([0, 10, 45, 100, 170, 200, 300])
    with pytest.warns(LinkworkWarning, match="over-closed.*O3, A3 of c3"):
        sol = linkwork.solve(mech, u, velocities=np.full(u.shape, 2.0))
    assert (sol.status == Status.OK).all()
    turn = u - u0
    for c, O, A in (("c1", "O1", "A1"), ("c2", "O2", "A2"), ("c3", "O3", "A3")):
        P = mech.points[A] - mech.points[O]
        want = mech.points[O] + np.stack([np.cos(turn) * P[0] - np.sin(turn) * P[1],
                                          np.sin(turn) * P[0] + np.cos(turn) * P[1]], axis=1)
        np.testing.assert_allclose(sol.point_on(c, mech.points[A]).position, want, atol=1e-9 * 45)
        np.testing.assert_allclose(sol.link(c).omega, 2.0, rtol=1e-9)
    np.testing.assert_allclose(sol.link("coupler").omega, 0.0, atol=1e-9)
    np.testing.assert_allclose(sol.link("coupler").alpha, 0.0, atol=1e-8)


def test_roberval_balance_swings_with_upright_pans():
    mech = linkwork.load_text(ROBERVAL)
    u0 = mech.driver_input_at_design(mech.drivers[0])
    u = u0 + _angles([-30, -10, 0, 15, 40])
    with pytest.warns(LinkworkWarning, match="over-closed"):
        sol = linkwork.solve(mech, u)
    assert (sol.status == Status.OK).all()
    def turned(ln):  # the link's turn from the drawing, in (−π, π]
        return np.angle(np.exp(1j * (sol.link(ln).angle - sol.reference_angle(ln))))

    np.testing.assert_allclose(turned("lower"), turned("upper"), atol=1e-9)
    np.testing.assert_allclose(turned("upper"), u - u0, atol=1e-9)
    for pan in ("left", "right"):
        np.testing.assert_allclose(turned(pan), 0.0, atol=1e-9)


def test_braced_pantograph_moves_as_the_unbraced_one():
    braced, free = _pantograph(True, True), _pantograph(False, True)
    u0 = braced.driver_input_at_design(braced.drivers[0])
    u = u0 + _angles([-20, -5, 0, 12, 18])
    with pytest.warns(LinkworkWarning, match="2 redundant equations"):
        a = linkwork.solve(braced, u)
    b = linkwork.solve(free, u)
    assert (a.status == Status.OK).all()
    for p in free.points:
        np.testing.assert_allclose(a.point(p).position, b.point(p).position, atol=1e-9 * 60)
        np.testing.assert_allclose(a.point(p).velocity, b.point(p).velocity, atol=1e-8 * 60)


def test_analyze_no_longer_refuses_them(tmp_path):
    from typer.testing import CliRunner

    from linkwork.cli.main import app

    f = tmp_path / "triple.toml"
    f.write_text(TRIPLE_PARALLEL_CRANKS)
    res = CliRunner().invoke(app, ["analyze", str(f), "--at", "80", "--format", "csv"])
    assert res.exit_code == 0, res.output
    assert ",ok," in res.output


def test_a_rigid_third_crank_is_refused_with_its_pairs():
    """c3 not parallel to the others (A3 moved up): the chain is rigid (F = 0 and no special
    dimensions), so the driver cannot move it."""
    text = TRIPLE_PARALLEL_CRANKS.replace("A3 = [45, 10]", "A3 = [47, 12]")
    with pytest.raises(StructureError, match="over-constrained.*A3"):
        linkwork.solve(linkwork.load_text(text), [1.2])


def test_a_parallel_crank_of_another_length_closes_only_at_the_design():
    """c3 parallel to the others but twice as long, A3 on the coupler's line extended: the
    velocities agree at the design position (first order) and nowhere else; a step of the
    input leaves its pair open, and that pair is named."""
    text = (TRIPLE_PARALLEL_CRANKS.replace("A3 = [45, 10]", "A3 = [50, 20]")
            .replace('A1 = [5, 10]', 'A1 = [5, 10]'))
    mech = linkwork.load_text(text)
    with pytest.raises(StructureError, match="design position only.*pair (O3|A3)"):
        linkwork.solve(mech, [1.2])
