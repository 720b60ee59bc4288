"""`linkwork draw` and `linkwork plot`: drawings (SVG, PNG, PDF) and diagrams over the motion.

Owns the two commands. ``draw`` solves the mechanism at one input (``--at``), draws the chosen
layers (``--show``), optionally one of the classical constructions (``--construction``; checked
against the exact values before anything is written) and, with ``--steps``, one drawing per step
(FILE-01.svg, FILE-02.svg, …) or, with ``--animate``, one SVG in which the steps appear one after
another. ``plot`` draws positions, velocities or accelerations of points and links over the whole
motion, a v–s diagram (``--vs``, with ``--construction subnormal|time`` drawn step by step with
``--steps``), Pöschl's motion diagrams (``--diagrams``) or the plans of a point (``--plans``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from ..errors import InputError
from ..units import MAX_MAGNITUDE
from .common import load_mechanism, positive_option, user_errors

#: the finest PNG resolution drawn (an A4 page at 2400 dpi is already 20 000 pixels wide)
MAX_DPI = 2400.0


def _list(text: Optional[str]) -> list[str]:
    return [t.strip() for t in text.split(",") if t.strip()] if text else []


def _close(fig) -> None:
    import matplotlib.pyplot as plt
    plt.close(fig)


def register(app: typer.Typer) -> None:
    @app.command()
    def draw(
        mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
        at: Optional[list[str]] = typer.Option(None, "--at", help="input value: degrees (revolute) or the file's length unit (prismatic) unless a unit is written, or a time (0.5s); several drivers: NAME=V per driver (--at O2=30 --at O5=10); default: the design position"),
        show: str = typer.Option("mechanism", "--show", help="layers, comma-separated: mechanism, paths, velocities, accelerations, poles, pole-lines, centrodes, inflection, return, bresse, gamma; forces (pair reactions and the driver's effort at scale, from the file's [masses]/[loads]); higher pairs: contact (contact point, common normal), equivalent (equivalent linkage, dashed)"),
        construction: Optional[str] = typer.Option(None, "--construction", help="rotated-velocities, velocity-plan, acceleration-plan, euler-savary, bobillier, hartmann, two-points, klein, kennedy, mohr"),
        point: Optional[str] = typer.Option(None, "--point", help="the point whose centre of curvature a curvature construction seeks"),
        link: Optional[str] = typer.Option(None, "--link", help="the link of a curvature construction (default: the coupler)"),
        steps: bool = typer.Option(False, "--steps", help="one drawing per construction step (FILE-01.svg, …)"),
        animate: Optional[float] = typer.Option(None, "--animate", help="one SVG whose steps appear one after another, SECONDS apart"),
        length_scale: Optional[float] = typer.Option(None, "--length-scale", help="mechanism units per mm of paper"),
        velocity_scale: Optional[float] = typer.Option(None, "--velocity-scale", help="velocity units per mm of paper"),
        acceleration_scale: Optional[float] = typer.Option(None, "--acceleration-scale", help="acceleration units per mm of paper"),
        frame: str = typer.Option("mechanism", "--frame", help="mechanism: the mechanism stays the subject, larger layers are cut at a frame around it (arrows to centres off the sheet); inset: cut at the frame too, and drawn whole in an inset at their own scale; all: everything drawn fits the sheet"),
        dpi: float = typer.Option(200.0, "--dpi", help="resolution of PNG output"),
        output: str = typer.Option(..., "-o", "--output", help="FILE.svg, FILE.png, FILE.pdf or FILE.dxf (mechanism and paths layers, in the file's length unit, for CAD)"),
    ) -> None:
        """Draw the mechanism at one position with layers and a construction, as the books do."""
        import numpy as np

        from ..constructions import construct
        from ..drawing import scene_figure
        from ..drawing.force_layers import draw_forces
        from ..io import load_dynamics
        from ..drawing.layers import Scene
        from ..kinematics import solve, solve_at
        from ..kinematics.at import require_assembled
        from .inputs import input_values

        with user_errors():
            positive_option(dpi, "--dpi", MAX_DPI)
            for value, option in ((length_scale, "--length-scale"), (velocity_scale, "--velocity-scale"),
                                  (acceleration_scale, "--acceleration-scale"), (animate, "--animate")):
                positive_option(value, option, MAX_MAGNITUDE)
            mech = load_mechanism(mechanism)
            out = Path(output)
            if out.suffix.lower() not in (".svg", ".png", ".pdf", ".dxf"):
                raise InputError(f"-o {output}: write .svg, .png, .pdf or .dxf")
            if animate is not None and out.suffix.lower() != ".svg":
                raise InputError("--animate writes an animated SVG: give -o FILE.svg")
            if mech.given:  # a chain driven by given point velocities: at its drawn position
                sol = solve_at(mech, at, asked="--at")
            elif at is None:
                value = np.array([mech.driver_input_at_design(d) for d in mech.drivers])[None, :]
                sol = solve(mech, value)
            else:
                kind, v = input_values(mech, at, None)
                if len(v) != 1:
                    raise InputError(f"--at {','.join(at)}: draw takes one position, got {len(v)}")
                sol = solve(mech, times=v) if kind == "time" else solve(mech, v)
            require_assembled(sol, 0, "the design position" if at is None else None)
            sc = Scene(mech, sol)
            if any(x is not None for x in (length_scale, velocity_scale, acceleration_scale)):
                sc.scales = sc.auto_scales(length=length_scale, velocity=velocity_scale,
                                           acceleration=acceleration_scale,
                                           plan_mm=70.0 if construction in ("velocity-plan", "acceleration-plan") else None)
            layers = _list(show)
            # the force layer needs the file's mass data: drawn here, after the kinematic layers
            forces = load_dynamics(mechanism) if "forces" in layers else None
            layers = [x for x in layers if x != "forces"]
            con = None
            if construction:
                opts = {}
                if point and construction in ("euler-savary", "bobillier", "hartmann"):
                    opts["point"] = point
                if link and construction in ("euler-savary", "bobillier", "hartmann", "two-points"):
                    opts["link"] = link
                if construction == "rotated-velocities" and sc.scales is not None and velocity_scale:
                    opts["scales"] = sc.scales
                con = construct(construction, mech, sol, **opts)
                con.require(0)
                con.check()
                typer.echo(con.describe())
            elif steps or animate:
                raise InputError("--steps and --animate need a --construction")
            if con is not None and steps:
                written = []
                for k in range(len(con.steps)):
                    fig = scene_figure(sc, layers, construction=con, step=k, frame=frame)
                    if forces is not None:
                        draw_forces(fig, sc, forces)
                    p = out.with_name(f"{out.stem}-{k + 1:02d}{out.suffix}")
                    fig.save(p, dpi=dpi)
                    written.append(p)
                typer.echo(f"wrote {len(written)} drawings {written[0]} … {written[-1]}")
                return
            if out.suffix.lower() == ".dxf":  # CAD: the mechanism's coordinates, no paper scale
                if con is not None:
                    raise InputError("a construction is drawn to SVG, PNG or PDF, not DXF")
                from ..drawing.dxf import write_dxf
                write_dxf(sc, out, layers)
                typer.echo(f"wrote {out}")
                return
            fig = scene_figure(sc, layers, construction=con, frame=frame)
            if forces is not None:
                draw_forces(fig, sc, forces)
            fig.save(out, dpi=dpi, animate=animate)
            typer.echo(f"wrote {out}")

    @app.command()
    def plot(
        mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
        point: Optional[str] = typer.Option(None, "--point", help="points, comma-separated"),
        link: Optional[str] = typer.Option(None, "--link", help="links, comma-separated"),
        quantity: str = typer.Option("velocity", "--quantity", help="position, velocity or acceleration"),
        against: str = typer.Option("input", "--against", help="input (angle or displacement) or time"),
        component: str = typer.Option("x,y,magnitude", "--component", help="x, y, magnitude (points)"),
        vs: bool = typer.Option(False, "--vs", help="the v–s diagram of the (first) point instead"),
        diagrams: bool = typer.Option(False, "--diagrams", help="Pöschl's s–t, v–t, a–t and jerk lines of the (first) point, with the graphical differentiation by chords"),
        plans: bool = typer.Option(False, "--plans", help="the r-, v- and b-plan (hodographs) of the (first) point with poles, scales and tangents (Pöschl §13)"),
        construction: Optional[str] = typer.Option(None, "--construction", help="with --vs: subnormal (the acceleration from the v–s line) or time (t = ∫ds/v by strips); with --diagrams: differentiation (the s–t line, the default of --steps) or integration (the a–t line by mean ordinates)"),
        steps: bool = typer.Option(False, "--steps", help="with --diagrams or --vs --construction: one drawing per step (FILE-01.png, …)"),
        at: Optional[float] = typer.Option(None, "--at", help="--plans: the input (degrees, or the file's length unit); --construction subnormal: the position as a fraction 0…1 of the stroke"),
        output: str = typer.Option(..., "-o", "--output", help="FILE.png, FILE.pdf or FILE.svg"),
    ) -> None:
        """Plot positions, velocities, accelerations over the whole motion, or a v–s diagram."""
        from ..drawing.plots import graphical_motion, motion_plot, save, vs_plot

        with user_errors():
            mech = load_mechanism(mechanism)
            points, links = _list(point), _list(link)
            chosen = [o for o, on in (("--vs", vs), ("--diagrams", diagrams), ("--plans", plans)) if on]
            if len(chosen) > 1:
                raise InputError(f"choose one of {', '.join(chosen)}")
            if chosen and not points:
                raise InputError(f"{chosen[0]} needs --point")
            if construction and not (vs or diagrams):
                raise InputError("--construction draws on the v–s diagram (--vs) or on the motion "
                                 "diagrams (--diagrams: differentiation or integration)")
            if steps and not (construction or diagrams):
                raise InputError("--steps draws --diagrams (the graphical differentiation or "
                                 "integration) or a --vs --construction step by step")
            if diagrams and (steps or construction):
                from ..drawing import calculus_plots
                which = construction or "differentiation"
                if which not in ("differentiation", "integration"):
                    raise InputError(f"--diagrams --construction is differentiation or integration, "
                                     f"not '{which}'")
                build = getattr(calculus_plots, f"{which}_steps")
                figs, texts, _ = build(mech, points[0])
            elif construction:
                from ..drawing.calculus_plots import vs_steps
                figs, texts, _ = vs_steps(mech, points[0], construction, at=at)
            if construction or (diagrams and steps):
                out = Path(output)
                if not steps:  # the finished construction only
                    for f in figs[:-1]:
                        _close(f)
                    figs, texts = figs[-1:], texts[-1:]
                written = []
                for k, (f, text) in enumerate(zip(figs, texts)):
                    p = out if not steps else out.with_name(f"{out.stem}-{k + 1:02d}{out.suffix}")
                    save(f, p)
                    written.append(p)
                    typer.echo(f"{k + 1}. {text}" if steps else text)
                typer.echo(f"wrote {written[0]}" + (f" … {written[-1]}" if len(written) > 1 else ""))
                return
            if plans:
                import numpy as np

                from ..drawing.calculus_plots import plans_figure
                u = None
                if at is not None:
                    kind = mech.joint(mech.drivers[0].joint).kind
                    u = np.radians(at) if kind == "revolute" else at
                fig, check = plans_figure(mech, points[0], at=u)
                typer.echo(f"tangent of the v-plan against the acceleration: {check.tangent_v_vs_acceleration_deg:.3g}°; "
                           f"of the b-plan against the jerk: {check.tangent_b_vs_jerk_deg:.3g}°")
            elif vs:
                fig = vs_plot(mech, points[0])
            elif diagrams:
                fig = graphical_motion(mech, points[0])
            else:
                fig = motion_plot(mech, points=points, links=links, quantity=quantity, against=against,
                                  components=_list(component))
            save(fig, output)
            typer.echo(f"wrote {output}")
