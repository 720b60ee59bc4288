"""The workbench server's side of playing a whole motion: the page's requests while it plays,
timed by the server (its Server-Timing header).

A server (as `linkwork serve` runs it, its loops compiled: bench_workbench.py's) is started; per
case the page's requests are sent as the page sends them: `/api/motion` once, then
`/api/drawing` at successive samples of the whole motion (`at` = the sample's inputs, or
`times` = its time, `motion: true`, the layers of the case), the first frame apart (it computes the kept motions);
the motion is played twice (the first time, the server solves the samples as they come).
Printed: the first frame's server time, then per frame median and p95 of `app` (the request in
the server), and the medians of its stages (solve, scene, svg, encode) and of `cpu` (the
server thread's CPU time, which other processes on the machine do not stretch).

    uv run python bench/bench_play.py
    uv run python bench/bench_play.py --every 5 --only heusinger-valve-gear
"""

from __future__ import annotations

import argparse
import json
import urllib.request

import numpy as np

from bench_workbench import start_server, wait_compiled

#: (library name, layers besides "mechanism", how the frames ask: by the sample's inputs as
#: the page does, or by its time, as a motion with time laws may be asked)
CASES = [("crank-rocker", [], "at"), ("watt-i-six-bar", [], "at"), ("heusinger-valve-gear", [], "at"),
         ("heusinger-valve-gear", ["paths", "velocities", "poles"], "at"),
         ("heusinger-valve-gear", ["velocities", "centrodes"], "times")]
STAGES = ("solve", "scene", "svg", "encode", "app", "cpu")


def post(url: str, path: str, body: dict) -> tuple[dict, dict]:
    """The answer's JSON and its Server-Timing stages (ms)."""
    req = urllib.request.Request(url + path, data=json.dumps(body).encode(),
                                 headers={"content-type": "application/json"})
    with urllib.request.urlopen(req, timeout=600) as r:
        timing = {}
        for part in (r.headers.get("server-timing") or "").split(","):
            name, _, dur = part.strip().partition(";dur=")
            if dur:
                timing[name] = float(dur)
        return json.loads(r.read()), timing


def play(url: str, name: str, layers: list[str], by: str, every: int) -> None:
    source = {"library": name}
    motion, _ = post(url, "/api/motion", {"source": source, "detail": "full"})
    inputs = [s["input" if by == "at" else "time"] for s in motion["samples"]]
    for turn in (1, 2):
        frames = []
        for k in range(0, len(inputs), every):
            _, timing = post(url, "/api/drawing", {"source": source, by: [inputs[k]],
                                                   "motion": True, "layers": ["mechanism", *layers]})
            frames.append(timing)
        first, rest = frames[0], frames[1:]
        app = np.array([f["app"] for f in rest])
        stages = "  ".join(f"{s} {np.median([f.get(s, 0.0) for f in rest]):6.1f}" for s in STAGES)
        print(f"{name:22s} {'+'.join(layers) or 'default':24s} by {by:5s} play {turn}: first "
              f"{first['app']:7.1f} ms; {len(rest)} frames: app p50 {np.median(app):6.1f} p95 "
              f"{np.percentile(app, 95):6.1f} ms | medians: {stages}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--every", type=int, default=10, help="draw every n-th sample (default 10)")
    ap.add_argument("--only", nargs="*", help="library names of the cases to run")
    args = ap.parse_args()
    proc, url = start_server()
    try:
        wait_compiled(url, 120)
        for name, layers, by in CASES:
            if not args.only or name in args.only:
                play(url, name, layers, by, args.every)
    finally:
        proc.terminate()
        proc.wait()


if __name__ == "__main__":
    main()
