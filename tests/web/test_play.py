"""Playing a mechanism's whole motion in the workbench: a drawing at a sample of the whole motion
is taken from the whole motion the server keeps per mechanism (`web.app.motion_sample`,
`web.sources.Motions`) instead of being marched afresh from the design position, and the scene's
paths and fit come from the kept motion too.

The expectations are independent solves: each sample is solved again on its own from scratch
(`solve_at`, which marches straight from the design position to it, another path than the whole
motion's march through every sample before it), and the two must agree to rounding — positions,
velocities, accelerations and statuses. The 12-link Heusinger valve gear (two drivers with motion
laws, Newton-solved groups) is the mechanism whose play was slow."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the test client's notice about its HTTP library
    from fastapi.testclient import TestClient

from linkwork.kinematics import Status, solve_at, whole_motion
from linkwork.web import create_app
from linkwork.web import app as web_app
from linkwork.web import models as m
from linkwork.web.sources import Motions, Sources

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

NAME = "heusinger-valve-gear"
SAMPLES = [0, 45, 123, 200, 290, 360]  # spread over the whole motion (361 samples, one turn)


@pytest.fixture(scope="module")
def gear():
    """The valve gear (a mechanism object of its own: the kept motions are per object) and its
    whole motion solved here, by the kinematics alone."""
    mech = Sources(None).load(library=NAME).mechanism
    return mech, whole_motion(mech)


def assert_same_solution(a, b) -> None:
    """Two one-sample solutions equal to rounding: statuses exactly, every point's position,
    velocity and acceleration and every link's pose to 1e-9 of the mechanism's natural scales."""
    mech = a.mechanism
    L = mech.length_scale
    assert a.status.tolist() == b.status.tolist()
    np.testing.assert_array_equal(a.inputs, b.inputs)
    for p in mech.points:
        pa, pb = a.point(p), b.point(p)
        scale_v = max(1.0, float(np.abs(pb.velocity).max()))
        scale_a = max(1.0, float(np.abs(pb.acceleration).max()))
        np.testing.assert_allclose(pa.position, pb.position, rtol=0, atol=1e-9 * L, err_msg=p)
        np.testing.assert_allclose(pa.velocity, pb.velocity, rtol=0, atol=1e-9 * max(L, scale_v),
                                   err_msg=p)
        np.testing.assert_allclose(pa.acceleration, pb.acceleration, rtol=0,
                                   atol=1e-9 * max(L, scale_a), err_msg=p)
    for ln in mech.link_names:
        np.testing.assert_allclose(a.pose_derivatives(ln)[0], b.pose_derivatives(ln)[0],
                                   rtol=0, atol=1e-9 * L, err_msg=ln)


@pytest.mark.parametrize("k", SAMPLES)
def test_a_sample_asked_by_inputs_is_the_solve_at_those_inputs(gear, k):
    mech, motion = gear
    req = m.DrawingRequest.model_validate({"source": {"library": NAME},
                                           "at": [motion.inputs[k].tolist()]})
    kept = web_app.motion_sample(mech, req)
    assert kept is not None and len(kept) == 1
    assert_same_solution(kept, solve_at(mech, motion.inputs[k:k + 1]))


@pytest.mark.parametrize("k", SAMPLES)
def test_a_sample_asked_by_time_is_the_solve_at_that_time(gear, k):
    """By time the motion laws give the inputs' rates: the velocities are the motion's."""
    mech, motion = gear
    req = m.DrawingRequest.model_validate({"source": {"library": NAME},
                                           "times": [float(motion.time[k])]})
    kept = web_app.motion_sample(mech, req)
    assert kept is not None and kept.time.tolist() == [motion.time[k]]
    scratch = solve_at(mech, times=motion.time[k:k + 1])
    assert_same_solution(kept, scratch)
    # the wheel turns at 360°/s by its law, at every time
    np.testing.assert_allclose(kept.link("wheel").omega, [2 * np.pi], rtol=1e-12)


@pytest.mark.parametrize("k", [0, 57, 204, 359])
def test_a_position_between_samples_is_marched_from_the_nearest_and_is_solve_at(gear, k):
    """Between samples (a slider's value, another reversing-arm setting) the march goes on from
    the nearest kept sample: the answer is still `solve_at`'s from the design position."""
    mech, motion = gear
    between = 0.5 * (motion.inputs[k] + motion.inputs[k + 1])
    at = m.DrawingRequest.model_validate({"source": {"library": NAME}, "at": [between.tolist()]})
    kept = web_app.motion_sample(mech, at)
    assert_same_solution(kept, solve_at(mech, between[None]))
    t = 0.5 * (motion.time[k] + motion.time[k + 1])
    by_time = m.DrawingRequest.model_validate({"source": {"library": NAME}, "times": [float(t)]})
    assert_same_solution(web_app.motion_sample(mech, by_time), solve_at(mech, times=[t]))
    # another setting of the reversing arm (its driver: the second input), the wheel at a sample
    other = motion.inputs[k] + [0.0, np.radians(-7.0)]
    at = m.DrawingRequest.model_validate({"source": {"library": NAME}, "at": [other.tolist()]})
    assert_same_solution(web_app.motion_sample(mech, at), solve_at(mech, other[None]))


def test_other_requests_are_solved_as_before(gear):
    mech, motion = gear
    for asked in ({"at": [motion.inputs[10].tolist(), motion.inputs[11].tolist()]},
                  {"times": [0.1, 0.2]}, {}):
        req = m.DrawingRequest.model_validate({"source": {"library": NAME}, **asked})
        assert web_app.motion_sample(mech, req) is None, asked


def test_one_driver_samples_are_solved_as_before():
    """One driver's samples are solved each on its own (cheap): nothing is taken from a kept
    motion, so a rocker's return sweep keeps the rates `solve_at` gives."""
    mech = Sources(None).load(library="crank-rocker").mechanism
    req = m.DrawingRequest.model_validate({"source": {"library": "crank-rocker"}, "at": [0.3]})
    assert web_app.motion_sample(mech, req) is None


def test_the_drawing_at_a_sample_draws_the_solve_at_it(gear):
    """`/api/drawing` as the page plays: each frame's points are the sample's from a solve of
    its own, and the whole motion is computed once for all the frames."""
    mech, motion = gear
    client = TestClient(create_app())
    calls = []

    def counted(*args, **kwargs):
        calls.append(kwargs.get("order", 2))
        return whole_motion(*args, **kwargs)

    original = web_app.whole_motion
    web_app.whole_motion = counted
    try:
        for k in SAMPLES:
            for asked in ({"at": [motion.inputs[k].tolist()]}, {"times": [float(motion.time[k])]}):
                r = client.post("/api/drawing", json={
                    "source": {"library": NAME}, "motion": True, **asked,
                    "layers": ["mechanism", "paths", "velocities", "poles"]})
                assert r.status_code == 200, r.text
                doc = r.json()
                scratch = solve_at(mech, **({"inputs": motion.inputs[k:k + 1]} if "at" in asked
                                            else {"times": motion.time[k:k + 1]}))
                assert doc["status"] == str(Status(int(scratch.status[0])))
                for p, xy in doc["points"].items():
                    np.testing.assert_allclose(xy, scratch.point(p).position[0], rtol=0,
                                               atol=1e-9 * mech.length_scale, err_msg=p)
                assert doc["input"] == motion.inputs[k].tolist()
                assert (doc["time"] == motion.time[k]) if "times" in asked else True
    finally:
        web_app.whole_motion = original
    # the drawings' whole motion (order 1, the paths and the fit) and the samples' (order 2)
    assert sorted(calls) == [1, 2]


def test_the_page_asks_the_motion_and_the_frames_share_it(gear):
    """`/api/motion` and the frames' samples are one whole motion: the document's sample k is
    the drawing's at sample k."""
    client = TestClient(create_app())
    doc = client.post("/api/motion", json={"source": {"library": NAME}}).json()
    mech, motion = gear
    assert len(doc["samples"]) == len(motion)
    k = 77
    r = client.post("/api/drawing", json={"source": {"library": NAME}, "motion": True,
                                          "times": [float(motion.time[k])]}).json()
    assert r["time"] == doc["samples"][k]["time"]


def test_the_kept_motions_are_bounded_and_made_once():
    kept = Motions()
    made = []
    mechs = [Sources(None).load(library="crank-rocker").mechanism for _ in range(Motions.SIZE + 1)]
    for i, mech in enumerate(mechs):
        for _ in range(2):
            assert kept.kept(mech, "x", lambda: made.append(i) or i) == i
    assert made == list(range(Motions.SIZE + 1))
    assert not kept.has(mechs[0], "x") and kept.has(mechs[-1], "x")


def test_what_is_kept_warns_and_fails_for_every_request_as_for_the_first():
    """A kept whole motion's LinkworkWarnings reach every request that takes it (the first
    computed it, the later ones only read it), and its LinkworkError is raised again."""
    from linkwork.errors import InputError, LinkworkWarning

    mech = Sources(None).load(library="crank-rocker").mechanism
    made = []

    def warns():
        made.append(1)
        warnings.warn("a singular sample", LinkworkWarning)
        return "motion"

    def fails():
        made.append(2)
        raise InputError("no whole motion")

    for _ in range(2):
        with web_app._warnings() as warned:
            assert web_app._kept(mech, "warns", warns) == "motion"
        assert warned == ["a singular sample"]
        with web_app._warnings(), pytest.raises(InputError, match="no whole motion"):
            web_app._kept(mech, "fails", fails)
    assert made == [1, 2]


def test_a_moved_mechanism_is_played_from_its_kept_motion(monkeypatch):
    """After a drag the page asks for the moved mechanism's whole motion and plays it: its
    frames (the source names the moved point, so the drag's last frame is their `previous`)
    are taken from that motion too, and are the moved mechanism's own solves."""
    client = TestClient(create_app())
    source = {"library": NAME, "points": {"P45": [-1196.0, 352.0]}}
    for x in (-1199.0, -1197.5, -1196.0):  # the drag's frames
        r = client.post("/api/drawing", json={"source": {**source, "points": {"P45": [x, 352.0]}},
                                              "motion": False})
        assert r.status_code == 200, r.text
    doc = client.post("/api/motion", json={"source": source, "detail": "full"}).json()
    moved = Sources(None).load(library=NAME, points=source["points"]).mechanism
    solved = []
    original = web_app.solve_request
    monkeypatch.setattr(web_app, "solve_request", lambda *a, **k: solved.append(1) or original(*a, **k))
    for k in (30, 250):
        sample = doc["samples"][k]
        r = client.post("/api/drawing", json={"source": source, "motion": True,
                                              "at": [sample["input"]]}).json()
        scratch = solve_at(moved, np.array([sample["input"]]))
        for p, xy in r["points"].items():
            np.testing.assert_allclose(xy, scratch.point(p).position[0], rtol=0,
                                       atol=1e-9 * moved.length_scale, err_msg=p)
    assert solved == []


def test_a_sample_of_a_solution_has_its_numbers(gear):
    """`Solution.sample(n)`: the n-th sample alone, every number as in the whole."""
    mech, motion = gear
    for n in (0, 200, -1):
        one = motion.sample(n)
        k = range(len(motion))[n]
        assert len(one) == 1 and one.time.tolist() == [motion.time[k]]
        assert one.status.tolist() == [motion.status[k]]
        np.testing.assert_array_equal(one.inputs, motion.inputs[k:k + 1])
        for p in mech.points:
            for a, b in zip((one.point(p).position, one.point(p).velocity, one.point(p).acceleration),
                            (motion.point(p).position, motion.point(p).velocity,
                             motion.point(p).acceleration)):
                np.testing.assert_array_equal(a, b[k:k + 1])


def test_a_frame_from_what_is_kept_is_answered_in_the_event_loop(gear):
    """`long_drawing`: a frame of a play goes to a worker thread while the whole motion is not
    kept yet, and is answered at once (no hand-over) when it is."""
    from linkwork.web.sources import Loaded

    mech = Sources(None).load(library=NAME).mechanism
    _, motion = gear
    loaded = Loaded(mech, "", NAME)
    req = m.DrawingRequest.model_validate({"source": {"library": NAME}, "motion": True,
                                           "at": [motion.inputs[5].tolist()]})
    assert web_app.long_drawing(loaded, req)
    web_app.drawing(mech, req)
    assert not web_app.long_drawing(loaded, req)
    far = m.DrawingRequest.model_validate({"source": {"library": NAME}, "motion": True,
                                           "at": [motion.inputs[300].tolist()]})
    assert web_app.long_drawing(loaded, far)  # its samples' chunks are not solved yet


def test_a_working_folder_file_keeps_its_mechanism_while_its_text_is_the_same(tmp_path):
    """A file is read again for every request (it may change on disk): while its text is the
    same the mechanism kept for it serves (and so do its kept motions); a changed text gives a
    new one."""
    from linkwork.io import resolve

    text = resolve(f"library:{NAME}")[1]
    (tmp_path / "gear.toml").write_text(text, encoding="utf-8")
    sources = Sources(tmp_path)
    first = sources.load(file="gear.toml")
    assert sources.load(file="gear.toml") is first
    moved = sources.load(file="gear.toml", points={"P45": [-1199.0, 350.0]})
    assert sources.load(file="gear.toml", points={"P45": [-1199.0, 350.0]}) is moved
    (tmp_path / "gear.toml").write_text(text.replace('name = "Heusinger', 'name = "My Heusinger'),
                                        encoding="utf-8")
    again = sources.load(file="gear.toml")
    assert again is not first and again.mechanism.name.startswith("My Heusinger")
    assert sources.load(file="gear.toml", points={"P45": [-1199.0, 350.0]}) is not moved


def test_the_centrodes_are_computed_once_a_motion_and_drawn_as_before(gear, monkeypatch):
    """The centrodes layer depends on the whole motion alone (`Scene.of_motion`): kept with it
    for every frame, each frame's SVG is the one drawn with them computed for that frame."""
    mech, motion = gear
    frames = {}
    for k in (40, 250):
        req = m.DrawingRequest.model_validate({"source": {"library": NAME}, "motion": True,
                                               "times": [float(motion.time[k])],
                                               "layers": ["mechanism", "centrodes"]})
        frames[k] = (req, web_app.drawing(mech, req)["svg"])
    assert "centrode-fixed-" in frames[40][1]
    kept = web_app._kept
    monkeypatch.setattr(web_app, "_kept", lambda mech, what, make:
                        make() if what == "scene" else kept(mech, what, make))
    for req, svg in frames.values():
        assert web_app.drawing(mech, req)["svg"] == svg
