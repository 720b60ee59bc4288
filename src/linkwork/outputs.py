"""Writing output files safely: all or nothing.

Every file linkwork writes (tables, CSV, JSON, drawings, plots) is first written to a temporary
file beside the target and renamed over it only when complete. A full disk, a Ctrl-C or an
error half-way leaves the previous file as it was and no partial file behind. Every `OSError`
becomes one `OutputError` naming the path and the reason. Targets that are not regular files
(`/dev/stdout`, `/dev/full`, a FIFO) cannot be renamed over and are written in place.
"""

from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Iterable, Iterator

from .errors import OutputError


def _why(exc: OSError) -> str:
    return exc.strerror or str(exc) or type(exc).__name__


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextmanager
def output_path(path: str | Path) -> Iterator[Path]:
    """A path to write `path`'s content to (a temporary file beside it, with the same suffix):
    renamed over `path` when the block ends normally, removed when it raises (an error, a
    Ctrl-C). An `OSError` in the block or in the rename becomes an `OutputError`."""
    target = Path(path)
    if target.is_dir():
        raise OutputError(f"cannot write '{path}': it is a directory (give a file name)")
    if target.exists() and not target.is_file():
        try:
            yield target
        except OSError as exc:
            raise OutputError(f"cannot write '{path}': {_why(exc)}") from None
        return
    folder = target.parent
    if not folder.is_dir():
        raise OutputError(f"cannot write '{path}': there is no directory '{folder}'")
    try:
        fd, name = tempfile.mkstemp(dir=folder, prefix=f".{target.name}.", suffix=f".part{target.suffix}")
        os.close(fd)
    except OSError as exc:
        raise OutputError(f"cannot write '{path}': {_why(exc)}") from None
    tmp = Path(name)
    try:
        yield tmp
        mode = target.stat().st_mode & 0o7777 if target.exists() else 0o666 & ~_umask()
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except OSError as exc:
        raise OutputError(f"cannot write '{path}': {_why(exc)}") from None
    finally:
        tmp.unlink(missing_ok=True)


@contextmanager
def output_file(path: str | Path, mode: str = "w") -> Iterator[IO]:
    """An open file (text in UTF-8, or binary with mode 'wb') whose content replaces `path` when
    the block ends normally (see `output_path`)."""
    with output_path(path) as p:
        with open(p, mode, **({} if "b" in mode else {"encoding": "utf-8", "newline": ""})) as fh:
            yield fh


def write_output_file(path: str | Path, chunks: str | bytes | Iterable[str] | Iterable[bytes]) -> None:
    """Write text or bytes, whole or as an iterable of chunks (streamed: one chunk in memory at a
    time), to `path`, all or nothing."""
    if isinstance(chunks, (str, bytes)):
        chunks = (chunks,)
    it = iter(chunks)
    first = next(it, "")
    with output_file(path, "wb" if isinstance(first, bytes) else "w") as fh:
        fh.write(first)
        for chunk in it:
            fh.write(chunk)
