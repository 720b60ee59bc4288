"""`linkwork animate`: the motion of a mechanism with chosen layers, as a self-contained HTML
page (SVG frames shown in turn by CSS), a GIF, or an MP4 (needs ffmpeg: `linkwork[video]`)."""

from __future__ import annotations

from pathlib import Path

import typer

from ..units import MAX_MAGNITUDE
from .common import load_mechanism, positive_option, user_errors

#: the most frames drawn (one per degree of a full turn)
MAX_FRAMES = 360


def register(app: typer.Typer) -> None:
    @app.command()
    def animate(
        mechanism: str = typer.Argument(..., help="a mechanism file, or library:NAME"),
        show: str = typer.Option("mechanism", "--show", help="layers, comma-separated, as for `draw` (mechanism, paths, velocities, …)"),
        frames: int = typer.Option(36, "--frames", help="positions drawn, evenly spaced over the whole motion"),
        seconds: float = typer.Option(3.0, "--seconds", help="duration of one loop"),
        dpi: float = typer.Option(100.0, "--dpi", help="resolution of GIF and MP4 frames"),
        output: str = typer.Option(..., "-o", "--output", help="FILE.html (SVG frames, self-contained), FILE.gif, or FILE.mp4 (needs ffmpeg: the 'video' extra)"),
    ) -> None:
        """Animate the motion: the drawing of `draw` at N positions over the whole motion."""
        from ..drawing.animation import write_animation
        from ..errors import InputError

        with user_errors():
            positive_option(seconds, "--seconds", MAX_MAGNITUDE)
            positive_option(dpi, "--dpi", 600.0)
            if not 2 <= frames <= MAX_FRAMES:
                raise InputError(f"--frames {frames}: give 2 to {MAX_FRAMES}")
            mech = load_mechanism(mechanism)
            layers = [t.strip() for t in show.split(",") if t.strip()]
            n = write_animation(mech, Path(output), frames=frames, show=layers, seconds=seconds,
                                dpi=dpi)
            typer.echo(f"wrote {output} ({n} frames)")
