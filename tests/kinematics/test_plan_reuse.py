"""A drag's frame (a mechanism that follows the previous one, `continuation.follow`) takes over
the per-drawing constants of the groups the two draw alike (`solver.plan`,
`groups.drawn_alike`): the very numbers a plan from scratch computes, checked against one; the
groups whose drawing changed compute theirs anew."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.kinematics import branches, groups, solver
from linkwork.kinematics.continuation import follow
from linkwork.kinematics.groups import GroupSolver, drawn_alike
from linkwork.web.sources import moved


def same(a, b) -> bool:
    """Equal to the bit (dicts of numbers, arrays and names; None)."""
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(np.asarray(a), np.asarray(b))
    return a == b


def table_arrays(t) -> dict:
    return {k: v for k, v in vars(t).items() if isinstance(v, (np.ndarray, float, int))}


@pytest.mark.parametrize("name,point,kept", [
    ("crank-rocker", "C", {"driver", "RRR", "table"}),  # a tracer point: no pair names it
    ("heusinger-valve-gear", "P45", {"driver", "RRP", "table"}),  # eccentric rod, slotted link
    ("heusinger-valve-gear", "P23", set()),  # the drawing's extent (its length scale) changes
])
def test_a_frame_takes_the_constants_of_the_groups_drawn_alike(name, point, kept):
    base = linkwork.load(f"library:{name}")
    before = solver.plan(base)
    for s in before:  # the previous frame's tables, as its solve builds them
        groups.pair_table_of(base, s.group)
    m = moved(base, {point: base.points[point] + np.array([0.7, -0.4])})
    follow(m, base)
    after = solver.plan(m)
    taken, computed = set(), set()
    for old, new in zip(before, after):
        assert same(new.fast, GroupSolver(m, new.group).fast)  # what a plan from scratch has
        alike = drawn_alike(base, m, new.group)
        if old.fast is not None:
            assert (new.fast is old.fast) == alike
            (taken if alike else computed).add(new.kind)
        table = groups.pair_table_of(m, new.group)
        if table is not None:
            want = groups.pair_table(m, new.group.links, new.group.joints, new.group.drivers,
                                     new.group.wedge_pairs, groups.contact.row_index(m))
            assert table_arrays(table).keys() == table_arrays(want).keys()
            for k, v in table_arrays(want).items():
                assert same(table_arrays(table)[k], v), k
            assert (table is groups.pair_table_of(base, new.group)) == alike
            (taken if alike else computed).add("table")
    assert taken == kept


def test_a_closed_form_frame_solves_to_the_bit_as_from_scratch():
    base = linkwork.load("library:crank-rocker")
    u = np.linspace(0.0, 6.0, 7)
    linkwork.solve(base, u)
    m = moved(base, {"C": base.points["C"] + np.array([0.6, 0.2])})
    got = linkwork.solve(m, u, previous=base)
    want = linkwork.solve(moved(m, {}), u)  # a new object: nothing taken over
    for p in m.points:
        assert np.array_equal(got.point(p).position, want.point(p).position)
        assert np.array_equal(got.point(p).acceleration, want.point(p).acceleration)
    assert np.array_equal(got.condition, want.condition, equal_nan=True)
    assert np.array_equal(got.errors, want.errors, equal_nan=True)


@pytest.mark.parametrize("point,by,taken", [
    ("C", (0.5, 0.0), True),   # the coupler's tracer point (the drawing's extent kept)
    ("B", (0.0, 0.3), False),  # a hinge: the dyad is drawn otherwise, its scan runs again
])
def test_a_frame_drawn_alike_takes_the_change_points_of_the_previous(point, by, taken):
    base = linkwork.load("library:parallelogram")
    u = np.linspace(-1.0, 7.0, 41)  # across both change points of a turn, and on
    linkwork.solve(base, u)
    before = branches.branch_schedule(base)
    assert before  # the parallelogram's two change points
    m = moved(base, {point: base.points[point] + np.array(by)})
    got = linkwork.solve(m, u, previous=base)
    fresh = moved(m, {})  # a new object: nothing taken over
    want, _ = branches._scan_schedule(fresh, solver.plan(fresh))
    assert (branches.branch_schedule(m) is before) == taken
    assert branches.branch_schedule(m) == want  # the scan's numbers
    sol = linkwork.solve(fresh, u)
    for p in m.points:
        assert np.array_equal(got.point(p).position, sol.point(p).position, equal_nan=True)
    assert np.array_equal(got.status, sol.status)


def test_a_path_of_two_drivers_takes_the_change_points_of_the_groups_drawn_alike():
    base = linkwork.load("library:heusinger-valve-gear")
    design = np.array([base.driver_input_at_design(d) for d in base.drivers])
    at = (design + [0.4, 0.0])[None]
    linkwork.solve(base, at)
    before = branches._path_schedules[base][3]
    m = moved(base, {"P45": base.points["P45"] + np.array([0.7, -0.4])})
    follow(m, base)
    solvers = solver.plan(m)
    got, lam, _ = branches.path_schedule(m, solvers, at)
    fresh = moved(m, {})  # a new object: scanned from scratch
    want, lam_fresh, _ = branches.path_schedule(fresh, solver.plan(fresh), at)
    assert got == want and np.array_equal(lam, lam_fresh)
    alike, kinds = True, {}
    for s in solvers:
        alike = alike and drawn_alike(base, m, s.group)
        if s.kind in branches.BRANCHING:
            assert (got[s.group] is before[s.group]) == alike
            kinds[s.kind] = alike
    assert kinds == {"RRP": True, "RRR": False}  # P45 is a hinge of the RRR dyad
