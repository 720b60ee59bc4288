"""Mechanism files: every user mistake gets one clear message naming the part and the reason."""

import json

import numpy as np
import pytest

import linkwork
from linkwork.errors import MechanismFileError, StructureError, UnknownMechanismError
from linkwork.io.files import dump_schema, library_names
from mechanism_texts import five_bar_text

FOURBAR = """\
name = "test four-bar"
units = { length = "mm" }

[points]
O2 = [0, 0]
A  = [0, 10]
B  = [30, 30]
O4 = [40, 0]

[links]
frame   = ["O2", "O4"]
crank   = ["O2", "A"]
coupler = ["A", "B"]
rocker  = ["B", "O4"]

[joints]
O2 = { type = "revolute", links = ["frame", "crank"] }
A  = { type = "revolute", links = ["crank", "coupler"] }
B  = { type = "revolute", links = ["coupler", "rocker"] }
O4 = { type = "revolute", links = ["rocker", "frame"] }

[driver]
joint = "O2"
speed = "60 rpm"
"""


def test_valid_file_loads_with_design_lengths():
    mech = linkwork.load_text(FOURBAR)
    assert mech.link_names == ("frame", "crank", "coupler", "rocker")
    # 60 rpm = 2π rad/s
    assert mech.drivers[0].law.speed == pytest.approx(2 * np.pi)
    assert mech.drivers[0].reference == "A"


def _error(text: str) -> str:
    with pytest.raises(MechanismFileError) as info:
        linkwork.load_text(text, source="m.toml")
    return str(info.value)


def test_toml_syntax_error_names_line():
    msg = _error(FOURBAR.replace('B  = [30, 30]', 'B  = [30, 30'))
    # tomllib notices the unclosed array where the next line starts
    assert "m.toml:8" in msg and "Unclosed array" in msg


def test_misspelt_key_names_key_and_line():
    msg = _error(FOURBAR.replace('joint = "O2"', 'jiont = "O2"'))
    assert "driver.jiont" in msg and "did you mean 'joint'" in msg and "m.toml:23" in msg


def test_misspelt_joint_field_names_joint():
    msg = _error(FOURBAR.replace('A  = { type = "revolute", links = ["crank", "coupler"] }',
                                 'A  = { type = "revolute", link = ["crank", "coupler"] }'))
    assert "joints.A.link" in msg and "m.toml:18" in msg and "did you mean 'links'" in msg


def test_unknown_joint_type():
    msg = _error(FOURBAR.replace('B  = { type = "revolute"', 'B  = { type = "hinge"'))
    assert "joints.B" in msg


def test_missing_section():
    start = FOURBAR.index("[points]")
    end = FOURBAR.index("[links]")
    msg = _error(FOURBAR[:start] + FOURBAR[end:])
    assert "points" in msg and "missing" in msg


def test_link_with_unknown_point():
    msg = _error(FOURBAR.replace('coupler = ["A", "B"]', 'coupler = ["A", "X"]'))
    assert "link 'coupler'" in msg and "'X'" in msg


def test_joint_with_unknown_link():
    msg = _error(FOURBAR.replace('links = ["coupler", "rocker"]', 'links = ["coupler", "roker"]'))
    assert "joint 'B'" in msg and "'roker'" in msg


def test_hinge_point_not_on_link():
    msg = _error(FOURBAR.replace('rocker  = ["B", "O4"]', 'rocker  = ["O4", "A"]'))
    assert "revolute joint 'B'" in msg and "rocker" in msg


def test_no_driver():
    msg = _error(FOURBAR[: FOURBAR.index("[driver]")])
    assert "no [driver]" in msg


def test_driver_on_unknown_joint():
    msg = _error(FOURBAR.replace('joint = "O2"', 'joint = "Q"'))
    assert "joint 'Q', which is not in [joints]" in msg and "driver.joint" in msg


def test_bad_speed_unit():
    msg = _error(FOURBAR.replace('"60 rpm"', '"60 kg"'))
    assert "speed" in msg and "kg" in msg


def test_coincident_points_make_degenerate_link():
    msg = _error(FOURBAR.replace("A  = [0, 10]", "A  = [0, 0]"))
    assert "crank" in msg and "coincide" in msg


GEARS = """\
name = "gear pair"
[points]
O1 = [0, 0]
O2 = [60, 0]
P = [10, 0]
[links]
frame = ["O1", "O2"]
wheel1 = ["O1", "P"]
wheel2 = ["O2"]
[joints]
O1 = { type = "revolute", links = ["frame", "wheel1"] }
O2 = { type = "revolute", links = ["frame", "wheel2"] }
G = { type = "gear", links = ["wheel1", "wheel2"], carrier = "frame", radii = [40, 30] }
[driver]
joint = "O1"
"""


def test_gear_radii_must_fit_centre_distance():
    msg = _error(GEARS)
    assert "gear 'G'" in msg and "60" in msg and "70" in msg


def test_gear_pair_turns_in_ratio():
    mech = linkwork.load_text(GEARS.replace("[40, 30]", "[40, 20]"))
    sol = linkwork.solve(mech, np.radians([0.0, 30.0, 90.0]))
    # external pair: ω2 = −(r1/r2) ω1
    np.testing.assert_allclose(sol.link("wheel2").omega, -2.0 * sol.link("wheel1").omega)


def test_over_constrained_mechanism_is_named():
    text = FOURBAR.replace('[joints]', '[joints]\nX = { type = "revolute", point = "A", links = ["frame", "coupler"] }')
    text = text.replace('frame   = ["O2", "O4"]', 'frame   = ["O2", "O4", "A"]')
    mech = linkwork.load_text(text)
    with pytest.raises(StructureError, match="over-constrained"):
        linkwork.solve(mech, [0.5])


def test_under_constrained_mechanism_says_inputs_needed():
    five_bar = five_bar_text(name="test four-bar", units="mm", speed="60 rpm")
    mech = linkwork.load_text(five_bar)
    with pytest.raises(StructureError, match="under-constrained.*1 more input"):
        linkwork.solve(mech, [0.5])


def test_unknown_library_name_and_missing_path():
    with pytest.raises(UnknownMechanismError, match="no mechanism 'nosuch'"):
        linkwork.load("library:nosuch")
    with pytest.raises(UnknownMechanismError, match="no mechanism file"):
        linkwork.load("/nonexistent/file.toml")


def test_every_library_file_validates():
    for name in library_names():
        assert linkwork.load(f"library:{name}").name


def test_published_schema_is_current(tmp_path):
    from pathlib import Path
    published = Path(__file__).resolve().parents[2] / "docs" / "mechanism.schema.json"
    assert json.loads(published.read_text()) == json.loads(dump_schema())
