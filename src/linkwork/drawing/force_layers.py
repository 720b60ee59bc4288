"""The force layer: the pair reactions and the driver's effort at one input, drawn at scale on
the mechanism (the books' force plan, German *Kräfteplan* in the mechanism's drawing).

Owns :func:`force_scale` (the force scale *Kräftemaßstab* M_F, N per mm of paper, chosen like
the velocity scale of :meth:`~.layers.Scene.auto_scales`: the largest force about a third of
the drawing, rounded to a nice value) and :func:`draw_forces`. Every pair's reaction is drawn
as the force its links[0] exerts on its links[1], at the pair's point (the convention of
:mod:`linkwork.forces.kinetostatics`), labelled with the pair's name; a driver's force is drawn
the same way along its guide, a driver's torque as a turning arrow at its hinge with its value
(a couple has no point, so no length at scale). Couples of prismatic pairs are listed in the
legend.
"""

from __future__ import annotations

import numpy as np

from ..constructions.scales import Scale, nice_ceil
from ..errors import InputError, ModelError
from ..forces import ForceAnalysis, kinetostatics
from ..forces.loads import rotate
from ..model import Prismatic
from ..model.inertia import Dynamics
from .svg import Figure, Style

FORCE_COLOUR = "#8b1a1a"
EFFORT_COLOUR = "#c05800"


def force_analysis(dyn: Dynamics, sc) -> ForceAnalysis:
    """Kinetostatics of the scene's one sample; missing mass data is an :class:`InputError`
    naming the links."""
    try:
        return kinetostatics(dyn, sc.sol, virtual_work=False)
    except ModelError as exc:
        raise InputError(f"the forces layer: {exc}") from None


def _max_force(fa: ForceAnalysis, i: int, mech) -> float:
    mags = [float(r.magnitude[i]) for r in fa.reactions.values()]
    mags += [abs(float(fa.efforts[d.joint][i])) for d in mech.drivers
             if isinstance(mech.joint(d.joint), Prismatic)]
    mags = [m for m in mags if np.isfinite(m)]
    return max(mags, default=0.0)


def force_scale(sc, fa: ForceAnalysis, per_mm: float | None = None) -> Scale:
    """M_F in N per mm of paper: ``per_mm`` if given, else the largest drawn force about
    0.3 × the drawing's extent long (as the velocity vectors), rounded to a nice value."""
    if per_mm is None:
        vec_mm = 0.3 * sc.extent() / sc.scales.length.per_mm
        per_mm = nice_ceil((_max_force(fa, sc.index, sc.mech) or 1.0) / vec_mm)
    return Scale("force", "N", per_mm)


def draw_forces(fig: Figure, sc, dyn: Dynamics, *, per_mm: float | None = None,
                layer: str = "forces") -> tuple[ForceAnalysis, Scale]:
    """Add the reactions and the driver's effort of the scene's sample to ``fig``; returns the
    analysis and the force scale used (also shown as a scale bar in the legend)."""
    fa = force_analysis(dyn, sc)
    mech, i = sc.mech, sc.index
    scale = force_scale(sc, fa, per_mm)
    # a force of 1 N is drawn kF mechanism units long: the two scales combined
    kF = sc.scales.length.per_mm / scale.per_mm
    fig.extra_scales = [*getattr(fig, "extra_scales", []), scale]
    fig.note("forces: each pair's reaction is the force of its first link on its second")
    if not bool(fa.solved[i]):
        fig.note("forces: not computed at this input (unreachable, or a dead centre of the force "
                 "transmission)")
        return fa, scale
    tiny = 1e-9 * mech.length_scale
    for name, r in fa.reactions.items():
        p, f = r.point[i], r.force[i]
        if not (np.all(np.isfinite(p)) and np.all(np.isfinite(f))):
            continue
        if np.linalg.norm(f) * kF < tiny:
            fig.note(f"{name}: no force ({r.links[0]} on {r.links[1]})")
            continue
        head = p + kF * f
        fig.arrow(p, head, style=Style(stroke=FORCE_COLOUR, width=0.45), layer=layer,
                  ident=f"force-{name}")
        fig.label(head, f"F_{{{name}}}", colour=FORCE_COLOUR, size=3.0,
                  prefer=np.array([f[0], -f[1]]), ident=f"force-{name}")
        if r.couple[i] != 0:
            fig.note(f"{name}: couple {r.couple[i]:.6g} N·m ({r.links[0]} on {r.links[1]})")
    for d in mech.drivers:
        j = mech.joint(d.joint)
        e = float(fa.efforts[d.joint][i])
        if not np.isfinite(e):
            continue
        p = sc.pos(j.point)
        if isinstance(j, Prismatic):
            u = rotate(np.float64(sc.theta(j.links[0])), j.axis)  # the guide's direction now
            u = u / np.linalg.norm(u)
            if abs(e) * kF < tiny:
                continue
            head = p + kF * e * u
            fig.arrow(p, head, style=Style(stroke=EFFORT_COLOUR, width=0.5), layer=layer,
                      ident=f"effort-{d.joint}")
            fig.label(head, f"F_{{{d.joint}}} = {e:.4g} N", colour=EFFORT_COLOUR, size=3.0,
                      ident=f"effort-{d.joint}")
        else:
            _torque(fig, p, e, 4.0 * sc.scales.length.per_mm, layer, d.joint)
        fig.note(f"driver {d.joint}: {'force' if isinstance(j, Prismatic) else 'torque'} "
                 f"{e:.6g} {'N' if isinstance(j, Prismatic) else 'N·m'} ({d.base} on {d.driven})")
    return fa, scale


def _torque(fig: Figure, centre: np.ndarray, torque: float, r: float, layer: str, joint: str) -> None:
    """A turning arrow of 3/4 turn about ``centre`` in the sense of ``torque`` (counter-clockwise
    positive), radius ``r`` (mechanism units), with the value."""
    if torque == 0:
        return
    s = np.sign(torque)
    t = np.linspace(0.25 * np.pi, 0.25 * np.pi + s * 1.5 * np.pi, 40)
    xy = centre + r * np.stack([np.cos(t), np.sin(t)], -1)
    st = Style(stroke=EFFORT_COLOUR, width=0.45)
    fig.path(xy[:-1], style=st, layer=layer, ident=f"effort-{joint}")
    fig.arrow(xy[-3], xy[-1], style=st, layer=layer)
    fig.label(xy[0], f"M_{{{joint}}} = {torque:.4g} N·m", colour=EFFORT_COLOUR, size=3.0,
              ident=f"effort-{joint}")
