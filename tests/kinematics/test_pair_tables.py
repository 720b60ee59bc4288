"""The pair tables (`constraints.PairTable`) against the jets and against finite differences.

Newton's method and the continuation's tangents evaluate a group's residuals, Jacobian and
first and second rates from tables of its lower pairs; the jets (`groups.residual_and_jacobian_jets`,
`groups.rate_residuals_jets`) evaluate the same equations written once over Taylor series.
Two checks that do not use the tables' own output as expectation:

- the jets: the same residuals, Jacobian and rates at random poses, velocities and inputs,
  to rounding (1e-13 of the length scale);
- finite differences: the Jacobian's columns against central differences of the tables'
  own residuals (an error of the order h² · |r''|), the first rates against the difference
  quotient of the residuals along a straight motion of the known links and inputs, the second
  rates against the second difference along a motion with accelerations.

Groups: every generic group of the library mechanisms whose pairs the tables cover, and every
such mechanism as one group of all its moving links, pairs and drivers (as
`jacobian.constraint_jacobian` builds it): revolute, prismatic and revolute drivers, slots,
circular slots, gear pairs, wedge pairs. Plus long double poses (the polish in extended
precision), and the whole motions solved with and without the tables.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import linkwork
from linkwork.errors import LinkworkError, LinkworkWarning
from linkwork.kinematics import contact, groups, solver
from linkwork.kinematics.groups import State
from linkwork.io.library import library_names
from linkwork.topology import Group

RNG_SEED = 11


def _mechanisms():
    out = []
    for name in library_names():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", LinkworkWarning)  # the over-closed ones say so
            try:
                mech = linkwork.load(f"library:{name}")
                plan = solver.plan(mech)
            except LinkworkError:  # the free chains of the library: no drivers
                continue
        out.append((name, mech, plan))
    return out


MECHS = _mechanisms()


def _cases():
    """(id, mechanism, group) of every group the tables cover."""
    out = []
    for name, mech, plan in MECHS:
        for s in plan:
            if s.kind == "generic" and groups.pair_table_of(mech, s.group) is not None:
                out.append(pytest.param(mech, s.group, id=f"{name}-{'-'.join(s.group.links)}"))
        if mech.drivers and not any(contact.is_higher(j) for j in mech.joints):
            whole = Group(links=mech.moving_links, joints=tuple(j.name for j in mech.joints),
                          drivers=tuple(d.joint for d in mech.drivers))
            if groups.pair_table_of(mech, whole) is not None:
                out.append(pytest.param(mech, whole, id=f"{name}-whole"))
    return out


CASES = _cases()


def _state(mech, rng, N=6, dtype=float):
    """Random poses (x, y of the size of the drawing, any angle) and velocities of every row,
    random inputs and input rates."""
    L = mech.length_scale
    Q = rng.normal(size=(2, N, len(contact.rows(mech)), 3)) * np.array([L, L, 2.0])
    Q[:, :, mech.link_index[mech.frame]] = 0.0
    inputs = {d.joint: rng.normal(size=(2, N)) * np.array([[2.0], [1.0]]) for d in mech.drivers}
    return State(mech, Q.astype(dtype), {j: v.astype(dtype) for j, v in inputs.items()})


def test_the_cases_cover_every_pair_kind_of_the_tables():
    kinds = {linkwork.load(f"library:{p.id.split('-whole')[0]}").joint(j).kind
             for p in CASES if p.id.endswith("-whole") for j in p.values[1].joints}
    assert {"revolute", "prismatic", "slot", "circular-slot", "gear"} <= kinds
    driver_kinds = {type(p.values[0].joint(d)).__name__ for p in CASES for d in p.values[1].drivers}
    assert {"Revolute", "Prismatic"} <= driver_kinds
    assert any(p.values[1].wedge_pairs for p in CASES)


@pytest.mark.parametrize("mech, group", CASES)
def test_residuals_jacobian_and_rates_equal_the_jets(mech, group):
    rng = np.random.default_rng(RNG_SEED)
    state = _state(mech, rng)
    L = mech.length_scale
    r, J = groups.residual_and_jacobian(state, group)
    rj, Jj = groups.residual_and_jacobian_jets(state, group)
    assert r.shape == rj.shape and J.shape == Jj.shape
    np.testing.assert_allclose(r, rj, rtol=0, atol=1e-13 * L)
    # angle columns are lengths per radian, position columns dimensionless
    np.testing.assert_allclose(J, Jj, rtol=0, atol=1e-13 * L)
    v, vj = groups.rate_residuals(state, group, 1), groups.rate_residuals_jets(state, group, 1)
    np.testing.assert_allclose(v, vj, rtol=0, atol=1e-13 * L * (1 + np.abs(state.Q[1]).max()))


@pytest.mark.parametrize("mech, group", CASES)
def test_jacobian_equals_central_differences_of_the_residuals(mech, group):
    rng = np.random.default_rng(RNG_SEED + 1)
    state = _state(mech, rng, N=3)
    L = mech.length_scale
    table = groups.pair_table_of(mech, group)
    idx = [state.li(ln) for ln in group.links]
    _, J = groups.residual_and_jacobian(state, group)
    for col in range(3 * group.size):
        link, c = idx[col // 3], col % 3
        h = 1e-5 * (L if c < 2 else 1.0)
        plus, minus = state.Q[0].copy(), state.Q[0].copy()
        plus[:, link, c] += h
        minus[:, link, c] -= h
        u = {j: v[0] for j, v in state.inputs.items()}
        fd = (table.evaluate(plus, u)[0] - table.evaluate(minus, u)[0]) / (2 * h)
        # central differences: error ~ h² |r'''| / 6, with |r'''| of the order of L per rad³
        np.testing.assert_allclose(J[:, :, col], fd, rtol=0, atol=1e-7 * L, err_msg=str(col))


@pytest.mark.parametrize("mech, group", CASES)
def test_first_rates_equal_the_difference_quotient_along_a_motion(mech, group):
    """−r_1 of the velocity equation is d/dt of the residuals with the group held still: the
    known links move with their velocities Q[1], the inputs with their rates."""
    rng = np.random.default_rng(RNG_SEED + 2)
    state = _state(mech, rng, N=3)
    L = mech.length_scale
    table = groups.pair_table_of(mech, group)
    idx = [state.li(ln) for ln in group.links]
    V = state.Q[1].copy()
    V[:, idx] = 0.0  # the group's own velocities are left out of r_1
    h = 1e-5

    def at(t):
        return table.evaluate(state.Q[0] + t * V, {j: v[0] + t * v[1]
                                                   for j, v in state.inputs.items()})[0]
    fd = (at(h) - at(-h)) / (2 * h)
    np.testing.assert_allclose(groups.rate_residuals(state, group, 1), fd, rtol=0,
                               atol=1e-6 * L * (1 + np.abs(V).max()))


@pytest.mark.parametrize("mech, group", CASES)
def test_second_rates_equal_the_jets_and_the_second_difference_along_a_motion(mech, group):
    """−r_2 of the acceleration equation: the residuals' second Taylor coefficient along the
    motion q(t) = q₀ + q₁t + q₂t² of every link (the group's own q₂ left out) and inputs."""
    rng = np.random.default_rng(RNG_SEED + 4)
    L = mech.length_scale
    Q = rng.normal(size=(3, 3, len(contact.rows(mech)), 3)) * np.array([L, L, 2.0])
    Q[:, :, mech.link_index[mech.frame]] = 0.0
    inputs = {d.joint: rng.normal(size=(3, 3)) for d in mech.drivers}
    state = State(mech, Q, inputs)
    got = groups.rate_residuals(state, group, 2)
    size = L * (1 + np.abs(Q[1:]).max()) ** 2
    np.testing.assert_allclose(got, groups.rate_residuals_jets(state, group, 2), rtol=0,
                               atol=1e-13 * size)
    table = groups.pair_table_of(mech, group)
    idx = [state.li(ln) for ln in group.links]
    Q2 = Q[2].copy()
    Q2[:, idx] = 0.0
    h = 1e-4

    def at(t):
        return table.evaluate(Q[0] + t * Q[1] + t * t * Q2,
                              {j: v[0] + t * v[1] + t * t * v[2] for j, v in inputs.items()})[0]
    fd = (at(h) - 2 * at(0.0) + at(-h)) / (2 * h * h)
    np.testing.assert_allclose(got, fd, rtol=0, atol=1e-5 * size)


@pytest.mark.parametrize("mech, group", CASES[:6])
def test_long_double_poses_stay_long_double_and_agree(mech, group):
    state = _state(mech, np.random.default_rng(RNG_SEED + 3), N=2, dtype=np.longdouble)
    r, J = groups.residual_and_jacobian(state, group)
    rj, Jj = groups.residual_and_jacobian_jets(state, group)
    assert r.dtype == np.longdouble and J.dtype == np.longdouble
    eps = float(np.finfo(np.longdouble).eps)
    L = mech.length_scale
    np.testing.assert_allclose(r.astype(float), rj.astype(float), rtol=0, atol=1e3 * eps * L)
    np.testing.assert_allclose(J.astype(float), Jj.astype(float), rtol=0, atol=1e3 * eps * L)


def test_groups_with_higher_pairs_keep_the_jets():
    mech = linkwork.load("library:proell-schwabe-valve-gear")
    covered = [groups.pair_table_of(mech, s.group) is not None
               for s in solver.plan(mech) if s.kind == "generic"]
    assert covered.count(False) >= 1 and covered.count(True) >= 1


@pytest.mark.parametrize("name", ["heusinger-valve-gear", "heusinger-hinge-chain",
                                  "stephenson-link-motion", "roemer-mechanism",
                                  "rosenauer-shaping-machine"])
def test_whole_motion_with_the_tables_equals_the_one_on_jets(name, monkeypatch):
    """The whole motion marched and solved with the tables and on jets (a new mechanism each,
    so that neither reuses the other's march): the same poses, rates and statuses."""
    with_tables = linkwork.whole_motion(linkwork.load(f"library:{name}"))
    monkeypatch.setattr(groups, "PAIR_TABLES", False)
    on_jets = linkwork.whole_motion(linkwork.load(f"library:{name}"))
    mech = with_tables.mechanism
    L = mech.length_scale
    assert len(with_tables) == len(on_jets)
    np.testing.assert_array_equal(with_tables.status, on_jets.status)
    for p in mech.points:
        a, b = with_tables.point(p), on_jets.point(p)
        np.testing.assert_allclose(a.position, b.position, rtol=0, atol=1e-9 * L, err_msg=p)
        np.testing.assert_allclose(a.velocity, b.velocity, rtol=0,
                                   atol=1e-9 * np.nanmax(np.abs(b.velocity)) + 1e-9 * L, err_msg=p)
        np.testing.assert_allclose(a.acceleration, b.acceleration, rtol=0,
                                   atol=1e-8 * np.nanmax(np.abs(b.acceleration)) + 1e-9 * L,
                                   err_msg=p)
