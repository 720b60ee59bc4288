"""Pöschl's graphical calculus of point motion drawn as the books draw it (ch. II–III).

Owns :func:`differentiation_steps` (the s–t line differentiated with a pole, step by step, §7),
:func:`integration_steps` (the a–t line integrated by strips and mean ordinates, §10a),
:func:`plans_figure` (the r-, v- and b-plan of a point with the poles O, P, Q, the associated
points A, V, B and the tangents: the v-plan's tangent at V is the direction of the acceleration,
the b-plan's at B that of the jerk, §13) and :func:`vs_steps` (step-by-step constructions on the
v–s line: the subnormal construction of the acceleration and the time by integrating 1/v, §9–10).
The numbers drawn come from :mod:`linkwork.constructions.motion_calculus`, which works on drawing
lengths as the draughtsman does; each figure writes the engine's exact value next to the
constructed one. Figures are Matplotlib (Agg); :func:`linkwork.drawing.plots.save` writes them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..constructions.motion_calculus import (differentiate, integrate, integrate_reciprocal, plan,
                                             plan_scale, reciprocal_scale, subnormal)
from ..constructions.scales import nice_ceil
from ..errors import InputError
from ..kinematics import Solution, whole_motion
from ..model import Mechanism
from .plots import _abscissa, _plt, path_coordinate, subscripted

INK, AUX, RES = "#000000", "#6b6b6b", "#b3001b"


def _deg(v: np.ndarray) -> float:
    return float(np.degrees(np.arctan2(v[1], v[0])))


def _angle_between(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.degrees(abs(np.arctan2(a[0] * b[1] - a[1] * b[0], a @ b))))


def _num(v: float) -> str:
    """A scale's round number written out as the books do (20000, not 2e+04)."""
    return f"{v:.6g}" if 1e-4 <= abs(v) < 1e7 else f"{v:.3g}"


def _scale_bar(ax, scale: float, unit: str, quantity: str) -> None:
    """A bar of 1, 2 or 5 cm under the drawing with the value it stands for (the book's scale)."""
    x0, x1 = ax.get_xlim()
    y0, _ = ax.get_ylim()
    cm = 1.0 if (x1 - x0) < 8 else 2.0
    ax.plot([x0 + 0.3, x0 + 0.3 + cm], [y0 + 0.3] * 2, color=INK, lw=1.6, solid_capstyle="butt")
    ax.text(x0 + 0.3 + cm / 2, y0 + 0.45, f"{_num(cm * scale)} {unit}", ha="center", va="bottom", fontsize=7)
    ax.set_title(ax.get_title() + f"\n${quantity}$ = {_num(scale)} {unit} per cm", fontsize=8)


def _frame(ax, pts: np.ndarray, pad: float = 1.0) -> None:
    lo, hi = np.nanmin(pts, 0) - pad, np.nanmax(pts, 0) + pad
    lo[1] -= 0.8  # room for the scale bar
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    for s in ax.spines.values():
        s.set_linewidth(0.4)
        s.set_color(AUX)


TAN = "#1f4e9c"


def _tangent_line(ax, at: np.ndarray, direction: np.ndarray, length: float, label: str) -> None:
    """The tangent drawn through ``at``, labelled at its forward end (on the side away from the
    curve's bend, where the label does not sit on the curve)."""
    d = direction / np.linalg.norm(direction)
    a, b = at - d * length / 2, at + d * length / 2
    ax.plot([a[0], b[0]], [a[1], b[1]], "--", color=TAN, lw=0.9, zorder=4)
    # labelled at the end nearer the middle of the drawing, so that the label stays inside it
    mid = np.array([np.mean(ax.get_xlim()), np.mean(ax.get_ylim())])
    if np.linalg.norm(a - mid) < np.linalg.norm(b - mid):
        a, b, d = b, a, -d
    ax.annotate(label, b, fontsize=7, color=TAN, xytext=(3 * np.sign(d[0] or 1), 3),
                textcoords="offset points", ha="left" if d[0] >= 0 else "right", annotation_clip=True)


def _arrow(ax, tail, head, color, label: str, lw: float = 1.4) -> None:
    ax.annotate("", head, tail, arrowprops=dict(arrowstyle="-|>", color=color, lw=lw, shrinkA=0, shrinkB=0))
    ax.annotate(label, head, fontsize=8, color=color, xytext=(3, -9), textcoords="offset points")


def _pole(ax, xy, name: str) -> None:
    ax.plot([xy[0]], [xy[1]], "o", ms=4, mfc="white", mec=INK, mew=1.0, zorder=5)
    ax.annotate(name, xy, fontsize=8, xytext=(-9, -9), textcoords="offset points")


@dataclass(frozen=True)
class PlanCheck:
    """What :func:`plans_figure` drew and read, next to the engine's values."""

    index: int
    tangent_v_vs_acceleration_deg: float  # angle between the v-plan's drawn tangent and a
    tangent_b_vs_jerk_deg: float  # angle between the b-plan's drawn tangent and the jerk
    acceleration_read: np.ndarray  # the v-plan tip's velocity (nature)
    acceleration: np.ndarray  # the engine's


def _motion(mech: Mechanism, point: str, solution: Solution | None) -> tuple[Solution, np.ndarray]:
    if point not in mech.points:
        raise InputError(f"mechanism '{mech.name}' has no point '{point}'")
    sol = solution or whole_motion(mech, order=3)
    if sol.order < 3:
        raise InputError("the plans need the jerk: solve to order 3")
    if np.any(sol.status == 2):
        raise InputError(f"the motion of '{mech.name}' has unreachable positions: its plans would break there")
    t, _ = _abscissa(mech, sol, "time")
    if np.any(np.diff(t) <= 0):
        raise InputError(f"the motion of '{point}' has no increasing time axis to draw its plans on")
    return sol, t


def _index(sol: Solution, at: float | None, keep: np.ndarray) -> int:
    """The sample among ``keep`` nearest the input value ``at`` (radians or length), kept off the
    two ends where the drawn tangent has one neighbour only; default an eighth into them."""
    idx = np.flatnonzero(keep)
    if at is None:
        j = len(idx) // 8
    else:
        u = sol.inputs[idx, 0]
        j = int(np.argmin(np.abs(np.angle(np.exp(1j * (u - at)))) if np.ptp(u) > 6 else np.abs(u - at)))
    return int(idx[min(max(j, 1), len(idx) - 2)])


def plans_figure(mech: Mechanism, point: str, *, at: float | None = None,
                 solution: Solution | None = None) -> tuple[object, PlanCheck]:
    """The r-plan (path, from O), v-plan (from the pole P) and b-plan (from the pole Q) of
    ``point`` over the whole motion (Pöschl §13, Abb. 6), with the associated points A, V, B at
    the sample nearest the input ``at`` and the tangents: at A the path's (∥ v), at V the
    v-plan's (∥ b, the acceleration is the v-plan's velocity), at B the b-plan's (∥ jerk). Each
    plan at a round scale given under it. Returns the figure and the check against the engine."""
    sol, t = _motion(mech, point, solution)
    m = sol.point(point)
    # the plans over the samples where every vector is defined (at a dead centre or a jump of an
    # intermittent mechanism the rates are not): the plan's curve is broken there, not invented
    keep = np.all(np.isfinite(np.hstack([m.position, m.velocity, m.acceleration, m.jerk])), axis=1)
    if keep.sum() < 3:
        raise InputError(f"'{point}' has too few positions with defined rates to draw its plans")
    if not keep.all():
        runs = np.flatnonzero(np.diff(np.concatenate([[0], keep.astype(int), [0]])))
        i0, i1 = max(zip(runs[::2], runs[1::2]), key=lambda r: r[1] - r[0])
        keep = np.zeros(len(keep), bool)
        keep[i0:i1] = True
    k_abs = _index(sol, at, keep)
    m = type(m)(*(None if x is None else x[keep] for x in (m.position, m.velocity, m.acceleration, m.jerk)))
    t = t[keep]
    k = k_abs - int(np.flatnonzero(keep)[0])
    u = mech.length_unit
    l_r = plan_scale(m.position)
    rp = plan(t, m.position, scale=l_r)
    vp = plan(t, m.velocity, scale=plan_scale(m.velocity))
    bp = plan(t, m.acceleration, scale=plan_scale(m.acceleration))
    tv, tb, tr = vp.tangent()[k], bp.tangent()[k], rp.tangent()[k]
    a_read = vp.rate()[k]
    check = PlanCheck(k_abs, _angle_between(tv, m.acceleration[k]), _angle_between(tb, m.jerk[k]),
                      a_read, m.acceleration[k])
    plt = _plt()
    fig, axes = plt.subplots(1, 3, figsize=(11.0, 4.6))
    O, P, Q = np.zeros(2), np.zeros(2), np.zeros(2)
    # the tips: the file's point itself and the book's V, B with the point's name as subscript
    # (so that they are not taken for the file's own points of those names)
    panels = (
        (axes[0], rp, "r-plan (path)", "O", point.replace("$", "\\$"), "l_l", u, tr, "∥ v", "r"),
        (axes[1], vp, "v-plan (hodograph of v)", "P", subscripted("V", point), "l_v", f"{u}/s", tv, "∥ a", "v"),
        (axes[2], bp, "b-plan (hodograph of a)", "Q", subscripted("B", point), "l_b", f"{u}/s²", tb, "∥ jerk", "a"),
    )
    for ax, p, title, pole, tip, sym, unit, tan, tan_label, vec in panels:
        W = p.W
        ax.plot(W[:, 0], W[:, 1], "-", color=INK, lw=1.0)
        span = float(np.max(np.ptp(np.vstack([W, [[0, 0]]]), 0)))
        _frame(ax, np.vstack([W, [[0.0, 0.0]]]))
        ax.set_title(title, fontsize=9)
        _pole(ax, O if pole == "O" else (P if pole == "P" else Q), pole)
        _arrow(ax, np.zeros(2), W[k], RES if vec != "r" else AUX, f"{tip}", lw=1.2)
        _tangent_line(ax, W[k], tan, 0.45 * span, tan_label)
        _scale_bar(ax, p.scale, unit, sym)
    # the acceleration drawn from Q parallel to the v-plan's tangent at V: the associated point B
    import textwrap
    fig.text(0.01, 0.01, textwrap.fill(f"The arrow from Q is parallel to the v-plan's tangent at V: the acceleration is the "
             f"velocity of V along the v-plan (drawn tangent {check.tangent_v_vs_acceleration_deg:.2g}° off the "
             f"engine's acceleration); the b-plan's tangent at B is the jerk's direction "
             f"({check.tangent_b_vs_jerk_deg:.2g}° off the engine's).", 190), fontsize=7, color=AUX)
    fig.suptitle(f"{mech.name}: plans of {point} (Pöschl §13), the associated points at "
                 f"{_input_words(mech, sol, k_abs)}", fontsize=10)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    return fig, check


def _input_words(mech: Mechanism, sol: Solution, k: int) -> str:
    d = mech.drivers[0]
    if mech.joint(d.joint).kind == "revolute":
        return f"{d.joint} = {np.degrees(sol.inputs[k, 0]) % 360:.1f}°"
    return f"{d.joint} = {sol.inputs[k, 0]:.4g} {mech.length_unit}"


# ---------------------------------------------------------------------------- v–s constructions
@dataclass(frozen=True)
class VsStep:
    text: str


def _stroke(mech: Mechanism, point: str, solution: Solution | None):
    """One stroke of ``point`` along its path: s increasing, v > 0 (the first run of the motion
    in which the point moves forward), with its times. Returns (s, v, t, a_t, l_s, l_v)."""
    if point not in mech.points:
        raise InputError(f"mechanism '{mech.name}' has no point '{point}'")
    sol = solution or whole_motion(mech)
    t, _ = _abscissa(mech, sol, "time")
    m = sol.point(point)
    s, v, straight = path_coordinate(m.position, m.velocity)
    speed = np.linalg.norm(m.velocity, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        e = m.velocity / speed[:, None] * np.sign(v)[:, None]
    a_t = np.sum(m.acceleration * e, axis=1)
    closed = bool(np.allclose(m.position[0], m.position[-1], atol=1e-9 * (1 + float(np.ptp(m.position)))))
    n = len(s)
    if closed:
        # a periodic motion: one period more, so that a stroke across the end is whole
        period = t[-1] - t[0]
        s = np.concatenate([s, s[1:] + (s[-1] - s[0]) * (not straight)])
        v, a_t = np.concatenate([v, v[1:]]), np.concatenate([a_t, a_t[1:]])
        t = np.concatenate([t, t[1:] + period])
    fwd = (v > 0) & np.isfinite(v) & np.isfinite(t)
    # the longest run of forward motion
    edges = np.flatnonzero(np.diff(np.concatenate([[0], fwd.astype(int), [0]])))
    runs = list(zip(edges[::2], edges[1::2]))
    if not runs:
        raise InputError(f"'{point}' does not move along its path: no v–s line")
    i0, i1 = max(runs, key=lambda r: r[1] - r[0])
    i1 = min(i1, i0 + n)  # one period at most (a loop run forward all round)
    if i1 - i0 < 8:
        raise InputError(f"'{point}' moves forward for a few samples only: no v–s line to construct on")
    sl = slice(i0, i1)
    s, v, t, a_t = s[sl] - s[i0], v[sl], t[sl], a_t[sl]
    if np.any(np.diff(s) <= 0):
        raise InputError(f"the path coordinate of '{point}' does not increase along its stroke")
    l_s = nice_ceil(float(np.ptp(s)) / 10.0)  # the stroke at most 10 cm long
    l_v = nice_ceil(float(np.max(v)) / 5.0)  # the v–s line at most 5 cm high
    return s, v, t, a_t, l_s, l_v, straight


def vs_steps(mech: Mechanism, point: str, construction: str, *, at: float | None = None,
             strips: int = 8, H: float = 2.0, solution: Solution | None = None):
    """A construction on the v–s line of ``point`` drawn step by step: ``subnormal`` (the
    acceleration at the path position nearest ``at``, a fraction 0…1 of the stroke, default
    0.8) or ``time`` (t = ∫ds/v by strips with harmonic-mean ordinates and the pole at H′ cm,
    eq. 26–28, from 5 % to 95 % of the stroke, where v ≠ 0; the pole is laid off to the left
    and the t–s line grows downward, the book's figure mirrored in the s axis, so that the
    chords stay perpendicular to their rays without covering the v–s line). Returns (figures, step
    texts, (constructed, exact)): one figure per step, each drawing everything up to that step
    on the same sheet; the last compares the result with the engine's value."""
    s, v, t, a_t, l_s, l_v, straight = _stroke(mech, point, solution)
    S, V = s / l_s, v / l_v
    u = mech.length_unit
    plt = _plt()
    xlim = (-0.5 - (H if construction == "time" else 0.0), S.max() + 1.0)
    if construction == "subnormal":
        f = 0.8 if at is None else float(at)
        if not 0.0 < f < 1.0:
            raise InputError(f"--at {at}: give the position on the stroke as a fraction between 0 and 1")
        k = int(np.argmin(np.abs(s - (s[0] + f * np.ptp(s)))))
        k = min(max(k, 1), len(s) - 2)
        sn = subnormal(s, v, k, l_s=l_s, l_v=l_v)
        exact = float(a_t[k])
        texts = [f"the v–s line of {point}: s at l_s = {l_s:.4g} {u}/cm, v at l_v = {l_v:.4g} {u}/s per cm",
                 "at the point A of the line its ordinate AF",
                 "the tangent to the line at A",
                 "the normal at A, perpendicular to the tangent; it cuts the s axis in N",
                 f"the subnormal FN = V·dV/dS = {sn.N[0] - sn.F[0]:.3f} cm; "
                 f"a = l_a·FN, l_a = l_v²/l_s = {sn.l_a:.4g} {u}/s² per cm: "
                 f"a = {sn.acceleration:.5g} {u}/s² (engine {exact:.5g})"]
        ylo = min(0.0, sn.N[1]) - 1.0
        figs = []
        for step in range(len(texts)):
            fig, ax = _vs_sheet(plt, S, V, xlim, (ylo, V.max() + 1.0), texts, step, point)
            A, F, N = sn.A, sn.F, sn.N
            if step >= 1:
                ax.plot(*A, "o", color=INK, ms=4)
                ax.plot([A[0], F[0]], [A[1], F[1]], color=AUX, lw=0.9)
                ax.annotate("A", A, xytext=(4, 4), textcoords="offset points", fontsize=8)
                ax.annotate("F", F, xytext=(-9, -11), textcoords="offset points", fontsize=8)
            if step >= 2:
                _tangent_line(ax, A, sn.tangent, 4.0, "tangent")
            if step >= 3:
                ax.plot([A[0], N[0]], [A[1], N[1]], "-.", color=AUX, lw=0.9)
                ax.plot([A[0] + 0.0], [A[1]], alpha=0)
                ax.annotate("N", N, xytext=(3, -11), textcoords="offset points", fontsize=8)
                ax.plot(*N, "o", color=AUX, ms=3)
            if step >= 4:
                ax.plot([F[0], N[0]], [0.0, 0.0], color=RES, lw=2.4, solid_capstyle="butt")
                ax.annotate("a", ((F[0] + N[0]) / 2, 0), xytext=(0, 4), textcoords="offset points",
                            fontsize=9, color=RES, ha="center")
            figs.append(fig)
        return figs, texts, (sn.acceleration, exact)
    if construction != "time":
        raise InputError(f"a v–s construction is 'subnormal' or 'time', not '{construction}'")
    if strips < 1:
        raise InputError(f"the 1/v integration needs one strip at least, not {strips}")
    _positive_H(H)
    b = s[0] + np.ptp(s) * np.linspace(0.05, 0.95, strips + 1)
    d = integrate_reciprocal(s, v, b, l_x=l_s, l_y=l_v, H=H, samples=16)
    exact = np.interp(b, s, t) - np.interp(b[0], s, t)
    l_t = reciprocal_scale(H, l_s, l_v)
    # the t–s line is drawn below the s axis (time grows downward, as the book lays it off)
    Z = d.Y
    texts = [f"the v–s line of {point}: s at l_s = {l_s:.4g} {u}/cm, v at l_v = {l_v:.4g} {u}/s per cm",
             f"{strips} strips from 5 % to 95 % of the stroke (v ≠ 0), each with its mean ordinate "
             "(harmonic mean of 16 ordinates, as 1/v is integrated)",
             "each mean ordinate projected to the v axis (M″); the pole P′ at H′ = "
             f"{H:g} cm from the origin (left: the t–s line is laid off downward), the rays P′M″",
             "in each strip the chord of the t–s line perpendicular to its ray: ΔZ = H′ΔS/V_m (eq. 26)",
             f"t = l_t·Z, l_t = l_s/(H′ l_v) = {l_t:.4g} s per cm (eq. 28): t = {d.y[-1]:.5g} s over the "
             f"strips (engine {exact[-1]:.5g} s)"]
    ylo = -Z.max() - 1.0
    figs = []
    P = np.array([-H, 0.0])
    for step in range(len(texts)):
        fig, ax = _vs_sheet(plt, S, V, xlim, (ylo, V.max() + 1.0), texts, step, point)
        X = d.X
        if step >= 1:
            for j in range(strips):
                ax.fill_between([X[j], X[j + 1]], 0, d.means[j], color="#dfe7f3", lw=0)
                ax.plot([X[j], X[j + 1]], [d.means[j]] * 2, color=AUX, lw=0.8)
            for x in X:
                ax.axvline(x, color=AUX, lw=0.4, ymin=0, ymax=1, alpha=0.5)
        if step >= 2:
            _pole(ax, P, "P′")
            for j in range(strips):
                M = np.array([0.0, d.means[j]])
                ax.plot([X[j], 0.0], [d.means[j]] * 2, ":", color=AUX, lw=0.6)
                ax.plot([P[0], M[0]], [P[1], M[1]], color=AUX, lw=0.6)
        if step >= 3:
            ax.plot(X, -Z, "-", color=RES, lw=1.4, marker=".", ms=4)
            ax.annotate("t–s line", (X[-1], -Z[-1]), xytext=(4, 0), textcoords="offset points",
                        fontsize=8, color=RES)
        if step >= 4:
            inside = (s >= b[0]) & (s <= b[-1])
            ax.plot(s[inside] / l_s, -(t[inside] - np.interp(b[0], s, t)) / l_t, color=INK, lw=0.6,
                    label="engine: t(s)")
            ax.legend(fontsize=7, loc="lower left")
        figs.append(fig)
    return figs, texts, (d.y, exact)


def differentiation_steps(mech: Mechanism, point: str, *, chords: int = 12, H: float = 2.0,
                          solution: Solution | None = None):
    """Pöschl's graphical differentiation (§7, Abb. 1) of the s–t line of ``point`` over one
    stroke, step by step: the chords of the s–t line; the pole P at H cm left of the origin and
    through it the rays parallel to the chords, cutting the ordinate axis at V = H·ΔS/ΔT; each
    V carried over to its chord's middle gives the v–t line at l_v = l_s/(H l_t) (eq. 3).
    Returns (figures, step texts, (v read at the chords' middles, the engine's v there))."""
    if chords < 2:
        raise InputError(f"graphical differentiation needs two chords at least, not {chords}")
    _positive_H(H)
    s, v, t, a_t, l_s, l_v0, straight = _stroke(mech, point, solution)
    t = t - t[0]
    l_t = nice_ceil(float(t[-1]) / 10.0)  # the stroke's time at most 10 cm long
    idx = np.unique(np.linspace(0, len(t) - 1, chords + 1).round().astype(int))
    T, S = t[idx], s[idx]
    d = differentiate(T, S, l_t=l_t, l_x=l_s, H=H)
    exact = np.interp(d.x, t, v)
    u = mech.length_unit
    texts = [f"the s–t line of {point} over one stroke: t at l_t = {_num(l_t)} s/cm, s at l_s = {_num(l_s)} {u}/cm",
             f"{len(idx) - 1} chords of the s–t line",
             f"the pole P at H = {H:g} cm left of the origin; through it the rays parallel to the chords "
             "cut the ordinate axis at V = H·ΔS/ΔT",
             "each V carried over to the middle of its chord: the points of the v–t line (below)",
             f"v = l_v·V, l_v = l_s/(H l_t) = {_num(d.l_y)} {u}/s per cm (eq. 3); largest difference from "
             f"the engine's v at the chords' middles {np.max(np.abs(d.y - exact)):.3g} {u}/s "
             f"(the chord's slope is the mean velocity over it)"]
    plt = _plt()
    TT, SS = t / l_t, s / l_s
    Vmax = float(np.max(np.abs(d.Y)))
    xlim = (-H - 0.8, TT.max() + 1.0)
    ylim = (-Vmax - 1.0 - 0.5, max(SS.max(), Vmax) + 1.0)
    figs = []
    # the v–t diagram below the s–t diagram, on the same t axis (the book's Abb. 1): its own t
    # axis at `off`, the pole P on it H cm left of its origin
    off = -Vmax - 0.5
    P = np.array([-H, off])
    for step in range(len(texts)):
        fig, ax = _sheet(plt, xlim, ylim, texts, step)
        ax.axhline(off, color=INK, lw=0.4)
        ax.plot(TT, SS, color=INK, lw=1.2)
        ax.annotate("s", (0, ylim[1]), xytext=(4, -10), textcoords="offset points", fontsize=9)
        ax.annotate("t", (xlim[1], 0), xytext=(-8, 4), textcoords="offset points", fontsize=9)
        Tc, Sc = T / l_t, S / l_s
        if step >= 1:
            ax.plot(Tc, Sc, "-", color=RES, lw=0.8, marker=".", ms=4)
        if step >= 2:
            _pole(ax, P, "P")
            for V in d.Y:
                ax.plot([P[0], 0.0], [off, off + V], color=AUX, lw=0.5)
        if step >= 3:
            for X, V in zip(d.X, d.Y):
                ax.plot([0.0, X], [off + V, off + V], ":", color=AUX, lw=0.5)
            ax.plot(d.X, d.Y + off, "o", color=RES, ms=3)
            ax.annotate("v–t line", (d.X[-1], d.Y[-1] + off), xytext=(4, 0), textcoords="offset points",
                        fontsize=8, color=RES)
        if step >= 4:
            ax.plot(TT, v / d.l_y + off, color=INK, lw=0.6, label="engine: v(t)")
            ax.legend(fontsize=7, loc="lower right")
        figs.append(fig)
    return figs, texts, (d.y, exact)


def integration_steps(mech: Mechanism, point: str, *, strips: int = 8, H: float = 2.0,
                      solution: Solution | None = None):
    """Pöschl's graphical integration by strips (§10a, the polygon method) of the a–t line of
    ``point`` over one stroke (a the tangential acceleration along its path), step by step: the
    strips and each one's mean ordinate Y_m (the rectangle of the strip's area); each Y_m carried
    to the ordinate axis and joined to the pole P at H cm left of the origin; in the v–t diagram
    below, strip after strip from v₀ at the stroke's start, the chord parallel to that strip's ray
    (ΔZ = Y_m·ΔT/H, eq. 22). The chord polygon's corners are v at the strip boundaries, at
    l_v = H l_t l_a (eq. 24). Returns (figures, step texts, (v read at the boundaries, the
    engine's v there))."""
    if strips < 1:
        raise InputError(f"graphical integration needs one strip at least, not {strips}")
    _positive_H(H)
    s, v, t, a_t, l_s, l_v0, straight = _stroke(mech, point, solution)
    t = t - t[0]
    l_t = nice_ceil(float(t[-1]) / 10.0)  # the stroke's time at most 10 cm long
    l_a = nice_ceil(float(np.max(np.abs(a_t))) / 3.0)  # the a–t line at most 3 cm high
    b = np.linspace(0.0, float(t[-1]), strips + 1)
    d = integrate(t, a_t, b, l_x=l_t, l_y=l_a, H=H)
    Z = d.Y + v[0] / d.l_y  # the polygon starts at v₀ (the constant of integration)
    read = Z * d.l_y
    exact = np.interp(b, t, v)
    u = mech.length_unit
    texts = [f"the a–t line of {point} over one stroke (a along the path): t at l_t = {_num(l_t)} s/cm, "
             f"a at l_a = {_num(l_a)} {u}/s² per cm",
             f"{strips} strips; in each the mean ordinate Y_m, the height of the rectangle of the strip's "
             "area",
             f"each Y_m carried to the ordinate axis; the pole P at H = {H:g} cm left of the origin and the "
             "rays from P to them",
             "below, strip after strip from v₀ at the stroke's start: the chord parallel to the strip's ray "
             "(ΔZ = Y_m·ΔT/H); its corners are the v–t line at the strip boundaries",
             f"v = l_v·Z, l_v = H l_t l_a = {_num(d.l_y)} {u}/s per cm (eq. 24); largest difference from "
             f"the engine's v at the boundaries {np.max(np.abs(read - exact)):.3g} {u}/s (the mean "
             "ordinates keep each strip's area, so the corners are exact up to the drawing)"]
    plt = _plt()
    TT, AA = t / l_t, a_t / l_a
    Amax = float(np.max(np.abs(AA)))
    off = -Amax - 0.8 - float(np.max(Z))  # the v–t diagram's axis, below the a–t diagram
    xlim = (-H - 0.8, TT.max() + 1.0)
    ylim = (off - 0.8, Amax + 1.0)
    B = b / l_t
    P = np.array([-H, 0.0])
    figs = []
    for step in range(len(texts)):
        fig, ax = _sheet(plt, xlim, ylim, texts, step)
        ax.axhline(off, color=INK, lw=0.4)
        ax.plot(TT, AA, color=INK, lw=1.2)
        ax.annotate("a", (0, ylim[1]), xytext=(4, -10), textcoords="offset points", fontsize=9)
        ax.annotate("t", (xlim[1], 0), xytext=(-8, 4), textcoords="offset points", fontsize=9)
        ax.annotate("v", (0, off + float(np.max(Z))), xytext=(4, 4), textcoords="offset points",
                    fontsize=9)
        if step >= 1:
            for lo, hi, Ym in zip(B[:-1], B[1:], d.means):
                ax.plot([lo, lo, hi, hi], [0.0, Ym, Ym, 0.0], color=RES, lw=0.7)
        if step >= 2:
            _pole(ax, P, "P")
            for Ym, lo in zip(d.means, B[:-1]):
                ax.plot([lo, 0.0], [Ym, Ym], ":", color=AUX, lw=0.5)
                ax.plot([P[0], 0.0], [0.0, Ym], color=AUX, lw=0.5)
        if step >= 3:
            ax.plot(B, Z + off, "-", color=RES, lw=1.0, marker="o", ms=3)
            ax.annotate("v–t line", (B[-1], Z[-1] + off), xytext=(4, 0), textcoords="offset points",
                        fontsize=8, color=RES)
        if step >= 4:
            ax.plot(TT, v / d.l_y + off, color=INK, lw=0.6, label="engine: v(t)")
            ax.legend(fontsize=7, loc="lower right")
        figs.append(fig)
    return figs, texts, (read, exact)


def _sheet(plt, xlim, ylim, texts, step):
    """One sheet of a step-by-step construction in cm of drawing (equal scales), the same size for
    every step so that the drawing does not jump when paging; the step's sentence above it."""
    import textwrap
    w_cm, h_cm = xlim[1] - xlim[0], ylim[1] - ylim[0]
    width = 8.0
    height = min(11.0, max(3.0, width * 0.85 * h_cm / w_cm) + 1.4)
    fig, ax = plt.subplots(figsize=(width, height))
    ax.axhline(0, color=INK, lw=0.6)
    ax.axvline(0, color=INK, lw=0.6)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_aspect("equal")
    ax.set_xlabel("cm of drawing", fontsize=7)
    ax.tick_params(labelsize=6)
    ax.grid(True, lw=0.2, alpha=0.5)
    ax.set_title(textwrap.fill(f"step {step + 1} of {len(texts)}: {texts[step]}", 100), fontsize=8,
                 loc="left")
    fig.subplots_adjust(left=0.06, right=0.97, bottom=0.1 * 6 / height, top=1 - 0.75 / height)
    return fig, ax


def _positive_H(H: float) -> None:
    if not (np.isfinite(H) and H > 0):
        raise InputError(f"the pole distance H must be positive, got {H!r}")


def _vs_sheet(plt, S, V, xlim, ylim, texts, step, point):
    """A sheet (:func:`_sheet`) with the v–s line and its axes' names."""
    fig, ax = _sheet(plt, xlim, ylim, texts, step)
    ax.plot(S, V, color=INK, lw=1.2)
    ax.annotate("s", (xlim[1], 0), xytext=(-8, 4), textcoords="offset points", fontsize=9)
    ax.annotate(subscripted("v", point), (0, ylim[1]), xytext=(4, -10), textcoords="offset points", fontsize=9)
    return fig, ax
