"""The workbench's drag → redrawn frame time, in Debian's Chromium driven by Playwright.

A server (the application of `linkwork serve`, its kinematics loops compiled before it
listens) runs in its own process; the page opens a mechanism, moves the slider to a sample of
the whole motion (the design position, or a quarter of the motion on), enters *Drag design
points*, presses the mouse on a point and moves it in small steps round a circle, each step once
the frame of the previous one has been painted. The page records, per drawing of the drag, the
time from the pointer's move to the first paint after the new drawing (`window.linkworkFrames`);
p50 and p95 are printed, with `uptime` (the machine may be shared). Then the server's part is
timed in this process, split into the moved mechanism's build, the solve at the drawn input
(carrying the previous frame's march over, as the server does) and the scene and its SVG.

    uv run python bench/bench_workbench.py                 # four-bar and Heusinger valve gear
    uv run python bench/bench_workbench.py --frames 200 --warmup 40

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

import linkwork

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
#: (library name, the point dragged, the radius of the circle it is moved round (mm), the
#: slider's place as a fraction of the whole motion's samples)
CASES = [("crank-rocker", "C", 0.6, 0.0), ("heusinger-valve-gear", "P45", 4.0, 0.0),
         ("heusinger-valve-gear", "P45", 4.0, 0.25)]
# the loops compiled (or loaded from numba's cache) before the server listens: the frames timed
# are those of a warm server, not of one compiling in the background
SERVER = """
import sys, uvicorn
from linkwork.web import create_app
from linkwork.web.app import compile_kernels
compile_kernels()
uvicorn.run(create_app(None), host="127.0.0.1", port=int(sys.argv[1]), log_level="warning")
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
                frames: int, warmup: int) -> np.ndarray:
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
    for k, target in enumerate(targets):
        n = page.evaluate("window.linkworkFrames.length")
        page.mouse.move(*target)
        page.wait_for_function(f"window.linkworkFrames.length > {n}", timeout=60_000)
    page.mouse.up()
    took = np.array(page.evaluate("window.linkworkFrames"))
    fetched = np.array(page.evaluate("window.linkworkFetches"))
    return took[-frames:], fetched[-frames:]


def server_parts(name: str, point: str, radius: float, place: float,
                 frames: int) -> dict[str, np.ndarray]:
    """The server's work per drag frame, timed in this process with the compiled loops: each
    frame a new mechanism (the point moved on round its circle, never to a place it had), solved
    carrying the previous frame's march over, as the server solves it."""
    from linkwork.web.app import _warnings, compile_kernels
    from linkwork.web.sources import Sources

    compile_kernels()
    with _warnings():  # as the server runs a request (its loops compiled)
        return _server_parts(name, point, radius, place, frames, Sources(None))


def _server_parts(name, point, radius, place, frames, sources) -> dict[str, np.ndarray]:
    from linkwork.drawing import Scene, scene_figure
    from linkwork.web import models as m
    from linkwork.web.app import drawing, solve_at

    base = linkwork.load(f"library:{name}")
    motion = linkwork.whole_motion(base)
    u = motion.inputs[int(round(place * (len(motion) - 1)))]
    at = [float(u[0])] if len(u) == 1 else [[float(v) for v in u]]
    req = m.DrawingRequest(source=m.Source(library=name), at=at, layers=["mechanism"], motion=False)
    drawing(sources.load(library=name).mechanism, req)  # the page shows it before the drag
    parts = {"build": [], "solve": [], "draw": [], "total": [], "cpu": []}
    x0 = base.points[point]
    for k in range(2 * frames + 6):  # two loads a frame, each a point of its own
        a = 2 * math.pi * k / (2 * frames + 6)
        moved = {point: (x0[0] + radius * math.cos(a), x0[1] + radius * math.sin(a))}
        t0, c0 = time.perf_counter(), time.thread_time()
        loaded = sources.load(library=name, points=moved)
        t1 = time.perf_counter()
        if k % 2 == 0:
            sol = solve_at(loaded.mechanism, req, 2, loaded.previous)
            t2 = time.perf_counter()
            sc = Scene(loaded.mechanism, sol)
            sc.motion = None
            scene_figure(sc, ["mechanism"]).to_svg()
            t3 = time.perf_counter()
            if k >= 6:
                for key, v in (("build", t1 - t0), ("solve", t2 - t1), ("draw", t3 - t2)):
                    parts[key].append(v * 1e3)
        else:  # the whole request's work, as the server does it
            drawing(loaded.mechanism, req, loaded.previous)
            if k >= 6:
                parts["total"].append((time.perf_counter() - t0) * 1e3)
                parts["cpu"].append((time.thread_time() - c0) * 1e3)
    return {k: np.array(v) for k, v in parts.items()}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--frames", type=int, default=120, help="drag frames timed per mechanism")
    ap.add_argument("--warmup", type=int, default=20, help="drag frames before the timed ones")
    ap.add_argument("--compile-wait", type=float, default=120.0,
                    help="seconds to wait at most for the server's compiled loops")
    args = ap.parse_args()
    if not Path(CHROMIUM).is_file():
        raise SystemExit("needs Debian's chromium (apt-get install chromium)")
    from playwright.sync_api import sync_playwright

    print("uptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    proc, url = start_server()
    try:
        wait_compiled(url, args.compile_wait)
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
            page = browser.new_page(viewport={"width": 1280, "height": 900})
            print("drag → painted frame in Chromium, and of it the request's round trip (ms):")
            print(f"{'mechanism':24} {'point':6} {'at':>5} {'frames':>6} {'p50':>7} {'p95':>7} "
                  f"{'fetch p50':>10} {'p95':>7}")
            for name, point, radius, place in CASES:
                t, f = drag_frames(page, url, name, point, radius, place, args.frames, args.warmup)
                print(f"{name:24} {point:6} {place:5.2f} {len(t):6d} {np.percentile(t, 50):7.1f} "
                      f"{np.percentile(t, 95):7.1f} {np.percentile(f, 50):10.1f} {np.percentile(f, 95):7.1f}")
            browser.close()
    finally:
        proc.terminate()
        proc.wait(10)
    print("\nthe server's part of a drag frame (this process, compiled loops), median ms (and the "
          "request's CPU time, which a shared machine does not stretch):")
    print(f"{'mechanism':24} {'at':>5} {'build':>7} {'solve':>7} {'draw':>7} {'request':>8} {'cpu':>6}")
    for name, point, radius, place in CASES:
        parts = server_parts(name, point, radius, place, min(args.frames, 60))
        print(f"{name:24} {place:5.2f} " + " ".join(f"{np.median(parts[k]):7.1f}"
                                                     for k in ("build", "solve", "draw"))
              + f" {np.median(parts['total']):8.1f} {np.median(parts['cpu']):6.1f}")
    print("uptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


if __name__ == "__main__":
    main()
