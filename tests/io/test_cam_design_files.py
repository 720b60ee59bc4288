"""`[profiles.NAME] type = "cam-design"` in mechanism files: a cam written by hand (no synthesis
code involved) moves its follower by the law, the file's angle unit applies, and mistakes name
their key."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from linkwork.errors import MechanismFileError

Y0 = float(np.sqrt(45.0**2 - 4.0**2))  # roller centre above the prime circle R_b + ρ = 45, offset 4


def text(profile_extra: str = "", segments: str | None = None, angle: str = "deg") -> str:
    segs = segments or ('{ rise = 12, over = 90, law = "3-4-5" }, { dwell = 90 }, '
                        '{ return = 12, over = 90, law = "harmonic" }, { dwell = 90 }')
    if angle == "rad":
        segs = segs.replace("over = 90", f"over = {np.pi / 2!r}").replace("dwell = 90", f"dwell = {np.pi / 2!r}")
    return f"""
name = "hand-written cam"
units = {{ length = "mm", angle = "{angle}" }}
[points]
O = [10, 5]
M = [50, 5]
C = [14, {float(5 + Y0)!r}]
G = [14, 150]
[profiles.disc]
type = "cam-design"
follower = "roller"
base_radius = 40
roller_radius = 5
offset = 4
center = [10, 5]
segments = [{segs}]
{profile_extra}
[links]
frame = ["O"]
cam = ["O", "M"]
follower = ["C", "G"]
[joints]
O = {{ type = "revolute", links = ["frame", "cam"] }}
G = {{ type = "prismatic", links = ["frame", "follower"], axis = [0, 1] }}
K = {{ type = "cam", links = ["cam", "follower"], profile = "disc", follower = "roller", point = "C", radius = 5 }}
[driver]
joint = "O"
"""


@pytest.mark.parametrize("angle", ["deg", "rad"])
def test_hand_written_cam_follows_its_law(angle):
    """3-4-5 rise of 12 over 90°: s = 12(10x³ − 15x⁴ + 6x⁵), x = φ/90°."""
    mech = linkwork.load_text(text(angle=angle))
    phi = np.radians([10.0, 33.0, 45.0, 80.0, 120.0, 200.0, 300.0])
    sol = linkwork.solve(mech, phi)
    x = np.clip(phi / (np.pi / 2), 0, 1)
    rise = 12 * (10 * x**3 - 15 * x**4 + 6 * x**5)
    xr = np.clip((phi - np.pi) / (np.pi / 2), 0, 1)
    want = np.where(phi < np.pi, rise, 12 - 12 * (1 - np.cos(np.pi * xr)) / 2)
    np.testing.assert_allclose(sol.point("C").position[:, 1] - (5 + Y0), want, atol=1e-9)
    np.testing.assert_allclose(sol.point("C").position[:, 0], 14.0, atol=1e-9)


@pytest.mark.parametrize("change,key,message", [
    (('law = "3-4-5"', 'law = "quintic"'), "profiles.disc.segments[0].law", "Input should be"),
    (("{ dwell = 90 }, {", "{ dwell = 90, rise = 2 }, {"), "profiles.disc.segments[1]", "a cam segment is"),
    (("{ dwell = 90 }]", "{ dwell = 80 }]"), "profiles.disc", "cover 350°"),
    (("return = 12", "return = 11"), "profiles.disc", "end the turn where it starts"),
    (("roller_radius = 5\n", ""), "profiles.disc.roller_radius", "needs `roller_radius`"),
    (("offset = 4", "offset = 60"), "profiles.disc.offset", "must be smaller than the radius 45"),
    (("offset = 4", "ofset = 4"), "profiles.disc.ofset", "unknown key"),
])
def test_mistakes_name_their_key(change, key, message):
    t = text()
    assert change[0] in t
    with pytest.raises(MechanismFileError, match=message) as info:
        linkwork.load_text(t.replace(change[0], change[1], 1))
    assert f"key '{key}'" in str(info.value)
