"""The ``linkwork atlas`` command: list the planar one-degree-of-freedom hinge chains.

This module owns only the command line face of :mod:`linkwork.topology.atlas`
(option parsing, the Rich table, the JSON document and the SVG switch); all
structural work is done by the library functions.
"""

from __future__ import annotations

import json
from enum import Enum
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console
from rich.table import Table

from .common import user_errors
from linkwork.topology.atlas import SUPPORTED_LINK_COUNTS, TYPE_NAMES, Chain, enumerate_chains, write_atlas_svg


class AtlasFormat(str, Enum):
    table = "table"
    json = "json"


def _check_links(value: int) -> int:
    if value not in SUPPORTED_LINK_COUNTS:
        hint = " A one-degree-of-freedom hinge chain has an even number of links." if value % 2 else ""
        raise typer.BadParameter(
            f"{value} is not an atlas size; use one of {', '.join(map(str, SUPPORTED_LINK_COUNTS))}.{hint}"
        )
    return value


def _mix_text(mix: tuple[int, ...]) -> str:
    return "/".join(str(c) for c in mix)


def _document(n_links: int, chains: list[Chain]) -> dict:
    by_mix: dict[str, int] = {}
    for chain in chains:
        by_mix[_mix_text(chain.mix)] = by_mix.get(_mix_text(chain.mix), 0) + 1
    return {
        "n_links": n_links,
        "count": len(chains),
        "mix_order": [TYPE_NAMES.get(t, f"{t}-hinge") for t in range(2, n_links // 2 + 1)],
        "by_mix": by_mix,
        "chains": [chain.to_dict() for chain in chains],
    }


def _json(doc: dict) -> str:
    """The document indented, each chain on one line: json's indenting encoder is pure
    Python (two seconds for the 6 856 chains of 12 links), its compact one is C."""
    chains = doc["chains"]
    head = json.dumps({**doc, "chains": []}, indent=2)
    assert head.endswith("[]\n}")
    body = ",\n".join("    " + json.dumps(c) for c in chains)
    return head[: -len("[]\n}")] + ("[\n" + body + "\n  ]\n}" if chains else "[]\n}")


def _table(n_links: int, chains: list[Chain]) -> Table:
    header = "/".join(f"n{t}" for t in range(2, n_links // 2 + 1))
    first = chains[0]
    table = Table(
        title=f"Planar 1-DOF hinge chains with {n_links} links: {len(chains)}",
        caption=(
            f"each chain: {first.n_hinges} hinges, {first.loops} independent "
            f"loop{'s' if first.loops != 1 else ''}, "
            f"{first.poles} poles, {first.pole_lines} pole lines"
        ),
    )
    named = any(chain.name for chain in chains)  # names exist for 4 and 6 links only
    table.add_column("chain", justify="right")
    table.add_column(f"mix {header}")
    if named:
        table.add_column("name")
    table.add_column("inversions", justify="right")
    table.add_column("input choices", justify="right")
    table.add_column("hinges")
    for chain in chains:
        name = [chain.name or ""] if named else []
        table.add_row(
            chain.label,
            _mix_text(chain.mix),
            *name,
            str(chain.n_inversions),
            str(chain.n_input_choices),
            " ".join(f"{a}-{b}" for a, b in chain.edges),
        )
    return table


#: above this many chains the table is printed as plain columns: Rich lays a table out cell
#: by cell, three seconds for the 6 856 chains of 12 links
PLAIN_ABOVE = 100


def _plain(n_links: int, chains: list[Chain]) -> str:
    """The table of `_table` as plain aligned columns (the caption as its last line)."""
    from .main import _columns

    header = "/".join(f"n{t}" for t in range(2, n_links // 2 + 1))
    first = chains[0]
    rows = [[chain.label, _mix_text(chain.mix), str(chain.n_inversions), str(chain.n_input_choices),
             " ".join(f"{a}-{b}" for a, b in chain.edges)] for chain in chains]
    head = ["chain", f"mix {header}", "inversions", "input choices", "hinges"]
    caption = (f"each chain: {first.n_hinges} hinges, {first.loops} independent loops, "
               f"{first.poles} poles, {first.pole_lines} pole lines")
    return _columns(f"Planar 1-DOF hinge chains with {n_links} links: {len(chains)}", head,
                    rows) + "\n" + caption


def atlas(
    links: int = typer.Option(
        ...,
        "--links",
        "-n",
        callback=_check_links,
        help="Number of links: 4, 6, 8, 10 or 12.",
    ),
    svg: Optional[Path] = typer.Option(
        None, "--svg", help="Write one SVG sketch per chain into this directory.", file_okay=False
    ),
    fmt: AtlasFormat = typer.Option(AtlasFormat.table, "--format", "-f", help="Output format."),
) -> None:
    """List the planar one-degree-of-freedom chains of simple hinges without rigid sub-chains."""
    err = Console(stderr=True)
    # Rich draws the bar on stderr, so JSON on stdout stays clean.
    chains = enumerate_chains(links, progress=links >= 10)
    if fmt is AtlasFormat.json:
        typer.echo(_json(_document(links, chains)))
    elif len(chains) > PLAIN_ABOVE:
        typer.echo(_plain(links, chains))
    else:
        Console().print(_table(links, chains))
    if svg is not None:
        with user_errors():  # an OutputError naming the file or directory, one line
            written = write_atlas_svg(chains, svg, progress=True)
        err.print(f"wrote {len(written)} SVG files to {svg}", highlight=False)


def register(app: typer.Typer) -> None:
    """Add the ``atlas`` command to the ``linkwork`` application."""
    app.command("atlas")(atlas)
