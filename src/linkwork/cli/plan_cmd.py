"""`linkwork plan`: the velocity plan of a mechanism drawn by ruler, as Rosenauer writes it
(module level: the standard library, Typer and `cli.common` only, so registering it is cheap).

The command's face only: the constructibility test and the script are
`linkwork.topology.constructibility`, the construction at a position is
`linkwork.constructions.velocity_plan` (or `rotated_velocities`), checked against the engine.
"""

from __future__ import annotations

import json
from enum import Enum
from typing import Optional

import typer

from .common import load_mechanism, output_format, user_errors, write_output


class Mode(str, Enum):
    plan = "plan"
    rotated = "rotated"


class Format(str, Enum):
    text = "text"
    json = "json"


def _plan_command(mechanism: str, at: Optional[list[str]], explain: bool, mode: Mode,
                  fmt: Format | None, output: Optional[str]) -> None:
    # imported here: registering the command must stay cheap (tests/cli/test_startup.py)
    import numpy as np

    from ..constructions import rotated_velocities, velocity_plan
    from ..errors import InputError
    from ..topology.constructibility import Chain, plan_velocities, wittenbauer_rule
    from .inputs import input_values

    with user_errors():
        fmt = Format(output_format(fmt and fmt.value, output, ("text", "json"), "text"))
        mech = load_mechanism(mechanism)
        chain = Chain.from_mechanism(mech)
        script = plan_velocities(chain)
        witt = wittenbauer_rule(chain)
        doc: dict = {"mechanism": mech.name, "wittenbauer": witt.as_dict(),
                     "rosenauer": script.as_dict()}
        lines = [f"{mech.name}: velocity plan by ruler",
                 f"Wittenbauer's rule: {witt.text()}",
                 f"Rosenauer's rule: {script.verdict()}"]
        if explain or at is None:
            lines.append("Construction script (o: the pole of the plan; x \u27c2 XY: the line "
                         "through x perpendicular to XY):")
            lines.extend(script.script())
        if mech.given:  # no input: the construction at the drawn position, from the given data
            from ..kinematics import solve_at
            values = solve_at(mech, at, asked="--at")  # too few or too many conditions: reported here
            if script.direct or script.by_two_trials:
                at = []  # by the rule, or by similar point rows (two trials; `draw_given`)
            else:
                lines.append("The plan of this chain from its given data is not drawn: "
                             f"{script.verdict()}.")
        elif at is not None:
            samples = input_values(mech, at, None)
            if samples is None or samples[0] != "input":
                raise InputError("--at takes input values (degrees or the file's length unit)")
            values = np.asarray(samples[1], float)
            values = values[:, 0] if values.ndim == 2 else values
            values = values[:1]
        if at is not None:
            build = velocity_plan if mode is Mode.plan else rotated_velocities
            con = build(mech, values)
            con.require(0)  # a position where the construction degenerates is reported as such
            con.check()
            lines.append("")
            lines.append(con.describe())
            lines.append(f"largest relative error against the engine: {con.max_error():.2e}")
            doc["construction"] = {"steps": [s.text for s in con.steps],
                                   "max_relative_error": con.max_error(),
                                   "notes": con.messages()}
        if fmt is Format.json:
            write_output(json.dumps(doc, indent=1, ensure_ascii=False) + "\n", output)
        else:
            write_output("\n".join(lines) + "\n", output)


def register(app: typer.Typer) -> None:
    """Add `plan` to the `linkwork` application."""

    @app.command("plan")
    def plan_cmd(
        mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
        at: Optional[list[str]] = typer.Option(None, "--at", help="input value V (degrees or the file's length unit): carry the construction out there and check it against the engine (a chain driven by [[given]] point velocities: always, at its drawn position)"),
        explain: bool = typer.Option(False, "--explain", help="print the numbered construction script (q = (a \u27c2 AQ) \u2229 (b \u27c2 BQ) …)"),
        mode: Mode = typer.Option(Mode.plan, "--mode", help="plan: polar velocity plan; rotated: rotated velocities on the mechanism"),
        fmt: Optional[Format] = typer.Option(None, "--format", help="text or json (default: from the suffix of -o, else text)"),
        output: Optional[str] = typer.Option(None, "-o", "--output", help="write to this file instead of stdout"),
    ) -> None:
        """Velocity plan by ruler: Wittenbauer's and Rosenauer's constructibility rules, the
        auxiliary points Q, R, … and the numbered construction script (Rosenauer 1937)."""
        _plan_command(mechanism, at, explain, mode, fmt, output)
