"""The report of a designed cam with Matplotlib: the follower diagrams (*Bewegungsdiagramme*:
s, v, a, j over the cam angle), the pressure angle over the cycle with its limit, the profile's
radius of curvature, and the cam drawn (profile, pitch curve, base circle, the follower at cam
angle 0, cusps marked). `cam_report_figure` returns the figure; `plots.save` writes it.
"""

from __future__ import annotations

import numpy as np

from ..synthesis.cams import CamReport
from .plots import _plt


def cam_report_figure(report: CamReport, *, max_pressure_angle: float | None = None,
                      length_unit: str = "mm", title: str | None = None):
    """One page: diagrams on the left, the drawn cam and the pressure angle on the right."""
    plt = _plt()
    cam = report.cam
    osc = cam.motion == "oscillating"
    deg = np.degrees(report.phi)
    fig = plt.figure(figsize=(13.0, 9.0), layout="constrained")
    grid = fig.add_gridspec(5, 2, width_ratios=(1.15, 1.0))
    unit = "°" if osc else length_unit
    conv = np.degrees if osc else (lambda v: v)
    names = [("s", f"lift s [{unit}]"), ("v", f"v [{unit}/s]"), ("a", f"a [{unit}/s²]"), ("j", f"j [{unit}/s³]")]
    axes = []
    for row, (key, label) in enumerate(names):
        ax = fig.add_subplot(grid[row, 0], sharex=axes[0] if axes else None)
        ax.plot(deg, conv(report.diagrams[key]), lw=1.2, color="C0")
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set_ylabel(label)
        for j in report.joins:
            ax.axvline(np.degrees(j.angle), color="0.85", lw=0.6, zorder=0)
        ax.grid(True, lw=0.3, alpha=0.5)
        axes.append(ax)
    for ax in axes[:-1]:
        ax.tick_params(labelbottom=False)
    rax = fig.add_subplot(grid[4, 0], sharex=axes[0])
    # the curvature 1/ρ stays finite where the profile turns straight (ρ → ∞)
    with np.errstate(divide="ignore"):
        kappa = 1.0 / report.radius_of_curvature
    rax.plot(deg, kappa, lw=1.0, color="C2")
    rax.axhline(0.0, color="0.6", lw=0.6)
    rax.set_ylabel(f"1/ρ profile [1/{length_unit}]")
    rax.set_xlabel("cam angle φ [°]")
    rax.set_xlim(0, 360)
    rax.grid(True, lw=0.3, alpha=0.5)
    if report.undercut.any():
        lo, hi = rax.get_ylim()
        rax.fill_between(deg, lo, hi, where=report.undercut, color="C3", alpha=0.15, label="undercut")
        rax.legend(loc="upper right", fontsize=8)
    axes[0].set_title(f"follower diagrams at ω = {report.speed:.4g} rad/s", fontsize=10)

    # the cam drawn
    cax = fig.add_subplot(grid[0:3, 1])
    prof, pitch = report.profile, report.pitch
    closed = lambda p: np.vstack([p, p[:1]])  # noqa: E731
    cax.fill(*closed(prof).T, color="0.92", zorder=0)
    cax.plot(*closed(prof).T, color="k", lw=1.4, label="profile")
    if cam.follower != "flat":
        cax.plot(*closed(pitch).T, color="C0", lw=0.8, ls="--", label="pitch curve")
    t = np.linspace(0, 2 * np.pi, 361)
    O = np.asarray(cam.center, dtype=float)
    cax.plot(O[0] + cam.base_radius * np.cos(t), O[1] + cam.base_radius * np.sin(t), color="0.5", lw=0.6,
             ls=":", label="base circle")
    cax.plot(*O, "k+", ms=10)
    C = cam.follower_point()
    if cam.follower == "roller":
        cax.plot(C[0] + cam.roller_radius * np.cos(t), C[1] + cam.roller_radius * np.sin(t), color="C1", lw=1.2)
        cax.plot(*C, "o", color="C1", ms=3)
    elif cam.follower == "knife":
        cax.plot(*C, "v", color="C1", ms=7)
    else:
        nu = cam.face_normal()
        along = np.array([-nu[1], nu[0]])
        half = 0.6 * cam.base_radius
        seg = np.array([C - half * along, C + half * along])
        cax.plot(*seg.T, color="C1", lw=2.0)
    if osc:
        A = np.asarray(cam.pivot, dtype=float)
        cax.plot([A[0], C[0]], [A[1], C[1]], color="C1", lw=1.5)
        cax.plot(*A, "^", color="C1", ms=8)
    else:
        e = cam.line_of_motion()
        stem = np.array([C, C + (cam.base_radius + cam.program.max_lift) * e])
        cax.plot(*stem.T, color="C1", lw=1.5)
    if report.cusps.size:
        pts = cam.profile.derivatives(report.cusps, 0)[0]
        cax.plot(*pts.T, "x", color="C3", ms=8, label="cusps")
    cax.set_aspect("equal")
    cax.legend(loc="upper right", fontsize=8)
    cax.set_title(f"{cam.motion} {cam.follower} follower, base radius {cam.base_radius:.4g} {length_unit}"
                  + (f", roller {cam.roller_radius:.4g}" if cam.follower == "roller" else ""), fontsize=10)
    cax.grid(True, lw=0.3, alpha=0.4)

    pax = fig.add_subplot(grid[3:5, 1])
    pax.plot(deg, np.degrees(report.pressure_angle), color="C4", lw=1.2)
    if max_pressure_angle is not None:
        for sgn in (1, -1):
            pax.axhline(sgn * np.degrees(max_pressure_angle), color="C3", lw=0.8, ls="--")
    pax.axhline(0.0, color="0.6", lw=0.6)
    pax.set_xlim(0, 360)
    pax.set_xlabel("cam angle φ [°]")
    pax.set_ylabel("pressure angle α [°]")
    pax.set_title(f"largest |α| = {np.degrees(report.max_pressure_angle):.3f}° at "
                  f"φ = {np.degrees(report.angle_of_max_pressure):.2f}°", fontsize=10)
    pax.grid(True, lw=0.3, alpha=0.5)
    if title:
        fig.suptitle(title)
    return fig
