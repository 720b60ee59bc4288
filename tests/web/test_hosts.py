"""The workbench on this computer answers only requests addressed to it by its own names
(`web.app._KnownHosts`): a page of another site that has its name resolve to 127.0.0.1 (DNS
rebinding) sends its own name as the Host and gets nothing, neither over HTTP nor the socket."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

from linkwork.cli.serve_cmd import LOCAL_HOSTS
from linkwork.web import create_app

BODY = {"source": {"library": "crank-rocker"}, "layers": ["mechanism"]}


@pytest.fixture(scope="module")
def local():
    return TestClient(create_app(None, hosts=LOCAL_HOSTS), raise_server_exceptions=False)


@pytest.mark.parametrize("host", ["127.0.0.1:8765", "localhost:8765", "[::1]:8765", "localhost"])
def test_this_computers_names_are_answered(local, host):
    r = local.get("/api/library", headers={"host": host})
    assert r.status_code == 200 and "crank-rocker" in r.text


@pytest.mark.parametrize("host", ["attacker.example:8765", "attacker.example", "127.0.0.1.nip.io",
                                  "", "[::1"])
def test_another_name_is_refused_with_a_clear_error(local, host):
    r = local.get("/api/library", headers={"host": host})
    assert r.status_code == 400
    body = r.json()
    assert body["kind"] == "UnknownHost" and "127.0.0.1" in body["error"]
    assert local.post("/api/drawing", json=BODY, headers={"host": host}).status_code == 400
    assert local.get("/", headers={"host": host}).status_code == 400


def test_the_socket_is_refused_to_another_name(local):
    with pytest.raises(WebSocketDisconnect) as exc:
        with local.websocket_connect("/api/drawing/ws", headers={"host": "attacker.example"}) as ws:
            ws.send_json(BODY)
            ws.receive_json()
    assert exc.value.code == 1008
    with local.websocket_connect("/api/drawing/ws", headers={"host": "127.0.0.1:8765"}) as ws:
        ws.send_json(BODY)
        assert ws.receive_json()["status"] == 200


def test_an_app_made_without_hosts_answers_any():
    assert TestClient(create_app(None)).get("/api/library").status_code == 200
