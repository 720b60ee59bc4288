"""Compiled per-sample loops of the closed-form hot paths: the RRR and RRP dyads, the revolute
driver and the motion of a point carried by a link.

Why compiled (numba): a dyad's positions, velocities and accelerations are some 150 arithmetic
operations per sample. As NumPy array operations each of them is a Python call and a walk
through memory, which held the four-bar, the six-bars and Jansen's linkage to several hundred
nanoseconds per sample and dyad; these loops do the same arithmetic in registers. Each formula
has this one implementation, a pure per-sample helper (scalars in, scalars out: `_rrr_solve`,
`_rrr_rate_solve`, `_bound_2` …) that the per-group loops (array-indexed) and the fused pass's
block loops (vectorised, see `_ROWS`) share; the generic path (constraints on jets and a linear
solve, `groups.derivatives_generic`) stays the independent check of it
(tests/kinematics/test_generic_vs_closed_form.py).

A batch of a few thousand samples or fewer runs the same loops interpreted (`_loop`): numba's
import and the loading of its cached machine code cost a second or more per process, more than
the interpreted loops take for a command asking for a few positions or one turn
(tests/kinematics/test_kernel_modes.py holds the two executions to each other). The choice can
be made explicitly: `compiled_loops(True)` (or `solve(..., compiled=True)`) for every batch.

Array conventions (as in `groups.State`): Q[k, link, (x, y, θ), n] holds the k-th Taylor
coefficient q⁽ᵏ⁾/k! of every link pose, the sample axis last; T[link, (cos θ, sin θ), n].
A link's pose places its design point s at (x, y) + R(θ)·s. Division by zero gives inf/NaN as
in NumPy (error_model="numpy"); unassembled samples are flagged in `ok` and their values are
overwritten with NaN by `solver.solve`.
"""

from __future__ import annotations

import math
import types
from contextlib import contextmanager
from contextvars import ContextVar
from functools import lru_cache, wraps

import numpy as np

#: batches of at most this many samples run the loops below as Python source (interpreted),
#: larger ones compiled: loading numba and its compiled code costs a second or more per
#: process, which a command asking for a few positions, one turn or the branch scan (2 049
#: inputs) should not pay. The same source either way; the compiled loops may differ in the
#: last bits (numba contracts a·b + c to one fused multiply-add).
INTERPRETED_UP_TO = 4096
#: the choice of `compiled_loops` in force: None (by batch size), True or False
_CHOICE: ContextVar[bool | None] = ContextVar("linkwork_compiled_loops", default=None)


@contextmanager
def compiled_loops(compiled: bool | None = True):
    """Within this context the loops run compiled (True: a server that has loaded them once
    wants them for every batch), interpreted (False: no numba at all) or by batch size (None,
    the default: batches of at most `INTERPRETED_UP_TO` samples interpreted). A context
    variable: it holds for this thread (or task) only, and nests."""
    token = _CHOICE.set(compiled)
    try:
        yield
    finally:
        _CHOICE.reset(token)

_FLAGS = dict(cache=True, nogil=True, error_model="numpy", fastmath={"contract", "arcp", "nsz"})
#: every loop of this module by name: (its Python function, the axis of its first argument
#: that counts the samples, or None for the helpers the loops call)
_LOOPS: dict[str, tuple[types.FunctionType, int | None]] = {}


def _loop(samples_axis: int | None = None):
    """Register a loop; an entry point (`samples_axis` given) picks the interpreted or compiled
    version by its number of samples."""

    def register(fn: types.FunctionType):
        _LOOPS[fn.__name__] = (fn, samples_axis)
        if samples_axis is None:
            return fn

        @wraps(fn)
        def entry(*args):
            choice = _CHOICE.get()
            small = args[0].shape[samples_axis] <= INTERPRETED_UP_TO
            if (not choice) if choice is not None else small:
                with np.errstate(all="ignore"):  # as the compiled loops: inf and NaN, quietly
                    return _interpreted()[fn.__name__](*args)
            return _compiled()[fn.__name__](*args)

        return entry

    return register


#: the loops whose every written row is an argument of its own that no other argument reaches:
#: compiled with LLVM's noalias on their arguments (`_NoAlias`), which lets it vectorise them
_ROWS: set[str] = set()


def _rows(fn: types.FunctionType | None = None, *, samples_axis: int | None = None):
    """Register a loop whose written rows are arguments of their own (see `_ROWS`): a block
    loop of the fused pass, or with `samples_axis` an entry point as `_loop` makes them."""
    def register(fn: types.FunctionType):
        _ROWS.add(fn.__name__)
        return _loop(samples_axis)(fn)

    return register if fn is None else register(fn)


def _at(n):
    """A sample's index as the loops use it: unsigned when compiled (`_compiled`), so that
    numba leaves out the wraparound of negative indices, which keeps LLVM from seeing the rows
    as contiguous."""
    return n


def _bound(namespace: dict) -> dict:
    """Every loop rebound to `namespace` as its globals, so that the loops call each other's
    version of the same kind."""
    for name, (fn, _) in _LOOPS.items():
        namespace[name] = types.FunctionType(fn.__code__, namespace, name, fn.__defaults__)
    return namespace


#: `math` for the interpreted loops: NumPy's scalar functions, which give NaN and ±inf where
#: Python's raise, as the compiled loops do (error_model="numpy")
_NUMPY_MATH = types.SimpleNamespace(sqrt=np.sqrt, cos=np.cos, sin=np.sin, floor=np.floor,
                                    pi=math.pi, inf=math.inf, nan=math.nan)

#: π/2 in three parts for the argument reduction of `_sincos` (rounded from 300 bits; the test
#: checks them): the first two of 33 significant bits, so that q times them is exact for the
#: quadrants q of |θ| ≤ `SINCOS_LIMIT`
_PIO2_A = float.fromhex("0x1.921fb54400000p+0")
_PIO2_B = float.fromhex("0x1.0b4611a600000p-34")
_PIO2_C = float.fromhex("0x1.3198a2e037073p-69")
SINCOS_LIMIT = 2.0 ** 19 * _PIO2_A
#: the Taylor coefficients of sin r / r − 1 and (cos r − 1 + r²/2) / r⁴ in z = r² (|r| ≤ π/4:
#: the first term left out is below 10⁻²² of the sum)
_S1, _S2, _S3, _S4, _S5, _S6, _S7, _S8, _S9 = ((-1.0) ** k / math.factorial(2 * k + 1)
                                               for k in range(1, 10))
_C2, _C3, _C4, _C5, _C6, _C7, _C8, _C9, _C10 = ((-1.0) ** k / math.factorial(2 * k)
                                                for k in range(2, 11))


def _library_cos_sin(t):
    """cos t, sin t by NumPy (the C library's): the interpreted loops' `_sincos` and
    `_cos_sin`, which as Python is faster than the polynomial (within 2 ulp of it)."""
    return np.cos(t), np.sin(t)


@lru_cache(maxsize=1)
def _interpreted() -> dict:
    ns = _bound({**globals(), "math": _NUMPY_MATH})
    ns["_sincos"] = ns["_cos_sin"] = _library_cos_sin
    return ns


@lru_cache(maxsize=1)
def _compiled() -> dict:
    import numba as nb
    from platformdirs import user_cache_dir

    # numba caches compiled loops beside their source by default, which fails where the package
    # is installed read-only; a per-user cache folder works everywhere (NUMBA_CACHE_DIR wins)
    if not nb.config.CACHE_DIR:
        nb.config.CACHE_DIR = user_cache_dir("linkwork", appauthor=False)
    from numba.core.compiler import Compiler

    class _NoAlias(Compiler):
        """numba's pipeline with LLVM's noalias on every pointer argument (`_ROWS`)."""

        def define_pipelines(self):
            self.state.flags.noalias = True
            return super().define_pipelines()

    ns = _bound(dict(globals()))
    ns["_at"] = np.uint64
    for name, (_, samples_axis) in _LOOPS.items():
        if name in _ROWS:  # each compiled on its own (not inlined: its noalias would not hold)
            ns[name] = nb.njit(inline="never", pipeline_class=_NoAlias, **_FLAGS)(ns[name])
            continue
        # the per-sample helpers inlined into the loops by numba itself: LLVM leaves the calls
        # of the fused loops' large bodies in place, and each call then passes its arrays with
        # reference counting (atomic) at every sample and group, several times the arithmetic
        inline = "always" if samples_axis is None else "never"
        ns[name] = nb.njit(inline=inline, **_FLAGS)(ns[name])
    return ns


@_loop()
def _world(Q0, T, i, s0, s1, n):
    """World position of design point s on link i at sample n (its pose and cos θ, sin θ)."""
    c, sn = T[i, 0, n], T[i, 1, n]
    return Q0[i, 0, n] + c * s0 - sn * s1, Q0[i, 1, n] + sn * s0 + c * s1


@_loop()
def _origin(c, sn, s0, s1, px, py):
    """Origin of a link at angle (c, sn) = (cos θ, sin θ) whose design point s lies at (px, py)."""
    return px - (c * s0 - sn * s1), py - (sn * s0 + c * s1)


@_loop()
def _place(Q0, T, i, c, sn, s0, s1, px, py, n):
    """Place link i at sample n: angle given by c, sn = cos θ, sin θ, its design point s at
    (px, py)."""
    T[i, 0, n], T[i, 1, n] = c, sn
    Q0[i, 0, n], Q0[i, 1, n] = _origin(c, sn, s0, s1, px, py)


@_loop(2)
def rrr_positions(Q0, T, iA, A, iC, C, i1, i2, diff, L1sq, tol, branch, k1, k2, r, ok):
    """Circle–circle intersection: the hinge B of links i1 (through A) and i2 (through C) at
    |AB| = L1 and |CB| = L2 on the side branch[n] = ±1 of AC (diff = L1² − L2²). The
    links' cos θ and sin θ follow from the hinge vectors r (k = (cos φ, sin φ) for a link drawn
    at angle φ: cos θ = r·k/|r|, sin θ = r×k/|r|), divided by the vectors' own lengths so that
    they are exactly a rotation: near a dead centre |B − C| differs from L2 by the dyad's
    forward error, and a rotation off unit length would carry that error, magnified by the
    link's size over L2, into every point of the link; the hinge vectors B − A, B − C go to
    r[0:2], r[2:4], whose angles the caller takes with NumPy's vectorised arctan2 (a scalar
    atan2 here would cost more than the rest)."""
    for n in range(Q0.shape[2]):
        good, r[0, n], r[1, n], r[2, n], r[3, n] = _rrr_position(
            Q0, T, iA, A[0], A[1], iC, C[0], C[1], i1, i2, diff, L1sq, tol, branch[n], k1[0],
            k1[1], k2[0], k2[1], n)
        if not good:
            ok[n] = False


@_loop()
def _rrr_position(Q0, T, iA, pa0, pa1, iC, pc0, pc1, i1, i2, diff, L1sq, tol, sign, k10, k11,
                  k20, k21, n):
    """`rrr_positions` at sample n (branch sign `sign`): places i1 and i2; returns whether the
    dyad assembles and the hinge vectors B − A, B − C."""
    ax, ay = _world(Q0, T, iA, pa0, pa1, n)
    cx, cy = _world(Q0, T, iC, pc0, pc1, n)
    good, r1x, r1y, r2x, r2y, c1, s1, c2, s2 = _rrr_solve(ax, ay, cx, cy, diff, L1sq, tol, sign,
                                                          k10, k11, k20, k21)
    _place(Q0, T, i1, c1, s1, pa0, pa1, ax, ay, n)
    _place(Q0, T, i2, c2, s2, pc0, pc1, cx, cy, n)
    return good, r1x, r1y, r2x, r2y


@_loop()
def _rrr_solve(ax, ay, cx, cy, diff, L1sq, tol, sign, k10, k11, k20, k21):
    """The circle–circle intersection of `rrr_positions` from the world pivots A and C: whether
    it assembles, the hinge vectors B − A, B − C and the two links' cos θ, sin θ."""
    dx, dy = cx - ax, cy - ay
    D2 = dx * dx + dy * dy
    inv = 1.0 / math.sqrt(D2)
    a = (diff + D2) * (0.5 * inv)  # distance of B's foot from A along AC
    h2 = L1sq - a * a  # squared distance of B from AC
    # rounding may take a limit position just below zero; NaN fails too
    good = h2 > tol
    h = sign * math.sqrt(h2 if h2 > 0.0 else 0.0) * inv
    a *= inv
    r1x, r1y = a * dx - h * dy, a * dy + h * dx  # B − A
    r2x, r2y = ax + r1x - cx, ay + r1y - cy  # B − C
    n1 = 1.0 / math.sqrt(r1x * r1x + r1y * r1y)
    n2 = 1.0 / math.sqrt(r2x * r2x + r2y * r2y)
    return (good, r1x, r1y, r2x, r2y, (r1x * k10 + r1y * k11) * n1,
            (r1y * k10 - r1x * k11) * n1, (r2x * k20 + r2y * k21) * n2,
            (r2y * k20 - r2x * k21) * n2)


@_loop()
def _point_rates(Q, T, i, s0, s1, n):
    """Velocity and acceleration (vx, vy, ax, ay) of design point s on link i at sample n."""
    return _motion(T[i, 0, n], T[i, 1, n], s0, s1, Q[1, i, 0, n], Q[1, i, 1, n], Q[1, i, 2, n],
                   Q[2, i, 0, n], Q[2, i, 1, n], Q[2, i, 2, n])


@_loop()
def _motion(c, sn, s0, s1, vx, vy, w, ax2, ay2, at2):
    """Velocity and acceleration (vx, vy, ax, ay) of design point s on a link at angle (c, sn)
    whose origin's Taylor coefficients are (vx, vy, ω) and (ax2, ay2, at2) (second ones halved)."""
    rx, ry = c * s0 - sn * s1, sn * s0 + c * s1
    al = 2.0 * at2
    ww = w * w
    return (vx - w * ry, vy + w * rx, 2.0 * ax2 - al * ry - ww * rx,
            2.0 * ay2 + al * rx - ww * ry)


@_loop()
def _set_rates(Q, T, i, s0, s1, n, vx, vy, ax, ay, om, al):
    """Rates of link i from the motion (v, a) of its design point s and its ω and α
    (`_origin_rates`)."""
    (Q[1, i, 0, n], Q[1, i, 1, n], Q[1, i, 2, n], Q[2, i, 0, n], Q[2, i, 1, n],
     Q[2, i, 2, n]) = _origin_rates(T[i, 0, n], T[i, 1, n], s0, s1, vx, vy, ax, ay, om, al)


@_loop()
def _origin_rates(c, sn, s0, s1, vx, vy, ax, ay, om, al):
    """Taylor coefficients (first: x, y, θ; second: x, y, θ, halved) of a link at angle
    (c, sn) from the motion (v, a) of its design point s and its ω and α:
    v_origin = v − ω ⊥r, a_origin = a − α ⊥r + ω² r, r = R(θ)s, ⊥(x, y) = (−y, x)."""
    rx, ry = c * s0 - sn * s1, sn * s0 + c * s1
    oo = om * om
    return (vx + om * ry, vy - om * rx, om, 0.5 * (ax + al * ry + oo * rx),
            0.5 * (ay - al * rx + oo * ry), 0.5 * al)


@_loop(3)
def rrr_rates(Q, T, iA, A, iC, C, i1, i2, BA, BC, mid, hd2, unreliable, cond, L, omega, m, E,
              eps):
    """Velocities and accelerations of the RRR dyad by Cramer's rule on the hinge closure
    ω1 ⊥r1 − ω2 ⊥r2 = vC − vA (r1 = B − A, r2 = B − C) and its derivative. The condition
    number of the 2×2 system raises cond[n] where larger: its columns have lengths L1, L2,
    so σ² = mid ± √(hd2 + (r1·r2)²) with mid = (L1² + L2²)/2, hd2 = ((L1² − L2²)/2)², and
    σ_max/σ_min = σ_max²/|det| (σ_max σ_min = |det|), free of cancellation near singularity.
    Where it reaches `unreliable` the rates are NaN: no digit of them would be right. The
    error bounds E and sizes m (`propagate_errors`) are carried on here, in the same pass."""
    for n in range(Q.shape[3]):
        k = _rrr_rate(Q, T, iA, A[0], A[1], iC, C[0], C[1], i1, i2, BA[0], BA[1], BC[0], BC[1],
                      mid, hd2, unreliable, L, 1.0 / omega[n], m, E, n, eps, n)
        if k > cond[n]:
            cond[n] = k


@_loop()
def _rrr_rate(Q, T, iA, a0, a1, iC, c0, c1, i1, i2, ba0, ba1, bc0, bc1, mid, hd2, unreliable, L,
              inv_omega, m, E, j, eps, n):
    """`rrr_rates` at sample n, the error bounds in column j of m and E; returns the condition
    number."""
    vAx, vAy, aAx, aAy = _point_rates(Q, T, iA, a0, a1, n)
    vCx, vCy, aCx, aCy = _point_rates(Q, T, iC, c0, c1, n)
    c1_, s1, c2, s2 = T[i1, 0, n], T[i1, 1, n], T[i2, 0, n], T[i2, 1, n]
    om1, om2, al1, al2, k = _rrr_rate_solve(vAx, vAy, aAx, aAy, vCx, vCy, aCx, aCy, c1_, s1, c2,
                                            s2, ba0, ba1, bc0, bc1, mid, hd2, unreliable)
    _set_rates(Q, T, i1, a0, a1, n, vAx, vAy, aAx, aAy, om1, al1)
    _set_rates(Q, T, i2, c0, c1, n, vCx, vCy, aCx, aCy, om2, al2)
    _dyad_error_2(Q, i1, i2, k, L, inv_omega, m, E, j, eps, n)
    return k


@_loop()
def _dyad_error_2(Q, i1, i2, k, L, inv_omega, m, E, j, eps, n):
    """The error bounds of a dyad of links i1, i2 with condition number k at sample n
    (`_group_error_2` on the larger of the two links' sizes), in column j of m and E."""
    x0, x1, x2 = _sizes_2(Q, i1, n, L, inv_omega)
    y0, y1, y2 = _sizes_2(Q, i2, n, L, inv_omega)
    _group_error_2(k, m, E, j, eps, max(x0, y0), max(x1, y1), max(x2, y2))


@_loop()
def _rrr_rate_solve(vAx, vAy, aAx, aAy, vCx, vCy, aCx, aCy, c1_, s1, c2, s2, ba0, ba1, bc0, bc1,
                    mid, hd2, unreliable):
    """ω1, ω2, α1, α2 and the condition number of `rrr_rates` from the motion of A and C and
    the links' cos θ, sin θ (NaN where the condition number reaches `unreliable`)."""
    r1x, r1y = c1_ * ba0 - s1 * ba1, s1 * ba0 + c1_ * ba1
    r2x, r2y = c2 * bc0 - s2 * bc1, s2 * bc0 + c2 * bc1
    inv = 1.0 / (r1y * r2x - r1x * r2y)
    wx, wy = vCx - vAx, vCy - vAy
    om1 = -(wx * r2x + wy * r2y) * inv
    om2 = -(wx * r1x + wy * r1y) * inv
    o1, o2 = om1 * om1, om2 * om2
    w2x = aCx - aAx + o1 * r1x - o2 * r2x
    w2y = aCy - aAy + o1 * r1y - o2 * r2y
    al1 = -(w2x * r2x + w2y * r2y) * inv
    al2 = -(w2x * r1x + w2y * r1y) * inv
    b = r1x * r2x + r1y * r2y
    k = (mid + math.sqrt(hd2 + b * b)) * abs(inv)
    k = k if k < math.inf else math.inf  # NaN and ∞: the dyad is singular (or unassembled)
    bad = k >= unreliable
    return (math.nan if bad else om1, math.nan if bad else om2, math.nan if bad else al1,
            math.nan if bad else al2, k)


@_loop(2)
def rrp_positions(Q0, T, iA, A, ig, P, e0, rsq, tol, branch, ir, ib, k, r, ok):
    """Circle–line intersection: the block's point P (design coordinates in the guide link ig
    and in the block ib) on its track, the line through P's design place along the guide's
    axis e0 (fixed in ig), at |AP| = √rsq from the rod's pivot A (on link iA), on the side
    branch[n] = ±1 of the rod's foot on the track. The rod ir turns as the vector A→P, its
    cos θ and sin θ taken from that vector as in `rrr_positions` (k = (cos φ, sin φ) for the
    rod drawn at angle φ); the vector goes to r[0:2] for the caller's vectorised arctan2. The
    block keeps the guide's angle. A squared half chord below zero by rounding only (above tol)
    counts as zero."""
    for n in range(Q0.shape[2]):
        good, r[0, n], r[1, n] = _rrp_position(
            Q0, T, iA, A[0], A[1], ig, P[0], P[1], e0[0], e0[1], rsq, tol, branch[n], ir, ib,
            k[0], k[1], n)
        if not good:
            ok[n] = False


@_loop()
def _rrp_position(Q0, T, iA, a0, a1, ig, p0, p1, e00, e01, rsq, tol, sign, ir, ib, k0, k1, n):
    """`rrp_positions` at sample n (branch sign `sign`): places the rod and the block (the
    block's angle too); returns whether the dyad assembles and the rod's vector A → P."""
    cg, sg = T[ig, 0, n], T[ig, 1, n]
    ax, ay = _world(Q0, T, iA, a0, a1, n)
    qx, qy = _world(Q0, T, ig, p0, p1, n)
    good, rx, ry, c, sn, px, py = _rrp_solve(ax, ay, qx, qy, cg, sg, e00, e01, rsq, tol, sign, k0,
                                             k1)
    _place(Q0, T, ir, c, sn, a0, a1, ax, ay, n)
    _place(Q0, T, ib, cg, sg, p0, p1, px, py, n)
    Q0[ib, 2, n] = Q0[ig, 2, n]
    return good, rx, ry


@_loop()
def _rrp_solve(ax, ay, qx, qy, cg, sg, e00, e01, rsq, tol, sign, k0, k1):
    """The circle–line intersection of `rrp_positions` from the world pivot A, the world design
    place Q of P on the guide and the guide's cos θ, sin θ: whether it assembles, the rod's
    vector A → P, its cos θ, sin θ and P."""
    ex, ey = cg * e00 - sg * e01, sg * e00 + cg * e01
    wx, wy = qx - ax, qy - ay
    b = ex * wx + ey * wy
    disc = b * b - (wx * wx + wy * wy - rsq)
    disc = 0.0 if disc < 0.0 and disc > tol else disc
    lam = sign * math.sqrt(disc) - b  # NaN where the rod's circle misses the track
    px, py = qx + lam * ex, qy + lam * ey
    good = (px - px == 0.0) & (py - py == 0.0)  # not NaN or ∞
    rx, ry = px - ax, py - ay
    nr = 1.0 / math.sqrt(rx * rx + ry * ry)
    return good, rx, ry, (rx * k0 + ry * k1) * nr, (ry * k0 - rx * k1) * nr, px, py


@_loop(3)
def rrp_rates(Q, T, iA, A, ig, P, e0, AP, length, ir, ib, unreliable, cond, L, omega, m, E,
              eps):
    """Velocities and accelerations of the RRP dyad: the rod's ω and α, and with them the motion
    of P, from the closure vA + ω ⊥r = v_c + λ̇ e (r = P − A = R(θ_rod)·AP, e the track's
    direction, λ P's place along it from its design place, v_c the velocity of the guide's point
    under P) and its derivative, aA + α ⊥r − ω² r = a_c + λ̈ e + 2 λ̇ ω_g ⊥e, by Cramer's rule on
    the 2×2 system [⊥r, −e]. The block turns with the guide (ω_g, α_g). Condition number: that
    of the system with both columns of the rod's length (σ_max²/|det|, as in `rrr_rates`),
    (|r| + |r × e|)/|r·e|: infinite where the rod stands square to the track (the dyad's
    limit position). Error bounds carried on as in `rrr_rates`."""
    for n in range(Q.shape[3]):
        k = _rrp_rate(Q, T, iA, A[0], A[1], ig, P[0], P[1], e0[0], e0[1], AP[0], AP[1], length,
                      ir, ib, unreliable, L, 1.0 / omega[n], m, E, n, eps, n)
        if k > cond[n]:
            cond[n] = k


@_loop()
def _rrp_rate(Q, T, iA, a0, a1, ig, p0, p1, e00, e01, ap0, ap1, length, ir, ib, unreliable, L,
              inv_omega, m, E, j, eps, n):
    """`rrp_rates` at sample n, the error bounds in column j of m and E; returns the condition
    number."""
    vAx, vAy, aAx, aAy = _point_rates(Q, T, iA, a0, a1, n)
    c, sn, cg, sg = T[ir, 0, n], T[ir, 1, n], T[ig, 0, n], T[ig, 1, n]
    # P's place along the track (the block and the guide have the same angle)
    ex, ey = cg * e00 - sg * e01, sg * e00 + cg * e01
    lam = (Q[0, ib, 0, n] - Q[0, ig, 0, n]) * ex + (Q[0, ib, 1, n] - Q[0, ig, 1, n]) * ey
    vcx, vcy, acx, acy = _point_rates(Q, T, ig, p0 + lam * e00, p1 + lam * e01, n)
    og, ag = Q[1, ig, 2, n], 2.0 * Q[2, ig, 2, n]
    om, al, k, vPx, vPy, aPx, aPy = _rrp_rate_solve(vAx, vAy, aAx, aAy, vcx, vcy, acx, acy, c,
                                                    sn, ex, ey, ap0, ap1, og, length, unreliable)
    _set_rates(Q, T, ir, a0, a1, n, vAx, vAy, aAx, aAy, om, al)
    _set_rates(Q, T, ib, p0, p1, n, vPx, vPy, aPx, aPy, og, ag)
    _dyad_error_2(Q, ir, ib, k, L, inv_omega, m, E, j, eps, n)
    return k


@_loop()
def _rrp_rate_solve(vAx, vAy, aAx, aAy, vcx, vcy, acx, acy, c, sn, ex, ey, ap0, ap1, og, length,
                    unreliable):
    """The rod's ω, α, the condition number and the motion (v, a) of P of `rrp_rates`, from
    the motion of A and of the guide's point under P, the rod's cos θ, sin θ, the track's
    direction e and the guide's ω (NaN where the condition number reaches `unreliable`)."""
    rx, ry = c * ap0 - sn * ap1, sn * ap0 + c * ap1
    inv = 1.0 / (rx * ex + ry * ey)
    wx, wy = vcx - vAx, vcy - vAy
    om = (ex * wy - ey * wx) * inv
    slide = -(rx * wx + ry * wy) * inv  # λ̇
    cor, oo = 2.0 * slide * og, om * om
    w2x = acx - cor * ey - aAx + oo * rx
    w2y = acy + cor * ex - aAy + oo * ry
    al = (ex * w2y - ey * w2x) * inv
    k = (length + abs(rx * ey - ry * ex)) * abs(inv)
    k = k if k < math.inf else math.inf  # NaN and ∞: at the limit position (or unassembled)
    bad = k >= unreliable
    om = math.nan if bad else om
    al = math.nan if bad else al
    return (om, al, k, vAx - om * ry, vAy + om * rx, aAx - al * ry - om * om * rx,
            aAy + al * rx - om * om * ry)


@_loop(2)
def driver_positions(Q0, T, b, i, H, u, u0):
    """Revolute driver: link i turns about the hinge H of its base link b by the input u,
    θ = θ_b + u − u0 (u0 the input at the design position)."""
    for n in range(Q0.shape[2]):
        _driver_position(Q0, T, b, i, H[0], H[1], u[n], u0, n)


@_loop()
def _driver_position(Q0, T, b, i, h0, h1, u, u0, n):
    """`driver_positions` at sample n (input u)."""
    hx, hy = _world(Q0, T, b, h0, h1, n)
    th = Q0[b, 2, n] + (u - u0)
    c, sn = _cos_sin(th)
    _place(Q0, T, i, c, sn, h0, h1, hx, hy, n)
    Q0[i, 2, n] = th


@_loop()
def _sincos(t):
    """cos t, sin t for |t| ≤ `SINCOS_LIMIT` without a library call, so that the driver's loop
    vectorises (the C library's sincos, a call per sample, cost more than a dyad): t = q·π/2 +
    r by a three-part reduction, |r| ≤ π/4, the Taylor polynomials of sin r and cos r, the
    quadrant q mod 4 choosing and signing them. Within about an ulp of the C library's
    (test_kernel_modes)."""
    q = math.floor(t * (2.0 / math.pi) + 0.5)
    r = ((t - q * _PIO2_A) - q * _PIO2_B) - q * _PIO2_C
    z = r * r
    sr = r + r * z * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * (_S6 + z * (
        _S7 + z * (_S8 + z * _S9))))))))
    hz = 0.5 * z
    w = 1.0 - hz  # 1 − z/2 and its rounding carried on: cos r to the last bit near |r| = π/4
    cr = w + (((1.0 - w) - hz) + z * z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * (
        _C6 + z * (_C7 + z * (_C8 + z * (_C9 + z * _C10)))))))))
    j = q - 4.0 * math.floor(q * 0.25)  # the quadrant, 0 … 3
    odd = (j == 1.0) | (j == 3.0)
    a, b = (cr if odd else sr), (sr if odd else cr)
    return (-b if (j == 1.0) | (j == 2.0) else b), (-a if j >= 2.0 else a)


@_loop()
def _cos_sin(t):
    """cos t, sin t: `_sincos` within its range, the C library's beyond (many turns)."""
    if abs(t) <= SINCOS_LIMIT:
        return _sincos(t)
    return math.cos(t), math.sin(t)


@_loop()
def _within(u, u0, lo, hi):
    """|u[n] − u0| ≤ `SINCOS_LIMIT` at every sample of the block lo … hi − 1 (NaN: no)."""
    top = 0.0
    for n in range(lo, hi):
        top = _worse(top, abs(u[_at(n)] - u0))
    return top <= SINCOS_LIMIT


@_loop(3)
def driver_rates(Q, T, b, i, H, u1, u2, kappa, L, omega, m, E, eps):
    """Revolute driver: ω = ω_b + u̇, α = α_b + ü (u1 = u̇, u2 = ü/2 as Taylor coefficients);
    the driven link turns about the hinge H, whose motion is that of H on the base. Its
    condition number is kappa at every sample; the error bounds are carried on as in
    `rrr_rates`."""
    for n in range(Q.shape[3]):
        _driver_rate(Q, T, b, i, H[0], H[1], u1[n], u2[n], kappa, L, 1.0 / omega[n], m, E, n,
                     eps, n)


@_loop()
def _driver_rate(Q, T, b, i, h0, h1, u1, u2, kappa, L, inv_omega, m, E, j, eps, n):
    """`driver_rates` at sample n, the error bounds in column j of m and E."""
    vx, vy, ax, ay = _point_rates(Q, T, b, h0, h1, n)
    om = Q[1, b, 2, n] + u1
    al = 2.0 * (Q[2, b, 2, n] + u2)
    _set_rates(Q, T, i, h0, h1, n, vx, vy, ax, ay, om, al)
    a0, a1, a2 = _sizes_2(Q, i, n, L, inv_omega)
    _group_error_2(kappa, m, E, j, eps, a0, a1, a2)


@_loop(1)
def point_motion(C, c, s, sx, sy, out):
    """Time derivatives out[k, (x, y), n] (k = 0 … K) of the point s = (sx[n], sy[n]) fixed in
    a link with pose Taylor coefficients C[k, n, (x, y, θ)] (q⁽ᵏ⁾/k!) and cos θ, sin θ = c, s:
    r = R(θ)s, v = ṫ + ω ⊥r, a = ẗ + α ⊥r − ω² r, j = ⃛t + (ω̈ − ω³) ⊥r − 3ωα r."""
    K = C.shape[0] - 1
    for n in range(C.shape[1]):
        if K >= 2:
            (out[0, 0, n], out[0, 1, n], out[1, 0, n], out[1, 1, n], out[2, 0, n],
             out[2, 1, n]) = _point_pva(c[n], s[n], sx[n], sy[n], C[0, n, 0], C[0, n, 1],
                                        C[1, n, 0], C[1, n, 1], C[1, n, 2], C[2, n, 0],
                                        C[2, n, 1], C[2, n, 2])
        else:
            out[0, 0, n], out[0, 1, n], out[1, 0, n], out[1, 1, n], _, _ = _point_pva(
                c[n], s[n], sx[n], sy[n], C[0, n, 0], C[0, n, 1], C[1, n, 0], C[1, n, 1],
                C[1, n, 2], 0.0, 0.0, 0.0)
        if K >= 3:
            rx = c[n] * sx[n] - s[n] * sy[n]
            ry = s[n] * sx[n] + c[n] * sy[n]
            w, a = C[1, n, 2], 2.0 * C[2, n, 2]
            jt, wa = 6.0 * C[3, n, 2] - w * w * w, 3.0 * w * a
            out[3, 0, n] = 6.0 * C[3, n, 0] - jt * ry - wa * rx
            out[3, 1, n] = 6.0 * C[3, n, 1] + jt * rx - wa * ry


@_rows(samples_axis=0)
def point_motion_2(c, sn, sx, sy, x0, y0, x1, y1, w, x2, y2, t2, px, py, vx, vy, ax, ay):
    """`point_motion` of the design point (sx, sy) at order 2 from the link's rows cos θ, sin θ
    and Taylor coefficients (x0, y0), (x1, y1, ω), (x2, y2, t2), each row (of these and of the
    answer) an array of its own: vectorised."""
    for n in range(c.shape[0]):
        k = _at(n)
        px[k], py[k], vx[k], vy[k], ax[k], ay[k] = _point_pva(
            c[k], sn[k], sx, sy, x0[k], y0[k], x1[k], y1[k], w[k], x2[k], y2[k], t2[k])


@_loop()
def _point_pva(c, sn, sx, sy, x0, y0, x1, y1, w, x2, y2, t2):
    """Position, velocity and acceleration (x, y each) of the point s = (sx, sy) on a link at
    angle (c, sn) whose origin's Taylor coefficients are (x0, y0), (x1, y1, ω), (x2, y2, t2)."""
    rx = c * sx - sn * sy
    ry = sn * sx + c * sy
    a, ww = 2.0 * t2, w * w
    return (x0 + rx, y0 + ry, x1 - w * ry, y1 + w * rx, 2.0 * x2 - a * ry - ww * rx,
            2.0 * y2 + a * rx - ww * ry)


@_loop(3)
def propagate_errors(Q, links, L, omega, kappa, rho, m, E, eps):
    """First-order forward error of one group's pose coefficients, added to the running bounds
    E[k, n]: the largest error of the k-th Taylor coefficients so far, in the natural units
    L·Ω^k (angles Ω^k), Ω = omega[n] the inputs' rate. m[0, n] is the size of the drawing's
    coordinates over L (raised here to the links' angles, whose rounding grows with the turns),
    m[k, n] (k ≥ 1) the size of the k-th coefficients so far, raised here to those of the
    group's `links`.

    The group's k-th coefficients solve J·x_k = −r_k, with κ = kappa[n] the condition number
    of the scaled J: positions carry κ times their backward error (the residual rho[n], or none
    for a closed form when rho is empty; the rounding eps·m[0] of the constraints; the errors
    E[0] of the links they hang on); x_k carries κ times the error of its right-hand side, whose
    terms are products of lower coefficients (the jets' Cauchy products: errors e_j times sizes
    m[k − j]), plus δJ·x_k (e_0·m[k]) and its own rounding."""
    K = E.shape[0] - 1
    N = E.shape[1]
    # the sizes, one stream at a time (a pass per link, coordinate and order keeps the memory
    # access sequential)
    for i in links:  # an angle of many turns rounds to ε times its size
        for n in range(N):
            a = abs(Q[0, i, 2, n]) * (1.0 / math.pi)
            if a > m[0, n]:
                m[0, n] = a
    for k in range(1, K + 1):
        for i in links:
            for n in range(N):
                inv = 1.0 / omega[n]
                scale = inv
                for _ in range(k - 1):
                    scale *= inv
                v = _size(Q, k, i, n, L) * scale
                if v > m[k, n]:
                    m[k, n] = v
    e = np.empty(K + 1)
    for n in range(N):
        _group_error(kappa[n], rho[n] if rho.size else 0.0, m, E, n, eps, e)


@_loop()
def _size(Q, k, i, n, L):
    """Size of link i's k-th pose coefficient at sample n: lengths over L, angles as they are."""
    return _size3(Q[k, i, 0, n], Q[k, i, 1, n], Q[k, i, 2, n], L)


@_loop()
def _size3(x, y, t, L):
    """Size of a pose coefficient (x, y, θ): lengths over L, angles as they are."""
    return max(max(abs(x), abs(y)) / L, abs(t))


@_loop()
def _group_error_2(k_, m, E, n, eps, m0, m1, m2):
    """`_group_error` unrolled for order 2 with a closed form (no residual), the sizes m0, m1,
    m2 at hand (`_bound_2` on column n of m and E)."""
    m[0, n], m[1, n], m[2, n], E[0, n], E[1, n], E[2, n] = _bound_2(
        k_, eps, m[0, n], m[1, n], m[2, n], E[0, n], E[1, n], E[2, n], m0, m1, m2)


@_loop()
def _bound_2(k_, eps, m0, m1, m2, E0, E1, E2, x0, x1, x2):
    """The running sizes m0, m1, m2 and bounds E0, E1, E2 (order 2, a closed form: no
    residual) after a group of condition number k_ whose links' sizes are x0, x1, x2: the
    compiled kernels' pass, scalars in registers, without branches (vectorised loops)."""
    m0 = m0 if x0 < m0 else x0
    m1 = m1 if x1 < m1 else x1
    m2 = m2 if x2 < m2 else x2
    e0 = k_ * (eps * m0 + E0)
    e1 = k_ * (E1 + e0 * m1 + max(e0, E0) * m1 + eps * 2.0 * m0 * m1)
    e2 = k_ * (E2 + e0 * m2 + max(e0, E0) * m2 + max(e1, E1) * m1
               + eps * (2.0 * m0 * m2 + m1 * m1))
    bad = not k_ < math.inf
    return (m0, m1, m2, math.inf if bad else max(E0, e0), math.inf if bad else max(E1, e1),
            math.inf if bad else max(E2, e2))


@_loop()
def _sizes_2(Q, i, n, L, inv):
    """(angle over π, first, second coefficient sizes in units of Ω, Ω²) of link i."""
    return (abs(Q[0, i, 2, n]) * (1.0 / math.pi), _size(Q, 1, i, n, L) * inv,
            _size(Q, 2, i, n, L) * inv * inv)


@_loop()
def _group_error(k_, r, m, E, n, eps, e):
    """The recurrence of `propagate_errors` at sample n (κ = k_, residual r; e: work array)."""
    K = E.shape[0] - 1
    if not k_ < math.inf:
        for k in range(K + 1):
            E[k, n] = math.inf
        return
    e[0] = k_ * (r + eps * m[0, n] + E[0, n])
    for k in range(1, K + 1):
        s = E[k, n] + e[0] * m[k, n]
        rounding = 0.0
        for j in range(k):
            s += max(e[j], E[j, n]) * m[k - j, n]
        for j in range(k + 1):
            rounding += m[j, n] * m[k - j, n]
        e[k] = k_ * (s + eps * rounding)
    for k in range(K + 1):
        if e[k] > E[k, n]:
            E[k, n] = e[k]


@_loop(2)
def rate_scales(C, per, out):
    """Ω per sample: the largest |c_k/per|^(1/k) over the drivers' Taylor coefficients
    C[driver, k, n] (k ≥ 1; per: 1, or L for a slide); 1 where every rate is zero."""
    for n in range(C.shape[2]):
        out[n] = _rate_scale(C, per, n)


@_loop()
def _rate_scale(C, per, n):
    """`rate_scales` at sample n."""
    top = 0.0
    for d in range(C.shape[0]):
        for k in range(1, C.shape[1]):
            v = abs(C[d, k, n]) / per[d]
            if k == 2:
                v = math.sqrt(v)
            elif k == 4:
                v = math.sqrt(math.sqrt(v))
            elif k > 1:
                v = v ** (1.0 / k)
            if v > top:
                top = v
    return top if top > 0.0 else 1.0


@_loop(1)
def relative_errors(E, m, eps, weights, out):
    """out[n]: the largest E[k, n] (k ≤ out's orders: positions, velocities, accelerations)
    over the larger of 1 and m[k, n], times weights[k], plus eps (the rounding of the stored
    answer); inf where NaN."""
    for n in range(E.shape[1]):
        out[n] = _relative_error(E, m, eps, weights, n)


@_loop()
def _relative_error(E, m, eps, weights, n):
    """`relative_errors` of column n."""
    K = min(E.shape[0], 3)
    top = 0.0
    for k in range(K):  # positions against the scale L; rates against their size too
        top = _worse(top, (E[k, n] / max(m[k, n], 1.0) if k else E[0, n]) * weights[k])
    return top + eps


@_loop()
def _worse(top, v):
    """The larger of top and v, ∞ where v is NaN."""
    return top if v <= top else (v if v == v else math.inf)


# ---------------------------------------------------------------------------- the fused pass
#: opcodes of `fused_positions` / `fused_rates` (the solution order as tables, `fused.Tables`)
DRIVER, RRR, RRP = 0, 1, 2
#: samples per pass of a group within the fused loops' block: the rows a group reads (written
#: by the groups before it) and the error bounds stay in the CPU's L2 cache between the groups
SUBBLOCK = 1024


# The block loops of the fused pass, one per group kind and kind of work: every row they write
# is an argument of its own that no other argument reaches (`_rows`), and the samples are
# indexed unsigned (`_at`): LLVM then vectorises them (eight samples per instruction), which
# it cannot where rows written and read are parts of one array.
@_rows
def _driver_block_positions(u, u0, h0, h1, x, y, th, c, s, ok, lo, hi):
    """`driver_positions` of a driver on the frame on the block lo … hi − 1 (the frame's pose
    is zero: θ = u − u0, the hinge H where it is drawn; |θ| ≤ `SINCOS_LIMIT`, `_within`), link
    i's rows x, y, θ, cos θ, sin θ written; ok[n] false where the input is NaN or ∞."""
    for n in range(lo, hi):
        k = _at(n)
        t = u[k] - u0
        cc, ss = _sincos(t)
        th[k], c[k], s[k] = t, cc, ss
        x[k], y[k] = _origin(cc, ss, h0, h1, h0, h1)
        ok[k] = ok[k] & (u[k] - u[k] == 0.0)


@_rows
def _rrr_block_positions(QA, QC, T, iA, pa0, pa1, iC, pc0, pc1, diff, L1sq, tol, sign, k10,
                         k11, k20, k21, x1, y1, c1, s1, x2, y2, c2, s2, r1x, r1y, r2x, r2y, ok,
                         lo, hi):
    """`rrr_positions` on the block lo … hi − 1: the rows x, y, cos θ, sin θ of both links
    written, the hinge vectors to r1x … r2y[n − lo] (sign[n − lo]: the assembly signs). QA, QC:
    the positions Q0 the pivots' links are read from, None for a pivot on the frame (it stands
    where it is drawn: numba compiles that case without the reads)."""
    for n in range(lo, hi):
        k, j = _at(n), _at(n - lo)
        if QA is None:
            ax, ay = pa0, pa1
        else:
            ax, ay = _world(QA, T, iA, pa0, pa1, k)
        if QC is None:
            cx, cy = pc0, pc1
        else:
            cx, cy = _world(QC, T, iC, pc0, pc1, k)
        good, r1x[j], r1y[j], r2x[j], r2y[j], cc1, ss1, cc2, ss2 = _rrr_solve(
            ax, ay, cx, cy, diff, L1sq, tol, sign[j], k10, k11, k20, k21)
        c1[k], s1[k], c2[k], s2[k] = cc1, ss1, cc2, ss2
        x1[k], y1[k] = _origin(cc1, ss1, pa0, pa1, ax, ay)
        x2[k], y2[k] = _origin(cc2, ss2, pc0, pc1, cx, cy)
        ok[k] = ok[k] & good


@_rows
def _rrp_block_positions(QA, QG, T, iA, a0, a1, ig, p0, p1, e00, e01, rsq, tol, sign, k0, k1,
                         xr, yr, cr, sr, xb, yb, tb, cb, sb, rx, ry, ok, lo, hi):
    """`rrp_positions` on the block lo … hi − 1: the rod's rows x, y, cos θ, sin θ and the
    block's x, y, θ, cos θ, sin θ written, the rod's vector to rx, ry[n − lo]. QA, QG: the
    positions Q0 the pivot's and the guide's links are read from, None for the frame."""
    for n in range(lo, hi):
        k, j = _at(n), _at(n - lo)
        if QA is None:
            ax, ay = a0, a1
        else:
            ax, ay = _world(QA, T, iA, a0, a1, k)
        if QG is None:
            cg, sg, qx, qy, tg = 1.0, 0.0, p0, p1, 0.0
        else:
            cg, sg, tg = T[ig, 0, k], T[ig, 1, k], QG[ig, 2, k]
            qx, qy = _world(QG, T, ig, p0, p1, k)
        good, rx[j], ry[j], c, sn, px, py = _rrp_solve(ax, ay, qx, qy, cg, sg, e00, e01, rsq,
                                                       tol, sign[j], k0, k1)
        cr[k], sr[k], cb[k], sb[k], tb[k] = c, sn, cg, sg, tg
        xr[k], yr[k] = _origin(c, sn, a0, a1, ax, ay)
        xb[k], yb[k] = _origin(cg, sg, p0, p1, px, py)
        ok[k] = ok[k] & good


@_rows
def _driver_block_rates(T, Q0, i, h0, h1, u1, u2, kappa, L, eps, inv_omega, m0, m1, m2, E0, E1,
                        E2, cond, vx, vy, vt, wx, wy, wt, lo, hi):
    """`driver_rates` of a driver on the frame on the block lo … hi − 1 (the hinge H stands
    still: ω = u̇, α = ü): link i's rows of first (v…) and second (w…) coefficients written,
    the bounds (m…, E…[n − lo]) and cond[n] carried on."""
    for n in range(lo, hi):
        k, j = _at(n), _at(n - lo)
        v0, v1, v2, w0, w1, w2 = _origin_rates(T[i, 0, k], T[i, 1, k], h0, h1, 0.0, 0.0, 0.0,
                                               0.0, u1[k], 2.0 * u2[k])
        vx[k], vy[k], vt[k], wx[k], wy[k], wt[k] = v0, v1, v2, w0, w1, w2
        inv = inv_omega[j]
        m0[j], m1[j], m2[j], E0[j], E1[j], E2[j] = _bound_2(
            kappa, eps, m0[j], m1[j], m2[j], E0[j], E1[j], E2[j],
            abs(Q0[i, 2, k]) * (1.0 / math.pi), _size3(v0, v1, v2, L) * inv,
            _size3(w0, w1, w2, L) * inv * inv)
        cond[k] = kappa if kappa > cond[k] else cond[k]


@_rows
def _rrr_block_rates(QA, QC, Q, T, iA, a0, a1, iC, c0, c1, i1, i2, ba0, ba1, bc0, bc1, mid,
                     hd2, unreliable, L, eps, inv_omega, m0, m1, m2, E0, E1, E2, cond, v1x, v1y,
                     v1t, w1x, w1y, w1t, v2x, v2y, v2t, w2x, w2y, w2t, lo, hi):
    """`rrr_rates` on the block lo … hi − 1: both links' rows of first (v…) and second (w…)
    coefficients written, the bounds and cond carried on as in `_driver_block_rates`. QA, QC:
    the poses Q the pivots' motions are read from, None for a pivot on the frame (still)."""
    for n in range(lo, hi):
        k, j = _at(n), _at(n - lo)
        if QA is None:
            vAx = vAy = aAx = aAy = 0.0
        else:
            vAx, vAy, aAx, aAy = _point_rates(QA, T, iA, a0, a1, k)
        if QC is None:
            vCx = vCy = aCx = aCy = 0.0
        else:
            vCx, vCy, aCx, aCy = _point_rates(QC, T, iC, c0, c1, k)
        cs1, sn1, cs2, sn2 = T[i1, 0, k], T[i1, 1, k], T[i2, 0, k], T[i2, 1, k]
        om1, om2, al1, al2, kap = _rrr_rate_solve(vAx, vAy, aAx, aAy, vCx, vCy, aCx, aCy, cs1,
                                                  sn1, cs2, sn2, ba0, ba1, bc0, bc1, mid, hd2,
                                                  unreliable)
        p0, p1, p2, q0, q1, q2 = _origin_rates(cs1, sn1, a0, a1, vAx, vAy, aAx, aAy, om1, al1)
        v1x[k], v1y[k], v1t[k], w1x[k], w1y[k], w1t[k] = p0, p1, p2, q0, q1, q2
        r0, r1, r2, t0, t1, t2 = _origin_rates(cs2, sn2, c0, c1, vCx, vCy, aCx, aCy, om2, al2)
        v2x[k], v2y[k], v2t[k], w2x[k], w2y[k], w2t[k] = r0, r1, r2, t0, t1, t2
        inv = inv_omega[j]
        m0[j], m1[j], m2[j], E0[j], E1[j], E2[j] = _bound_2(
            kap, eps, m0[j], m1[j], m2[j], E0[j], E1[j], E2[j],
            max(abs(Q[0, i1, 2, k]) * (1.0 / math.pi), abs(Q[0, i2, 2, k]) * (1.0 / math.pi)),
            max(_size3(p0, p1, p2, L) * inv, _size3(r0, r1, r2, L) * inv),
            max(_size3(q0, q1, q2, L) * inv * inv, _size3(t0, t1, t2, L) * inv * inv))
        cond[k] = kap if kap > cond[k] else cond[k]


@_rows
def _rrp_block_rates(QA, QG, Q, T, iA, a0, a1, ig, p0, p1, e00, e01, ap0, ap1, length, ir, ib,
                     unreliable, L, eps, inv_omega, m0, m1, m2, E0, E1, E2, cond, vrx, vry, vrt,
                     wrx, wry, wrt, vbx, vby, vbt, wbx, wby, wbt, lo, hi):
    """`rrp_rates` on the block lo … hi − 1: the rod's and the block's rows written, the
    bounds and cond carried on as in `_driver_block_rates`. QA, QG: the poses Q the pivot's and
    the guide's motions are read from, None for the frame (still; the guide at angle 0)."""
    for n in range(lo, hi):
        k, j = _at(n), _at(n - lo)
        if QA is None:
            vAx = vAy = aAx = aAy = 0.0
        else:
            vAx, vAy, aAx, aAy = _point_rates(QA, T, iA, a0, a1, k)
        c, sn = T[ir, 0, k], T[ir, 1, k]
        if QG is None:  # the block at angle 0, as its positions wrote (its rows not read)
            ex, ey = e00, e01
            vcx = vcy = acx = acy = og = ag = 0.0
            cb, sb, tb = 1.0, 0.0, 0.0
        else:
            cb, sb, tb = T[ib, 0, k], T[ib, 1, k], Q[0, ib, 2, k]
            cg, sg = T[ig, 0, k], T[ig, 1, k]
            ex, ey = cg * e00 - sg * e01, sg * e00 + cg * e01
            # P's place along the track (the block and the guide have the same angle)
            lam = (Q[0, ib, 0, k] - QG[0, ig, 0, k]) * ex + (Q[0, ib, 1, k] - QG[0, ig, 1, k]) * ey
            vcx, vcy, acx, acy = _point_rates(QG, T, ig, p0 + lam * e00, p1 + lam * e01, k)
            og, ag = QG[1, ig, 2, k], 2.0 * QG[2, ig, 2, k]
        om, al, kap, vPx, vPy, aPx, aPy = _rrp_rate_solve(
            vAx, vAy, aAx, aAy, vcx, vcy, acx, acy, c, sn, ex, ey, ap0, ap1, og, length,
            unreliable)
        r0, r1, r2, t0, t1, t2 = _origin_rates(c, sn, a0, a1, vAx, vAy, aAx, aAy, om, al)
        vrx[k], vry[k], vrt[k], wrx[k], wry[k], wrt[k] = r0, r1, r2, t0, t1, t2
        q0, q1, q2, u0, u1, u2 = _origin_rates(cb, sb, p0, p1, vPx, vPy, aPx, aPy, og, ag)
        vbx[k], vby[k], vbt[k], wbx[k], wby[k], wbt[k] = q0, q1, q2, u0, u1, u2
        inv = inv_omega[j]
        m0[j], m1[j], m2[j], E0[j], E1[j], E2[j] = _bound_2(
            kap, eps, m0[j], m1[j], m2[j], E0[j], E1[j], E2[j],
            max(abs(Q[0, ir, 2, k]) * (1.0 / math.pi), abs(tb) * (1.0 / math.pi)),
            max(_size3(r0, r1, r2, L) * inv, _size3(q0, q1, q2, L) * inv),
            max(_size3(t0, t1, t2, L) * inv * inv, _size3(u0, u1, u2, L) * inv * inv))
        cond[k] = kap if kap > cond[k] else cond[k]


@_loop(0)
def fused_positions(ok, ops, fl, Q0, T, U, signs, fixed, R, lo, hi):
    """Positions of every group of a mechanism at the samples lo … hi − 1 (a block), through
    the whole solution order (the tables `ops`, `fl` of `fused.tables`: per group its opcode,
    link indices and constants), each group's loop over the block a vectorised block loop
    (`_rrr_block_positions` …) with the group's constants in registers. ok[n]: every group
    assembles. U[driver, k, n]: the inputs' Taylor coefficients; signs[row, n − lo]: the dyads'
    assembly signs, or fixed[row] where it is a number (the dyad's sign at every sample: the row
    not read, the loop given a sub-block's copy of it, which stays in the L1 cache; NaN: the
    row's); the dyads' hinge vectors go to R[col …, n − lo] for the caller's
    vectorised arctan2."""
    for n in range(lo, hi):
        ok[n] = True
    own = np.empty(SUBBLOCK)
    for lo2 in range(lo, hi, SUBBLOCK):  # each group's inputs still in the cache
        hi2 = min(hi, lo2 + SUBBLOCK)
        a, b = lo2 - lo, hi2 - lo
        for g in range(ops.shape[0]):
            op, i1, i2, i3, i4, row, c = (ops[g, 0], ops[g, 1], ops[g, 2], ops[g, 3], ops[g, 4],
                                          ops[g, 5], ops[g, 6])
            f0, f1, f2, f3, f4, f5, f6 = fl[g, 0], fl[g, 1], fl[g, 2], fl[g, 3], fl[g, 4], \
                fl[g, 5], fl[g, 6]
            f7, f8, f9, f10, f11 = fl[g, 7], fl[g, 8], fl[g, 9], fl[g, 10], fl[g, 11]
            still = ops[g, 7]
            if op != DRIVER:
                sign = signs[row][a:b]
                if fixed[row] == fixed[row]:
                    sign = own[:b - a]
                    sign[:] = fixed[row]
            if op == DRIVER and _within(U[i3, 0], f2, lo2, hi2):
                _driver_block_positions(U[i3, 0], f2, f0, f1, Q0[i2, 0], Q0[i2, 1], Q0[i2, 2],
                                        T[i2, 0], T[i2, 1], ok, lo2, hi2)
            elif op == DRIVER:  # inputs of many turns (or NaN): sample by sample, `_cos_sin`
                for n in range(lo2, hi2):
                    u = U[i3, 0, n]
                    _driver_position(Q0, T, i1, i2, f0, f1, u, f2, n)
                    ok[n] = ok[n] & (u - u == 0.0)
            elif op == RRR:
                rrr_pos = (T, i1, f0, f1, i2, f2, f3, f4, f5, f6, sign, f8, f9, f10,
                        f11, Q0[i3, 0], Q0[i3, 1], T[i3, 0], T[i3, 1], Q0[i4, 0], Q0[i4, 1],
                        T[i4, 0], T[i4, 1], R[c][a:b], R[c + 1][a:b], R[c + 2][a:b],
                        R[c + 3][a:b], ok, lo2, hi2)
                if still == 1:  # a pivot on the frame: its own compiled case, without reads
                    _rrr_block_positions(None, Q0, *rrr_pos)
                elif still == 2:
                    _rrr_block_positions(Q0, None, *rrr_pos)
                else:
                    _rrr_block_positions(Q0, Q0, *rrr_pos)
            else:
                rrp_pos = (T, i1, f0, f1, i2, f2, f3, f4, f5, f6, f7, sign, f9, f10,
                        Q0[i3, 0], Q0[i3, 1], T[i3, 0], T[i3, 1], Q0[i4, 0], Q0[i4, 1],
                        Q0[i4, 2], T[i4, 0], T[i4, 1], R[c][a:b], R[c + 1][a:b], ok, lo2, hi2)
                if still == 1:
                    _rrp_block_positions(None, Q0, *rrp_pos)
                elif still == 2:
                    _rrp_block_positions(Q0, None, *rrp_pos)
                else:
                    _rrp_block_positions(Q0, Q0, *rrp_pos)


@_loop(0)
def fused_rates(cond, ops, fl, Q, T, U, per, L, eps, m0, unreliable, plain, weighted, err, serr,
                E0, m, E, lo, hi):
    """Velocities and accelerations of every group at the samples lo … hi − 1 (a block),
    through the solution order as in `fused_positions`, with the condition numbers (cond[n]:
    the largest of 1 and the groups'), the forward error bounds of `precision.ErrorBudget`
    (work arrays m, E of the block's size; m0: the drawing's coordinates over L) and their
    relative values (`relative_errors` with the weights `plain` into err, `weighted` into
    serr); E0[n − lo]: the positions' bound."""
    for lo2 in range(lo, hi, SUBBLOCK):  # the bounds and each group's inputs in the cache
        hi2 = min(hi, lo2 + SUBBLOCK)
        inv = E0[lo2 - lo:hi2 - lo]
        m0r, m1r, m2r, E0r, E1r, E2r = m[0], m[1], m[2], E[0], E[1], E[2]
        for d in range(U.shape[0]):  # 1/Ω in inv until the end (`_rate_scale`)
            _rate_scale_block(U[d, 1], U[d, 2], per[d], inv, d == 0, lo2, hi2)
        _bounds_start_block(m0, inv, m0r, m1r, m2r, E0r, E1r, E2r, cond, lo2, hi2)
        for g in range(ops.shape[0]):
            op, i1, i2, i3, i4 = ops[g, 0], ops[g, 1], ops[g, 2], ops[g, 3], ops[g, 4]
            f0, f1, f2, f3, f4, f5 = fl[g, 0], fl[g, 1], fl[g, 2], fl[g, 3], fl[g, 4], fl[g, 5]
            f11, f12, f13, f14, f15, f16, f17 = fl[g, 11], fl[g, 12], fl[g, 13], fl[g, 14], \
                fl[g, 15], fl[g, 16], fl[g, 17]
            still = ops[g, 7]
            if op == DRIVER:
                _driver_block_rates(T, Q[0], i2, f0, f1, U[i3, 1], U[i3, 2], f3, L, eps, inv,
                                    m0r, m1r, m2r, E0r, E1r, E2r, cond, Q[1, i2, 0],
                                    Q[1, i2, 1], Q[1, i2, 2], Q[2, i2, 0], Q[2, i2, 1],
                                    Q[2, i2, 2], lo2, hi2)
            elif op == RRR:
                rrr_rate = (Q, T, i1, f0, f1, i2, f2, f3, i3, i4, f12, f13, f14, f15, f16, f17,
                        unreliable, L, eps, inv, m0r, m1r, m2r, E0r, E1r, E2r, cond,
                        Q[1, i3, 0], Q[1, i3, 1], Q[1, i3, 2], Q[2, i3, 0], Q[2, i3, 1],
                        Q[2, i3, 2], Q[1, i4, 0], Q[1, i4, 1], Q[1, i4, 2], Q[2, i4, 0],
                        Q[2, i4, 1], Q[2, i4, 2], lo2, hi2)
                if still == 1:  # as in `fused_positions`
                    _rrr_block_rates(None, Q, *rrr_rate)
                elif still == 2:
                    _rrr_block_rates(Q, None, *rrr_rate)
                else:
                    _rrr_block_rates(Q, Q, *rrr_rate)
            else:
                rrp_rate = (Q, T, i1, f0, f1, i2, f2, f3, f4, f5, f11, f12, f13, i3, i4, unreliable,
                        L, eps, inv, m0r, m1r, m2r, E0r, E1r, E2r, cond, Q[1, i3, 0],
                        Q[1, i3, 1], Q[1, i3, 2], Q[2, i3, 0], Q[2, i3, 1], Q[2, i3, 2],
                        Q[1, i4, 0], Q[1, i4, 1], Q[1, i4, 2], Q[2, i4, 0], Q[2, i4, 1],
                        Q[2, i4, 2], lo2, hi2)
                if still == 1:
                    _rrp_block_rates(None, Q, *rrp_rate)
                elif still == 2:
                    _rrp_block_rates(Q, None, *rrp_rate)
                else:
                    _rrp_block_rates(Q, Q, *rrp_rate)
        _relative_block(m1r, m2r, E0r, E1r, E2r, eps, plain, weighted, err, serr, inv, lo2,
                        hi2)


@_rows
def _rate_scale_block(u1, u2, per, top, first, lo, hi):
    """`_rate_scale` of one driver at order 2 on the block lo … hi − 1 (u1, u2: its first and
    second Taylor coefficients), raising top[n − lo] (set when `first`)."""
    for n in range(lo, hi):
        k, j = _at(n), _at(n - lo)
        t = 0.0 if first else top[j]
        v = abs(u1[k]) / per
        t = v if v > t else t
        v = math.sqrt(abs(u2[k]) / per)
        top[j] = v if v > t else t


@_rows
def _bounds_start_block(m0, inv, m0r, m1r, m2r, E0r, E1r, E2r, cond, lo, hi):
    """The error bounds' start on a block (`precision.ErrorBudget`): sizes m0 (the drawing's
    coordinates), 0, 0, bounds 0, the condition numbers cond[n] 1 (the caller's array need not
    be filled); inv[j]: Ω there, 1/Ω here (Ω = 1 where every rate is 0)."""
    for j in range(hi - lo):
        i = _at(j)
        t = inv[i]
        inv[i] = 1.0 / (t if t > 0.0 else 1.0)
        m0r[i], m1r[i], m2r[i], E0r[i], E1r[i], E2r[i] = m0, 0.0, 0.0, 0.0, 0.0, 0.0
        cond[_at(lo + j)] = 1.0


@_rows
def _relative_block(m1, m2, E0, E1, E2, eps, plain, weighted, err, serr, pos, lo, hi):
    """`relative_errors` at order 2 on the block lo … hi − 1: with the weights `plain` into
    err[n], `weighted` into serr[n]; the positions' bound E0 to pos[n − lo]."""
    for n in range(lo, hi):
        k, j = _at(n), _at(n - lo)
        a, b, c = E0[j], E1[j] / max(m1[j], 1.0), E2[j] / max(m2[j], 1.0)
        err[k] = _worse(_worse(_worse(0.0, a * plain[0]), b * plain[1]), c * plain[2]) + eps
        serr[k] = _worse(_worse(_worse(0.0, a * weighted[0]), b * weighted[1]),
                         c * weighted[2]) + eps
        pos[j] = a
