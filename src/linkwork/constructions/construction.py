"""The construction model: a ruler-and-compass construction as an ordered list of steps.

Owns :class:`Construction` (steps, drawn elements, numeric results compared with the analytic
values), :class:`Step`, :class:`Element` with its :class:`Role` (given, auxiliary, result — the
books' *gegeben*, *Hilfslinie*, *Ergebnis*), the drawable value objects that the geometry layer
does not have (:class:`Segment`, :class:`Arrow`, :class:`Polygon`), and :class:`Builder`, the
drafting table on which every module of :mod:`linkwork.constructions` works: *join*, *draw the
perpendicular/parallel*, *intersect*, *strike a circle*, *lay off a length*, each call drawing one
element and returning its exact geometry.

Everything is batch-first: one construction is carried out at N positions at once (every
element holds a batch of N items); :meth:`Construction.sample` picks one position for drawing.

A construction is an *independent* computation: it starts from the given data only (the
mechanism's points and the given input velocities/accelerations) and uses ruler-and-compass
operations. Its results are then compared with the core engine's analytic values
(:meth:`Construction.check`); a disagreement beyond ``1e-9`` relative is an error
(:class:`ConstructionMismatch`), not a warning. Positions where the construction degenerates
(parallel lines, a pole at infinity, circles that do not meet) are recorded with a message
(:attr:`Construction.notes`) and their results are NaN unless a limiting construction applies.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field, replace
from typing import Any, Iterable, Sequence

import numpy as np

from ..errors import LinkworkError
from ..geometry import Circle, Line, Point, Vector, intersect
from ..geometry._base import Batch
from ..topology.constructibility import literal, prose  # noqa: F401  (literal: re-exported)

#: the tolerance of the issue: a construction result may differ from the analytic value by at
#: most this much, relative to the result's reference scale
RTOL = 1e-9


class ConstructionMismatch(LinkworkError):
    """A construction's result disagrees with the analytic value beyond the tolerance."""


class DegenerateConstruction(LinkworkError):
    """The construction cannot be carried out at the requested position (message says why)."""


class Role(str, enum.Enum):
    """What an element is to the construction (line weights in the drawing follow it)."""

    GIVEN = "given"  # gegeben / dots: the data the construction starts from
    AUXILIARY = "auxiliary"  # Hilfslinie / palīglīnija
    RESULT = "result"  # Ergebnis / rezultāts

    def __str__(self) -> str:
        return self.value


# ---------------------------------------------------------------------------- drawables
@dataclass(frozen=True, eq=False)
class Segment(Batch):
    """The straight segment from ``start`` to ``end`` (finite points)."""

    start: Point
    end: Point

    @property
    def shape(self) -> tuple[int, ...]:
        return self.start.shape

    @property
    def length(self) -> np.ndarray:
        return np.linalg.norm(self.end.xy - self.start.xy, axis=-1)


@dataclass(frozen=True, eq=False)
class Arrow(Batch):
    """A vector drawn from ``tail`` to ``head`` (a velocity, an acceleration, a component)."""

    tail: Point
    head: Point

    @property
    def shape(self) -> tuple[int, ...]:
        return self.tail.shape

    @property
    def vector(self) -> np.ndarray:
        return self.head.xy - self.tail.xy


@dataclass(frozen=True, eq=False)
class Polygon:
    """A closed polygon through ``vertices`` (velocity and acceleration images, link plates)."""

    vertices: tuple[Point, ...]

    @property
    def shape(self) -> tuple[int, ...]:
        return self.vertices[0].shape

    def __getitem__(self, index: Any) -> Polygon:
        return Polygon(tuple(v[index] for v in self.vertices))


# ---------------------------------------------------------------------------- elements, steps
@dataclass(frozen=True, eq=False)
class Element:
    """One drawn object of a construction.

    ``label`` is in the books' notation with ``_`` for a subscript (``W_0``, ``C_a``, ``P_13``);
    ``space`` names the drawing it belongs to (``mechanism``, ``velocity``, ``acceleration``);
    ``kind`` refines the style (``velocity``, ``acceleration``, ``pole``, ``circle`` …);
    ``span`` lists the points a straight line must cover when drawn (books draw a line just past
    the points it is used for), ``arcs`` the points near which only short compass arcs are drawn.
    """

    key: str
    obj: Any
    role: Role
    label: str | None = None
    kind: str = ""
    space: str = "mechanism"
    span: tuple[Point, ...] = ()
    arcs: tuple[Point, ...] = ()
    step: int = 0

    def sample(self, i: int) -> Element:
        return replace(self, obj=self.obj[i], span=tuple(p[i] for p in self.span),
                       arcs=tuple(p[i] for p in self.arcs))


@dataclass(frozen=True)
class Step:
    """One sentence of the construction and the keys of the elements it draws."""

    text: str
    keys: tuple[str, ...]


#: the largest constructed value taken as zero where the analytic values are all zero (the
#: rounding of coordinates of a few hundred units)
AT_REST = 1e-9


@dataclass(frozen=True)
class Result:
    """A number (or vector) read off the construction, next to the analytic value it must equal.

    ``scale`` (per sample) is the magnitude the error is measured against (for a vector the
    magnitude of a typical vector of that kind, so that a component near zero is not compared
    relatively to itself). ``unit`` is written in the legend and the reports.
    """

    key: str
    label: str
    description: str
    constructed: np.ndarray
    analytic: np.ndarray
    scale: np.ndarray
    unit: str = ""
    shown: tuple[np.ndarray, np.ndarray] | None = None  # (constructed, analytic) for reports

    @property
    def error(self) -> np.ndarray:
        """Relative error per sample: |constructed − analytic| / scale (NaN where undefined).
        Where the scale is zero (a mechanism at rest: every analytic value zero) the constructed
        value must be zero to rounding: error 0 within AT_REST of the drawing's units, else ∞."""
        d = np.asarray(self.constructed, float) - np.asarray(self.analytic, float)
        if d.ndim > np.ndim(self.scale):
            d = np.linalg.norm(d, axis=-1)
        else:
            d = abs(d)
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = d / self.scale
        return np.where(np.asarray(self.scale) == 0.0, np.where(d <= AT_REST, 0.0, np.inf), rel)


@dataclass(frozen=True)
class Note:
    """A degenerate case: where it happens (mask over the samples) and what the user is told."""

    mask: np.ndarray
    message: str
    limiting: bool = False  # True: the limiting construction was used, the results stand


@dataclass(frozen=True, eq=False)
class Construction:
    """A finished construction at N positions: steps, elements, results, degenerate notes."""

    name: str
    title: str
    source: str
    n: int
    elements: dict[str, Element]
    steps: tuple[Step, ...]
    results: dict[str, Result]
    notes: tuple[Note, ...] = ()
    spaces: dict[str, str] = field(default_factory=lambda: {"mechanism": "length"})
    scales: Any = None  # drawing scales used for vectors drawn on the mechanism (or None)
    sampled: int | None = None  # the sample index when this is one position of a batch
    own_labels: bool = False  # the construction names the mechanism's points in its own notation
    legend: tuple[str, ...] = ()  # lines for the drawing's legend (e.g. an implied scale)

    # ------------------------------------------------------------------ degenerate cases
    @property
    def degenerate(self) -> np.ndarray:
        """Mask of the samples at which the construction degenerates."""
        m = np.zeros(self.n, bool)
        for note in self.notes:
            if not note.limiting:
                m |= np.broadcast_to(note.mask, (self.n,))
        return m

    def messages(self, i: int | None = None) -> list[str]:
        """The degenerate-case messages (at sample ``i``, or anywhere)."""
        out = []
        for note in self.notes:
            mask = np.broadcast_to(note.mask, (self.n,))
            if (mask.any() if i is None else mask[i]) and note.message not in out:
                out.append(note.message)
        return out

    # ------------------------------------------------------------------ checking
    def errors(self) -> dict[str, np.ndarray]:
        return {k: r.error for k, r in self.results.items()}

    def max_error(self) -> float:
        """The largest relative error over all results and non-degenerate samples (0 if none)."""
        ok = ~self.degenerate
        worst = 0.0
        for r in self.results.values():
            ref = np.isfinite(np.asarray(r.analytic, float).reshape(self.n, -1)).all(axis=1)
            e = np.broadcast_to(r.error, (self.n,))[ok & ref]
            if e.size:
                worst = max(worst, float(np.max(np.where(np.isnan(e), np.inf, e))))
        return worst

    def check(self, rtol: float = RTOL) -> Construction:
        """Raise :class:`ConstructionMismatch` if any result misses its analytic value by more
        than ``rtol`` (relative to the result's scale) at a non-degenerate sample. NaN results
        at non-degenerate samples count as a mismatch."""
        ok = ~self.degenerate
        bad = []
        for r in self.results.values():
            e = np.broadcast_to(r.error, (self.n,))
            # where the analytic value itself is undefined there is nothing to compare with
            ref = np.isfinite(np.asarray(r.analytic, float).reshape(self.n, -1)).all(axis=1)
            fail = ok & ref & ~(e <= rtol)
            if fail.any():
                k = int(np.argmax(np.where(fail, np.nan_to_num(e, nan=np.inf), -1)))
                bad.append(f"{prose(r.label)} ({prose(r.description)}): relative error {e[k]:.3g} at sample {k} "
                           f"(constructed {np.asarray(r.constructed)[k]}, analytic "
                           f"{np.asarray(r.analytic)[k]}), {int(fail.sum())} of {self.n} samples fail")
        if bad:
            raise ConstructionMismatch(f"construction '{self.name}' disagrees with the analytic "
                                       "values: " + "; ".join(bad))
        return self

    # ------------------------------------------------------------------ views
    def sample(self, i: int) -> Construction:
        """The construction at one position (single items), for drawing."""
        if self.sampled is not None:
            return self
        if not -self.n <= i < self.n:
            raise IndexError(f"sample {i} out of range for a construction at {self.n} positions")
        i = i % self.n
        els = {k: e.sample(i) for k, e in self.elements.items()}
        res = {k: replace(r, constructed=np.asarray(r.constructed)[i:i + 1],
                          analytic=np.asarray(r.analytic)[i:i + 1],
                          shown=None if r.shown is None else tuple(np.asarray(x)[i:i + 1] for x in r.shown),
                          scale=np.broadcast_to(r.scale, (self.n,))[i:i + 1])
               for k, r in self.results.items()}
        notes = tuple(Note(np.broadcast_to(n.mask, (self.n,))[i:i + 1], n.message, n.limiting)
                      for n in self.notes)
        return replace(self, elements=els, results=res, notes=notes, n=1, sampled=i)

    def require(self, i: int = 0) -> None:
        """Raise :class:`DegenerateConstruction` with the reasons if sample ``i`` degenerates."""
        msgs = self.messages(i)
        mask = self.degenerate
        if mask[i]:
            raise DegenerateConstruction(f"{self.title}: " + "; ".join(msgs))

    def elements_up_to(self, step: int) -> list[Element]:
        """Elements drawn in steps 0..step (for step-by-step drawings)."""
        keys = [k for s in self.steps[:step + 1] for k in s.keys]
        return [self.elements[k] for k in keys]

    def describe(self) -> str:
        """The construction as numbered sentences, then the results and degenerate cases."""
        lines = [f"{self.title}  [{self.source}]"]
        for k, s in enumerate(self.steps, 1):
            lines.append(f"{k:2d}. {s.text}")
        for r in self.results.values():
            c, a = (np.asarray(x) for x in (r.shown or (r.constructed, r.analytic)))
            if self.n == 1:
                lines.append(f"    {prose(r.label)} = {_fmt(c[0])} {r.unit}  (analytic {_fmt(a[0])}, "
                             f"relative error {float(np.asarray(r.error)[0]):.1e})")
        for m in self.messages():
            lines.append(f"    note: {m}")
        return "\n".join(lines)


def _fmt(v: Any) -> str:
    v = np.asarray(v, float)
    if v.ndim == 1 and v.size == 2 and np.isinf(v[0]):
        return f"at infinity, direction {v[1]:.6g}\u00b0"
    if v.ndim == 0:
        return f"{float(v):.6g}"
    return "(" + ", ".join(f"{float(x):.6g}" for x in v) + ")"


# ---------------------------------------------------------------------------- the builder
def _nan_points(n_shape: tuple[int, ...]) -> np.ndarray:
    return np.full(n_shape + (3,), np.nan)


def mask_points(p: Point, bad: np.ndarray) -> Point:
    """``p`` with the items under ``bad`` replaced by the undefined (NaN) point."""
    if not np.any(bad):
        return p
    return Point(np.where(np.asarray(bad)[..., None], np.nan, p.coords))


def safe_join(p: Point, q: Point) -> tuple[Line, np.ndarray]:
    """The line through ``p`` and ``q``, NaN where they coincide (returned mask)."""
    c = np.cross(*np.broadcast_arrays(p.coords, q.coords))
    same = (c == 0).all(axis=-1)
    nan = np.isnan(c).any(axis=-1)
    c = np.where((same | nan)[..., None], np.nan, c)
    c = np.where(np.isnan(c), np.nan, c)
    # Line() rejects (0, 0, 0) only; NaN rows pass through as undefined items
    return Line(np.where(np.isnan(c), np.nan, c)), same & ~nan


class Builder:
    """The drafting table: each method performs one ruler-or-compass operation on N samples,
    records the drawn element in the current step and returns its exact geometry.

    >>> b = Builder("demo", "Demo", "—", n=1)
    >>> b.step("Join A and B.")
    >>> AB = b.join("AB", A, B)
    """

    def __init__(self, name: str, title: str, source: str, n: int, *,
                 spaces: dict[str, str] | None = None, scales: Any = None) -> None:
        self.name, self.title, self.source, self.n = name, title, source, n
        self.elements: dict[str, Element] = {}
        self.steps: list[tuple[str, list[str]]] = []
        self.results: dict[str, Result] = {}
        self.notes: list[Note] = []
        self.spaces = spaces or {"mechanism": "length"}
        self.scales = scales
        self.own_labels = False
        self.legend: list[str] = []
        self.length: float | None = None  # the drawing's size, for tolerances (set by constructions)
        self._spans: dict[str, list[Point]] = {}

    def key(self, letters: dict[str, str]) -> None:
        """The book's letters of the steps against the file's point names, as a legend line
        (drawn points carry the file's names; the key is needed only where the two differ)."""
        pairs = [(book, name) for book, name in letters.items() if book.replace("_", "") != name]
        if pairs:
            self.legend.append("key, book's letters in the steps = the file's points: "
                               + ", ".join(f"{book} = {literal(name)}" for book, name in pairs))

    # ------------------------------------------------------------------ bookkeeping
    def step(self, text: str) -> None:
        """Begin a new step with its sentence."""
        self.steps.append((prose(text), []))

    def add(self, key: str, obj: Any, role: Role = Role.AUXILIARY, label: str | None = None, *,
            kind: str = "", space: str = "mechanism", span: Iterable[Point] = (),
            arcs: Iterable[Point] = ()) -> Any:
        """Record an element drawn in the current step and return ``obj``."""
        if not self.steps:
            self.step("Given.")
        if key in self.elements:
            raise ValueError(f"construction '{self.name}': element '{key}' drawn twice")
        self.elements[key] = Element(key, obj, Role(role), label, kind, space, (), tuple(arcs),
                                     len(self.steps) - 1)
        self._spans[key] = list(span)
        self.steps[-1][1].append(key)
        return obj

    def extend(self, key: str, *points: Point) -> None:
        """Make the drawn line ``key`` also cover ``points`` (e.g. an intersection found later)."""
        self._spans[key].extend(points)

    def degenerate(self, mask: Any, message: str) -> np.ndarray:
        """Record that the construction degenerates where ``mask`` holds; returns the mask."""
        mask = np.broadcast_to(np.asarray(mask, bool), (self.n,)).copy()
        if mask.any():
            self.notes.append(Note(mask, prose(message)))
        return mask

    def limiting(self, mask: Any, message: str) -> np.ndarray:
        """Record that the limiting construction is used where ``mask`` holds (results stand)."""
        mask = np.broadcast_to(np.asarray(mask, bool), (self.n,)).copy()
        if mask.any():
            self.notes.append(Note(mask, prose(message), limiting=True))
        return mask

    @property
    def bad(self) -> np.ndarray:
        m = np.zeros(self.n, bool)
        for note in self.notes:
            if not note.limiting:
                m |= note.mask
        return m

    # ------------------------------------------------------------------ ruler
    def point(self, key: str, p: Point, role: Role = Role.GIVEN, label: str | None = None, **kw) -> Point:
        return self.add(key, p, role, label, kind=kw.pop("kind", "point"), **kw)

    def join(self, key: str, p: Point, q: Point, role: Role = Role.AUXILIARY,
             label: str | None = None, *, why: str | None = None, **kw) -> Line:
        """The line through ``p`` and ``q`` (either may be a point at infinity: a direction)."""
        line, same = safe_join(p, q)
        if same.any():
            self.degenerate(same & ~self.bad,
                            why or f"the points of line {label or key} coincide, so the line is undetermined")
        span = [x for x in (p, q)]
        return self.add(key, line, role, label, kind=kw.pop("kind", "line"), span=span, **kw)

    def perpendicular(self, key: str, through: Point, to: Line, role: Role = Role.AUXILIARY,
                      label: str | None = None, **kw) -> Line:
        """The perpendicular to ``to`` through ``through``."""
        n = np.array(to.coords[..., :2], float)
        n[(n == 0).all(axis=-1)] = np.nan  # the line at infinity has no direction
        direction = Point(np.concatenate([n, np.zeros(n.shape[:-1] + (1,))], axis=-1))
        line, _ = safe_join(through, direction)
        return self.add(key, line, role, label, kind=kw.pop("kind", "line"), span=[through], **kw)

    def parallel(self, key: str, through: Point, to: Line | Vector, role: Role = Role.AUXILIARY,
                 label: str | None = None, **kw) -> Line:
        """The parallel to ``to`` (a line, or a direction vector) through ``through``."""
        if isinstance(to, Vector):
            d = np.array(to.xy, float)
        else:
            d = np.stack([to.coords[..., 1], -to.coords[..., 0]], axis=-1)
        d[(d == 0).all(axis=-1)] = np.nan  # no direction: the zero vector, the line at infinity
        direction = Point(np.concatenate([d, np.zeros(d.shape[:-1] + (1,))], axis=-1))
        line, _ = safe_join(through, direction)
        return self.add(key, line, role, label, kind=kw.pop("kind", "line"), span=[through], **kw)

    def meet(self, key: str, l1: Line, l2: Line, role: Role = Role.AUXILIARY,
             label: str | None = None, *, k1: str | None = None, k2: str | None = None,
             finite: bool = True, why: str | None = None, **kw) -> Point:
        """The intersection of two lines; extends the drawn lines ``k1``, ``k2`` to it.

        With ``finite`` (default), samples where the lines are parallel (the intersection is at
        infinity) or coincide are recorded as degenerate with ``why`` and give NaN.
        """
        x = np.cross(*np.broadcast_arrays(l1.coords, l2.coords))
        scale = np.linalg.norm(l1.coords[..., :2], axis=-1) * np.linalg.norm(l2.coords[..., :2], axis=-1)
        par = abs(x[..., 2]) <= 1e-13 * scale
        x[..., 2] = np.where(par, 0.0, x[..., 2])
        inputs_nan = np.isnan(x).any(axis=-1)
        coincide = (x == 0).all(axis=-1) & ~inputs_nan
        if self.length is not None:
            # (nearly) coincident lines: in coordinates scaled by the drawing's size the two
            # homogeneous lines are (nearly) the same vector
            u1, u2 = (np.concatenate([c[..., :2], c[..., 2:] / self.length], axis=-1)
                      for c in np.broadcast_arrays(l1.coords, l2.coords))
            with np.errstate(invalid="ignore", divide="ignore"):
                u1 = u1 / np.linalg.norm(u1, axis=-1, keepdims=True)
                u2 = u2 / np.linalg.norm(u2, axis=-1, keepdims=True)
                q = np.linalg.norm(np.cross(u1, u2), axis=-1)
            coincide |= (q <= 1e-9) & ~inputs_nan
        undefined = inputs_nan | coincide
        x = np.where(undefined[..., None], np.nan, x)
        self.degenerate(coincide & ~self.bad, f"the two lines through {label or key} coincide, so "
                        f"{label or key} is undetermined")
        if finite:
            self.degenerate(par & ~undefined & ~self.bad,
                            why or f"the lines meeting in {label or key} are parallel, so it lies at infinity")
            x = np.where(par[..., None], np.nan, x)
        p = Point(x)
        self.add(key, p, role, label, kind=kw.pop("kind", "point"), **kw)
        for k in (k1, k2):
            if k is not None:
                self.extend(k, p)
        return p

    def foot(self, key: str, p: Point, line: Line, role: Role = Role.AUXILIARY,
             label: str | None = None, *, k: str | None = None, **kw) -> Point:
        """The foot of the perpendicular from ``p`` on ``line`` (drawn as a thin segment)."""
        f = line.project(p)
        self.add(key, f, role, label, kind=kw.pop("kind", "point"), **kw)
        self.add(key + ".perp", Segment(p, f), Role.AUXILIARY, None, kind="segment",
                 space=kw.get("space", "mechanism"))
        if k is not None:
            self.extend(k, f)
        return f

    def segment(self, key: str, p: Point, q: Point, role: Role = Role.AUXILIARY,
                label: str | None = None, **kw) -> Segment:
        return self.add(key, Segment(p, q), role, label, kind=kw.pop("kind", "segment"), **kw)

    def arrow(self, key: str, tail: Point, head: Point, role: Role = Role.GIVEN,
              label: str | None = None, *, kind: str = "velocity", **kw) -> Arrow:
        return self.add(key, Arrow(tail, head), role, label, kind=kind, **kw)

    def polygon(self, key: str, vertices: Sequence[Point], role: Role = Role.RESULT,
                label: str | None = None, **kw) -> Polygon:
        return self.add(key, Polygon(tuple(vertices)), role, label, kind=kw.pop("kind", "polygon"), **kw)

    # ------------------------------------------------------------------ compass
    def circle(self, key: str, centre: Point, radius: Any, role: Role = Role.AUXILIARY,
               label: str | None = None, *, arcs: Iterable[Point] = (), **kw) -> Circle:
        """The circle about ``centre`` with ``radius`` (a number, or a point it passes through).

        ``arcs``: draw only short arcs near these points (a compass mark), else the full circle.
        """
        if isinstance(radius, Point):
            r = np.linalg.norm(radius.xy - centre.xy, axis=-1)
        else:
            r = np.broadcast_to(np.asarray(radius, float), centre.shape)
        c = np.where(np.isnan(centre.xy), 0.0, centre.xy)
        bad = np.isnan(centre.xy).any(-1) | np.isnan(r)
        circ = Circle(Point.from_xy(c - np.stack([np.where(bad, 0, r), np.zeros_like(r)], -1)),
                      Vector.of(1.0, 0.0), np.where(bad, 0.0, r))
        if bad.any():
            circ = _nan_circle(circ, bad)
        return self.add(key, circ, role, label, kind=kw.pop("kind", "circle"), arcs=arcs, **kw)

    def circle_through(self, key: str, p: Point, q: Point, r: Point, role: Role = Role.AUXILIARY,
                       label: str | None = None, **kw) -> Circle:
        circ = Circle.through(p, q, r)
        return self.add(key, circ, role, label, kind=kw.pop("kind", "circle"), **kw)

    def cut(self, keys: tuple[str, str], first: Circle | Line, second: Circle | Line,
            role: Role = Role.AUXILIARY, labels: tuple[str | None, str | None] = (None, None), *,
            why: str | None = None, **kw) -> tuple[Point, Point]:
        """The two intersections of a circle with a line or a circle (``plus``, ``minus`` as in
        :func:`linkwork.geometry.intersect`); samples where they do not meet are degenerate."""
        pair = intersect(first, second)
        valid = np.broadcast_to(pair.valid, (self.n,))
        prior = np.isnan(pair.plus.coords).all(-1) & ~valid
        self.degenerate(~valid & ~self.bad & ~prior,
                        why or "the circles (or the circle and the line) do not meet")
        out = []
        for key, p, lab in zip(keys, (pair.plus, pair.minus), labels):
            if key is not None:
                self.add(key, p, role, lab, kind="point", **kw)
            out.append(p)
        return out[0], out[1]

    def copy_angle(self, key: str, V: Point, R1: Point, R2: Point, W: Point, S: Point, *,
                   sense: int = 1, radius: Any = None, role: Role = Role.AUXILIARY,
                   label: str | None = None, **kw) -> Line:
        """Lay off at ``W``, from the ray W→S, the angle ∠R1 V R2 with compass and ruler:
        a circle about V meets its rays in X1, X2; the same circle about W meets WS in Y1; the
        circle about Y1 through the chord X1X2 meets it in Y2 (``sense`` +1: the angle keeps its
        orientation, −1: it is laid off the other way). Returns the line W Y2 (drawn as a ray)."""
        Vx, Wx = V.xy, W.xy

        def unit(d):
            with np.errstate(invalid="ignore", divide="ignore"):
                return d / np.linalg.norm(d, axis=-1, keepdims=True)
        if radius is None:
            radius = 0.3 * np.minimum(np.linalg.norm(R1.xy - Vx, axis=-1), np.linalg.norm(S.xy - Wx, axis=-1))
        rho = np.broadcast_to(np.asarray(radius, float), (self.n,))
        X1 = Vx + rho[:, None] * unit(R1.xy - Vx)
        X2 = Vx + rho[:, None] * unit(R2.xy - Vx)
        Y1 = Wx + rho[:, None] * unit(S.xy - Wx)
        chord = np.linalg.norm(X2 - X1, axis=-1)
        # the chord transferred: the two intersections, the one with the right orientation
        d = np.linalg.norm(Y1 - Wx, axis=-1)
        with np.errstate(invalid="ignore", divide="ignore"):
            a = (d * d - chord * chord + rho * rho) / (2 * d)
            # ρ² − a² as the product (ρ − a)(ρ + a), each written without cancellation: a small
            # angle (a short chord) keeps its digits instead of half of them
            lo = (chord * chord - (d - rho) ** 2) / (2 * d)
            hi = ((d + rho) ** 2 - chord * chord) / (2 * d)
            h = np.sqrt(np.maximum(lo * hi, 0.0))
        u = unit(Y1 - Wx)
        nrm = np.stack([-u[:, 1], u[:, 0]], axis=-1)
        o1 = np.sign((X1 - Vx)[:, 0] * (X2 - Vx)[:, 1] - (X1 - Vx)[:, 1] * (X2 - Vx)[:, 0])
        Y2 = Wx + a[:, None] * u + (sense * np.where(o1 == 0, 1.0, o1) * h)[:, None] * nrm
        sp = kw.get("space", "mechanism")
        p1, p2, q1, q2 = (pt(x) for x in (X1, X2, Y1, Y2))
        self.add(key + ".arc1", _circle_at(V, rho, self.n), Role.AUXILIARY, None, kind="circle",
                 space=sp, arcs=(p1, p2))
        self.add(key + ".arc2", _circle_at(W, rho, self.n), Role.AUXILIARY, None, kind="circle",
                 space=sp, arcs=(q1, q2))
        self.add(key + ".arc3", _circle_at(q1, chord, self.n), Role.AUXILIARY, None, kind="circle",
                 space=sp, arcs=(q2,))
        line, _ = safe_join(W, q2)
        self.add(key, line, role, label, kind=kw.pop("kind", "line"), span=[W, q2], **kw)
        return line

    # ------------------------------------------------------------------ results
    def compare_points(self, key: str, label: str, description: str, constructed: Point,
                       analytic: Point, length: float, origin: Any = (0.0, 0.0)) -> Result:
        """Compare two batches of points, either possibly at infinity, by their projective
        distance in units of ``length`` about ``origin``: |Δ|/length for nearby finite points,
        the sine of the angle between directions for points at infinity."""
        o = np.asarray(origin, float)

        def h(p):
            c = np.array(p.coords, float)
            c = np.concatenate([(c[..., :2] - c[..., 2:] * o) / length, c[..., 2:]], axis=-1)
            with np.errstate(invalid="ignore", divide="ignore"):
                return c / np.linalg.norm(c, axis=-1, keepdims=True)
        hc, ha = h(constructed), h(analytic)
        s = np.sign(np.sum(hc * ha, axis=-1))
        hc = hc * np.where((s == 0) | np.isnan(s), 1.0, s)[..., None]
        r = self.compare(key, label, description, hc, ha, np.ones(self.n), "")
        with np.errstate(invalid="ignore", divide="ignore"):
            # finite points as (x, y); points at infinity as (inf, direction angle in degrees)
            shown = tuple(np.where(p.is_finite[..., None], p.coords[..., :2],
                                   np.stack([np.full(p.shape, np.inf),
                                             np.degrees(np.arctan2(p.coords[..., 1], p.coords[..., 0])) % 180],
                                            axis=-1))
                          for p in (constructed, analytic))
        r = replace(r, shown=shown)
        self.results[key] = r
        return r

    def compare(self, key: str, label: str, description: str, constructed: Any, analytic: Any,
                scale: Any, unit: str = "") -> Result:
        """Record a number read off the construction next to its analytic value."""
        c = np.asarray(constructed, float)
        bad = self.bad
        if c.ndim >= 1 and c.shape[0] == self.n:
            c = np.where(bad.reshape((-1,) + (1,) * (c.ndim - 1)), np.nan, c)
        r = Result(key, label, description, c, np.asarray(analytic, float),
                   np.broadcast_to(np.asarray(scale, float), (self.n,)).copy(), unit)
        self.results[key] = r
        return r

    def finish(self) -> Construction:
        # a result left undefined where no degenerate case was recorded still gets a message
        for r in list(self.results.values()):
            c = np.asarray(r.constructed, float).reshape(self.n, -1)
            ref = np.isfinite(np.asarray(r.analytic, float).reshape(self.n, -1)).all(axis=1)
            nan = np.isnan(c).any(axis=1) & ~self.bad & ref
            if nan.any():
                self.degenerate(nan, f"{r.label} ({r.description}) is undefined at this position "
                                     "(a degenerate configuration of the construction)")
        els = {k: replace(e, span=tuple(self._spans.get(k, ()))) for k, e in self.elements.items()}
        return Construction(self.name, self.title, self.source, self.n, els,
                            tuple(Step(t, tuple(k)) for t, k in self.steps), dict(self.results),
                            tuple(self.notes), dict(self.spaces), self.scales,
                            own_labels=self.own_labels, legend=tuple(self.legend))


def _nan_circle(c: Circle, bad: np.ndarray) -> Circle:
    """Blank the items under ``bad`` (NaN anchor and radius); geometry code passes NaN through."""
    anchor = Point(np.where(bad[..., None], np.nan, c.anchor.coords))
    obj = object.__new__(Circle)
    object.__setattr__(obj, "anchor", anchor)
    object.__setattr__(obj, "normal", c.normal)
    r = np.array(c.radius)
    r[bad] = np.nan
    r.flags.writeable = False
    object.__setattr__(obj, "radius", r)
    return obj


def _circle_at(centre: Point, radius: np.ndarray, n: int) -> Circle:
    c = np.where(np.isnan(centre.xy), 0.0, centre.xy)
    r = np.broadcast_to(np.asarray(radius, float), (n,))
    bad = np.isnan(centre.xy).any(-1) | ~np.isfinite(r)
    circ = Circle(Point.from_xy(c - np.stack([np.where(bad, 0, r), np.zeros(n)], -1)), Vector.of(1.0, 0.0),
                  np.where(bad, 0.0, r))
    return _nan_circle(circ, bad) if bad.any() else circ


def xy(p: Point) -> np.ndarray:
    """Cartesian coordinates (NaN for points at infinity or undefined points)."""
    return p.xy


def pt(a: np.ndarray) -> Point:
    """Finite points from an (..., 2) array that may contain NaN rows (undefined items)."""
    a = np.asarray(a, float)
    c = np.concatenate([a, np.ones(a.shape[:-1] + (1,))], axis=-1)
    c[~np.isfinite(a).all(-1)] = np.nan
    return Point(c)
