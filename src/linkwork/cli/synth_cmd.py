"""`linkwork synth`: linkages designed from what they must do.

    linkwork synth poses --pose 0,0,0 --pose 1,0.4,20 --pose 1.8,1.2,45 --pose 2.2,2.1,70 \\
        --pose 2.3,3,95 -o guide.toml --report guide.json
    linkwork synth function --function "log10(x)" --x 1:2 --input-range 30:120 \\
        --output-range 60:150 --points 3 -o log.toml

`poles` draws Hamilton's construction of the poles, the pole triangle and homologous points
by reflections (Pöschl §57), with --steps one drawing per step. `poses` guides a plane (a coupler) through prescribed positions x, y, angle (degrees): three
positions with two chosen pivots (--centre for a fixed pivot, --circle for a moving pivot
drawn in the first position), four with two fixed pivots on the centre-point curve (or
--slider for the curve's point at infinity) or, without them, the best pairs of points along
that curve, five from the Burmester points (every four-bar they make, best first); --draw
FILE.svg draws the positions, poles, pole triangles, for four positions the centre-point and
circle-point curves, and the pivots used (five: the Burmester points). `function` designs a four-bar (or --slider: a slider-crank) whose output
follows y = f(x) through precision points by Freudenstein's equation. `dwell` adds Alt's dwell
dyad to a four-bar at a coupler point (Pöschl §37); `substitute` replaces a crank of a four-bar
by Pröll's (Rosenauer §29), keeping the coupler's motion to second order (--order 3: to the jerk). `path` finds a
four-bar whose coupler point passes through target points (least squares from several starts);
`six-bar-path` does the same with a Watt I or Stephenson III six-bar; `cognates` writes the
Roberts–Chebyshev cognates of a four-bar's coupler point; `straight-line` designs Watt's,
Chebyshev's and Evans's linkages from a stroke, a Ball-point tracer or Hart's exact line from a
four-bar, and `straightness` measures any point path against its best line.

Every file written is loaded again and solved by the engine at the positions' (or precision
points') inputs; the deviation is reported and must stay within 1e-9, else the command stops
with an error.
"""

from __future__ import annotations

import ast
import json
import math
from pathlib import Path
from typing import Optional

import numpy as np
import typer
from rich.console import Console
from rich.table import Table

from ..errors import InputError
from ..outputs import write_output_file
from .cam_cmd import _number, _pair
from .common import err_console, output_format, user_errors

TOLERANCE = 1e-9


def _pose(text: str, what: str) -> tuple[float, float, float]:
    parts = text.replace(";", ",").split(",")
    if len(parts) != 3:
        raise InputError(f"{what} {text}: write X,Y,ANGLE (angle in degrees)")
    x, y, a = (_number(p, f"{what} {text}") for p in parts)
    return x, y, math.radians(a)


def _poses(pose: list[str], poses_file: Optional[str]):
    from ..synthesis import Positions

    rows = [_pose(p, "--pose") for p in pose or []]
    if poses_file:
        try:
            text = Path(poses_file).read_text()
        except OSError as exc:
            raise InputError(f"--poses {poses_file}: {exc.strerror or exc}") from None
        for n, line in enumerate(text.splitlines(), start=1):
            line = line.split("#")[0].strip()
            if not line or line[0].isalpha():  # a header
                continue
            rows.append(_pose(line, f"--poses {poses_file} line {n}:"))
    if len(rows) < 3:
        raise InputError(f"give at least three positions (--pose X,Y,ANGLE or --poses FILE), got {len(rows)}")
    if len(rows) > 5:
        raise InputError(f"{len(rows)} positions: a four-bar guides a plane exactly through at most five")
    return Positions.from_poses(np.array(rows))


def _paths(output: str, n: int) -> list[Path]:
    out = Path(output)
    if n == 1:
        return [out]
    return [out.with_name(f"{out.stem}-{k}{out.suffix or '.toml'}") for k in range(1, n + 1)]


def _engine_pose_error(path: Path, lk) -> float:
    """Load the written file, solve it at the positions' input angles and measure the coupler
    points P and Q against the positions (relative to their size)."""
    from ..io import load
    from ..kinematics import solve

    mech = load(path)
    pos, ref = lk.positions, lk.ref
    sol = solve(mech, lk.input_angles(), order=1)
    worst = 0.0
    for name in ("P", "Q"):
        want = pos.homologous(mech.points[name], ref)
        got = sol.point(name).position
        worst = max(worst, float(np.nanmax(np.hypot(*(got - want).T))) / pos.size)
    return worst if np.isfinite(worst) else math.inf


def _linkage_table(found, errors) -> Table:
    t = Table(title="synthesized linkages", show_lines=False)
    for col in ("#", "kind", "Grashof type", "order", "circuit", "branch", "min μ", "engine error"):
        t.add_column(col)
    for k, (lk, err) in enumerate(zip(found, errors), start=1):
        c = lk.check
        t.add_row(str(k), lk.kind, c.name.split(" (")[0], "defect" if c.order_defect else "ok",
                  "defect" if c.circuit_defect else "ok", "defect" if c.branch_defect else "ok",
                  f"{math.degrees(c.min_transmission):.2f}°", "—" if err is None else f"{err:.1e}")
    return t


def _summary(title: str, rows: list[tuple[str, str]]) -> Table:
    t = Table(title=title, show_header=False)
    t.add_column("quantity")
    t.add_column("value", justify="right")
    for r in rows:
        t.add_row(*r)
    return t


def _xy_text(p) -> str:
    return f"{p[0]:.9g}, {p[1]:.9g}"


def _point_json(p):
    return {"at_infinity": list(map(float, p.direction.xy))} if p.is_infinite else list(map(float, p.xy))


def _dyads(pos, centres, circles, slider: bool):
    from ..synthesis import centre_point_curve, dyad

    ds = [dyad(pos, _pair(c, "--centre")) for c in centres or []]
    ds += [dyad(pos, circle=_pair(c, "--circle")) for c in circles or []]
    if slider:
        if len(pos) == 4:
            ds.append(centre_point_curve(pos).slider())
        else:
            raise InputError("--slider (the centre-point curve's point at infinity) needs four positions")
    return ds


_FUNCTIONS = {name: getattr(np, name) for name in (
    "sin", "cos", "tan", "arcsin", "arccos", "arctan", "sinh", "cosh", "tanh", "exp", "log", "log10",
    "log2", "sqrt", "abs")}
_CONSTANTS = {"pi": math.pi, "e": math.e}


def _function(text: str):
    """y = f(x) from an expression in x with + − * / **, numbers, pi, e and NumPy's elementary
    functions; anything else is refused before it is evaluated."""
    try:
        tree = ast.parse(text, mode="eval")
    except SyntaxError:
        raise InputError(f"--function '{text}': not an expression in x") from None
    allowed = (ast.Expression, ast.BinOp, ast.UnaryOp, ast.Call, ast.Name, ast.Constant, ast.Load,
               ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow, ast.USub, ast.UAdd)
    for node in ast.walk(tree):
        if not isinstance(node, allowed):
            raise InputError(f"--function '{text}': '{ast.unparse(node) if isinstance(node, ast.expr) else type(node).__name__}' "
                             "is not allowed (use x, numbers, + − * / **, pi, e and "
                             + ", ".join(_FUNCTIONS) + ")")
        if isinstance(node, ast.Constant) and not isinstance(node.value, (int, float)):
            raise InputError(f"--function '{text}': only numbers are allowed as constants")
        if isinstance(node, ast.Call) and not (isinstance(node.func, ast.Name) and node.func.id in _FUNCTIONS
                                               and not node.keywords):
            raise InputError(f"--function '{text}': unknown function in '{ast.unparse(node)}'")
        if isinstance(node, ast.Name) and node.id not in _FUNCTIONS and node.id not in _CONSTANTS and node.id != "x":
            raise InputError(f"--function '{text}': unknown name '{node.id}' (the variable is x)")
    code = compile(tree, "<function>", "eval")

    def f(x):
        with np.errstate(all="ignore"):
            return np.asarray(eval(code, {"__builtins__": {}}, {**_FUNCTIONS, **_CONSTANTS, "x": x}),  # noqa: S307
                              dtype=float) * np.ones_like(x)
    return f


def _range(text: str, what: str, degrees: bool) -> tuple[float, float]:
    parts = text.split(":")
    if len(parts) != 2:
        raise InputError(f"{what} {text}: write START:END")
    a, b = (_number(p, f"{what} {text}") for p in parts)
    return (math.radians(a), math.radians(b)) if degrees else (a, b)


def register(app: typer.Typer) -> None:
    synth = typer.Typer(no_args_is_help=True, help="Synthesis: linkages designed from positions, a function, a path or a straight line.")
    app.add_typer(synth, name="synth")
    register_curvature_designs(synth)
    register_straight_lines(synth)

    @synth.command("poses")
    def poses_command(
        pose: Optional[list[str]] = typer.Option(None, "--pose", help="X,Y,ANGLE: a position of the moving plane (its origin and the angle of its x-axis, degrees); repeat, 3 to 5 times"),
        poses_file: Optional[str] = typer.Option(None, "--poses", help="a CSV file of positions x,y,angle (degrees), one a line"),
        centre: Optional[list[str]] = typer.Option(None, "--centre", help="X,Y: a fixed pivot (centre point) to use; three positions: any point, four: a point of the centre-point curve"),
        circle: Optional[list[str]] = typer.Option(None, "--circle", help="X,Y: a moving pivot (circle point) drawn in the first position (three positions)"),
        slider: bool = typer.Option(False, "--slider", help="four positions: a slider whose pin's homologous points lie on a line (the centre-point curve's point at infinity)"),
        unit: str = typer.Option("mm", "--unit", help="length unit of the files"),
        name: str = typer.Option("Synthesized linkage", "--name", help="the mechanisms' name"),
        all_: bool = typer.Option(False, "--all", help="write every linkage found, also those with defects (five positions, or four without pivots)"),
        best: Optional[int] = typer.Option(None, "--best", help="write at most this many of the usable linkages, best first (default: all for five positions, 3 for four without pivots)"),
        min_transmission: float = typer.Option(30.0, "--min-transmission", help="DEG: a linkage is usable from this least transmission angle on"),
        output: str = typer.Option(..., "-o", "--output", help="the mechanism file to write (several: NAME-1.toml, NAME-2.toml, …)"),
        report: Optional[str] = typer.Option(None, "--report", help="FILE.json: poles, Burmester points, linkages and their checks"),
        draw: Optional[str] = typer.Option(None, "--draw", help="FILE.svg (.png, .pdf): the positions, poles, pole triangles, for four positions the Burmester curves, and the pivots found"),
    ) -> None:
        """Guide a plane through 3–5 prescribed positions with a four-bar or slider-crank."""
        with user_errors():
            output_format(None, output, ("toml",), "toml")  # a mechanism file
            from ..synthesis import Linkage, burmester_points, linkages
            from ..units import check_length_unit

            check_length_unit(unit)
            pos = _poses(pose, poses_file)
            n = len(pos)
            doc: dict = {"positions": [[float(p[0]), float(p[1]), math.degrees(p[2])] for p in pos.poses],
                         "poles": {f"P{i + 1}{j + 1}": {"point": _point_json(p),
                                                         "rotation_deg": math.degrees(pos.rotation(i, j))}
                                   for (i, j), p in pos.poles().items()}}
            auto = n == 5 or (n == 4 and not (centre or circle or slider))
            if best is not None and best < 1:
                raise InputError(f"--best {best}: give at least 1")
            if n == 5 and (centre or circle or slider):
                raise InputError("five positions: the pivots are the Burmester points (drop --centre, "
                                 "--circle, --slider)")
            if n == 4:  # the curves to choose the pivots from, sampled for drawing
                from ..synthesis import centre_point_curve, circle_point_curve, curve_samples

                for key, curve in (("centre_point_curve", centre_point_curve(pos)),
                                   ("circle_point_curve", circle_point_curve(pos))):
                    pts = curve_samples(curve, samples=360)
                    doc[key] = {"coefficients": curve.coefficients.tolist(),
                                "points": [None if not np.isfinite(p).all() else p.tolist() for p in pts]}
            if auto:
                if n == 5:
                    bp = burmester_points(pos)
                    doc["burmester"] = {"real": [{"centre": _point_json(d.centre), "circle": _point_json(d.circle)}
                                                 for d in bp.dyads], "complex": bp.complex_count}
                    if len(bp.dyads) < 2:
                        raise InputError(bp.message)
                    found, what = linkages(bp.dyads, name), bp.message
                else:
                    from ..synthesis.linkages import four_position_linkages

                    with err_console.status("trying pairs of centre points along the centre-point curve …"):
                        found = four_position_linkages(pos, name=name)
                    what = f"{len(found)} linkages from points of the centre-point curve"
                limit = best if best is not None else (None if n == 5 else 3)
                if all_:
                    chosen = found[:limit]
                else:  # found is ranked without the engine: its check confirms the first usable ones
                    chosen = []
                    for lk in found:
                        if limit is not None and len(chosen) >= limit:
                            break
                        if lk.geometry_ok and lk.check.usable(math.radians(min_transmission)):
                            chosen.append(lk)
                if not chosen:
                    shown = [lk for lk in found if lk.geometry_ok][:10]
                    if shown:
                        Console().print(_linkage_table(shown, [None] * len(shown)))
                    raise InputError(f"{what}, but none is usable (no defect, least transmission angle "
                                     f"≥ {min_transmission:g}°); --all writes them anyway")
            else:
                ds = _dyads(pos, centre, circle, slider)
                if len(ds) != 2:
                    raise InputError(f"{n} positions: give two pivots (--centre X,Y or --circle X,Y"
                                     + (", or --slider" if n == 4 else "") + f"), got {len(ds)}")
                if ds[0].is_slider:
                    ds.reverse()
                chosen = [Linkage(ds[0], ds[1], name)]
            if draw:
                from ..drawing.synthesis_layers import draw_positions

                marked = list(bp.dyads) if n == 5 else [chosen[0].input, chosen[0].output]
                draw_positions(pos, marked, unit=unit, title=name).save(draw)
            paths = _paths(output, len(chosen))
            errors = []
            for k, (lk, path) in enumerate(zip(chosen, paths), start=1):
                label = name if len(chosen) == 1 else f"{name} {k}"
                write_output_file(path, lk.mechanism_text(name=label, length_unit=unit))
                errors.append(_engine_pose_error(path, lk))
            doc["linkages"] = [{"file": str(p), "lengths": lk.lengths, "input_pivot": _point_json(lk.input.centre),
                                "output_pivot": _point_json(lk.output.centre), **lk.check.as_dict(),
                                "engine_error": e} for lk, p, e in zip(chosen, paths, errors)]
            Console().print(_linkage_table(chosen, errors))
            for lk, p in zip(chosen, paths):
                for note in lk.check.notes:
                    Console().print(f"{p.name}: {note}", highlight=False)
            if report:
                write_output_file(report, json.dumps(doc, indent=2, default=float) + "\n")
            Console().print("wrote " + ", ".join(str(p) for p in paths) + (f", {report}" if report else "")
                            + (f", {draw}" if draw else ""))
            bad = [str(p) for p, e, lk in zip(paths, errors, chosen) if e > TOLERANCE and not lk.check.circuit_defect]
            if bad:
                raise InputError("the engine does not reproduce the positions with " + ", ".join(bad)
                                 + f" (beyond {TOLERANCE:g}): not a usable design")

    @synth.command("poles")
    def poles_command(
        pose: Optional[list[str]] = typer.Option(None, "--pose", help="X,Y,ANGLE: a position of the moving plane (degrees); repeat, 3 to 5 times"),
        poses_file: Optional[str] = typer.Option(None, "--poses", help="a CSV file of positions x,y,angle (degrees), one a line"),
        point: Optional[str] = typer.Option(None, "--point", help="X,Y: the point D1 of the first position whose homologous points are found (default: the middle of its segment)"),
        triple: str = typer.Option("1,2,3", "--triple", help="I,J,K: the three positions of the construction (numbered from 1)"),
        steps: bool = typer.Option(False, "--steps", help="one drawing per construction step (FILE-01.svg, …)"),
        unit: str = typer.Option("mm", "--unit", help="length unit of the drawing"),
        output: str = typer.Option(..., "-o", "--output", help="FILE.svg (.png, .pdf): the positions with Hamilton's construction"),
    ) -> None:
        """Hamilton's construction (Pöschl §57): poles, pole triangle, homologous points by reflections."""
        with user_errors():
            from ..constructions.scales import Scales
            from ..drawing.layers import construction_box, construction_extent, draw_construction
            from ..drawing.svg import Figure
            from ..synthesis.reflections import pole_construction
            from ..units import check_length_unit

            check_length_unit(unit)
            if Path(output).suffix.lower() not in (".svg", ".png", ".pdf"):
                raise InputError(f"-o {output}: write .svg, .png or .pdf")
            pos = _poses(pose, poses_file)
            try:
                t = tuple(int(v) - 1 for v in triple.split(","))
            except ValueError:
                raise InputError(f"--triple {triple}: write three position numbers I,J,K") from None
            con = pole_construction(pos, None if point is None else _pair(point, "--point"), triple=t)
            con.require(0)
            con.check()
            Console().print(con.describe(), highlight=False)
            con = con.sample(0)  # the drawing takes single items
            out = Path(output)
            scales = Scales.auto(unit, 1.2 * construction_extent(con))

            def figure():  # the construction draws the positions itself (step 1)
                fig = Figure(scales, title="Hamilton's construction (Pöschl §57)")
                fig.clip["mechanism"] = construction_box(con)
                return fig
            if steps:
                written = []
                for k in range(len(con.steps)):
                    fig = figure()
                    draw_construction(fig, con, upto=k, highlight=k)
                    p = out.with_name(f"{out.stem}-{k + 1:02d}{out.suffix}")
                    fig.save(p)
                    written.append(p)
                Console().print(f"wrote {len(written)} drawings {written[0]} … {written[-1]}")
            else:
                fig = figure()
                draw_construction(fig, con)
                fig.save(out)
                Console().print(f"wrote {out}")

    @synth.command("function")
    def function_command(
        function: str = typer.Option(..., "--function", help="y = f(x), e.g. 'log10(x)', 'x**2', 'sin(x)'"),
        x: str = typer.Option(..., "--x", help="START:END: the range of x"),
        input_: str = typer.Option(..., "--input-range", help="START:END: the input crank's angles (degrees) at the ends of the range"),
        output_: str = typer.Option(..., "--output-range", help="START:END: the rocker's angles (degrees), or with --slider the slider's positions (length unit), at the ends"),
        points: int = typer.Option(3, "--points", help="number of Chebyshev-spaced precision points (three: exact; more: least squares)"),
        at: Optional[str] = typer.Option(None, "--at", help="X1,X2,…: precision points instead of Chebyshev's"),
        slider: bool = typer.Option(False, "--slider", help="a slider-crank (the output a slider on the x-axis's parallel)"),
        frame: float = typer.Option(1.0, "--frame", help="four-bar: the frame length"),
        samples: int = typer.Option(201, "--samples", help="samples of the structural error"),
        unit: str = typer.Option("mm", "--unit", help="length unit of the file"),
        name: str = typer.Option("Function generator", "--name", help="the mechanism's name"),
        out: str = typer.Option(..., "-o", "--output", help="the mechanism file to write"),
        report: Optional[str] = typer.Option(None, "--report", help="FILE.json or FILE.csv: the structural error over x"),
    ) -> None:
        """A four-bar or slider-crank whose output follows y = f(x): Freudenstein's equation."""
        with user_errors():
            output_format(None, out, ("toml",), "toml")  # a mechanism file
            from ..io import load
            from ..synthesis.function import FunctionTask, function_generator
            from ..units import check_length_unit

            check_length_unit(unit)
            if report is not None and Path(report).suffix.lower() not in (".json", ".csv"):
                raise InputError(f"--report {report}: write .json or .csv")
            kind = "slider-crank" if slider else "four-bar"
            if samples < 2:
                raise InputError(f"--samples {samples}: give at least 2")
            task = FunctionTask(_function(function), _range(x, "--x", False), _range(input_, "--input-range", True),
                                _range(output_, "--output-range", not slider))
            precision = points if at is None else [_number(v, f"--at {at}") for v in at.split(",")]
            gen = function_generator(task, precision, kind, frame=frame, name=name)
            path = Path(out)
            write_output_file(path, gen.mechanism_text(length_unit=unit))
            xs, err = gen.structural_error(samples)
            # the file as written, solved at the precision points
            load(path)
            at_points = gen.generated(gen.precision) - task.output(gen.precision)
            scale = 1.0 if not slider else max(abs(v) for v in gen.lengths.values())
            exact = len(gen.precision) == 3
            t = _summary(f"{kind} function generator", [])
            for k, v in gen.lengths.items():  # signed: a negative crank's pin is opposite its angle
                t.add_row(k + (" (signed)" if k in ("input", "output", "offset") else ""), f"{v:.9g} {unit}")
            t.add_row("precision points x", ", ".join(f"{v:.6g}" for v in gen.precision))
            t.add_row("Freudenstein K", ", ".join(f"{v:.9g}" for v in gen.K))
            conv = (lambda v: f"{v:.3g} {unit}") if slider else (lambda v: f"{math.degrees(v):.4g}°")
            worst = float(np.nanmax(np.abs(err))) if np.isfinite(err).any() else math.nan
            t.add_row("largest structural error", conv(worst) + f" (in y: {float(task.output_to_y(worst)):.3g})")
            t.add_row("error at the precision points", conv(float(np.nanmax(np.abs(at_points)))))
            unreachable = int(np.sum(~np.isfinite(err)))
            if unreachable:
                t.add_row("samples out of reach", f"{unreachable} of {samples}")
            Console().print(t)
            if report:
                if report.lower().endswith(".csv"):
                    lines = ["x,y,error,error_y"] + [
                        f"{float(a)!r},{float(task.y(a))!r},{float(e)!r},{float(task.output_to_y(e))!r}"
                        for a, e in zip(xs, err)]
                    write_output_file(report, "\n".join(lines) + "\n")
                else:
                    write_output_file(report, json.dumps({
                        "kind": kind, "lengths": gen.lengths, "K": gen.K.tolist(),
                        "precision_points": gen.precision.tolist(), "residual": gen.residual,
                        "x": xs.tolist(), "error": [None if not np.isfinite(e) else float(e) for e in err]},
                        indent=2) + "\n")
            Console().print(f"wrote {path}" + (f" and {report}" if report else ""))
            if exact and not (np.abs(at_points) <= TOLERANCE * scale).all():
                raise InputError(f"the engine does not meet the precision points with {path} "
                                 f"(off by {np.nanmax(np.abs(at_points)):.3g}): the points lie on different "
                                 "assemblies or out of reach")


def _angle_option(text: str, what: str) -> float:
    return math.radians(_number(text, what))


def _targets(unit: str, point, timing):
    """The path commands' targets (--point, at least three) and timing (--timing, degrees)."""
    from ..units import check_length_unit

    check_length_unit(unit)
    targets = np.array([_pair(p, "--point") for p in point or []])
    if len(targets) < 3:
        raise InputError(f"give at least three target points (--point X,Y), got {len(targets)}")
    tm = None if timing is None else np.radians([_number(v, f"--timing {timing}") for v in timing.split(",")])
    return targets, tm


def register_curvature_designs(synth: typer.Typer) -> None:
    @synth.command("dwell")
    def dwell_command(
        mechanism: str = typer.Argument(..., help="a four-bar: a mechanism file, or library:NAME"),
        at: str = typer.Option(..., "--at", help="DEG: the input angle of the dwell"),
        point: str = typer.Option(..., "--point", help="the coupler point: its name, or X,Y design coordinates"),
        pivot: Optional[str] = typer.Option(None, "--pivot", help="X,Y: the output rocker's fixed pivot (default: the rocker at right angles to the dwell link)"),
        output: str = typer.Option(..., "-o", "--output", help="the six-bar's mechanism file"),
    ) -> None:
        """Alt's dwell linkage: a dyad on a coupler point's centre of curvature."""
        with user_errors():
            output_format(None, output, ("toml",), "toml")  # a mechanism file
            from ..io import load
            from ..kinematics import solve
            from ..synthesis.second_order import alt_dwell

            mech = load(mechanism)
            pt = point if "," not in point else _pair(point, "--point")
            d = alt_dwell(mech, _angle_option(at, "--at"), pt,
                          pivot=None if pivot is None else _pair(pivot, "--pivot"))
            write_output_file(output, d.text)
            sol = solve(load(output), [d.input], order=3)
            out = sol.link(d.output_link)
            Console().print(_summary("Alt's dwell linkage", [
                ("centre of curvature K", _xy_text(d.centre)), ("dwell link (radius of curvature)", f"{d.radius:.9g}"),
                ("output pivot E", _xy_text(d.pivot)),
                ("output ω, α, jerk at the dwell", f"{out.omega[0]:.2e}, {out.alpha[0]:.2e}, {out.jerk[0]:.2e}")]))
            Console().print(f"wrote {output}")

    @synth.command("path")
    def path_command(
        point: Optional[list[str]] = typer.Option(None, "--point", help="X,Y: a target point of the coupler curve; repeat (at least 3), in order"),
        timing: Optional[str] = typer.Option(None, "--timing", help="DEG,DEG,…: the crank angle at each target (prescribed timing), relative to the first"),
        starts: int = typer.Option(24, "--starts", help="starting points of the search"),
        unit: str = typer.Option("mm", "--unit", help="length unit of the file"),
        name: str = typer.Option("Path generator", "--name", help="the mechanism's name"),
        output: str = typer.Option(..., "-o", "--output", help="the four-bar's mechanism file"),
    ) -> None:
        """A four-bar whose coupler point passes through target points (least squares)."""
        with user_errors():
            output_format(None, output, ("toml",), "toml")  # a mechanism file
            from ..io import load
            from ..kinematics import solve
            from ..synthesis.path import path_generator

            targets, tm = _targets(unit, point, timing)
            if starts < 1:
                raise InputError(f"--starts {starts}: give at least 1")
            gen = path_generator(targets, timing=tm, starts=starts, name=name)
            write_output_file(output, gen.linkage.mechanism_text(length_unit=unit))
            sol = solve(load(output), gen.linkage.input_angles(), order=1)
            engine = float(np.nanmax(np.hypot(*(sol.point("P").position - targets).T)))
            c = gen.linkage.check
            Console().print(_summary("path generator (four-bar)", [
                *((k, f"{v:.9g} {unit}") for k, v in gen.linkage.lengths.items()),
                ("fixed pivots A0, B0", f"{_xy_text(gen.linkage.input.centre.xy)}; {_xy_text(gen.linkage.output.centre.xy)}"),
                ("Grashof type", c.name), ("defects", ", ".join(n.split(" (")[0] for n in c.notes) or "none"),
                ("least transmission angle", f"{math.degrees(c.min_transmission):.2f}°"),
                ("largest distance from the targets (engine)", f"{engine:.3g} {unit}")]))
            Console().print(f"wrote {output}")

    @synth.command("six-bar-path")
    def six_bar_path_command(
        kind: str = typer.Option("stephenson", "--kind", help="watt (Watt I: dyad between crank and coupler) or stephenson (Stephenson III: dyad from the coupler to a frame pivot)"),
        point: Optional[list[str]] = typer.Option(None, "--point", help="X,Y: a target point of the tracer's path; repeat (at least 3), in order"),
        timing: Optional[str] = typer.Option(None, "--timing", help="DEG,DEG,…: the crank angle at each target (prescribed timing), relative to the first"),
        starts: int = typer.Option(12, "--starts", help="starting points of the search (the best-fitting random six-bars)"),
        unit: str = typer.Option("mm", "--unit", help="length unit of the file"),
        name: Optional[str] = typer.Option(None, "--name", help="the mechanism's name"),
        output: str = typer.Option(..., "-o", "--output", help="the six-bar's mechanism file"),
    ) -> None:
        """A Watt or Stephenson six-bar whose tracer P passes through target points (least squares)."""
        with user_errors():
            from ..io import load
            from ..synthesis.six_bar_path import six_bar_path_generator

            targets, tm = _targets(unit, point, timing)
            gen = six_bar_path_generator(targets, kind, timing=tm, starts=starts, name=name, length_unit=unit)
            write_output_file(output, gen.text)
            load(output)
            Console().print(_summary(f"path generator ({kind} six-bar)", [
                ("crank angles at the targets", ", ".join(f"{math.degrees(a):.6g}°" for a in gen.angles)),
                ("assemblies (four-bar, dyad)", f"{gen.assembly[0]:+d}, {gen.assembly[1]:+d}"),
                ("largest distance from the targets (engine)", f"{gen.engine_error:.3g} {unit}")]))
            Console().print(f"wrote {output}")

    @synth.command("cognates")
    def cognates_command(
        mechanism: str = typer.Argument(..., help="a four-bar: a mechanism file, or library:NAME"),
        point: str = typer.Option(..., "--point", help="the coupler point: its name, or X,Y design coordinates"),
        output: str = typer.Option(..., "-o", "--output", help="NAME.toml: the cognates go to NAME-1.toml and NAME-2.toml"),
    ) -> None:
        """The Roberts–Chebyshev cognates: two more four-bars tracing the same coupler curve."""
        with user_errors():
            output_format(None, output, ("toml",), "toml")  # a mechanism file
            from ..io import load
            from ..synthesis.cognates import cognates

            mech = load(mechanism)
            cg = cognates(mech, point if "," not in point else _pair(point, "--point"))
            paths = _paths(output, 2)
            for path, text in zip(paths, (cg.first, cg.second)):
                write_output_file(path, text)
                load(path)
            Console().print(f"third fixed pivot: {_xy_text(cg.third_pivot)}")
            Console().print("wrote " + ", ".join(str(p) for p in paths))

    @synth.command("substitute")
    def substitute_command(
        mechanism: str = typer.Argument(..., help="a four-bar: a mechanism file, or library:NAME"),
        at: str = typer.Option(..., "--at", help="DEG: the input angle at which the motion is kept"),
        pivot: str = typer.Option(..., "--pivot", help="X,Y: the new fixed pivot"),
        replace: str = typer.Option("input", "--replace", help="input (the driven crank) or output (the rocker)"),
        order: int = typer.Option(2, "--order", help="2: same pole and inflection circle; 3: the pivot moved along its ray from the pole onto the centre-point curve, the motion kept to the jerk"),
        output: str = typer.Option(..., "-o", "--output", help="the new four-bar's mechanism file"),
    ) -> None:
        """Pröll's substitution: a crank from a new pivot with the same pole and inflection circle (--order 3: and the same jerk)."""
        with user_errors():
            output_format(None, output, ("toml",), "toml")  # a mechanism file
            from ..io import load
            from ..synthesis.second_order import proell_substitution

            mech = load(mechanism)
            sub = proell_substitution(mech, _angle_option(at, "--at"), _pair(pivot, "--pivot"), replace=replace,
                                      order=order)
            write_output_file(output, sub.text)
            load(output)
            Console().print(_summary("Pröll's substitution", [
                ("pole P", _xy_text(sub.pole)), ("inflection pole W", _xy_text(sub.inflection_pole)),
                ("new fixed pivot C3", _xy_text(sub.pivot)), ("its conjugate A3 (coupler)", _xy_text(sub.moving_pivot))]))
            Console().print(f"wrote {output}")


def _straightness_rows(st, unit: str) -> list[tuple[str, str]]:
    rows = [("stroke", f"{st.stroke:.9g} {unit}"), ("deviation (half the narrowest strip)", f"{st.deviation:.3g} {unit}"),
            ("deviation per stroke", f"{st.relative:.3g}"),
            ("best line through", _xy_text(st.point)), ("best line direction", _xy_text(st.direction))]
    if st.inputs is not None:
        rows.append(("inputs measured", f"{math.degrees(st.inputs[0]):.6g}° … {math.degrees(st.inputs[1]):.6g}°"))
    return rows


def register_straight_lines(synth: typer.Typer) -> None:
    kinds = ("watt", "chebyshev", "evans", "ball-point", "hart")

    @synth.command("straight-line")
    def straight_line_command(
        kind: str = typer.Argument(..., help="watt, chebyshev, evans (from a stroke), ball-point or hart (from a four-bar, --mechanism)"),
        stroke: Optional[float] = typer.Option(None, "--stroke", help="L: the straight stroke of the tracer (watt, chebyshev, evans; ball-point: the stroke to measure)"),
        deviation: Optional[float] = typer.Option(None, "--deviation", help="L: watt, chebyshev, evans: the largest deviation allowed over the stroke (chebyshev: instead of --stroke; evans: instead of --lever)"),
        arm: Optional[float] = typer.Option(None, "--arm", help="L: watt: the arms' length"),
        coupler: Optional[float] = typer.Option(None, "--coupler", help="L: watt: the coupler's length"),
        frame: Optional[float] = typer.Option(None, "--frame", help="L: watt: the overall size, the fixed pivots' distance"),
        angle: float = typer.Option(45.0, "--angle", help="DEG: evans: the bar's swing about the horizontal"),
        fraction: float = typer.Option(0.7, "--fraction", help="evans: C = A + FRACTION·(B − A) (0–1 first form, > 1 second, < 0 third)"),
        lever: Optional[float] = typer.Option(None, "--lever", help="L: evans: E's distance from line AO (default 4·AB)"),
        mechanism: Optional[str] = typer.Option(None, "--mechanism", help="ball-point, hart: the four-bar (a file or library:NAME)"),
        at: Optional[str] = typer.Option(None, "--at", help="DEG: ball-point, hart: the input of the design position (hart: default the design input)"),
        unit: str = typer.Option("mm", "--unit", help="length unit of the file (watt, chebyshev, evans)"),
        output: str = typer.Option(..., "-o", "--output", help="the mechanism file to write"),
        report: Optional[str] = typer.Option(None, "--report", help="FILE.json: lengths and the straightness"),
    ) -> None:
        """Straight-line linkages: Watt, Chebyshev, Evans from a stroke; a Ball-point tracer or Hart's exact line from a four-bar."""
        with user_errors():
            from ..io import load
            from ..synthesis import straight_line as sl
            from ..units import check_length_unit

            if kind not in kinds:
                raise InputError(f"straight-line {kind}: choose one of {', '.join(kinds)}")
            if kind in ("ball-point", "hart"):
                if mechanism is None:
                    raise InputError(f"straight-line {kind}: give the four-bar with --mechanism")
                mech = load(mechanism)
                u = None if at is None else _angle_option(at, "--at")
                if kind == "ball-point":
                    if u is None:
                        raise InputError("straight-line ball-point: give the input with --at DEG")
                    des = sl.ball_point_linkage(mech, u, stroke=stroke)
                else:
                    des = sl.hart_straight_line(mech, u)
                length_unit = mech.length_unit
            else:
                check_length_unit(unit)
                if stroke is None and not (kind == "chebyshev" and deviation is not None):
                    raise InputError(f"straight-line {kind}: give the stroke with --stroke L")
                if kind == "watt":
                    des = sl.watt_linkage(stroke, deviation=deviation, arm=arm, coupler=coupler, frame=frame, unit=unit)
                elif kind == "chebyshev":
                    des = sl.chebyshev_linkage(stroke, deviation=deviation, unit=unit)
                else:
                    des = sl.evans_linkage(stroke, angle=math.radians(angle), fraction=fraction, lever=lever,
                                           deviation=deviation, unit=unit)
                length_unit = unit
            write_output_file(output, des.text)
            load(output)  # the engine reads the file back
            rows = [(k, f"{v:.9g}" if isinstance(v, float) else _xy_text(v)) for k, v in des.lengths.items()]
            rows.append(("tracing point", f"{des.tracer} at {_xy_text(des.points[des.tracer])}"))
            if des.straightness is not None:
                rows += _straightness_rows(des.straightness, length_unit)
            Console().print(_summary(des.kind, rows))
            if report:
                doc = {"kind": des.kind, "tracer": des.tracer, "lengths": des.lengths,
                       "straightness": None if des.straightness is None else des.straightness.as_dict()}
                write_output_file(report, json.dumps(doc, indent=2, default=float) + "\n")
            Console().print(f"wrote {output}" + (f" and {report}" if report else ""))

    @synth.command("straightness")
    def straightness_command(
        mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME (one driver)"),
        point: str = typer.Option(..., "--point", help="the point whose path is measured"),
        stroke: Optional[float] = typer.Option(None, "--stroke", help="L: measure the part of the path running this far along its tangent at --at (default: the whole path)"),
        at: Optional[str] = typer.Option(None, "--at", help="DEG: the input in the middle of the stroke (default the design input)"),
        samples: int = typer.Option(2001, "--samples", help="samples of the path"),
    ) -> None:
        """The deviation of a point's path from its best straight line (over a stroke)."""
        with user_errors():
            from ..io import load
            from ..synthesis.straight_line import path_straightness

            mech = load(mechanism)
            st = path_straightness(mech, point, at=None if at is None else _angle_option(at, "--at"),
                                   stroke=stroke, samples=samples)
            Console().print(_summary(f"straightness of {point}", _straightness_rows(st, mech.length_unit)))
