"""Array plumbing shared by the geometry value objects.

Owns: read-only float arrays, shape validation, batch-shape agreement, exact power-of-two
normalisation of homogeneous coordinates, and the :class:`Batch` mixin (``shape``, ``len``,
indexing) that every value object inherits.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from .errors import GeometryError


def frozen(value: Any) -> np.ndarray:
    """A private, read-only float copy of ``value``."""
    a = np.array(value, dtype=float)
    a.flags.writeable = False
    return a


def core_array(value: Any, size: int, what: str, *, allow_inf: bool = False) -> np.ndarray:
    """``value`` as a float array of shape ``(..., size)``; rejects ±inf unless allowed."""
    a = np.array(value, dtype=float)
    if a.ndim == 0 or a.shape[-1] != size:
        raise GeometryError(f"{what} must have shape (..., {size}), got {a.shape}")
    if not allow_inf and np.isinf(a).any():
        raise GeometryError(f"{what} must not contain ±inf")
    return a


def batch_shape(*shapes: tuple[int, ...], what: str) -> tuple[int, ...]:
    """The common batch shape (scalar items broadcast against a batch of N)."""
    try:
        return np.broadcast_shapes(*shapes)
    except ValueError:
        raise GeometryError(f"{what}: batch shapes {list(shapes)} do not agree") from None


def where_(mask: np.ndarray) -> str:
    """Human-readable location of the offending items, for error messages."""
    return "" if np.ndim(mask) == 0 else f" at batch index {np.argwhere(mask).squeeze(-1).tolist()}"


def pow2_normalise(v: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """Divide ``v`` (..., k) by the power of two just above ``ref`` (...): exact in floating point.

    Homogeneous coordinates are defined up to scale; rescaling by a power of two keeps integer
    and dyadic inputs exact while preventing overflow/underflow in later cross products.
    """
    _, e = np.frexp(np.where(np.isfinite(ref), ref, 0.0))
    return np.ldexp(v, -e[..., None])


def norm(v: np.ndarray) -> np.ndarray:
    return np.linalg.norm(v, axis=-1)


def cross2(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """z-component of the cross product of 2-vectors (twice the signed triangle area)."""
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def dot(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return np.sum(u * v, axis=-1)


def rot90(v: np.ndarray) -> np.ndarray:
    """Counter-clockwise quarter turn of (..., 2) vectors."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


class Batch:
    """Mixin: one item (``shape == ()``) or a batch (``shape == (N,)``), sample axis first.

    Subclasses are frozen dataclasses whose array fields carry the batch axes in front of their
    core axes, so indexing every field with the same index selects the same items.
    """

    @property
    def shape(self) -> tuple[int, ...]:
        raise NotImplementedError

    @property
    def single(self) -> bool:
        return self.shape == ()

    def __len__(self) -> int:
        if self.single:
            raise TypeError(f"a single {type(self).__name__} has no len()")
        return self.shape[0]

    def __getitem__(self, index: Any) -> Any:
        if self.single:
            raise TypeError(f"a single {type(self).__name__} is not subscriptable")
        return type(self)(**{f.name: getattr(self, f.name)[index] for f in dataclasses.fields(self)})
