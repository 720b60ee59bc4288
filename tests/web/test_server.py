"""The workbench server under concurrent requests and over-size messages: a drawing that asks
for long work (the whole motion, a fresh march) runs in a worker thread and holds no drag frame
up, which runs in the event loop; uvicorn, set up as `linkwork serve` sets it up, closes a
WebSocket whose message is larger than the API's limit (code 1009) and goes on serving."""

from __future__ import annotations

import asyncio
import json
import threading
import time
import warnings

import httpx
import numpy as np
import pytest

with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the test client's notice about its HTTP library
    from fastapi.testclient import TestClient

import linkwork
from linkwork.cli.serve_cmd import _free_port, server_options
from linkwork.kinematics import continuation
from linkwork.web import app as web_app
from linkwork.web import create_app
from linkwork.web.app import MAX_BODY

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

#: a drag's frame of a four-bar: no whole motion, nothing marched
QUICK = {"source": {"library": "crank-rocker", "points": {"C": [15.5, 25.0]}}, "at": [1.0],
         "layers": ["mechanism"], "motion": False}
#: the valve gear with its whole motion (its paths drawn)
LONG = {"source": {"library": "heusinger-valve-gear"}, "layers": ["mechanism", "paths"]}


class Watched:
    """`web.app.drawing` recording the thread each drawing runs in; a drawing that asks for the
    whole motion waits (after saying it started) until released, and says when it finished."""

    def __init__(self, monkeypatch) -> None:
        self.started, self.release, self.finished = (threading.Event() for _ in range(3))
        self.threads: list[tuple[str, bool, threading.Thread]] = []
        real = web_app.drawing

        def drawing(mech, req, *args, **kwargs):
            self.threads.append((mech.name, req.motion, threading.current_thread()))
            if req.motion:
                self.started.set()
                # in the event loop this would hold everything: the test fails, not hangs
                self.release.wait(10)
                try:
                    return real(mech, req, *args, **kwargs)
                finally:
                    self.finished.set()
            return real(mech, req, *args, **kwargs)

        monkeypatch.setattr(web_app, "drawing", drawing)

    async def until_started(self) -> None:
        deadline = time.monotonic() + 60
        while not self.started.is_set():
            assert time.monotonic() < deadline, "the long drawing never started"
            await asyncio.sleep(0.005)


def test_a_long_drawing_does_not_hold_a_drag_frame_up(monkeypatch):
    watched = Watched(monkeypatch)
    app = create_app(None)

    async def run():
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://test") as client:
            long = asyncio.create_task(client.post("/api/drawing", json=LONG))
            await watched.until_started()
            quick = await client.post("/api/drawing", json=QUICK)
            long_was_done = long.done()
            watched.release.set()
            return quick, long_was_done, await long

    quick, long_was_done, long = asyncio.run(run())
    assert quick.status_code == 200 and long.status_code == 200, (quick.text, long.text)
    assert not long_was_done  # the frame was answered while the long drawing went on
    where = {motion: thread for _, motion, thread in watched.threads}
    assert where[False] is threading.current_thread()  # the frame: in the event loop
    assert where[True] is not threading.current_thread()  # the whole motion: a worker's
    # the answers are those of the drawings asked alone
    alone = TestClient(create_app(None), raise_server_exceptions=False)
    assert quick.json() == alone.post("/api/drawing", json=QUICK).json()
    assert long.json()["svg"] == alone.post("/api/drawing", json=LONG).json()["svg"]


def test_a_long_drawing_over_the_socket_does_not_hold_a_request_up(monkeypatch):
    watched = Watched(monkeypatch)
    with TestClient(create_app(None), raise_server_exceptions=False) as client:  # one loop
        with client.websocket_connect("/api/drawing/ws") as ws:
            ws.send_text(json.dumps(LONG))
            assert watched.started.wait(60)
            quick = client.post("/api/drawing", json=QUICK)
            assert not watched.finished.is_set()  # answered while the long drawing went on
            watched.release.set()
            long = json.loads(ws.receive_text())
    assert quick.status_code == 200 and long["status"] == 200, (quick.text, long)


def fresh_march() -> dict:
    """The valve gear with its first driver turned by 0.5 rad: marched from its design position
    when nothing was solved before."""
    mech = linkwork.load("library:heusinger-valve-gear")
    at = [mech.driver_input_at_design(d) for d in mech.drivers]
    at[0] += 0.5
    return {"source": {"library": "heusinger-valve-gear"}, "at": [at], "motion": False}


@pytest.mark.parametrize("requests_, worker", [
    ([QUICK], [False]),
    ([LONG], [True]),
    # the design position of a mechanism with Newton-solved groups: nothing to march
    ([{"source": {"library": "heusinger-valve-gear"}, "motion": False}], [False]),
    # away from it and nothing solved before: a march from the design position; then a drag's
    # frame carrying that march over
    (["fresh", "frame"], [True, False]),
], ids=["four-bar-frame", "whole-motion", "design-position", "fresh-march-then-frame"])
def test_the_worker_thread_is_chosen_by_what_a_drawing_asks(monkeypatch, requests_, worker):
    watched = Watched(monkeypatch)
    watched.release.set()
    app = create_app(None)
    fresh = fresh_march()
    frame = {**fresh, "source": {**fresh["source"], "points": {"P45": [1.0, 0.0]}}}
    named = {"fresh": fresh, "frame": frame}

    async def run():
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://test") as client:
            for r in requests_:
                got = await client.post("/api/drawing", json=named[r] if isinstance(r, str) else r)
                assert got.status_code == 200, got.text

    asyncio.run(run())
    assert [t is not threading.current_thread() for _, _, t in watched.threads] == worker


def test_a_frame_that_would_wait_for_a_march_elsewhere_waits_in_a_worker(monkeypatch):
    """A march in another thread (a long drawing's) holds every march until it is done: a
    frame that marches waits for it in a worker thread, the others go on in the loop."""
    watched = Watched(monkeypatch)
    watched.release.set()
    app = create_app(None)
    held, done = threading.Event(), threading.Event()

    def march_elsewhere():
        with continuation._marching:
            held.set()
            done.wait(30)

    elsewhere = threading.Thread(target=march_elsewhere)
    elsewhere.start()
    newton = {"source": {"library": "heusinger-valve-gear"}, "motion": False}

    async def run():
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://test") as client:
            waiting = asyncio.create_task(client.post("/api/drawing", json=newton))
            deadline = time.monotonic() + 60
            while not watched.threads:  # the Newton frame handed over
                assert time.monotonic() < deadline
                await asyncio.sleep(0.005)
            quick = await client.post("/api/drawing", json=QUICK)
            was_waiting = not waiting.done()
            done.set()
            return quick, was_waiting, await waiting

    try:
        assert held.wait(30)
        quick, was_waiting, newton_frame = asyncio.run(run())
    finally:
        done.set()
        elsewhere.join(30)
    assert quick.status_code == 200 and newton_frame.status_code == 200
    assert was_waiting
    where = {name: thread for name, _, thread in watched.threads}
    assert where["Heusinger (Walschaerts) valve gear"] is not threading.current_thread()
    assert [t for name, _, t in watched.threads if name != "Heusinger (Walschaerts) valve gear"] \
        == [threading.current_thread()]


@pytest.fixture
def served():
    """The workbench on a real uvicorn in a thread, with `linkwork serve`'s settings."""
    import uvicorn
    port = _free_port("127.0.0.1", 0)
    server = uvicorn.Server(uvicorn.Config(create_app(None), host="127.0.0.1", port=port,
                                           **server_options()))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 60
    while not server.started:
        assert thread.is_alive() and time.monotonic() < deadline, "the server did not start"
        time.sleep(0.01)
    yield f"127.0.0.1:{port}"
    server.should_exit = True
    thread.join(30)


def test_the_servers_websocket_limit_is_the_apis(served):
    from websockets.exceptions import ConnectionClosedError
    from websockets.sync.client import connect

    url = f"ws://{served}/api/drawing/ws"
    with connect(url, max_size=None) as ws:  # as large as the API takes: read and answered
        ws.send(" " * MAX_BODY)
        got = json.loads(ws.recv(timeout=60))
        assert got["status"] == 422 and got["body"]["kind"] == "RequestValidationError"
    with connect(url, max_size=None) as ws:  # one byte more: the socket is closed, 1009
        ws.send(" " * (MAX_BODY + 1))
        with pytest.raises(ConnectionClosedError) as e:
            ws.recv(timeout=60)
        assert e.value.rcvd is not None and e.value.rcvd.code == 1009
    with connect(url) as ws:  # and the server goes on serving
        ws.send(json.dumps(QUICK))
        assert json.loads(ws.recv(timeout=60))["status"] == 200
    r = httpx.post(f"http://{served}/api/drawing", content=b" " * (MAX_BODY + 1),
                   headers={"content-type": "application/json"}, timeout=60)
    assert r.status_code == 413 and r.json()["kind"] == "BodyTooLarge"


def test_a_frames_warnings_are_its_own_whichever_thread_computes_it():
    """The over-closed pantograph's plan warns (made first to choose the thread): the warning
    is the drawing's, in the loop and in a worker thread alike."""
    app = create_app(None)
    base = linkwork.load("library:pantograph")
    point = next(iter(base.points))
    frame = {"source": {"library": "pantograph", "points": {point: base.points[point].tolist()}},
             "motion": False}
    whole = {"source": {"library": "pantograph"}}

    async def run():
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://test") as client:
            return [await client.post("/api/drawing", json=r) for r in (frame, whole)]

    for got in asyncio.run(run()):
        assert got.status_code == 200, got.text
        assert any("over-closed" in w for w in got.json()["warnings"]), got.json()["warnings"]
