"""Figures of a wrist pair like the paper's: the ratio i(θ) and mating angle φ(θ) (closed form vs
the ODE and both mating rules), and the two pitch meridians in contact (matplotlib, no display)."""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ...design import spherical as sph  # noqa: E402

__all__ = ["wrist_figure"]


def wrist_figure(I: float, A: float, theta_max: float, rows, png, svg=None, title: str = "") -> None:
    """Three panels: i(θ), φ(θ), and the meridians of both pitch surfaces (straight wrist)."""
    end = sph.valid_end(I)
    t = np.linspace(0, end, 400)
    fig, ax = plt.subplots(1, 3, figsize=(15, 5))
    ts, i_ode = sph.ratio_ode(end, I, 400)
    ax[0].plot(np.degrees(t), sph.ratio(t, I), lw=2, label="closed form I / (cos²(θ/2) + I² sin²(θ/2))")
    ax[0].plot(np.degrees(ts[::20]), i_ode[::20], "o", ms=4, label="the paper's ODE (RK4)")
    ax[0].axvline(math.degrees(end), color="k", ls=":", label=f"end of the valid range {math.degrees(end):.1f}°")
    ax[0].axvspan(0, math.degrees(theta_max), color="#4c78a8", alpha=0.08, label="workspace")
    ax[0].set_xlabel("θ (°) on gear 1")
    ax[0].set_ylabel("ratio i = r1 / r2")
    ax[0].ticklabel_format(axis="y", useOffset=False)  # a constant ratio reads 1.000, not 1e-12 + 1
    lo, hi = ax[0].get_ylim()
    if hi - lo < 1e-3:  # a constant ratio (I = 1): a readable band around it
        ax[0].set_ylim(lo - 0.05, hi + 0.05)
    ax[0].legend(fontsize=8)
    ax[1].plot(np.degrees(t), np.degrees(sph.mating_angle_meridian(t, I)), lw=2, label="φ = ∫ i dθ (meridian arcs)")
    ax[1].plot(np.degrees(t[::25]), np.degrees(sph.mating_angle_latitude(t[::25], I)), "s", ms=4,
               label="φ = arcsin(i sin θ) (latitude arcs)")
    ax[1].plot(np.degrees(t), np.degrees(t), color="#aaa", ls="--", label="φ = θ (I = 1)")
    for r in rows[1:]:
        ax[1].plot(math.degrees(r.theta), math.degrees(r.phi), "k^")
    ax[1].set_xlabel("θ (°) on gear 1")
    ax[1].set_ylabel("φ (°) on gear 2")
    ax[1].legend(fontsize=8)
    r1, r2 = sph.pitch_radii(t, I, A)
    phi = sph.mating_angle(t, I)
    for sgn in (1, -1):
        ax[2].plot(sgn * r1 * np.sin(t), r1 * np.cos(t), color="#4c78a8", lw=2, label="gear 1" if sgn > 0 else None)
        ax[2].plot(sgn * r2 * np.sin(phi), A - r2 * np.cos(phi), color="#f58518", lw=2, label="gear 2" if sgn > 0 else None)
    for r in rows:
        p1 = float(sph.pitch_radii(r.theta, I, A)[0])
        ax[2].plot([p1 * math.sin(r.theta), -p1 * math.sin(r.theta)], [p1 * math.cos(r.theta)] * 2, "o", color="#4c78a8")
    ax[2].plot([0, 0], [0, A], "k+", ms=12)
    ax[2].set_aspect("equal")
    ax[2].set_xlabel("mm")
    ax[2].set_title("pitch meridians, wrist straight; dots: tooth rings")
    fig.suptitle(title or f"I = {I:g}, A = {A:g} mm")
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    if svg is not None:
        fig.savefig(svg)
    plt.close(fig)


def mate_figure(spec, rows, png) -> None:
    """Two panels: the cross gear and its mate in mesh in their mid-plane (the cross gear's plane
    x = 0), and the transmission error over the traced mate turns."""
    from shapely.geometry import Polygon

    from ...geometry.cross_gear import GROW
    from ...geometry.cross_mate import mate_pose, mate_section
    from ...geometry.gear import gear_outline

    cs, mate = spec.cross, spec.mate
    sec = mate_section(cs, mate)
    T = mate_pose(0.0, cs, mate)
    fig, ax = plt.subplots(1, 2, figsize=(13, 5.5))
    mp = np.asarray(sec.exterior.coords)
    P = np.column_stack([mp, np.zeros(len(mp))]) @ T[:3, :3].T + T[:3, 3]  # the mate's section in the cross gear's frame
    ax[0].fill(P[:, 1], P[:, 2], facecolor="#e45756", edgecolor="#8c1c13", lw=0.8, alpha=0.6, label=f"mate, {mate.teeth} teeth")
    prof = np.asarray(Polygon(gear_outline(cs).points).buffer(GROW, join_style="mitre").exterior.coords)
    ax[0].fill(prof[:, 0], prof[:, 1], facecolor="#54a24b", edgecolor="#1d5e1d", lw=0.8, alpha=0.6, label=f"cross gear, {cs.teeth} teeth")
    A, ra = mate.centre_distance(cs), mate.tip_radius(cs)
    ax[0].set_xlim(-ra - 2, ra + 2)
    ax[0].set_ylim(cs.root_radius - 4, A + 4)
    ax[0].set_aspect("equal")
    ax[0].set_xlabel("y (mm)")
    ax[0].set_ylabel("z (mm), the cross gear's pole axis")
    ax[0].set_title("mid-plane (x = 0): the mate's exact generated section")
    ax[0].legend(fontsize=8, loc="lower right")
    psi, te = rows[:, 0], rows[:, 2]
    ax[1].plot(np.degrees(psi), te * cs.pitch_radius * 1000, "o-", ms=3)
    ax[1].set_xlabel("mate turn ψ (°)")
    ax[1].set_ylabel("transmission error at the cross gear's pitch circle (µm)")
    ax[1].set_title(f"ratio {cs.teeth}/{mate.teeth}: mate turns per cross-gear turn")
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)
