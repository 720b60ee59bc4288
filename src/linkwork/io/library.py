"""The shipped library of mechanisms (`library:NAME`): names and file texts.

Standard library only, so that listing the library costs no NumPy, pydantic or solver
(`linkwork library`); `files.load` builds a mechanism from the text.
"""

from __future__ import annotations

import re
import tomllib
from importlib import resources

from ..errors import UnknownMechanismError

LIBRARY_PREFIX = "library:"


def library_names() -> list[str]:
    """The names of the shipped mechanisms (load one as `library:NAME`), sorted."""
    root = resources.files("linkwork") / "library"
    return sorted(p.name[:-5] for p in root.iterdir() if p.name.endswith(".toml"))


def _read(name: str) -> str:
    return (resources.files("linkwork") / "library" / f"{name}.toml").read_text(encoding="utf-8")


def library_text(name: str) -> str:
    """The TOML text of the shipped mechanism `name`; `UnknownMechanismError` with the close
    names for a name the library does not have."""
    names = library_names()
    if name not in names:
        close = [n for n in names if name.lower() in n or n in name.lower()]
        hint = f"; did you mean {', '.join(close)}?" if close else "; `linkwork library` lists them"
        raise UnknownMechanismError(f"the library has no mechanism '{name}'{hint}")
    return _read(name)


#: the library's groups, in the order `linkwork library` shows them
CATEGORIES = ("four-bars", "slider mechanisms", "six-bars and multi-loop linkages",
              "straight-line linkages", "valve gears", "governors", "cams", "gears",
              "intermittent", "over-closed chains", "several drivers", "free and open chains", "other")


def _category(doc: dict) -> str:
    """A file's `category`, or, for a file without one, the group its pairs put it in: a valve
    gear by its name, then cams, gears (toothed or rolling) and intermittent pairs by their type."""
    if doc.get("category"):
        return doc["category"]
    if "valve gear" in doc.get("name", "").lower():
        return "valve gears"
    kinds = {j.get("type") for j in doc.get("joints", {}).values() if isinstance(j, dict)}
    for kind, group in (("geneva", "intermittent"), ("star-wheel", "intermittent"), ("cam", "cams"),
                        ("gear", "gears"), ("rolling", "gears")):
        if kind in kinds:
            return group
    return "other"


def _header(text: str) -> dict:
    """The top-level keys of a mechanism file (name, category, description: all the listing
    needs), read from the text before its first table, which `linkwork library` then parses
    alone (the whole library parsed was most of the command's time); the whole file where
    that part does not parse by itself or has no category (`_category` looks at the pairs)."""
    head = re.split(r"(?m)^\[", text, maxsplit=1)[0]
    try:
        doc = tomllib.loads(head)
    except tomllib.TOMLDecodeError:
        doc = {}
    return doc if doc.get("category") else tomllib.loads(text)


def library_entries() -> list[dict[str, str]]:
    """Every shipped mechanism as {name, title, category, description}, grouped in the order
    of `CATEGORIES` (unknown groups after them, alphabetically), by name within a group."""
    out = []
    for n in library_names():  # (names just listed: read without listing the folder again)
        doc = _header(_read(n))
        out.append({"name": n, "title": doc.get("name", ""), "category": _category(doc),
                    "description": doc.get("description", "")})
    rank = {c: i for i, c in enumerate(CATEGORIES)}
    return sorted(out, key=lambda e: (rank.get(e["category"], len(rank)), e["category"], e["name"]))


def search_library(text: str | None = None, category: str | None = None) -> list[dict[str, str]]:
    """The library entries whose name, title or description contain every word of `text`
    (case-insensitive, umlauts folded: 'proell' and 'proll' find Pröll) and whose category starts with
    `category`."""
    def fold(s: str) -> str:
        s = s.lower()
        for a, b in (("ä", "a"), ("ö", "o"), ("ü", "u"), ("ß", "ss"), ("–", "-"), ("ae", "a"), ("oe", "o"),
                     ("ue", "u")):
            s = s.replace(a, b)
        return s

    words = fold(text or "").split()
    hits = []
    for e in library_entries():
        hay = fold(" ".join((e["name"], e["title"], e["description"])))
        if all(w in hay for w in words) and (not category or fold(e["category"]).startswith(fold(category))):
            hits.append(e)
    return hits
