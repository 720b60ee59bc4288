"""Structural decomposition: the groups (Assur groups, *Gruppen*) in the order they are solved.

Starting from the frame, the next group is the smallest set of still-unknown links whose pairs
with the known links and among themselves remove exactly 3 degrees of freedom per link. A driver
removes one more at its pair. Two-link groups are the dyads (RRR, RRP, RPR, PRP, …), one-link
groups arise from sliding pairs (a rod with a pin in a slot), larger groups are the triads of
eight-link chains or the six-link group of Heusinger's valve gear. This is the one place that
decides the solution order; the kinematics layer follows it.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

from ..errors import StructureError
from ..model import Gear, Joint, Mechanism

#: degrees of freedom each pair removes (Grübler's g₁ pairs count 2, point contact pairs 1)
PAIR_CONSTRAINTS = {"revolute": 2, "prismatic": 2, "slot": 1, "circular-slot": 1, "gear": 1}


@dataclass(frozen=True)
class Group:
    """A set of links fixed by its pairs to the links solved before it."""

    links: tuple[str, ...]
    joints: tuple[str, ...]
    drivers: tuple[str, ...]

    @property
    def size(self) -> int:
        return len(self.links)


def _involved(j: Joint) -> tuple[str, ...]:
    return tuple(j.links) + ((j.carrier,) if isinstance(j, Gear) else ())


def constraint_count(joints: list[Joint], driver_joints: set[str]) -> int:
    return sum(PAIR_CONSTRAINTS[j.kind] + (j.name in driver_joints) for j in joints)


def solution_order(mech: Mechanism) -> tuple[Group, ...]:
    """The groups of `mech` in solution order, from the frame and the drivers.

    Raises `StructureError` naming the links that stay undetermined (too few inputs) or the pairs
    that over-determine a group (redundant constraints).
    """
    driver_joints = {d.joint for d in mech.drivers}
    known = {mech.frame}
    unknown = [n for n in mech.link_names if n != mech.frame]
    remaining = list(mech.joints)
    groups: list[Group] = []
    while unknown:
        found = None
        for size in range(1, len(unknown) + 1):
            for subset in combinations(unknown, size):
                reach = known.union(subset)
                js = [j for j in remaining
                      if set(_involved(j)) <= reach and any(ln in subset for ln in j.links)]
                count = constraint_count(js, driver_joints)
                if count > 3 * size:
                    raise StructureError(
                        f"over-constrained: the links {', '.join(subset)} are fixed by the pairs "
                        f"{', '.join(j.name for j in js)}, which remove {count} degrees of freedom "
                        f"where {3 * size} determine them (a redundant pair, or too many drivers)")
                if count == 3 * size:
                    found = Group(tuple(subset), tuple(j.name for j in js),
                                  tuple(j.name for j in js if j.name in driver_joints))
                    break
            if found:
                break
        if found is None:
            js = [j for j in remaining]
            missing = 3 * len(unknown) - constraint_count(js, driver_joints)
            raise StructureError(
                f"under-constrained: the links {', '.join(unknown)} are not determined by the "
                f"drivers ({', '.join(sorted(driver_joints)) or 'none'}); the mechanism needs "
                f"{max(missing, 1)} more input{'s' if missing > 1 else ''} or pairs")
        groups.append(found)
        known.update(found.links)
        unknown = [n for n in unknown if n not in found.links]
        remaining = [j for j in remaining if j.name not in found.joints]
    if remaining:
        raise StructureError(
            "over-constrained: the pairs " + ", ".join(j.name for j in remaining)
            + " join links that the other pairs already determine (redundant constraints); "
            "remove them or a link")
    return tuple(groups)
