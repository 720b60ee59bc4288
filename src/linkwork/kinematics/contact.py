"""Higher pairs in the solver: contact coordinates, their constraint equations, and the contact
report (contact points, common normal, pressure angle, sliding).

Where a higher pair touches is not a property of either link: it is the parameter u of the
contact on the profile of links[0], and v on the follower's element (a second profile, the flat
face). The solver treats these as coordinates of their own, solved with the link poses of the
pair's group: every higher pair adds one *contact row* `@NAME` to the pose array
Q[k, n, row, 3] after the links, holding (u − u0, v − v0, 0), zero in the design drawing as every
link pose is. Its equations are written once at position level on jets like every other pair's
(the profile's derivatives enter by Taylor composition, `Jet.compose`), so velocities,
accelerations, jerks and snaps through the pair are exact:

- roller (radius ρ) and knife edge (ρ = 0) at C: the tangential and normal components of
  C − c(u) are 0 and ±ρ (2 rows, unknown u);
- flat face through P along e: c(u) lies on the face, c′(u) is parallel to e (2 rows, unknown u;
  the contact's place along the face is reported, not solved);
- two profiles: c₂(v) = c₁(u) and c′₁ ∥ c′₂ (3 rows, unknowns u, v);
- rolling: as two profiles, and the arc lengths rolled off both are equal (4 rows).

A contact row's unused coordinates get trivial rows (held at zero), so each group's system
stays square and its condition number meaningful.
"""

from __future__ import annotations

from functools import lru_cache
from types import MappingProxyType
from typing import Mapping

import numpy as np

from ..model import CamContact, Mechanism, RollingContact, design_contact
from .jet import Jet

PREFIX = "@"


def is_higher(j) -> bool:
    return isinstance(j, (CamContact, RollingContact))


def row_name(pair) -> str:
    return PREFIX + pair.name


@lru_cache(maxsize=256)
def rows(mech: Mechanism) -> tuple[str, ...]:
    """Rows of the pose array: the links, then one contact row per higher pair."""
    return mech.link_names + tuple(row_name(j) for j in mech.joints if is_higher(j))


@lru_cache(maxsize=256)
def row_index(mech: Mechanism) -> Mapping[str, int]:
    return MappingProxyType({n: i for i, n in enumerate(rows(mech))})


@lru_cache(maxsize=256)
def _design(mech: Mechanism, name: str):
    return design_contact(mech, mech.joint(name))


@lru_cache(maxsize=256)
def rolling_sense(mech: Mechanism, name: str) -> float:
    """+1 when the two profiles' parameters run the same way at the contact (arc lengths grow
    together as they roll), −1 when they run against each other."""
    j = mech.joint(name)
    d = _design(mech, name)
    t1 = mech.profiles[j.profiles[0]].derivatives(np.array(d.u0), 1)[1]
    t2 = mech.profiles[j.profiles[1]].derivatives(np.array(d.v0), 1)[1]
    return 1.0 if float(t1 @ t2) >= 0 else -1.0


def _curve(profile, u: Jet, order: int) -> tuple[Jet, Jet, Jet, Jet]:
    """Jets of c(u) and c′(u) (x and y each) for the parameter jet u."""
    D = profile.derivatives(u.c[0], order + 1)
    c = u.compose(D[: order + 1])
    t = u.compose(D[1: order + 2])
    return Jet(c.c[..., 0]), Jet(c.c[..., 1]), Jet(t.c[..., 0]), Jet(t.c[..., 1])


def _arc_length(profile, u: Jet, order: int) -> Jet:
    """Jet of the arc length s(u): s(u₀) from the profile, its u-derivatives from |c′(u)|."""
    D = profile.derivatives(u.c[0], order)  # c, c′, …, c⁽ᵒʳᵈᵉʳ⁾
    # |c′(u₀ + δ)| as a series in δ, then s⁽ᵐ⁺¹⁾(u₀) = m!·(its m-th coefficient)
    tx = Jet.from_derivatives(D[1:, ..., 0])
    ty = Jet.from_derivatives(D[1:, ..., 1])
    speed = (tx * tx + ty * ty).sqrt()
    derivs = np.empty((order + 1,) + u.c.shape[1:])
    derivs[0] = profile.arc_length(u.c[0])
    for m in range(order):
        derivs[m + 1] = speed.derivative(m)
    return u.compose(derivs)


def residuals(mech: Mechanism, j, pose, point, rotate) -> list[Jet]:
    """Constraint rows of higher pair `j` (lengths), on the jets `pose(row)` gives; `point` and
    `rotate` map design coordinates and directions of a link into the frame."""
    d = _design(mech, j.name)
    q = pose(row_name(j))
    order = q[0].order
    L = mech.length_scale
    u = q[0] + d.u0
    a, b = j.links
    prof = mech.profiles[j.profile if isinstance(j, CamContact) else j.profiles[0]]
    cx, cy, tx, ty = _curve(prof, u, order)
    cwx, cwy = point(pose, a, (cx, cy))
    twx, twy = rotate(pose, a, (tx, ty))
    inv = (tx * tx + ty * ty).sqrt().reciprocal()
    trivial_w = q[2] * L
    follower = j.follower if isinstance(j, CamContact) else "rolling"
    if follower in ("roller", "knife"):
        Cx, Cy = point(pose, b, mech.points[j.point])
        dx, dy = Cx - cwx, Cy - cwy
        along = (dx * twx + dy * twy) * inv
        across = (twx * dy - twy * dx) * inv - d.sign * j.radius
        return [along, across, q[1] * 1.0, trivial_w]
    if follower == "flat":
        P = mech.points[j.point]
        Px, Py = point(pose, b, P)
        ex, ey = rotate(pose, b, j.axis)
        on_face = (cwx - Px) * (-ey) + (cwy - Py) * ex
        parallel = (twx * ey - twy * ex) * inv * L
        return [on_face, parallel, q[1] * 1.0, trivial_w]
    mate = mech.profiles[j.mate if isinstance(j, CamContact) else j.profiles[1]]
    v = q[1] + d.v0
    mx, my, sx, sy = _curve(mate, v, order)
    mwx, mwy = point(pose, b, (mx, my))
    swx, swy = rotate(pose, b, (sx, sy))
    dx, dy = mwx - cwx, mwy - cwy
    rows_ = [(dx * twx + dy * twy) * inv, (twx * dy - twy * dx) * inv,
             (twx * swy - twy * swx) * inv * (sx * sx + sy * sy).sqrt().reciprocal() * L]
    if follower == "rolling":
        s1 = _arc_length(prof, u, order)
        s2 = _arc_length(mate, v, order)
        s10 = float(prof.arc_length(np.array(d.u0)))
        s20 = float(mate.arc_length(np.array(d.v0)))
        rows_.append((s1 - s10) - (s2 - s20) * rolling_sense(mech, j.name))
    rows_.append(trivial_w)
    return rows_


def contact_row_count(j) -> int:
    """Equations of a higher pair's contact row (its 3 coordinates plus the freedoms it removes)."""
    return 3 + (2 if isinstance(j, RollingContact) else 1)


def design_offsets(mech: Mechanism, name: str) -> tuple[float, float]:
    d = _design(mech, name)
    return d.u0, d.v0
