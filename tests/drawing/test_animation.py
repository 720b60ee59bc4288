"""`linkwork animate`: the HTML page holds N frames at N evenly spaced inputs of the whole
motion, whose points are where `solve` puts them at those inputs (and the crank pin where the
crank's closed form puts it); the drawn dots are the same affine image of those positions in
every frame (one layout for all frames); the GIF has N frames."""

from __future__ import annotations

import html
import json
import re

import numpy as np
import pytest
from PIL import Image
from typer.testing import CliRunner

import linkwork
from linkwork.cli import app

runner = CliRunner()


def _frames(text: str) -> list[dict]:
    out = []
    for m in re.finditer(r'<div class="frame" id="frame-(\d+)"[^>]*data-input=\'([^\']*)\' '
                         r'data-points=\'([^\']*)\'>(.*?)</svg>\s*</div>', text, re.S):
        out.append({"k": int(m.group(1)), "input": json.loads(html.unescape(m.group(2))),
                    "points": json.loads(html.unescape(m.group(3))), "svg": m.group(4)})
    return out


@pytest.mark.parametrize("n", [12, 8])
def test_html_frames_are_the_solver_positions(tmp_path, n):
    out = tmp_path / "m.html"
    r = runner.invoke(app, ["animate", "library:crank-rocker", "--show", "mechanism,paths",
                            "--frames", str(n), "-o", str(out)])
    assert r.exit_code == 0, r.output
    text = out.read_text()
    frames = _frames(text)
    assert [f["k"] for f in frames] == list(range(n))
    assert text.count('class="frame"') == n
    mech = linkwork.load("library:crank-rocker")
    u0 = mech.driver_input_at_design(mech.drivers[0])
    u = u0 + 2 * np.pi * np.arange(n) / n  # a full turn in n equal steps
    np.testing.assert_allclose([f["input"][0] for f in frames], u, rtol=0, atol=1e-12)
    sol = linkwork.solve(mech, u)
    for k, f in enumerate(frames):
        for p, xy in f["points"].items():
            np.testing.assert_allclose(xy, sol.point(p).position[k], rtol=0, atol=1e-9)
    # the crank pin A on its circle about O2 (closed form)
    O2, A = np.array(frames[0]["points"]["O2"]), np.array(frames[0]["points"]["A"])
    r = np.hypot(*(A - O2))
    for k, f in enumerate(frames):
        np.testing.assert_allclose(f["points"]["A"], O2 + r * np.array([np.cos(u[k]), np.sin(u[k])]),
                                   atol=1e-9)
    # drawn: the tracer point's dot is x_svg = ox + x/s, y_svg = oy - y/s in every frame
    dots = []
    for f in frames:
        m = re.search(rf'<circle id="f{f["k"]}-point-C" cx="([-\d.]+)" cy="([-\d.]+)"', f["svg"])
        dots.append([float(m.group(1)), float(m.group(2))])
    dots, world = np.array(dots), np.array([f["points"]["C"] for f in frames])
    s = (world[1, 0] - world[0, 0]) / (dots[1, 0] - dots[0, 0])
    origin = dots[0] - world[0] * np.array([1, -1]) / s
    np.testing.assert_allclose(dots, origin + world * np.array([1, -1]) / s, atol=2e-3)


def test_gif_has_n_frames(tmp_path):
    out = tmp_path / "m.gif"
    r = runner.invoke(app, ["animate", "library:crank-rocker", "--frames", "6", "--dpi", "40",
                            "-o", str(out)])
    assert r.exit_code == 0, r.output
    with Image.open(out) as im:
        assert im.format == "GIF" and im.n_frames == 6


@pytest.mark.parametrize("args, words", [
    (["--frames", "1"], "--frames"), (["--frames", "5000"], "--frames"),
    (["-o", "x.mp3"], ".html, .gif or .mp4"), (["--show", "nonsense"], "unknown layer")])
def test_bad_arguments_are_named(tmp_path, args, words):
    argv = ["animate", "library:crank-rocker", "-o", str(tmp_path / "m.html")] + args
    if "-o" in args:
        argv = ["animate", "library:crank-rocker"] + ["-o", str(tmp_path / args[1])]
    r = runner.invoke(app, argv)
    assert r.exit_code != 0 and words in r.output


def test_mp4_has_n_frames_of_the_gif_size(tmp_path):
    """The MP4 read back by ffmpeg: N frames, the GIF's frame size (rounded up to even numbers,
    as 4:2:0 video needs), N frames in the loop's seconds, and the same picture as the GIF."""
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")
    n, seconds = 6, 2.0
    args = ["animate", "library:crank-rocker", "--frames", str(n), "--dpi", "40",
            "--seconds", str(seconds)]
    gif, mp4 = tmp_path / "m.gif", tmp_path / "m.mp4"
    for out in (gif, mp4):
        r = runner.invoke(app, args + ["-o", str(out)])
        assert r.exit_code == 0, r.output
    with Image.open(gif) as im:
        w, h = im.size
        im.seek(0)
        first = np.asarray(im.convert("RGB"), dtype=float)
    reader = imageio_ffmpeg.read_frames(str(mp4))
    meta = next(reader)
    frames = [np.frombuffer(f, np.uint8) for f in reader]
    assert len(frames) == n
    assert tuple(meta["size"]) == (w + w % 2, h + h % 2)
    assert meta["fps"] == pytest.approx(n / seconds)
    picture = frames[0].reshape(h + h % 2, w + w % 2, 3)[:h, :w].astype(float)
    assert np.abs(picture - first).mean() < 8  # lossy coding of the same drawing


def test_mp4_without_ffmpeg_names_what_is_missing(tmp_path, monkeypatch):
    import builtins
    import shutil

    real_import = builtins.__import__

    def no_imageio(name, *a, **k):
        if name == "imageio_ffmpeg":
            raise ImportError(name)
        return real_import(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", no_imageio)
    monkeypatch.setattr(shutil, "which", lambda name: None)
    out = tmp_path / "m.mp4"
    r = runner.invoke(app, ["animate", "library:crank-rocker", "-o", str(out)])
    assert r.exit_code != 0
    assert "ffmpeg" in r.output and "linkwork[video]" in r.output
    assert not out.exists()
