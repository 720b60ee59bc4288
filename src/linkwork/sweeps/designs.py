"""Design parameters of a mechanism and the designs of a sweep.

A parameter is a dimension of the drawing (the design position defines everything, README):
`P.x` / `P.y` a point's coordinate, or `A-B` the distance from point A to point B, changed by
moving B along the line from A (nothing else moves). A design is one value per parameter;
`apply` builds the mechanism of a design (`Mechanism.build` again: lengths, slot radii and the
assembly branch follow from the new drawing, as they do from a file).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..model import Mechanism

_NAME = re.compile(r"^(?P<p>[^\s.=:-][^\s=:]*?)\.(?P<c>[xy])$|^(?P<a>[^\s=:-]+)-(?P<b>[^\s=:-]+)$")


@dataclass(frozen=True)
class Parameter:
    """One design parameter: `kind` "x", "y" (a coordinate of `point`) or "length" (the
    distance from `base` to `point`, along which `point` moves)."""

    name: str
    kind: str
    point: str
    base: str | None = None

    def value(self, mech: Mechanism) -> float:
        p = np.asarray(mech.points[self.point], dtype=float)
        if self.kind == "length":
            return float(np.linalg.norm(p - mech.points[self.base]))
        return float(p[0 if self.kind == "x" else 1])


def parameter(mech: Mechanism, name: str) -> Parameter:
    """The parameter `name` of `mech` (`P.x`, `P.y` or `A-B`), or an `InputError` naming what
    is wrong with it."""
    m = _NAME.match(name.strip())
    if m is None:
        raise InputError(f"--vary {name}: name a coordinate (P.x, P.y) or a distance (A-B) of the "
                         "drawing's points")
    known = sorted(mech.points)
    if m.group("p"):
        if m.group("p") not in mech.points:
            raise InputError(f"--vary {name}: there is no point '{m.group('p')}' (points: {', '.join(known)})")
        return Parameter(name, m.group("c"), m.group("p"))
    a, b = m.group("a"), m.group("b")
    for p in (a, b):
        if p not in mech.points:
            raise InputError(f"--vary {name}: there is no point '{p}' (points: {', '.join(known)})")
    if np.linalg.norm(np.asarray(mech.points[b], float) - mech.points[a]) == 0:
        raise InputError(f"--vary {name}: the points {a} and {b} coincide, so the line along which "
                         f"{b} moves is undefined")
    return Parameter(name, "length", b, a)


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
        else:
            pts[prm.point][0 if prm.kind == "x" else 1] = v
    return Mechanism.build(name=mech.name, points=pts, links={l.name: list(l.points) for l in mech.links},
                           joints=list(mech.joints), drivers=list(mech.drivers), frame=mech.frame,
                           length_unit=mech.length_unit, description=mech.description,
                           profiles=dict(mech.profiles))


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
