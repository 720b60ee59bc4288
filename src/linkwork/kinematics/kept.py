"""A few values kept by key for the next frame of a drag to take over from the one before it
(`solver.plan`, `groups.pair_table_of`, `branches.branch_schedule`, `branches.path_schedule`)."""

from __future__ import annotations

from collections import OrderedDict
from threading import Lock


class Kept:
    """The last `size` values put, by key (the oldest dropped first); safe from several
    threads (a server solves in several)."""

    def __init__(self, size: int) -> None:
        self.size = size
        self._values: OrderedDict = OrderedDict()
        self._lock = Lock()

    def put(self, key, value) -> None:
        with self._lock:
            self._values[key] = value
            self._values.move_to_end(key)
            while len(self._values) > self.size:
                self._values.popitem(last=False)

    def get(self, key, default=None):
        return self._values.get(key, default)

    def __getitem__(self, key):
        return self._values[key]
