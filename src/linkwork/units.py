"""Quantities with units: parsing of the strings users write ("60 rpm", "1.2rad", "5 mm").

One pint registry for the whole package. Internally linkwork works in the file's length unit,
radians and seconds; this module converts at the boundary and nowhere else.
"""

from __future__ import annotations

from functools import lru_cache

import pint

from .errors import InputError


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:
    return pint.UnitRegistry()


def parse_quantity(text: str | float | int, *, default_unit: str, kind: str) -> float:
    """Value of `text` expressed in `default_unit`.

    A bare number is taken in `default_unit`; a number with a unit is converted. `kind` names
    what the value is for, so that the error message can say it ("speed", "input angle").
    """
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return float(text)
    ureg = registry()
    try:
        q = ureg.Quantity(str(text).strip())
    except Exception as exc:  # pint raises several unrelated types for garbage
        raise InputError(f"cannot read {kind} '{text}': {exc}") from None
    if isinstance(q, (int, float)):
        return float(q)
    if q.dimensionless and str(q.units) == "dimensionless":
        return float(q.magnitude)
    try:
        return float(q.to(default_unit).magnitude)
    except pint.DimensionalityError:
        raise InputError(
            f"{kind} '{text}' has unit '{q.units}', which cannot be converted to '{default_unit}'"
        ) from None


def unit_dimension(text: str) -> str | None:
    """'time', 'angle', 'length' or None for a quantity string without a unit."""
    ureg = registry()
    try:
        q = ureg.Quantity(str(text).strip())
    except Exception:
        raise InputError(f"cannot read quantity '{text}'") from None
    if not hasattr(q, "units") or str(q.units) == "dimensionless":
        return None
    for dim, unit in (("time", "s"), ("angle", "rad"), ("length", "m")):
        if q.check(ureg.Unit(unit).dimensionality):
            return dim
    return "other"


def check_length_unit(unit: str) -> str:
    """Validate a length unit name ('mm', 'm', 'in'); return it unchanged."""
    ureg = registry()
    try:
        u = ureg.Unit(unit)
    except Exception:
        raise InputError(f"unknown length unit '{unit}'") from None
    if u.dimensionality != ureg.Unit("m").dimensionality:
        raise InputError(f"'{unit}' is not a unit of length")
    return unit
