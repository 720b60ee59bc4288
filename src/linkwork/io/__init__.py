"""Reading and writing: mechanism files (TOML), the shipped library, solution exports.

The names below load on first use (PEP 562): `io.library` alone needs no NumPy or pydantic."""

from __future__ import annotations

import importlib

__all__ = ["dump_schema", "load", "load_text", "resolve"]


def __getattr__(name: str):
    if name in __all__:
        return getattr(importlib.import_module(".files", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
