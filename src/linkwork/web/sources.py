"""Where the workbench's mechanisms come from: the library, a file inside the working folder the
user named, or TOML text sent with the request, optionally with design points moved.

Nothing outside the library and the working folder is ever read: a file name is resolved (links
followed) and refused unless it lies inside the working folder, and the profile CSV files a
mechanism names are read from its own folder only (`io.profiles` keeps them there)."""

from __future__ import annotations

import os
import re

from collections import OrderedDict
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from threading import Lock

import numpy as np

from ..errors import InputError, UnknownMechanismError
from ..io import load_text, resolve
from ..kinematics.kept import Kept
from ..io.library import LIBRARY_PREFIX, library_names
from ..model import Mechanism
from ..units import MAX_MAGNITUDE

#: the size of a mechanism file the workbench reads or accepts (the library's are a few kB)
MAX_TEXT = 200_000


@dataclass(frozen=True)
class Loaded:
    """A mechanism with the text it was read from and the label its messages name; a moved
    mechanism (a frame of a drag) also with the mechanism loaded from the same source before
    it (`previous`), whose march its solves may carry over (`solve(..., previous=)`)."""

    mechanism: Mechanism
    text: str
    label: str
    previous: Mechanism | None = None


def library_folder() -> Path:
    return Path(str(resources.files("linkwork") / "library"))


def working_file(workdir: Path | None, name: str) -> Path:
    """The file `name` (relative) of the working folder, refused if it leads outside it."""
    if workdir is None:
        raise InputError("the workbench has no working folder (start it with `linkwork serve "
                         "--workdir DIR` to open files)")
    root = workdir.resolve()
    if not name or Path(name).is_absolute() or "\x00" in name:
        raise InputError(f"file '{name}': give a path relative to the working folder")
    path = (root / name).resolve()
    if not path.is_relative_to(root):
        raise InputError(f"file '{name}' lies outside the working folder")
    if path.suffix.lower() != ".toml":
        raise InputError(f"file '{name}': the workbench opens mechanism files (.toml)")
    if not path.is_file():
        raise UnknownMechanismError(f"the working folder has no file '{name}'")
    return path


#: folders the list of the working folder's files does not enter (tools' and packages' trees)
_NOT_ENTERED = {"node_modules", "__pycache__", "site-packages", "venv", "build", "dist"}
#: how deep the list goes below the working folder, and how many files it lists at most
_DEPTH, _LISTED = 4, 1000
#: a mechanism file states its points (`[points]`, or `points = {…}`) at its top level
_MECHANISM = re.compile(rb"(?m)^[ \t]*(\[points\]|points[ \t]*=)")


def working_files(workdir: Path | None) -> list[str]:
    """The mechanism files (.toml that state points) of the working folder and its subfolders
    to `_DEPTH` levels, relative; hidden folders and tools' trees are not entered, and the walk
    stops at `_LISTED` files, so that a large folder (a home folder) is listed quickly."""
    if workdir is None:
        return []
    root = workdir.resolve()
    out: list[str] = []
    for folder, subfolders, files in os.walk(root):
        here = Path(folder)
        depth = len(here.relative_to(root).parts)
        subfolders[:] = sorted(d for d in subfolders if not d.startswith(".") and
                               d not in _NOT_ENTERED and depth < _DEPTH)
        for name in sorted(files):
            if not name.lower().endswith(".toml"):
                continue
            path = here / name
            try:
                if not path.resolve().is_relative_to(root) or not path.is_file():
                    continue
                with path.open("rb") as f:
                    head = f.read(65536)
            except OSError:
                continue
            if _MECHANISM.search(head):
                out.append(path.relative_to(root).as_posix())
                if len(out) >= _LISTED:
                    return sorted(out)
    return sorted(out)


def moved(mech: Mechanism, points: dict[str, tuple[float, float]]) -> Mechanism:
    """`mech` with the design coordinates of `points` replaced: links, pairs and drivers are the
    same, and everything the design position defines (lengths, angles, branches) follows."""
    new = dict(mech.points)
    for name, xy in points.items():
        if name not in mech.points:
            raise InputError(f"mechanism '{mech.name}' has no point '{name}' (its points are "
                             f"{', '.join(mech.points)})")
        xy = np.asarray(xy, float)
        if xy.shape != (2,) or not np.all(np.isfinite(xy)) or np.any(np.abs(xy) > MAX_MAGNITUDE):
            raise InputError(f"point '{name}': give two finite coordinates of at most 1e12")
        new[name] = xy
    return Mechanism.build(name=mech.name, points=new,
                           links={ln.name: list(ln.points) for ln in mech.links},
                           joints=list(mech.joints), drivers=list(mech.drivers), frame=mech.frame,
                           length_unit=mech.length_unit, description=mech.description,
                           profiles=mech.profiles, given=mech.given)


class Sources:
    """Loads mechanisms for requests and keeps the last few (a mechanism is immutable, so one
    object serves every request that names the same source)."""

    SIZE = 64

    def __init__(self, workdir: Path | None) -> None:
        self.workdir = None if workdir is None else Path(workdir).resolve()
        self._cache = Kept(self.SIZE)  # key -> Loaded
        # per source (without moved points): the mechanism last built from it, the previous
        # frame of the next one moved
        self._last = Kept(self.SIZE)

    def _read(self, library: str | None, file: str | None, text: str | None,
              name: str | None, body: str | None = None) -> Loaded:
        """`body`: the file's text, read already."""
        if library is not None:
            label, body = resolve(LIBRARY_PREFIX + library)
            return Loaded(load_text(body, source=label, base_dir=library_folder()), body, label)
        if file is not None:
            path = working_file(self.workdir, file)
            if body is None:
                body = resolve(path)[1]
            return Loaded(load_text(body, source=file, base_dir=path.parent), body, file)
        assert text is not None
        if len(text) > MAX_TEXT:
            raise InputError(f"the mechanism text has {len(text)} characters; at most {MAX_TEXT}")
        label = name or "<text>"
        # a text's profile files are looked up in the working folder (or the library), never
        # in the server's current folder
        base = self.workdir or library_folder()
        return Loaded(load_text(text, source=label, base_dir=base), text, label)

    def load(self, *, library: str | None = None, file: str | None = None,
             text: str | None = None, name: str | None = None,
             points: dict[str, tuple[float, float]] | None = None) -> Loaded:
        key = (library, file, text, name,
               tuple(sorted((k, tuple(map(float, v))) for k, v in (points or {}).items())))
        # a file may change on disk between requests: read it again every time, and take what
        # is kept for it only while its text is the same (and it names no profile files, which
        # may change on their own): the kept whole motions are per mechanism object
        body = None if file is None else resolve(working_file(self.workdir, file))[1]
        hit = self._cache.get(key)
        if hit is not None and (file is None or hit.text == body and not hit.mechanism.profiles):
            self._cache.put(key, hit)  # (the last used)
            return hit
        if points:  # the file as read (kept for the next frame of a drag), then moved
            previous = self._last.get(key[:4])
            base = self.load(library=library, file=file, text=text, name=name)
            out = Loaded(moved(base.mechanism, points), base.text, base.label,
                         previous or base.mechanism)
        else:
            out = self._read(library, file, text, name, body)
        self._cache.put(key, out)
        self._last.put(key[:4], out.mechanism)
        return out

    @staticmethod
    def library() -> list[str]:
        return library_names()


class Motions:
    """The last few whole motions per mechanism, and what else is solved over one (the samples
    solved by their inputs, the scene's paths): a mechanism is immutable and compared by
    identity, so what is computed for it once serves every later request that names it (the
    frames of a play, each at one sample of the whole motion, with its paths drawn).

    `kept(mech, what, make)`: the value kept under (mech, what), made by `make()` the first
    time; two threads asking for the same one at once make it once (the second waits)."""

    SIZE = 8  # mechanisms: the one played, the one before, a few drag results

    def __init__(self) -> None:
        self._kept: OrderedDict[Mechanism, dict] = OrderedDict()
        self._lock = Lock()
        self._making: dict[tuple, Lock] = {}

    def has(self, mech: Mechanism, what) -> bool:
        with self._lock:
            return what in self._kept.get(mech, ())

    def kept(self, mech: Mechanism, what, make):
        with self._lock:
            per = self._kept.get(mech)
            if per is not None and what in per:
                self._kept.move_to_end(mech)
                return per[what]
            making = self._making.setdefault((mech, what), Lock())
        with making:
            with self._lock:
                per = self._kept.get(mech)
                if per is not None and what in per:
                    return per[what]
            try:
                value = make()
                with self._lock:
                    self._kept.setdefault(mech, {})[what] = value
                    self._kept.move_to_end(mech)
                    while len(self._kept) > self.SIZE:
                        self._kept.popitem(last=False)
            finally:
                with self._lock:
                    self._making.pop((mech, what), None)
        return value


#: the server's whole motions (`Motions`), shared by its requests
MOTIONS = Motions()
