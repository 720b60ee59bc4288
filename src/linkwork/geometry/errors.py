"""The single exception type of :mod:`linkwork.geometry`."""


class GeometryError(ValueError):
    """An invalid or undetermined geometric construction (bad shapes, degenerate input).

    Subclasses :class:`ValueError` so callers that only know the standard library can catch it.
    """
