"""Library mechanisms and their whole motions, loaded and solved once per test process."""

from __future__ import annotations

from functools import lru_cache

import linkwork


@lru_cache(maxsize=None)
def mech(name: str):
    return linkwork.load(f"library:{name}")


@lru_cache(maxsize=None)
def motion(name: str):
    return linkwork.whole_motion(mech(name))


def driven_names() -> list[str]:
    """The library's mechanisms that run from drivers (not the chains driven by given point
    velocities at their drawn position, `tests/library/test_given_chains.py`)."""
    from linkwork.io.files import library_names
    return [n for n in library_names() if not mech(n).given]
