"""Constraint equations of every pair and driver, written once at position level over jets.

Link poses are (x, y, θ): a point with design coordinates s is at (x, y) + R(θ)·s, since every
link's own coordinates coincide with the frame's in the design position. Evaluating these
residuals on jets yields the constraint equations' time derivatives exactly; `groups.py` uses
them for Newton's method and for the velocity/acceleration/jerk linear solves.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from ..model import CircularSlot, Driver, Gear, Joint, Mechanism, Prismatic, Revolute, Slot
from . import contact, intermittent
from .jet import Jet

# pose(link) -> (x, y, θ, cos θ, sin θ) jets
PoseFn = Callable[[str], tuple[Jet, Jet, Jet, Jet, Jet]]


def point(pose: PoseFn, link: str, s: np.ndarray) -> tuple[Jet, Jet]:
    x, y, _, c, sn = pose(link)
    return x + c * s[0] - sn * s[1], y + sn * s[0] + c * s[1]


def rotate(pose: PoseFn, link: str, v: np.ndarray) -> tuple[Jet, Jet]:
    _, _, _, c, sn = pose(link)
    return c * v[0] - sn * v[1], sn * v[0] + c * v[1]


def joint_residuals(mech: Mechanism, j: Joint, pose: PoseFn) -> list[Jet]:
    """Residuals (zero when the pair is closed), each in units of length."""
    if contact.is_higher(j):
        return contact.residuals(mech, j, pose, point, rotate)
    if intermittent.is_intermittent(j):
        return intermittent.residuals(mech, j, pose, point, rotate)
    if isinstance(j, Gear):
        return [_gear(mech, j, pose)]
    P = mech.points[j.point]
    a, b = j.links
    if isinstance(j, Revolute):
        xa, ya = point(pose, a, P)
        xb, yb = point(pose, b, P)
        return [xb - xa, yb - ya]
    if isinstance(j, (Prismatic, Slot)):
        nx, ny = rotate(pose, a, np.array([-j.axis[1], j.axis[0]]))
        xa, ya = point(pose, a, P)
        xb, yb = point(pose, b, P)
        res = [nx * (xb - xa) + ny * (yb - ya)]
        if isinstance(j, Prismatic):
            # the block keeps its angle to the guide; scaled to length units
            res.append((pose(b)[2] - pose(a)[2]) * mech.length_scale)
        return res
    if isinstance(j, CircularSlot):
        R = j.radius(mech)
        xk, yk = point(pose, a, mech.points[j.center])
        xb, yb = point(pose, b, P)
        dx, dy = xb - xk, yb - yk
        return [(dx * dx + dy * dy - R * R) * (0.5 / R)]
    raise TypeError(j)  # pragma: no cover


def rack_sense(mech: Mechanism, g: Gear) -> float:
    """+1 or −1: rack displacement per pinion turn (relative to the carrier), divided by r."""
    guide = mech.rack_guide(g)
    centre = mech.points[mech.wheel_centre(g, g.links[0])]
    u = guide.axis
    n = np.array([-u[1], u[0]])
    probe = mech.points[g.point] if g.point else mech.points[guide.point]
    m = n if np.dot(probe - centre, n) >= 0 else -n
    return float(np.dot(np.array([-m[1], m[0]]), u))


def _gear(mech: Mechanism, g: Gear, pose: PoseFn) -> Jet:
    th_c = pose(g.carrier)[2]
    d1 = pose(g.links[0])[2] - th_c
    r1, r2 = g.radii
    if g.gear_kind == "rack":
        guide = mech.rack_guide(g)
        ux, uy = rotate(pose, g.carrier, guide.axis)
        xr, yr, *_ = pose(g.links[1])
        xc, yc, *_ = pose(g.carrier)
        s = ux * (xr - xc) + uy * (yr - yc)
        return s - d1 * (r1 * rack_sense(mech, g))
    d2 = pose(g.links[1])[2] - th_c
    # pitch circles roll: equal arc lengths, opposite senses for an external pair
    return d1 * r1 + d2 * (r2 if g.gear_kind == "external" else -r2)


def driver_residual(mech: Mechanism, d: Driver, pose: PoseFn, value: Jet) -> Jet:
    """Driver constraint: the pair's relative angle or slide equals the input."""
    j = mech.joint(d.joint)
    if isinstance(j, Prismatic):
        ux, uy = rotate(pose, d.base, j.axis)
        xb, yb, *_ = pose(d.driven)
        xa, ya, *_ = pose(d.base)
        return ux * (xb - xa) + uy * (yb - ya) - value
    rel = pose(d.driven)[2] - pose(d.base)[2]
    return (rel - (value - mech.driver_input_at_design(d))) * mech.length_scale


# ---------------------------------------------------------------------------- as arrays
class PairTable:
    """The residuals and Jacobian of a group of lower pairs (revolute, prismatic, slot,
    circular slot, gear pairs of two wheels) and drivers, as NumPy array operations on tables
    built once per group: the same equations as `joint_residuals` and `driver_residual`, with
    their derivatives written out, for Newton's method and the continuation's tangents, which
    evaluate a group hundreds of times on a handful of samples (where the jets' per-call
    Python work is most of the time). The jets stay the reference
    (tests/kinematics/test_pair_tables.py holds the two to each other and to finite
    differences).

    Columns: (x, y, θ) of `links` (Q rows: the group's unknown links first, then the known
    links its pairs reach), then one per driver input of the group. Rows: as `groups`
    stacks them (each pair's rows in the group's order, a wedge pair's first row only, then the
    drivers in the mechanism's order)."""

    def __init__(self, mech: Mechanism, group_links: tuple[str, ...], joints: tuple[str, ...],
                 drivers: tuple[str, ...], wedge_pairs: tuple[str, ...], row_of) -> None:
        self.L = mech.length_scale
        slot: dict[str, int] = {}
        for ln in group_links:
            slot.setdefault(ln, len(slot))
        self.k = len(group_links)

        def col(link: str, c: int) -> int:
            return 3 * slot.setdefault(link, len(slot)) + c

        points: dict[tuple, int] = {}

        def pt(link: str, s) -> int:
            key = (link, float(s[0]), float(s[1]))
            if key not in points:
                col(link, 0)
                points[key] = len(points)
            return points[key]

        # per kind: (row, point/link indices …); constant Jacobian entries (row, col, value)
        rev, pri, circ, rows_const = [], [], [], []
        fixed: list[tuple[int, int, float]] = []
        gears: list[tuple[int, tuple, tuple]] = []
        row = 0
        for jn in joints:
            j = mech.joint(jn)
            a, b = j.links
            if isinstance(j, Revolute):
                P = mech.points[j.point]
                rev.append((row, pt(a, P), pt(b, P), col(a, 0), col(b, 0)))
                fixed += [(row, col(b, 0), 1.0), (row, col(a, 0), -1.0),
                          (row + 1, col(b, 1), 1.0), (row + 1, col(a, 1), -1.0)]
                row += 2
            elif isinstance(j, (Prismatic, Slot)):
                P = mech.points[j.point]
                n0 = (-float(j.axis[1]), float(j.axis[0]))
                pri.append((row, pt(a, P), pt(b, P), col(a, 0), col(b, 0), n0))
                row += 1
                if isinstance(j, Prismatic) and jn not in wedge_pairs:
                    rows_const.append((row, col(b, 2), col(a, 2)))
                    fixed += [(row, col(b, 2), self.L), (row, col(a, 2), -self.L)]
                    row += 1
            elif isinstance(j, CircularSlot):
                R = j.radius(mech)
                circ.append((row, pt(a, mech.points[j.center]), pt(b, mech.points[j.point]),
                             col(a, 0), col(b, 0), R))
                row += 1
            else:  # a gear pair of two wheels: linear in the angles
                r1, r2 = j.radii
                r2 = r2 if j.gear_kind == "external" else -r2
                gears.append((row, (col(a, 2), col(b, 2), col(j.carrier, 2)), (r1, r2)))
                fixed += [(row, col(a, 2), r1), (row, col(b, 2), r2),
                          (row, col(j.carrier, 2), -(r1 + r2))]
                row += 1
        self.drivers: list[tuple] = []
        for d in drivers:
            col(d.driven, 0), col(d.base, 0)
        n_links = len(slot)  # the inputs' columns follow the links'
        for i, d in enumerate(drivers):
            dj = mech.joint(d.joint)
            u_col = 3 * n_links + i
            if isinstance(dj, Prismatic):
                self.drivers.append((row, "prismatic", col(d.driven, 0), col(d.base, 0), d.joint,
                                     (float(dj.axis[0]), float(dj.axis[1])), 0.0))
                fixed.append((row, u_col, -1.0))
            else:
                self.drivers.append((row, "revolute", col(d.driven, 0), col(d.base, 0), d.joint,
                                     None, mech.driver_input_at_design(d)))
                fixed += [(row, col(d.driven, 2), self.L), (row, col(d.base, 2), -self.L),
                          (row, u_col, -self.L)]
            row += 1
        self.rows = row
        self.links = [None] * len(slot)
        for ln, i in slot.items():
            self.links[i] = ln
        self.rows_q = np.array([row_of[ln] for ln in self.links], dtype=np.intp)
        self.cols = 3 * len(slot) + len(drivers)
        pts = sorted(points.items(), key=lambda kv: kv[1])
        self.pt_link = np.array([slot[k[0]] for k, _ in pts], dtype=np.intp)
        self.s0 = np.array([k[1] for k, _ in pts])
        self.s1 = np.array([k[2] for k, _ in pts])
        self.J0 = np.zeros((self.rows, self.cols))
        for r, c, v in fixed:
            self.J0[r, c] += v
        # the entries that change with the poses, in the order `evaluate` lists their values
        # (complex values count twice: x then y)
        var: list[tuple[int, int]] = []

        def arr(items, i):
            return np.array([it[i] for it in items], dtype=np.intp)

        def pairs(r0, c):  # rows r0 and r0 + 1 of column c, per pair: x then y
            return [rc for a, b in zip(r0, c) for rc in ((a, b), (a + 1, b))]

        def across(r0, c):  # columns c and c + 1 of row r0, per pair
            return [rc for a, b in zip(r0, c) for rc in ((a, b), (a, b + 1))]

        # every pair's point difference d = (point on b) − (point on a), at once
        dA, dB = [], []
        self.rev = None
        if rev:
            r0, pa, pb, ca, cb = (arr(rev, i) for i in range(5))
            self.rev = (np.stack([r0, r0 + 1], axis=1).ravel(), len(dA), pa, pb)
            dA += list(pa)
            dB += list(pb)
            var += pairs(r0, cb + 2) + pairs(r0, ca + 2)
        self.pri = None
        if pri:
            r0, pa, pb, ca, cb = (arr(pri, i) for i in range(5))
            n0 = np.array([it[5] for it in pri])
            self.pri = (r0, len(dA), pa, pb, ca // 3, n0[:, 0], n0[:, 1])
            dA += list(pa)
            dB += list(pb)
            var += across(r0, cb) + across(r0, ca) + list(zip(r0, cb + 2)) + list(zip(r0, ca + 2))
        self.circ = None
        if circ:
            r0, pk, pp, ca, cb = (arr(circ, i) for i in range(5))
            R = np.array([it[5] for it in circ])
            self.circ = (r0, len(dA), pk, pp, R)
            dA += list(pk)
            dB += list(pp)
            var += across(r0, cb) + across(r0, ca) + list(zip(r0, cb + 2)) + list(zip(r0, ca + 2))
        self.dA, self.dB = np.array(dA, dtype=np.intp), np.array(dB, dtype=np.intp)
        self.gears = gears
        self.prismatic_angles = rows_const
        for r, kind, cd, cb, _, axis, _ in self.drivers:
            if kind == "prismatic":
                var += [(r, cd), (r, cd + 1), (r, cb), (r, cb + 1), (r, cb + 2)]
        if len(set(var)) != len(var) or any(self.J0[r, c] != 0 for r, c in var):
            raise ValueError("two terms of one equation on one coordinate")  # pragma: no cover
        self.var = np.array([r * self.cols + c for r, c in var], dtype=np.intp)

    def evaluate(self, Q0: np.ndarray, inputs: dict) -> tuple[np.ndarray, np.ndarray]:
        """Residuals (N, rows) and Jacobian (N, rows, cols) at the poses Q0 (N, Q rows, 3) and
        the driver inputs (joint -> (N,) values). Points and their differences are held as
        complex numbers x + iy, whose (x, y) pairs are a revolute pair's two rows and its
        entries in x then y (`view`): few array operations, which is what a handful of samples
        costs. Every product is of reals (NumPy's complex product fuses a·b − c·d in its
        vector loops and not in its scalar ones: a sample's digits would depend on its batch);
        sums, differences and products by ±i are exact in either."""
        P, c, sn, Rs, tR, D = self._points(Q0)
        N, real = P.shape[0], P.dtype
        cplx = Rs.dtype
        r = np.empty((N, self.rows), dtype=real)
        vals = []
        if self.rev is not None:
            rows, at, pa, pb = self.rev
            r[:, rows] = D[:, at:at + pa.size].view(real)
            vals += [tR.take(pb, axis=1).view(real), (-tR.take(pa, axis=1)).view(real)]
        if self.pri is not None:
            r0, at, pa, pb, ta, n0x, n0y = self.pri
            d = D[:, at:at + pa.size]
            dx, dy = d.real, d.imag
            ca, sa = c.take(ta, axis=1), sn.take(ta, axis=1)
            n = np.empty(ca.shape, dtype=cplx)  # the guide's normal
            nx, ny = n.real, n.imag
            nx[:] = ca * n0x - sa * n0y
            ny[:] = sa * n0x + ca * n0y
            r[:, r0] = nx * dx + ny * dy
            tb, ta_ = tR.take(pb, axis=1), tR.take(pa, axis=1)
            vals += [n.view(real), (-n).view(real), nx * tb.real + ny * tb.imag,
                     nx * dy - ny * dx - (nx * ta_.real + ny * ta_.imag)]
        for row, cb, ca in self.prismatic_angles:
            r[:, row] = (P[:, cb // 3, 2] - P[:, ca // 3, 2]) * self.L
        if self.circ is not None:
            r0, at, pk, pp, R = self.circ
            d = D[:, at:at + pk.size]
            dx, dy = d.real, d.imag
            r[:, r0] = (dx * dx + dy * dy - R * R) * (0.5 / R)
            e = np.empty(d.shape, dtype=cplx)
            ex, ey = e.real, e.imag
            ex[:], ey[:] = dx / R, dy / R
            tp, tk = tR.take(pp, axis=1), tR.take(pk, axis=1)
            vals += [e.view(real), (-e).view(real), ex * tp.real + ey * tp.imag,
                     -(ex * tk.real + ey * tk.imag)]
        for row, (c1, c2, cc), (r1, r2) in self.gears:
            th1, th2, thc = P[:, c1 // 3, 2], P[:, c2 // 3, 2], P[:, cc // 3, 2]
            r[:, row] = (th1 - thc) * r1 + (th2 - thc) * r2
        for row, kind, cd, cb, joint, axis, u0 in self.drivers:
            u = inputs[joint]
            qd, qb = P[:, cd // 3], P[:, cb // 3]
            if kind == "revolute":
                r[:, row] = (qd[:, 2] - qb[:, 2] - (u - u0)) * self.L
            else:
                cb_, sb = c[:, cb // 3], sn[:, cb // 3]
                ux, uy = cb_ * axis[0] - sb * axis[1], sb * axis[0] + cb_ * axis[1]
                dx, dy = qd[:, 0] - qb[:, 0], qd[:, 1] - qb[:, 1]
                r[:, row] = ux * dx + uy * dy - u
                vals += [ux[:, None], uy[:, None], -ux[:, None], -uy[:, None],
                         (ux * dy - uy * dx)[:, None]]
        J = np.empty((N, self.rows, self.cols), dtype=real)
        J[:] = self.J0
        if vals:
            J.reshape(N, -1)[:, self.var] = np.concatenate(vals, axis=1)
        return r, J

    def _points(self, Q0: np.ndarray) -> tuple:
        """The links' poses (N, links, 3), cos θ, sin θ, and of every point the pairs name
        R(θ)·s and ∂/∂θ of it (i·R(θ)·s), and the pairs' point differences D, complex."""
        # gathers by `take`: C order whatever Q's layout, so that the complex arrays are pairs
        P = Q0.take(self.rows_q, axis=1)
        cplx = np.result_type(P.dtype, np.complex64)
        c, sn = np.cos(P[..., 2]), np.sin(P[..., 2])
        cp, sp = c.take(self.pt_link, axis=1), sn.take(self.pt_link, axis=1)
        Rs = np.empty(cp.shape, dtype=cplx)  # R(θ)·s of every point the pairs name
        Rs.real = cp * self.s0 - sp * self.s1
        Rs.imag = sp * self.s0 + cp * self.s1
        W = _complex(P[..., 0], P[..., 1]).take(self.pt_link, axis=1) + Rs
        D = W.take(self.dB, axis=1) - W.take(self.dA, axis=1)
        return P, c, sn, Rs, Rs * 1j, D

    def quadratic(self, Q0: np.ndarray, Q1: np.ndarray) -> np.ndarray:
        """(N, rows): ½·q̇ᵀ·∇²r·q̇, the part of the residuals' second Taylor coefficient that
        the Jacobian does not give (r₂ = J·q₂ + this), at the poses Q0 with the first
        coefficients Q1 (N, Q rows, 3) of every link the pairs name; the inputs enter the
        equations linearly. A point z + R(θ)·s moves with ż + θ̇·i·R(θ)·s and bends by
        −½θ̇²·R(θ)·s; a guide's normal n turns with θ̇·i·n."""
        P, c, sn, Rs, tR, D = self._points(Q0)
        N, real = P.shape[0], P.dtype
        V = Q1.take(self.rows_q, axis=1)
        w = V[..., 2]  # θ̇ of every link
        wp = w.take(self.pt_link, axis=1)
        V1 = _complex(V[..., 0], V[..., 1]).take(self.pt_link, axis=1) + _times(tR, wp)
        bend = _times(Rs, -0.5 * wp * wp)
        D1 = V1.take(self.dB, axis=1) - V1.take(self.dA, axis=1)
        B = bend.take(self.dB, axis=1) - bend.take(self.dA, axis=1)
        out = np.zeros((N, self.rows), dtype=real)
        if self.rev is not None:
            rows, at, pa, _ = self.rev
            out[:, rows] = B[:, at:at + pa.size].view(real)
        if self.pri is not None:
            r0, at, pa, _, ta, n0x, n0y = self.pri
            sl = slice(at, at + pa.size)
            ca, sa, wa = c.take(ta, axis=1), sn.take(ta, axis=1), w.take(ta, axis=1)
            nx, ny = ca * n0x - sa * n0y, sa * n0x + ca * n0y
            d, d1, b = D[:, sl], D1[:, sl], B[:, sl]
            out[:, r0] = (nx * b.real + ny * b.imag + wa * (nx * d1.imag - ny * d1.real)
                          - 0.5 * wa * wa * (nx * d.real + ny * d.imag))
        if self.circ is not None:
            r0, at, pk, _, R = self.circ
            sl = slice(at, at + pk.size)
            d, d1, b = D[:, sl], D1[:, sl], B[:, sl]
            out[:, r0] = ((d.real * b.real + d.imag * b.imag) / R
                          + (d1.real * d1.real + d1.imag * d1.imag) * (0.5 / R))
        for row, kind, cd, cb, _, axis, _ in self.drivers:
            if kind == "prismatic":
                k, j = cb // 3, cd // 3
                ux, uy = c[:, k] * axis[0] - sn[:, k] * axis[1], sn[:, k] * axis[0] + c[:, k] * axis[1]
                dx, dy = P[:, j, 0] - P[:, k, 0], P[:, j, 1] - P[:, k, 1]
                vx, vy = V[:, j, 0] - V[:, k, 0], V[:, j, 1] - V[:, k, 1]
                wb = w[:, k]
                out[:, row] = wb * (ux * vy - uy * vx) - 0.5 * wb * wb * (ux * dx + uy * dy)
        return out


def _complex(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """x + iy (exact)."""
    z = np.empty(x.shape, dtype=np.result_type(x.dtype, np.complex64))
    z.real, z.imag = x, y
    return z


def _times(z: np.ndarray, a: np.ndarray) -> np.ndarray:
    """z·a for real a, by real products (see `PairTable.evaluate`)."""
    return _complex(z.real * a, z.imag * a)


def pair_table(mech: Mechanism, links: tuple[str, ...], joints: tuple[str, ...],
               drivers: tuple[str, ...], wedge_pairs: tuple[str, ...], row_of) -> PairTable | None:
    """The `PairTable` of a group, or None where one of its pairs is not a lower pair or a
    gear pair of two wheels (higher pairs, intermittent pairs, racks: the jets serve those)."""
    for jn in joints:
        j = mech.joint(jn)
        if contact.is_higher(j) or intermittent.is_intermittent(j) or \
                not isinstance(j, (Revolute, Prismatic, Slot, CircularSlot, Gear)) or \
                (isinstance(j, Gear) and j.gear_kind == "rack"):
            return None
    drv = tuple(d for d in mech.drivers if d.joint in drivers)
    return PairTable(mech, links, joints, drv, wedge_pairs, row_of)
