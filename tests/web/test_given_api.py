"""The workbench's API on a chain driven by given point velocities (library: Rosenauer 1937,
paper 2's free chains): solved, its poles, its velocity plan and its drawing at the drawn
position; an input value is refused with its reason."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from linkwork.web.app import create_app

SOURCE = {"library": "rosenauer-free-watt-chain"}


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    return TestClient(create_app(tmp_path_factory.mktemp("work")), raise_server_exceptions=False)


def test_solve_poles_plan_and_drawing(client):
    doc = client.post("/api/solve", json={"source": SOURCE}).json()
    assert doc["drivers"] == [] and len(doc["samples"]) == 1
    assert client.post("/api/poles", json={"source": SOURCE}).status_code == 200
    r = client.post("/api/construction", json={"source": SOURCE, "name": "velocity-plan"})
    assert r.status_code == 200
    assert "given: a = o + v_A" in r.json()["steps"]
    assert client.post("/api/drawing", json={"source": SOURCE}).json()["svg"].lstrip().startswith("<")


def test_an_input_value_is_refused(client):
    r = client.post("/api/solve", json={"source": SOURCE, "at": [0.5]})
    assert r.status_code == 400 and "drawn position only" in r.json()["error"]


def test_moving_a_design_point_keeps_the_given_data():
    import linkwork
    from linkwork.web.sources import moved

    mech = linkwork.load("library:rosenauer-free-watt-chain")
    m2 = moved(mech, {"D": [2.0, 1.0]})
    assert [(g.point, g.kind) for g in m2.given] == [(g.point, g.kind) for g in mech.given]
