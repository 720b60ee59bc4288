"""The Aronhold–Kennedy construction of all poles, line by line (*Dreipolsatz*, Rosenauer
§62, §75, §91–92; Pöschl §51).

Owns :func:`kennedy`. The schedule comes from the poles layer
(:func:`linkwork.instant.pole_schedule`): the primary poles are read off the pairs (a hinge is
the pole of its two links; a block on a guide has its pole at infinity normal to the guide; a
gear pair's pole is its pitch point; a pin in a slot gives the contact normal, one line through
the pole); then each further pole P_ij is drawn as the intersection of two lines P_ik P_jk and
P_im P_jm through poles already found (the three poles of three links lie on one line). Lines
through a pole at infinity are parallels. Where the schedule's two lines are (nearly) parallel at a
position, the best-conditioned pair of the other lines of that step is used and reported.

Every pole is compared with the poles from the velocity solution (:func:`linkwork.instant.poles`),
by the projective distance (so poles at infinity compare by direction). Poles the theorem cannot
reach (chains without four-bar loops, Rosenauer 1937) are listed in a note.
"""

from __future__ import annotations

from itertools import combinations

import numpy as np

from .construction import Builder, Construction, Role, safe_join
from ..geometry import Point
from ..instant import pole_schedule, poles
from ..instant.poles import contact_normal_line, pole_label, primary_pole
from ..model import Mechanism
from ._common import as_solution, singular_positions

SOURCE = "Rosenauer §62, §75, §91–92; Pöschl §51 (Aronhold–Kennedy three-pole theorem)"


def _lab(links, pair) -> str:
    t = pole_label(links, pair)
    return "P_{" + t[1:] + "}"


def kennedy(mech: Mechanism, inputs) -> Construction:
    """All poles of ``mech`` at ``inputs`` by the three-pole theorem, drawn step by step."""
    sol = as_solution(mech, inputs)
    n = len(sol)
    sch = pole_schedule(mech)
    links = sch.links
    b = Builder("kennedy", "Aronhold\u2013Kennedy construction of the poles", SOURCE, n)
    singular_positions(b, sol)
    b.own_labels = False
    legend = ", ".join(f"{i + 1} = {ln}" for i, ln in enumerate(links))
    b.step(f"Number the links ({legend}); the mechanism has {len(links) * (len(links) - 1) // 2} poles.")
    known: dict[tuple[str, str], Point] = {}
    words = {"hinge": "the hinge {}", "common hinge": "the hinge {}",
             "slider": "at infinity, normal to the guide of {}",
             "gear": "the pitch point of the gear pair {}",
             "rolling": "the point of contact of the rolling pair {}"}
    for st in sch.primary:
        lab = _lab(links, st.pair)
        b.step(f"{lab} is {words[st.rule].format(st.joint)}.")
        known[st.pair] = b.point(f"pole.{pole_label(links, st.pair)}", Point(primary_pole(sol, st)),
                                 Role.GIVEN, lab, kind="pole")
    for st in sch.derived:
        lab = _lab(links, st.pair)
        lines, texts = [], []
        for k, src in enumerate(st.lines):
            if src.poles is not None:
                p, q = (known[x] for x in src.poles)
                ln, _ = safe_join(p, q)
                texts.append("".join(_lab(links, x) for x in src.poles))
                lines.append((ln, (p, q)))
            else:
                ln, through = _normal(sol, src.joint)
                texts.append(f"the contact normal of {src.joint}")
                lines.append((ln, through))
        b.step(f"{lab} = {texts[0]} \u2229 {texts[1]} (three-pole theorem).")
        keys = []
        for k, (ln, through) in enumerate(lines[:2]):
            key = f"line.{pole_label(links, st.pair)}.{k}"
            b.add(key, ln, Role.AUXILIARY, None, kind="line", span=[p for p in through])
            keys.append(key)
        x = _best(lines, b, lab, mech.length_scale, texts)
        P = b.point(f"pole.{pole_label(links, st.pair)}", Point(x), Role.RESULT, lab, kind="pole")
        for key in keys:
            b.extend(key, P)
        known[st.pair] = P
    if sch.unreachable:
        labs = ", ".join(pole_label(links, p) for p in sch.unreachable)
        b.step(f"Not reachable by the three-pole theorem: {labs} (they need the velocities).")
    ref = poles(sol)
    o = np.mean(np.array(list(mech.points.values())), axis=0)
    for pair, P in known.items():
        # a pole the theorem leaves undetermined (reported above) has nothing to be compared with
        undetermined = np.isnan(P.coords).any(axis=1)
        r = Point(np.where(undetermined[:, None], np.nan, ref[pair].coords))
        b.compare_points(pole_label(links, pair), pole_label(links, pair), f"pole of {pair[0]} and {pair[1]}",
                         P, r, mech.length_scale, o)
    return b.finish()


def _normal(sol, joint: str):
    """The line through the relative pole of a pin in a slot, a cam or an intermittent pair
    (`instant.poles.contact_normal_line`) and the points it is drawn through."""
    X, d, K = contact_normal_line(sol, joint)
    pin = Point.from_xy(X)
    if K is not None:  # a circular slot: through the pin and the slot's centre
        c = Point.from_xy(K)
        ln, _ = safe_join(pin, c)
        return ln, (pin, c)
    ln, _ = safe_join(pin, Point.at_infinity(d))
    return ln, (pin,)


def _best(lines, b: Builder, lab: str, L: float, texts: list[str]) -> np.ndarray:
    """The intersection of the first two lines; where they coincide or are nearly parallel, the
    best-conditioned pair of the others (reported). Lines are compared in coordinates scaled by
    the mechanism size L, where |l1 × l2| is small exactly when the lines (nearly) coincide."""
    def unit(c):
        c = np.array(c.coords, float)
        c[:, 2] /= L
        with np.errstate(invalid="ignore", divide="ignore"):
            return c / np.linalg.norm(c, axis=1, keepdims=True)
    U = [unit(ln) for ln, _ in lines]
    x0 = np.cross(U[0], U[1])
    qual = np.nan_to_num(np.linalg.norm(x0, axis=1), nan=-1.0)
    best = x0.copy()
    first_bad = qual <= 1e-9
    alt = np.zeros(len(x0), bool)
    for i, j in combinations(range(len(U)), 2):
        if (i, j) == (0, 1):
            continue
        x = np.cross(U[i], U[j])
        q = np.nan_to_num(np.linalg.norm(x, axis=1), nan=-1.0)
        better = first_bad & (q > qual)
        best[better] = x[better]
        qual = np.where(better, q, qual)
        alt |= better
    undefined = qual <= 1e-9
    b.limiting(alt & ~undefined & ~b.bad, f"the lines {texts[0]} and {texts[1]} coincide here; "
               f"another pair of pole lines through {lab} was used")
    b.limiting(undefined & ~b.bad, f"the pole lines through {lab} ({' and '.join(texts)}) coincide "
               f"here (e.g. because three links share one hinge), so {lab} (and every pole found "
               "from it) is undetermined by the three-pole theorem")
    best[undefined] = np.nan
    best[:, :2] *= 1.0
    best[:, 2] = best[:, 2] / L  # back to unscaled homogeneous coordinates (x, y, w/L)
    return best
