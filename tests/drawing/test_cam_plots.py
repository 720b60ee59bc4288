"""The cam design report: the follower diagrams, curvature, the cam drawn and the pressure angle on
one page, with the largest pressure angle in its title; written as SVG, PNG or PDF."""

from __future__ import annotations

import numpy as np
import pytest

from linkwork.drawing.cam_plots import cam_report_figure
from linkwork.drawing.plots import save
from linkwork.model import DiscCam, MotionProgram, Segment
from linkwork.synthesis import analyse


def cam(follower="roller", **kw):
    prog = MotionProgram([Segment("rise", np.radians(90), 20.0, "cycloidal"), Segment("dwell", np.radians(90)),
                          Segment("return", np.radians(90), 20.0, "parabolic"), Segment("dwell", np.radians(90))])
    return DiscCam(prog, follower, 30.0, roller_radius=8.0 if follower == "roller" else 0.0, **kw)


@pytest.mark.parametrize("follower", ["roller", "knife", "flat"])
def test_report_page(tmp_path, follower):
    rep = analyse(cam(follower))
    fig = cam_report_figure(rep, max_pressure_angle=np.radians(30), title="test cam")
    assert len(fig.axes) == 7
    titles = " ".join(ax.get_title() for ax in fig.axes)
    assert f"largest |α| = {np.degrees(rep.max_pressure_angle):.3f}°" in titles
    assert f"translating {follower} follower" in titles
    for ext in ("svg", "png", "pdf"):
        path = save(cam_report_figure(rep), tmp_path / f"r.{ext}")
        assert path.stat().st_size > 5_000
