"""The kinematics' compiled loops for every batch size, in a process that solves many times.

A command line solve of a few samples runs the loops of `kernels` interpreted, because loading
numba costs a second or more per process. A long-running process — the workbench's server, a
worker of a design sweep — pays that once, and a four-bar's whole motion (limit scan, branch
scan, solve) then takes a few milliseconds instead of some sixty.
"""

from __future__ import annotations

from contextlib import contextmanager
from typing import Iterator

import numpy as np


def compiled_kernels() -> bool:
    """Whether this process runs the compiled loops for every batch size already."""
    from . import kernels
    return kernels.INTERPRETED_UP_TO == 0


def compile_kernels() -> None:
    """Run the kinematics' compiled loops for every batch size from now on. The loops are
    compiled (or loaded from numba's cache) first by batches large enough to take the compiled
    path anyway, so no solve waits for the compiler; only then is the threshold lowered."""
    from ..io import load
    from ..io.library import LIBRARY_PREFIX
    from . import kernels
    from .solver import solve
    if compiled_kernels():
        return
    inputs = np.linspace(0.0, 2 * np.pi, kernels.INTERPRETED_UP_TO + 1)[:, None]
    for name in ("crank-rocker", "slider-crank-centric"):  # the RRR and RRP dyads, the driver
        solve(load(LIBRARY_PREFIX + name), inputs, order=2)
    kernels.INTERPRETED_UP_TO = 0


@contextmanager
def compiled_loops() -> Iterator[None]:
    """The compiled loops for every batch size within the block (loaded first, once per
    process), the threshold as it was after it: the solves around it keep their results to
    the last bit."""
    from . import kernels
    before = kernels.INTERPRETED_UP_TO
    compile_kernels()
    try:
        yield
    finally:
        kernels.INTERPRETED_UP_TO = before
