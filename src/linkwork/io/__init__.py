"""Reading and writing: mechanism files (TOML), the shipped library, solution exports.

The names below load on first use (PEP 562): `io.library` alone needs no NumPy or pydantic."""

from __future__ import annotations

import importlib

_MODULES = {"dump_schema": ".files", "load": ".files", "load_text": ".files", "resolve": ".files",
            "dynamics_from_text": ".dynamics", "load_dynamics": ".dynamics"}
__all__ = sorted(_MODULES)


def __getattr__(name: str):
    if name in _MODULES:
        return getattr(importlib.import_module(_MODULES[name], __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
