"""Cam design (*Kurvensynthese*): the analyses of a disc cam designed from a motion program.

Given a `model.DiscCam` (the program, the follower and the base circle), this module gives

- the follower diagrams s, v, a, j (*Weg-, Geschwindigkeits-, Beschleunigungs- und
  Ruckdiagramm*) over the cam angle at a constant cam speed ω: v = ω·s′, a = ω²·s″, j = ω³·s‴;
- the pressure angle (*Druckwinkel*, *Übertragungswinkel* is its complement) over the cycle:
  between the common normal at the contact (the line of the contact force without friction)
  and the direction in which the follower's point there can move;
- the profile's radius of curvature (*Krümmungsradius*), signed: positive where the profile
  is convex, negative where it is concave; cusps (the radius passes through zero: the profile
  turns back on itself) and undercut (*Unterschneidung*: where it runs backwards, the roller or
  face cuts away what the law needs); corners of the pitch curve where the velocity jumps;
- the smallest base circle (*kleinster Grundkreis*) for a largest allowed pressure angle or a
  smallest allowed radius of curvature;
- the mechanism file of the cam with its follower drawn in place (`mechanism_text`), which
  `linkwork analyze` runs.

All closed forms are written with the complex numbers of `model.disc_cams`: for a roller or
knife at C(φ) on the follower (in the frame, about the cam centre), the pitch curve's tangent
turned back into the frame is T = C′ − iC and the follower point moves along D (the line of
motion e, or i(C − A) about the lever's pivot A); the pressure angle is arctan(T·D / T×D),
positive while the cam pushes the follower up its line of motion on the rise
(tan α = (s′ − ε)/(s₀ + s) for a translating follower with offset ε).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..errors import InputError
from ..geometry.profiles import curvature, offset_cusps, sign_changes
from ..model.disc_cams import DiscCam
from ..model.motion_programs import TWO_PI, CamDesignError, Join
from ._file import number as _n
from ._file import point as _pt
from ._file import toml_string as _toml_str

__all__ = ["CamReport", "analyse", "follower_diagrams", "pressure_angle", "radius_of_curvature",
           "cusps", "corners", "smallest_base_radius", "with_base_radius", "mechanism_text"]


# ---------------------------------------------------------------------------- diagrams
def follower_diagrams(cam: DiscCam, phi: np.ndarray, speed: float = 1.0, side: int = 1) -> dict[str, np.ndarray]:
    """The follower's lift s (a length, or for an oscillating follower the lever's swing away
    from its rest position, radians), velocity v, acceleration a and jerk j at cam angles φ for
    a cam turning at the constant `speed` ω (rad/s): the k-th time derivative is ωᵏ·dᵏs/dφᵏ."""
    d = cam.program.derivatives(np.asarray(phi, dtype=float), 3, side)
    w = float(speed)
    return {"s": d[0], "v": w * d[1], "a": w**2 * d[2], "j": w**3 * d[3]}


# ---------------------------------------------------------------------------- pressure angle
def _flat_contact(cam: DiscCam, phi: np.ndarray, side: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Contact point X in the frame (complex, about the cam centre), the face normal ν and the
    profile's signed radius of curvature p + d²p/dθ² of a flat face: with x′ = θ′·i e^{iθ}·(p +
    d²p/dθ²) along the face, the radius is x′·(i e^{iθ})/θ′."""
    theta, _ = cam.face_line(phi, 1, side)
    x = cam.profile.derivatives(phi, 1, side=side)
    x0 = (x[0, ..., 0] - cam.center[0]) + 1j * (x[0, ..., 1] - cam.center[1])
    x1 = x[1, ..., 0] + 1j * x[1, ..., 1]
    m = np.exp(1j * theta[0])
    radius = (x1 * np.conj(1j * m)).real / theta[1]
    turn = np.exp(1j * phi)
    return turn * x0, turn * m, radius


def pressure_angle(cam: DiscCam, phi: np.ndarray, side: int = 1) -> np.ndarray:
    """Signed pressure angle (radians) at cam angles φ; |α| is what the engine's contact report
    gives (`Solution.joint(...)['pressure_angle']`). Defined in dwells too: the follower's
    direction of motion is known there although it rests."""
    phi = np.asarray(phi, dtype=float)
    if cam.follower == "flat":
        if cam.motion == "translating":
            return np.zeros_like(phi)
        X, nu, _ = _flat_contact(cam, phi, side)
        D = 1j * (X - cam.pivot_vector)
        return np.arctan((D * np.conj(1j * nu)).real / (D * np.conj(nu)).real)
    C, dC = cam.element_point(phi, 1, side)
    T = dC - 1j * C
    D = cam.line_vector if cam.motion == "translating" else 1j * (C - cam.pivot_vector)
    D = np.broadcast_to(D, T.shape)
    dot = (T * np.conj(D)).real
    cross = (np.conj(T) * D).imag
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.arctan(dot / cross)


# ---------------------------------------------------------------------------- curvature
def radius_of_curvature(cam: DiscCam, phi: np.ndarray, side: int = 1, *, of: str = "profile") -> np.ndarray:
    """Signed radius of curvature of the profile (or, `of="pitch"`, of the pitch curve) at the
    point that touches at cam angle φ: positive where convex, negative where concave; it passes
    through zero at a cusp and is negative on a convex part cut back (undercut)."""
    phi = np.asarray(phi, dtype=float)
    if cam.follower == "flat":
        return _flat_contact(cam, phi, side)[2]
    # the pitch curve runs clockwise: convex where its curvature (counter-clockwise positive) < 0
    r_pitch = -1.0 / curvature(cam.pitch_curve, phi, side)
    if of == "pitch" or cam.follower == "knife":
        return r_pitch
    return r_pitch - cam.roller_radius


def cusps(cam: DiscCam) -> np.ndarray:
    """Cam angles where the profile has a cusp (its radius of curvature passes through zero):
    the roller's or face's envelope turns back there, so the profile between two cusps is cut
    away (undercut) and the follower does not follow the law."""
    if cam.follower == "roller":
        return offset_cusps(cam.pitch_curve, cam.roller_radius)
    if cam.follower == "knife":
        return np.empty(0)
    return sign_changes(lambda u, side=1: radius_of_curvature(cam, u, side), (0.0, TWO_PI),
                        cam.program.breaks, closed=True, samples=4096)


def corners(cam: DiscCam) -> list[Join]:
    """Joins where the follower's velocity jumps: the pitch curve has a corner there (a
    roller rounds a convex one off with its own radius and cuts into a concave one)."""
    return [j for j in cam.program.joins() if j.jumps[0] != 0.0]


# ---------------------------------------------------------------------------- report
@dataclass(frozen=True)
class CamReport:
    """Everything `analyse` computes over one turn (arrays over `phi`, radians)."""

    cam: DiscCam
    phi: np.ndarray
    speed: float
    diagrams: dict
    pressure_angle: np.ndarray
    radius_of_curvature: np.ndarray
    profile: np.ndarray
    pitch: np.ndarray
    cusps: np.ndarray
    undercut: np.ndarray
    joins: list
    corners: list

    @property
    def max_pressure_angle(self) -> float:
        return float(np.nanmax(np.abs(self.pressure_angle)))

    @property
    def angle_of_max_pressure(self) -> float:
        return float(self.phi[int(np.nanargmax(np.abs(self.pressure_angle)))])

    @property
    def min_radius_of_curvature(self) -> float:
        """The smallest radius of curvature on the convex parts (inf if there are none)."""
        r = self.radius_of_curvature
        convex = r[r > 0]
        return float(convex.min()) if convex.size else np.inf

    @property
    def peaks(self) -> dict[str, float]:
        return {k: float(np.nanmax(np.abs(v))) for k, v in self.diagrams.items()}


def analyse(cam: DiscCam, samples: int = 1441, speed: float = 1.0) -> CamReport:
    """The cam's diagrams, pressure angle, curvature, cusps and joins at `samples` cam angles
    over one turn, with every join of the program among them (taken from the segment that
    starts there)."""
    if samples < 8:
        raise InputError(f"analyse needs at least 8 samples, got {samples}")
    phi = np.union1d(np.linspace(0.0, TWO_PI, samples, endpoint=False), cam.program.breaks)
    r = radius_of_curvature(cam, phi)
    prof = cam.profile.derivatives(phi, 0)[0]
    pitch = cam.pitch_curve.derivatives(phi, 0)[0]
    undercut = r < 0 if cam.follower == "flat" else (
        (radius_of_curvature(cam, phi, of="pitch") > 0) & (r < 0))
    return CamReport(cam, phi, float(speed), follower_diagrams(cam, phi, speed), pressure_angle(cam, phi), r,
                     prof, pitch, cusps(cam), undercut, cam.program.joins(), corners(cam))


# ---------------------------------------------------------------------------- base circle
def with_base_radius(cam: DiscCam, base_radius: float) -> DiscCam:
    """The same design on another base circle."""
    return replace(cam, base_radius=float(base_radius))


def _dense(cam: DiscCam, n: int = 8192) -> np.ndarray:
    return np.union1d(np.linspace(0.0, TWO_PI, n, endpoint=False), cam.program.breaks)


def _refined_max(f, grid: np.ndarray) -> float:
    """max f over one turn: the best of the grid, refined by Brent's method between its
    neighbours (f continuous inside the pieces; the joins are grid points)."""
    v = f(grid)
    i = int(np.nanargmax(v))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    best = float(v[i])
    if hi > lo:
        res = minimize_scalar(lambda x: -float(f(np.array([x]))[0]), bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-13})
        best = max(best, -float(res.fun))
    return best


def _feasible_range(cam: DiscCam) -> tuple[float, float]:
    """Open interval of base radii for which the follower can be drawn at all."""
    rho = cam.roller_radius if cam.follower == "roller" else 0.0
    if cam.motion == "translating":
        lo = abs(cam.offset) - rho if cam.follower != "flat" else 0.0
        return max(lo, 0.0), np.inf
    d = abs(cam.pivot_vector)
    if cam.follower == "flat":
        f = cam.face_offset
        return max(-d - f, 0.0), d - f
    return max(abs(d - cam.arm) - rho, 0.0), d + cam.arm - rho


def _scan(cam: DiscCam, criterion, lo: float, hi: float, what: str) -> float:
    """The smallest base radius in (lo, hi) from which on criterion(cam) ≤ 0: a scan of 160
    radii (up to 64 times the given one past an unbounded `hi`), then Brent's method on the
    first bracket (bisection where the radius below cannot be drawn at all)."""
    if not np.isfinite(hi):
        hi = max(lo, cam.base_radius) * 64 + 1.0

    def g(rb):
        try:
            return float(criterion(with_base_radius(cam, rb)))
        except CamDesignError:
            return np.nan

    radii = np.linspace(lo, hi, 162)[1:-1]
    vals = np.array([g(rb) for rb in radii])
    ok = np.flatnonzero(vals <= 0)
    if not ok.size:
        raise CamDesignError(f"no base radius up to {hi:.6g} meets {what}")
    k = int(ok[0])
    a, b = (radii[k - 1], radii[k]) if k else (lo, radii[0])
    if np.isfinite(g(a)):
        return float(brentq(g, a, b, xtol=1e-12 * b, rtol=1e-14))
    for _ in range(60):  # below a lies no drawable cam: bisect on "drawable and within the limit"
        mid = (a + b) / 2
        a, b = (a, mid) if g(mid) <= 0 else (mid, b)
    return float(b)


def smallest_base_radius(cam: DiscCam, max_pressure_angle: float | None = None,
                         min_radius_of_curvature: float | None = None) -> float:
    """The smallest base radius for which the pressure angle stays within
    `max_pressure_angle` (radians) over the whole turn and/or the profile's radius of curvature
    on its convex parts stays at least `min_radius_of_curvature` (no undercut: give a small
    positive value). Other parameters as in `cam`.

    Translating roller or knife, closed form: tan α = (s′ − ε)/(s₀ + s) ≤ tan α_max for all φ
    gives s₀ ≥ max(|s′ − ε|/tan α_max − s) and R₀ = √(s₀² + ε²). Translating flat face: the
    radius of curvature R_b + s + s″ gives R_b ≥ ρ_min − min(s + s″). Otherwise the criterion
    is scanned over the drawable base radii and its root found by Brent's method.
    """
    if max_pressure_angle is None and min_radius_of_curvature is None:
        raise CamDesignError("give a largest pressure angle or a smallest radius of curvature")
    results = []
    lo, hi = _feasible_range(cam)
    rho = cam.roller_radius if cam.follower == "roller" else 0.0
    if max_pressure_angle is not None:
        a = float(max_pressure_angle)
        if not 0 < a < np.pi / 2:
            raise CamDesignError(f"the largest pressure angle must lie between 0° and 90°, got {np.degrees(a):g}°")
        if cam.follower == "flat" and cam.motion == "translating":
            raise CamDesignError("a flat face perpendicular to its line of motion has a pressure angle of "
                                 "0 whatever the base circle: limit the radius of curvature instead")
        if cam.motion == "translating":
            tan = np.tan(a)
            eps = cam.offset

            def need(u):
                d = cam.program.derivatives(u, 1)
                return np.abs(d[1] - eps) / tan - d[0]

            s0 = _refined_max(need, _dense(cam))
            if s0 <= 0:
                raise CamDesignError(f"the pressure angle stays below {np.degrees(a):g}° on every base "
                                     "circle: limit the radius of curvature instead")
            results.append(float(np.hypot(s0, eps)) - rho)
        else:
            grid = _dense(cam, 2048)
            results.append(_scan(cam, lambda c: np.nanmax(np.abs(pressure_angle(c, grid))) - a, lo, hi,
                                 f"a pressure angle of at most {np.degrees(a):g}°"))
    if min_radius_of_curvature is not None:
        rmin = float(min_radius_of_curvature)
        if cam.follower == "flat" and cam.motion == "translating":
            def deficit(u, side=1):
                d = cam.program.derivatives(u, 2, side)
                return -(d[0] + d[2])

            worst = max(_refined_max(deficit, _dense(cam)), float(np.max(deficit(cam.program.breaks, -1))))
            results.append(rmin + worst)
        else:
            grid = _dense(cam, 2048)

            def crit(c):
                r = radius_of_curvature(c, grid)
                if c.follower != "flat":
                    r = r[radius_of_curvature(c, grid, of="pitch") > 0]
                return rmin - float(np.min(r)) if r.size else -1.0

            results.append(_scan(cam, crit, lo, hi, f"a radius of curvature of at least {rmin:g}"))
    return float(max(results))


# ---------------------------------------------------------------------------- the file
def mechanism_text(cam: DiscCam, *, name: str = "Designed disc cam", speed: str = "1 rad/s",
                   length_unit: str = "mm", description: str | None = None) -> str:
    """The mechanism file of the cam: frame, cam (turning about O, the driver) and follower with
    its element drawn touching the profile at cam angle 0; the profile is the `cam-design` table
    itself, so loading the file designs the same cam again."""
    prog = cam.program
    osc = cam.motion == "oscillating"
    segs = []
    for s in prog.segments:
        over = _n(np.degrees(s.extent))
        if s.kind == "dwell":
            segs.append(f"    {{ dwell = {over} }},")
        else:
            lift = _n(np.degrees(s.lift) if osc else s.lift)
            segs.append(f'    {{ {s.kind} = {lift}, over = {over}, law = "{s.law}" }},')
    C = cam.follower_point()
    O = np.asarray(cam.center, dtype=float)
    prof = [f'type = "cam-design"', f'follower = "{cam.follower}"', f"base_radius = {_n(cam.base_radius)}"]
    if cam.follower == "roller":
        prof.append(f"roller_radius = {_n(cam.roller_radius)}")
    prof.append(f'motion = "{cam.motion}"')
    if any(O != 0):
        prof.append(f"center = {_pt(O)}")
    # M marks the cam's angle (a point of its base circle on the x-axis)
    lines_points = [f"O = {_pt(O)}", f"M = {_pt(O + [cam.base_radius, 0.0])}", f"C = {_pt(C)}"]
    if osc:
        prof.append(f"pivot = {_pt(cam.pivot)}")
        if cam.follower == "flat":
            prof.append(f"face_offset = {_n(cam.face_offset)}")
        else:
            prof.append(f"arm = {_n(cam.arm)}")
        prof.append(f'side = "{cam.side}"')
        lines_points.append(f"A = {_pt(cam.pivot)}")
        links = ['frame = ["O", "A"]', 'cam = ["O", "M"]', 'follower = ["C", "A"]']
        guide = 'A = { type = "revolute", links = ["frame", "follower"] }'
    else:
        prof.append(f"offset = {_n(cam.offset)}")
        prof.append(f"direction = {_n(np.degrees(cam.direction))}")
        e = cam.line_of_motion()
        G = C + (cam.base_radius + prog.max_lift) * e  # a point of the follower's stem
        lines_points.append(f"G = {_pt(G)}")
        links = ['frame = ["O"]', 'cam = ["O", "M"]', 'follower = ["C", "G"]']
        guide = (f'G = {{ type = "prismatic", links = ["frame", "follower"], axis = '
                 f'{_n(np.degrees(cam.direction))} }}')
    if cam.follower == "roller":
        contact = f'follower = "roller", point = "C", radius = {_n(cam.roller_radius)}'
    elif cam.follower == "knife":
        contact = 'follower = "knife", point = "C"'
    else:
        nu = cam.face_normal()
        contact = f'follower = "flat", point = "C", axis = {_n(np.degrees(np.arctan2(nu[0], -nu[1])))}'
    unit = "°" if osc else f" {length_unit}"
    plan = ", ".join(f"{s.kind} {_n(np.degrees(s.extent))}°" + (
        "" if s.kind == "dwell" else f" by {_n(np.degrees(s.lift) if osc else s.lift)}{unit} ({s.law})")
        for s in prog.segments)
    desc = description or (f"A disc cam designed from its follower's motion program: {plan}; "
                           f"{cam.motion} {cam.follower} follower. Written by `linkwork cam design`.")
    return "\n".join([
        f"name = {_toml_str(name)}",
        f"description = {_toml_str(desc)}",
        f'units = {{ length = "{length_unit}", angle = "deg" }}',
        "",
        "[points]", *lines_points,
        "",
        "[profiles.cam]", *prof,
        "segments = [", *segs, "]",
        "",
        "[links]", *links,
        "",
        "[joints]",
        'O = { type = "revolute", links = ["frame", "cam"] }',
        guide,
        f'K = {{ type = "cam", links = ["cam", "follower"], profile = "cam", {contact} }}',
        "",
        "[driver]",
        'joint = "O"',
        f"speed = {_toml_str(speed)}",
        "",
    ])
