"""`linkwork cam design`: a disc cam from its follower's motion program, written as a mechanism
file (which `linkwork analyze` runs) with a report of its diagrams, pressure angle and profile.

    linkwork cam design --rise 20:120:cycloidal --dwell 60 --return 20:120:3-4-5 --dwell 60 \\
        --follower roller --radius 8 --base-radius 40 -o cam.toml --report cam.svg

The segments are taken in the order written. The command checks its own work: it loads the file
it wrote, lets the engine move the follower over the whole turn and reports how far that
motion strays from the law (it stops with an error beyond 1e-9 of the lift).
"""

from __future__ import annotations

import warnings
from enum import Enum
from pathlib import Path
from typing import Optional

import numpy as np
import typer
from rich.console import Console
from rich.table import Table
from typer.core import TyperCommand

from ..errors import InputError, LinkworkWarning
from ..outputs import write_output_file
from ..units import parse_quantity
from .common import err_console, output_format, user_errors

SEGMENT_OPTIONS = ("rise", "dwell", "return_")
CHECK_SAMPLES = 1440


class _InOrder(TyperCommand):
    """Keeps the order in which --rise, --dwell and --return are written (Typer hands each
    option's values over separately)."""

    def parse_args(self, ctx, args):
        try:
            _, _, order = self.make_parser(ctx).parse_args(args=list(args))
            ctx.meta["segment_order"] = [p.name for p in order if p.name in SEGMENT_OPTIONS]
        except Exception:  # the real parse below reports the error
            pass
        return super().parse_args(ctx, args)


class Follower(str, Enum):
    roller = "roller"
    knife = "knife"
    flat = "flat"


class Motion(str, Enum):
    translating = "translating"
    oscillating = "oscillating"


class Side(str, Enum):
    left = "left"
    right = "right"


def _number(text: str, what: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise InputError(f"{what}: '{text}' is not a number") from None
    if not np.isfinite(v):
        raise InputError(f"{what}: '{text}' is not a finite number")
    return v


def _segments(order: list[str], rises: list[str], dwells: list[str], returns: list[str], oscillating: bool):
    from ..model.motion_programs import Segment

    queues = {"rise": list(rises), "dwell": list(dwells), "return_": list(returns)}
    if not order or sum(len(q) for q in queues.values()) != len(order):
        # the order was not recorded (called without the command line): rises, dwells, returns
        order = ["rise"] * len(rises) + ["dwell"] * len(dwells) + ["return_"] * len(returns)
    out = []
    for n, kind in enumerate(order, start=1):
        text = queues[kind].pop(0)
        option = "--return" if kind == "return_" else f"--{kind}"
        where = f"{option} {text} (segment {n})"
        if kind == "dwell":
            out.append(Segment("dwell", np.radians(_number(text, where))))
            continue
        parts = text.split(":")
        if len(parts) != 3:
            raise InputError(f"{where}: write LIFT:ANGLE:LAW, e.g. 20:120:cycloidal")
        lift, angle = _number(parts[0], where), _number(parts[1], where)
        out.append(Segment("rise" if kind == "rise" else "return", np.radians(angle),
                           np.radians(lift) if oscillating else lift, parts[2].strip()))
    return out


def _pair(text: str, what: str) -> tuple[float, float]:
    parts = text.replace(";", ",").split(",")
    if len(parts) != 2:
        raise InputError(f"{what}: write X,Y")
    return _number(parts[0], what), _number(parts[1], what)


def _summary(report, cam, unit: str, check: float | None) -> Table:
    osc = cam.motion == "oscillating"
    t = Table(title="designed cam", show_header=False)
    t.add_column("quantity")
    t.add_column("value", justify="right")
    t.add_row("base radius", f"{cam.base_radius:.6g} {unit}")
    if cam.follower == "roller":
        t.add_row("roller radius", f"{cam.roller_radius:.6g} {unit}")
    t.add_row("largest pressure angle", f"{np.degrees(report.max_pressure_angle):.4f}° at "
                                        f"φ = {np.degrees(report.angle_of_max_pressure):.3f}°")
    t.add_row("smallest radius of curvature (convex)", f"{report.min_radius_of_curvature:.6g} {unit}")
    t.add_row("cusps (undercut)", ", ".join(f"{np.degrees(c):.3f}°" for c in report.cusps) or "none")
    lu = "°" if osc else unit
    conv = np.degrees if osc else float
    peaks = report.peaks
    t.add_row("largest |v|, |a|, |j|",
              f"{conv(peaks['v']):.6g} {lu}/s, {conv(peaks['a']):.6g} {lu}/s², {conv(peaks['j']):.6g} {lu}/s³")
    names = {1: "velocity", 2: "acceleration", 3: "jerk", 4: "snap"}
    for j in report.joins:
        k = j.first_jump
        if k is not None and k <= 3:
            jump = conv(j.jumps[k - 1])
            t.add_row(f"join at {np.degrees(j.angle):.3f}°", f"{names[k]} jumps by {jump:.6g} {lu}/rad{'²³'[k - 2] if k > 1 else ''}")
    if check is not None:
        t.add_row("engine vs law (whole turn)", f"{check:.2e} of the lift")
    return t


def register(app: typer.Typer) -> None:
    cam_app = typer.Typer(no_args_is_help=True, help="Cam design: disc cams from a follower motion program.")
    app.add_typer(cam_app, name="cam")

    @cam_app.command("design", cls=_InOrder)
    def design(
        ctx: typer.Context,
        rise: Optional[list[str]] = typer.Option(None, "--rise", help="LIFT:ANGLE:LAW, a rise of LIFT (the length unit; degrees for an oscillating follower) over ANGLE degrees of cam angle; LAW one of uniform, harmonic, cycloidal, 3-4-5, 4-5-6-7, modified-trapezoid, modified-sine, parabolic"),
        dwell: Optional[list[str]] = typer.Option(None, "--dwell", help="ANGLE: a dwell over ANGLE degrees"),
        return_: Optional[list[str]] = typer.Option(None, "--return", help="LIFT:ANGLE:LAW, a return (as --rise); segments are taken in the order written and must fill 360°"),
        follower: Follower = typer.Option(Follower.roller, "--follower", help="the follower's element"),
        radius: Optional[float] = typer.Option(None, "--radius", help="roller radius"),
        base_radius: Optional[float] = typer.Option(None, "--base-radius", help="base circle radius (with --max-pressure-angle: at least this)"),
        max_pressure_angle: Optional[float] = typer.Option(None, "--max-pressure-angle", help="DEG: use the smallest base circle whose pressure angle stays within DEG"),
        min_curvature_radius: Optional[float] = typer.Option(None, "--min-curvature-radius", help="use the smallest base circle whose profile's radius of curvature stays at least this (no undercut)"),
        motion: Motion = typer.Option(Motion.translating, "--motion", help="translating or oscillating follower"),
        offset: float = typer.Option(0.0, "--offset", help="translating: the line of motion's distance to the right of the cam centre"),
        pivot: Optional[str] = typer.Option(None, "--pivot", help="oscillating: the lever's pivot X,Y (cam centre at 0,0)"),
        arm: Optional[float] = typer.Option(None, "--arm", help="oscillating roller or knife: pivot to roller centre or knife tip"),
        face_offset: float = typer.Option(0.0, "--face-offset", help="oscillating flat face: its distance from the pivot"),
        side: Side = typer.Option(Side.left, "--side", help="oscillating: the follower's side (left or right) of the line from the cam centre to the pivot"),
        speed: str = typer.Option("1 rad/s", "--speed", help="cam speed written to the file and used for the diagrams, e.g. '300 rpm'"),
        unit: str = typer.Option("mm", "--unit", help="length unit of the file"),
        name: str = typer.Option("Designed disc cam", "--name", help="the mechanism's name"),
        output: str = typer.Option(..., "-o", "--output", help="the mechanism file to write (TOML)"),
        report: Optional[str] = typer.Option(None, "--report", help="FILE.svg, FILE.png or FILE.pdf: diagrams, pressure angle and the profile"),
    ) -> None:
        """Design a disc cam from rise/dwell/return segments and write its mechanism file."""
        with user_errors():
            output_format(None, output, ("toml",), "toml")  # a mechanism file
            from ..model.disc_cams import DiscCam
            from ..model.motion_programs import MotionProgram
            from ..synthesis import analyse, mechanism_text, smallest_base_radius, with_base_radius
            from ..units import check_length_unit

            check_length_unit(unit)
            out = Path(output)
            if report is not None and Path(report).suffix.lower() not in (".svg", ".png", ".pdf"):
                raise InputError(f"--report {report}: write .svg, .png or .pdf")
            if not (rise or return_ or dwell):
                raise InputError("give the motion: --rise LIFT:ANGLE:LAW, --dwell ANGLE, --return LIFT:ANGLE:LAW …")
            osc = motion is Motion.oscillating
            program = MotionProgram(_segments(ctx.meta.get("segment_order", []), rise or [], dwell or [],
                                              return_ or [], osc))
            w = parse_quantity(speed, default_unit="rad/s", kind="--speed")
            if follower is Follower.roller and radius is None:
                raise InputError("a roller follower needs --radius")
            if base_radius is None and max_pressure_angle is None and min_curvature_radius is None:
                raise InputError("give --base-radius, or --max-pressure-angle (or --min-curvature-radius) "
                                 "to find the smallest base circle")
            if osc and pivot is None:
                raise InputError("an oscillating follower needs --pivot X,Y")
            if osc and follower is not Follower.flat and arm is None:
                raise InputError("an oscillating roller or knife needs --arm")
            pv = _pair(pivot, "--pivot") if pivot else None
            kw = dict(roller_radius=radius or 0.0, motion=motion.value, offset=offset, pivot=pv, arm=arm,
                      face_offset=face_offset, side=side.value)
            searching = max_pressure_angle is not None or min_curvature_radius is not None
            cam = _searchable(program, follower.value, base_radius, kw) if searching else \
                DiscCam(program, follower.value, base_radius, **kw)
            status = err_console.status("finding the smallest base circle …")
            if max_pressure_angle is not None or min_curvature_radius is not None:
                with status:
                    rb = smallest_base_radius(cam, None if max_pressure_angle is None else np.radians(max_pressure_angle),
                                              min_curvature_radius)
                if base_radius is not None and base_radius > rb:
                    rb = base_radius
                cam = with_base_radius(cam, rb)
            text = mechanism_text(cam, name=name, speed=speed, length_unit=unit)
            write_output_file(out, text)  # all or nothing, OSError as one line
            rep = analyse(cam, speed=w)
            if rep.cusps.size:
                warnings.warn(LinkworkWarning(
                    "the profile has cusps at " + ", ".join(f"{np.degrees(c):.2f}°" for c in rep.cusps)
                    + ": it is undercut between them and the follower cannot follow the law there; "
                    "enlarge the base circle" + (" or take a smaller roller" if cam.follower == "roller" else "")))
            check = _check(out, cam)
            Console().print(_summary(rep, cam, unit, check))
            Console().print(f"wrote {out}" + (f" and {report}" if report else ""))
            if report:
                from ..drawing.cam_plots import cam_report_figure
                from ..drawing.plots import save
                save(cam_report_figure(rep, max_pressure_angle=None if max_pressure_angle is None
                                       else np.radians(max_pressure_angle), length_unit=unit, title=name),
                     report)


def _searchable(program, follower: str, start: float | None, kw: dict):
    """A cam to start the base-circle search from: the given base radius if it can be drawn,
    else one that can (the offset line must cut the prime circle; an oscillating lever reaches
    only some base circles)."""
    from ..model.disc_cams import DiscCam
    from ..model.motion_programs import CamDesignError

    rho = kw["roller_radius"] if follower == "roller" else 0.0
    if start is not None:
        try:
            return DiscCam(program, follower, start, **kw)
        except CamDesignError:
            pass
    if kw["motion"] == "translating":
        return DiscCam(program, follower, max(abs(kw["offset"]) + 1.0 - rho, 1.0), **kw)
    if kw["pivot"] is None:
        raise InputError("an oscillating follower needs --pivot X,Y")
    d = float(np.hypot(*kw["pivot"]))
    if follower == "flat":
        mid = (d - kw["face_offset"]) / 2
    else:
        arm = kw["arm"] or 0.0
        mid = (abs(d - arm) + d + arm) / 2 - rho
    return DiscCam(program, follower, max(mid, 1e-9), **kw)


def _check(path: Path, cam) -> float:
    """Load the written file, move it with the engine over the whole turn and return the
    largest deviation of the follower from the law, relative to the lift."""
    from ..io import load
    from ..kinematics import solve

    phi = (np.arange(CHECK_SAMPLES) + 0.5) * (2 * np.pi / CHECK_SAMPLES)
    with err_console.status("checking the design with the engine over the whole turn …"):
        mech = load(path)
        sol = solve(mech, phi, order=1)
    pose = sol.pose_derivatives("follower")[0]
    want = cam.follower_motion(phi, 0)[0]
    if cam.motion == "translating":
        e = cam.line_of_motion()
        got = pose[:, :2] @ e + cam.program.derivatives(np.array(0.0), 0)[0]
    else:
        got = pose[:, 2] + cam.rocker_start
    lift = max(cam.program.max_lift, 1e-300)
    dev = float(np.nanmax(np.abs(got - want))) / lift
    if not np.isfinite(dev) or dev > 1e-9:
        raise InputError(f"the engine moves the follower of {path} up to {dev:.3g} of the lift away from "
                         "the law (the profile may be undercut: see its cusps); not a usable design")
    return dev
