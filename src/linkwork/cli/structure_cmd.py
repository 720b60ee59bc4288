"""`linkwork structure`: the structural analysis of a mechanism on the command line.

This module owns only the command's face (options, the Rich tables, the JSON document); the
work is `linkwork.structure.structure_report`. An over- or under-constrained mechanism is a
finding, not an error: it is reported with exit status 0. Files that cannot be read are user
errors (exit status 2, one message).
"""

from __future__ import annotations

import json
import math
from enum import Enum
from typing import Optional

import typer
from rich.markup import escape
from rich.table import Table

from ..structure import StructureReport, structure_report
from ..structure.assur import ROMAN
from .common import load_mechanism, output_format, recording_console, user_errors, write_output


class Format(str, Enum):
    table = "table"
    json = "json"


SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def _deg(x: float) -> str:
    return f"{math.degrees(x):.3f}°"


def _input_text(rep: StructureReport, v: float) -> str:
    mech = rep.mechanism
    if len(mech.drivers) == 1 and mech.joint(mech.drivers[0].joint).kind == "prismatic":
        return f"{v:.6g} {mech.length_unit}"
    return _deg(v)


def _counts_table(rep: StructureReport) -> Table:
    c = rep.mobility.counts
    t = Table(title=f"{escape(rep.mechanism.name)}: counts as the seeds write them", show_header=False)
    t.add_column("quantity")
    t.add_column("value")
    hinge_parts = ", ".join(f"g{str(k + 1).translate(SUB)} = {gk}"
                            for k, gk in enumerate(c.hinges) if gk)
    t.add_row("links n (frame and die blocks included)", str(c.n))
    t.add_row("hinges g = g₁ + 2g₂ + 3g₃ + …", f"{c.g}" + (f"  ({hinge_parts})" if hinge_parts else ""))
    t.add_row("sliding pairs s", str(c.s))
    t.add_row("lower pairs z = g + s", str(c.z))
    t.add_row("higher pairs h = h_n + 2h_p", f"{c.h}  (h_n = {c.h_n}, h_p = {c.h_p})")
    t.add_row("closed slider groups γ", str(c.gamma))
    if c.h == 0:
        t.add_row("Grübler (Pöschl 97): 3n − 2g = 4", f"3·{c.n} − 2·{c.z} = {c.grubler}")
    t.add_row("Rosenauer (53): h + 2z − 3n + 4 − γ = 0",
              f"{c.h} + 2·{c.z} − 3·{c.n} + 4 − {c.gamma} = {c.criterion}")
    if c.hinge_chain:
        t.add_row("free term g − 3n/2 (Rosenauer 55)", str(c.free_term))
    t.add_row("count's mobility F = 3(n − 1) − 2z − h + γ", str(c.mobility))
    t.add_row("by the count", escape(c.verdict()))
    return t


def _mobility_table(rep: StructureReport) -> Table:
    m = rep.mobility
    t = Table(title="real mobility (rank of the constraint Jacobian at the design position)",
              show_header=False)
    t.add_column("quantity")
    t.add_column("value")
    t.add_row("Jacobian", f"{m.equations} equations × {3 * m.moving_links} pose coordinates, "
                          f"rank {m.rank}")
    t.add_row("real mobility", str(m.real_mobility))
    t.add_row("count's mobility", str(m.count_mobility))
    t.add_row("redundant constraints",
              ", ".join(escape(str(r)) for r in m.redundant) if m.redundant else "none")
    if m.dependent_pairs:
        t.add_row("pairs taking part", ", ".join(m.dependent_pairs))
    t.add_row("drivers", ", ".join(m.drivers) or "none")
    t.add_row("inputs still needed", str(m.inputs_needed))
    if m.surplus_drivers:
        t.add_row("drivers too many", ", ".join(m.surplus_drivers))
    if m.finite_motion is not None:
        t.add_row("finite motion from the design position",
                  "yes" if m.finite_motion else "no (infinitesimal only)")
    types = ", ".join(f"n{str(k).translate(SUB)} = {v}" for k, v in rep.link_types.items())
    t.add_row("links by elements", types)
    t.add_row("verdict", escape(m.verdict()))
    return t


def _groups_table(rep: StructureReport) -> Table:
    cls = rep.mechanism_class
    title = "Assur groups in solution order"
    if cls:
        title += f" (mechanism of class {ROMAN.get(cls, cls)})"
    t = Table(title=title)
    for col in ("#", "group", "links", "pairs", "drivers"):
        t.add_column(col)
    for i, g in enumerate(rep.groups or (), 1):
        t.add_row(str(i), escape(g.name), ", ".join(g.links), ", ".join(g.joints),
                  ", ".join(g.group.drivers))
    return t


def _loops_table(rep: StructureReport) -> Table:
    t = Table(title="Grashof classification", show_header=False)
    t.add_column("quantity")
    t.add_column("value")
    for lp in rep.loops:
        if lp.chain == "slider-crank":  # Rosenauer's numbering of the chain's links (001a §4)
            num = {"crank": 1, "rod": 2, "block": 3, "guide": 4}
            t.add_row("chain links", ", ".join(f"{num[k]} {k} = {v}" for k, v in lp.links.items()))
        else:
            t.add_row("loop", ", ".join(f"{k} = {v}" for k, v in lp.links.items()))
        t.add_row("type", escape(lp.name))
        if lp.lengths:
            t.add_row("lengths", ", ".join(f"{k} {v:.6g}" for k, v in lp.lengths.items()))
        if lp.input_turns_fully is not None:
            t.add_row("input turns fully", "yes" if lp.input_turns_fully else "no")
        if lp.transmission is not None:
            t.add_row("transmission angle", f"{_deg(lp.transmission[0])} … {_deg(lp.transmission[1])}"
                                            f" (worst {_deg(lp.min_transmission)})")
        if lp.input_limits is not None:
            t.add_row("input limits (closed form)",
                      " … ".join(_input_text(rep, v) for v in lp.input_limits))
        dp = lp.dead_positions
        if dp:
            t.add_row("dead positions at input", ", ".join(_input_text(rep, v) for v in dp["input"]))
            if "output_swing" in dp:
                t.add_row("output swing", _deg(dp["output_swing"]))
            if "stroke" in dp:
                t.add_row("stroke", f"{dp['stroke']:.6g} {rep.mechanism.length_unit}")
            t.add_row("dead-position angle δ, time ratio",
                      f"{_deg(dp['dead_position_angle'])}, {dp['time_ratio']:.6g}")
        for note in lp.notes:
            t.add_row("note", escape(note))
    return t


def _construction_table(mech) -> Table:
    """Rosenauer 1937 paper 2: can the velocity plan be drawn directly (no similar point rows)?"""
    from ..topology.constructibility import Chain, plan_velocities, wittenbauer_rule

    chain = Chain.from_mechanism(mech)
    script = plan_velocities(chain)
    t = Table(title="velocity plan by ruler (Wittenbauer's and Rosenauer's rules)", show_header=False)
    t.add_column("quantity")
    t.add_column("value")
    t.add_row("Wittenbauer's rule", escape(wittenbauer_rule(chain).text()))
    t.add_row("Rosenauer's rule", escape(script.verdict()))
    if script.order:
        t.add_row("links in the order they become known", ", ".join(script.order))
    return t


def _construction_doc(mech) -> dict:
    from ..topology.constructibility import Chain, plan_velocities, wittenbauer_rule

    chain = Chain.from_mechanism(mech)
    return {"wittenbauer": wittenbauer_rule(chain).as_dict(),
            "rosenauer": plan_velocities(chain).as_dict()}


def _text(rep: StructureReport) -> str:
    con = recording_console(150)
    con.print(_counts_table(rep))
    con.print(_mobility_table(rep))
    if rep.groups is not None:
        con.print(_groups_table(rep))
    else:
        con.print(f"No solution order: {escape(rep.structure_error or '')}")
    if rep.groups is not None:
        con.print(_construction_table(rep.mechanism))
    if rep.loops:
        con.print(_loops_table(rep))
    if rep.input_limits is not None:
        con.print("Input limits of the whole mechanism (numerical): "
                  + " … ".join(_input_text(rep, v) for v in rep.input_limits))
    elif rep.input_limits_note:
        con.print(f"Input limits: {escape(rep.input_limits_note)}")
    return con.export_text()


def _structure_command(mechanism: str, fmt: Format | None, output: Optional[str]) -> None:
    with user_errors():
        fmt = Format(output_format(fmt and fmt.value, output, ("table", "json"), "table"))
        mech = load_mechanism(mechanism)
        rep = structure_report(mech)
        if fmt is Format.json:
            doc = rep.as_dict()
            if rep.groups is not None:
                doc["velocity_construction"] = _construction_doc(mech)
            write_output(json.dumps(doc, indent=1, ensure_ascii=False) + "\n", output)
        else:
            write_output(_text(rep), output)


def register(app: typer.Typer) -> None:
    """Add `structure` to the `linkwork` application."""

    @app.command("structure")
    def structure_cmd(
        mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
        fmt: Optional[Format] = typer.Option(None, "--format", help="table or json (default: from the suffix of -o, else table)"),
        output: Optional[str] = typer.Option(None, "-o", "--output", help="write to this file instead of stdout"),
    ) -> None:
        """Structure: mobility by the seeds' counts and by the Jacobian's rank, redundant
        constraints, Assur groups and solution order, Grashof type and inversion name."""
        _structure_command(mechanism, fmt, output)
