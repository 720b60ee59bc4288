"""The error types linkwork raises for user mistakes.

Every error a user can cause (bad file, unknown name, unassemblable design, wrong structure)
derives from `LinkworkError`; the command line prints its message and exits non-zero
without a traceback. Anything else escaping is a bug in linkwork.
"""

from __future__ import annotations


class LinkworkError(Exception):
    """Base class of every error caused by the user's input."""


class MechanismFileError(LinkworkError):
    """A mechanism file that cannot be read: syntax, unknown keys, bad values.

    The message names the file, the offending key and, where it can be found, its line.
    """

    def __init__(self, message: str, *, source: str | None = None, key: str | None = None,
                 line: int | None = None) -> None:
        where = []
        if source:
            where.append(str(source) + (f":{line}" if line else ""))
        if key:
            where.append(f"key '{key}'")
        super().__init__((", ".join(where) + ": " if where else "") + message)
        self.source, self.key, self.line = source, key, line


class UnknownMechanismError(LinkworkError):
    """A `library:NAME` that the library does not hold, or a path that does not exist."""


class ModelError(LinkworkError):
    """A mechanism whose description is inconsistent (a joint on a link that lacks its point,
    a degenerate link, gear radii that do not match the centre distance, ...)."""


class StructureError(LinkworkError):
    """A mechanism that is over- or under-constrained, so it cannot be solved for its inputs."""


class AssemblyError(LinkworkError):
    """A position at which the chain cannot be assembled, where the caller required it."""


class SolveError(LinkworkError):
    """A solve that cannot be carried out within its bounds (the continuation of the design's
    branch needs more steps than its budget), named with the input where it stopped."""


class InputError(LinkworkError):
    """A bad input value: an unparsable quantity, a sweep with zero step, a wrong unit."""


class LinkworkWarning(UserWarning):
    """Something the user should know about their input that does not stop the work (the
    command line prints it as one line on stderr)."""


class OutputError(LinkworkError):
    """An output that cannot be written (no such folder, a folder given as file, a full disk,
    no permission) or that would be larger than the limit without --force."""
