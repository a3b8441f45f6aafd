"""Figures of the balanced Bennett butterfly: the linkage drawn at a few poses (the planar form and
the spatial one, from above and in perspective) and the centre-of-mass trace (matplotlib, no display)."""

from __future__ import annotations

import dataclasses
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ...design import bennett_butterfly as bbf  # noqa: E402
from ...design.balanced import LINKS  # noqa: E402
from ...export.render import view_matrix  # noqa: E402
from ...export.report import figure_png  # noqa: E402

__all__ = ["poses_figure", "com_figure"]

COLOURS = {1: "#4c78a8", 4: "#4c78a8", 7: "#4c78a8", 10: "#4c78a8"}  # central links through S


def _segments(points: dict[str, np.ndarray]) -> list[tuple[int, np.ndarray]]:
    """(link, (k, 3) polyline of its joint points) for one pose."""
    out = []
    for i, (joints, _, _) in LINKS.items():
        out.append((i, np.array([points[j] for j in joints])))
    return out


def poses_figure(bb: bbf.BennettButterfly, angles_deg: list[float], com: list[np.ndarray] | None = None) -> bytes:
    """Rows: the planar form (all twists 0) from above, the spatial form from above, the spatial form
    seen from the side (elevation 25°, azimuth −60°: projected with ``render.view_matrix``, drawn
    in 2-D); one column per angle between links 1 and 4. PNG bytes."""
    flat = dataclasses.replace(bb, alpha=0.0, beta=0.0)
    n = len(angles_deg)
    view = view_matrix(25.0, -60.0)
    fig, axes = plt.subplots(3, n, figsize=(4.2 * n, 12), squeeze=False)
    for c, ang in enumerate(angles_deg):
        q1, q4 = 0.0, -math.radians(ang)
        for r, (form, persp) in enumerate(((flat, False), (bb, False), (bb, True))):
            P = bbf.pose(form, q1, q4)
            pts = {k: v[0] for k, v in P.points.items()}
            if persp:
                pts = {k: view @ v for k, v in pts.items()}
            ax = axes[r, c]
            for i, line in _segments(pts):
                col = COLOURS.get(i, "#f58518" if i in (2, 3, 5, 6) else "#54a24b")
                ax.plot(line[:, 0], line[:, 1], "-o", color=col, lw=2.5, ms=3)
                if not persp:
                    ax.annotate(str(i), line.mean(axis=0)[:2], fontsize=7, color="k")
            if persp:
                for j, (_, g, at) in bbf.JOINTS.items():  # joint axes as short ticks
                    p0, d = pts[at], view @ (P.axis[g][0] * 25)
                    ax.plot(*np.stack([p0 - d, p0 + d])[:, :2].T, color="0.5", lw=0.8)
            ax.plot(0, 0, "k*", ms=12)
            ax.set_aspect("equal")
            ax.grid(alpha=0.3)
            title = ("planar form (twists 0)", "spatial form from above", "spatial form from the side, joint axes grey")[r]
            ax.set_title(f"{title}\n{ang:.0f}° between links 1 and 4", fontsize=9)
    fig.suptitle("the balanced butterfly at a few poses (q1 = 0; S marked ★ at the origin)")
    return figure_png(fig, 90, "tight")


def com_figure(angles_deg: np.ndarray, traces: dict[str, list[float]], tolerance: float,
               labels: dict[str, str]) -> bytes:
    """Worst distance of the common centre of mass from S (over q1) against the shape angle, per mass model."""
    fig, ax = plt.subplots(figsize=(9, 4.5))
    for key, ys in traces.items():
        ax.semilogy(angles_deg, np.maximum(np.asarray(ys), 1e-9), "-o", ms=3, label=labels.get(key, key))
    ax.axhline(tolerance, color="k", ls=":", label=f"tolerance {tolerance:g} mm")
    ax.set_xlabel("angle between links 1 and 4 (°)")
    ax.set_ylabel("centre of mass from S (mm, worst over q1)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax.set_title("centre-of-mass trace over the input grid")
    return figure_png(fig, 90, "tight")
