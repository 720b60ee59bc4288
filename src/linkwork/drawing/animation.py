"""Motion animations: the drawing of `linkwork draw` at N positions over the whole motion, as a
self-contained HTML page (the frames' SVGs shown in turn by CSS keyframes, no script), as a
GIF (each frame rendered to PNG by cairosvg, assembled by Pillow), or as an MP4 (the same
frames encoded by ffmpeg: the binary of the optional `imageio-ffmpeg` package, `linkwork[video]`,
or an `ffmpeg` on the PATH).

Every frame is drawn with the same scales and the same panel (the box of the whole motion), so
that only the mechanism moves. The frames are samples of `whole_motion`, evenly spaced over its
reachable samples; the last sample is left out, since a full turn ends where it began and the
animation loops.
"""

from __future__ import annotations

import html
import io
import json
import re
import shutil
import subprocess
from fractions import Fraction
from pathlib import Path
from typing import Iterable

import numpy as np

from ..errors import InputError, LinkworkError, OutputError
from ..kinematics import Status, whole_motion
from ..model import Mechanism
from ..outputs import output_path, write_output_file
from .layers import Scene, scene_figure
from .svg import convert

#: frames of an animation: at least two, at most one per sample of the whole motion
MIN_FRAMES = 2


def frame_samples(status: np.ndarray, n: int) -> np.ndarray:
    """Indices of `n` frames evenly spaced over the reachable samples (the last one left out)."""
    ok = np.flatnonzero(status != Status.UNREACHABLE)
    usable = ok[:-1] if len(ok) > 1 else ok
    if n < MIN_FRAMES or n > len(usable):
        raise InputError(f"--frames {n}: give {MIN_FRAMES} to {len(usable)} frames (the whole "
                         f"motion has {len(usable)} reachable samples to draw)")
    return usable[(np.arange(n) * len(usable)) // n]


def motion_frames(mech: Mechanism, n: int, show: Iterable[str] = ("mechanism",)):
    """The scenes and SVG texts of `n` frames over the whole motion: (scenes, svgs)."""
    show = list(show)
    try:
        motion = whole_motion(mech)
    except LinkworkError as exc:
        raise InputError(f"animate: the whole motion of '{mech.name}' cannot be computed: "
                         f"{exc}") from None
    idx = frame_samples(motion.status, n)
    first = Scene(mech, motion, index=int(idx[0]))
    scene_figure(first, show)  # sets the scales, which every frame shares
    # every frame fits the same world box: the layout does not jump from frame to frame
    view = first.box(grow=0.12)
    scenes, svgs = [], []
    for k in idx:
        sc = Scene(mech, motion, scales=first.scales, index=int(k))
        sc.__dict__["motion"] = first.motion  # one whole motion (cached) for all the paths
        fig = scene_figure(sc, show)
        fig.view["mechanism"] = view
        scenes.append(sc)
        svgs.append(fig.to_svg())
    return scenes, svgs


def _inline(svg: str, k: int) -> str:
    """An SVG document as an element of the page: no XML declaration, ids made unique per
    frame (the frames are drawn from the same layers, with the same ids)."""
    svg = svg.split("?>", 1)[1] if svg.startswith("<?xml") else svg
    svg = re.sub(r'\bid="', f'id="f{k}-', svg)
    return re.sub(r'url\(#', f'url(#f{k}-', svg)


def animation_html(mech: Mechanism, scenes: list[Scene], svgs: list[str],
                   seconds: float) -> str:
    """A self-contained HTML page showing the frames in a loop, `seconds` per turn. Each frame
    carries its input (radians or the length unit) and its points' positions (the file's length
    unit) as data, for programs that read the page."""
    n = len(svgs)
    dt = seconds / n
    share = 100.0 / n
    frames = []
    for k, (sc, svg) in enumerate(zip(scenes, svgs)):
        pts = {p: [float(v) for v in sc.pos(p)] for p in mech.points}
        inputs = [float(v) for v in sc.sol.inputs[sc.index]]
        frames.append(
            f'<div class="frame" id="frame-{k}" style="animation-delay:{k * dt:.6g}s" '
            f"data-input='{html.escape(json.dumps(inputs), quote=True)}' "
            f"data-points='{html.escape(json.dumps(pts), quote=True)}'>{_inline(svg, k)}</div>")
    title = html.escape(mech.name)
    return (
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
        f"<title>{title} — motion</title><style>\n"
        ".stage{position:relative}\n"
        ".frame{position:absolute;top:0;left:0;visibility:hidden;"
        f"animation:lw-show {seconds:.6g}s step-end infinite}}\n"
        ".frame:first-child{position:relative}\n"
        f"@keyframes lw-show{{0%{{visibility:visible}}{share:.6g}%{{visibility:hidden}}"
        "100%{visibility:hidden}}\n"
        "@media (prefers-reduced-motion: reduce){.frame{animation:none}"
        ".frame:first-child{visibility:visible}}\n"
        f"</style></head><body>\n<div class=\"stage\" data-frames=\"{n}\" "
        f"data-length-unit=\"{html.escape(mech.length_unit)}\">\n"
        + "\n".join(frames) + "\n</div>\n</body></html>\n")


#: the formats `write_animation` writes, by suffix
FORMATS = (".html", ".gif", ".mp4")


def ffmpeg_executable() -> str:
    """The ffmpeg program that encodes MP4: the one shipped by `imageio-ffmpeg` (installed with
    `linkwork[video]`), else `ffmpeg` on the PATH. An `OutputError` names what is missing."""
    try:
        import imageio_ffmpeg
    except ImportError:
        imageio_ffmpeg = None
    if imageio_ffmpeg is not None:
        try:
            return imageio_ffmpeg.get_ffmpeg_exe()
        except RuntimeError:  # the package without its binary (a platform it has no wheel for)
            pass
    exe = shutil.which("ffmpeg")
    if exe is None:
        raise OutputError("writing .mp4 needs ffmpeg, which is missing: install the 'video' "
                          "extra (pip install 'linkwork[video]', which brings imageio-ffmpeg and "
                          "its ffmpeg) or an ffmpeg program on the PATH; or write .gif or .html")
    return exe


def _rasters(svgs: list[str], path: Path, dpi: float) -> list:
    """The frames as RGB Pillow images (each SVG rendered to PNG by cairosvg)."""
    from PIL import Image

    images = []
    for svg in svgs:
        buf = Path(path).with_name(f".{path.stem}-frame.png")
        try:
            convert(svg, buf, dpi=dpi)
            with Image.open(buf) as im:
                images.append(im.convert("RGB"))
        finally:
            buf.unlink(missing_ok=True)
    return images


def _even(images: list) -> list:
    """The frames padded with white to the largest width and height rounded up to even numbers:
    H.264 in its common 4:2:0 form halves both, and every frame of a video has one size."""
    from PIL import Image

    w = max(im.width for im in images)
    h = max(im.height for im in images)
    w, h = w + w % 2, h + h % 2
    out = []
    for im in images:
        if im.size != (w, h):
            canvas = Image.new("RGB", (w, h), "white")
            canvas.paste(im, (0, 0))
            im = canvas
        out.append(im)
    return out


def write_mp4(images: list, path: Path, seconds: float) -> None:
    """Encode the frames as an H.264 MP4 (MPEG-4 part 2 where the ffmpeg lacks libx264), one
    loop in `seconds`, all or nothing."""
    exe = ffmpeg_executable()
    frames = _even(images)
    w, h = frames[0].size
    rate = (Fraction(len(frames)) / Fraction(repr(float(seconds)))).limit_denominator(1000)
    try:
        encoders = subprocess.run([exe, "-hide_banner", "-encoders"], capture_output=True,
                                  text=True, check=False).stdout
    except OSError as exc:
        raise OutputError(f"writing .mp4: ffmpeg ({exe}) cannot be run: {exc}") from None
    codec = (["-c:v", "libx264", "-pix_fmt", "yuv420p"] if " libx264 " in encoders
             else ["-c:v", "mpeg4", "-q:v", "3", "-pix_fmt", "yuv420p"])
    with output_path(path) as tmp:
        cmd = [exe, "-hide_banner", "-loglevel", "error", "-y",
               "-f", "rawvideo", "-pix_fmt", "rgb24", "-s", f"{w}x{h}",
               "-framerate", f"{rate.numerator}/{rate.denominator}", "-i", "-",
               *codec, "-movflags", "+faststart", "-f", "mp4", str(tmp)]
        raw = b"".join(im.tobytes() for im in frames)
        done = subprocess.run(cmd, input=raw, capture_output=True, check=False)
        if done.returncode != 0:
            why = done.stderr.decode("utf-8", "replace").strip().splitlines()[-1:] or ["?"]
            raise OutputError(f"writing {path}: ffmpeg failed: {why[0]}")


def write_animation(mech: Mechanism, path: Path, *, frames: int = 36,
                    show: Iterable[str] = ("mechanism",), seconds: float = 3.0,
                    dpi: float = 100.0) -> int:
    """Write the motion of `mech` as `path` (.html, .gif or .mp4); returns the number of
    frames."""
    suffix = path.suffix.lower()
    if suffix not in FORMATS:
        raise InputError(f"-o {path}: write {', '.join(FORMATS[:-1])} or {FORMATS[-1]}")
    if suffix == ".mp4":
        ffmpeg_executable()  # the missing codec is named before the frames are drawn
    scenes, svgs = motion_frames(mech, frames, show)
    if suffix == ".html":
        write_output_file(path, animation_html(mech, scenes, svgs, seconds))
        return len(svgs)
    images = _rasters(svgs, path, dpi)
    if suffix == ".mp4":
        write_mp4(images, path, seconds)
        return len(images)
    from PIL import Image

    images = [im.convert("P", palette=Image.Palette.ADAPTIVE) for im in images]
    out = io.BytesIO()
    images[0].save(out, format="GIF", save_all=True, append_images=images[1:],
                   duration=max(int(round(1000 * seconds / len(images))), 20), loop=0,
                   disposal=1)
    write_output_file(path, out.getvalue())
    return len(images)
