"""Plots over the whole motion with Matplotlib (*Weg-, Geschwindigkeits- und
Beschleunigungsdiagramme*).

Owns :func:`motion_plot` (positions, velocities or accelerations of chosen points — components
and magnitude — and angles, angular velocities or accelerations of chosen links, against the
input or the time) and :func:`vs_plot` (the v–s diagram of a point, Rosenauer §61 II: velocity
over the path; for a point on a straight line the acceleration is the diagram's subnormal
v·dv/ds, drawn as a check for a chosen position) and :func:`graphical_motion` (Pöschl's s–t,
v–t, a–t lines with the graphical differentiation by chords). All return a Matplotlib ``Figure``
(Agg backend, no display needed); :func:`save` writes PNG, PDF or SVG.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

import numpy as np

from ..errors import InputError
from ..outputs import output_path
from ..kinematics import Solution, whole_motion
from ..model import Mechanism

QUANTITIES = ("position", "velocity", "acceleration")
COMPONENTS = ("x", "y", "magnitude")


def _plt():
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    return plt


#: characters a user's name may have and still be set upright inside mathtext
_MATH_SAFE = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_ .,-'")


def subscripted(symbol: str, name: str, extra: str = "") -> str:
    """``symbol`` with the user's point or link ``name`` as its subscript, the name printed as
    written (upright, ``pin_A`` keeps its underscore; ``extra`` such as ``,x`` follows it). A name
    with characters mathtext would read as commands is written after the symbol instead."""
    if set(name) <= _MATH_SAFE:
        body = name.replace("_", r"\_").replace(" ", r"\ ")
        return f"${symbol}_{{\\mathrm{{{body}}}{extra}}}$"
    return f"${symbol}$ ({name.replace('$', chr(92) + '$')}{extra})"


def _abscissa(mech: Mechanism, sol: Solution, against: str) -> tuple[np.ndarray, str]:
    if against == "time":
        if sol.time is not None:
            return sol.time, "time t [s]"
        d = mech.drivers[0]
        w = sol.link(d.driven).omega if mech.joint(d.joint).kind == "revolute" else None
        u = sol.inputs[:, 0]
        rate = np.gradient(u) if w is None else w
        dt = np.diff(u) / np.where(rate[:-1] == 0, np.nan, rate[:-1])
        t = np.concatenate([[0.0], np.nancumsum(np.abs(dt))])
        return t, "time t [s]"
    if against != "input":
        raise InputError(f"plot against 'input' or 'time', not '{against}'")
    d = mech.drivers[0]
    if mech.joint(d.joint).kind == "revolute":
        u = np.degrees(sol.inputs[:, 0])
        # unwrap a full turn into a monotonic axis as the books plot it
        return u, f"input angle \u03c6 [\u00b0] ({d.joint})"
    return sol.inputs[:, 0], f"input displacement s [{mech.length_unit}] ({d.joint})"


def motion_plot(mech: Mechanism, *, points: Sequence[str] = (), links: Sequence[str] = (),
                quantity: str = "velocity", against: str = "input",
                components: Sequence[str] = COMPONENTS, solution: Solution | None = None,
                title: str | None = None):
    """Quantity of points and links over the whole motion (or over ``solution``'s samples)."""
    if quantity not in QUANTITIES:
        raise InputError(f"quantity must be one of {', '.join(QUANTITIES)}, not '{quantity}'")
    bad = [c for c in components if c not in COMPONENTS]
    if bad:
        raise InputError(f"unknown component(s) {', '.join(bad)}; use x, y, magnitude")
    if not points and not links:
        raise InputError("choose at least one point (--point) or link (--link) to plot")
    for p in points:
        if p not in mech.points:
            raise InputError(f"mechanism '{mech.name}' has no point '{p}'")
    for ln in links:
        mech.link(ln)
    sol = solution or whole_motion(mech)
    x, xlabel = _abscissa(mech, sol, against)
    plt = _plt()
    nax = (1 if points else 0) + (1 if links else 0)
    fig, axes = plt.subplots(nax, 1, figsize=(8.0, 3.2 * nax + 0.6), sharex=True, squeeze=False)
    axes = axes[:, 0]
    unit = mech.length_unit
    sym = {"position": ("r", unit), "velocity": ("v", f"{unit}/s"), "acceleration": ("a", f"{unit}/s\u00b2")}
    k = 0
    if points:
        ax = axes[k]
        k += 1
        s, u = sym[quantity]
        for p in points:
            m = sol.point(p)
            arr = {"position": m.position, "velocity": m.velocity, "acceleration": m.acceleration}[quantity]
            for c in components:
                y = np.linalg.norm(arr, axis=1) if c == "magnitude" else arr[:, "xy".index(c)]
                style = "-" if c == "magnitude" else ("--" if c == "x" else ":")
                lab = f"|{subscripted(s, p)}|" if c == "magnitude" else subscripted(s, p, f",{c}")
                ax.plot(x, y, style, lw=1.2, label=lab)
        ax.set_ylabel(f"{quantity} [{u}]")
        ax.legend(loc="best", fontsize=8, ncol=2)
        ax.grid(True, lw=0.3, alpha=0.6)
    if links:
        ax = axes[k]
        for ln in links:
            m = sol.link(ln)
            if quantity == "position":
                y, lab, u = np.degrees(np.unwrap(m.angle)), subscripted(r"\varphi", ln), "\u00b0"
            elif quantity == "velocity":
                y, lab, u = m.omega, subscripted(r"\omega", ln), "rad/s"
            else:
                y, lab, u = m.alpha, subscripted(r"\alpha", ln), "rad/s\u00b2"
            ax.plot(x, y, lw=1.2, label=lab)
        ax.set_ylabel({"position": "angle", "velocity": "angular velocity",
                       "acceleration": "angular acceleration"}[quantity] + f" [{u}]")
        ax.legend(loc="best", fontsize=8)
        ax.grid(True, lw=0.3, alpha=0.6)
    axes[-1].set_xlabel(xlabel)
    fig.suptitle(title or f"{mech.name}: {quantity} over the whole motion", fontsize=11)
    fig.tight_layout()
    return fig


def path_coordinate(position: np.ndarray, velocity: np.ndarray) -> tuple[np.ndarray, np.ndarray, bool]:
    """(s, v, straight): the path coordinate and the velocity along it. A straight path uses the
    displacement along its line (signed); a curved one the arc length and the signed speed
    (positive along the first direction of travel)."""
    d = position - position[0]
    span = np.nanmax(np.linalg.norm(d, axis=1))
    if span == 0:
        return np.zeros(len(d)), np.zeros(len(d)), True
    # principal direction; the path is straight if the points deviate by < 1e-9 of its span
    c = position - np.nanmean(position, axis=0)
    _, sv, vt = np.linalg.svd(np.nan_to_num(c), full_matrices=False)
    straight = sv[1] <= 1e-9 * max(sv[0], 1e-300)
    if straight:
        e = vt[0]
        return c @ e, velocity @ e, True
    seg = np.linalg.norm(np.diff(position, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    t = np.diff(position, axis=0)
    t = np.vstack([t, t[-1:]])
    sign = np.sign(np.sum(t * velocity, axis=1))
    return s, sign * np.linalg.norm(velocity, axis=1), False


def vs_plot(mech: Mechanism, point: str, *, solution: Solution | None = None, title: str | None = None):
    """The v–s diagram of ``point`` over the whole motion (Rosenauer §61 II)."""
    if point not in mech.points:
        raise InputError(f"mechanism '{mech.name}' has no point '{point}'")
    sol = solution or whole_motion(mech)
    m = sol.point(point)
    s, v, straight = path_coordinate(m.position, m.velocity)
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.0, 4.5))
    ax.plot(s, v, lw=1.3, color="#1f4e9c")
    ax.axhline(0.0, color="#888", lw=0.5)
    u = mech.length_unit
    ax.set_xlabel(("displacement s" if straight else "arc length s") + f" [{u}]")
    ax.set_ylabel(f"velocity {subscripted('v', point)} [{u}/s]")
    ax.grid(True, lw=0.3, alpha=0.6)
    if straight:
        ax.text(0.02, 0.96, "acceleration = subnormal v\u00b7dv/ds", transform=ax.transAxes, fontsize=8,
                va="top")
    fig.suptitle(title or f"{mech.name}: v\u2013s diagram of {point}", fontsize=11)
    fig.tight_layout()
    return fig


def graphical_motion(mech: Mechanism, point: str, *, chords: int = 36, H: float = 2.0,
                     solution: Solution | None = None):
    """Pöschl's motion diagrams of ``point`` along its path (ch. II §7): the s–t, v–t, a–t and
    jerk lines (a the tangential acceleration d²s/dt², the jerk d³s/dt³), the last three from the
    engine, and over them the graphically differentiated chord polygons (pole distance ``H`` cm,
    ``chords`` chords over the motion, :mod:`linkwork.constructions.motion_calculus`) as markers,
    read at the derived scales l_v = l_s/(H l_t), l_a = l_v/(H l_t), l_j = l_a/(H l_t), which
    are given in the panels' titles. The engine's jerk line needs a solution to order 3 (solved
    so when ``solution`` is not given); without it only the chords are drawn."""
    from ..constructions.motion_calculus import differentiate, path_jerk
    if point not in mech.points:
        raise InputError(f"mechanism '{mech.name}' has no point '{point}'")
    if chords < 2:
        raise InputError(f"graphical differentiation needs two chords at least, not {chords}")
    sol = solution or whole_motion(mech, order=3)
    m = sol.point(point)
    t, tlabel = _abscissa(mech, sol, "time")
    s, v, straight = path_coordinate(m.position, m.velocity)
    speed = np.linalg.norm(m.velocity, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        e = m.velocity / speed[:, None] * np.sign(v)[:, None]
    if straight:  # the line's direction, also where the point stands still
        e = np.tile(e[np.nanargmax(speed)], (len(v), 1))
    a = np.sum(m.acceleration * e, axis=1)
    jerk = None if m.jerk is None else path_jerk(m.velocity, m.acceleration, m.jerk, e)
    ok = np.isfinite(t) & np.isfinite(s) & np.isfinite(v)
    if ok.sum() < 3 or np.any(np.diff(t[ok]) <= 0):
        raise InputError(f"the motion of '{point}' has no increasing time axis to draw the diagrams on")
    idx = np.unique(np.linspace(0, ok.sum() - 1, chords + 1).round().astype(int))
    T, S, V = t[ok][idx], s[ok][idx], v[ok][idx]
    # drawing scales as the book chooses them: the t axis about 15 cm, the s line about 5 cm high
    l_t = float(np.ptp(T)) / 15.0 or 1.0
    l_s = float(np.ptp(S)) / 5.0 or 1.0
    dv = differentiate(T, S, l_t=l_t, l_x=l_s, H=H)
    da = differentiate(T, V, l_t=l_t, l_x=dv.l_y, H=H)
    # the a–t line's chords over the samples where the acceleration is finite (an intermittent
    # mechanism's acceleration jumps, and is undefined at the jump)
    fa = ok & np.isfinite(a)
    A = np.interp(T, t[fa], a[fa]) if fa.sum() >= 2 else np.full(len(T), np.nan)
    good = np.isfinite(A)
    dj = differentiate(T[good], A[good], l_t=l_t, l_x=da.l_y, H=H) if good.sum() >= 3 else None
    u = mech.length_unit
    plt = _plt()
    fig, axes = plt.subplots(4, 1, figsize=(7.5, 10.0), sharex=True)
    axes[0].plot(t, s, lw=1.2, color="#000")
    axes[0].plot(T, S, "-", lw=0.5, color="#b3001b", marker=".", ms=3, label="chords")
    axes[0].set_ylabel(f"s [{u}]")
    axes[0].set_title(f"s–t line, $l_s$ = {l_s:.3g} {u}/cm, $l_t$ = {l_t:.3g} s/cm", fontsize=9)
    axes[1].plot(t, v, lw=1.2, color="#1f4e9c", label="engine")
    axes[1].plot(dv.x, dv.y, "o", ms=3, color="#b3001b", label=f"chord slopes, H = {H:g} cm")
    axes[1].set_ylabel(f"v [{u}/s]")
    axes[1].set_title(f"v–t line, $l_v = l_s/(H\\,l_t)$ = {dv.l_y:.3g} {u}/s per cm", fontsize=9)
    axes[2].plot(t, a, lw=1.2, color="#1b7a3a", label="engine (tangential)")
    axes[2].plot(da.x, da.y, "o", ms=3, color="#b3001b", label=f"chord slopes, H = {H:g} cm")
    axes[2].set_ylabel(f"a [{u}/s²]")
    axes[2].set_title(f"a–t line, $l_a = l_v/(H\\,l_t)$ = {da.l_y:.3g} {u}/s² per cm", fontsize=9)
    if jerk is not None:
        axes[3].plot(t, jerk, lw=1.2, color="#7a4b1b", label="engine (d³s/dt³)")
    axes[3].set_ylabel(f"j [{u}/s³]")
    if dj is not None:
        axes[3].plot(dj.x, dj.y, "o", ms=3, color="#b3001b", label=f"chord slopes, H = {H:g} cm")
        axes[3].set_title(f"jerk–t line, $l_j = l_a/(H\\,l_t)$ = {dj.l_y:.3g} {u}/s³ per cm", fontsize=9)
    axes[3].set_xlabel(tlabel)
    for ax in axes:
        ax.axhline(0.0, color="#888", lw=0.5)
        ax.grid(True, lw=0.3, alpha=0.6)
        ax.legend(fontsize=7, loc="upper right")
    fig.suptitle(f"{mech.name}: motion diagrams of {point.replace('$', chr(92) + '$')} ("
                 + ("displacement" if straight else "arc length") + ", graphical differentiation)", fontsize=10)
    fig.tight_layout()
    return fig


def save(fig, path: str | Path, dpi: float = 150.0) -> Path:
    path = Path(path)
    if path.suffix.lower() not in (".png", ".pdf", ".svg"):
        raise InputError(f"cannot write '{path}': plots are written as .png, .pdf or .svg")
    try:
        with output_path(path) as tmp:  # all or nothing
            fig.savefig(tmp, dpi=dpi, format=path.suffix.lower()[1:])
    finally:
        _plt().close(fig)
    return path
