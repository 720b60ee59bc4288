"""Higher pairs in mechanism files: `[profiles.NAME]` tables and `type = "cam"` / `"rolling"`
joints give the same mechanism as the one built in Python, and errors name the part."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from higher_pair_mechanisms import E, R, RHO, eccentric
from linkwork.errors import MechanismFileError

Y0 = float(np.sqrt((R + RHO) ** 2 - E**2))


def cam_text(joint: str = 'follower = "roller", point = "C", radius = 5', profile: str = "disc") -> str:
    return f"""
name = "Eccentric cam, roller"
[points]
O = [0, 0]
E = [{E}, 0]
C = [0, {Y0!r}]
F = [0, -20]
[profiles.disc]
type = "circle"
center = [{E}, 0]
radius = {R}
[links]
frame = ["O"]
cam = ["O", "E"]
follower = ["C", "F"]
[joints]
O = {{ type = "revolute", links = ["frame", "cam"] }}
F = {{ type = "prismatic", links = ["frame", "follower"], axis = 90 }}
K = {{ type = "cam", links = ["cam", "follower"], profile = "{profile}", {joint} }}
[driver]
joint = "O"
"""


def test_file_equals_python_model():
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    a = linkwork.solve(linkwork.load_text(cam_text()), phi)
    b = linkwork.solve(eccentric("roller"), phi)
    np.testing.assert_allclose(a.point("C").acceleration, b.point("C").acceleration, atol=1e-9)
    np.testing.assert_allclose(a.joint("K")["pressure_angle"], b.joint("K")["pressure_angle"], atol=1e-12)


def test_csv_profile_beside_the_file(tmp_path):
    """A disc given as points read from a CSV beside the mechanism file: a closed spline through
    720 points of the circle reproduces the circle's follower motion closely."""
    t = np.linspace(0, 2 * np.pi, 720, endpoint=False)
    np.savetxt(tmp_path / "disc.csv", np.column_stack([E + R * np.cos(t), R * np.sin(t)]),
               delimiter=",", header="x,y", comments="")
    text = cam_text().replace('type = "circle"\ncenter = [10.0, 0]\nradius = 30.0',
                              'type = "points"\nfile = "disc.csv"\nclosed = true')
    assert 'file = "disc.csv"' in text
    path = tmp_path / "cam.toml"
    path.write_text(text)
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    a = linkwork.solve(linkwork.load(path), phi)
    b = linkwork.solve(eccentric("roller"), phi)
    np.testing.assert_allclose(a.point("C").position, b.point("C").position, atol=1e-7 * R)


@pytest.mark.parametrize("joint,profile,message", [
    ('follower = "roller", point = "C", radius = 5', "disk", r"profile 'disk', which is not in \[profiles\] \(did you mean 'disc'\?\)"),
    ('follower = "roller", point = "C"', "disc", "roller needs a positive radius"),
    ('follower = "roller", point = "Q", radius = 5', "disc", r"point 'Q', which is not in \[points\]"),
    ('follower = "wheel", point = "C", radius = 5', "disc", "follower"),
    ('follower = "roller", point = "C", radius = 6', "disc", "does not touch profile 'disc'"),
    ('follower = "flat", point = "C"', "disc", "flat face needs `axis`"),
])
def test_errors_name_the_part(joint, profile, message):
    with pytest.raises(MechanismFileError, match=message):
        linkwork.load_text(cam_text(joint, profile))
