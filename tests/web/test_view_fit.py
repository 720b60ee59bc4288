"""The workbench's view of the whole motion holds every element drawn: a Geneva or star wheel's
cross turns within its rim, which the view must hold at every position (the audit saw a third
of the Geneva wheel cut off: the fit knew cam profiles, not indexing wheels)."""

from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

import linkwork
from linkwork.web import create_app


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(None), raise_server_exceptions=False)


@pytest.mark.parametrize("name", ["geneva-4", "geneva-6"])
def test_the_view_holds_the_wheel_at_every_position(client, name):
    mech = linkwork.load(f"library:{name}")
    r = client.post("/api/drawing", json={"source": {"library": name}, "layers": ["mechanism"],
                                           "motion": True, "fit": "motion"})
    assert r.status_code == 200, r.text
    t = r.json()["transforms"]["mechanism"]
    lo, hi = np.array(t["lo"]), np.array(t["hi"])
    # the cross's rim passes through the slots' mouths, where the pin enters them at right
    # angles to the driver's crank (shock-free entry, Pöschl §25a): at sqrt(D² − r²) from the
    # wheel's centre C (D = MC the centre distance, r = MB the pin's radius); the cross turns
    # within that circle
    M, B, C = (np.asarray(mech.points[p], float) for p in ("M", "B", "C"))
    reach = np.sqrt(np.sum((C - M) ** 2) - np.sum((B - M) ** 2))
    assert np.all(lo <= C - reach) and np.all(C + reach <= hi), (lo, hi, C, reach)


def test_a_drag_frame_with_a_held_view_does_not_march_the_whole_motion(client, monkeypatch):
    """A drag's frame (motion left out, the view of the drawing the drag began on held) is
    drawn from its own position: the whole motion of the moved mechanism is not computed for
    it (it was, for the held view's scales: the valve gear's frame took 60 ms more)."""
    from linkwork.drawing import layers

    first = client.post("/api/drawing", json={"source": {"library": "crank-rocker"},
                                              "layers": ["mechanism", "velocities"]}).json()
    t = first["transforms"]["mechanism"]

    def no_motion(*a, **k):
        raise AssertionError("the whole motion was computed for a drag frame")

    monkeypatch.setattr(layers, "whole_motion", no_motion)
    r = client.post("/api/drawing", json={
        "source": {"library": "crank-rocker", "points": {"C": [15.5, 25.0]}},
        "layers": ["mechanism", "velocities"], "motion": False,
        "view": {"lo": t["lo"], "hi": t["hi"], "per_mm": t["per_mm"]}})
    assert r.status_code == 200, r.text
    assert r.json()["transforms"]["mechanism"]["per_mm"] == t["per_mm"]


def test_a_drag_frame_holds_the_vectors_scales_it_is_given(client):
    """The first drawing (the whole motion known) says its scales; a drag frame given them in
    its view draws its vectors at those scales (its own position alone would choose others:
    the vectors would change length when the drag begins), and says so."""
    body = {"source": {"library": "crank-rocker"}, "layers": ["mechanism", "velocities", "accelerations"]}
    first = client.post("/api/drawing", json=body).json()
    scales, t = first["scales"], first["transforms"]["mechanism"]
    assert scales["length"] == t["per_mm"] and scales["velocity"] > 0 and scales["acceleration"] > 0
    moved = {**body, "source": {"library": "crank-rocker", "points": {"C": [15.5, 25.0]}},
             "motion": False}
    own = client.post("/api/drawing", json={**moved, "view": {
        "lo": t["lo"], "hi": t["hi"], "per_mm": t["per_mm"]}}).json()["scales"]
    held = client.post("/api/drawing", json={**moved, "view": {
        "lo": t["lo"], "hi": t["hi"], "per_mm": t["per_mm"], "velocity_per_mm": scales["velocity"],
        "acceleration_per_mm": scales["acceleration"]}}).json()
    assert held["scales"] == scales
    assert own["velocity"] != scales["velocity"]  # the frame alone would choose another
    svg = held["svg"]
    assert f"{scales['velocity']:g} mm/s" in svg.replace("\u2009", " ")
    bad = client.post("/api/drawing", json={**moved, "view": {
        "lo": t["lo"], "hi": t["hi"], "per_mm": t["per_mm"], "velocity_per_mm": -1}})
    assert bad.status_code == 422
