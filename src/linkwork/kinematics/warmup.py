"""The kinematics' compiled loops for every batch size, in a process that solves many times.

A command line solve of a few samples runs the loops of `kernels` interpreted, because loading
numba costs a second or more per process. A long-running process — the workbench's server, a
worker of a design sweep — pays that once, and a four-bar's whole motion (limit scan, branch
scan, solve) then takes a few milliseconds instead of some sixty.
"""

from __future__ import annotations

import threading
from contextlib import contextmanager
from typing import Iterator

import numpy as np

#: set once `compile_kernels` has loaded the compiled loops in this process
READY = threading.Event()
_LOCK = threading.Lock()


def compile_kernels() -> None:
    """Load the compiled loops (compiled, or read from numba's cache) by solving a few library
    mechanisms with them and reading their points: the fused pass (a four-bar, a slider-crank)
    and the per-group loops (chains with a Newton group), so that no solve after this waits for
    the compiler. Once per process; sets `READY`."""
    from ..io import load
    from ..io.library import LIBRARY_PREFIX
    from .kernels import compiled_loops as kernel_choice
    from .solver import solve
    with _LOCK:
        if READY.is_set():
            return
        with kernel_choice(True):
            for name in ("crank-rocker", "slider-crank-centric", "alt-ten-link",
                         "crank-driven-wedge"):
                mech = load(LIBRARY_PREFIX + name)
                sol = solve(mech, np.full((8, 1), mech.driver_input_at_design(mech.drivers[0])),
                            order=2)
                for p in mech.points:  # the points' loops too (`Solution.point`)
                    sol.point(p)
        READY.set()


@contextmanager
def loaded_compiled_loops() -> Iterator[None]:
    """The compiled loops for every batch size within the block (loaded first, once per
    process); `kernels.compiled_loops` holds the choice for this thread only, so the solves
    around the block keep theirs."""
    from .kernels import compiled_loops as kernel_choice
    compile_kernels()
    with kernel_choice(True):
        yield
