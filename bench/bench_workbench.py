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
                frames: int, warmup: int, transport: str) -> dict[str, np.ndarray]:
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
               for a in np.linspace(0, 2 * math.pi * (frames + warmup) / 24, frames + warmup)]
    for target in targets:
        # the page says when a frame is recorded: waiting for it costs the page nothing (a
        # poll by animation frames or timers would run in the page during the frame timed)
        page.evaluate(NEXT_FRAME)
        page.mouse.move(*target)
        page.evaluate("() => window.nextFrame")
    page.mouse.up()
    timed = page.evaluate("window.linkworkFrames")[-frames:]
    came = {f["via"] for f in timed}
    if came != {transport}:
        raise SystemExit(f"{name}: frames came over {came}, not {transport}")
    return stages(timed)


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
                        t = drag_frames(page, url, name, point, radius, place, args.frames,
                                        args.warmup, transport)
                        print(f"{name:21} {place:4.2f} {np.percentile(t['frame'], 50):6.1f} "
                              f"{np.percentile(t['frame'], 95):6.1f} |"
                              + "".join(f"{np.nanmedian(t[c]):8.1f}" for c in cols))
                    page.close()
                browser.close()
    finally:
        proc.terminate()
        proc.wait(10)
    print("\nuptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


if __name__ == "__main__":
    main()
