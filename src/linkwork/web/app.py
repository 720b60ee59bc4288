"""The workbench's ASGI application: the Python API over HTTP (JSON in and out, the names and
units of the command line's JSON) and the page that draws with it.

Safe by design: every request is validated by the pydantic models of `.models` and its body is
limited in size; no user text is evaluated (TOML is parsed, quantities are parsed by `units`);
files are read only from the library and the working folder (`.sources`); a `LinkworkError`
becomes a 4xx answer with its message, anything else a 500 answer without a trace.
"""

from __future__ import annotations

import json
import threading
import time
import tomllib
import warnings
from contextlib import asynccontextmanager, contextmanager
from contextvars import ContextVar
from importlib import resources
from pathlib import Path
from typing import Iterable, Iterator
from urllib.parse import urlsplit

import numpy as np
from fastapi import FastAPI, Request, WebSocket, WebSocketDisconnect
from fastapi.encoders import jsonable_encoder
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse, Response
from fastapi.staticfiles import StaticFiles
from starlette.concurrency import run_in_threadpool
from pydantic import ValidationError

from ..errors import LinkworkError, LinkworkWarning, InputError, UnknownMechanismError
from ..kinematics import Solution, Status, compiled_loops, solve, solve_at, whole_motion
from ..kinematics.at import require_assembled
from ..kinematics.export import to_document
from ..kinematics import warmup
from ..kinematics.continuation import carried, follow, input_weights, marching
from ..kinematics.solver import driver_samples, plan
from ..kinematics.warmup import compile_kernels
from ..model import Mechanism, Prismatic
from . import models as m
from .sources import MOTIONS, Loaded, Sources

#: the largest request body accepted (a mechanism text of MAX_TEXT and its options)
MAX_BODY = 1_000_000
STATIC = Path(str(resources.files("linkwork") / "web" / "static"))


class _BodyLimit:
    """Refuse request bodies above `limit` bytes, announced or streamed (413): the body is read
    here, counted, and handed on whole."""

    def __init__(self, app, limit: int) -> None:
        self.app, self.limit = app, limit

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        too_large = _error(*_too_large(self.limit))
        length = dict(scope.get("headers") or []).get(b"content-length")
        if length is not None and (not length.isdigit() or int(length) > self.limit):
            return await too_large(scope, receive, send)
        parts, size, more = [], 0, True
        while more:
            message = await receive()
            if message["type"] != "http.request":  # the client went away
                return
            parts.append(message.get("body", b""))
            size += len(parts[-1])
            if size > self.limit:
                return await too_large(scope, receive, send)
            more = message.get("more_body", False)
        body = {"type": "http.request", "body": b"".join(parts), "more_body": False}
        sent = False

        async def replay():
            nonlocal sent
            if not sent:
                sent = True
                return body
            return await receive()

        return await self.app(scope, replay, send)


class _KnownHosts:
    """Answer only requests addressed to this computer by one of `hosts` (the Host header, the
    port aside): a page of another site may make the browser resolve its own name to
    127.0.0.1 (DNS rebinding) and would then read the working folder's files through the
    workbench as a page of its "own" origin. Its requests carry its name as their Host."""

    def __init__(self, app, hosts: frozenset[str]) -> None:
        self.app, self.hosts = app, hosts

    async def __call__(self, scope, receive, send):
        if scope["type"] not in ("http", "websocket"):
            return await self.app(scope, receive, send)
        host = dict(scope.get("headers") or []).get(b"host", b"").decode("latin-1")
        try:
            name = urlsplit("//" + host).hostname or ""
        except ValueError:
            name = ""
        if name in self.hosts:
            return await self.app(scope, receive, send)
        if scope["type"] == "websocket":
            return await send({"type": "websocket.close", "code": 1008})
        return await _error(400, f"this workbench answers requests to {', '.join(sorted(self.hosts))} "
                                 f"only, not to '{host}'", "UnknownHost")(scope, receive, send)


class _ServerTiming:
    """The whole request's time in the server (routing, validation, the work, the encoding) as
    `app` in the answer's Server-Timing header, after the stages the endpoint measured itself
    (`Stages`): the browser's developer tools show them, bench/bench_workbench.py reads them."""

    def __init__(self, app) -> None:
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http" or not scope.get("path", "").startswith("/api/"):
            return await self.app(scope, receive, send)
        t0 = time.perf_counter()

        async def timed(message):
            if message["type"] == "http.response.start":
                headers = list(message.get("headers") or [])
                total = f"app;dur={(time.perf_counter() - t0) * 1e3:.2f}".encode()
                for k, (name, value) in enumerate(headers):
                    if name.lower() == b"server-timing":
                        headers[k] = (name, value + b", " + total)
                        break
                else:
                    headers.append((b"server-timing", total))
                message = {**message, "headers": headers}
            await send(message)

        return await self.app(scope, receive, timed)


class Stages:
    """Milliseconds per stage of a request (wall clock; `cpu` the thread's CPU time, which
    other processes on a shared machine do not stretch), written as a Server-Timing header."""

    def __init__(self) -> None:
        self.ms: dict[str, float] = {}
        self.cpu0 = time.thread_time()
        self._cpu_before = 0.0  # ms of CPU in the thread the request left (`handed_over`)
        self._cpu_total: float | None = None

    def handed_over(self, cpu_before: float) -> None:
        """The request's work goes on in this thread (a worker's) after `cpu_before` ms of CPU
        in the event loop's; the CPU time is taken at `done`, in this thread."""
        self._cpu_before, self.cpu0 = cpu_before, time.thread_time()

    def done(self) -> None:
        """The work is done: the CPU time is what it is now (read in any thread after)."""
        self._cpu_total = self.cpu()

    def cpu(self) -> float:
        """CPU ms of the request so far."""
        if self._cpu_total is not None:
            return self._cpu_total
        return self._cpu_before + (time.thread_time() - self.cpu0) * 1e3

    @contextmanager
    def __call__(self, name: str) -> Iterator[None]:
        t = time.perf_counter()
        try:
            yield
        finally:
            self.ms[name] = self.ms.get(name, 0.0) + (time.perf_counter() - t) * 1e3

    def header(self) -> str:
        ms = {**self.ms, "cpu": self.cpu()}
        return ", ".join(f"{k};dur={v:.2f}" for k, v in ms.items())


def _error(status: int, message: str, kind: str) -> JSONResponse:
    return JSONResponse({"error": message, "kind": kind}, status_code=status)


def _failure(exc: Exception) -> tuple[int, str, str]:
    """(status, message, kind) of an answer that failed with `exc`, over HTTP and the socket
    alike: a LinkworkError's own message (404 for an unknown mechanism, else 400), anything
    else a 500 without a trace."""
    if isinstance(exc, LinkworkError):
        status = 404 if isinstance(exc, UnknownMechanismError) else 400
        return status, str(exc), type(exc).__name__
    return 500, f"internal error in linkwork ({type(exc).__name__}); please report it", "InternalError"


def _too_large(limit: int) -> tuple[int, str, str]:
    """(status, message, kind) of a request body above `limit` bytes."""
    return 413, f"the request body is larger than {limit} bytes", "BodyTooLarge"


def _validation_message(exc: RequestValidationError | ValidationError | list) -> str:
    parts = []
    for e in (exc if isinstance(exc, list) else exc.errors())[:5]:
        loc = ".".join(str(x) for x in e.get("loc", ()) if x != "body")
        parts.append(f"{loc or 'request'}: {e.get('msg', 'invalid')}")
    return "; ".join(parts)


#: the warnings list of the request this thread (or task) works for, if any (`_warnings`)
_COLLECTING: ContextVar[list[str] | None] = ContextVar("linkwork_request_warnings", default=None)
_ROUTER_LOCK = threading.Lock()
_shown_before = warnings.showwarning  # where the warnings of no request go (`_route_warnings`)


def _routed(message, category, filename, lineno, file=None, line=None):
    """`warnings.showwarning` of the server: a LinkworkWarning raised for a request goes to that
    request's list; any other warning where it went before."""
    out = _COLLECTING.get()
    if out is not None and issubclass(category, LinkworkWarning):
        out.append(str(message))
    else:
        _shown_before(message, category, filename, lineno, file, line)


def _route_warnings() -> None:
    """Put `_routed` in place (again, if a `warnings.catch_warnings` around the server, as a
    test's, restored another), with every LinkworkWarning shown each time it is raised."""
    global _shown_before
    with _ROUTER_LOCK:
        if warnings.showwarning is not _routed:
            _shown_before, warnings.showwarning = warnings.showwarning, _routed
        always = ("always", None, LinkworkWarning, None, 0)
        if not warnings.filters or warnings.filters[0] != always:
            warnings.filterwarnings("always", category=LinkworkWarning)


@contextmanager
def _collected() -> Iterator[list[str]]:
    """The LinkworkWarnings raised inside, for this thread or task alone (`_routed`)."""
    out: list[str] = []
    _route_warnings()
    token = _COLLECTING.set(out)
    try:
        yield out
    finally:
        _COLLECTING.reset(token)


@contextmanager
def _warnings(compiled: bool = False) -> Iterator[list[str]]:
    """Collect the LinkworkWarnings raised inside (as the command line prints them); the
    kinematics' loops run compiled inside once the server has them (`compile_kernels`).

    Not `warnings.catch_warnings`: it swaps the module's global state in and out, so two
    requests in two threads (a long drawing in a worker thread, a drag's frame in the event
    loop) could take each other's warnings or leave a dead list in place. The list is a context
    variable instead, which each thread and task has its own of."""
    with _collected() as out, \
            compiled_loops(True if compiled and warmup.READY.is_set() else None):
        yield out
    out[:] = dict.fromkeys(out)


def _finite(x) -> float | None:
    """A number of the JSON: null where it is not finite (an unreachable sample's error bound)."""
    x = float(x)
    return x if np.isfinite(x) else None


def solve_request(mech: Mechanism, req: m.At, order: int | None = None,
                  previous: Mechanism | None = None) -> Solution:
    """Solve where the request says: its inputs, its times, or the design position
    (`kinematics.solve_at`). `previous`: the mechanism of the drag's previous frame
    (`Loaded.previous`), whose march the Newton-solved groups carry over."""
    values = req.at
    n = len(mech.drivers)
    if values is not None and n and isinstance(values[0], list):
        bad = [len(v) for v in values if len(v) != n]
        if bad:
            raise InputError(f"at: every sample needs one value per driver ({n}: "
                             f"{', '.join(d.joint for d in mech.drivers)}), got {bad[0]}")
        values = np.asarray(values, float)
    elif values is not None and n:
        if n != 1:
            raise InputError(f"mechanism '{mech.name}' has {n} drivers: give at as one list "
                             f"of {n} values per sample")
        values = np.asarray(values, float)[:, None]
    times = None if req.times is None else np.asarray(req.times, float)
    return solve_at(mech, values, times=times, order=order, previous=previous, asked="at or times")


def _kept(mech: Mechanism, what, make):
    """`make()` computed once for `mech` and kept (`sources.MOTIONS`), with the LinkworkWarnings
    it raised and the LinkworkError it ended in: each later request gets them as the first did."""
    def run():
        with _collected() as out:
            try:
                return make(), None, out
            except LinkworkError as exc:
                return None, exc, out

    value, error, warned = MOTIONS.kept(mech, what, run)
    collecting = _COLLECTING.get()
    if collecting is not None:
        collecting.extend(warned)
    else:
        for text in warned:
            warnings.warn(text, LinkworkWarning, stacklevel=2)
    if error is not None:
        raise error
    return value


def kept_motion(mech: Mechanism, order: int = 2) -> Solution:
    """`whole_motion(mech, order=order)`, computed once per mechanism: `/api/motion`, the
    scene's paths and fit (order 1, as `Scene.motion`) and the samples a play draws."""
    return _kept(mech, ("motion", order), lambda: whole_motion(mech, order=order))


#: samples of the whole motion per solve of `_Played` (each solve's end kept: a position between
#: samples is marched from the nearest one, at most half of this many samples away)
PLAY_CHUNK = 10


class _Played:
    """The whole motion's inputs solved by inputs, as `solve_at` solves them (the drivers'
    constant speeds, not the motion laws' rates), in chunks of `PLAY_CHUNK` samples each going
    on from where the one before left the path (`solve(..., resume=)`: the same numbers as one
    solve), as far as the samples asked so far need (a play asks them in order) — so that
    every chunk's end is kept, for a position between samples to be marched from (`carried`)."""

    def __init__(self, mech: Mechanism, inputs: np.ndarray) -> None:
        self.mech, self.inputs = mech, inputs
        self.parts: list[Solution] = []
        self.weights = input_weights(mech)
        self._lock = threading.Lock()

    def _upto(self, n: int) -> None:
        """Solve the chunks up to the one of sample `n`."""
        with self._lock:
            while len(self.parts) <= n // PLAY_CHUNK:
                lo = len(self.parts) * PLAY_CHUNK
                end = self.parts[-1].path_end if self.parts else None
                self.parts.append(solve(self.mech, self.inputs[lo:lo + PLAY_CHUNK], resume=end))

    def _weighted(self, values: np.ndarray | None, times: np.ndarray | None) -> np.ndarray:
        """The inputs asked (at `times`: the laws'), in the march's metric (`input_weights`)."""
        u = values if times is None else driver_samples(self.mech, times=times)[1]
        return u[0] * self.weights

    def nearest(self, values: np.ndarray | None, times: np.ndarray | None) -> int:
        """The sample nearest to the inputs asked (the first of equals)."""
        u = self._weighted(values, times)
        return int(np.argmin(np.linalg.norm(self.inputs * self.weights - u, axis=1)))

    def ready(self, n: int) -> bool:
        """Whether sample `n` needs at most a few chunks solved (a play's next frames)."""
        return n // PLAY_CHUNK < len(self.parts) + 2

    def sample(self, n: int) -> Solution:
        self._upto(n)
        return self.parts[n // PLAY_CHUNK].sample(n % PLAY_CHUNK)

    def carried(self, values: np.ndarray | None, times: np.ndarray | None) -> Solution:
        """The solve at `values` (one sample's inputs) or `times` (one time), its path going on
        from the kept chunk end nearest to its inputs (or from the design position, if that is
        nearer): a march of a few samples' length instead of one from the design position."""
        mech = self.mech
        u = self._weighted(values, times)
        self._upto(self.nearest(values, times))
        design = np.array([mech.driver_input_at_design(d) for d in mech.drivers]) * self.weights
        ends = [None] + [p.path_end for p in self.parts if p.path_end is not None]
        start = ends[int(np.argmin([np.linalg.norm(u - (design if e is None else e.vertex))
                                    for e in ends]))]
        if times is not None:
            return solve(mech, times=times, resume=start)
        return solve(mech, values, resume=start)


def _one_position(mech: Mechanism, req: m.At) -> tuple | None:
    """(values, times) of a request for one position of a mechanism of several drivers, one
    of them None (each as `solve` takes them); None for any other request."""
    if len(mech.drivers) < 2 or mech.given:
        return None
    if req.times is not None and len(req.times) == 1:
        return None, np.asarray(req.times, float)
    if req.at is not None and len(req.at) == 1 and isinstance(req.at[0], list) \
            and len(req.at[0]) == len(mech.drivers):
        return np.asarray(req.at, float), None
    return None


def _from_motion(mech: Mechanism, req: m.DrawingRequest, previous: Mechanism | None) -> bool:
    """Whether a drawing takes its position from the whole motion kept (`motion_sample`): one
    with the whole motion, at one position of several drivers; of a moved mechanism (a drag's
    `previous` given) only once its whole motion was asked for (the page plays it), while a
    drag's frames carry their march from frame to frame."""
    return req.motion and _one_position(mech, req) is not None and (
        previous is None or MOTIONS.has(mech, ("motion", 2)))


def _kept_play(mech: Mechanism) -> tuple[Solution, _Played]:
    """The whole motion kept for `mech` and its inputs as `_Played` solves them."""
    motion = kept_motion(mech)
    return motion, _kept(mech, "played", lambda: _Played(mech, motion.inputs))


def _played_ready(mech: Mechanism, req: m.At) -> bool:
    """Whether `motion_sample` would take the request's position from what is kept already,
    solving a few samples at most (so that the drawing is short work)."""
    if not (MOTIONS.has(mech, ("motion", 2)) and MOTIONS.has(mech, "played")):
        return False
    values, times = _one_position(mech, req)
    try:
        motion, played = _kept_play(mech)
    except LinkworkError:
        return False  # solved alone (`solve_request`): a march from the design position
    if times is not None and motion.time is not None and (motion.time == times[0]).any():
        return True
    return played.ready(played.nearest(values, times))


def motion_sample(mech: Mechanism, req: m.At) -> Solution | None:
    """The position a drawing asks for, from the whole motion kept for `mech`: its sample when
    the request's input (or time) is one of its samples (to the bit), else a solve whose path
    goes on from the kept sample nearest to it; None when there is nothing kept to take it from
    (to be solved as `solve_request` solves it).

    Only for several drivers: their solve follows the path of the inputs from the design
    position, so that a sample far along the motion costs a march of that length, while one
    driver's samples are solved each on its own from a march kept per mechanism. Asked by
    `times`: the whole motion's sample at that time (it is solved by times). Asked by `at`:
    the whole motion's inputs solved by inputs (`_Played`: `solve_at`'s rates), kept beside it.
    The answers are `solve_at`'s to rounding (the march's path differs, not its branch)."""
    asked = _one_position(mech, req)
    if asked is None:
        return None
    values, times = asked
    try:
        motion, played = _kept_play(mech)
    except LinkworkError:  # no whole motion: the position is solved (and its error given) alone
        return None
    if times is not None:
        hits = np.flatnonzero(motion.time == times[0]) if motion.time is not None else ()
        if len(hits):
            return motion.sample(int(hits[0]))
    else:
        hits = np.flatnonzero((played.inputs == values[0]).all(axis=1))
        if hits.size:
            return played.sample(int(hits[0]))
    return played.carried(values, times)


def _json(doc) -> str:
    """JSON text as the API's answers write it (`JSONResponse`: NaN refused, UTF-8 kept)."""
    return json.dumps(jsonable_encoder(doc), ensure_ascii=False, allow_nan=False,
                      separators=(",", ":"))


async def _socket_drawing(message: dict, answer) -> tuple[int, "Stages", str]:
    """One drawing request of the socket answered as `/api/drawing` answers it (`answer`, a
    coroutine function of the request): (status, the stages, the JSON body), an error as its
    exception handlers write it."""
    stage = Stages()
    data = message.get("text")
    if data is None:
        data = message.get("bytes") or b""
    size = len(data.encode() if isinstance(data, str) else data)
    try:
        if size > MAX_BODY:
            status, message, kind = _too_large(MAX_BODY)
            return status, stage, _json({"error": message, "kind": kind})
        # as FastAPI reads a body: the JSON parsed, then the Python object validated (so that
        # the messages are the HTTP API's word for word)
        try:
            req = m.DrawingRequest.model_validate(json.loads(data))
        except ValidationError as exc:
            errors = exc.errors()
        except ValueError as exc:  # not JSON, or bytes that are not UTF-8
            errors = [{"loc": ("body", getattr(exc, "pos", 0)), "msg": "JSON decode error"}]
        else:
            text, stage = await answer(req)
            return 200, stage, text
        return 422, stage, _json({"error": _validation_message(errors),
                                  "kind": "RequestValidationError"})
    except Exception as exc:  # noqa: BLE001 - never a trace to the page, as over HTTP
        status, message, kind = _failure(exc)
        return status, stage, _json({"error": message, "kind": kind})


def mechanism_info(loaded, warned: list[str]) -> dict:
    from ..constructions import CONSTRUCTIONS
    from ..drawing import LAYERS
    mech = loaded.mechanism
    return {
        "name": mech.name, "description": mech.description, "source": loaded.label,
        "text": loaded.text, "units": {"length": mech.length_unit, "angle": "rad", "time": "s"},
        "frame": mech.frame,
        "points": {p: [float(v) for v in xy] for p, xy in mech.points.items()},
        "links": {ln.name: list(ln.points) for ln in mech.links},
        "owners": dict(mech.point_owner),
        "joints": [{"name": j.name, "type": j.kind, "links": list(j.links),
                    "point": getattr(j, "point", None)} for j in mech.joints],
        "drivers": [{"joint": d.joint,
                     "kind": "prismatic" if isinstance(mech.joint(d.joint), Prismatic) else "revolute",
                     "design_input": mech.driver_input_at_design(d)} for d in mech.drivers],
        "layers": [name for name in LAYERS if name != "construction"],
        "constructions": list(CONSTRUCTIONS),
        "warnings": warned,
    }


def long_drawing(loaded: Loaded, req: m.DrawingRequest) -> bool:
    """Whether the drawing asks for work that may take long (seconds for a large mechanism),
    by what it asks, not by a clock: the whole motion (`motion`), or of a mechanism with
    Newton-solved groups a position away from the design one with no previous frame whose
    march it carries over (a march from the design position: a drag's frames carry theirs),
    or any march while another thread marches (it would wait for that one)."""
    mech = loaded.mechanism
    if req.motion:  # unless the whole motion is kept, and the position is one of its samples
        if not MOTIONS.has(mech, ("motion", 1)):
            return True
        if _from_motion(mech, req, loaded.previous):  # a sample, or a short march from one
            return not _played_ready(mech, req) or marching()
    if loaded.previous is not None:  # (as the solve will: its plan takes the previous one's)
        follow(mech, loaded.previous)
    if not any(s.kind == "generic" for s in plan(mech)):
        return False
    if marching():
        return True
    return loaded.previous is None and (req.at is not None or req.times is not None)


def drawing(mech: Mechanism, req: m.DrawingRequest, previous: Mechanism | None = None,
            stage: Stages | None = None) -> dict:
    """The drawing of `linkwork draw` for the request, with what the page needs beside it
    (`previous`: the drag's previous frame, see `solve_request`; `stage`: times the solve, the
    scene and the SVG)."""
    stage = stage or Stages()
    with stage("solve"):
        sol = motion_sample(mech, req) if _from_motion(mech, req, previous) else None
        if sol is None:
            sol = solve_request(mech, req, previous=previous)
    if len(sol) != 1:
        raise InputError(f"a drawing shows one position; got {len(sol)} samples")
    require_assembled(sol, 0, "the design position" if req.at is None and req.times is None
                      else None)
    with stage("scene"):
        fig, steps, scales = _figure(mech, sol, req)
    with stage("svg"):
        svg, transforms = fig.svg_and_transforms()
    return {"svg": svg, "status": str(Status(int(sol.status[0]))),
            "input": [None if not np.isfinite(v) else float(v) for v in sol.inputs[0]],
            "time": None if sol.time is None else float(sol.time[0]),
            "points": {p: (None if not np.all(np.isfinite(xy)) else [float(xy[0]), float(xy[1])])
                       for p in mech.points for xy in [sol.point(p).position[0]]},
            "poses": {ln: (None if not np.all(np.isfinite(q)) else [float(v) for v in q])
                      for ln in mech.link_names for q in [sol.pose_derivatives(ln)[0, 0]]},
            "transforms": transforms, "steps": steps, "scales": scales,
            "march": None if carried(mech) is None else str(carried(mech))}


def _scene_motion(mech: Mechanism) -> Solution | None:
    """`Scene.motion` (the whole motion to order 1, None where there is none), kept."""
    try:
        return kept_motion(mech, order=1)
    except LinkworkError:
        return None


def _figure(mech: Mechanism, sol: Solution, req: m.DrawingRequest):
    """The scene's figure for the request's layers and construction, the construction's step
    texts, and the drawing's scales (units per mm: a drag holds them, `m.View`)."""
    from ..constructions import construct
    from ..drawing import Scene, scene_figure

    sc = Scene(mech, sol)
    if req.motion:  # the whole motion kept (`Scene.motion`), and what the layers draw of it
        sc.motion = _scene_motion(mech)
        sc.motion_kept = _kept(mech, "scene", dict)
    if not req.motion:
        sc.motion = None  # what the layers draw when the whole motion is not known
    if req.view is not None and not req.construction:
        # the held view's length scale (a construction has its own); the rest from this frame,
        # as every frame without the whole motion (a drag's) takes them: not from a whole
        # motion of the moved mechanism, which would be marched again for every frame
        sc.scales = sc.auto_scales(length=req.view.per_mm, velocity=req.view.velocity_per_mm,
                                   acceleration=req.view.acceleration_per_mm)
    con = None
    steps: list[str] = []
    if req.construction:
        opts = {}
        if req.point and req.construction in ("euler-savary", "bobillier", "hartmann"):
            opts["point"] = req.point
        if req.link and req.construction in ("euler-savary", "bobillier", "hartmann", "two-points"):
            opts["link"] = req.link
        con = construct(req.construction, mech, sol, **opts)
        con.require(0)
        con.check()
        steps = [s.text for s in con.steps]
        if req.step is not None and req.step >= len(steps):
            raise InputError(f"step {req.step}: the construction has {len(steps)} steps (0 to "
                             f"{len(steps) - 1})")
    layers = list(req.layers)
    if req.paths is not None:
        unknown = [p for p in req.paths if p not in mech.points]
        if unknown:
            raise InputError(f"paths: mechanism '{mech.name}' has no point '{unknown[0]}' (its "
                             f"points are {', '.join(mech.points)})")
        if not req.paths:
            layers = [n for n in layers if n != "paths"]
    fig = scene_figure(sc, layers, construction=con, step=req.step, paths=req.paths or None)
    if req.view is not None:
        fig.view["mechanism"] = (np.array(req.view.lo, float), np.array(req.view.hi, float))
    elif req.fit == "motion" and con is None and req.motion:
        fig.view["mechanism"] = sc.box(grow=0.12)
    scales = {name: None if s is None else float(s.per_mm) for name, s in (
        ("length", sc.scales.length), ("velocity", sc.scales.velocity),
        ("acceleration", sc.scales.acceleration))}
    return fig, steps, scales


def create_app(workdir: str | Path | None = None, *, compiled: bool = False,
               hosts: Iterable[str] | None = None) -> FastAPI:
    """The workbench application; files are opened only from the library and `workdir`.
    `compiled`: compile the kinematics' loops in the background and use them for every solve
    (`linkwork serve`; see `compile_kernels`). `hosts`: the only host names requests may be
    addressed to (`linkwork serve` on this computer: its local names, see `_KnownHosts`);
    None answers any."""
    sources = Sources(None if workdir is None else Path(workdir))

    @asynccontextmanager
    async def lifespan(app):
        if compiled:  # when the server starts (not when the application is merely made)
            threading.Thread(target=compile_kernels, name="compile-kernels", daemon=True).start()
        yield

    app = FastAPI(title="linkwork workbench", version="1", lifespan=lifespan,
                  description="The linkwork Python API over HTTP: lengths in the mechanism "
                              "file's unit, angles in radians, times in seconds.",
                  openapi_url="/api/openapi.json", docs_url=None, redoc_url=None)
    app.state.sources = sources

    @app.exception_handler(LinkworkError)
    async def _linkwork_error(request: Request, exc: LinkworkError):
        return _error(*_failure(exc))

    @app.exception_handler(RequestValidationError)
    async def _invalid(request: Request, exc: RequestValidationError):
        return _error(422, _validation_message(exc), "RequestValidationError")

    @app.exception_handler(Exception)
    async def _bug(request: Request, exc: Exception):
        return _error(*_failure(exc))

    from starlette.exceptions import HTTPException

    @app.exception_handler(HTTPException)
    async def _http(request: Request, exc: HTTPException):
        return _error(exc.status_code, str(exc.detail), "HTTPException")

    errors = {400: {"model": m.Error}, 404: {"model": m.Error}, 413: {"model": m.Error},
              422: {"model": m.Error}, 500: {"model": m.Error}}

    def load(src: m.Source):
        return sources.load(library=src.library, file=src.file, text=src.text, name=src.name,
                            points=src.points)

    def respond(doc: dict) -> JSONResponse:
        return JSONResponse(jsonable_encoder(doc))

    @app.get("/api/library", response_model=m.LibraryList, responses=errors)
    def library_list():
        """The library's mechanisms (open them as `{"library": NAME}`) and the mechanism files
        of the working folder (as `{"file": PATH}`)."""
        out = []
        for name in sources.library():
            text = sources.load(library=name).text
            out.append({"name": name, "title": tomllib.loads(text).get("name", "")})
        return {"mechanisms": out, "files": sources_files()}

    def sources_files():
        from .sources import working_files
        return working_files(sources.workdir)

    @app.get("/api/library/{name}", response_model=m.MechanismText, responses=errors)
    def library_text(name: str):
        """The file of one library mechanism (`linkwork library NAME`)."""
        if name not in sources.library():
            raise UnknownMechanismError(f"the library has no mechanism '{name}'")
        return {"name": name, "text": sources.load(library=name).text}

    @app.post("/api/mechanism", response_model=m.MechanismInfo, responses=errors)
    def mechanism(req: m.MechanismRequest):
        """Load and validate a mechanism: its points, links, pairs and drivers."""
        with _warnings(compiled) as warned:
            loaded = load(req.source)
        return mechanism_info(loaded, warned)

    @app.post("/api/solve", response_model=m.SolutionDocument, responses=errors)
    def solve_(req: m.SolveRequest):
        """`linkwork.solve` at the given inputs or times (`analyze --at … --format json`)."""
        with _warnings(compiled) as warned:
            loaded = load(req.source)
            sol = solve_request(loaded.mechanism, req, req.order, loaded.previous)
            doc = to_document(sol)
        return respond({**doc, "warnings": warned})

    @app.post("/api/motion", response_model=m.SolutionDocument, responses=errors)
    def motion(req: m.MotionRequest):
        """`linkwork.whole_motion` (`analyze --format json` without --at)."""
        with _warnings(compiled) as warned:
            sol = kept_motion(load(req.source).mechanism)
            if req.detail == "status":
                mech = sol.mechanism
                single = len(mech.drivers) == 1
                doc = {"mechanism": mech.name,
                       "units": {"length": mech.length_unit, "angle": "rad", "time": "s"},
                       "drivers": [d.joint for d in mech.drivers],
                       "samples": [{"input": float(sol.inputs[n, 0]) if single else sol.inputs[n].tolist(),
                                    "status": str(Status(int(sol.status[n]))),
                                    "error": _finite(sol.errors[n])} for n in range(len(sol))]}
            else:
                doc = to_document(sol)
        return respond({**doc, "warnings": warned})

    @app.post("/api/poles", response_model=m.Document, responses=errors)
    def poles_(req: m.PolesRequest):
        """All relative poles (`linkwork poles --format json`)."""
        from ..instant.export import poles_document
        with _warnings(compiled) as warned:
            doc = poles_document(solve_request(load(req.source).mechanism, req, 1), req.schedule)
        return respond({**doc, "warnings": warned})

    @app.post("/api/curvature", response_model=m.Document, responses=errors)
    def curvature_(req: m.CurvatureRequest):
        """Curvature theory of a link (`linkwork curvature --format json`); `points` are point
        names or design coordinates [x, y]."""
        from ..instant.export import curvature_document
        with _warnings(compiled) as warned:
            mech = load(req.source).mechanism
            asked = []
            for p in req.points:
                if isinstance(p, str):
                    if p not in mech.points:
                        raise InputError(f"points: mechanism '{mech.name}' has no point '{p}' "
                                         f"(its points are {', '.join(mech.points)})")
                    asked.append((p, p))
                else:
                    asked.append((f"{p[0]:g},{p[1]:g}", np.asarray(p, float)))
            doc = curvature_document(solve_request(mech, req, 3), req.link, req.relative_to, asked)
        return respond({**doc, "warnings": warned})

    @app.post("/api/structure", response_model=m.Document, responses=errors)
    def structure_(req: m.MechanismRequest):
        """Mobility, Assur groups, Grashof type (`linkwork structure --format json`)."""
        from ..structure import structure_report
        with _warnings(compiled) as warned:
            doc = structure_report(load(req.source).mechanism).as_dict()
        return respond({**doc, "warnings": warned})

    @app.post("/api/construction", response_model=m.ConstructionResult, responses=errors)
    def construction_(req: m.ConstructionRequest):
        """A classical construction at one position, checked against the exact values, with
        its steps in words (`linkwork draw --construction NAME`)."""
        from ..constructions import construct
        with _warnings(compiled) as warned:
            mech = load(req.source).mechanism
            sol = solve_request(mech, req)
            if len(sol) != 1:
                raise InputError(f"a construction is drawn at one position; got {len(sol)}")
            opts = {k: v for k, v in (("point", req.point), ("link", req.link)) if v is not None}
            con = construct(req.name, mech, sol, **opts)
            con.require(0)
            con.check()
        return {"name": req.name, "title": con.title, "steps": [s.text for s in con.steps],
                "description": con.describe(), "warnings": warned}

    def drawn(req: m.DrawingRequest, loaded: Loaded, warned: list[str], stage: Stages,
              cpu_before: float | None = None) -> tuple[str, Stages]:
        """The drawing of a loaded request as JSON text (`cpu_before`: the request began in
        another thread, see `Stages.handed_over`)."""
        if cpu_before is not None:
            stage.handed_over(cpu_before)
        with _warnings(compiled) as more:
            doc = drawing(loaded.mechanism, req, loaded.previous, stage)
        with stage("encode"):
            text = _json({**doc, "warnings": list(dict.fromkeys(warned + more))})
        stage.done()
        return text, stage

    async def drawing_answer(req: m.DrawingRequest) -> tuple[str, Stages]:
        """The answer of `/api/drawing` (its JSON text) and where its time went.

        A drag's frame is computed in the event loop itself, not handed to a worker thread and
        back: it is a few milliseconds of work, and on a loaded machine each hand-over waits
        for a core to wake the other thread (the GIL lets no two requests compute at once
        anyway). What may take long (`long_drawing`: the whole motion, or a march from the
        design position) goes to a worker thread, so that it holds no other request up."""
        stage = Stages()
        with _warnings(compiled) as warned:
            with stage("load"):
                loaded = load(req.source)
            with stage("solve"):  # (its plan, which the solve would make: its warnings too)
                long = long_drawing(loaded, req)
        if long:
            return await run_in_threadpool(drawn, req, loaded, warned, stage, stage.cpu())
        return drawn(req, loaded, warned, stage)

    @app.post("/api/drawing", response_model=m.Drawing, responses=errors)
    async def drawing_(req: m.DrawingRequest):
        """The SVG of `linkwork draw` at one position, with the layers and construction asked,
        the point positions drawn and how the drawing maps world to SVG coordinates."""
        text, stage = await drawing_answer(req)
        return Response(text, media_type="application/json",
                        headers={"Server-Timing": stage.header()})

    @app.websocket("/api/drawing/ws")
    async def drawing_socket(ws: WebSocket):
        """`/api/drawing` over a WebSocket, for a drag's frames (no HTTP round trip per frame):
        each message is a drawing request, each answer `{"status", "timing", "body"}` with the
        HTTP answer's status, its Server-Timing stages (ms) and its JSON body (the drawing, or
        `{"error", "kind"}`). Only pages of this server may connect (a browser lets any site open
        a socket to 127.0.0.1, and reads its answers: the same-origin rule of HTTP does not hold)."""
        origin = ws.headers.get("origin")
        if origin is not None and urlsplit(origin).netloc != ws.headers.get("host"):
            await ws.close(code=1008, reason="another site's page may not use this socket")
            return
        await ws.accept()
        try:
            while True:
                message = await ws.receive()
                if message["type"] == "websocket.disconnect":
                    return
                t0 = time.perf_counter()
                status, stage, body = await _socket_drawing(message, drawing_answer)
                timing = {**stage.ms, "cpu": stage.cpu(),
                          "app": (time.perf_counter() - t0) * 1e3}
                await ws.send_text(f'{{"status":{status},"timing":{_json(timing)},"body":{body}}}')
        except WebSocketDisconnect:
            return

    @app.post("/api/drawing.png", responses={**errors, 200: {"content": {"image/png": {}}}},
              response_class=Response)
    def drawing_png(req: m.PngRequest):
        """The drawing of `/api/drawing` as PNG (`linkwork draw -o FILE.png`: cairo converts
        the very same SVG)."""
        import tempfile

        from ..drawing.svg import convert
        with _warnings(compiled):
            svg = drawing(load(req.source).mechanism, req)["svg"]
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "drawing.png"
            convert(svg, out, dpi=req.dpi)
            data = out.read_bytes()
        return Response(data, media_type="image/png")

    @app.post("/api/motion.csv", responses={**errors, 200: {"content": {"text/csv": {}}}},
              response_class=Response)
    def motion_csv(req: m.MechanismRequest):
        """The whole motion as the CSV of `linkwork analyze --format csv` (one row a sample,
        each header with its unit, `name [unit]`)."""
        from ..kinematics.export import csv_lines
        with _warnings(compiled):
            sol = kept_motion(load(req.source).mechanism)
            text = "".join(csv_lines(sol, units=True))
        return Response(text, media_type="text/csv; charset=utf-8")

    @app.get("/", include_in_schema=False)
    def page():
        index = STATIC / "index.html"
        return FileResponse(index, headers={"Cache-Control": "no-cache"})

    app.mount("/static", StaticFiles(directory=STATIC, check_dir=False), name="static")
    app.add_middleware(_BodyLimit, limit=MAX_BODY)
    if hosts is not None:
        app.add_middleware(_KnownHosts, hosts=frozenset(hosts))
    app.add_middleware(_ServerTiming)
    return app
