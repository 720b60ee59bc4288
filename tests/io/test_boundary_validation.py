"""Validation at the boundary (issue 10): every bad value or name in a mechanism file ends in one
MechanismFileError naming the key and its line, before anything reaches the solver."""

import re

import numpy as np
import pytest

import linkwork
from linkwork.errors import MechanismFileError, ModelError
from linkwork.model import ConstantSpeed, Mechanism, PolynomialLaw, Revolute, TabulatedLaw

from test_files import FOURBAR  # the same four-bar as the other file tests

# line numbers of FOURBAR, counted once here by hand
LINE = {"A": 6, "B": 7, "frame": 11, "coupler": 13, "joints.A": 18, "joints.B": 19,
        "driver": 22, "driver.joint": 23, "driver.speed": 24}


def error(text: str) -> MechanismFileError:
    with pytest.raises(MechanismFileError) as info:
        linkwork.load_text(text, source="m.toml")
    return info.value


def replaced(old: str, new: str, text: str = FOURBAR) -> str:
    assert old in text, old
    return text.replace(old, new)


def test_the_base_file_loads():
    assert linkwork.load_text(FOURBAR).name == "test four-bar"


# ----------------------------------------------------------------------------- numbers
@pytest.mark.parametrize("value,why", [
    ("nan", "finite"), ("inf", "finite"), ("-inf", "finite"), ("true", "expected a number"),
    ('"10"', "without quotes"), ("1e300", "larger than 1e+12"),
    ("1" + "0" * 30, "larger than 1e+12"),
])
def test_coordinates_must_be_finite_numbers_of_sane_size(value, why):
    e = error(replaced("A  = [0, 10]", f"A  = [0, {value}]"))
    assert e.key == "points.A[1]" and e.line == LINE["A"] and why in str(e)


def test_integer_beyond_the_toml_reader_is_an_error():
    e = error(replaced("A  = [0, 10]", "A  = [0, " + "9" * 5000 + "]"))
    assert "not valid TOML" in str(e)


@pytest.mark.parametrize("speed,why", [
    ("nan", "finite"), ("inf", "finite"), ("true", "expected a number"),
    ('"9**9**9 rpm"', "exponents go up to 4"), ('"10**400 rpm"', "exponents go up to 4"),
    ('"1e400 rpm"', "finite number"), ('"nan rpm"', "not a finite number"),
    ('"60 kg"', "cannot be converted"),
])
def test_speed_must_be_a_finite_quantity(speed, why):
    e = error(replaced('speed = "60 rpm"', f"speed = {speed}"))
    assert e.key == "driver.speed" and e.line == LINE["driver.speed"] and why in str(e)


def test_speed_and_law_together_are_refused():
    text = replaced('speed = "60 rpm"', 'speed = "60 rpm"\nlaw = { type = "polynomial", coefficients = [0, 360] }')
    e = error(text)
    assert e.key == "driver" and e.line == LINE["driver"] and "not both" in str(e)


@pytest.mark.parametrize("law,why", [
    ('{ type = "polynomial", coefficients = [] }', "at least 1"),
    ('{ type = "polynomial", coefficients = [0, 360], duration = 0 }', "positive"),
    ('{ type = "table", time = [0, 1, 2, nan], value = [0, 1, 2, 3] }', "finite"),
    ('{ type = "table", time = [0, 1, 2, 3], value = [0, 1, inf, 3] }', "finite"),
    ('{ type = "table", time = [0, 2, 1, 3], value = [0, 1, 2, 3] }', "increase"),
])
def test_bad_motion_laws(law, why):
    e = error(replaced('speed = "60 rpm"', f"law = {law}"))
    assert e.key.startswith("driver.law") and e.line is not None and why in str(e)


GEARS = """\
name = "gears"
[points]
O1 = [0, 0]
O2 = [30, 0]
P1 = [10, 0]
P2 = [30, 10]
[links]
frame = ["O1", "O2"]
g1 = ["O1", "P1"]
g2 = ["O2", "P2"]
[joints]
O1 = { type = "revolute", links = ["frame", "g1"] }
O2 = { type = "revolute", links = ["frame", "g2"] }
G = { type = "gear", links = ["g1", "g2"], radii = [10, 20] }
[driver]
joint = "O1"
"""


def test_gear_file_loads_and_nan_radius_is_refused():
    assert linkwork.load_text(GEARS).joint("G").radii == (10.0, 20.0)
    e = error(replaced("radii = [10, 20]", "radii = [nan, 20]", GEARS))
    assert e.key == "joints.G.radii[0]" and e.line == 14 and "finite" in str(e)
    e = error(replaced("radii = [10, 20]", "radii = [-10, 40]", GEARS))
    assert "positive" in str(e)


@pytest.mark.parametrize("axis", ["1e30", "[1e30, 0]", "[nan, 1]", '"inf deg"', '"30 kg"'])
def test_absurd_axes_are_refused(axis):
    text = replaced('O4 = { type = "revolute", links = ["rocker", "frame"] }',
                    f'O4 = {{ type = "prismatic", links = ["frame", "rocker"], axis = {axis} }}')
    text = replaced('rocker  = ["B", "O4"]', 'rocker  = ["B", "O4"]', text)
    e = error(text)
    assert e.key.startswith("joints.O4") and e.line == 20


def test_zero_axis_is_refused_with_its_joint():
    text = replaced('O4 = { type = "revolute", links = ["rocker", "frame"] }',
                    'O4 = { type = "prismatic", links = ["frame", "rocker"], axis = [0, 0] }')
    e = error(text)
    assert e.key == "joints.O4" and e.line == 20 and "zero vector" in str(e)


# ----------------------------------------------------------------------------- names
@pytest.mark.parametrize("old,new,key,line,hint", [
    ('coupler = ["A", "B"]', 'coupler = ["A", "Bx"]', "links.coupler", 13, "did you mean 'B'"),
    ('links = ["coupler", "rocker"]', 'links = ["coupler", "roker"]', "joints.B.links", 19,
     "did you mean 'rocker'"),
    ('joint = "O2"', 'joint = "O22"', "driver.joint", 23, "did you mean 'O2'"),
    ('joint = "O2"', 'joint = "O2"\nreference = "AA"', "driver.reference", 24, "did you mean 'A'"),
    ('A  = { type = "revolute", links', 'A  = { type = "revolute", point = "Q", links',
     "joints.A.point", 18, "which is not in [points]"),
])
def test_unknown_names_are_found_before_the_model(old, new, key, line, hint):
    e = error(replaced(old, new))
    assert e.key == key and e.line == line and hint in str(e)


def test_joint_without_point_of_its_name():
    e = error(replaced('O4 = { type = "revolute"', 'O5 = { type = "revolute"'))
    assert e.key == "joints.O5" and "no `point`" in str(e) and "did you mean 'O4'" in str(e)


def test_point_on_no_link_is_refused():
    e = error(replaced("O4 = [40, 0]", "O4 = [40, 0]\nZ = [5, 5]"))
    assert e.key == "points.Z" and e.line == 9 and "on no link" in str(e)


def test_frame_missing_suggests_a_name():
    e = error(replaced('frame   = ["O2", "O4"]', 'frme    = ["O2", "O4"]').replace(
        '["frame"', '["frme"').replace('"frame"]', '"frme"]'))
    assert "no frame link 'frame'" in str(e) and "did you mean 'frme'" in str(e)


def test_two_drivers_on_one_joint():
    text = FOURBAR[:FOURBAR.index("[driver]")] + (
        '[[drivers]]\njoint = "O2"\n\n[[drivers]]\njoint = "O2"\nspeed = 2\n')
    e = error(text)
    assert e.key == "drivers[1].joint" and e.line == 26 and "two drivers" in str(e)


def test_drivers_array_line_numbers():
    text = FOURBAR[:FOURBAR.index("[driver]")] + (
        '[[drivers]]\njoint = "O2"\n\n[[drivers]]\njoint = "A"\nspeed = "1 kg"\n')
    e = error(text)
    assert e.key == "drivers[1].speed" and e.line == 27


# ----------------------------------------------------------------------------- the model's errors
def test_model_errors_carry_key_and_line():
    # B's hinge point is not carried by the rocker: the model finds it, the loader maps it
    e = error(replaced('rocker  = ["B", "O4"]', 'rocker  = ["O4", "A"]'))
    assert e.key == "joints.B" and e.line == LINE["joints.B"] and "revolute joint 'B'" in str(e)
    assert re.match(r"m\.toml:19, key 'joints\.B': ", str(e))


def test_zero_length_link_is_an_error():
    # B drawn on A: the coupler has no length between its hinges (was: every sample unreachable)
    text = replaced("B  = [30, 30]", "B  = [0, 10]\nC  = [15, 25]")
    e = error(replaced('coupler = ["A", "B"]', 'coupler = ["A", "B", "C"]', text))
    assert e.key == "links.coupler" and e.line == LINE["coupler"] + 1 and "zero length" in str(e)


def test_huge_coordinate_is_not_called_coincident_points():
    e = error(replaced("O4 = [40, 0]", "O4 = [40, 0]\nF = [1e12, 0]").replace(
        'frame   = ["O2", "O4"]', 'frame   = ["O2", "O4", "F"]'))
    msg = str(e)
    assert "coincide" not in msg and "drawing's size" in msg and e.key.startswith("links.")


def test_non_utf8_file(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_bytes(FOURBAR.encode() + b'\n# caf\xe9\n')
    with pytest.raises(MechanismFileError) as info:
        linkwork.load(p)
    assert "not UTF-8" in str(info.value) and info.value.line == 26


def test_section_names_survive_in_messages():
    msg = str(error(replaced('coupler = ["A", "B"]', 'coupler = ["A", "X"]')))
    assert msg.endswith("which is not in [points] (did you mean 'A'?)") or "[points]" in msg


# ----------------------------------------------------------------------------- the model API
def test_mechanism_build_refuses_nan_coordinates_and_laws():
    base = dict(name="m", points={"O": [0, 0], "A": [0, float("nan")]},
                links={"frame": ["O"], "crank": ["O", "A"]},
                joints=[Revolute("O", "O", ("frame", "crank"))], drivers=[{"joint": "O"}])
    with pytest.raises(ModelError, match="point 'A'"):
        Mechanism.build(**base)
    base["points"]["A"] = [0, 1]
    assert Mechanism.build(**base).name == "m"
    for law, why in ((ConstantSpeed(speed=float("nan")), "not finite"),
                     (PolynomialLaw((), 1.0), "at least one coefficient"),
                     (TabulatedLaw((0.0, 1.0), (0.0,)), "as many values")):
        with pytest.raises(ModelError, match=why):
            Mechanism.build(**{**base, "drivers": [{"joint": "O", "law": law}]})


def test_driver_on_a_joint_with_an_unknown_link_is_a_model_error():
    with pytest.raises(ModelError):
        Mechanism.build(name="m", points={"O": [0, 0], "A": [0, 1]},
                        links={"frame": ["O"], "crank": ["O", "A"]},
                        joints=[Revolute("O", "O", ("frame", "crnk"))], drivers=[{"joint": "O"}])


def test_every_library_file_still_loads():
    from linkwork.io.files import library_names
    for name in library_names():
        assert np.isfinite(linkwork.load(f"library:{name}").length_scale)


def test_profile_errors_carry_their_line():
    from linkwork.io.files import library_names, resolve
    assert "radial-roller-cam" in library_names()
    text = resolve("library:radial-roller-cam")[1]
    lines = text.splitlines()
    at = lines.index("radius = 30") + 1  # the disc's radius, below [profiles.disc]
    assert lines[at - 4] == "[profiles.disc]"
    e = error(text.replace("radius = 30", "radius = nan", 1))
    assert e.key == "profiles.disc.radius" and e.line == at and "finite" in str(e)
    e = error(text.replace("radius = 30", "radius = 30\nfoo = 1", 1))
    assert e.key == "profiles.disc.foo" and e.line == at + 1


@pytest.mark.parametrize("slots", ["1e12", "1000000", '"6"', "true", "2"])
def test_geneva_slot_count_is_a_sane_integer(slots):
    from linkwork.io.files import resolve
    text = resolve("library:geneva-6")[1]
    assert "slots = 6" in text
    e = error(text.replace("slots = 6", f"slots = {slots}"))
    assert e.key.endswith(".slots") and e.line is not None
