"""The server's drawing of a drag frame, without the browser: `scene_figure` and
`Figure.svg_and_transforms()` timed as the workbench calls them, and every library mechanism's
drawings dumped to a folder, to compare two versions of the drawing code byte for byte.

    uv run python bench/bench_drawing.py time                      # the cases below
    uv run python bench/bench_drawing.py time --frames 200 --only crank-rocker
    uv run python bench/bench_drawing.py dump /tmp/before          # SVG + transforms of all
    uv run python bench/bench_drawing.py dump /tmp/after && diff -r /tmp/before /tmp/after

*time*: a drag as the page makes it (`web.app.drawing`): the point is moved round a small circle,
each frame's mechanism built anew (`web.sources.moved`) and solved at the design position with
the previous frame's mechanism (`solve_at(…, previous=…)`), its scene drawn without the whole
motion (the page sends ``motion: false`` while dragging) with the case's layers, then its SVG
text and transforms. Printed per case: median and best (ms of the process's CPU time, which
other processes on the machine do not stretch) of the scene and of the SVG over the frames (the
first few, which fill the caches, left out).

*dump*: for every library mechanism, at the design position and at a dragged position, the
SVG text and the transforms of a set of layer combinations (with and without the whole motion,
framed as the workbench frames and as `--frame all`/`inset`), the drawings of the constructions
of a few mechanisms (whole, one step, animated), and the force layer where the file has mass
data; an error is written as its message. One file per drawing, named after what it draws.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import subprocess
import time
from pathlib import Path

import numpy as np

import linkwork
from linkwork.drawing import LAYERS, Scene, scene_figure
from linkwork.errors import LinkworkError
from linkwork.kinematics import solve_at
from linkwork.web.sources import moved

LIBRARY = Path(linkwork.__file__).parent / "library"

#: (library name, the point dragged, the radius of the circle it is moved round (mm))
DRAGS = [("crank-rocker", "C", 0.6), ("heusinger-valve-gear", "P45", 4.0),
         ("slider-crank-offset", "A", 0.6), ("jansen-linkage", "F", 0.6)]
#: the layers a drag frame draws: the page's default, and with more toggled
LAYER_SETS = {
    "mechanism": ["mechanism"],
    "vectors": ["mechanism", "velocities", "accelerations"],
    "poles": ["mechanism", "poles", "pole-lines"],
    "curvature": ["mechanism", "velocities", "poles", "inflection", "return", "bresse", "gamma"],
}
#: the layer combinations dumped: (name, layers, whole motion known, frame)
DUMPED = [
    ("mechanism", ["mechanism"], False, "mechanism"),
    ("vectors", ["mechanism", "velocities", "accelerations"], False, "mechanism"),
    ("poles", ["mechanism", "poles", "pole-lines"], False, "mechanism"),
    ("curvature", ["mechanism", "inflection", "return", "bresse", "gamma"], False, "mechanism"),
    ("higher", ["mechanism", "contact", "equivalent"], False, "mechanism"),
    ("all-motion", [n for n in LAYERS if n != "construction"], True, "mechanism"),
    ("all-motion-inset", [n for n in LAYERS if n != "construction"], True, "inset"),
    ("paths-all", ["mechanism", "paths", "centrodes", "velocities"], True, "all"),
]
#: mechanisms whose constructions are dumped too
CONSTRUCTED = ["crank-rocker", "slider-crank-offset", "heusinger-valve-gear",
               "oscillating-crank-slotted-lever", "five-bar"]


def figure(mech, sol, layers, *, motion: bool = False, frame: str = "mechanism", **kw):
    sc = Scene(mech, sol)
    if not motion:
        sc.motion = None  # as the workbench draws a drag frame
    return scene_figure(sc, layers, frame=frame, **kw)


def drag_frames(name: str, point: str, radius: float, frames: int):
    """The drag's mechanisms and their solutions, one a frame."""
    base = linkwork.load(f"library:{name}")
    x0 = base.points[point]
    previous, out = base, []
    for k in range(frames):
        a = 2 * math.pi * k / frames
        mech = moved(base, {point: (x0[0] + radius * math.cos(a), x0[1] + radius * math.sin(a))})
        out.append((mech, solve_at(mech, previous=previous)))
        previous = mech
    return out


def time_case(name: str, point: str, radius: float, layers: list[str], frames: int,
              warmup: int) -> tuple[list[float], list[float]]:
    scene, svg = [], []
    clock = time.process_time  # CPU time: steadier than the wall clock on a shared machine
    for k, (mech, sol) in enumerate(drag_frames(name, point, radius, frames + warmup)):
        t0 = clock()
        fig = figure(mech, sol, layers)
        t1 = clock()
        fig.svg_and_transforms()
        t2 = clock()
        if k >= warmup:
            scene.append((t1 - t0) * 1e3)
            svg.append((t2 - t1) * 1e3)
    return scene, svg


def run_times(args) -> None:
    print("uptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    print(f"{'mechanism':22} {'layers':10} {'scene med':>9} {'best':>6} {'svg med':>8} {'best':>6}  (ms)")
    for name, point, radius in DRAGS:
        if args.only and name not in args.only:
            continue
        for tag, layers in LAYER_SETS.items():
            if args.layers and tag not in args.layers:
                continue
            scene, svg = time_case(name, point, radius, layers, args.frames, args.warmup)
            print(f"{name:22} {tag:10} {statistics.median(scene):9.2f} {min(scene):6.2f} "
                  f"{statistics.median(svg):8.2f} {min(svg):6.2f}", flush=True)


# ---------------------------------------------------------------------------- the dump
def _write(folder: Path, stem: str, make) -> None:
    """`make()` → (svg, transforms) written as STEM.svg and STEM.json, or its error as STEM.err."""
    try:
        svg, tfs = make()
    except (LinkworkError, ValueError) as exc:
        (folder / f"{stem}.err").write_text(f"{type(exc).__name__}: {exc}\n")
        return
    (folder / f"{stem}.svg").write_text(svg)
    (folder / f"{stem}.json").write_text(json.dumps(tfs, indent=1, sort_keys=True) + "\n")


def _dragged(mech):
    """The mechanism with its last moving point moved by 2 % of its size (a drag frame)."""
    p = next(p for p in reversed(list(mech.points)) if mech.point_owner[p] != mech.frame)
    xy = mech.points[p] + 0.02 * mech.length_scale * np.array([0.6, 0.8])
    new = moved(mech, {p: tuple(xy)})
    return new, solve_at(new, previous=mech)


def dump(folder: Path, only: list[str] | None) -> None:
    from linkwork.constructions import CONSTRUCTIONS, construct
    from linkwork.drawing.force_layers import draw_forces
    from linkwork.io import load_dynamics

    folder.mkdir(parents=True, exist_ok=True)
    names = sorted(p.stem for p in LIBRARY.glob("*.toml"))
    for name in names:
        if only and name not in only:
            continue
        t = time.perf_counter()
        mech = linkwork.load(f"library:{name}")
        try:
            sol = solve_at(mech)
        except LinkworkError as exc:
            (folder / f"{name}.err").write_text(f"{type(exc).__name__}: {exc}\n")
            continue
        for tag, layers, motion, frame in DUMPED:
            _write(folder, f"{name}__{tag}",
                   lambda: figure(mech, sol, layers, motion=motion, frame=frame).svg_and_transforms())
        try:
            drag = _dragged(mech)
        except LinkworkError as exc:
            (folder / f"{name}__drag.err").write_text(f"{type(exc).__name__}: {exc}\n")
        else:
            for tag, layers, motion, frame in DUMPED[:4]:
                _write(folder, f"{name}__drag-{tag}",
                       lambda: figure(*drag, layers).svg_and_transforms())
        if name in CONSTRUCTED:
            for con_name in CONSTRUCTIONS:
                try:
                    con = construct(con_name, mech, sol)
                    con.require(0)
                    con.check()
                except LinkworkError as exc:
                    (folder / f"{name}__con-{con_name}.err").write_text(f"{type(exc).__name__}: {exc}\n")
                    continue
                _write(folder, f"{name}__con-{con_name}",
                       lambda: figure(mech, sol, ["mechanism"], construction=con).svg_and_transforms())
                _write(folder, f"{name}__con-{con_name}-step1",
                       lambda: figure(mech, sol, ["mechanism"], construction=con, step=1).svg_and_transforms())
                _write(folder, f"{name}__con-{con_name}-animated",
                       lambda: (figure(mech, sol, ["mechanism"], construction=con).to_svg(animate=1.0), {}))
        dyn = load_dynamics(f"library:{name}")
        if dyn.masses:
            def forces():
                sc = Scene(mech, sol)
                fig = scene_figure(sc, ["mechanism"])
                draw_forces(fig, sc, dyn)
                return fig.svg_and_transforms()
            _write(folder, f"{name}__forces", forces)
        print(f"{name}: {time.perf_counter() - t:.1f} s", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="what", required=True)
    t = sub.add_parser("time", help="time the drag frames' scene and SVG")
    t.add_argument("--frames", type=int, default=100, help="drag frames timed per case")
    t.add_argument("--warmup", type=int, default=5, help="frames drawn before timing")
    t.add_argument("--only", nargs="*", help="mechanisms (library names) to time")
    t.add_argument("--layers", nargs="*", choices=list(LAYER_SETS), help="layer sets to time")
    d = sub.add_parser("dump", help="write every library mechanism's drawings to a folder")
    d.add_argument("folder", type=Path)
    d.add_argument("--only", nargs="*", help="mechanisms (library names) to dump")
    args = ap.parse_args()
    if args.what == "time":
        run_times(args)
    else:
        dump(args.folder, args.only)


if __name__ == "__main__":
    main()
