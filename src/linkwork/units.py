"""Quantities with units: parsing of the strings users write ("60 rpm", "1.2rad", "5 mm/s^2").

One pint registry for the whole package. Internally linkwork works in the file's length unit,
radians and seconds; this module converts at the boundary and nowhere else.

A quantity is read by a small grammar of its own, never by handing the text to pint's
expression evaluator (which computes `9**9**9` as an integer of 370 million digits):

    quantity := sign? product
    product  := power (("*" | "/" | juxtaposition) power)*
    power    := atom (("^" | "**") exponent)?
    exponent := sign? integer, at most MAX_EXPONENT in size
    atom     := number | unit name | "(" product ")"

Numbers are decimal (`12`, `1.5`, `2e-3`); unit names are looked up in pint's registry one by
one, and pint does the unit arithmetic and the conversion. Every number read and the final
value must be finite and at most MAX_MAGNITUDE in size.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from typing import TYPE_CHECKING

from .errors import InputError

if TYPE_CHECKING:
    import pint

#: the largest size of any number linkwork accepts from a user (file or command line): larger
#: ones are typing mistakes, and squares of them would overflow the solver's arithmetic
MAX_MAGNITUDE = 1e12
#: the largest exponent in a quantity (`mm/s^2`, `rad*s^-3`)
MAX_EXPONENT = 4
#: the longest quantity text read (a quantity is a few words)
MAX_LENGTH = 200


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:
    """pint's registry, made on first use (a bare number needs none). Its parsed definitions
    are cached in the user's cache folder, which makes it ten times faster to build; where
    that folder cannot be written, it is built from the definitions."""
    import sys

    if "pint" not in sys.modules and "dask" not in sys.modules:
        # pint imports dask whenever it is installed (it is, for the sweeps), which doubles
        # pint's import time; linkwork hands pint no dask arrays, so its dask support is left
        # out (a None entry makes dask look absent; dask itself imports normally afterwards)
        sys.modules["dask"] = None
        try:
            import pint
        finally:
            del sys.modules["dask"]
    import pint

    try:
        return pint.UnitRegistry(cache_folder=":auto:")
    except OSError:
        return pint.UnitRegistry()


#: a bare decimal number: read without the unit machinery
_PLAIN_NUMBER = re.compile(r"\s*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\s*")


def _plain_number(text: str) -> bool:
    return len(text) <= MAX_LENGTH and _PLAIN_NUMBER.fullmatch(text) is not None


_TOKEN = re.compile(r"\s*(?:(?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)"
                    r"|(?P<name>[^\W\d][\w°]*|°)"
                    r"|(?P<op>\*\*|[*/^()+\-]))")


def _tokens(text: str, what: str) -> list[tuple[str, str]]:
    out, pos = [], 0
    text = text.rstrip()
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            raise InputError(f"{what}: unexpected '{text[pos:].strip()[:20]}' (write a number and "
                             "a unit, e.g. '60 rpm', '2 rad/s', '5 mm/s^2')")
        kind = m.lastgroup
        out.append((kind, m.group(kind)))
        pos = m.end()
    return out


def _finite(value: float, what: str, text: str) -> float:
    if not math.isfinite(value) or abs(value) > MAX_MAGNITUDE:
        raise InputError(f"{what}: '{text}' is not a finite number of at most {MAX_MAGNITUDE:g} "
                         "in size")
    return value


class _Reader:
    """Recursive descent over the tokens: magnitude (a float) and unit (a pint Unit)."""

    def __init__(self, text: str, what: str) -> None:
        self.text, self.what = text, what
        self.tokens = _tokens(text, what)
        self.i = 0
        self.ureg = registry()

    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> tuple[str, str]:
        tok = self.peek()
        if tok is None:
            raise InputError(f"{self.what}: '{self.text}' ends too early")
        self.i += 1
        return tok

    def fail(self, why: str):
        raise InputError(f"{self.what}: cannot read '{self.text}': {why}")

    def quantity(self) -> tuple[float, pint.Unit]:
        if not self.tokens:
            raise InputError(f"{self.what}: empty quantity")
        sign = 1.0
        while self.peek() in (("op", "-"), ("op", "+")):
            sign *= -1.0 if self.take()[1] == "-" else 1.0
        mag, unit = self.product()
        if self.peek() is not None:
            self.fail(f"unexpected '{self.peek()[1]}'")
        return sign * mag, unit

    def product(self) -> tuple[float, pint.Unit]:
        mag, unit = self.power()
        while True:
            tok = self.peek()
            if tok in (("op", "*"), ("op", "/")):
                self.take()
                m, u = self.power()
                if tok[1] == "*":
                    mag, unit = mag * m, unit * u
                else:
                    if m == 0:
                        self.fail("division by zero")
                    mag, unit = mag / m, unit / u
            elif tok is not None and (tok[0] in ("number", "name") or tok == ("op", "(")):
                m, u = self.power()  # juxtaposition: "60 rpm", "2 rad s^-1"
                mag, unit = mag * m, unit * u
            else:
                return _finite(mag, self.what, self.text), unit

    def power(self) -> tuple[float, pint.Unit]:
        mag, unit = self.atom()
        if self.peek() in (("op", "^"), ("op", "**")):
            self.take()
            sign = 1
            while self.peek() in (("op", "-"), ("op", "+")):
                sign *= -1 if self.take()[1] == "-" else 1
            kind, value = self.take()
            if kind != "number" or not value.isdigit():
                self.fail("an exponent is a whole number")
            if len(value) > 3 or int(value) > MAX_EXPONENT:
                self.fail(f"exponents go up to {MAX_EXPONENT}")
            if self.peek() in (("op", "^"), ("op", "**")):
                self.fail("write one exponent per factor")
            n = sign * int(value)
            if mag == 0 and n < 0:
                self.fail("division by zero")
            mag, unit = mag ** n, unit ** n
        return _finite(mag, self.what, self.text), unit

    def atom(self) -> tuple[float, pint.Unit]:
        kind, value = self.take()
        if kind == "number":
            return _finite(float(value), self.what, value), self.ureg.Unit("")
        if kind == "name":
            if value.lower() in ("nan", "inf", "infinity"):
                self.fail("not a finite number")
            try:
                if value not in self.ureg:
                    raise KeyError(value)
                return 1.0, self.ureg.Unit(value)
            except Exception:
                self.fail(f"unknown unit '{value}'")
        if value == "(":
            inner = self.product()
            if self.take() != ("op", ")"):
                self.fail("a '(' is not closed")
            return inner
        self.fail(f"unexpected '{value}'")


def read_quantity(text: str, what: str = "quantity") -> pint.Quantity:
    """The quantity `text` by the grammar of the module's docstring; `InputError` naming `what`
    for anything else."""
    text = str(text).strip()
    if len(text) > MAX_LENGTH:
        raise InputError(f"{what}: a quantity of {len(text)} characters is too long to be one")
    mag, unit = _Reader(text, what).quantity()
    return registry().Quantity(mag, unit)


def check_number(value, what: str) -> float:
    """`value` as a float if it is a finite number (not a bool) of at most MAX_MAGNITUDE in
    size; `InputError` naming `what` otherwise."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{what}: expected a number, got {value!r}")
    if isinstance(value, int) and abs(value) > MAX_MAGNITUDE:
        raise InputError(f"{what}: {value} is larger than {MAX_MAGNITUDE:g} in size")
    return _finite(float(value), what, repr(value))


#: (unit, wanted unit) -> factor: "number unit" in these is converted without pint (whose
#: import costs more than a command's whole solve), by pint's own factor, so to the same bits
#: (tests/io/test_unit_fast_paths.py holds them to pint)
QUICK_FACTORS = {
    ("rpm", "rad/s"): 2 * math.pi / 60, ("deg/s", "rad/s"): math.pi / 180,
    ("rad/s", "rad/s"): 1.0, ("rpm", "deg/s"): 6.0,
    ("deg", "rad"): math.pi / 180, ("rad", "rad"): 1.0, ("rad", "deg"): 180 / math.pi,
    ("deg", "deg"): 1.0, ("s", "s"): 1.0, ("ms", "s"): 1e-3, ("min", "s"): 60.0,
    ("mm", "mm"): 1.0, ("m", "m"): 1.0, ("mm", "m"): 1e-3, ("cm", "m"): 1e-2, ("in", "m"): 0.0254,
    ("m", "mm"): 1000.0, ("cm", "mm"): 10.0,
    ("mm/s", "mm/s"): 1.0, ("m/s", "m/s"): 1.0, ("in/s", "in/s"): 1.0,
}
_QUICK = re.compile(r"\s*(?P<number>[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*"
                    r"(?P<unit>[a-z]+(?:/s)?)\s*")


def parse_quantity(text: str | float | int, *, default_unit: str, kind: str) -> float:
    """Value of `text` expressed in `default_unit`.

    A bare number is taken in `default_unit`; a number with a unit is converted. `kind` names
    what the value is for, so that the error message can say it ("speed", "input angle").
    """
    if not isinstance(text, str):
        return check_number(text, kind)
    if _plain_number(text):
        return _finite(float(text), kind, text.strip())
    quick = _QUICK.fullmatch(text) if len(text) <= MAX_LENGTH else None
    if quick is not None and (quick["unit"], default_unit) in QUICK_FACTORS:
        value = _finite(float(quick["number"]), kind, text.strip())
        return _finite(value * QUICK_FACTORS[quick["unit"], default_unit], kind, text.strip())
    q = read_quantity(text, kind)
    if str(q.units) == "dimensionless":
        return float(q.magnitude)
    from pint.errors import PintError

    try:
        value = float(q.to(default_unit).magnitude)
    except PintError:  # other dimensions, offset units (degC) in a product
        raise InputError(
            f"{kind} '{text}' has unit '{q.units}', which cannot be converted to '{default_unit}'"
        ) from None
    return _finite(value, kind, text)


def unit_dimension(text: str, what: str = "quantity") -> str | None:
    """'time', 'angle', 'length' or None for a quantity string without a unit."""
    if _plain_number(text):
        return None
    ureg = registry()
    q = read_quantity(text, what)
    if str(q.units) == "dimensionless":
        return None
    for dim, unit in (("time", "s"), ("angle", "rad"), ("length", "m")):
        if q.check(ureg.Unit(unit).dimensionality):
            return dim
    return "other"


#: length units written without asking pint (whose import and registry cost a few tenths of a
#: second, more than a command's whole solve): the names mechanism files use. Any other name
#: is looked up in pint's registry (tests/test_units.py checks these against it)
COMMON_LENGTH_UNITS = frozenset({
    "mm", "cm", "dm", "m", "km", "um", "µm", "nm", "in", "inch", "ft", "foot", "yd",
    "millimeter", "millimetre", "centimeter", "centimetre", "meter", "metre"})


def check_length_unit(unit: str) -> str:
    """Validate a length unit name ('mm', 'm', 'in'); return it unchanged."""
    if unit in COMMON_LENGTH_UNITS:
        return unit
    ureg = registry()
    try:
        if not re.fullmatch(r"[^\W\d]\w*", unit) or unit not in ureg:
            raise KeyError(unit)
        u = ureg.Unit(unit)
    except Exception:
        raise InputError(f"unknown length unit '{unit}'") from None
    if u.dimensionality != ureg.Unit("m").dimensionality:
        raise InputError(f"'{unit}' is not a unit of length")
    return unit


def Q_(value, unit: str | None = None) -> pint.Quantity:
    """A quantity of linkwork's registry: `Q_([0, 30], "deg")`, `Q_(2, "rad/s")`."""
    return registry().Quantity(value, unit)


def is_quantity(value) -> bool:
    """Whether `value` is a pint quantity (of any registry), checked without importing pint
    for plain numbers and arrays."""
    return type(value).__module__.startswith("pint") and hasattr(value, "to")


def column_magnitudes(value, units: list[str], what: str, names: list[str]):
    """`value` as plain numbers with one column per entry of `units`, where `value` may carry
    units: a pint quantity (array of shape (N,) or (N, columns); one column for one unit), or
    a sequence of one quantity per column. Plain numbers are returned unchanged (they are taken
    in `units` already). A quantity that cannot be converted to a column's unit is an
    `InputError` naming `what` and that column's `names` entry."""
    import numpy as np

    def convert(q, unit: str, name: str):
        from pint.errors import PintError

        try:
            return np.asarray(q.to(unit).magnitude, dtype=float)
        except PintError:
            raise InputError(f"{what} for {name}: '{q.units}' cannot be converted to '{unit}'"
                             ) from None

    if is_quantity(value):
        mag = np.asarray(value.magnitude, dtype=float)
        if len(units) == 1:
            return convert(value, units[0], names[0])
        if mag.ndim == 0 or mag.shape[-1] != len(units):
            # the shape check of the caller gives the message; convert with the first unit
            return convert(value, units[0], names[0])
        return np.stack([convert(value[..., i], u, n) for i, (u, n) in
                         enumerate(zip(units, names))], axis=-1)
    if isinstance(value, (list, tuple)) and value and any(is_quantity(v) for v in value):
        if len(units) == 1 and all(is_quantity(v) for v in value):  # one driver: samples
            return np.array([convert(v, units[0], names[0]) for v in value])
        if len(value) != len(units) or not all(is_quantity(v) for v in value):
            raise InputError(f"{what}: give one quantity per driver ({len(units)}), or one "
                             "quantity array for all")
        cols = [convert(v, u, n) for v, u, n in zip(value, units, names)]
        return np.stack(np.broadcast_arrays(*cols), axis=-1)
    return value
