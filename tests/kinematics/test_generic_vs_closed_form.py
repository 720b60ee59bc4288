"""Second-method check of the solver: every closed-form group kind against the generic path.

The solver has two ways to every answer. Positions: the closed forms of the dyads and one-link
groups (RRR, RRP, rod-in-slot, RPR, slotted-lever) or Newton's method on the group's constraint
equations, started by continuation from the design position. Derivatives: the hand-written RRR
fast path (`GroupSolver._der_RRR`) or the generic linear solve on the group Jacobian built from
jets (`derivatives_generic`). Random mechanisms of each kind are solved both ways and must agree
to 1e-9 of the length scale (times ω, ω²).
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork import Status
from linkwork.kinematics import groups, solver
from linkwork.kinematics.groups import GroupSolver, derivatives_generic

RTOL = 1e-9
MAX_CONDITION = 1e3
PATH_CONDITION = 50.0
NEWTON_TOL = 1e-14
SEEDS = range(6)


def _pt(p):
    return f"[{float(p[0])!r}, {float(p[1])!r}]"


def _text(points, links, joints, driver="O", reference=None, speed="1.7 rad/s"):
    out = ['name = "random"', "[points]"]
    out += [f"{k} = {_pt(v)}" for k, v in points.items()]
    out += ["[links]"] + [f"{k} = [{', '.join(chr(34) + p + chr(34) for p in v)}]" for k, v in links.items()]
    out += ["[joints]"] + [f"{k} = {{ {v} }}" for k, v in joints.items()]
    out += ["[driver]", f'joint = "{driver}"', f'speed = "{speed}"']
    if reference:
        out.append(f'reference = "{reference}"')
    return "\n".join(out) + "\n"


def _rev(a, b, point=None):
    return f'type = "revolute", links = ["{a}", "{b}"]' + (f', point = "{point}"' if point else "")


def _slide(kind, a, b, axis, point=None):
    return (f'type = "{kind}", links = ["{a}", "{b}"], axis = {_pt(axis)}'
            + (f', point = "{point}"' if point else ""))


def _far_apart(pts, pairs, minimum=0.2):
    return all(np.hypot(*(np.subtract(pts[p], pts[q]))) > minimum for p, q in pairs)


def _points(rng, names, pairs, scale):
    while True:
        pts = {n: rng.uniform(-1, 1, 2) for n in names}
        pts["O"] = np.zeros(2)
        if _far_apart(pts, pairs):
            return {k: v * scale for k, v in pts.items()}


# ---------------------------------------------------------------------------- random mechanisms
def four_bar(rng, scale):
    P = _points(rng, ["O", "A", "B", "D", "C"], [("O", "A"), ("A", "B"), ("B", "D"), ("O", "D")], scale)
    return _text(P, dict(frame=["O", "D"], crank=["O", "A"], coupler=["A", "B", "C"], rocker=["B", "D"]),
                 dict(O=_rev("frame", "crank"), A=_rev("crank", "coupler"), B=_rev("coupler", "rocker"),
                      D=_rev("rocker", "frame")))


def _axis(rng):
    a = rng.uniform(0, np.pi)
    return np.array([np.cos(a), np.sin(a)])


def rrp(rng, scale):
    """Crank, rod and a block on a frame guide of random direction and offset: RRP dyad."""
    while True:
        P = _points(rng, ["O", "A", "B", "C"], [("O", "A"), ("A", "B"), ("A", "C")], scale)
        ax = _axis(rng)
        if abs(ax @ (P["B"] - P["A"])) > 0.3 * np.hypot(*(P["B"] - P["A"])):
            break
    return _text(P, dict(frame=["O"], crank=["O", "A"], rod=["A", "B", "C"], block=["B"]),
                 dict(O=_rev("frame", "crank"), A=_rev("crank", "rod"), B=_rev("rod", "block"),
                      guide=_slide("prismatic", "frame", "block", ax, "B")))


def rod_in_slot(rng, scale):
    """Crank and rod whose end B is a pin in a straight slot of the frame: one-link group."""
    while True:
        P = _points(rng, ["O", "A", "B", "C"], [("O", "A"), ("A", "B"), ("A", "C")], scale)
        ax = _axis(rng)
        if abs(ax @ (P["B"] - P["A"])) > 0.3 * np.hypot(*(P["B"] - P["A"])):
            break
    return _text(P, dict(frame=["O"], crank=["O", "A"], rod=["A", "B", "C"]),
                 dict(O=_rev("frame", "crank"), A=_rev("crank", "rod"),
                      B=_slide("slot", "frame", "rod", ax)))


def _lever_geometry(rng, scale):
    """Crank O–A, lever pivot B, slot line through A at a random offset from B."""
    while True:
        P = _points(rng, ["O", "A", "B", "T"], [("O", "A"), ("O", "B"), ("A", "B"), ("B", "T")], scale)
        ax = _axis(rng)
        offset = abs(ax[0] * (P["A"] - P["B"])[1] - ax[1] * (P["A"] - P["B"])[0])
        if offset < 0.5 * np.hypot(*(P["A"] - P["B"])):
            return P, ax


def rpr(rng, scale):
    """Block pinned on the crank at A, sliding in the lever pivoted at B: RPR dyad."""
    P, ax = _lever_geometry(rng, scale)
    return _text(P, dict(frame=["O", "B"], crank=["O", "A"], block=["A"], lever=["B", "T"]),
                 dict(O=_rev("frame", "crank"), A=_rev("crank", "block"),
                      slot=_slide("prismatic", "lever", "block", ax, "A"), B=_rev("lever", "frame")))


def slotted_lever(rng, scale):
    """The crank's pin A runs in a straight slot of the lever pivoted at B: one-link group."""
    P, ax = _lever_geometry(rng, scale)
    return _text(P, dict(frame=["O", "B"], crank=["O", "A"], lever=["B", "T"]),
                 dict(O=_rev("frame", "crank"), slot=_slide("slot", "lever", "crank", ax, "A"),
                      B=_rev("lever", "frame")))


KINDS = {"RRR": four_bar, "RRP": rrp, "rod-in-slot": rod_in_slot, "RPR": rpr,
         "slotted-lever": slotted_lever}


# ---------------------------------------------------------------------------- both ways
def _generic_kind(mech, group):
    return ("driver", {}) if group.drivers and group.size == 1 else ("generic", {})


def _solve(text, u, *, generic_positions=False, generic_derivatives=False, monkeypatch):
    solver.plan.cache_clear()
    with monkeypatch.context() as mp:
        # the two paths are compared as they compute; near a singular position each would be
        # re-solved in extended precision (`precision.polish`), the same way for both
        mp.setattr(solver, "polishable", lambda mech: False)
        if generic_positions:
            mp.setattr(groups, "_classify", _generic_kind)
            # Newton stops at the first iterate within NEWTON_TOL·L (1e-12), leaving up to
            # ~1e-12·L·condition in the positions and ~condition² times that in accelerations;
            # a tighter stop (still well above rounding, ~1e-15·L) lets the two methods be
            # compared at 1e-9
            mp.setattr(groups, "NEWTON_TOL", NEWTON_TOL)
        if generic_derivatives:
            def generic(self, state, ok):
                cond = derivatives_generic(state, self.group, ok)
                if state.budget is not None:
                    state.budget.add(state, self, cond)
                return cond

            mp.setattr(GroupSolver, "derivatives", generic)
        mech = linkwork.load_text(text)
        kinds = [s.kind for s in solver.plan(mech)]
        sol = linkwork.solve(mech, u)
    solver.plan.cache_clear()
    return mech, kinds, sol


def _inputs(rng, mech, n=40):
    """Random inputs that continuation reaches from the design position without passing near a
    singular position: within the input interval around the design where the closed form's
    condition stays below PATH_CONDITION (scanned in steps of 0.25° over ±180°). Near-singular
    passages are left out: there both paths lose digits in proportion to the condition, and the
    comparison would test the conditioning rather than the two methods."""
    u0 = mech.driver_input_at_design(mech.drivers[0])
    grid = np.radians(np.arange(-180.0, 180.01, 0.25))
    sol = linkwork.solve(mech, u0 + grid, order=1)
    good = (sol.status == Status.OK) & (sol.condition < PATH_CONDITION)
    mid = len(grid) // 2
    if not good[mid]:
        return None  # the drawing itself is near a singular position
    bad_up, bad_down = np.flatnonzero(~good[mid:]), np.flatnonzero(~good[:mid + 1][::-1])
    hi = grid[mid + bad_up[0] - 1] if len(bad_up) else grid[-1]
    lo = grid[mid - bad_down[0] + 1] if len(bad_down) else grid[0]
    return u0 + np.concatenate([[0.0], rng.uniform(lo, hi, n)])


def _compare(mech, a, b, ok):
    L = mech.length_scale
    w = abs(mech.drivers[0].law.speed)
    for p in mech.points:
        pa, pb = a.point(p), b.point(p)
        np.testing.assert_allclose(pb.position[ok], pa.position[ok], rtol=0, atol=RTOL * L, err_msg=p)
        np.testing.assert_allclose(pb.velocity[ok], pa.velocity[ok], rtol=RTOL, atol=RTOL * L * w,
                                   err_msg=p)
        np.testing.assert_allclose(pb.acceleration[ok], pa.acceleration[ok], rtol=RTOL,
                                   atol=RTOL * L * w * w, err_msg=p)
    for ln in mech.moving_links:
        la, lb = a.link(ln), b.link(ln)
        np.testing.assert_allclose(np.angle(np.exp(1j * (lb.angle - la.angle)))[ok], 0.0, atol=RTOL,
                                   err_msg=ln)
        np.testing.assert_allclose(lb.omega[ok], la.omega[ok], rtol=RTOL, atol=RTOL * w, err_msg=ln)
        np.testing.assert_allclose(lb.alpha[ok], la.alpha[ok], rtol=RTOL, atol=RTOL * w * w, err_msg=ln)


def _usable(*sols):
    ok = np.ones(len(sols[0]), dtype=bool)
    for s in sols:
        # assembled and well-conditioned (the error bound of `precision` may exceed the 1e-9 of
        # an `ok` with a Newton path's residual at κ ≈ 30; the comparison itself is the check)
        ok &= (s.status != Status.UNREACHABLE) & (s.condition < MAX_CONDITION)
    return ok


@pytest.mark.parametrize("seed", SEEDS)
def test_rrr_fast_derivatives_equal_generic_jacobian_solve(seed, monkeypatch):
    """Same closed-form positions; velocities and accelerations by `_der_RRR` and by
    `derivatives_generic`."""
    rng = np.random.default_rng(seed)
    text = four_bar(rng, 10.0 ** rng.uniform(-2, 3))
    u = rng.uniform(-np.pi, np.pi, 60)  # any input: both paths start from the same positions
    mech, kinds, fast = _solve(text, u, monkeypatch=monkeypatch)
    assert kinds == ["driver", "RRR"]
    _, _, slow = _solve(text, fast.input, generic_derivatives=True, monkeypatch=monkeypatch)
    # positions are computed once, the same way
    assert np.array_equal(fast.pose_derivatives("coupler")[0], slow.pose_derivatives("coupler")[0],
                          equal_nan=True)
    ok = _usable(fast, slow)
    assert ok.sum() >= 5
    _compare(mech, fast, slow, ok)


@pytest.mark.parametrize("seed", SEEDS)
def test_rrp_fast_derivatives_equal_generic_jacobian_solve(seed, monkeypatch):
    """The RRP dyad's compiled rates (`kernels.rrp_rates`) against `derivatives_generic`, from
    the same closed-form positions."""
    rng = np.random.default_rng(500 + seed)
    ok = np.zeros(0, dtype=bool)
    while ok.sum() < 5:
        text = rrp(rng, 10.0 ** rng.uniform(-2, 3))
        u = rng.uniform(-np.pi, np.pi, 60)
        mech, kinds, fast = _solve(text, u, monkeypatch=monkeypatch)
        assert kinds == ["driver", "RRP"]
        _, _, slow = _solve(text, fast.input, generic_derivatives=True, monkeypatch=monkeypatch)
        ok = _usable(fast, slow)
    for link in ("rod", "block"):
        assert np.array_equal(fast.pose_derivatives(link)[0], slow.pose_derivatives(link)[0],
                              equal_nan=True)
    _compare(mech, fast, slow, ok)


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("kind", sorted(KINDS))
def test_closed_form_group_equals_generic_newton(kind, seed, monkeypatch):
    """Closed-form positions (and RRR's fast derivatives) against Newton's method plus the
    generic Jacobian solve, at random inputs over a whole turn of the crank."""
    rng = np.random.default_rng(1000 + seed)
    u = None
    while u is None:
        text = KINDS[kind](rng, 10.0 ** rng.uniform(-2, 3))
        u = _inputs(rng, linkwork.load_text(text))
    mech, kinds, closed = _solve(text, u, monkeypatch=monkeypatch)
    assert kinds == ["driver", kind]
    _, gkinds, newton = _solve(text, u, generic_positions=True, generic_derivatives=True,
                               monkeypatch=monkeypatch)
    assert gkinds == ["driver", "generic"]
    # Newton reaches from the design position only what continuation reaches; where it does, the
    # closed form must have assembled too
    assert not ((newton.status != Status.UNREACHABLE) & (closed.status == Status.UNREACHABLE)).any()
    ok = _usable(closed, newton)
    assert ok[0]  # the design position itself
    _compare(mech, closed, newton, ok)


def test_library_mechanisms_closed_forms_equal_generic_newton(monkeypatch):
    """The library's closed-form mechanisms, over their whole turn."""
    for name in ["crank-rocker", "slider-crank-offset", "oscillating-crank-slotted-lever",
                 "whitworth-quick-return"]:
        text = linkwork.io.files.resolve(f"library:{name}")[1]
        mech = linkwork.load_text(text)
        u = mech.driver_input_at_design(mech.drivers[0]) + np.radians(np.arange(0, 360, 7.5))
        _, kinds, closed = _solve(text, u, monkeypatch=monkeypatch)
        assert "generic" not in kinds
        _, _, newton = _solve(text, u, generic_positions=True, generic_derivatives=True,
                              monkeypatch=monkeypatch)
        ok = _usable(closed, newton)
        assert ok.all(), name
        _compare(mech, closed, newton, ok)
