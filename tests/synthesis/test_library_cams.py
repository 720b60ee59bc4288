"""The designed cams of the library (written by `linkwork cam design`) move their followers by
their laws, written out by hand; the knife-edge cam shows Pöschl's constant acceleration on its
rise (±4L/β² on the two halves, jumping in the middle) and a constant speed −L/β on its
uniform return."""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from cam_laws_by_hand import program_by_hand

W = 300 * 2 * np.pi / 60  # the files' 300 rpm
PHI = np.radians(np.arange(0.41, 360.0, 3.7))

CAMS = {
    "designed-cam-offset-roller": ([("rise", 120.0, 20.0, "cycloidal"), ("dwell", 60.0, 0, None),
                                    ("return", 120.0, 20.0, "3-4-5"), ("dwell", 60.0, 0, None)], "y"),
    "designed-cam-oscillating-roller": ([("rise", 100.0, np.radians(15.0), "modified-sine"), ("dwell", 50.0, 0, None),
                                         ("return", 150.0, np.radians(15.0), "modified-trapezoid"),
                                         ("dwell", 60.0, 0, None)], "angle"),
    "designed-cam-flat-face": ([("rise", 150.0, 12.0, "4-5-6-7"), ("dwell", 30.0, 0, None),
                                ("return", 150.0, 12.0, "harmonic"), ("dwell", 30.0, 0, None)], "y"),
    "designed-cam-knife": ([("rise", 90.0, 10.0, "parabolic"), ("dwell", 90.0, 0, None),
                            ("return", 90.0, 10.0, "uniform"), ("dwell", 90.0, 0, None)], "y"),
}


@pytest.mark.parametrize("name", CAMS)
def test_library_cam_follows_its_law(name):
    segs, coord = CAMS[name]
    sol = linkwork.solve(linkwork.load(f"library:{name}"), PHI)
    P = sol.pose_derivatives("follower")
    want = program_by_hand(segs, PHI)
    got = P[:3, :, 1]
    if coord == "angle":  # the lever turns one way or the other as the roller lifts
        got = np.sign(np.sum(P[1, :, 2] * want[1])) * P[:3, :, 2]
    lift = segs[0][2]
    for k in range(3):
        np.testing.assert_allclose(got[k], W**k * want[k], rtol=0, atol=1e-9 * lift * (W / np.radians(90)) ** k)


def test_poeschl_constant_acceleration_on_the_knife_cam():
    beta, L = np.radians(90.0), 10.0
    phi = np.radians([10.0, 40.0, 50.0, 80.0, 200.0, 250.0])
    sol = linkwork.solve(linkwork.load("library:designed-cam-knife"), phi)
    C = sol.point("C")
    np.testing.assert_allclose(C.acceleration[:4, 1], W**2 * np.array([4, 4, -4, -4]) * L / beta**2, rtol=1e-9)
    np.testing.assert_allclose(C.velocity[4:, 1], -W * L / beta, rtol=1e-9)
