"""The unit checks that skip pint (issue 17: a command should not pay for pint's import when
it needs none), held to pint itself."""

from __future__ import annotations

import subprocess
import sys

import pytest

from linkwork.units import COMMON_LENGTH_UNITS, check_length_unit, registry


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
