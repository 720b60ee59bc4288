"""The quantity grammar of `linkwork.units`: numbers, unit names, `*`, `/`, `^`/`**` with small
integer exponents and parentheses; anything else refused at once with a clear message."""

import math

import pytest

from linkwork.errors import InputError
from linkwork.units import MAX_MAGNITUDE, parse_quantity, read_quantity, unit_dimension


@pytest.mark.parametrize("text,unit,value", [
    ("60 rpm", "rad/s", 2 * math.pi),          # 60 turns a minute = one turn a second
    ("2 rad/s", "rad/s", 2.0),
    ("1.2rad", "rad", 1.2),
    ("-30", "deg", -30.0),
    ("180 deg", "rad", math.pi),
    ("5 mm/s^2", "m/s**2", 0.005),
    ("5 mm/s**2", "m/s**2", 0.005),
    ("5 mm*s^-2", "m/s**2", 0.005),
    ("(2 rad)/(4 s)", "rad/s", 0.5),
    ("1.5e3 mm", "m", 1.5),
    ("2^3 mm", "mm", 8.0),
    ("90 °", "rad", math.pi / 2),
])
def test_readable_quantities(text, unit, value):
    assert parse_quantity(text, default_unit=unit, kind="x") == pytest.approx(value)


@pytest.mark.parametrize("text,why", [
    ("9**9**9", "exponents go up to 4"),
    ("10**400 deg", "exponents go up to 4"),
    ("2^2^2", "one exponent per factor"),
    ("2^1.5", "whole number"),
    ("1e400", "finite number"),
    ("1e13 mm", "finite number"),
    ("nan", "not a finite number"),
    ("inf rpm", "not a finite number"),
    ("1/0 s", "division by zero"),
    ("3 furlongz", "unknown unit 'furlongz'"),
    ("__import__('os')", "unexpected"),
    ("2 + 3", r"unexpected '\+'"),
    ("(2 s", "ends too early"),
    ("", "empty"),
    ("1" * 300, "too long"),
    ("60 kg", "cannot be converted"),
    ("5 degC/s", "cannot be converted"),
])
def test_refused_quantities(text, why):
    with pytest.raises(InputError, match=why):
        parse_quantity(text, default_unit="rad/s", kind="speed")


def test_message_names_what_the_value_is_for():
    with pytest.raises(InputError, match="^driver 'O2' speed: "):
        parse_quantity("9**9**9", default_unit="rad/s", kind="driver 'O2' speed")


@pytest.mark.parametrize("value", [float("nan"), float("inf"), True, 10 ** 30, 2 * MAX_MAGNITUDE])
def test_numbers_passed_directly_are_checked(value):
    with pytest.raises(InputError):
        parse_quantity(value, default_unit="rad/s", kind="speed")


def test_dimensions():
    assert unit_dimension("0.5 s") == "time"
    assert unit_dimension("30") is None
    assert unit_dimension("3 in") == "length"
    assert unit_dimension("2 deg") == "angle"
    assert unit_dimension("2 kg") == "other"
    assert str(read_quantity("60 rpm").units) == "revolutions_per_minute"
