"""The solution order is kept per structure (`topology.structure_key`): a mechanism whose design
points moved (a drag in the workbench) re-plans nothing that depends on the structure alone.

Checked here: the same structure gives the very same order, another structure (another driven
pair, another pair kind, other links joined) another one; the guides of a group of sliding
pairs, the one part of the order that reads the drawing, are still checked for each
mechanism; and a moved mechanism solved after the order was kept gives bit for bit the
solution of the same drawing read from its file with every cache emptied."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.errors import StructureError
from linkwork.kinematics import branches, continuation, solver
from linkwork.model import Mechanism
from linkwork.topology import groups as topology_groups
from linkwork.topology import solution_order, structure_key
from mechanism_texts import joint, mechanism_text

CRANK_ROCKER = {"O2": (0, 0), "A": (0, 10), "B": (30, 30), "O4": (40, 0), "C": (15, 25)}


def four_bar(points=CRANK_ROCKER, driver="O2", kind="revolute") -> str:
    """The library's crank-rocker as text, with other coordinates, driver or kind of the
    rocker's frame pair (a slider on the frame instead of the rocker's hinge)."""
    frame_pair = (joint("O4", "revolute", "rocker", "frame") if kind == "revolute" else
                  joint("O4", "prismatic", "frame", "rocker", axis=0, point="O4"))
    return mechanism_text(
        name="four-bar", units="mm", points=points,
        links={"frame": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B", "C"],
               "rocker": ["B", "O4"]},
        joints=[joint("O2", "revolute", "frame", "crank"), joint("A", "revolute", "crank", "coupler"),
                joint("B", "revolute", "coupler", "rocker"), frame_pair],
        driver=driver, speed=1 if isinstance(driver, str) else (1,) * len(driver))


def with_points(mech: Mechanism, **points) -> Mechanism:
    """`mech` with design points moved, its links, pairs and drivers the same objects."""
    new = {**mech.points, **{k: np.asarray(v, float) for k, v in points.items()}}
    return Mechanism.build(name=mech.name, points=new, links={ln.name: list(ln.points) for ln in mech.links},
                           joints=list(mech.joints), drivers=list(mech.drivers), frame=mech.frame,
                           length_unit=mech.length_unit)


def forget_everything() -> None:
    """Empty every cache the solve keeps (orders, plans, change points, marches)."""
    topology_groups._orders.clear()
    solver.plan.cache_clear()
    branches.branch_schedule.cache_clear()
    continuation._marches.clear()


def test_the_same_structure_gives_the_same_order():
    a = linkwork.load_text(four_bar())
    b = with_points(a, B=(31, 29), C=(14, 26))
    c = linkwork.load_text(four_bar({**CRANK_ROCKER, "A": (1, 11)}))  # read again: new objects
    assert structure_key(a) == structure_key(b) == structure_key(c)
    assert solution_order(b) is solution_order(a)
    assert solution_order(c) is solution_order(a)
    assert [s.group for s in solver.plan(b)] == [s.group for s in solver.plan(a)]


def test_another_structure_gives_another_order():
    base = linkwork.load_text(four_bar())
    rocker_driven = linkwork.load_text(four_bar(driver="O4"))
    slider = linkwork.load_text(four_bar(kind="prismatic"))
    keys = {structure_key(m) for m in (base, rocker_driven, slider)}
    assert len(keys) == 3
    order = solution_order(base)
    # the crank first (driven at O2), else the rocker first (driven at O4)
    assert order[0].links == ("crank",) and order[1].links == ("coupler", "rocker")
    driven = solution_order(rocker_driven)
    assert driven[0].links == ("rocker",) and driven[0].drivers == ("O4",)
    assert driven[1].links == ("crank", "coupler")
    assert solution_order(slider)[1].joints == ("A", "B", "O4")
    assert {s.kind for s in solver.plan(slider)} == {"driver", "RRP"}


def wedge(beta: float) -> str:
    """A wedge (three sliding pairs in a loop): the input slide along x, the face at 20°, the
    follower's guide at β. β = 0 puts the follower's guide parallel to the input's."""
    return mechanism_text(
        name=f"wedge β={beta}", units="mm", points={"O": (0, 0), "W": (0, 0), "C": (40, 30)},
        links={"frame": ["O"], "wedge": ["W"], "follower": ["C"]},
        joints=[joint("slide", "prismatic", "frame", "wedge", axis=0, point="W"),
                joint("face", "prismatic", "wedge", "follower", axis=0 if beta == 0 else 20, point="C"),
                joint("guide", "prismatic", "frame", "follower", axis=beta, point="C")],
        driver="slide", speed=10)


def test_the_guides_are_checked_for_every_mechanism_of_a_kept_structure():
    good, parallel = linkwork.load_text(wedge(90)), linkwork.load_text(wedge(0))
    assert structure_key(good) == structure_key(parallel)
    assert len(solution_order(good)) == 2  # kept
    with pytest.raises(StructureError, match="parallel lines"):
        solution_order(parallel)
    assert len(solution_order(good)) == 2


def test_a_structural_error_is_raised_again_from_the_kept_order():
    m = linkwork.load_text(four_bar(driver=("O2", "O4")))  # two drivers for one freedom
    for _ in range(2):
        with pytest.raises(StructureError, match="over-constrained"):
            solution_order(m)


@pytest.mark.parametrize("name,point,to,at", [
    ("crank-rocker", "B", (31.5, 28.0), [0.3, 2.0, 4.0]),
    ("alt-eight-link", None, None, None),          # a Newton-solved group, one driver
    ("heusinger-valve-gear", "P45", (-1196.0, 353.0), None),  # and two drivers
])
def test_a_moved_mechanism_is_solved_as_its_own_file_with_no_cache(name, point, to, at):
    base = linkwork.load(f"library:{name}")
    if point is None:  # the first moving hinge of the Newton-solved group, moved by 1 %
        g = next(s for s in solver.plan(base) if s.kind == "generic")
        point = next(j.point for j in map(base.joint, g.group.joints) if j.kind == "revolute")
        to = base.points[point] + 0.01 * base.length_scale
    design = np.array([base.driver_input_at_design(d) for d in base.drivers])
    inputs = (design[None, :] + np.array([0.0, 0.2, -0.3])[:, None] * (np.arange(len(design)) == 0)
              if at is None else np.asarray(at)[:, None])
    linkwork.solve(base, inputs)  # the order and plan of the structure are kept from here
    moved = with_points(base, **{point: to})
    assert solution_order(moved) is solution_order(base)
    kept = linkwork.solve(moved, inputs)
    # the same drawing from its own text, every cache emptied first
    forget_everything()
    text = linkwork.load(f"library:{name}")
    fresh_mech = with_points(text, **{point: to})
    fresh = linkwork.solve(fresh_mech, inputs)
    for ln in moved.link_names:
        assert np.array_equal(kept.pose_derivatives(ln), fresh.pose_derivatives(ln), equal_nan=True)
    assert np.array_equal(kept.status, fresh.status)
    assert np.array_equal(kept.errors, fresh.errors, equal_nan=True)
    # and it is the moved drawing that was solved: each link keeps its moved lengths
    owner = moved.point_owner[point]
    other = next(p for p in moved.link(owner).points if p != point)
    drawn = np.hypot(*(np.asarray(to) - moved.points[other]))
    got = np.hypot(*(kept.point(point).position - kept.point(other).position).T)
    assert np.allclose(got[np.isfinite(got)], drawn, rtol=1e-9)
    assert not np.allclose(drawn, np.hypot(*(base.points[point] - base.points[other])))
