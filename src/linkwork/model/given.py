"""Given point velocities: a chain driven by the prescribed velocities, or velocity directions,
of several of its points instead of by a crank (German *gegebene Geschwindigkeiten*; Rosenauer
1937, paper 2: free chains, *freie Ketten*, Latvian *brīvas ķēdes*, and open chains, *offene
Ketten*, constructed from v_A, v_B, … or from the directions of motion of B and C).

A condition holds at the chain's drawn position:

* `GivenVelocity`: the velocity vector of a point (two conditions), optionally its acceleration
  (two more, for the acceleration solve);
* `GivenDirection`: the line the velocity of a point lies on (one condition: its component
  along the normal of that line is zero, so the point's pole lies on the normal), optionally the
  curvature of the point's path there (the acceleration's normal component is then κ·v²; a
  straight guide has κ = 0).

Values may be one vector (2,) or a batch (N, 2) of N velocity sets (sample axis first). How many
conditions a chain needs is its mobility at the drawn position, which `linkwork.kinematics.
point_inputs` finds from the rank of its pairs' equations; here only the names and the numbers
are checked.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Union

import numpy as np

from ..errors import ModelError

if TYPE_CHECKING:  # pragma: no cover
    from .mechanism import Mechanism


def _vectors(value, what: str) -> np.ndarray:
    a = np.array(value, dtype=float)
    if a.ndim not in (1, 2) or a.shape[-1] != 2 or not np.isfinite(a).all():
        raise ModelError(f"{what}: give finite [x, y] components (one vector, or N of them), got "
                         f"an array of shape {a.shape}" if a.ndim else f"{what}: give [x, y], got {value!r}")
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class GivenVelocity:
    """The velocity of ``point`` (taken as a point of ``link``; default: the link that reports
    the point), in the length unit per second; ``acceleration`` in the length unit per s²."""

    point: str
    velocity: np.ndarray
    acceleration: np.ndarray | None = None
    link: str | None = None
    kind = "velocity"
    #: scalar conditions it states
    count = 2

    def describe(self) -> str:
        return f"the velocity of {self.point}"


@dataclass(frozen=True, eq=False)
class GivenDirection:
    """The velocity of ``point`` lies along ``direction`` (a vector; its sense and length do not
    matter). ``curvature``: of the point's path, signed, positive where the path bends to the
    left of ``direction`` (1/length; 0 for a straight guide)."""

    point: str
    direction: np.ndarray
    curvature: float | np.ndarray | None = None
    link: str | None = None
    kind = "direction"
    count = 1

    def describe(self) -> str:
        return f"the direction of v_{self.point}"


Given = Union[GivenVelocity, GivenDirection]


def normalized(mech: "Mechanism", given, *, alone: bool = True) -> tuple[Given, ...]:
    """The conditions with their arrays read-only and each condition's link filled in, checked
    against ``mech``: known points and links, a point given once, finite numbers, a direction
    that is no zero vector, batches of one length, and (``alone``: the mechanism's own inputs)
    no drivers beside them."""
    out: list[Given] = []
    seen: dict[str, str] = {}
    sizes: set[int] = set()
    for g in given:
        if not isinstance(g, (GivenVelocity, GivenDirection)):
            raise ModelError(f"a given condition must be a GivenVelocity or a GivenDirection, got {g!r}")
        p = g.point
        if p not in mech.points:
            raise ModelError(f"given point '{p}' is not in [points]")
        if p in seen:
            raise ModelError(f"given point '{p}' is given twice ({seen[p]} and {g.describe()}); "
                             "state each point's data once")
        seen[p] = g.describe()
        link = g.link or mech.point_owner[p]
        if link not in mech.link_index:
            raise ModelError(f"given point '{p}': link '{link}' is not in [links]")
        if p not in mech.link(link).points:
            raise ModelError(f"given point '{p}': link '{link}' does not carry it")
        if link == mech.frame:
            raise ModelError(f"given point '{p}' is a point of the frame '{mech.frame}', which stands "
                             "still: its velocity cannot be given")
        if isinstance(g, GivenVelocity):
            v = _vectors(g.velocity, f"given point '{p}': velocity")
            a = None if g.acceleration is None else _vectors(g.acceleration, f"given point '{p}': acceleration")
            g = replace(g, velocity=v, acceleration=a, link=link)
            arrays = [v] + ([a] if a is not None else [])
        else:
            d = _vectors(g.direction, f"given point '{p}': direction")
            if not (np.hypot(d[..., 0], d[..., 1]) > 0).all():
                raise ModelError(f"given point '{p}': the direction is the zero vector")
            k = None
            if g.curvature is not None:
                k = np.array(g.curvature, dtype=float)
                if k.ndim > 1 or not np.isfinite(k).all():
                    raise ModelError(f"given point '{p}': the curvature must be a finite number (or N of them)")
                k.setflags(write=False)
            g = replace(g, direction=d, curvature=k, link=link)
            arrays = [d] + ([k[:, None]] if k is not None and k.ndim == 1 else [])
        sizes.update(x.shape[0] for x in arrays if x.ndim == 2)
        out.append(g)
    if len(sizes) > 1:
        raise ModelError(f"the given conditions come in batches of different lengths {sorted(sizes)}; "
                         "give one value or N values for each")
    if out and alone and mech.drivers:
        raise ModelError(f"mechanism '{mech.name}' has drivers ({', '.join(d.joint for d in mech.drivers)}) "
                         "and given point velocities: a chain is driven by one or the other")
    return tuple(out)


def batch_size(given) -> int:
    """N of the batch the conditions hold (1 when every value is a single one)."""
    for g in given:
        for x in (getattr(g, "velocity", None), getattr(g, "acceleration", None),
                  getattr(g, "direction", None)):
            if x is not None and np.ndim(x) == 2:
                return int(np.shape(x)[0])
        k = getattr(g, "curvature", None)
        if k is not None and np.ndim(k) == 1:
            return int(np.shape(k)[0])
    return 1


def condition_count(given) -> int:
    """The number of scalar conditions the given data state (2 per velocity, 1 per direction)."""
    return sum(g.count for g in given)


def hinge_chain(name: str, points, links, given=(), *, frame: str = "frame",
                length_unit: str = "mm", description: str = "") -> "Mechanism":
    """A hinge chain written as its links only (``{"CDG": ["C", "D", "G"], "AC": ["A", "C"]}``):
    every point two links share is a hinge between them, as the papers draw their chains. The
    ``frame`` is the link of that name if listed (an open chain on its frame), else an empty
    one (a free chain); ``given``: its given point velocities or directions."""
    from .mechanism import Mechanism, Revolute

    pts = {k: list(v) for k, v in links.items()}
    pts.setdefault(frame, [])
    names = list(pts)
    joints = []
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            for p in pts[a]:
                if p in pts[b]:
                    joints.append(Revolute(p if p not in {j.name for j in joints} else f"{p}_{b}", p, (a, b)))
    return Mechanism.build(name=name, points=points, links=pts, joints=joints, drivers=[], frame=frame,
                           length_unit=length_unit, description=description, given=given)
