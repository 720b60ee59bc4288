"""Function generation (*Funktionsgetriebe*): a four-bar whose output angle, or a slider-crank
whose slider position, follows a prescribed function y = f(x) of the input angle, after
Freudenstein (1955).

The variable x runs over [x_s, x_f] while the input turns linearly from φ_s to φ_f; y = f(x)
over [f(x_s), f(x_f)] maps linearly onto the output, ψ_s … ψ_f (an angle) or s_s … s_f (a
length along the line of stroke).

**Four-bar.** Fixed pivots O₂ = (0, 0) and O₄ = (d, 0), input crank a at angle φ, output
rocker c at angle ψ (both from the frame line O₂→O₄, counter-clockwise), coupler b. The loop
|O₄ + c e^{iψ} − a e^{iφ}| = b, squared, is Freudenstein's equation

    K₁ cos ψ − K₂ cos φ + K₃ = cos(φ − ψ),
    K₁ = d/a,  K₂ = d/c,  K₃ = (a² − b² + c² + d²)/(2ac),

linear in K: three precision points give K exactly, more a least-squares fit. A negative a or c
puts that crank's pin on the other side of its pivot (the angle measured to the pin's opposite).

**Slider-crank.** Crank a about O = (0, 0) at angle φ, the slider's pin B = (s, e) on the line
of stroke y = e, rod b: |B − a e^{iφ}|² = b² gives

    K₁ s cos φ + K₂ sin φ − K₃ = s²,   K₁ = 2a,  K₂ = 2ae,  K₃ = a² + e² − b²,

linear again.

**Chebyshev spacing** of n precision points (*Tschebyscheff-Abstände*):
x_j = (x_s + x_f)/2 − (x_f − x_s)/2 · cos((2j − 1)π/(2n)), j = 1 … n, which keeps the largest
structural error of a polynomial-like error curve small.

**Structural error** (*Strukturfehler*): the output the linkage produces (solved by the engine
from its mechanism file) minus the prescribed one, over the range; zero at exact precision points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import InputError
from ._file import mechanism_file
from .positions import SynthesisError, wrap

__all__ = ["FunctionGenerator", "FunctionTask", "chebyshev_spacing", "freudenstein",
           "function_generator"]


def chebyshev_spacing(x_start: float, x_final: float, n: int) -> np.ndarray:
    """n Chebyshev precision points of [x_start, x_final], in ascending order of j (from x_start's
    end)."""
    if n < 1:
        raise InputError(f"give at least one precision point, got {n}")
    j = np.arange(1, n + 1)
    return (x_start + x_final) / 2 - (x_final - x_start) / 2 * np.cos((2 * j - 1) * np.pi / (2 * n))


@dataclass(frozen=True)
class FunctionTask:
    """y = f(x) on [x_start, x_final], the input's range (radians) and the output's range
    (radians for a four-bar's rocker, a length for a slider) the ends map to."""

    function: Callable[[np.ndarray], np.ndarray]
    x_range: tuple[float, float]
    input_range: tuple[float, float]
    output_range: tuple[float, float]

    def __post_init__(self) -> None:
        x0, xf = (float(v) for v in self.x_range)
        if not (np.isfinite([x0, xf]).all() and xf != x0):
            raise InputError(f"the range of x must be two different finite numbers, got {self.x_range}")
        for what, (a, b) in (("input", self.input_range), ("output", self.output_range)):
            if not (np.isfinite([a, b]).all() and a != b):
                raise InputError(f"the {what} range must be two different finite numbers, got {(a, b)}")
        y = self.y(np.array([x0, xf]))
        if not np.isfinite(y).all() or y[0] == y[1]:
            raise InputError(f"f(x) must be finite at both ends and differ there, got f = {y.tolist()}")

    def y(self, x) -> np.ndarray:
        return np.asarray(self.function(np.asarray(x, dtype=float)), dtype=float)

    def input(self, x) -> np.ndarray:
        (x0, xf), (p0, pf) = self.x_range, self.input_range
        return p0 + (np.asarray(x, dtype=float) - x0) / (xf - x0) * (pf - p0)

    def output(self, x) -> np.ndarray:
        y0, yf = self.y(np.array(self.x_range, dtype=float))
        q0, qf = self.output_range
        return q0 + (self.y(x) - y0) / (yf - y0) * (qf - q0)

    def output_to_y(self, delta) -> np.ndarray:
        """An output difference (an error) as a difference of y."""
        y0, yf = self.y(np.array(self.x_range, dtype=float))
        q0, qf = self.output_range
        return np.asarray(delta) * (yf - y0) / (qf - q0)


def freudenstein(phi, out, kind: str = "four-bar") -> tuple[np.ndarray, float]:
    """Freudenstein's constants K (3,) from input angles φ and outputs ψ (four-bar) or s
    (slider-crank): exact for three points, least squares for more; with the largest residual
    of the equations."""
    phi, out = np.asarray(phi, dtype=float).ravel(), np.asarray(out, dtype=float).ravel()
    if phi.shape != out.shape or phi.size < 3:
        raise InputError(f"give at least three precision points (input and output alike), got {phi.size}")
    if kind == "four-bar":
        M = np.column_stack([np.cos(out), -np.cos(phi), np.ones_like(phi)])
        rhs = np.cos(phi - out)
    elif kind == "slider-crank":
        M = np.column_stack([out * np.cos(phi), np.sin(phi), -np.ones_like(phi)])
        rhs = out**2
    else:
        raise InputError(f"unknown function generator '{kind}' (four-bar or slider-crank)")
    if np.linalg.matrix_rank(M, tol=1e-12 * np.abs(M).max()) < 3:
        raise SynthesisError("the precision points do not determine Freudenstein's constants (two of "
                             "them coincide, or they are otherwise degenerate)")
    if phi.size == 3:
        K = np.linalg.solve(M, rhs)
    else:
        K = np.linalg.lstsq(M, rhs, rcond=None)[0]
    return K, float(np.abs(M @ K - rhs).max())


@dataclass(frozen=True, eq=False)
class FunctionGenerator:
    """A function generator found from precision points: its lengths (signed cranks, see the
    module's docstring), its design position at the start of the range and the file."""

    kind: str
    task: FunctionTask
    precision: np.ndarray  # x of the precision points
    K: np.ndarray
    residual: float
    lengths: dict
    name: str = "Function generator"

    # ------------------------------------------------------------------ geometry
    def _pin(self, phi) -> np.ndarray:
        a = self.lengths["input"]
        phi = np.asarray(phi, dtype=float)
        return np.stack([a * np.cos(phi), a * np.sin(phi)], axis=-1)

    def _output_point(self, A: np.ndarray, want: float) -> np.ndarray:
        """The output pin for crank pin A: of the two assemblies the one nearer the prescribed
        output `want` (the design's branch)."""
        L = self.lengths
        b = L["coupler"]
        if self.kind == "four-bar":
            O4, c = np.array([L["frame"], 0.0]), L["output"]
            v = O4 - A
            d = float(np.hypot(*v))
            x = (b * b - c * c + d * d) / (2 * d)
            h2 = b * b - x * x
            if h2 < 0:
                raise SynthesisError("the function generator cannot be assembled at its first precision point")
            u = v / d
            n = np.array([-u[1], u[0]])
            cands = [A + x * u + s * math.sqrt(h2) * n for s in (1.0, -1.0)]
            psi = [math.atan2(*(np.sign(c) * (B - O4))[::-1]) for B in cands]
            k = int(np.argmin([abs(wrap(p - want)) for p in psi]))
            return cands[k]
        e = L["offset"]
        h2 = b * b - (e - A[1]) ** 2
        if h2 < 0:
            raise SynthesisError("the function generator cannot be assembled at its first precision point")
        cands = [np.array([A[0] + s * math.sqrt(h2), e]) for s in (1.0, -1.0)]
        k = int(np.argmin([abs(B[0] - want) for B in cands]))
        return cands[k]

    def design(self) -> dict[str, np.ndarray]:
        """The points at the first precision point (where the linkage is drawn: it meets the
        prescribed output there, exactly for three points; the ends of the range may lie beyond
        its reach)."""
        x0 = float(self.precision[0])
        phi0 = float(self.task.input(x0))
        A = self._pin(phi0)
        B = self._output_point(A, float(np.ravel(self.task.output(x0))[0]))
        pts = {"O2": np.zeros(2), "A": A, "B": B}
        if self.kind == "four-bar":
            pts["O4"] = np.array([self.lengths["frame"], 0.0])
        else:
            pts["G"] = B + np.array([abs(self.lengths["coupler"]) / 4, 0.0])
        return pts

    def mechanism_text(self, *, length_unit: str = "mm", description: str | None = None) -> str:
        pts = self.design()
        x0, xf = self.task.x_range
        p0, pf = self.task.input_range
        desc = description or (
            f"A {self.kind} function generator from Freudenstein's equation ({len(self.precision)} "
            f"precision points): x from {x0:g} to {xf:g} as the input turns from "
            f"{math.degrees(p0):.6g}° to {math.degrees(pf):.6g}°. Written by linkwork's synthesis.")
        if self.kind == "four-bar":
            links = {"frame": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["B", "O4"]}
            joints = {"O2": ("revolute", ("frame", "crank"), ""), "A": ("revolute", ("crank", "coupler"), ""),
                      "B": ("revolute", ("coupler", "rocker"), ""), "O4": ("revolute", ("rocker", "frame"), "")}
        else:
            links = {"frame": ["O2"], "crank": ["O2", "A"], "rod": ["A", "B"], "block": ["B", "G"]}
            joints = {"O2": ("revolute", ("frame", "crank"), ""), "A": ("revolute", ("crank", "rod"), ""),
                      "B": ("revolute", ("rod", "block"), ""),
                      "guide": ("prismatic", ("frame", "block"), 'axis = [1, 0], point = "B"')}
        return mechanism_file(name=self.name, description=desc, length_unit=length_unit, points=pts,
                              links=links, joints=joints, driver="O2", speed="1 rad/s" if pf > p0 else "-1 rad/s")

    def mechanism(self, length_unit: str = "mm"):
        from ..io import load_text

        return load_text(self.mechanism_text(length_unit=length_unit), source=self.name)

    def generated(self, x) -> np.ndarray:
        """The output the engine gives at x: the rocker's angle ψ (four-bar) or the slider's
        position s (slider-crank); NaN where it cannot be assembled."""
        from ..kinematics import Status, solve

        x = np.atleast_1d(np.asarray(x, dtype=float))
        phi = self.task.input(x)
        # the driver's input is the angle of O2→A: a negative crank points the other way
        drive = phi + (np.pi if self.lengths["input"] < 0 else 0.0)
        sol = solve(self.mechanism(), drive, order=1)
        B = np.array(sol.point("B").position, dtype=float)
        B[sol.status == Status.UNREACHABLE] = np.nan
        if self.kind == "slider-crank":
            return B[:, 0]
        O4 = np.array([self.lengths["frame"], 0.0])
        v = np.sign(self.lengths["output"]) * (B - O4)
        psi = np.arctan2(v[:, 1], v[:, 0])
        want = self.task.output(x)
        return want + wrap(psi - want)

    def structural_error(self, samples: int = 201) -> tuple[np.ndarray, np.ndarray]:
        """(x, error): the generated output minus the prescribed one at `samples` values of x
        over the range (radians or lengths; `task.output_to_y` turns it into y)."""
        if samples < 2:
            raise InputError(f"give at least two samples, got {samples}")
        x = np.linspace(*self.task.x_range, samples)
        return x, self.generated(x) - self.task.output(x)


def function_generator(task: FunctionTask, precision=3, kind: str = "four-bar", *, frame: float = 1.0,
                       name: str = "Function generator") -> FunctionGenerator:
    """The four-bar (frame length `frame`) or slider-crank through the precision points: an
    integer n takes n Chebyshev-spaced points, an array the given x values."""
    if np.ndim(precision) == 0:
        xs = chebyshev_spacing(*task.x_range, int(precision))
    else:
        xs = np.asarray(precision, dtype=float).ravel()
    if not np.isfinite(xs).all():
        raise InputError("the precision points must be finite numbers")
    phi, out = task.input(xs), task.output(xs)
    K, res = freudenstein(phi, out, kind)
    if kind == "four-bar":
        d = float(frame)
        if not d > 0:
            raise InputError(f"the frame length must be positive, got {frame}")
        if K[0] == 0 or K[1] == 0:
            raise SynthesisError("Freudenstein's constants give a crank of infinite length")
        a, c = d / K[0], d / K[1]
        b2 = a * a + c * c + d * d - 2 * a * c * K[2]
        if b2 <= 0:
            raise SynthesisError(f"Freudenstein's constants give no real coupler (b² = {b2:.6g}): choose "
                                 "other precision points or ranges")
        lengths = {"frame": d, "input": a, "coupler": math.sqrt(b2), "output": c}
    else:
        a = K[0] / 2
        if a == 0:
            raise SynthesisError("Freudenstein's constants give a crank of zero length")
        e = K[1] / K[0]
        b2 = a * a + e * e - K[2]
        if b2 <= 0:
            raise SynthesisError(f"Freudenstein's constants give no real rod (b² = {b2:.6g})")
        lengths = {"input": a, "coupler": math.sqrt(b2), "offset": e}
    return FunctionGenerator(kind, task, xs, K, res, lengths, name)

