"""The closed loop: a cam designed from a motion program, written as a mechanism file, loaded and
solved by the engine, moves its follower by the program's law, to 1e-9 of the lift.

The expectation is each law's closed form written out by hand (`cam_laws_by_hand`); the engine
knows nothing of laws: it keeps the follower's element touching the designed profile by the
cam pair's contact equations. Velocities and accelerations (cam at ω = 1 rad/s, so they equal
ds/dφ and d²s/dφ²) and jerks come out of the engine's jets through the profile's derivatives.
"""

from __future__ import annotations

import numpy as np
import pytest

import linkwork
from cam_laws_by_hand import program_by_hand
from linkwork.model.disc_cams import DiscCam
from linkwork.model.motion_programs import LAWS, CamDesignError, MotionProgram, Segment
from linkwork.synthesis import mechanism_text, pressure_angle

# cam angles clear of every join (segments at 0, 140, 180, 300°; joins inside laws at 1/8 … 7/8)
PHI = np.radians(np.arange(0.37, 360.0, 2.9))

FOLLOWERS = {
    "translating roller": dict(follower="roller", roller_radius=8.0, offset=6.0),
    "translating knife": dict(follower="knife"),
    "translating flat": dict(follower="flat"),
    "oscillating roller": dict(follower="roller", roller_radius=8.0, motion="oscillating", pivot=(75.0, 35.0), arm=60.0),
    "oscillating knife": dict(follower="knife", motion="oscillating", pivot=(70.0, -20.0), arm=55.0, side="right"),
    "oscillating flat": dict(follower="flat", motion="oscillating", pivot=(90.0, 10.0), face_offset=5.0),
}
LIFT = {"translating": 18.0, "oscillating": np.radians(12.0)}


def segments(law: str, lift: float):
    return [("rise", 140.0, lift, law), ("dwell", 40.0, 0.0, None), ("return", 120.0, lift, law),
            ("dwell", 60.0, 0.0, None)]


def design(law: str, kind: str) -> tuple[DiscCam, list]:
    kw = FOLLOWERS[kind]
    segs = segments(law, LIFT[kw.get("motion", "translating")])
    prog = MotionProgram([Segment(k, np.radians(e), lift, lw) for k, e, lift, lw in segs])
    return DiscCam(prog, base_radius=40.0, **kw), segs


CASES = [(law, kind) for law in LAWS for kind in ("translating roller", "translating knife", "translating flat")
         if not (law == "uniform" and kind.endswith("flat"))]
CASES += [(law, kind.replace("translating", "oscillating")) for law, kind in CASES]


def _follower_motion(mech, sol, kind):
    """The follower's lift from the engine: its displacement along the line of motion, or the
    lever's turn from the drawing; and the roller centre's distance from the cam centre."""
    P = sol.pose_derivatives("follower")
    if kind.startswith("translating"):
        return P[:4, :, 1]
    return P[:4, :, 2]


@pytest.mark.parametrize("law,kind", CASES, ids=[f"{a}-{b.replace(' ', '-')}" for a, b in CASES])
def test_engine_reproduces_the_law(law, kind):
    cam, segs = design(law, kind)
    mech = linkwork.load_text(mechanism_text(cam, name=f"{law} cam, {kind} follower"))
    sol = linkwork.solve(mech, PHI, order=3)
    assert (sol.status == linkwork.Status.OK).all()
    lift = segs[0][2]
    want = program_by_hand(segs, PHI)
    got = _follower_motion(mech, sol, kind)
    if kind.startswith("oscillating"):
        # the lever turns one way or the other; the lift carries the roller (face) away from O
        sense = np.sign(got[1][np.argmax(np.abs(got[1]))] * want[1][np.argmax(np.abs(got[1]))])
        got = sense * got
        if not kind.endswith("flat"):
            r = np.hypot(*sol.point("C").position.T)
            assert np.all(np.diff(r)[np.diff(want[0]) > 1e-9 * lift] > 0)
    scale = [lift, lift / np.radians(120.0), lift / np.radians(120.0) ** 2, lift / np.radians(120.0) ** 3]
    for k in range(4):
        np.testing.assert_allclose(got[k], want[k], rtol=0, atol=1e-9 * scale[k])
    # the engine's pressure angle (where the follower moves) is the synthesis' closed form
    moving = np.abs(want[1]) > 1e-6 * scale[1]
    engine = sol.joint("K")["pressure_angle"][moving]
    np.testing.assert_allclose(engine, np.abs(pressure_angle(cam, PHI[moving])), atol=1e-7)
    # a roller or knife touches its profile at the parameter u = φ
    if not kind.endswith("flat"):
        np.testing.assert_allclose(np.mod(sol.joint("K")["u"], 2 * np.pi), PHI, atol=1e-9)


def test_file_round_trip_designs_the_same_cam(tmp_path):
    """The file `mechanism_text` writes, loaded from disk, carries the profile of the cam it was
    written from (same points along the whole profile)."""
    cam, _ = design("modified-sine", "oscillating roller")
    path = tmp_path / "cam.toml"
    path.write_text(mechanism_text(cam))
    mech = linkwork.load(path)
    u = np.linspace(0, 2 * np.pi, 721)
    np.testing.assert_allclose(mech.profiles["cam"].derivatives(u, 2), cam.profile.derivatives(u, 2), atol=1e-9)


def test_flat_face_refuses_a_velocity_jump():
    with pytest.raises(CamDesignError, match="flat face cannot follow a jump of velocity"):
        design("uniform", "translating flat")


def test_uniform_law_with_a_knife_reports_its_corners():
    from linkwork.synthesis import corners
    cam, _ = design("uniform", "translating knife")
    angles = sorted(round(np.degrees(j.angle), 9) for j in corners(cam))
    assert angles == [0.0, 140.0, 180.0, 300.0]


@pytest.mark.parametrize("follower", ["roller", "knife", "flat"])
def test_turned_line_of_motion_and_shifted_centre(follower):
    """The follower's line turned to 30°, the cam's centre away from the origin, the turn
    starting in a dwell: the lift along the line is the program's, and nothing moves across it."""
    segs = [("dwell", 30.0, 0.0, None), ("rise", 100.0, 12.0, "modified-sine"), ("dwell", 50.0, 0.0, None),
            ("return", 150.0, 12.0, "4-5-6-7"), ("dwell", 30.0, 0.0, None)]
    prog = MotionProgram([Segment(k, np.radians(e), lift, lw) for k, e, lift, lw in segs])
    kw = {"roller": dict(roller_radius=6.0, offset=-4.0), "knife": dict(offset=3.0), "flat": {}}[follower]
    cam = DiscCam(prog, follower, 30.0, direction=np.radians(30.0), center=(5.0, -3.0), **kw)
    sol = linkwork.solve(linkwork.load_text(mechanism_text(cam)), PHI, order=2)
    P = sol.pose_derivatives("follower")
    e = np.array([np.cos(np.radians(30.0)), np.sin(np.radians(30.0))])
    want = program_by_hand(segs, PHI)
    for k in range(3):
        np.testing.assert_allclose(P[k, :, :2] @ e, want[k], rtol=0, atol=1e-9 * 12.0 / np.radians(100.0) ** k)
    np.testing.assert_allclose(P[0, :, :2] @ np.array([-e[1], e[0]]), 0.0, atol=1e-12)
