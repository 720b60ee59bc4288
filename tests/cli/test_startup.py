"""A small job pays only for the machinery it uses (issue 17): which heavy packages a command
imports, checked in a fresh interpreter. Times are measured by bench/, not asserted here."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

#: (pydantic is not among them: Typer itself converts option values with it)
HEAVY = ("numpy", "scipy", "scipy.interpolate", "scipy.spatial", "scipy.optimize", "pint", "numba",
         "networkx", "matplotlib", "pandas")

_PROBE = """
import io, json, sys
from contextlib import redirect_stdout
from linkwork.cli import run
heavy = json.loads(sys.argv[2])
sys.argv = ["linkwork", *json.loads(sys.argv[1])]
out = io.StringIO()
try:
    with redirect_stdout(out):
        run()
except SystemExit as e:
    code = e.code or 0
else:
    code = 0
print(json.dumps({"code": code, "loaded": sorted(m for m in heavy if m in sys.modules),
                  "out": out.getvalue()[:2000]}))
"""


def _loaded(*args: str) -> dict:
    res = subprocess.run([sys.executable, "-c", _PROBE, json.dumps(args), json.dumps(HEAVY)],
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    return json.loads(res.stdout.strip().splitlines()[-1])


def test_listing_the_library_imports_no_numerics():
    r = _loaded("library")
    assert r["code"] == 0 and "crank-rocker" in r["out"]
    assert r["loaded"] == []


def test_printing_a_library_file_imports_no_numerics():
    r = _loaded("library", "crank-rocker")
    assert r["code"] == 0 and "[links]" in r["out"]
    assert r["loaded"] == []


def test_an_unknown_library_name_is_refused_without_numerics():
    r = _loaded("library", "crank-rockr")
    assert r["code"] == 2 and r["loaded"] == []


@pytest.mark.parametrize("mech", ["library:crank-rocker", "library:jansen-linkage"])
def test_analyze_at_a_few_inputs_loads_no_profiles_plots_or_tables(mech):
    """(numba brings scipy.linalg for its own linear algebra; splines, KD-trees and root
    finders of SciPy, Matplotlib and pandas are not needed for a four-bar's table.)"""
    r = _loaded("analyze", mech, "--at", "30,60", "--format", "json")
    assert r["code"] == 0
    assert not {"scipy.interpolate", "scipy.spatial", "scipy.optimize", "matplotlib",
                "pandas"} & set(r["loaded"])


def test_csv_output_needs_no_pandas():
    r = _loaded("analyze", "library:crank-rocker", "--format", "csv")
    assert r["code"] == 0 and r["out"].startswith("input [rad],status,")
    assert "pandas" not in r["loaded"]


def test_a_bare_number_needs_no_unit_registry():
    """`--at 30` is read without pint; `--at 30deg` with it: the same value."""
    probe = ("import sys, math; from linkwork.units import parse_quantity as p; "
             "a = p('30', default_unit='deg', kind='x'); print('pint' in sys.modules, a); "
             "b = p('30 deg', default_unit='deg', kind='x'); print(math.isclose(a, b, rel_tol=1e-15))")
    res = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120)
    assert res.stdout.split() == ["False", "30.0", "True"], res.stderr
