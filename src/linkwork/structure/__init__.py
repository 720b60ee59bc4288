"""Structure of mechanisms: the graph of links and pairs, groups and their solution order,
mobility (counts and the real mobility), Assur groups, and Grashof's classification."""

from .groups import Group, constraint_count, solution_order
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
