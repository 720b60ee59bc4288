"""The drawing socket (`/api/drawing/ws`) answers as `/api/drawing` does: for each request the
HTTP answer's status and the very same JSON body (the drawing, or the error with the engine's
message); only pages of the server itself may connect."""

from __future__ import annotations

import json
import math
import warnings

import pytest

with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the test client's notice about its HTTP library
    from fastapi.testclient import TestClient
    from starlette.websockets import WebSocketDisconnect

from linkwork.web import create_app
from linkwork.web.app import MAX_BODY

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

FRAME = {"source": {"library": "crank-rocker", "points": {"C": [15.5, 25.0]}}, "at": [1.0],
         "layers": ["mechanism"], "motion": False}

# A moved from (0, 10) to (0, 25), a crank of 25, turned to 180°: A at (−25, 0), |A O4| = 65 >
# coupler + rocker = √925 + √1000 ≈ 62.0, the chain cannot close (the page's drag test's case)
UNASSEMBLABLE = {**FRAME, "source": {"library": "crank-rocker", "points": {"A": [0.0, 25.0]}},
                 "at": [math.pi]}


@pytest.fixture
def client():
    return TestClient(create_app(None), raise_server_exceptions=False)


def both(client, request) -> tuple[dict, object]:
    """The socket's answer to `request` (a dict, or the message's text) and the HTTP one's."""
    text = request if isinstance(request, str) else json.dumps(request)
    with client.websocket_connect("/api/drawing/ws") as ws:
        ws.send_text(text)
        got = json.loads(ws.receive_text())
    return got, client.post("/api/drawing", content=text,
                            headers={"content-type": "application/json"})


@pytest.mark.parametrize("request_", [
    FRAME,
    {**FRAME, "layers": ["mechanism", "poles", "velocities"]},
    UNASSEMBLABLE,
    {**FRAME, "source": {"library": "no-such-mechanism"}},  # 404
    {**FRAME, "layers": "mechanism", "at": "one"},  # 422, pydantic's words
    "{not json",  # 422
], ids=["frame", "layers", "unassemblable", "unknown", "invalid", "not-json"])
def test_the_socket_answers_as_the_http_api(client, request_):
    got, http = both(client, request_)
    assert got["status"] == http.status_code
    assert got["body"] == http.json()
    assert set(got["timing"]) >= {"cpu", "app"}


def test_an_unassemblable_frame_carries_the_engines_message(client):
    got, _ = both(client, UNASSEMBLABLE)
    assert got["status"] == 400 and "cannot be assembled" in got["body"]["error"]


def test_a_drag_over_the_socket_carries_the_march_as_over_http(client):
    """Several frames on one socket: each the drawing HTTP gives for the same request after
    the same previous frames (the previous frame's march is per source, socket or not)."""
    frames = [{**FRAME, "source": {"library": "heusinger-valve-gear",
                                   "points": {"P45": [x, 0.0]}}, "at": None}
              for x in (0.0, 1.0, 2.0)]
    sock, http = [], []
    with client.websocket_connect("/api/drawing/ws") as ws:
        for f in frames:
            ws.send_text(json.dumps(f))
            sock.append(json.loads(ws.receive_text()))
    other = TestClient(create_app(None), raise_server_exceptions=False)
    for f in frames:
        http.append(other.post("/api/drawing", json=f).json())
    assert [s["status"] for s in sock] == [200, 200, 200]
    assert [s["body"] for s in sock] == http
    assert sock[-1]["body"]["march"] is None or "previous" in sock[-1]["body"]["march"]


def test_a_message_over_the_size_limit_is_refused(client):
    with client.websocket_connect("/api/drawing/ws") as ws:
        ws.send_text(" " * (MAX_BODY + 1))
        got = json.loads(ws.receive_text())
        assert got["status"] == 413 and got["body"]["kind"] == "BodyTooLarge"
        ws.send_text(json.dumps(FRAME))  # the socket stays open for the next frame
        assert json.loads(ws.receive_text())["status"] == 200


def test_bytes_that_are_not_json_are_refused_as_over_http(client):
    with client.websocket_connect("/api/drawing/ws") as ws:
        ws.send_bytes(b"\xff\xfe")
        got = json.loads(ws.receive_text())
    http = client.post("/api/drawing", content=b"\xff\xfe", headers={"content-type": "application/json"})
    assert (got["status"], got["body"]) == (http.status_code, http.json())
    assert got["status"] == 422


def test_another_sites_page_may_not_connect(client):
    with pytest.raises(WebSocketDisconnect) as e:
        with client.websocket_connect("/api/drawing/ws",
                                      headers={"origin": "http://elsewhere.example"}):
            pass
    assert e.value.code == 1008
    with client.websocket_connect("/api/drawing/ws",
                                  headers={"origin": "http://testserver"}) as ws:
        ws.send_text(json.dumps(FRAME))
        assert json.loads(ws.receive_text())["status"] == 200
