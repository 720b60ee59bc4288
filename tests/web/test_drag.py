"""Drag frames over the API: each frame of a drag is a new mechanism (the design points moved);
its Newton-solved groups carry the previous frame's march over (`solve(..., previous=)`), and
the drawing's numbers are still those of a fresh solve of the moved drawing. A jump that takes
the previous frame's poses onto another assembly branch is reported in `march` and not taken."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the test client's notice about its HTTP library
    from fastapi.testclient import TestClient

import linkwork
from linkwork.web import create_app
from linkwork.web.sources import moved

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture
def client():
    return TestClient(create_app(None), raise_server_exceptions=False)


def frame(client, name: str, points: dict, at) -> dict:
    r = client.post("/api/drawing", json={"source": {"library": name, "points": points},
                                          "at": at, "layers": ["mechanism"], "motion": False})
    assert r.status_code == 200, r.text
    return r.json()


def fresh_points(name: str, points: dict, at) -> dict:
    """The points of the moved drawing solved on its own (a new mechanism, nothing carried)."""
    mech = moved(linkwork.load(f"library:{name}"), points)
    sol = linkwork.solve(mech, np.atleast_2d(np.asarray(at, float)).reshape(1, -1))
    return {p: sol.point(p).position[0] for p in mech.points}


def test_a_drag_carries_the_march_from_frame_to_frame(client):
    name, point = "heusinger-valve-gear", "P45"
    base = linkwork.load(f"library:{name}")
    design = [base.driver_input_at_design(d) for d in base.drivers]
    at = [[design[0] + 0.5, design[1]]]
    assert frame(client, name, {}, at)["march"] is None  # as opened and shown before the drag
    marches = []
    for k in range(6):
        a = 2 * math.pi * k / 6
        xy = base.points[point] + 4.0 * np.array([math.cos(a), math.sin(a)])
        doc = frame(client, name, {point: xy.tolist()}, at)
        marches.append(doc["march"])
        want = fresh_points(name, {point: xy}, at)
        for p, got in doc["points"].items():
            np.testing.assert_allclose(got, want[p], rtol=0, atol=1e-9 * base.length_scale)
        assert doc["status"] == "ok"
    assert all(m.startswith("continued from the previous mechanism") for m in marches)


def test_a_change_of_branch_in_a_drag_is_reported_and_not_taken(client):
    name = "alt-eight-link"
    base = linkwork.load(f"library:{name}")
    u = base.driver_input_at_design(base.drivers[0]) + 1.66
    frame(client, name, {}, [u])  # the drawing as opened: the first frame's previous
    xy = base.points["E"] + np.array([45.7, 14.5])  # a jump a Newton solve takes to another branch
    doc = frame(client, name, {"E": xy.tolist()}, [u])
    assert doc["march"].startswith("marched again") and "another assembly branch" in doc["march"]
    want = fresh_points(name, {"E": xy}, [u])
    for p, got in doc["points"].items():
        np.testing.assert_allclose(got, want[p], rtol=0, atol=1e-9 * base.length_scale)


def test_a_closed_form_mechanism_reports_no_march(client):
    doc = frame(client, "crank-rocker", {"C": [15.5, 25.0]}, [1.0])
    assert doc["march"] is None
