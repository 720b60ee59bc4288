"""Helpers shared by every command module: loading a mechanism, writing an output, and
turning user mistakes into one clear message with a non-zero exit status.

Light on purpose (standard library, Typer and Rich): every command module imports it when the
command line starts (see `cli.main`); reading input values, which needs NumPy, is `cli.inputs`."""

from __future__ import annotations

import math
import os
import sys
import warnings
from contextlib import contextmanager
from typing import TYPE_CHECKING, Iterable, Iterator

import typer
from rich.console import Console
from rich.text import Text

from ..errors import InputError, LinkworkError, LinkworkWarning
from ..outputs import write_output_file

if TYPE_CHECKING:
    from ..model import Mechanism

err_console = Console(stderr=True)


def recording_console(width: int, *, markup: bool = True) -> Console:
    """A console that only records (for `export_text`): tables laid out at `width` columns,
    written nowhere."""
    import io

    return Console(record=True, width=width, file=io.StringIO(), markup=markup)


def print_message(kind: str, message: str) -> None:
    """One line on stderr, `error: …` or `warning: …`: the message printed as it is (a TOML
    section such as `[links]` in it is text, not Rich markup)."""
    style = "bold red" if kind == "error" else "bold yellow"
    err_console.print(Text.assemble((f"{kind}:", style), " ", message), highlight=False,
                      soft_wrap=True)


@contextmanager
def user_errors() -> Iterator[None]:
    """Print a `LinkworkError` as one line on stderr and exit with status 2; print each
    `LinkworkWarning` as one line on stderr and go on."""

    def show(message, category, filename, lineno, file=None, line=None) -> None:
        if issubclass(category, LinkworkWarning):
            print_message("warning", str(message))
        else:
            shown(message, category, filename, lineno, file, line)

    with warnings.catch_warnings():
        shown = warnings.showwarning
        warnings.showwarning = show
        try:
            yield
        except LinkworkError as exc:
            print_message("error", str(exc))
            raise typer.Exit(2) from None


def positive_option(value: float | None, option: str, largest: float | None = None) -> None:
    """Refuse a numeric option that is not a finite positive number (at most `largest`)."""
    if value is None:
        return
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"{option} {value:g}: give a finite number greater than 0")
    if largest is not None and value > largest:
        raise InputError(f"{option} {value:g}: at most {largest:g}")


def load_mechanism(spec: str) -> Mechanism:
    """The mechanism of a file path or `library:NAME` (validated; errors name key and line)."""
    from ..io import load

    return load(spec)


#: suffixes of the formats linkwork writes (a command given one that it does not write refuses
#: it, rather than put its text in a file whose name promises another format)
KNOWN_SUFFIXES = {".csv": "csv", ".json": "json", ".jsonl": "jsonl", ".parquet": "parquet",
                  ".pq": "parquet", ".toml": "toml", ".svg": "svg", ".png": "png", ".pdf": "pdf",
                  ".dxf": "dxf", ".gif": "gif", ".html": "html", ".mp4": "mp4"}


def output_format(fmt: str | None, output: str | None, writes: Iterable[str],
                  default: str) -> str:
    """The format of a command's output from its --format (None: not given) and the suffix of
    -o: the suffix chooses when --format is not given; a suffix contradicting --format is
    refused, and so is the suffix of a format that the command does not write (`writes`: the
    formats it writes, by the names of `KNOWN_SUFFIXES`). Other suffixes (.txt, none) get
    --format or `default`."""
    from pathlib import Path

    writes = tuple(writes)
    suffix = Path(output).suffix.lower() if output else ""
    by_suffix = KNOWN_SUFFIXES.get(suffix)
    if by_suffix is not None and by_suffix not in writes:
        known = [s for s, f in KNOWN_SUFFIXES.items() if f in writes and s != ".pq"]
        text = "" if default in KNOWN_SUFFIXES.values() else f" or {default} text (any other suffix)"
        raise InputError(f"-o {output}: this command writes {', '.join(known)}{text}, not {suffix}")
    if fmt is None:
        return by_suffix or default
    if by_suffix is not None and by_suffix != fmt:
        raise InputError(f"-o {output} has the suffix of {by_suffix}, but --format is {fmt}: "
                         "drop --format or change the suffix")
    return fmt


def write_output(text: str | Iterable[str], output: str | None) -> None:
    """Text, whole or as chunks (streamed), to the file `output` (all or nothing: see
    `linkwork.outputs`) or to stdout."""
    if output:
        write_output_file(output, text)
        return
    try:
        for chunk in ((text,) if isinstance(text, str) else text):
            sys.stdout.write(chunk)
        sys.stdout.flush()
    except BrokenPipeError:  # `linkwork analyze … | head`: the reader has what it wanted
        sys.stdout = open(os.devnull, "w")
