"""Structure analyses that use the solver: mobility (counts and the real mobility), Assur groups,
Grashof's classification. The graph-only part (solution order, chain atlas) is `linkwork.topology`."""

from ..topology import Group, constraint_count, solution_order  # re-exported: the order lives below kinematics
from .assur import AssurGroup, assur_groups, mechanism_class
from .grashof import (LoopReport, classify_four_bar, classify_slider_crank, four_bar_transmission,
                      loops)
from .mobility import (Mobility, PairCounts, StructureReport, chain_counts, counts, mobility,
                       structure_report)

__all__ = ["Group", "constraint_count", "solution_order",
           "AssurGroup", "assur_groups", "mechanism_class",
           "LoopReport", "classify_four_bar", "classify_slider_crank", "four_bar_transmission",
           "loops",
           "Mobility", "PairCounts", "StructureReport", "chain_counts", "counts", "mobility",
           "structure_report"]
