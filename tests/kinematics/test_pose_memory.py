"""`solver._pose_memory`: a large solve takes the pose memory of the last one once no solution
refers to it, and never the memory of a solution still alive."""

from __future__ import annotations

import gc
import platform
import subprocess
import sys

import numpy as np
import pytest

import linkwork
from linkwork.kinematics import solver
from linkwork.kinematics.solution import Status


def test_live_solutions_keep_their_memory_and_dropped_ones_lend_it(monkeypatch):
    monkeypatch.setattr(solver, "SPARE_FROM", 1)  # every pose array through the spare
    monkeypatch.setattr(solver, "_SPARE", [None, None])
    mech = linkwork.load("library:crank-rocker")
    u = np.linspace(0.0, 6.0, 5000)
    a = linkwork.solve(mech, u)
    expect = a._C.copy()
    b = linkwork.solve(mech, u + 0.1)  # a is alive: fresh memory
    assert not np.shares_memory(a._C, b._C)
    np.testing.assert_array_equal(a._C, expect)  # untouched by b's solve
    spare = solver._SPARE[0].__array_interface__["data"][0]  # b's memory (an address only)
    del b
    gc.collect()
    c = linkwork.solve(mech, u + 0.2)  # b's memory, no one refers to it any more
    assert c._C.base.__array_interface__["data"][0] == spare
    assert not np.shares_memory(c._C, a._C)
    np.testing.assert_array_equal(a._C, expect)
    # the same answer as in fresh memory (every row written, the frame's zeroed)
    monkeypatch.setattr(solver, "SPARE_FROM", 1 << 60)
    fresh = linkwork.solve(mech, u + 0.2)
    np.testing.assert_array_equal(np.isnan(c._C), np.isnan(fresh._C))
    np.testing.assert_array_equal(np.nan_to_num(c._C), np.nan_to_num(fresh._C))


def test_a_view_of_a_point_or_link_keeps_nothing_and_a_kept_pose_keeps_its_memory(monkeypatch):
    """Reading points copies out of the pose array: dropping the solution frees it for the
    next solve; holding on to its pose array (a view) does not."""
    monkeypatch.setattr(solver, "SPARE_FROM", 1)
    monkeypatch.setattr(solver, "_SPARE", [None, None])
    mech = linkwork.load("library:crank-rocker")
    u = np.linspace(0.0, 6.0, 5000)
    sol = linkwork.solve(mech, u)
    C = sol.point("C").position
    keep = sol._C[0]  # a view of the pose memory
    del sol
    gc.collect()
    other = linkwork.solve(mech, u + 1.0)
    assert not np.shares_memory(other._C, keep)
    assert not np.shares_memory(other._C, C)


def test_frame_rows_are_kept_zero_only_by_solves_that_do_not_write_them(monkeypatch):
    """A solve whose every sample assembles leaves the frame's rows zero and says so: the next
    pose array of its shape in that memory keeps them; a solve with unassembled samples (NaN
    in every row of those) does not, and the next one zeroes them again. Either way the answer
    is the one in fresh memory."""
    monkeypatch.setattr(solver, "SPARE_FROM", 1)
    monkeypatch.setattr(solver, "_SPARE", [None, None])
    rocker = linkwork.load("library:double-rocker")
    u = rocker.driver_input_at_design(rocker.drivers[0]) + np.linspace(-np.pi, np.pi, 3000)
    frame = rocker.link_index[rocker.frame]

    def fresh(v):
        monkeypatch.setattr(solver, "SPARE_FROM", 1 << 60)
        try:
            return linkwork.solve(rocker, v)._C.copy()
        finally:
            monkeypatch.setattr(solver, "SPARE_FROM", 1)

    def same(C, expect):
        np.testing.assert_array_equal(np.isnan(C), np.isnan(expect))
        np.testing.assert_array_equal(np.nan_to_num(C), np.nan_to_num(expect))

    a = linkwork.solve(rocker, u)  # a double-rocker: some of these do not assemble
    assert (a.status == Status.UNREACHABLE).any() and np.isnan(a._C[:, :, frame]).any()
    assert solver._SPARE[1] is None
    del a
    gc.collect()
    ok = u[linkwork.solve(rocker, u).status != Status.UNREACHABLE]
    gc.collect()
    v = np.resize(ok, u.size)  # the same shape, every sample assembling
    b = linkwork.solve(rocker, v)  # in the NaN-marked memory: the frame's rows zeroed again
    assert not np.isnan(b._C[:, :, frame]).any() and (b._C[:, :, frame] == 0.0).all()
    same(b._C, fresh(v))
    assert solver._SPARE[1] is not None  # kept zero, and said so
    spare = b._C.__array_interface__["data"][0]
    del b
    gc.collect()
    c = linkwork.solve(rocker, v[::-1].copy())  # the same memory, its frame rows not written
    assert c._C.__array_interface__["data"][0] == spare
    assert (c._C[:, :, frame] == 0.0).all()
    same(c._C, fresh(v[::-1].copy()))


_FAULTS = """
import resource, sys
import numpy as np
import linkwork
from linkwork.kinematics import solver
if sys.argv[1] == "without":
    solver._raise_mmap_threshold = lambda: None
mech = linkwork.load("library:jansen-linkage")
x = np.linspace(0.0, 2 * np.pi, 100_000)
def one():
    sol = linkwork.solve(mech, x, velocities=2 * np.pi, compiled=True)
    for p in mech.points:
        sol.point(p)
for _ in range(3):
    one()
f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(10):
    one()
print((resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0) / 10)
"""


@pytest.mark.skipif(not sys.platform.startswith("linux") or platform.libc_ver()[0] != "glibc",
                    reason="glibc's mmap threshold")
def test_a_process_whose_first_large_array_is_the_spare_pays_no_page_faults_per_solve():
    """Jansen's linkage (a 55 MB pose array, the spare) solved and read in a loop in a fresh
    process: its other large arrays come from memory the allocator keeps, not from fresh pages
    of the system (`solver._raise_mmap_threshold`). The same process without it pays about
    1 600 page faults per solve (the control: the count measures what it should)."""
    def faults(mode: str) -> float:
        out = subprocess.run([sys.executable, "-c", _FAULTS, mode], capture_output=True,
                             text=True, check=True)
        return float(out.stdout.split()[-1])

    assert faults("with") < 50
    assert faults("without") > 500
