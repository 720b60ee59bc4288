"""The shipped library of mechanisms (`library:NAME`): names and file texts.

Standard library only, so that listing the library costs no NumPy, pydantic or solver
(`linkwork library`); `files.load` builds a mechanism from the text.
"""

from __future__ import annotations

from importlib import resources

from ..errors import UnknownMechanismError

LIBRARY_PREFIX = "library:"


def library_names() -> list[str]:
    """The names of the shipped mechanisms (load one as `library:NAME`), sorted."""
    root = resources.files("linkwork") / "library"
    return sorted(p.name[:-5] for p in root.iterdir() if p.name.endswith(".toml"))


def library_text(name: str) -> str:
    """The TOML text of the shipped mechanism `name`; `UnknownMechanismError` with the close
    names for a name the library does not have."""
    names = library_names()
    if name not in names:
        close = [n for n in names if name.lower() in n or n in name.lower()]
        hint = f"; did you mean {', '.join(close)}?" if close else "; `linkwork library` lists them"
        raise UnknownMechanismError(f"the library has no mechanism '{name}'{hint}")
    return (resources.files("linkwork") / "library" / f"{name}.toml").read_text(encoding="utf-8")
