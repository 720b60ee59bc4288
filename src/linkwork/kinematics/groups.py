"""Solving one group (see `linkwork.topology.groups`) for all samples at once.

Positions: the dyads and one-link groups in closed form (circle–circle, circle–line, line through
a point), on the branch of the design position (flipped past change points: `branches`); any
other group (triads, gear groups, the
Heusinger group) by Newton's method on that group alone, batched over samples.

Derivatives: for every group, by linear solves on the group's constraint Jacobian. The k-th
Taylor coefficient of the unknown poses enters the k-th coefficient of the constraint residuals
linearly, J·q⁽ᵏ⁾/k! = −r_k, where r_k comes from evaluating the constraints on jets with the
unknown coefficient set to zero; so one code path gives velocities, accelerations and jerks.
The RRR and RRP dyads and the revolute driver, the hot path of four-bars, six-bars,
slider-cranks and Jansen's linkage, run as compiled loops (`kernels`): positions at any order, velocities and accelerations at
order 2. Every link's cos θ and sin θ are kept once in `State.T`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from math import factorial

import numpy as np

from ..model import CircularSlot, ConstantSpeed, Driver, Gear, Mechanism, Prismatic, Revolute, Slot
from ..topology import Group
from . import cam_group, contact, intermittent
from .constraints import PairTable, driver_residual, joint_residuals, pair_table
from .jet import Jet
from .kept import Kept

NEWTON_TOL = 1e-12  # relative to the mechanism's length scale
LIMIT_RESIDUAL = 1e-8  # … a pose closed this well at a limit position is returned (singular)
#: a Newton residual at most this many times ε·(the drawing's coordinates) is the rounding of
#: the equations themselves (polished samples of the library: up to 6.5; `backward_error`)
ROUNDING_RESIDUAL = 8.0
# above this the linear solve for the rates loses every digit (condition × ε ~ 1): the rates of
# such samples are NaN, not invented (the sample is singular either way)
UNRELIABLE_CONDITION = 1e14


def backward_error(mech: Mechanism, residual: np.ndarray, eps: float | None = None) -> np.ndarray:
    """Newton's final residual (a length, per sample) as the error budget takes it
    (`precision.ErrorBudget`, the group's backward error over L). A residual at the level of
    the equations' rounding (`ROUNDING_RESIDUAL`·ε·the drawing's coordinates) counts as none:
    Newton's last step leaves the exact poses rounded, as a closed form does, and the budget
    counts that rounding for every group alike (ε·m₀). The residual measured there is rounding
    noise that differs with the path Newton came along (a march carried over from a drag's
    previous frame or marched afresh, 0.3 … 3 ε·m₀ at the same sample): added to the bound it
    moved samples whose bound lies near the tolerance between ok and singular. A larger
    residual (a limit position, an over-closed group's least squares) is counted in full.
    `eps`: the unit roundoff of the arithmetic Newton ran in (double unless given; the polish
    in long double, `precision._newton`, gives its own)."""
    from .precision import EPS, coordinate_size  # (precision imports this module)

    r = residual / mech.length_scale
    with np.errstate(invalid="ignore"):
        return np.where(r <= ROUNDING_RESIDUAL * (EPS if eps is None else eps) *
                        coordinate_size(mech), 0.0, r)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _rot(theta: np.ndarray, s: np.ndarray) -> np.ndarray:
    c, sn = np.cos(theta), np.sin(theta)
    return np.stack([c * s[0] - sn * s[1], sn * s[0] + c * s[1]], axis=-1)


def _angle(v: np.ndarray) -> np.ndarray:
    return np.arctan2(v[..., 1], v[..., 0])


@dataclass
class State:
    """Work arrays of a solve: Q[k, n, link, (x, y, θ)] = k-th Taylor coefficient of link poses.

    `T[link, (cos θ, sin θ), n]` holds each link's cos θ and sin θ once known (`known`): the
    group solvers read them instead of recomputing, the compiled kernels write them as they
    place a link, and `solve` hands them to `Solution`. Rotated design vectors R(θ)·s of the
    NumPy paths are cached in `rots`. Whoever writes angles into Q by other means must drop the
    link's entries (`forget_trig`).
    """

    mech: Mechanism
    Q: np.ndarray
    inputs: dict[str, np.ndarray]  # driver joint -> (K+1, N) Taylor coefficients of its input
    T: np.ndarray | None = None
    known: set = field(default_factory=set)
    rots: dict = field(default_factory=dict)
    branches: dict = field(default_factory=dict)  # group -> (N,) assembly signs (`branches`)
    residuals: dict = field(default_factory=dict)  # group -> (N,) Newton's final residual / L
    budget: object = None  # `precision.ErrorBudget` the derivatives carry on, if any
    # a cam follower's last Newton evaluation, handed to its rates (`cam_group`)
    contacts: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.T is None:
            self.T = np.empty((len(contact.rows(self.mech)), 2, self.Q.shape[1]))

    @property
    def order(self) -> int:
        return self.Q.shape[0] - 1

    @property
    def Qm(self) -> np.ndarray:
        """Q as the kernels index it: Qm[k, link, (x, y, θ), n] (a view)."""
        return self.Q.transpose(0, 2, 3, 1)

    def li(self, link: str) -> int:
        """Row of a link (or of a higher pair's contact coordinates, `contact.rows`) in Q."""
        return contact.row_index(self.mech)[link]

    def cs(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """(cos θ, sin θ), each (N,), of link index i's angle (computed once)."""
        if i not in self.known:
            th = self.Q[0, :, i, 2]
            np.cos(th, out=self.T[i, 0])
            np.sin(th, out=self.T[i, 1])
            self.known.add(i)
        return self.T[i, 0], self.T[i, 1]

    def rot(self, i: int, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """R(θ)·s for link index i and design vector s, as (x, y) arrays (cached)."""
        key = (i, float(s[0]), float(s[1]))
        r = self.rots.get(key)
        if r is None:
            c, sn = self.cs(i)
            r = self.rots[key] = (c * s[0] - sn * s[1], sn * s[0] + c * s[1])
        return r

    def forget_trig(self, indices=None) -> None:
        """Drop cos/sin and rotated vectors (of the given link indices, or all) after Q[0]
        changed."""
        if indices is None:
            self.known.clear()
            self.rots.clear()
            return
        gone = set(indices)
        self.known -= gone
        for k in [k for k in self.rots if k[0] in gone]:
            del self.rots[k]

    def placed(self, *indices: int) -> None:
        """Links whose Q[0] and T a kernel has just written."""
        self.forget_trig(indices)
        self.known.update(indices)

    def world(self, link: str, s: np.ndarray) -> np.ndarray:
        """(N, 2) positions of the point with design coordinates s on `link`."""
        i = self.li(link)
        q = self.Q[0, :, i]
        c, sn = self.cs(i)
        return q[:, :2] + np.stack([c * s[0] - sn * s[1], sn * s[0] + c * s[1]], axis=-1)

    def set_pose(self, link: str, point_w: np.ndarray, s: np.ndarray, theta: np.ndarray) -> None:
        """Place `link` so that its design point s is at point_w and its angle is θ."""
        i = self.li(link)
        self.Q[0, :, i, 2] = theta
        self.forget_trig([i])
        c, sn = self.cs(i)
        self.Q[0, :, i, :2] = point_w - np.stack([c * s[0] - sn * s[1], sn * s[0] + c * s[1]],
                                                 axis=-1)


def input_coefficients(mech: Mechanism, values: np.ndarray, rates: np.ndarray | None,
                        accels: np.ndarray | None, jerks: np.ndarray | None,
                        order: int, snaps: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Per driver joint, the (order+1, N) Taylor coefficients of its input (values, rates,
    accelerations, jerks and snaps given per sample; a constant-speed law supplies the rate)."""
    out = {}
    extra = [rates, accels, jerks, snaps]
    for i, d in enumerate(mech.drivers):
        der = np.empty((order + 1, values.shape[0]))  # every row written once, in place (no
        der[0] = values[:, i]                         # temporaries of the batch's size)
        for k in range(1, order + 1):
            given = extra[k - 1]
            if given is not None:
                np.divide(given[:, i], factorial(k), out=der[k])
            elif k == 1 and isinstance(d.law, ConstantSpeed):
                der[k] = d.law.speed
            else:
                der[k] = 0.0
        out[d.joint] = der
    return out


# ---------------------------------------------------------------------------- jets of poses
#: groups of lower pairs evaluate their residuals, Jacobian and first rates from
#: `constraints.PairTable` (off: on jets everywhere; tests/kinematics/test_pair_tables.py and
#: bench/bench_newton.py compare the two)
PAIR_TABLES = True


def pair_table_of(mech: Mechanism, group: Group) -> PairTable | None:
    """The group's `PairTable` (built once per mechanism and group, or taken over from a
    mechanism that draws the group alike: `GroupSolver`'s `like`), or None: it has pairs
    the tables do not cover, or `PAIR_TABLES` is off."""
    return _pair_table(mech, group) if PAIR_TABLES else None


#: (mechanism, group) -> its pair table; -> a mechanism whose table of the group it may take
_tables = Kept(256)
_tables_like = Kept(256)


def _pair_table(mech: Mechanism, group: Group) -> PairTable | None:
    key = (mech, group)
    table = _tables.get(key, _NONE)
    if table is not _NONE:
        return table
    like = _tables_like.get(key)
    table = _tables.get((like, group), _NONE) if like is not None else _NONE
    if table is _NONE:
        table = pair_table(mech, group.links, group.joints, group.drivers, group.wedge_pairs,
                           contact.row_index(mech))
    _tables.put(key, table)
    return table


_NONE = object()


#: the pairs whose equations read the drawing only through the points they name (and their
#: own fields): a group of these is drawn alike where those points are
_PLAIN_PAIRS = (Revolute, Prismatic, Slot, CircularSlot, Gear)


def drawn_alike(a: Mechanism, b: Mechanism, group: Group) -> bool:
    """Whether two mechanisms of one structure (their links and contact rows in the same order)
    draw `group` alike, so that it is solved to the same numbers in both: the same length
    scale, the same pair and driver objects, and the same coordinates of every point its pairs
    name (a revolute's hinge, a guide's point, a circular slot's centre) and of its drivers'
    reference points — everything its per-drawing constants (`GroupSolver.fast`, its
    `PairTable`) and its positions read. Only groups of lower pairs and gear pairs of two wheels
    (higher pairs read profiles, intermittent pairs their wheels' drawings). A drag that
    moves one point changes few groups, a point no pair names (a coupler's tracer point) none."""
    if a.length_scale != b.length_scale or a.link_names != b.link_names or \
            contact.row_index(a) != contact.row_index(b):
        return False
    names: set[str] = set()
    for j in group.joints:
        ja = a.joint(j)
        if ja is not b.joint(j) or not isinstance(ja, _PLAIN_PAIRS) or \
                (isinstance(ja, Gear) and ja.gear_kind == "rack"):
            return False
        names.update(v for v in vars(ja).values() if isinstance(v, str) and v in a.points)
    for d in group.drivers:
        da = next((x for x in a.drivers if x.joint == d), None)
        if da is None or da is not next((x for x in b.drivers if x.joint == d), None):
            return False
        if da.reference:
            names.add(da.reference)
    pa, pb = a.points, b.points
    # (two numbers each, compared as Python floats: a NumPy call per point costs more here)
    return all(n in pb and pa[n].tolist() == pb[n].tolist() for n in names)


def _pose_fn(state: State, group_links: tuple[str, ...], U: np.ndarray | None, order: int):
    """pose(link) over jets of batch shape (N, M). Unknown links read U (order+1, N, M, k, 3);
    known links read Q, broadcast over M."""
    cache: dict[str, tuple] = {}
    gidx = {ln: i for i, ln in enumerate(group_links)}

    def pose(link: str):
        if link not in cache:
            if U is not None and link in gidx:
                c = U[: order + 1, :, :, gidx[link], :]
            else:
                c = state.Q[: order + 1, :, state.li(link), :][:, :, None, :]
            x, y, th = Jet(c[..., 0]), Jet(c[..., 1]), Jet(c[..., 2])
            cs, sn = th.cos_sin()
            cache[link] = (x, y, th, cs, sn)
        return cache[link]

    return pose


def _residuals(state: State, group: Group, U: np.ndarray, order: int) -> list[Jet]:
    mech = state.mech
    pose = _pose_fn(state, group.links, U, order)
    res: list[Jet] = []
    for jn in group.joints:
        r = joint_residuals(mech, mech.joint(jn), pose)
        # the sliding pair that closes a loop of sliding pairs (a wedge) keeps only its offset
        # row: its "no turning" row repeats the loop's other pairs (Rosenauer §95)
        res.extend(r[:1] if jn in group.wedge_pairs else r)
    for d in mech.drivers:
        if d.joint in group.drivers:
            value = Jet(state.inputs[d.joint][: order + 1, :, None])
            res.append(driver_residual(mech, d, pose, value))
    return res


def residual_and_jacobian(state: State, group: Group, *,
                          all_columns: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Residuals (N, rows) of the group's constraints at the poses in Q[0] and their Jacobian
    (N, rows, 3k) with respect to its link poses. rows = 3k, less one per wedge pair. From the
    group's `PairTable` where it has one (lower pairs and drivers), else from one evaluation on
    first-order jets (`residual_and_jacobian_jets`). `all_columns`: from a table, the
    Jacobian's columns of the known links and inputs follow (`rate_residuals` takes them)."""
    table = pair_table_of(state.mech, group)
    if table is None:
        return residual_and_jacobian_jets(state, group)
    r, J = table.evaluate(state.Q[0], {j: v[0] for j, v in state.inputs.items()})
    return r, (J if all_columns else J[:, :, :3 * group.size])


def residual_and_jacobian_jets(state: State, group: Group) -> tuple[np.ndarray, np.ndarray]:
    """`residual_and_jacobian` on first-order jets (the residuals are the jets' values): every
    pair kind, and the reference the pair tables are tested against."""
    N, k = state.Q.shape[1], group.size
    m = 3 * k
    U = np.zeros((2, N, m, k, 3), dtype=state.Q.dtype)  # extended precision stays so
    U[0] = state.Q[0][:, [state.li(ln) for ln in group.links]][:, None]
    U[1] = np.eye(m).reshape(m, k, 3)[None]
    # only the unknowns' directions are wanted: known links and inputs held still
    still = State(state.mech, np.stack([state.Q[0], np.zeros_like(state.Q[0])]),
                  {j: np.stack([v[0], np.zeros_like(v[0])]) for j, v in state.inputs.items()})
    res = _residuals(still, group, U, 1)
    # a row that none of the group's unknowns enter (a pair between links solved before, in a
    # group set aside as redundant) has no direction axis of its own: broadcast it
    return (np.stack([np.broadcast_to(x.c[0], (N, m))[:, 0] for x in res], axis=1),
            np.stack([np.broadcast_to(x.c[1], (N, m)) for x in res], axis=1))


def group_jacobian(state: State, group: Group) -> np.ndarray:
    """(N, rows, 3k) Jacobian of the group's constraints with respect to its link poses."""
    return residual_and_jacobian(state, group)[1]


def rate_residuals(state: State, group: Group, k: int,
                   jacobian: np.ndarray | None = None) -> np.ndarray:
    """(N, rows): the k-th Taylor coefficient of the group's constraint residuals with the
    group's own k-th pose coefficients set to zero, the right-hand side −r_k of J·q⁽ᵏ⁾/k! = −r_k
    (all lower coefficients as they stand in Q). First and second order from the group's
    `PairTable` where it has one (the Jacobian's columns of the known links and inputs times
    their k-th coefficients, at second order plus the velocities' quadratic part,
    `PairTable.quadratic`; `jacobian`: that Jacobian at the poses in Q[0], all its columns, if
    at hand), else on jets (`rate_residuals_jets`)."""
    table = pair_table_of(state.mech, group) if k <= 2 else None
    if table is None:
        return rate_residuals_jets(state, group, k)
    J = jacobian
    if J is None or J.shape[2] != table.cols:
        _, J = table.evaluate(state.Q[0], {j: v[0] for j, v in state.inputs.items()})
    known = table.rows_q[group.size:]
    rates = [state.Q[k][:, known].reshape(J.shape[0], -1)]
    rates += [state.inputs[d[4]][k][:, None] for d in table.drivers]
    r = np.einsum("nij,nj->ni", J[:, :, 3 * group.size:], np.concatenate(rates, axis=1))
    if k == 2:  # the velocities' part (the group's own included)
        r += table.quadratic(state.Q[0], state.Q[1])
    return r


def rate_residuals_jets(state: State, group: Group, k: int) -> np.ndarray:
    """`rate_residuals` on jets: any order, every pair kind."""
    idx = [state.li(ln) for ln in group.links]
    U = state.Q[: k + 1, :, idx, :][:, :, None].copy()
    U[k] = 0.0
    res = _residuals(state, group, U, k)
    return np.stack([x.c[k][:, 0] for x in res], axis=1)


def least_squares(J: np.ndarray, b: np.ndarray) -> np.ndarray:
    """x with J·x = b, per sample: by LU when every J is square and regular, else in the least
    squares sense (a singular sample in the batch, or more constraint rows than unknowns where
    sliding pairs repeat a rotation row)."""
    out = np.full(b.shape[:-1] + J.shape[-1:], np.nan, dtype=np.result_type(J, b))
    if J.shape[-1] == J.shape[-2]:
        try:
            return np.linalg.solve(J, b[..., None])[..., 0]
        except np.linalg.LinAlgError:
            pass
    # samples with NaN in them (a contact run off the end of its profile) stay NaN: the SVD of
    # pinv would not converge on them; of the others only the singular ones by the
    # pseudo-inverse, so that the others' answers do not depend on what else is in the batch
    good = np.isfinite(J).all(axis=(-2, -1)) & np.isfinite(b).all(axis=-1)
    Jg, bg = J[good], b[good]
    if J.shape[-1] != J.shape[-2]:
        out[good] = (np.linalg.pinv(Jg) @ bg[..., None])[..., 0]
        return out
    sv = np.linalg.svd(Jg, compute_uv=False)
    regular = sv[..., -1] > 1e-15 * sv[..., 0]
    res = np.empty(bg.shape, dtype=out.dtype)
    if regular.any():
        res[regular] = np.linalg.solve(Jg[regular], bg[regular][..., None])[..., 0]
    if (~regular).any():
        res[~regular] = (np.linalg.pinv(Jg[~regular]) @ bg[~regular][..., None])[..., 0]
    out[good] = res
    return out


def _scaled(J: np.ndarray, scale: float, links: tuple[str, ...] = ()) -> np.ndarray:
    """Jacobian with angle columns in length units, so its condition number is unit-free; the
    columns of contact coordinates (rows named in `links` with `contact.PREFIX`: profile
    parameters of any unit) scaled to unit length."""
    Js = J.copy()
    Js[..., 2::3] /= scale
    for i, ln in enumerate(links):
        if ln.startswith(contact.PREFIX):
            cols = Js[..., 3 * i:3 * i + 3]
            norm = np.sqrt((cols * cols).sum(axis=-2, keepdims=True))
            cols /= np.where(norm > 0, norm, 1.0)
    return Js


def _solve(J: np.ndarray, r: np.ndarray, ok: np.ndarray) -> np.ndarray:
    out = np.full(r.shape[:1] + J.shape[2:], np.nan)
    if ok.any():
        # more rows than unknowns (an over-closed group): least squares, exact where consistent
        out[ok] = least_squares(J[ok], r[ok])
    return out


def derivatives_generic(state: State, group: Group, ok: np.ndarray) -> np.ndarray:
    """Fill the velocity (and higher) coefficients of the group's links; return the condition."""
    idx = [state.li(ln) for ln in group.links]
    J = group_jacobian(state, group)
    finite = ok & np.isfinite(J).all(axis=(1, 2))
    cond = np.full(J.shape[0], np.inf)
    if finite.any():
        cond[finite] = np.linalg.cond(_scaled(J[finite], state.mech.length_scale, group.links))
    good = finite & (cond < UNRELIABLE_CONDITION)
    for k in range(1, state.order + 1):
        sol = _solve(J, -rate_residuals(state, group, k), good)
        state.Q[k][:, idx, :] = sol.reshape(-1, group.size, 3)
    return cond


# ---------------------------------------------------------------------------- group kinds
def _classify(mech: Mechanism, group: Group) -> tuple[str, dict]:
    """Recognise the groups with closed-form positions; 'generic' otherwise."""
    joints = [mech.joint(j) for j in group.joints]
    g = set(group.links)
    if group.drivers:
        return ("driver", {}) if group.size == 1 else ("generic", {})
    kinds = sorted(j.kind for j in joints)
    if group.size == 2 and kinds == ["revolute"] * 3:
        inner = [j for j in joints if set(j.links) <= g]
        outer = [j for j in joints if not set(j.links) <= g]
        if len(inner) == 1 and len(outer) == 2:
            (a, c) = outer
            l1 = a.links[0] if a.links[0] in g else a.links[1]
            l2 = c.links[0] if c.links[0] in g else c.links[1]
            if l1 != l2:
                return "RRR", dict(a=a, b=inner[0], c=c, l1=l1, l2=l2)
    if group.size == 1 and len(joints) == 2:
        (ln,) = group.links
        ind = [j for j in joints if intermittent.is_intermittent(j) and j.links[1] == ln]
        rev = [j for j in joints if isinstance(j, Revolute)]
        if ind and rev and set(rev[0].links) == {ln, ind[0].carrier}:
            return "intermittent", dict(pair=ind[0], wheel=ln, pivot=rev[0])
    if group.size == 1:
        (ln,) = group.links
        rev = [j for j in joints if isinstance(j, Revolute)]
        slot = [j for j in joints if isinstance(j, Slot)]
        if len(rev) == 1 and len(slot) == 1 and len(joints) == 2:
            s = slot[0]
            if s.links[1] == ln:
                return "rod-in-slot", dict(pivot=rev[0], line=s, rod=ln)
            return "slotted-lever", dict(pivot=rev[0], line=s, lever=ln)
    if group.size == 2 and len(joints) == 3:
        rev = [j for j in joints if isinstance(j, Revolute)]
        pri = [j for j in joints if isinstance(j, Prismatic)]
        if len(rev) == 2 and len(pri) == 1:
            p = pri[0]
            if p.links[1] in g and p.links[0] not in g:  # block on a known guide: RRP
                block = p.links[1]
                inner = [j for j in rev if set(j.links) == g]
                outer = [j for j in rev if not set(j.links) <= g]
                if len(inner) == 1 and len(outer) == 1:
                    rod = next(ln for ln in g if ln != block)
                    if rod in outer[0].links:
                        return "RRP", dict(pivot=outer[0], hinge=inner[0], guide=p, rod=rod, block=block)
            if set(p.links) == g:  # block slides in the lever: RPR
                lever, block = p.links
                outer = [j for j in rev if not set(j.links) <= g]
                if len(outer) == 2:
                    lj = next((j for j in outer if lever in j.links), None)
                    bj = next((j for j in outer if block in j.links), None)
                    if lj is not None and bj is not None:
                        return "RPR", dict(pivot=lj, pin=bj, guide=p, lever=lever, block=block)
    return "generic", {}


def _other(j, link: str) -> str:
    return j.links[1] if j.links[0] == link else j.links[0]


def _circle_line(state: State, centre: np.ndarray, radius: float, q: np.ndarray, e: np.ndarray,
                 branch) -> np.ndarray:
    """Point on the line q + λe (unit e) at distance `radius` from `centre`, on `branch` (±1,
    or one sign per sample)."""
    w = q - centre
    b = np.einsum("ij,ij->i", e, w)
    disc = b * b - (np.einsum("ij,ij->i", w, w) - radius * radius)
    disc = np.where((disc < 0) & (disc > -1e-12 * radius * radius), 0.0, disc)
    with np.errstate(invalid="ignore"):  # no intersection: NaN marks the sample unassembled
        lam = -b + branch * np.sqrt(disc)
    return q + lam[:, None] * e


def _design_branch(b: float) -> float:
    return 1.0 if b >= 0 else -1.0


class GroupSolver:
    """Solves one group: positions (closed form or Newton) and derivatives."""

    def __init__(self, mech: Mechanism, group: Group, like: "GroupSolver | None" = None) -> None:
        # a group's higher pairs bring their contact coordinates as rows of their own
        extra = tuple(contact.row_name(mech.joint(j)) for j in group.joints
                      if contact.is_higher(mech.joint(j)))
        self.mech, self.group = mech, replace(group, links=group.links + extra) if extra else group
        self.kind, self.parts = _classify(mech, group)
        # a cam follower is solved in its own two unknowns (`cam_group`); the continuation still
        # treats it as generic (its rows are the generic rows)
        self.cam = cam_group.recognise(mech, group) if self.kind == "generic" else None
        if like is not None and like.group == self.group and like.kind == self.kind and \
                drawn_alike(like.mech, mech, self.group):
            # the group drawn as in `like`'s mechanism (a drag's previous frame): its constants
            # are the same numbers, taken over instead of computed again
            self.__dict__["fast"] = like.fast
            _tables_like.put((mech, self.group), like.mech)
        self.fast  # noqa: B018  (computed once here; `plan` keeps the solver per mechanism)

    @property
    def compiled(self) -> bool:
        """Positions (and at order 2 the rates) of this group run in the compiled kernels."""
        return self.fast is not None

    @cached_property
    def fast(self) -> dict | None:
        """Per-group constants of the closed-form hot paths (None: the generic path)."""
        if self.kind == "RRR":
            return self._rrr_constants()
        if self.kind == "RRP":
            return self._rrp_constants()
        if self.kind == "driver":
            return self._driver_constants()
        return None

    def _rrr_constants(self) -> dict:
        p, P, li = self.parts, self.mech.points, self.mech.link_index
        A, B, C = P[p["a"].point], P[p["b"].point], P[p["c"].point]
        L1, L2 = np.hypot(*(B - A)), np.hypot(*(B - C))
        phi1, phi2 = _angle(B - A), _angle(B - C)
        # cos θ = (r·(cos φ, sin φ))/|r|, sin θ = (r × (cos φ, sin φ))/|r| for the hinge
        # vector r of a link drawn at angle φ; the condition number needs only L1², L2², c1·c2
        return dict(
            A=A, C=C, BA=B - A, BC=B - C, L1sq=L1 * L1, diff=L1 * L1 - L2 * L2, tol=-1e-12 * L1 * L1,
            branch=_design_branch(_cross(C - A, B - A)), phi1=phi1, phi2=phi2,
            k1=np.array([np.cos(phi1), np.sin(phi1)]),
            k2=np.array([np.cos(phi2), np.sin(phi2)]),
            mid=0.5 * (L1 * L1 + L2 * L2), hd2=(0.5 * (L1 * L1 - L2 * L2)) ** 2,
            i1=li[p["l1"]], i2=li[p["l2"]],
            iA=li[_other(p["a"], p["l1"])], iC=li[_other(p["c"], p["l2"])])

    def _rrp_constants(self) -> dict:
        p, P, li = self.parts, self.mech.points, self.mech.link_index
        A, Pd = P[p["pivot"].point], P[p["hinge"].point]
        r = float(np.hypot(*(Pd - A)))
        phi = _angle(Pd - A)
        axis = np.asarray(p["guide"].axis, dtype=float)
        return dict(A=A, P=Pd, AP=Pd - A, e0=axis / np.hypot(*axis),
                    rsq=r * r, tol=-1e-12 * r * r, length=r, phi=phi,
                    k=np.array([np.cos(phi), np.sin(phi)]),
                    iA=li[_other(p["pivot"], p["rod"])], ig=li[p["guide"].links[0]],
                    ir=li[p["rod"]], ib=li[p["block"]])

    def _driver_constants(self) -> dict | None:
        mech = self.mech
        (ln,) = self.group.links
        d: Driver = next(d for d in mech.drivers if d.joint in self.group.drivers)
        j = mech.joint(d.joint)
        if isinstance(j, Prismatic):
            return None
        H = mech.points[j.point]
        # The group's Jacobian (hinge rows, driver row) scaled as in `derivatives_generic`:
        # its singular values depend on |H| only, not on the pose, so the condition number
        # is the same at every sample: the one at the design position.
        state = State(mech, np.zeros((2, 1, len(contact.rows(mech)), 3)),
                      {dd.joint: np.zeros((2, 1)) for dd in mech.drivers})
        J = group_jacobian(state, self.group)
        cond = float(np.linalg.cond(_scaled(J, mech.length_scale))[0])
        return dict(H=H, joint=d.joint, u0=mech.driver_input_at_design(d),
                    i=mech.link_index[ln], b=mech.link_index[d.base], cond=cond)

    # ------------------------------------------------------------------ positions
    def positions(self, state: State, guess: np.ndarray | None = None) -> np.ndarray:
        """Fill the group's poses in Q[0]; return the per-sample assembly mask."""
        fn = getattr(self, f"_pos_{self.kind.replace('-', '_')}")
        return fn(state, guess) if self.kind == "generic" else fn(state)

    def _pos_driver(self, state: State) -> np.ndarray:
        mech = self.mech
        (ln,) = self.group.links
        d: Driver = next(d for d in mech.drivers if d.joint in self.group.drivers)
        j = mech.joint(d.joint)
        base = state.Q[0, :, state.li(d.base)]
        u = state.inputs[d.joint][0]
        if isinstance(j, Prismatic):
            theta = base[:, 2]
            shift = u[:, None] * _rot(theta, j.axis)
            state.Q[0, :, state.li(ln), :2] = base[:, :2] + shift
            state.Q[0, :, state.li(ln), 2] = theta
            state.forget_trig([state.li(ln)])
        else:
            f = self.fast
            state.cs(f["b"])
            from . import kernels  # numba loads on the first solve, not on import
            kernels.driver_positions(state.Qm[0], state.T, f["b"], f["i"], f["H"], u, f["u0"])
            state.placed(f["i"])
        return np.isfinite(u) & np.isfinite(base).all(axis=1)

    def _pos_RRR(self, state: State) -> np.ndarray:
        """Circle–circle intersection (`kernels.rrr_positions`)."""
        f = self.fast
        state.cs(f["iA"])
        state.cs(f["iC"])
        N = state.Q.shape[1]
        ok = np.ones(N, dtype=bool)
        r = np.empty((4, N))
        Q0 = state.Qm[0]
        branch = self._branch_signs(state, N)
        from . import kernels
        kernels.rrr_positions(Q0, state.T, f["iA"], f["A"], f["iC"], f["C"], f["i1"], f["i2"],
                              f["diff"], f["L1sq"], f["tol"], branch, f["k1"], f["k2"], r, ok)
        for i, (x, y), phi in ((f["i1"], r[:2], f["phi1"]), (f["i2"], r[2:], f["phi2"])):
            np.subtract(np.arctan2(y, x), phi, out=Q0[i, 2])
        state.placed(f["i1"], f["i2"])
        return ok

    def discriminant(self, state: State) -> np.ndarray:
        """Of a group with two assemblies whose neighbours are placed: RRR, h²/|AB|², the squared
        distance of its hinge from the line AC; RRP and rod in slot, d²/|AP|², the squared half
        chord the rod's circle cuts from the track. Negative: it cannot assemble; zero: a limit
        or change position."""
        if self.kind != "RRR":
            _, _, Aw, q, e, r = self._track(state)
            w = q - Aw
            b = np.einsum("ij,ij->i", e, w)
            return (b * b - (np.einsum("ij,ij->i", w, w) - r * r)) / (r * r)
        f = self.fast
        Q0 = state.Q[0]
        (ax, ay), (cx, cy) = ((Q0[:, i, 0] + state.rot(i, s)[0], Q0[:, i, 1] + state.rot(i, s)[1])
                              for i, s in ((f["iA"], f["A"]), (f["iC"], f["C"])))
        D2 = (cx - ax) ** 2 + (cy - ay) ** 2
        with np.errstate(invalid="ignore", divide="ignore"):
            a = (f["diff"] + D2) / (2 * np.sqrt(D2))
        return 1.0 - a * a / f["L1sq"]

    def pivot_gap(self, state: State) -> np.ndarray:
        """Of an RRR dyad whose neighbours are placed: |AC|²/|AB|², the squared distance of its
        two outer hinges. Zero: they coincide (the Galloway kite's fold, Rosenauer §100), the
        line AC turns over, and with it the side of AC its hinge B keeps."""
        f = self.fast
        Q0 = state.Q[0]
        (ax, ay), (cx, cy) = ((Q0[:, i, 0] + state.rot(i, s)[0], Q0[:, i, 1] + state.rot(i, s)[1])
                              for i, s in ((f["iA"], f["A"]), (f["iC"], f["C"])))
        return ((cx - ax) ** 2 + (cy - ay) ** 2) / f["L1sq"]

    def _track(self, state: State) -> tuple:
        """A circle–line group (RRP, rod in slot): the rod's pivot A and its guided point P
        (design), A in the world, P's track (a point q on it and its unit direction e), |AP|."""
        p, P = self.parts, self.mech.points
        line = p["guide"] if self.kind == "RRP" else p["line"]
        A = P[p["pivot"].point]
        Pd = P[p["hinge"].point] if self.kind == "RRP" else P[line.point]
        Aw = state.world(_other(p["pivot"], p["rod"]), A)
        gl = line.links[0]
        q = state.world(gl, Pd)  # the track: the line through P's design place, fixed in gl
        e = _rot(state.Q[0, :, state.li(gl), 2], line.axis)
        return A, Pd, Aw, q, e, np.hypot(*(Pd - A))

    def _branch_signs(self, state: State, N: int) -> np.ndarray:
        """The assembly sign per sample: the schedule's across change points, else the design's
        side everywhere."""
        branch = state.branches.get(self.group)
        return np.broadcast_to(self.design_sign, (N,)) if branch is None else branch

    @cached_property
    def design_sign(self) -> float:
        """The assembly sign the drawing shows (RRR: side of AC on which B lies; circle–line:
        side of the rod's foot on the track on which the guided point lies)."""
        if self.kind == "RRR":
            return self.fast["branch"]
        p, P = self.parts, self.mech.points
        line = p["guide"] if self.kind == "RRP" else p["line"]
        Pd = P[p["hinge"].point] if self.kind == "RRP" else P[line.point]
        return _design_branch(np.dot(line.axis, Pd - P[p["pivot"].point]))

    def _circle_line_point(self, state: State) -> tuple:
        A, Pd, Aw, q, e, r = self._track(state)
        Pw = _circle_line(state, Aw, r, q, e, state.branches.get(self.group, self.design_sign))
        state.set_pose(self.parts["rod"], Aw, A, _angle(Pw - Aw) - _angle(Pd - A))
        return Pd, Pw

    def _pos_rod_in_slot(self, state: State) -> np.ndarray:
        _, Pw = self._circle_line_point(state)
        return np.isfinite(Pw).all(axis=1)

    def _pos_RRP(self, state: State) -> np.ndarray:
        """Circle–line intersection (`kernels.rrp_positions`)."""
        f = self.fast
        state.cs(f["iA"])
        state.cs(f["ig"])
        N = state.Q.shape[1]
        ok = np.ones(N, dtype=bool)
        r = np.empty((2, N))
        Q0 = state.Qm[0]
        branch = self._branch_signs(state, N)
        from . import kernels
        kernels.rrp_positions(Q0, state.T, f["iA"], f["A"], f["ig"], f["P"], f["e0"], f["rsq"],
                              f["tol"], branch, f["ir"], f["ib"], f["k"], r, ok)
        np.subtract(np.arctan2(r[1], r[0]), f["phi"], out=Q0[f["ir"], 2])
        state.placed(f["ir"], f["ib"])
        return ok

    def _lever_angle(self, state: State, pivot, lever: str, pin_w: np.ndarray, pin_d: np.ndarray,
                     axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Angle of a lever pivoted at `pivot` whose line (axis through pin_d) passes the pin."""
        O = self.mech.points[pivot.point]
        Ow = state.world(_other(pivot, lever), O)
        e = _cross(axis, pin_d - O)  # signed distance of the slot line from the pivot
        d = pin_w - Ow
        rho = np.hypot(d[:, 0], d[:, 1])
        with np.errstate(invalid="ignore", divide="ignore"):
            s = e / rho
            s = np.where((np.abs(s) > 1) & (np.abs(s) < 1 + 1e-12), np.sign(s), s)
            if np.dot(axis, pin_d - O) >= 0:
                phi = _angle(d) - np.arcsin(s)
            else:
                phi = _angle(d) - np.pi + np.arcsin(s)
        return Ow, phi - _angle(axis)

    def _pos_slotted_lever(self, state: State) -> np.ndarray:
        p = self.parts
        line, lever = p["line"], p["lever"]
        pin_d = self.mech.points[line.point]
        pin_w = state.world(line.links[1], pin_d)
        Ow, th = self._lever_angle(state, p["pivot"], lever, pin_w, pin_d, line.axis)
        state.set_pose(lever, Ow, self.mech.points[p["pivot"].point], th)
        return np.isfinite(th)

    def _pos_RPR(self, state: State) -> np.ndarray:
        p = self.parts
        P = self.mech.points
        pin, lever, block = p["pin"], p["lever"], p["block"]
        pin_d = P[pin.point]
        pin_w = state.world(_other(pin, block), pin_d)
        Ow, th = self._lever_angle(state, p["pivot"], lever, pin_w, pin_d, p["guide"].axis)
        state.set_pose(lever, Ow, P[p["pivot"].point], th)
        state.set_pose(block, pin_w, pin_d, th)
        return np.isfinite(th)

    def _pos_intermittent(self, state: State) -> np.ndarray:
        """A wheel indexed by a Geneva or star-wheel pair: its angle in closed form from the
        driver's rotation relative to the carrier (`intermittent.wheel_angle`)."""
        p = self.parts
        j, wheel = p["pair"], p["wheel"]
        th_c = state.Q[0, :, state.li(j.carrier), 2]
        delta = state.Q[0, :, state.li(j.links[0]), 2] - th_c
        th = th_c + intermittent.wheel_angle(self.mech, j, delta)
        C = self.mech.points[p["pivot"].point]
        state.set_pose(wheel, state.world(j.carrier, C), C, th)
        return np.isfinite(th)

    def _pos_generic(self, state: State, guess: np.ndarray | None) -> np.ndarray:
        """Newton's method on the group alone, from `guess` (N, k, 3) poses."""
        if self.cam is not None:
            ok, err = cam_group.positions(self.cam, state, guess, NEWTON_TOL * self.mech.length_scale)
            state.residuals[self.group] = backward_error(self.mech, err)
            return ok
        idx = [state.li(ln) for ln in self.group.links]
        N = state.Q.shape[1]
        q = np.zeros((N, self.group.size, 3)) if guess is None else guess.copy()
        scale = self.mech.length_scale
        active = np.isfinite(q).all(axis=(1, 2))
        converged = np.zeros(N, dtype=bool)
        polished = np.zeros(N, dtype=bool)
        q[~active] = 0.0
        for it in range(50):
            state.Q[0][:, idx, :] = q
            r, J = residual_and_jacobian(state, self.group)
            err = np.abs(r).max(axis=1)
            if it == 0:  # samples whose known links did not assemble upstream
                active &= np.isfinite(err)
            converged = active & (err <= NEWTON_TOL * scale)
            todo = active & ~(converged & polished)
            if not todo.any():
                break  # err is the residual at the final poses
            # a converged sample takes one more step: Newton's quadratic convergence then leaves
            # only rounding, which the acceleration solve needs (its error scales with it)
            polished |= converged
            step = least_squares(J[todo], -r[todo])
            # damp steps that would turn a link by more than a radian: keeps the branch
            big = np.abs(step[:, 2::3]).max(axis=1, initial=0.0)
            step *= np.minimum(1.0, 1.0 / np.maximum(big, 1e-300))[:, None]
            q[todo] += step.reshape(-1, self.group.size, 3)
        else:
            state.Q[0][:, idx, :] = q
            err = np.abs(residual_and_jacobian(state, self.group)[0]).max(axis=1, initial=0.0)
        # a limit position (a fold of the group): Newton's method slows down to a crawl there,
        # but the poses are closed to within LIMIT_RESIDUAL; they are returned, the residual in
        # the error bound marking the sample singular (`precision`), not invented as unreachable
        converged |= active & (err <= LIMIT_RESIDUAL * scale)
        q[~converged] = np.nan
        state.Q[0][:, idx, :] = q
        state.forget_trig(idx)
        # the backward error of the poses, for the forward error estimate (`precision`)
        state.residuals[self.group] = backward_error(self.mech, err)
        return converged

    # ------------------------------------------------------------------ derivatives
    def derivatives(self, state: State, ok: np.ndarray) -> np.ndarray:
        """Fill velocity and acceleration (and jerk) coefficients; return condition numbers.
        The forward error bounds of `state.budget` (`precision.ErrorBudget`), if any, are
        carried on for this group (by the compiled kernels in the same pass)."""
        budget = state.budget
        if state.order == 2 and self.fast is not None:
            if budget is None:  # (the continuation's tangents: no bound wanted)
                from .precision import ErrorBudget
                budget = ErrorBudget(self.mech, state)
            if self.kind == "RRR":
                return self._der_RRR(state, ok, budget)
            if self.kind == "RRP":
                return self._der_RRP(state, ok, budget)
            return self._der_driver(state, ok, budget)
        if self.cam is not None:
            cond = cam_group.derivatives(self.cam, state, ok, UNRELIABLE_CONDITION)
        elif self.kind == "intermittent":
            cond = self._der_intermittent(state)
        else:
            cond = derivatives_generic(state, self.group, ok)
        if budget is not None:
            budget.add(state, self, cond)
        return cond

    def _der_intermittent(self, state: State) -> np.ndarray:
        """Rates of a wheel indexed by an intermittent pair, in closed form: its angle relative
        to the carrier is T(δ) of the driver's relative angle δ, so its jet is T composed with
        δ's jet (the transmission's derivatives, `intermittent.transmission`); its origin follows
        from its pivot C on the carrier. The same rates as the phase equations' linear solve
        (`derivatives_generic`, the independent check in the tests), without it. The condition
        number is the one of that solve's scaled Jacobian, in closed form: the pivot's rows
        [I | v] and the pair's row (0, 0, g), g = 1 locked, (D − r)/L in the pin gear, |CB|/L on
        a slot, whose singular values are 1 and those of [[1, |v|], [0, g]]."""
        p = self.parts
        j, wheel, mech = p["pair"], p["wheel"], self.mech
        K = state.order
        ic, iw = state.li(j.carrier), state.li(wheel)
        Qc = state.Q[: K + 1, :, ic]
        th_c = Jet(Qc[..., 2])
        delta = Jet(state.Q[: K + 1, :, state.li(j.links[0]), 2]) - th_c
        th = th_c + delta.compose(intermittent.transmission(mech, j, delta.c[0], order=K))
        C = mech.points[p["pivot"].point]
        cc, sc = th_c.cos_sin()
        cw, sw = th.cos_sin()
        state.Q[1: K + 1, :, iw, 0] = (Jet(Qc[..., 0]) + (cc - cw) * C[0] - (sc - sw) * C[1]).c[1:]
        state.Q[1: K + 1, :, iw, 1] = (Jet(Qc[..., 1]) + (sc - sw) * C[0] + (cc - cw) * C[1]).c[1:]
        state.Q[1: K + 1, :, iw, 2] = th.c[1:]
        L = mech.length_scale
        g = intermittent.row_slope(mech, j, state.Q[0, :, state.li(j.links[0]), 2] - Qc[0, :, 2]) / L
        v2 = (C[0] ** 2 + C[1] ** 2) / L**2
        t = 1.0 + v2 + g * g
        root = np.sqrt(np.maximum(t * t - 4 * g * g, 0.0))
        s_hi, s_lo = np.sqrt(0.5 * (t + root)), np.abs(g) / np.sqrt(0.5 * (t + root))
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.maximum(s_hi, 1.0) / np.minimum(s_lo, 1.0)

    def _der_driver(self, state: State, ok: np.ndarray, b) -> np.ndarray:
        """Revolute driver (`kernels.driver_rates`); its condition number is the design one."""
        f = self.fast
        u = state.inputs[f["joint"]]
        from . import kernels
        kernels.driver_rates(state.Qm, state.T, f["b"], f["i"], f["H"], u[1], u[2], f["cond"],
                             self.mech.length_scale, b.omega, b.m, b.E, b.eps)
        return np.full(state.Q.shape[1], f["cond"])

    def _der_RRR(self, state: State, ok: np.ndarray, b) -> np.ndarray:
        """Velocities and accelerations of an RRR dyad (`kernels.rrr_rates`)."""
        f = self.fast
        cond = np.ones(state.Q.shape[1])
        from . import kernels
        kernels.rrr_rates(state.Qm, state.T, f["iA"], f["A"], f["iC"], f["C"], f["i1"], f["i2"],
                          f["BA"], f["BC"], f["mid"], f["hd2"], UNRELIABLE_CONDITION, cond,
                          self.mech.length_scale, b.omega, b.m, b.E, b.eps)
        return cond

    def _der_RRP(self, state: State, ok: np.ndarray, b) -> np.ndarray:
        """Velocities and accelerations of an RRP dyad (`kernels.rrp_rates`)."""
        f = self.fast
        cond = np.ones(state.Q.shape[1])
        from . import kernels
        kernels.rrp_rates(state.Qm, state.T, f["iA"], f["A"], f["ig"], f["P"], f["e0"], f["AP"],
                          f["length"], f["ir"], f["ib"], UNRELIABLE_CONDITION, cond,
                          self.mech.length_scale, b.omega, b.m, b.E, b.eps)
        return cond
