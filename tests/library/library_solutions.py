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
