"""Counting formulas on the bare graph of links and pairs (no geometry)."""

from __future__ import annotations


def kutzbach(n: int, lower: int = 0, higher: int = 0) -> int:
    """Kutzbach's count for plane chains: F = 3(n − 1) − 2·lower − higher."""
    return 3 * (n - 1) - 2 * lower - higher
