"""The `linkwork` command line (Typer + Rich).

`app` is the whole application (every layer's commands registered); `run` is the installed
`linkwork` command: for one of the core commands (analyze, library, schema) it skips loading
the other layers' command modules, so that a small job answers at once."""

from __future__ import annotations

import sys
from functools import lru_cache

__all__ = ["app", "run"]


@lru_cache(maxsize=1)
def _full_app():
    from .main import app, register_layers

    register_layers(app)
    return app


def __getattr__(name: str):
    if name == "app":
        return _full_app()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def run() -> None:
    """Entry point of the `linkwork` command."""
    from .main import CORE_COMMANDS, app

    words = [a for a in sys.argv[1:] if not a.startswith("-")]
    if words and words[0] in CORE_COMMANDS and "--help" not in sys.argv[1:2]:
        app()
    else:
        _full_app()()
