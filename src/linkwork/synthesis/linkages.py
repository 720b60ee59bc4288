"""Four-bars and slider-cranks from two dyads that guide a plane through prescribed positions,
written as mechanism files and checked with the engine.

Two cranks (`burmester.Dyad`: a centre point and its circle point) carried by one coupler make
a four-bar (*Gelenkviereck*); a crank and a slider (a centre point at infinity: the circle
point's homologous points lie on a straight line, the line of stroke) a slider-crank
(*Schubkurbel*). The first dyad is the driven crank. The mechanism is drawn in position `ref`
(its design position), the coupler carrying the plane's origin P and a point Q on its x-axis,
so that the coupler's pose in the engine is the displacement from position `ref`.

A design is checked (`Linkage.check`):

- Grashof type (`structure.grashof`), whether the input turns fully;
- order (*Reihenfolge*) defect: the input does not reach the positions in their order turning
  one way (a crank), or within one swing (a rocker);
- circuit defect: the positions need both assemblies of the driven dyad (the sign of the
  triangle coupler pin – output pin – output pivot changes; for a slider-crank the side of the
  crank pin's foot on the line of stroke), so the linkage cannot pass them without being taken
  apart;
- branch defect: a dead position of the input lies between two positions (the engine cannot
  assemble the chain somewhere on the way: unreachable samples of the sweep);
- the transmission angle (*Übertragungswinkel*) at the positions and its least value over the
  sweep from the first to the last position;
- the engine's own answer: the coupler's pose solved at each position's input angle against
  the prescribed displacement (`pose_error`, lengths relative to the positions' size).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..errors import StructureError
from ..structure.grashof import classify_four_bar, classify_slider_crank
from ._file import mechanism_file, point
from .burmester import Dyad
from .positions import SynthesisError, wrap

__all__ = ["Linkage", "LinkageCheck", "linkages", "four_position_linkages"]

SWEEP_SAMPLES = 48  # per gap between positions
MIN_TRANSMISSION = math.radians(30.0)  # a usual lower bound for a usable transmission angle


@dataclass(frozen=True)
class LinkageCheck:
    """What `Linkage.check` finds (angles in radians)."""

    kind: str  # "four-bar" or "slider-crank"
    name: str  # Grashof's name of the chain and its inversion
    grashof: str
    input_turns_fully: bool
    input_angles: np.ndarray  # the driver's input at each position
    sense: int  # +1 the positions follow turning counter-clockwise, −1 clockwise, 0 neither
    order_defect: bool
    circuit_defect: bool
    branch_defect: bool
    transmission: np.ndarray  # at each position, folded into [0, 90°]
    min_transmission: float  # over the sweep from the first to the last position
    pose_error: float  # the engine's coupler pose against the prescribed one
    notes: tuple[str, ...] = field(default=())

    def usable(self, min_transmission: float = MIN_TRANSMISSION, tol: float = 1e-9) -> bool:
        return (not (self.order_defect or self.circuit_defect or self.branch_defect)
                and self.min_transmission >= min_transmission and self.pose_error <= tol)

    def as_dict(self) -> dict:
        return {"kind": self.kind, "name": self.name, "grashof": self.grashof,
                "input_turns_fully": self.input_turns_fully,
                "input_angles_deg": np.degrees(self.input_angles).tolist(), "sense": self.sense,
                "order_defect": self.order_defect, "circuit_defect": self.circuit_defect,
                "branch_defect": self.branch_defect,
                "transmission_deg": np.degrees(self.transmission).tolist(),
                "min_transmission_deg": math.degrees(self.min_transmission),
                "pose_error": self.pose_error, "notes": list(self.notes)}


def _angle(v: np.ndarray) -> np.ndarray:
    return np.arctan2(v[..., 1], v[..., 0])


def _fold(mu: np.ndarray) -> np.ndarray:
    """A transmission angle folded into [0, 90°] (μ and 180° − μ transmit alike)."""
    mu = np.abs(np.remainder(mu, np.pi))
    return np.minimum(mu, np.pi - mu)


def _between(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The angle between the lines along u and v (..., 2), folded into [0, 90°]."""
    return _fold(np.arctan2(u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0], np.sum(u * v, axis=-1)))


@dataclass(frozen=True, eq=False)
class Linkage:
    """A four-bar (two cranks) or slider-crank (a crank and a slider) through the positions;
    `input` is the driven crank."""

    input: Dyad
    output: Dyad
    name: str = "Synthesized linkage"

    def __post_init__(self) -> None:
        a, b = self.input, self.output
        if a.positions is not b.positions and not (
                np.array_equal(a.positions.poses, b.positions.poses) and a.ref == b.ref):
            raise SynthesisError("the two dyads belong to different positions")
        for d, which in ((a, "input"), (b, "output")):
            if d.circle.is_infinite:
                raise SynthesisError(f"the {which} dyad's circle point is at infinity: it is no crank")
        if a.is_slider:
            raise SynthesisError("the input dyad is a slider: drive the crank (give it first)")
        size = a.positions.size
        if not b.is_slider and np.hypot(*(a.centre.xy - b.centre.xy)) <= 1e-9 * size:
            raise SynthesisError("the two centre points coincide: the frame has no length")
        if np.hypot(*(a.circle.xy - b.circle.xy)) <= 1e-9 * size:
            raise SynthesisError("the two circle points coincide: the coupler has no length")
        if a.length <= 1e-9 * size or (not b.is_slider and b.length <= 1e-9 * size):
            raise SynthesisError("a circle point lies on its centre point: the crank has no length")

    # ------------------------------------------------------------------ geometry
    @property
    def positions(self):
        return self.input.positions

    @property
    def ref(self) -> int:
        return self.input.ref

    @property
    def kind(self) -> str:
        return "slider-crank" if self.output.is_slider else "four-bar"

    @property
    def guide(self) -> np.ndarray:
        """Unit direction of the line of stroke (slider-crank): normal to the centre's
        direction at infinity."""
        u = self.output.centre.direction.xy
        return np.array([-u[1], u[0]])

    @property
    def lengths(self) -> dict[str, float]:
        A0, A, B = self.input.centre.xy, self.input.circle.xy, self.output.circle.xy
        out = {"input": float(np.hypot(*(A - A0))), "coupler": float(np.hypot(*(B - A)))}
        if self.kind == "four-bar":
            B0 = self.output.centre.xy
            out["output"] = float(np.hypot(*(B - B0)))
            out["frame"] = float(np.hypot(*(B0 - A0)))
        else:
            g = self.guide
            out["offset"] = float(abs((A0 - B)[0] * g[1] - (A0 - B)[1] * g[0]))
        return out

    def pins(self) -> tuple[np.ndarray, np.ndarray]:
        """(n, 2) each: the input's and the output's moving pivot in every position."""
        return self.input.homologous(), self.output.homologous()

    def input_angles(self) -> np.ndarray:
        A = self.pins()[0]
        return _angle(A - self.input.centre.xy)

    # ------------------------------------------------------------------ the file
    @cached_property
    def _order(self) -> tuple[str, str, bool, int]:
        """Grashof's name and verdict, whether the input turns fully, and the sense (+1, −1)
        in which the input reaches the positions in their order (0: in neither)."""
        name, grashof, turns = self._classify()
        theta = self.input_angles()
        if turns:  # a crank: any number of turns less than one between first and last
            for s in (1, -1):
                if np.all(np.diff(np.remainder(s * (theta - theta[0]), 2 * np.pi)) > 0):
                    return name, grashof, turns, s
            return name, grashof, turns, 0
        d = np.diff(wrap(theta - theta[0]))  # a rocker: within one swing
        return name, grashof, turns, (1 if np.all(d > 0) else -1 if np.all(d < 0) else 0)

    def mechanism_text(self, *, name: str | None = None, length_unit: str = "mm",
                       description: str | None = None) -> str:
        """The mechanism file: drawn in position `ref`, driven at the input's fixed pivot A0,
        turning the way the positions follow (clockwise: a negative speed)."""
        pos, ref = self.positions, self.ref
        A0, A, B = self.input.centre.xy, self.input.circle.xy, self.output.circle.xy
        P = pos.origin[ref]
        size = pos.size
        Q = P + 0.25 * size * np.array([np.cos(pos.angle[ref]), np.sin(pos.angle[ref])])
        speed = "-1 rad/s" if self._order[3] < 0 else "1 rad/s"
        pts = {"A0": A0, "A": A, "B": B}
        links = {"frame": ["A0"], "crank": ["A0", "A"], "coupler": ["A", "B", "P", "Q"]}
        joints = {"A0": ("revolute", ("frame", "crank"), ""), "A": ("revolute", ("crank", "coupler"), "")}
        if self.kind == "four-bar":
            pts["B0"] = self.output.centre.xy
            links["frame"] = ["A0", "B0"]
            links["rocker"] = ["B", "B0"]
            joints["B"] = ("revolute", ("coupler", "rocker"), "")
            joints["B0"] = ("revolute", ("rocker", "frame"), "")
        else:
            g = self.guide
            pts["G"] = B + 0.25 * size * g  # a point of the block, on the line of stroke
            links["block"] = ["B", "G"]
            joints["B"] = ("revolute", ("coupler", "block"), "")
            joints["guide"] = ("prismatic", ("frame", "block"), f'axis = {point(g)}, point = "B"')
        pts.update(P=P, Q=Q)
        desc = description or (
            f"A {self.kind} that guides its coupler (origin P, x-axis towards Q) through {len(pos)} "
            f"prescribed positions, drawn in position {ref + 1}; input angles at the positions: "
            + ", ".join(f"{math.degrees(a):.6g}°" for a in self.input_angles())
            + ". Written by linkwork's synthesis.")
        return mechanism_file(name=name or self.name, description=desc, length_unit=length_unit, points=pts,
                              links=links, joints=joints, driver="A0", speed=speed)

    def mechanism(self, length_unit: str = "mm"):
        """The `Mechanism` of `mechanism_text` (loaded from that text: what is checked is what
        is written)."""
        from ..io import load_text

        return load_text(self.mechanism_text(length_unit=length_unit), source=self.name)

    # ------------------------------------------------------------------ checks
    @cached_property
    def geometry_ok(self) -> bool:
        """No order and no circuit defect, seen from the dyads alone (no engine run)."""
        if self._order[3] == 0:
            return False
        A, B = self.pins()
        signs = self._assembly(A, B)
        return bool(np.all(signs == signs[self.ref]) and np.all(signs != 0))

    def _classify(self):
        L = self.lengths
        if self.kind == "four-bar":
            try:
                c = classify_four_bar(L["frame"], L["input"], L["coupler"], L["output"])
            except StructureError as exc:
                raise SynthesisError(str(exc)) from None
            return c.name, c.grashof, c.input_turns_fully
        c = classify_slider_crank(L["input"], L["coupler"], L["offset"], "guide")
        turns = L["input"] + L["offset"] <= L["coupler"] * (1 + 1e-12)
        return c.name, c.grashof, turns

    def _assembly(self, A: np.ndarray, B: np.ndarray) -> np.ndarray:
        """The sign that tells the driven dyad's two assemblies apart at pins A, B (n, 2)."""
        if self.kind == "four-bar":
            B0 = self.output.centre.xy
            u, v = B - A, B0 - A
            return np.sign(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
        return np.sign((B - A) @ self.guide)

    def _sweep(self) -> np.ndarray:
        """The input angles from the first position to the last the way the input turns (from
        the least to the largest when the order is broken), `SWEEP_SAMPLES` per gap."""
        theta = self.input_angles()
        n, ref = len(theta), self.ref
        _, _, turns, sense = self._order
        if sense:
            d = np.remainder(sense * (theta - theta[0]), 2 * np.pi) if turns else sense * wrap(theta - theta[0])
            return theta[0] + sense * np.union1d(np.linspace(0.0, float(d.max()), SWEEP_SAMPLES * (n - 1) + 1), d)
        rel = wrap(theta - theta[ref])
        lo, hi = float(rel.min()), float(rel.max())
        return theta[ref] + np.union1d(np.linspace(lo, hi, SWEEP_SAMPLES * (n - 1) + 1), rel)

    @cached_property
    def screen(self) -> tuple[bool, float]:
        """(branch defect, least transmission angle) over `_sweep`, from the dyads in closed
        form (the driven pin where the coupler's circle about A meets the output's circle or
        line on the assembly of position `ref`): what `check` finds with the engine, at a
        fraction of its cost, to rank many candidates before the engine checks the best."""
        from .path import _meet

        u = self._sweep()
        A0 = self.input.centre.xy
        L = self.lengths
        A = A0 + L["input"] * np.column_stack([np.cos(u), np.sin(u)])
        Ar, Br = self.pins()
        sign = self._assembly(Ar, Br)[self.ref]
        if self.kind == "four-bar":
            B0 = self.output.centre.xy
            B, h2 = _meet(A, L["coupler"], np.broadcast_to(B0, A.shape), L["output"], -sign)
            other = B0 - B
        else:
            g = self.guide
            w = A - Br[self.ref]
            wg = w @ g
            h2 = wg**2 - np.sum(w * w, axis=1) + L["coupler"] ** 2
            B = Br[self.ref] + (wg + sign * np.sqrt(np.maximum(h2, 0.0)))[:, None] * g
            other = np.broadcast_to(np.array([-g[1], g[0]]), B.shape)
        ok = h2 >= 0
        mu = _between(B - A, other)[ok]
        return bool((~ok).any()), float(mu.min()) if mu.size else float("nan")

    @cached_property
    def check(self) -> LinkageCheck:
        """Grashof type, order, circuit and branch defects, transmission angles and the engine's
        pose error (see the module's docstring)."""
        from ..kinematics import Status, solve

        pos, ref = self.positions, self.ref
        name, grashof, turns, sense = self._order
        theta = self.input_angles()
        notes = []
        order_defect = sense == 0
        A, B = self.pins()
        signs = self._assembly(A, B)
        circuit_defect = bool(np.any(signs != signs[ref])) or bool(np.any(signs == 0))
        sweep = self._sweep()
        mech = self.mechanism()
        sol = solve(mech, sweep, order=1)
        branch_defect = bool(np.any(sol.status == Status.UNREACHABLE))
        if branch_defect:
            notes.append("the input cannot turn from the first position to the last without the chain "
                         "falling apart (a dead position of the input lies between)")
        pa, pb = sol.point("A").position, sol.point("B").position
        line = (pb - pa)
        other = (mech.points["B0"] - pb) if self.kind == "four-bar" else np.broadcast_to(
            np.array([-self.guide[1], self.guide[0]]), pb.shape)
        mu = _between(line, other)
        min_mu = float(np.nanmin(mu)) if np.isfinite(mu).any() else float("nan")
        mu_at = _between(B - A, (self.output.centre.xy - B) if self.kind == "four-bar" else
                         np.broadcast_to(np.array([-self.guide[1], self.guide[0]]), B.shape))
        at = solve(mech, theta, order=1)
        pose = at.pose_derivatives("coupler")[0]
        want_th = wrap(pos.angle - pos.angle[ref])
        c, s = np.cos(want_th), np.sin(want_th)
        d_ref = pos.origin[ref]
        want_xy = pos.origin - np.column_stack([c * d_ref[0] - s * d_ref[1], s * d_ref[0] + c * d_ref[1]])
        err_xy = np.hypot(*(pose[:, :2] - want_xy).T) / pos.size
        err_th = np.abs(wrap(pose[:, 2] - want_th))
        pose_error = float(np.max(np.maximum(err_xy, err_th)))
        if not np.isfinite(pose_error):
            pose_error = float("inf")
        if circuit_defect:
            notes.append("the positions lie on both assemblies of the driven dyad (circuit defect)")
        if order_defect:
            notes.append("the input does not reach the positions in their order turning one way"
                         + ("" if turns else " within one swing"))
        return LinkageCheck(self.kind, name, grashof, turns, theta, sense, order_defect, circuit_defect,
                            branch_defect, mu_at, min_mu, pose_error, tuple(notes))


def linkages(dyads, name: str = "Synthesized linkage") -> list[Linkage]:
    """Every linkage two of the dyads make, each crank once as input (a slider only as the
    output), sorted by `Linkage.screen` (the dyads in closed form, no engine run): usable
    designs first, then by their least transmission angle. The engine's `check` is computed
    when asked for (take the first usable ones: `check` confirms them)."""
    ds = list(dyads)
    out = []
    for i, a in enumerate(ds):
        for j, b in enumerate(ds):
            if i == j or a.is_slider:
                continue
            try:
                out.append(Linkage(a, b, name))
            except SynthesisError:
                continue

    def key(lk: Linkage):  # ranked by the dyads alone: `check` (the engine) is left for the best
        if not lk.geometry_ok:
            return (True, True, 0.0)
        branch, mu = lk.screen
        return (False, branch or not mu >= MIN_TRANSMISSION, -np.nan_to_num(mu, nan=-1.0))

    out.sort(key=key)
    return out


def four_position_linkages(pos, candidates: int = 12, *, reach: float = 3.0, slider: bool = True,
                           name: str = "Synthesized linkage") -> list[Linkage]:
    """Linkages for four positions without chosen pivots: `candidates` centre points spread
    along the centre-point curve within `reach` times the positions' size of their middle
    (and, with `slider`, the curve's point at infinity), every pair of them made into a
    linkage and ranked as `linkages` ranks them."""
    from .burmester import centre_point_curve, curve_samples, dyad

    if len(pos) != 4:
        raise SynthesisError(f"four_position_linkages takes four positions, got {len(pos)}")
    if candidates < 2:
        raise SynthesisError(f"give at least two candidates, got {candidates}")
    curve = centre_point_curve(pos)
    pts = curve_samples(curve, samples=1440)
    middle = pos.origin.mean(axis=0)
    near = np.isfinite(pts).all(axis=1)
    near[near] = np.hypot(*(pts[near] - middle).T) <= reach * pos.size
    pts = pts[near]
    if len(pts) < 2:
        raise SynthesisError("the centre-point curve does not come near the positions")
    # spread the candidates evenly by arc length along the sampled pieces
    step = np.hypot(*np.diff(pts, axis=0).T)
    step[step > 0.05 * pos.size * reach] = 0.0  # a jump between pieces is no arc
    s = np.concatenate([[0.0], np.cumsum(step)])
    picks = np.unique(np.searchsorted(s, np.linspace(0.0, s[-1], candidates), side="left").clip(0, len(pts) - 1))
    ds = []
    for M in pts[picks]:
        try:
            ds.append(dyad(pos, M))
        except SynthesisError:
            continue  # a pole line's point: its circle point is not unique
    if slider:
        ds.append(curve.slider())
    return linkages(ds, name)
