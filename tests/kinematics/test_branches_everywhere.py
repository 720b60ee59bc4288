"""Assembly branches below Newton-solved groups (`kinematics.branches`).

Hart's straight line from an arbitrary four-bar (Pöschl §66c, digest 002b): E is where the
lines O₁O₂ and AB cross; the circles through E, A, O₁ and through E, B, O₂ meet again at F;
the tangents to them at F cut the cranks at C and D; the dyad C–Q–D with CQ = DF and DQ = CF,
on the isosceles-trapezoid branch (Q the mirror of F in the perpendicular bisector of CD),
makes Q run exactly on a line perpendicular to O₁O₂. The dyad passes change points (F on the
line CD), where the design's sign would turn the trapezoid into the parallelogram Q = C + D − F
and Q leaves the line, its velocity jumping. Checked here with the four-bar solved in closed
form and by Newton's method (the case the change points were not searched for).
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork import Status
from linkwork.kinematics import groups, solver
from mechanism_texts import mechanism_text, revolute


def _circle(p, q, r):
    """Centre of the circle through p, q, r."""
    (ax, ay), (bx, by), (cx, cy) = p, q, r
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    return np.array([((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay)
                      + (cx * cx + cy * cy) * (ay - by)) / d,
                     ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx)
                      + (cx * cx + cy * cy) * (bx - ax)) / d])


def _cross_lines(p1, d1, p2, d2):
    t = np.linalg.solve(np.array([d1, -d2]).T, p2 - p1)
    return p1 + t[0] * d1


def hart_text():
    O1, A, B, O2 = (np.array(p, dtype=float) for p in ((0, 0), (10, 25), (45, 40), (50, 0)))
    E = _cross_lines(O1, O2 - O1, A, B - A)
    ca, cb = _circle(E, A, O1), _circle(E, B, O2)
    axis = (cb - ca) / np.hypot(*(cb - ca))
    F = ca + 2 * np.dot(E - ca, axis) * axis - (E - ca)  # E mirrored in the line of centres
    C = _cross_lines(F, np.array([-(F - ca)[1], (F - ca)[0]]), O1, A - O1)
    D = _cross_lines(F, np.array([-(F - cb)[1], (F - cb)[0]]), O2, B - O2)
    u = (D - C) / np.hypot(*(D - C))
    Q = F - 2 * np.dot(F - (C + D) / 2, u) * u
    pts = dict(O1=O1, A=A, B=B, O2=O2, C=C, D=D, Q=Q)
    links = dict(frame=["O1", "O2"], crank1=["O1", "A", "C"], coupler=["A", "B"],
                 crank2=["O2", "B", "D"], cq=["C", "Q"], dq=["D", "Q"])
    joints = [revolute("O1", "frame", "crank1"), revolute("A", "crank1", "coupler"),
              revolute("B", "coupler", "crank2"), revolute("O2", "crank2", "frame"),
              revolute("C", "crank1", "cq"), revolute("D", "crank2", "dq"),
              revolute("Q", "cq", "dq")]
    return mechanism_text(name="Hart's straight line", points=pts, links=links, joints=joints,
                          driver="O1", speed="1 rad/s"), float(Q[0])


@pytest.mark.parametrize("newton", [False, True])
def test_hart_straight_line_keeps_its_branch(newton, monkeypatch):
    text, x_line = hart_text()
    classify = groups._classify
    if newton:  # the four-bar's dyad by Newton's method, as a group without a closed form
        monkeypatch.setattr(groups, "_classify", lambda mech, g: ("generic", {})
                            if set(g.links) == {"coupler", "crank2"} else classify(mech, g))
    solver.plan.cache_clear()
    try:
        mech = linkwork.load_text(text)
        kinds = [s.kind for s in solver.plan(mech)]
        assert kinds == ["driver", "generic" if newton else "RRR", "RRR"]
        h = np.radians(0.25)
        u0 = mech.driver_input_at_design(mech.drivers[0])
        u = u0 + h * np.arange(1441)  # a whole turn of the crank (it turns fully: Grashof)
        sol = linkwork.solve(mech, u)
    finally:
        solver.plan.cache_clear()
    assert (sol.status != Status.UNREACHABLE).all()
    Q = sol.point("Q")
    # on the line x = x_Q of the drawing, perpendicular to O1O2, all the way round
    np.testing.assert_allclose(Q.position[:, 0], x_line, atol=1e-7 * 50)
    # no jump: the velocity is the derivative of the positions (central differences, O(h²))
    fd = (Q.position[2:] - Q.position[:-2]) / (2 * h)
    ok = (sol.status[1:-1] == Status.OK) & (sol.status[2:] == Status.OK) & (sol.status[:-2] == Status.OK)
    scale = np.abs(Q.velocity[1:-1]).max(axis=1) + 1.0
    err = np.abs(Q.velocity[1:-1] - fd).max(axis=1) / scale
    assert (err[ok] < 1e-3).all()


def triad_text():
    """A crank O2A drives link AR of a triad: ternary PQR held by the rockers O4P and O6Q (an
    Assur group of class III, solved by Newton's method); the crank rocks between two limits."""
    pts = dict(O2=(0, 0), O4=(40, -5), O6=(60, 30), A=(0, 12), R=(22, 28), P=(38, 12), Q=(52, 40))
    links = dict(frame=["O2", "O4", "O6"], crank=["O2", "A"], ar=["A", "R"], tri=["P", "Q", "R"],
                 r4=["O4", "P"], r6=["O6", "Q"])
    joints = [revolute("O2", "frame", "crank"), revolute("A", "crank", "ar"),
              revolute("R", "ar", "tri"), revolute("P", "tri", "r4"), revolute("O4", "r4", "frame"),
              revolute("Q", "tri", "r6"), revolute("O6", "r6", "frame")]
    return mechanism_text(name="Stephenson six-bar with a triad", points=pts, links=links,
                          joints=joints, driver="O2", speed="1 rad/s")


def test_limit_samples_of_a_triad_come_with_their_pose():
    mech = linkwork.load_text(triad_text())
    assert [s.kind for s in solver.plan(mech)] == ["driver", "generic"]
    sol = linkwork.whole_motion(mech)
    lo, hi = sol.input.min(), sol.input.max()
    at_limit = (sol.input == lo) | (sol.input == hi)
    assert at_limit.sum() >= 2
    # the limit samples: singular (a fold of the triad), not unreachable, and their pairs closed
    assert (sol.status[at_limit] == Status.SINGULAR).all()
    assert (sol.status != Status.UNREACHABLE).all()
    L = mech.length_scale
    for j in mech.joints:
        a, b = j.links
        P = mech.points[j.point]
        gap = np.hypot(*(sol.point_on(a, P).position - sol.point_on(b, P).position).T)
        assert (gap[at_limit] <= 1e-7 * L).all(), j.name


def test_galloway_kite_passes_its_fold_without_a_jump():
    """Galloway's kite (Rosenauer §100): crank = frame = 40, coupler = rocker = 20. At crank
    angle 0 the crank pin A lies on the rocker pivot O4; the line A–O4 turns over there, so the
    coupler's hinge B keeps its place only by changing sides of it. B must move on continuously
    (its velocity the derivative of its path), the fold sample itself marked, never an `ok`
    sample carrying the other assembly."""
    from mechanism_texts import four_bar_from_lengths

    mech = linkwork.load_text(four_bar_from_lengths(40, 40, 20, 20, 30, speed="1 rad/s",
                                                    links=("frame", "crank", "coupler", "rocker")))
    h = np.radians(0.25)
    u = np.radians(-10.0) + h * np.arange(81)  # −10° … +10°, through the fold at 0
    sol = linkwork.solve(mech, u, velocities=np.ones(u.shape))
    fold = np.abs(u) < 1e-12
    # the fold sample is marked (its rates NaN: B may be anywhere on its circle there)
    assert fold.sum() == 1 and sol.status[fold][0] != Status.OK
    assert np.isnan(sol.link("rocker").omega[fold]).all()
    B = sol.point("B")
    ok = sol.status == Status.OK
    both = ok[1:] & ok[:-1]
    step = np.hypot(*np.diff(B.position, axis=0).T)
    speed = np.hypot(*B.velocity.T)
    assert (step[both] <= 1.5 * h * np.maximum(speed[1:], speed[:-1])[both] + 1e-9).all()
    fd = (B.position[2:] - B.position[:-2]) / (2 * h)
    inner = ok[1:-1] & ok[2:] & ok[:-2]
    np.testing.assert_allclose(B.velocity[1:-1][inner], fd[inner], atol=1e-3 * 20)
