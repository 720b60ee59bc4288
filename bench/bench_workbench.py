"""The workbench's drag → redrawn frame time, in Debian's Chromium driven by Playwright.

A server (the application of `linkwork serve`, its kinematics loops compiled before it
listens) runs in its own process; the page opens a mechanism, moves the slider to a sample of
the whole motion (the design position, or a quarter of the motion on), enters *Drag design
points*, presses the mouse on a point and moves it in small steps round a circle, each step once
the frame of the previous one has been painted. The page records each frame of the drag
(`window.linkworkFrames`): the pointer event's time stamp, its handler, the request sent, the
answer's headers and body, the drawing in the page, the first paint after it, and the server's
stages from the answer's Server-Timing header.

Two browsers are driven, one after the other:

- *unthrottled*: Chromium without its frame-rate limit and vsync (`UNTHROTTLED`): the paint
  follows the drawing without waiting for a display's frame clock; this measures what the
  software costs;
- *60 Hz*: Chromium as it starts, where the pointer event waits for the next display frame
  (16.7 ms) and so does the paint: what a user of a 60 Hz screen sees (up to two frames more).

Printed per case: p50 and p95 of the whole frame (pointer event → painted), and the median of
each stage: input (event → handler), the server's (load: the moved mechanism built; solve;
scene: the layers' figure; svg: the SVG text and transforms; encode: the JSON; app: the request
in the server from routing to the answer; cpu: the server thread's CPU time, which other
processes do not stretch), transfer (the round trip less `app`), parse (the answer's body),
dom (the drawing and the numbers into the page) and paint (to the first paint after it).

The page sends a drag's drawings over its WebSocket (`/api/drawing/ws`) while it is open;
`--transport http` takes the socket away from the page (it falls back to `POST /api/drawing`),
to compare the two (both by default, the socket first).

    uv run python bench/bench_workbench.py                 # four-bar and Heusinger valve gear
    uv run python bench/bench_workbench.py --frames 200 --warmup 40 --mode unthrottled

Targets (issue 12): p95 under 20 ms for the four-bar, under 50 ms for the 12-link valve gear.
"""

from __future__ import annotations

import argparse
import json
import math
import shutil
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np


CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
#: (library name, the point dragged, the radius of the circle it is moved round (mm), the
#: slider's place as a fraction of the whole motion's samples)
CASES = [("crank-rocker", "C", 0.6, 0.0), ("heusinger-valve-gear", "P45", 4.0, 0.0),
         ("heusinger-valve-gear", "P45", 4.0, 0.25)]
#: Chromium's switches for the unthrottled browser (both accepted by Debian's Chromium headless;
#: --run-all-compositor-stages-before-draw would also shorten the input's wait, but it keeps the
#: idle page drawing frames at 125 % CPU, on the cores the server needs)
UNTHROTTLED = ["--disable-frame-rate-limit", "--disable-gpu-vsync"]
MODES = {"unthrottled": UNTHROTTLED, "60Hz": []}
#: the server's stages (Server-Timing) printed, in order
SERVER_STAGES = ("load", "solve", "scene", "svg", "encode", "app", "cpu")
# the loops compiled (or loaded from numba's cache) before the server listens, and used for every
# solve as `linkwork serve` does: the frames timed are those of a warm server
SERVER = """
import sys, uvicorn
from linkwork.web import create_app
from linkwork.web.app import compile_kernels
compile_kernels()
uvicorn.run(create_app(None, compiled=True), host="127.0.0.1", port=int(sys.argv[1]), log_level="warning")
"""


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_server() -> tuple[subprocess.Popen, str]:
    port = free_port()
    proc = subprocess.Popen([sys.executable, "-c", SERVER, str(port)])
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 600  # compiling first: minutes when numba's cache is cold
    while True:
        try:
            urllib.request.urlopen(f"{url}/api/library", timeout=5).read()
            return proc, url
        except OSError:
            if time.monotonic() > deadline or proc.poll() is not None:
                proc.kill()
                raise SystemExit("the workbench server did not start")
            time.sleep(0.2)


def wait_compiled(url: str, seconds: float) -> None:
    """Warm the server up (its loops are compiled before it listens; the first requests still
    import what a drawing needs): drag frames are timed once a frame's request has become fast."""
    body = json.dumps({"source": {"library": "crank-rocker", "points": {"C": [15.1, 25.0]}},
                       "at": [1.0], "layers": ["mechanism"], "motion": False}).encode()
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        t = time.perf_counter()
        req = urllib.request.Request(f"{url}/api/drawing", data=body,
                                     headers={"content-type": "application/json"})
        urllib.request.urlopen(req, timeout=60).read()
        if time.perf_counter() - t < 0.05:
            return
        time.sleep(0.5)


def screen_of(page, xy) -> tuple[float, float]:
    t = json.loads(page.get_attribute("#drawing", "data-transform"))
    sx = t["origin"][0] + (xy[0] - t["lo"][0]) / t["per_mm"]
    sy = t["origin"][1] + (t["hi"][1] - xy[1]) / t["per_mm"]
    return tuple(page.eval_on_selector("#drawing svg", """(svg, p) => {
        const q = new DOMPoint(p[0], p[1]).matrixTransform(svg.getScreenCTM());
        return [q.x, q.y]; }""", [sx, sy]))


def drag_frames(page, url: str, name: str, point: str, radius: float, place: float,
                frames: int, warmup: int, transport: str, traced: int = 0,
                browser=None) -> tuple[dict[str, np.ndarray], list[str]]:
    """The stages of `frames` drag frames after `warmup`; with `traced`, that many frames more
    recorded in a Chromium trace (`browser`'s), and the lines summing it up."""
    page.goto(f"{url}/?library={name}")
    page.wait_for_selector("body[data-ready=true]", timeout=120_000)
    if place:  # the slider to that sample, and its drawing shown
        before = page.get_attribute("#drawing", "data-input")
        k = int(round(place * int(page.get_attribute("#input-slider", "max"))))
        page.eval_on_selector("#input-slider", "(e, k) => { e.value = String(k); "
                              "e.dispatchEvent(new Event('input')); }", k)
        page.wait_for_function("b => document.querySelector('#drawing').dataset.input !== b",
                               arg=before, timeout=120_000)
        page.wait_for_timeout(300)
    page.check("#edit")
    page.wait_for_timeout(300)
    xy = json.loads(page.eval_on_selector(f"#numbers tr[data-point='{point}']",
                                          "r => JSON.stringify([+r.cells[1].textContent, +r.cells[2].textContent])"))
    page.mouse.move(*screen_of(page, xy))
    page.mouse.down()
    # the drawing keeps its layout during the drag (the page reads the pointer in the drawing
    # the drag started on), so the screen places are taken once
    centre = np.asarray(xy, float)
    targets = [screen_of(page, centre + radius * np.array([math.cos(a), math.sin(a)]))
               for a in np.linspace(0, 2 * math.pi * (frames + warmup + traced) / 24,
                                    frames + warmup + traced)]
    trace = None
    for i, target in enumerate(targets):
        if traced and i == warmup + frames:  # the frames timed are not traced: tracing slows them
            browser.start_tracing(page=page, categories=TRACE_CATEGORIES)
        # the page says when a frame is recorded: waiting for it costs the page nothing (a
        # poll by animation frames or timers would run in the page during the frame timed)
        page.evaluate(NEXT_FRAME)
        page.mouse.move(*target)
        page.evaluate("() => window.nextFrame")
    if traced:  # before the pointer's release asks for the whole motion
        trace = browser.stop_tracing()
    page.mouse.up()
    timed = page.evaluate("window.linkworkFrames")[-(frames + traced):][:frames]
    came = {f["via"] for f in timed}
    if came != {transport}:
        raise SystemExit(f"{name}: frames came over {came}, not {transport}")
    return stages(timed), trace_summary(trace, traced) if trace else []


#: what a trace records: the events of the Performance panel of Chromium's developer tools (the
#: page's script, parsing, style, layout, paint, commit; raster), the display compositor's draw
TRACE_CATEGORIES = ["devtools.timeline", "disabled-by-default-devtools.timeline", "viz"]
#: the renderer's main-thread events summed by their own time (less the events inside them)
MAIN_EVENTS = {"FunctionCall": "script", "EvaluateScript": "script", "RunMicrotasks": "script",
               "TimerFire": "script", "FireAnimationFrame": "script", "EventDispatch": "script",
               "v8.callFunction": "script", "ParseHTML": "parse", "UpdateLayoutTree": "style",
               "Layout": "layout", "PrePaint": "prepaint", "Paint": "paint",
               "Layerize": "layerize", "Commit": "commit", "HitTest": "hit test",
               "MinorGC": "gc", "MajorGC": "gc"}


def trace_summary(data: bytes, frames: int) -> list[str]:
    """A Chromium trace of `frames` drag frames summed up: the renderer main thread's time by
    what it did (own time, ms per frame; "busy" is all its tasks, the bench's own calls into the
    page and the trace's cost included), how much of the page each layout and paint covered, the
    tiles rastered and the display compositor's drawing (ms per frame)."""
    doc = json.loads(data)
    events = doc["traceEvents"] if isinstance(doc, dict) else doc
    threads = {(e["pid"], e["tid"]): e["args"]["name"] for e in events
               if e.get("ph") == "M" and e.get("name") == "thread_name"}
    # the page's renderer: the process whose main thread received the drawings
    pid = next(e["pid"] for e in events if e.get("name") == "WebSocketReceive"
               or e.get("name") == "ResourceReceiveResponse")
    main = [e for e in events if e.get("ph") == "X" and e["pid"] == pid
            and threads.get((pid, e["tid"])) == "CrRendererMain"]
    own: dict[str, float] = {}
    stack: list[tuple[float, str]] = []  # (end, what) of the events open, outermost first
    busy = 0.0
    for e in sorted(main, key=lambda e: (e["ts"], -e.get("dur", 0))):
        while stack and stack[-1][0] <= e["ts"]:
            stack.pop()
        if e["name"] == "RunTask" and not stack:
            busy += e.get("dur", 0)
        what = MAIN_EVENTS.get(e["name"])
        if what is None:
            continue
        inner = [s for s in stack if s[1] != "task"]
        if inner:  # the enclosing event's own time loses this one
            own[inner[-1][1]] -= e.get("dur", 0)
        own[what] = own.get(what, 0.0) + e.get("dur", 0)
        stack.append((e["ts"] + e.get("dur", 0), what))
    per = 1e-3 / frames
    layouts = [e["args"]["beginData"] for e in main if e["name"] == "Layout"]
    paints = [e["args"]["data"].get("clip", []) for e in main if e["name"] == "Paint"]
    area = sum(abs((c[4] - c[0]) * (c[5] - c[1])) for c in paints if len(c) == 8)
    raster = [e for e in events if e.get("name") == "RasterTask" and e.get("ph") == "X"]
    draw = [e for e in events if e.get("name") == "Display::DrawAndSwap" and e.get("ph") == "X"]
    lines = [f"  trace of {frames} frames, ms per frame: main thread busy {busy * per:.2f}: "
             + ", ".join(f"{k} {v * per:.2f}" for k, v in sorted(own.items(), key=lambda kv: -kv[1])
                         if v * per >= 0.01)]
    lines.append(
        f"  {len(layouts) / frames:.1f} layouts a frame, objects laid out (median) "
        f"{np.median([b.get('dirtyObjects', 0) for b in layouts]) if layouts else 0:.0f} of "
        f"{np.median([b.get('totalObjects', 0) for b in layouts]) if layouts else 0:.0f}; "
        f"{len(paints) / frames:.1f} paints a frame, {area / frames / 1e3:.0f} kpx; "
        f"raster {sum(e['dur'] for e in raster) * per:.2f} ({len(raster) / frames:.1f} tiles); "
        f"display draw {sum(e['dur'] for e in draw) * per:.2f}")
    return lines


#: how the page sends a drag's drawings: its WebSocket, or (the socket taken away before the
#: page's script runs) HTTP
TRANSPORTS = {"socket": None, "http": "delete window.WebSocket;"}

NEXT_FRAME = """() => { window.nextFrame = new Promise((done, fail) => {
    const late = setTimeout(() => fail(new Error("no frame drawn in a minute")), 60000);
    window.addEventListener("linkworkframe", () => { clearTimeout(late); done(); }, { once: true });
}); }"""


def stages(frames: list[dict]) -> dict[str, np.ndarray]:
    """Per frame (ms): the whole frame, and its stages in the order they happen."""
    f = {k: np.array([fr[k] for fr in frames], float)
         for k in ("event", "handler", "sent", "headers", "parsed", "shown", "painted")}
    server = {k: np.array([fr["server"].get(k, np.nan) for fr in frames], float)
              for k in SERVER_STAGES}
    return {"frame": f["painted"] - f["event"], "input": f["handler"] - f["event"], **server,
            "transfer": f["headers"] - f["sent"] - server["app"],
            "parse": f["parsed"] - f["headers"], "dom": f["shown"] - f["parsed"],
            "paint": f["painted"] - f["shown"]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--frames", type=int, default=120, help="drag frames timed per mechanism")
    ap.add_argument("--warmup", type=int, default=20, help="drag frames before the timed ones")
    ap.add_argument("--mode", choices=list(MODES), action="append",
                    help="the browser's frame clock (default: both, unthrottled first)")
    ap.add_argument("--compile-wait", type=float, default=120.0,
                    help="seconds to wait at most for the server's compiled loops")
    ap.add_argument("--transport", choices=list(TRANSPORTS), action="append",
                    help="how the page sends the drag's drawings (default: both, socket first)")
    ap.add_argument("--trace", type=int, default=0, metavar="FRAMES",
                    help="after the frames timed, record a Chromium trace of this many frames "
                         "more and print where the page's time went")
    args = ap.parse_args()
    if not Path(CHROMIUM).is_file():
        raise SystemExit("needs Debian's chromium (apt-get install chromium)")
    from playwright.sync_api import sync_playwright

    print("uptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    proc, url = start_server()
    cols = ("input", *SERVER_STAGES, "transfer", "parse", "dom", "paint")
    try:
        wait_compiled(url, args.compile_wait)
        with sync_playwright() as p:
            for mode in args.mode or list(MODES):
                browser = p.chromium.launch(executable_path=CHROMIUM,
                                            args=["--no-sandbox", *MODES[mode]])
                for transport in args.transport or list(TRANSPORTS):
                    page = browser.new_page(viewport={"width": 1280, "height": 900})
                    if TRANSPORTS[transport]:
                        page.add_init_script(TRANSPORTS[transport])
                    print(f"\n{mode}, over {transport}: drag → painted frame (ms), p50 and p95, "
                          "and the median of each stage")
                    print(f"{'mechanism':21} {'at':>4} {'p50':>6} {'p95':>6} |"
                          + "".join(f"{c:>8}" for c in cols))
                    for name, point, radius, place in CASES:
                        t, traced = drag_frames(page, url, name, point, radius, place,
                                                args.frames, args.warmup, transport, args.trace,
                                                browser)
                        print(f"{name:21} {place:4.2f} {np.percentile(t['frame'], 50):6.1f} "
                              f"{np.percentile(t['frame'], 95):6.1f} |"
                              + "".join(f"{np.nanmedian(t[c]):8.1f}" for c in cols))
                        for line in traced:
                            print(line)
                    page.close()
                browser.close()
    finally:
        proc.terminate()
        proc.wait(10)
    print("\nuptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


if __name__ == "__main__":
    main()
