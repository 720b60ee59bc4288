"""Design parameters of a mechanism and the designs of a sweep.

A parameter is a dimension of the drawing (the design position defines everything, README):
`P.x` / `P.y` a point's coordinate, `A-B` the distance from point A to point B, changed by
moving B along the line from A, or `A-B.angle` the direction of B from A (degrees,
counter-clockwise from the x-axis), changed by turning B about A (nothing else moves). A design is one value per parameter;
`apply` builds the mechanism of a design (`Mechanism.build` again: lengths, slot radii and the
assembly branch follow from the new drawing, as they do from a file).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..model import Mechanism

_NAME = re.compile(r"^(?P<a2>[^\s=:-]+)-(?P<b2>[^\s=:-]+)\.angle$|^(?P<p>[^\s.=:-][^\s=:]*?)\.(?P<c>[xy])$"
                   r"|^(?P<a>[^\s=:-]+)-(?P<b>[^\s=:-]+)$")


@dataclass(frozen=True)
class Parameter:
    """One design parameter: `kind` "x", "y" (a coordinate of `point`), "length" (the
    distance from `base` to `point`, along which `point` moves) or "angle" (the direction of
    `point` from `base` in degrees, about which `point` turns)."""

    name: str
    kind: str
    point: str
    base: str | None = None

    def value(self, mech: Mechanism) -> float:
        p = np.asarray(mech.points[self.point], dtype=float)
        if self.kind == "length":
            return float(np.linalg.norm(p - mech.points[self.base]))
        if self.kind == "angle":
            d = p - mech.points[self.base]
            return float(np.degrees(np.arctan2(d[1], d[0])))
        return float(p[0 if self.kind == "x" else 1])


def parameter(mech: Mechanism, name: str, named: dict[str, str] | None = None) -> Parameter:
    """The parameter `name` of `mech` (`P.x`, `P.y` or `A-B`, or a name the file's
    `[parameters]` table, `named`, gives one of those), or an `InputError` naming what is wrong
    with it."""
    if named and name.strip() in named:
        p = parameter(mech, named[name.strip()])
        return Parameter(name.strip(), p.kind, p.point, p.base)
    m = _NAME.match(name.strip())
    if m is None:
        raise InputError(f"--vary {name}: name a coordinate (P.x, P.y), a distance (A-B) or a direction (A-B.angle) of the "
                         "drawing's points, or a parameter of the file's [parameters]"
                         + (f" ({', '.join(sorted(named))})" if named else ""))
    known = sorted(mech.points)
    if m.group("p"):
        if m.group("p") not in mech.points:
            raise InputError(f"--vary {name}: there is no point '{m.group('p')}' (points: {', '.join(known)})")
        return Parameter(name, m.group("c"), m.group("p"))
    a, b = (m.group("a"), m.group("b")) if m.group("a") else (m.group("a2"), m.group("b2"))
    for p in (a, b):
        if p not in mech.points:
            raise InputError(f"--vary {name}: there is no point '{p}' (points: {', '.join(known)})")
    if np.linalg.norm(np.asarray(mech.points[b], float) - mech.points[a]) == 0:
        raise InputError(f"--vary {name}: the points {a} and {b} coincide, so the line along which "
                         f"{b} moves is undefined")
    return Parameter(name, "length" if m.group("a") else "angle", b, a)


def apply(mech: Mechanism, params: list[Parameter], values) -> Mechanism:
    """The mechanism whose drawing has `values` for `params` (in order; a length first moves
    its point along the line from its base in the original drawing)."""
    pts = {k: np.array(v, dtype=float) for k, v in mech.points.items()}
    for prm, v in zip(params, values):
        v = float(v)
        if not np.isfinite(v):
            raise InputError(f"parameter {prm.name}: the value {v} is not a finite number")
        if prm.kind == "length":
            if v <= 0:
                raise InputError(f"parameter {prm.name}: a length must be positive, got {v:g}")
            base = pts[prm.base]
            d = np.asarray(mech.points[prm.point], float) - mech.points[prm.base]
            pts[prm.point] = base + v * d / np.linalg.norm(d)
        elif prm.kind == "angle":
            r = np.linalg.norm(pts[prm.point] - pts[prm.base])
            pts[prm.point] = pts[prm.base] + r * np.array([np.cos(np.radians(v)), np.sin(np.radians(v))])
        else:
            pts[prm.point][0 if prm.kind == "x" else 1] = v
    return Mechanism.build(name=mech.name, points=pts, links={l.name: list(l.points) for l in mech.links},
                           joints=list(mech.joints), drivers=list(mech.drivers), frame=mech.frame,
                           length_unit=mech.length_unit, description=mech.description,
                           profiles=dict(mech.profiles), given=mech.given)


def _numbers(text: str, what: str) -> list[float]:
    try:
        return [float(x) for x in text.split(":")]
    except ValueError:
        raise InputError(f"--vary {what}: values must be numbers, got '{text}'") from None


def grid_values(spec: str) -> tuple[str, np.ndarray]:
    """`NAME=START:STOP:STEP` → (NAME, values from START to STOP inclusive) or `NAME=V[,V…]`."""
    name, sep, rng = spec.partition("=")
    if not sep or not name.strip():
        raise InputError(f"--vary {spec}: write NAME=START:STOP:STEP or NAME=V,V,…")
    if "," in rng or ":" not in rng:
        vals = [float(v) for v in _numbers(rng.replace(",", ":"), spec)]
        return name.strip(), np.array(vals)
    parts = _numbers(rng, spec)
    if len(parts) != 3:
        raise InputError(f"--vary {spec}: write NAME=START:STOP:STEP (with --samples: NAME=LOW:HIGH)")
    start, stop, step = parts
    if step == 0 or np.sign(stop - start) * np.sign(step) < 0:
        raise InputError(f"--vary {spec}: the step {step:g} does not lead from {start:g} to {stop:g}")
    n = int(np.floor((stop - start) / step + 1e-9)) + 1
    if n > 10_000_000:
        raise InputError(f"--vary {spec}: {n} values; a parameter takes at most 10 000 000")
    return name.strip(), start + step * np.arange(n)


def random_range(spec: str) -> tuple[str, float, float]:
    """`NAME=LOW:HIGH` → (NAME, LOW, HIGH) for a random sample."""
    name, sep, rng = spec.partition("=")
    parts = _numbers(rng, spec) if sep else []
    if len(parts) != 2 or not name.strip() or not parts[0] < parts[1]:
        raise InputError(f"--vary {spec}: with --samples write NAME=LOW:HIGH (LOW < HIGH)")
    return name.strip(), parts[0], parts[1]


def grid(axes: list[np.ndarray]) -> np.ndarray:
    """Every combination of the axes' values: (designs, parameters), the last axis fastest."""
    mesh = np.meshgrid(*axes, indexing="ij")
    return np.stack([m.ravel() for m in mesh], axis=-1)


def random_designs(lows, highs, n: int, seed: int = 0) -> np.ndarray:
    """`n` designs drawn uniformly in the box (reproducible by `seed`)."""
    if n < 1:
        raise InputError(f"--samples {n}: give at least one sample")
    rng = np.random.default_rng(seed)
    lows, highs = np.asarray(lows, float), np.asarray(highs, float)
    return lows + (highs - lows) * rng.random((n, len(lows)))
