"""Intermittent pairs in mechanism files: `type = "geneva"` and `type = "star-wheel"` joints give
the same mechanism as the one built in Python, and errors name the key or the pair."""

from __future__ import annotations

import json

import numpy as np
import pytest

import linkwork
from intermittent_mechanisms import D, geneva
from linkwork.errors import MechanismFileError
from linkwork.io.files import dump_schema


def geneva_text(joint: str = 'pin = "B", slots = 4', r: float = D * np.sin(np.pi / 4)) -> str:
    return f"""
name = "Geneva 4"
[points]
M = [0, 0]
C = [{D}, 0]
B = [{float(r)!r}, 0]
W = [{D}, {0.3 * D}]
[links]
frame = ["M", "C"]
disc = ["M", "B"]
wheel = ["C", "W"]
[joints]
M = {{ type = "revolute", links = ["frame", "disc"] }}
C = {{ type = "revolute", links = ["frame", "wheel"] }}
G = {{ type = "geneva", links = ["disc", "wheel"], {joint} }}
[driver]
joint = "M"
"""


def test_file_equals_python_model():
    phi = np.radians(np.arange(-180.0, 180.0, 7.5))
    a = linkwork.solve(linkwork.load_text(geneva_text()), phi, order=3)
    b = linkwork.solve(geneva(4), phi, order=3)
    for k in ("angle", "omega", "alpha", "jerk"):
        np.testing.assert_allclose(getattr(a.link("wheel"), k), getattr(b.link("wheel"), k), atol=1e-12)


def test_star_wheel_entry_angles_in_the_file_units():
    """A one-pin group with its entry slots at 45° is the 4-slot Geneva wheel; written in
    degrees, radians or with a unit it is the same."""
    ref = linkwork.solve(geneva(4), np.radians(np.arange(0.0, 360.0, 10.0)))
    for entry in ("[45]", '["0.7853981633974483 rad"]'):
        text = geneva_text(f'groups = [["B"]], entry = {entry}').replace('"geneva"', '"star-wheel"')
        sol = linkwork.solve(linkwork.load_text(text), ref.inputs[:, 0])
        np.testing.assert_allclose(sol.link("wheel").omega, ref.link("wheel").omega, atol=1e-12)


@pytest.mark.parametrize("joint,r,message", [
    ('pin = "B", slots = 2', None, "key 'joints.G.slots'"),
    ('pin = "B", slot = 4', None, "unknown key"),
    ('pin = "B", slots = 4', 60.0, "geneva pair 'G'.*does not reach into the slots"),
    ('pin = "Q", slots = 4', None, "the pin 'Q' must be a point of the driver 'disc'"),
    ('slots = 4', None, "the pin 'G' must be a point of the driver"),  # default: the joint's name
])
def test_errors_name_the_part(joint, r, message):
    with pytest.raises(MechanismFileError, match=message):
        linkwork.load_text(geneva_text(joint, *(() if r is None else (r,))))


def test_schema_lists_the_intermittent_pairs():
    schema = json.loads(dump_schema())
    text = json.dumps(schema)
    assert '"geneva"' in text and '"star-wheel"' in text


@pytest.mark.parametrize("name", ["geneva-4", "geneva-6", "star-wheel"])
def test_library_files_cite_the_seed(name):
    mech = linkwork.load(f"library:{name}")
    assert "Pöschl §25" in mech.description
