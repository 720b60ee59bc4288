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


def mechanism_file(*, name: str, description: str, length_unit: str, points: dict, links: dict,
                   joints: dict, driver: str, speed: str) -> str:
    """A mechanism file of revolute and prismatic pairs: `points` name → (x, y), `links` name →
    point names, `joints` name → (type, (link, link), extra TOML key = value text or "")."""
    lines = [f"name = {toml_string(name)}", f"description = {toml_string(description)}",
             f'units = {{ length = "{length_unit}" }}', "", "[points]"]
    lines += [f"{k} = {point(v)}" for k, v in points.items()]
    lines += ["", "[links]"]
    lines += [f"{k} = [{', '.join(toml_string(p) for p in v)}]" for k, v in links.items()]
    lines += ["", "[joints]"]
    for k, (kind, (a, b), extra) in joints.items():
        tail = f", {extra}" if extra else ""
        lines.append(f'{k} = {{ type = "{kind}", links = [{toml_string(a)}, {toml_string(b)}]{tail} }}')
    lines += ["", "[driver]", f"joint = {toml_string(driver)}", f"speed = {toml_string(speed)}", ""]
    return "\n".join(lines)
