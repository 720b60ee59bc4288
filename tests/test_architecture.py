"""The layers of docs/ARCHITECTURE.md: every module imports only from its own layer and the layers
below it (read from the source with `ast`, lazy imports inside functions included)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "linkwork"

# lowest first; a layer may import any layer at or below its own rank
RANK = {"errors": 0, "units": 0, "geometry": 0, "model": 1, "io": 2, "topology": 2,
        "kinematics": 3, "structure": 4, "instant": 4, "forces": 4, "constructions": 5, "synthesis": 5,
        "sweeps": 5, "drawing": 6, "web": 7, "cli": 8}


def _layer(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[0] == "linkwork" else None


def _imports(path: Path) -> list[tuple[int, str]]:
    rel = path.relative_to(SRC.parent).with_suffix("")
    package = list(rel.parts[:-1]) if rel.name != "__init__" else list(rel.parts[:-1])
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
                names = [mod] if node.module else [f"{mod}.{a.name}" for a in node.names]
            else:
                names = [node.module or ""]
            out.extend((node.lineno, n) for n in names)
        elif isinstance(node, ast.Import):
            out.extend((node.lineno, a.name) for a in node.names)
    return out


FILES = sorted(p for p in SRC.rglob("*.py") if p.parent != SRC)


@pytest.mark.parametrize("path", FILES, ids=lambda p: str(p.relative_to(SRC)))
def test_imports_point_down(path: Path) -> None:
    own = path.relative_to(SRC).parts[0]
    if own not in RANK:
        pytest.fail(f"{own}/ is not a layer of docs/ARCHITECTURE.md (add it there and here)")
    for line, mod in _imports(path):
        target = _layer(mod)
        if target is None or target not in RANK:
            continue
        assert RANK[target] <= RANK[own], (
            f"{path.relative_to(SRC)}:{line} imports {mod}: {own}/ may not import from "
            f"{target}/ (it sits above it)")
