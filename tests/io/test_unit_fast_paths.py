"""The unit checks and conversions that skip pint (issue 17: a command should not pay for pint's
import when it needs none), held to pint itself."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from linkwork.errors import InputError
from linkwork.units import (COMMON_LENGTH_UNITS, QUICK_FACTORS, check_length_unit, parse_quantity,
                            registry)


@pytest.mark.parametrize("unit", sorted(COMMON_LENGTH_UNITS))
def test_every_length_unit_known_without_pint_is_a_length_in_pint(unit):
    ureg = registry()
    assert unit in ureg
    assert ureg.Unit(unit).dimensionality == ureg.Unit("m").dimensionality
    assert check_length_unit(unit) == unit


def test_other_length_units_still_go_to_pint():
    assert check_length_unit("mile") == "mile"
    with pytest.raises(Exception, match="not a unit of length"):
        check_length_unit("second")


def _probe(code: str) -> str:
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    return res.stdout.strip().splitlines()[-1]


def test_loading_a_mechanism_in_millimetres_needs_no_pint():
    out = _probe("import sys, linkwork; linkwork.load('library:heusinger-valve-gear'); "
                 "print('pint' in sys.modules)")
    assert out == "False"


def test_pint_without_its_dask_support_and_dask_still_importable():
    """pint is imported with dask looking absent (linkwork gives it no dask arrays); dask is
    imported normally afterwards and works."""
    out = _probe("from linkwork.units import parse_quantity; import sys; "
                 "v = parse_quantity('120 rpm', default_unit='rad/s', kind='speed'); "
                 "d = 'dask' in sys.modules; import dask.array as da; "
                 "print(d, abs(v - 4 * 3.141592653589793) < 1e-12, float(da.ones(4).sum().compute()))")
    assert out == "False True 4.0"


@pytest.mark.parametrize("unit, wanted", sorted(QUICK_FACTORS))
def test_quantities_read_without_pint_have_pint_s_value_to_the_bit(unit, wanted):
    ureg = registry()
    rng = np.random.default_rng(7)
    values = np.concatenate([rng.uniform(0, 1000, 300), rng.uniform(-1, 1, 100),
                             [0.0, 1.0, 10.31, 15.1, 60.0, 90.0, 120.0, 300.0]])
    for v in values:
        text = f"{float(v)!r} {unit}"
        got = parse_quantity(text, default_unit=wanted, kind="x")
        assert got == ureg.Quantity(float(v), unit).to(wanted).magnitude, text


def test_a_quantity_the_quick_path_does_not_know_goes_to_pint():
    """Other units, other wanted units, products: pint's path, as before."""
    assert parse_quantity("2 rad*s^-1", default_unit="rad/s", kind="x") == 2.0
    assert parse_quantity("1 ft", default_unit="m", kind="x") == pytest.approx(0.3048, rel=1e-15)
    with pytest.raises(InputError, match="cannot be converted"):
        parse_quantity("3 mm", default_unit="rad/s", kind="speed")
    with pytest.raises(InputError, match="finite number"):
        parse_quantity("1e13 rpm", default_unit="rad/s", kind="speed")


def test_loading_a_mechanism_with_a_speed_in_rpm_needs_no_pint():
    out = _probe("import sys, linkwork; m = linkwork.load('library:heusinger-hinge-chain'); "
                 "print('pint' in sys.modules, m.drivers[0].law.speed)")
    assert out == f"False {120 * (2 * np.pi / 60)!r}"
