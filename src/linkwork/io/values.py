"""Numbers in mechanism files: finite, of sane size, and really numbers.

TOML knows `nan`, `inf`, booleans and integers of any size; pydantic's lax float takes the
string "10" and `true` as numbers. A mechanism file's numbers are coordinates, radii, speeds and
times: each must be an integer or a float (not a bool, not a string), finite, and at most
`units.MAX_MAGNITUDE` in size, so that no NaN or overflow reaches the solver.
"""

from __future__ import annotations

import math
from typing import Annotated, Any

from pydantic import BeforeValidator, Field

from ..units import MAX_MAGNITUDE


def _number(value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        shown = f"'{value}'" if isinstance(value, str) else repr(value)
        raise ValueError(f"expected a number, got {shown}"
                         + (" (write it without quotes)" if isinstance(value, str) else ""))
    if isinstance(value, int):
        if abs(value) > MAX_MAGNITUDE:
            digits = int(abs(value).bit_length() * math.log10(2)) + 1  # str() refuses > 4300 digits
            raise ValueError(f"an integer of about {digits} digits is larger than "
                             f"{MAX_MAGNITUDE:g} in size")
        return float(value)
    if not math.isfinite(value):
        raise ValueError(f"expected a finite number, got {value}")
    if abs(value) > MAX_MAGNITUDE:
        raise ValueError(f"{value:g} is larger than {MAX_MAGNITUDE:g} in size")
    return value


def _positive(value: Any) -> float:
    v = _number(value)
    if not v > 0:
        raise ValueError(f"expected a positive number, got {value!r}")
    return v


#: a finite number (int or float, not bool or string) of at most MAX_MAGNITUDE in size
Number = Annotated[float, BeforeValidator(_number)]
#: the same, greater than zero
PositiveNumber = Annotated[float, Field(gt=0), BeforeValidator(_positive)]
