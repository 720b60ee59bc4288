"""Structure of mechanisms: the graph of links and pairs, groups and their solution order."""

from .groups import Group, constraint_count, solution_order

__all__ = ["Group", "constraint_count", "solution_order"]
