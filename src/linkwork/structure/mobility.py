"""Mobility (*Laufgrad*, *kustības brīvība*): the counts of the seeds and the real mobility.

Two answers, reported side by side:

* **The count.** Grübler's criterion as Pöschl writes it for hinge chains, 3n − 2g = 4 for
  constrained motion (*Zwanglauf*, *piespiesta kustība*; Pöschl eq. 97), and Rosenauer's general
  form h + 2z − 3n + 4 = 0 (his eq. 53), with

  - n the links, frame included (*Glieder*, *locekļi*);
  - g = g₁ + 2g₂ + 3g₃ + … the hinges, a hinge joining k links counting k − 1 times (eq. 50:
    simple, double, triple joints, *vienkāršs / dubult- / trīskārtīgs šarnīrs*);
  - s the sliding pairs (*Schubpaare*, *slīdpāri*), z = g + s the lower pairs;
  - h = h_n + 2h_p the higher pairs, a self-closed one (*paarschlüssig*, *patstāvīgi slēgts*)
    counting twice (eq. 52);
  - γ the closed slider groups (Rosenauer's wedge exception, *ķīļsavienojums*: a loop of
    sliding pairs only moves although 2z − 3n + 4 = γ ≠ 0).

  The count's mobility is F = 3(n − 1) − 2z − h + γ (Kutzbach's count, which is 1 exactly when
  Rosenauer's criterion holds). Hinge chains with more hinges than 3n/2 − 2 are over-closed
  (*übergeschlossen*, *pārāk slēgtas ķēdes*, eq. 55); the free term of g − 3n/2 tells how many
  redundant links they carry (eqs. 55a, 55b).

* **The real mobility**: 3k − rank J, J the Jacobian of all pair constraints with respect to the
  poses of the k moving links at the design position (`linkwork.kinematics.jacobian`). Chains
  that move only thanks to special dimensions (parallel cranks, Roberval's balance, a pantograph
  with both braces) have fewer independent constraints than pairs: the redundant equations are
  listed. With the drivers' equations added, the rank says how many inputs the mechanism still
  needs, or which drivers are too many.

`structure_report` gathers everything `linkwork structure` prints: these two, the Assur groups in
solution order (`assur`), and the Grashof loops (`grashof`).

A mechanism counts its folded pairs as the seeds draw them: a pin in a slot (`slot`,
`circular-slot`) is the die block (*Stein*, *kulises akmens*) with a hinge and a sliding pair,
so it adds one link, one hinge and one slider; a gear pair is a non-self-closed higher pair.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ..errors import InputError
from ..model import Mechanism
from ..topology.counts import kutzbach
from ..topology.groups import RotationClasses, slider_loop

# ---------------------------------------------------------------------------- the counts


@dataclass(frozen=True)
class PairCounts:
    """The numbers a seed writes down for a chain.

    `hinges[k - 1]` is g_k, the number of hinges joining k + 1 links (g₁ simple, g₂ double, …).
    """

    n: int
    hinges: tuple[int, ...] = ()
    s: int = 0
    h_n: int = 0
    h_p: int = 0
    gamma: int = 0

    def __post_init__(self) -> None:
        if self.n < 1 or any(v < 0 for v in (*self.hinges, self.s, self.h_n, self.h_p, self.gamma)):
            raise InputError("counts must be non-negative and a chain has at least one link")

    # ---------------------------------------------------------------- derived numbers
    @property
    def g1(self) -> int:
        return self.hinges[0] if len(self.hinges) > 0 else 0

    @property
    def g2(self) -> int:
        return self.hinges[1] if len(self.hinges) > 1 else 0

    @property
    def g3(self) -> int:
        return self.hinges[2] if len(self.hinges) > 2 else 0

    @property
    def g(self) -> int:
        """g = g₁ + 2g₂ + 3g₃ + … (Rosenauer eq. 50)."""
        return sum((k + 1) * gk for k, gk in enumerate(self.hinges))

    @property
    def z(self) -> int:
        """Lower pairs, z = g + s."""
        return self.g + self.s

    @property
    def h(self) -> int:
        """Higher pairs, self-closed ones counted twice: h = h_n + 2h_p (eq. 52)."""
        return self.h_n + 2 * self.h_p

    @property
    def hinge_chain(self) -> bool:
        """Only hinges (*Gelenkkette*): Grübler's and Rosenauer's hinge formulas apply."""
        return self.s == 0 and self.h == 0

    @property
    def grubler(self) -> int:
        """3n − 2g, which Pöschl's Grübler condition (97) wants equal to 4. Counts sliding
        pairs like hinges (both remove two freedoms) and ignores higher pairs."""
        return 3 * self.n - 2 * self.z

    @property
    def criterion(self) -> int:
        """h + 2z − 3n + 4 − γ: zero for constrained motion (Rosenauer eqs. 45, 53 and the
        slider-group form 2z − 3n + 4 = γ); positive for over-closed or rigid chains, negative
        for chains that need more inputs."""
        return self.h + 2 * self.z - 3 * self.n + 4 - self.gamma

    @property
    def mobility(self) -> int:
        """The count's mobility F = 3(n − 1) − 2z − h + γ = 1 − criterion."""
        return 1 - self.criterion

    @property
    def constrained(self) -> bool:
        """The count says *zwangläufig*: one input moves every link."""
        return self.criterion == 0

    @property
    def free_term(self) -> Fraction:
        """x = g − 3n/2 for hinge chains: −2 constrained (eq. 44), −3/2 with one redundant link
        (55a), −1 with two (55b)."""
        return Fraction(self.z) - Fraction(3 * self.n, 2)

    @property
    def redundant_links(self) -> int:
        """Redundant links of an over-closed chain by the free term, 2(x + 2) (§101); 0 unless
        the count is over-closed."""
        return max(0, self.criterion)

    def verdict(self) -> str:
        c = self.criterion
        if c == 0:
            return "constrained motion (zwangläufig)"
        if c > 0:
            return (f"over-closed or rigid by the count (übergeschlossen): {c} constraint"
                    f"{'s' if c > 1 else ''} more than constrained motion allows")
        return f"not constrained by the count: {-c} more input{'s' if c < -1 else ''} needed"

    def as_dict(self) -> dict:
        return {
            "n": self.n, "g": self.g, "g1": self.g1, "g2": self.g2, "g3": self.g3,
            "hinges": list(self.hinges), "s": self.s, "z": self.z, "h": self.h,
            "h_n": self.h_n, "h_p": self.h_p, "gamma": self.gamma,
            "grubler_3n_minus_2g": self.grubler if self.h == 0 else None,
            "criterion": self.criterion, "mobility": self.mobility,
            "free_term": str(self.free_term) if self.hinge_chain else None,
            "verdict": self.verdict(),
        }


def chain_counts(n: int, g: int = 0, *, g1: int = 0, g2: int = 0, g3: int = 0, s: int = 0,
                 h_n: int = 0, h_p: int = 0, gamma: int = 0) -> PairCounts:
    """Counts as a seed gives them: `g` simple hinges (or `g1`, `g2`, `g3` simple, double and
    triple hinges), `s` sliders, `h_n` non-self-closed and `h_p` self-closed higher pairs,
    `gamma` closed slider groups."""
    hinges = (g + g1, g2, g3)
    while len(hinges) > 1 and hinges[-1] == 0:
        hinges = hinges[:-1]
    return PairCounts(n=n, hinges=hinges, s=s, h_n=h_n, h_p=h_p, gamma=gamma)


def grubler_constrained(n: int, g: int) -> bool:
    """Pöschl's form of Grübler's condition (97): a hinge chain of n links and g hinges (a
    hinge of k links counted k − 1 times) is constrained when 3n − 2g = 4."""
    return 3 * n - 2 * g == 4


# ---------------------------------------------------------------------------- a mechanism's counts


def hinge_groups(mech: Mechanism) -> list[tuple[str, tuple[str, ...], tuple[str, ...]]]:
    """The hinges of `mech` as the seeds count them: revolute pairs at one point form one hinge
    joining all their links. Returns (point, links, revolute joints) per hinge."""
    by_point: dict[str, list] = defaultdict(list)
    for j in mech.joints:
        if j.kind == "revolute":
            by_point[j.point].append(j)
    out = []
    for p, js in by_point.items():
        links: list[str] = []
        for j in js:
            for ln in j.links:
                if ln not in links:
                    links.append(ln)
        out.append((p, tuple(links), tuple(j.name for j in js)))
    return out


def slider_groups(mech: Mechanism) -> int:
    """γ: independent closed loops made of straight sliding pairs only (Rosenauer §95: the
    3-link slider chain, the wedge, moves although the count says it should not): the sliding
    pairs that join two links already in one rotation class."""
    pris = [j for j in mech.joints if j.kind == "prismatic"]
    classes = RotationClasses({ln for j in pris for ln in j.links})
    return sum(not classes.join(*j.links) for j in pris)


def counts(mech: Mechanism) -> PairCounts:
    """The seed-style counts of `mech`: die blocks of slots unfolded, hinges at one point merged
    into multiple hinges, gears, cam contacts and the intermittent pairs of Geneva and star
    wheels (h = 1 in every phase) as non-self-closed higher pairs, rolling
    contacts as self-closed ones (Rosenauer §109–110: the rolling lever h = 1, the Proell–Schwabe
    wheel on its lever h = 2)."""
    folded = [j for j in mech.joints if j.kind in ("slot", "circular-slot")]
    hinges: dict[int, int] = defaultdict(int)
    for _, links, joints in hinge_groups(mech):
        k = len(links) - 1
        hinges[k] += 1
        extra = len(joints) - k  # revolutes beyond a spanning tree of the hinge's links
        if extra > 0:
            hinges[1] += extra
    hinges[1] += len(folded)  # each die block's pin
    top = max(hinges) if hinges else 1
    ht = tuple(hinges.get(k, 0) for k in range(1, top + 1))
    s = sum(1 for j in mech.joints if j.kind == "prismatic") + len(folded)
    # a rolling pair on two pivots of one carrier (non-circular gears) counts as a gear pair does
    on_pivots = sum(1 for j in mech.joints if j.kind == "rolling" and j.carrier)
    h_n = sum(1 for j in mech.joints if j.kind in ("gear", "cam", "geneva", "star-wheel")) + on_pivots
    h_p = sum(1 for j in mech.joints if j.kind == "rolling") - on_pivots
    return PairCounts(n=len(mech.links) + len(folded), hinges=ht, s=s, h_n=h_n, h_p=h_p,
                      gamma=slider_groups(mech))


def link_degrees(mech: Mechanism) -> dict[str, int]:
    """Elements per link (binary 2, ternary 3, …; Rosenauer §87) of the unfolded chain: the
    pairs each link takes part in, a slot adding one to its pin link and to its slotted link."""
    deg: dict[str, int] = {ln: 0 for ln in mech.link_names}
    for j in mech.joints:
        for ln in j.links:
            deg[ln] += 1
        if j.kind in ("slot", "circular-slot"):
            deg[f"{j.name}:block"] = 2
    return deg


def link_types(mech: Mechanism) -> dict[int, int]:
    """n_i: how many links carry i elements (n₂ binary, n₃ ternary, …)."""
    out: dict[int, int] = defaultdict(int)
    for d in link_degrees(mech).values():
        out[d] += 1
    return dict(sorted(out.items()))


# ---------------------------------------------------------------------------- real mobility


@dataclass(frozen=True)
class Redundant:
    """One constraint equation that repeats what the others already impose."""

    joint: str
    equation: str
    wedge: bool = False  # the rotation equation of a closed slider group (not an over-closure)

    def __str__(self) -> str:
        note = " (closed slider group, Rosenauer's wedge exception)" if self.wedge else ""
        return f"{self.joint}.{self.equation}{note}"


@dataclass(frozen=True)
class Mobility:
    """The count and the real mobility of a mechanism, side by side."""

    mechanism: str
    counts: PairCounts
    moving_links: int
    equations: int
    rank: int
    real_mobility: int
    redundant: tuple[Redundant, ...]
    dependent_pairs: tuple[str, ...]
    drivers: tuple[str, ...]
    surplus_drivers: tuple[str, ...]
    inputs_needed: int
    finite_motion: bool | None = None
    off_design_mobility: int | None = None
    free_spins: tuple[tuple[str, str], ...] = ()  # (link, its pivot's joint)

    @property
    def count_mobility(self) -> int:
        return self.counts.mobility

    @property
    def overclosure(self) -> int:
        """Redundant constraints beyond the closed slider groups' (0 unless over-closed)."""
        return sum(1 for r in self.redundant if not r.wedge)

    @property
    def singular(self) -> bool:
        """The design position is singular: the chain is rigid next to it (only infinitesimally
        mobile), or it moves there with another mobility than next to it (a change position,
        *Wechsellage*, *maiņas punkts*)."""
        return self.finite_motion is False or (
            self.off_design_mobility is not None and self.off_design_mobility != self.real_mobility)

    @property
    def overclosed(self) -> bool:
        """Over-closed (*übergeschlossen*): redundant constraints that persist along the motion."""
        return self.overclosure > 0 and not self.singular

    @property
    def constrained(self) -> bool:
        """*Zwangläufig* with its drivers: every link follows them, and none is too many."""
        return self.inputs_needed == 0 and not self.surplus_drivers

    def verdict(self) -> str:
        parts = []
        if self.finite_motion is False:
            parts.append(f"singular design position: the Jacobian leaves {self.real_mobility} "
                         f"free motion{'s' if self.real_mobility != 1 else ''} there, but the chain "
                         "does not move along it (infinitesimal mobility only; rigid next to it)")
        elif self.singular:
            parts.append(f"singular design position (dead or change position, Wechsellage): "
                         f"mobility {self.real_mobility} there, {self.off_design_mobility} next to it")
        if self.real_mobility == 0:
            parts.append("rigid: no link can move (starr, negrozāma sistēma)")
        if self.overclosed:
            names = ", ".join(str(r) for r in self.redundant if not r.wedge)
            parts.append(f"over-closed (übergeschlossen, pārāk slēgta ķēde): moves only by its "
                         f"special dimensions; {self.overclosure} redundant constraint"
                         f"{'s' if self.overclosure > 1 else ''} ({names})")
        for link, pivot in self.free_spins:
            parts.append(f"free spin: link '{link}' turns freely about its pivot {pivot} (its "
                         "own turning moves no other link: not an input the mechanism needs)")
        if self.inputs_needed > 0:
            parts.append(f"under-constrained: needs {self.inputs_needed} more input"
                         f"{'s' if self.inputs_needed > 1 else ''}"
                         + (" at the design position" if self.singular else ""))
        if self.surplus_drivers:
            parts.append("too many drivers: " + ", ".join(self.surplus_drivers)
                         + " cannot move independently")
        if self.constrained and self.real_mobility > 0 and not self.singular:
            parts.insert(0, "constrained motion (zwangläufig)")
        return "; ".join(parts)

    def as_dict(self) -> dict:
        return {
            "counts": self.counts.as_dict(),
            "count_mobility": self.count_mobility,
            "real_mobility": self.real_mobility,
            "jacobian": {"equations": self.equations, "unknowns": 3 * self.moving_links,
                         "rank": self.rank},
            "redundant_constraints": [
                {"joint": r.joint, "equation": r.equation, "wedge": r.wedge} for r in self.redundant],
            "overclosed": self.overclosed,
            "singular_design_position": self.singular,
            "dependent_pairs": list(self.dependent_pairs),
            "drivers": list(self.drivers),
            "surplus_drivers": list(self.surplus_drivers),
            "inputs_needed": self.inputs_needed,
            "finite_motion": self.finite_motion,
            "off_design_mobility": self.off_design_mobility,
            "free_spins": [{"link": ln, "pivot": p} for ln, p in self.free_spins],
            "constrained": self.constrained,
            "verdict": self.verdict(),
        }


def _on_slider_loop(mech: Mechanism) -> set[str]:
    """Prismatic joints lying on a loop of prismatic joints only."""
    return {j.name for j in mech.joints if j.kind == "prismatic" and slider_loop(mech, j.name)}


def _greedy_dependent(M: np.ndarray, ref: np.ndarray, order: list[int], tol: float) -> list[int]:
    """Rows of M (in `order`) that do not raise the rank of the rows taken before them."""
    from ..kinematics.jacobian import numerical_rank

    taken: list[int] = []
    dependent: list[int] = []
    rank = 0
    for i in order:
        r = numerical_rank(M[taken + [i]], tol, reference=ref)
        if r > rank:
            taken.append(i)
            rank = r
        else:
            dependent.append(i)
    return dependent


def mobility(mech: Mechanism, *, check_finite: bool = True) -> Mobility:
    """The count and the real mobility of `mech` at its design position."""
    from ..kinematics.jacobian import RANK_TOL, design_jacobian, numerical_rank

    c = counts(mech)
    J = design_jacobian(mech, drivers=True)
    n_pair_rows = len(J.rows) - len(mech.drivers)
    P = J.scaled[:n_pair_rows]
    k = len(mech.moving_links)
    rank = numerical_rank(P, RANK_TOL, reference=J.scaled)
    real = 3 * k - rank
    dep = _greedy_dependent(P, J.scaled, list(range(n_pair_rows)), RANK_TOL)
    loops = _on_slider_loop(mech)
    redundant = tuple(Redundant(J.rows[i][0], J.rows[i][1],
                                wedge=(J.rows[i][1] == "angle" and J.rows[i][0] in loops))
                      for i in dep)
    dependent_pairs: tuple[str, ...] = ()
    if dep:
        # rows taking part in some dependency: the support of the left null space
        U, sv, _ = np.linalg.svd(P, full_matrices=True)
        null = U[:, rank:]
        support = np.abs(null).max(axis=1) > 1e-8
        dependent_pairs = tuple(dict.fromkeys(J.rows[i][0] for i in np.flatnonzero(support)))
    # drivers: rows after the pairs
    all_rank = numerical_rank(J.scaled, RANK_TOL)
    surplus_rows = _greedy_dependent(J.scaled, J.scaled, list(range(len(J.rows))), RANK_TOL)
    surplus = tuple(J.rows[i][0] for i in surplus_rows if i >= n_pair_rows)
    spins = _free_spins(mech, J)
    # given point velocities (a chain without drivers) are inputs too, one per scalar condition
    needed = max(0, 3 * k - all_rank - len(spins) - sum(g.count for g in mech.given))
    finite, off = (None, None)
    if check_finite and real > 0 and (dep or real > len(mech.drivers)):
        finite, off = _finite_step(mech, real)
    return Mobility(mechanism=mech.name, counts=c, moving_links=k, equations=n_pair_rows,
                    rank=rank, real_mobility=real, redundant=redundant,
                    dependent_pairs=dependent_pairs, drivers=tuple(d.joint for d in mech.drivers),
                    surplus_drivers=surplus, inputs_needed=needed, finite_motion=finite,
                    off_design_mobility=off, free_spins=spins)


def _free_spins(mech: Mechanism, J) -> tuple[tuple[str, str], ...]:
    """Links that can turn about one of their hinges while everything else stands still: the
    turning about the hinge P, pose rates θ̇·(P_y, −P_x, 1) of that link alone (at the design
    position, where a point s of the link moves as (ẋ − θ̇ s_y, ẏ + θ̇ s_x)), lies in the null
    space of the constraint Jacobian with the drivers (a wheel on its axle that nothing else
    turns, as the Proell–Schwabe wheel would without its rolling condition)."""
    from ..kinematics.jacobian import RANK_TOL

    col = {c: i for i, c in enumerate(J.columns)}
    top = np.linalg.norm(J.scaled, 2) if J.scaled.size else 0.0
    out = []
    for ln in mech.moving_links:
        for j in mech.joints:
            if j.kind != "revolute" or ln not in j.links:
                continue
            P = mech.points[j.point]
            v = np.zeros(len(J.columns))
            v[[col[(ln, "x")], col[(ln, "y")], col[(ln, "θ")]]] = (P[1], -P[0], 1.0)
            vs = v.copy()
            vs[2::3] *= mech.length_scale  # the scaled Jacobian's coordinates
            if np.linalg.norm(J.scaled @ vs) <= RANK_TOL * top * np.linalg.norm(vs):
                out.append((ln, j.name))
                break
    return tuple(out)


def _finite_step(mech: Mechanism, real: int, step: float = 1e-3) -> tuple[bool, int | None]:
    """Move a small step along a free direction of the design position and close the pairs
    again (Gauss–Newton on all residuals, redundant ones included). Returns whether the chain
    closes there (a true motion, not only an infinitesimal one) and its mobility there."""
    from ..kinematics.jacobian import RANK_TOL, constraint_jacobian, numerical_rank, pair_residuals

    scale = mech.length_scale
    k = len(mech.moving_links)
    J0 = constraint_jacobian(mech)
    _, _, Vt = np.linalg.svd(J0.scaled)
    free = Vt[3 * k - real:]  # right null space, scaled coordinates (angles × scale)
    # a deterministic direction in the free space: the sum of its basis vectors
    d = free.sum(axis=0) if real > 1 else free[0]
    if np.linalg.norm(d) < 1e-12:
        d = free[0]
    d = d / np.linalg.norm(d)
    unscale = np.tile([1.0, 1.0, 1.0 / scale], k)

    def to_q(u):
        return u * unscale

    u0 = step * scale * d
    u = u0.copy()
    ok = False
    for _ in range(60):
        q = to_q(u)
        r = pair_residuals(mech, q.reshape(k, 3))
        if not (np.isfinite(r).all() and np.isfinite(q).all()):
            break  # Gauss–Newton ran away (a degenerate drawing): the chain does not close
        along = float(np.dot(d, u - u0))
        if np.abs(r).max(initial=0.0) <= 1e-11 * scale and abs(along) <= 1e-11 * scale:
            ok = True
            break
        Jq = constraint_jacobian(mech, q.reshape(k, 3)).scaled
        A = np.vstack([Jq, d[None]])
        b = -np.concatenate([r, [along]])
        du, *_ = np.linalg.lstsq(A, b, rcond=None)
        u = u + du
    if not ok:
        return False, None
    Jq = constraint_jacobian(mech, to_q(u).reshape(k, 3)).scaled
    return True, 3 * k - numerical_rank(Jq, RANK_TOL)




# ---------------------------------------------------------------------------- the whole report


@dataclass(frozen=True)
class StructureReport:
    """Everything `linkwork structure` prints: counts, real mobility, Assur groups in solution
    order (or why there is none), the mechanism's class, and the Grashof loops."""

    mechanism: Mechanism
    mobility: Mobility
    link_types: dict[int, int]
    groups: tuple | None  # AssurGroup, in solution order
    structure_error: str | None
    mechanism_class: int | None
    loops: tuple  # grashof.LoopReport
    input_limits: tuple[float, float] | None = None
    input_limits_note: str | None = None

    def as_dict(self) -> dict:
        from .assur import ROMAN

        mech = self.mechanism
        return {
            "mechanism": mech.name,
            "units": {"length": mech.length_unit, "angle": "rad"},
            **self.mobility.as_dict(),
            "link_types": {str(k): v for k, v in self.link_types.items()},
            "groups": None if self.groups is None else [g.as_dict() for g in self.groups],
            "solution_order": None if self.groups is None else [list(g.links) for g in self.groups],
            "structure_error": self.structure_error,
            "mechanism_class": self.mechanism_class,
            "mechanism_class_roman": ROMAN.get(self.mechanism_class) if self.mechanism_class else None,
            "grashof": [lp.as_dict() for lp in self.loops],
            "input_limits": None if self.input_limits is None else list(self.input_limits),
            "input_limits_note": self.input_limits_note,
        }


def structure_report(mech: Mechanism, *, limits: bool = True) -> StructureReport:
    """The structural analysis of `mech`. Over- and under-constrained mechanisms are reported,
    not refused: their groups are missing and `structure_error` says why. With `limits`, the
    whole mechanism's input limits are searched numerically (`kinematics.motion.input_limits`)
    when it is constrained and has one driver."""
    from ..errors import LinkworkError
    from .assur import assur_groups, mechanism_class
    from .grashof import loops

    mob = mobility(mech)
    groups, err = None, None
    try:
        groups = assur_groups(mech)
    except LinkworkError as exc:
        err = str(exc)
        if mob.free_spins:
            err += "; of these, " + ", ".join(f"'{ln}' spins freely about its pivot {p}"
                                              for ln, p in mob.free_spins) + " (a free spin)"
    lim, note = None, None
    if limits and groups is not None and len(mech.drivers) == 1 and mob.constrained:
        from ..kinematics.motion import input_limits

        try:
            lim = input_limits(mech)
            if lim is not None:
                lim = (float(lim[0]), float(lim[1]))
            else:
                note = "the input turns fully"
        except LinkworkError as exc:
            note = str(exc)
    return StructureReport(mechanism=mech, mobility=mob, link_types=link_types(mech),
                           groups=groups, structure_error=err,
                           mechanism_class=None if groups is None else mechanism_class(groups),
                           loops=tuple(loops(mech)), input_limits=lim, input_limits_note=note)


__all__ = ["Mobility", "PairCounts", "Redundant", "StructureReport", "chain_counts", "counts",
           "grubler_constrained", "hinge_groups", "kutzbach", "link_degrees", "link_types",
           "mobility", "slider_groups", "structure_report"]
