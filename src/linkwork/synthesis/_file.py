"""How the synthesis modules write numbers, points and strings into mechanism files."""

from __future__ import annotations


def number(x: float) -> str:
    """A number as the file writes it: 15 significant digits (so 120° comes back as 120)."""
    v = float(f"{float(x):.15g}")
    return repr(int(v)) if v.is_integer() and abs(v) < 1e15 else repr(v)


def point(p) -> str:
    """[x, y], a coordinate below 1e-12 of the other written as 0 (rounding of cos 90°)."""
    x, y = (float(v) for v in p)
    scale = max(abs(x), abs(y))
    x, y = (0.0 if abs(v) <= 1e-12 * scale else v for v in (x, y))
    return f"[{number(x)}, {number(y)}]"


def toml_string(s: str) -> str:
    return '"' + str(s).replace("\\", "\\\\").replace('"', '\\"') + '"'
