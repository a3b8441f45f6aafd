"""Pictures of what a chain draws: target vs traced with the links at a few crank angles, and an
animation of the mechanism drawing the curve (matplotlib, no display needed)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.animation import FuncAnimation, PillowWriter  # noqa: E402

from ...design.mechanism import ChainDesign  # noqa: E402
from ...design.synthesis import Chain, trace  # noqa: E402
from ...design.trace import built_chain, target_paths  # noqa: E402

__all__ = ["trace_figure", "trace_animation"]

LINK_ANGLES_DEG = (0, 60, 150, 250)


def _joints(chain: Chain, theta: float) -> np.ndarray:
    """(n + 1, 2) joint positions of a chain (ground pivot at its offset), mm."""
    steps = np.array([l.vector(np.array([theta]))[0] for l in chain.links])
    p = chain.offset + np.concatenate([[0j], np.cumsum(steps)])
    return np.column_stack([p.real, p.imag])


def _curves(mech: ChainDesign, n: int = 4000):
    theta = np.linspace(0, 2 * np.pi, n)
    paths = target_paths(mech, theta)
    built = built_chain(mech)
    return theta, paths, built, trace(built, theta)


def band_axes(ax, pen: np.ndarray, theta: np.ndarray, band) -> None:
    """The pen's error band (``design.play.PenBand``) beside the nominal path: its worst case and the
    95 % of prints, each drawn as the band across the path (the nominal path ± the band's part along
    its normal)."""
    at = np.interp(theta % (2 * np.pi), band.theta, band.worst_normal, period=2 * np.pi)
    p95 = np.interp(theta % (2 * np.pi), band.theta, band.p95_normal, period=2 * np.pi)
    t = np.gradient(pen)
    nrm = 1j * t / np.maximum(np.abs(t), 1e-12)
    for w, colour, alpha, label in ((at, "#f58518", 0.25, f"worst case from play (≤ {band.worst_normal.max():.2f} mm "
                                                          "across the path)"),
                                    (p95, "#e45756", 0.35, f"95 % of prints (≤ {band.p95_path_max:.2f} mm across)")):
        hi, lo = pen + nrm * w, pen - nrm * w
        ax.fill(np.concatenate([hi.real, lo.real[::-1]]), np.concatenate([hi.imag, lo.imag[::-1]]), color=colour,
                alpha=alpha, lw=0, label=label)


def band_figure(band, png, title: str = "") -> None:
    """The pen's error band (``design.play.PenBand``) over the crank's turn: across the path, the worst
    case and the band 95 % of prints stay in (what the drawing shows); from the nominal point at the
    same crank angle, the worst case (a lag along the path included)."""
    deg = np.degrees(band.theta)
    fig, ax = plt.subplots(figsize=(7.2, 3.4))
    ax.plot(deg, band.worst, color="#9d9d9d", lw=1, ls="--",
            label=f"worst case from the nominal point (≤ {band.worst.max():.2f} mm)")
    ax.fill_between(deg, 0, band.worst_normal, color="#f58518", alpha=0.35,
                    label=f"worst case across the path (≤ {band.worst_normal.max():.2f} mm)")
    ax.fill_between(deg, 0, band.p95_normal, color="#e45756", alpha=0.55,
                    label=f"95 % of prints across the path (each print ≤ {band.p95_path_max:.2f} mm)")
    ax.set_xlim(0, 360)
    ax.set_ylim(0, None)
    ax.set_xlabel("crank angle (°)")
    ax.set_ylabel("pen error (mm)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")
    if title:
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def trace_figure(mech: ChainDesign, stats: dict, png, svg=None, title: str = "", band=None) -> None:
    """Target (full series), the design's chain and the chain as built, links drawn at a few
    crank angles, arrows for the pen's direction, which way is up, and (``band``) the pen's error
    band from the kit's play beside the nominal path."""
    fig = trace_fig(mech, stats, title, band)
    fig.savefig(png, dpi=110)
    if svg is not None:
        fig.savefig(svg)
    plt.close(fig)


def _clear_of(texts: list, avoid: list, fig) -> None:
    """Move each annotation of ``texts`` (its text, by its offset from the point it marks) to the
    first of a ring of offsets where its text box overlaps none of ``avoid`` (artists: the legend,
    the other notes) and stays on its axes (else on the figure), measured with the figure's renderer."""
    from matplotlib.text import Text

    r = fig.canvas.get_renderer()
    page = fig.bbox
    offsets = [(20, 20), (20, -30), (-20, 20), (-20, -30)] + \
        [(d * np.cos(a), d * np.sin(a)) for d in (40, 70, 110, 160, 220) for a in np.radians(np.arange(0, 360, 30))]
    for t in texts:
        others = [a.get_window_extent(r) for a in avoid if a is not t] + \
            [Text.get_window_extent(o, r) for o in texts if o is not t]
        for frame in (t.axes.get_window_extent(r), page):  # on its axes if it can be
            for dx, dy in offsets:
                t.xyann = (dx, dy)
                t.set_horizontalalignment("left" if dx >= 0 else "right")
                b = Text.get_window_extent(t, r)
                if (b.x0 >= frame.x0 and b.x1 <= frame.x1 and b.y0 >= frame.y0 and b.y1 <= frame.y1
                        and not any(b.overlaps(o) for o in others)):
                    break
            else:
                continue
            break


def trace_fig(mech: ChainDesign, stats: dict, title: str = "", band=None):
    """The figure of :func:`trace_figure` (pyplot; the caller closes it), its notes placed clear of
    its legend."""
    theta, paths, built, pen = _curves(mech)
    dr = mech.drawing
    if dr is not None:
        fig, (ax, ax2) = plt.subplots(1, 2, figsize=(15, 8.5), gridspec_kw={"width_ratios": [1.25, 1]})
        tradeoff_axes(ax2, dr)
        z = np.append(dr.samples, dr.samples[0])
        ax.plot(z.real, z.imag, color="#999", lw=3.5, alpha=0.6, label=f"target: your drawing ({dr.source})")
    else:
        fig, ax = plt.subplots(figsize=(9, 9))
    if "full" in paths:
        ax.plot(paths["full"].real, paths["full"].imag, color="#999", lw=3.5, alpha=0.6, label="target: full Fourier series")
    ax.plot(paths["pruned"].real, paths["pruned"].imag, color="#4c78a8", lw=1.8, label="target: the design's links (pruned)")
    if band is not None:
        band_axes(ax, pen, theta, band)
    ax.plot(pen.real, pen.imag, color="#e45756", lw=0.9, ls="--", label="traced by the kit as built (its teeth)")
    turns = abs(mech.chain.links[0].speed)  # crank turns per drawing (the drive pair is 1:1)
    for k, deg in enumerate(LINK_ANGLES_DEG):
        J = _joints(built, np.radians(deg))
        ax.plot(J[:, 0], J[:, 1], "-o", color=plt.cm.viridis(k / len(LINK_ANGLES_DEG)), lw=1.2, ms=2.5, alpha=0.8,
                label=f"links at crank {deg}°" if turns == 1 else
                f"links at θ {deg}° (crank {deg * turns}°)")
    step = len(theta) // 24
    d = np.gradient(pen)[::step]
    d = d / np.maximum(np.abs(d), 1e-12) * 0.04 * np.ptp(pen.real)  # direction only, a fixed length
    ax.quiver(pen.real[::step], pen.imag[::step], d.real, d.imag, angles="xy", scale_units="xy", scale=1,
              color="#e45756", width=0.003, alpha=0.9)
    ax.plot([mech.chain.offset.real], [mech.chain.offset.imag], "k^", ms=9, label="ground pivot")
    notes = []
    if "max_deviation_mm" in stats and dr is not None:
        k = int(np.argmin(np.abs(dr.theta - stats["worst_theta_rad"])))
        notes.append(ax.annotate(f"largest deviation (same θ) {stats['max_deviation_mm']:.1f} mm", (dr.samples[k].real, dr.samples[k].imag),
                    xytext=(20, 20), textcoords="offset points", arrowprops={"arrowstyle": "->"}))
    elif "max_deviation_mm" in stats and "full" in paths:
        k = int(np.argmin(np.abs(theta - stats["worst_theta_rad"])))
        notes.append(ax.annotate(f"largest deviation {stats['max_deviation_mm']:.1f} mm",
                                 (paths["full"][k].real, paths["full"][k].imag), xytext=(20, 20),
                                 textcoords="offset points", arrowprops={"arrowstyle": "->"}))
    up = ax.annotate("up (+y)", xy=(0.04, 0.96), xytext=(0.04, 0.86), xycoords="axes fraction",
                arrowprops={"arrowstyle": "-|>", "lw": 2}, ha="center", fontsize=9)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    text = ", ".join(f"{k.split('_mm')[0].replace('_', ' ')} {v:.2f} mm" for k, v in stats.items()
                     if k.endswith("_mm") and isinstance(v, (int, float)))  # figures, not the error band's table
    ax.set_title(title or f"{text}")
    legend = ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.set_dpi(110)  # measured as saved
    _clear_of(notes, [legend, up], fig)
    return fig


def tradeoff_axes(ax, d) -> None:
    """Links against the measured deviation of their chain from the drawing; the chosen count marked."""
    n = [r.links for r in d.rows]
    ax.plot(n, [r.hausdorff_mm for r in d.rows], "-o", color="#e45756", label="Hausdorff (curve to curve)")
    ax.plot(n, [r.max_mm for r in d.rows], "--s", color="#4c78a8", ms=4, label="max at the same crank angle")
    ax.plot(n, [r.rms_mm for r in d.rows], ":^", color="#54a24b", ms=4, label="RMS at the same crank angle")
    if d.chosen:
        ax.axvline(d.chosen, color="#333", lw=1, ls="--")
        ax.annotate(f"chosen: {d.chosen} links", (d.chosen, ax.get_ylim()[1]), xytext=(5, -15),
                    textcoords="offset points", fontsize=9)
    ax.set_yscale("log")
    ax.set_xticks(n)
    ax.set_xlabel("links (the longest printable ones)")
    ax.set_ylabel("deviation from the drawing (mm)")
    ax.set_title(f"links vs deviation ({d.parametrisation.replace('_', ' ')})")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def trace_animation(mech: ChainDesign, gif, frames: int = 60, fps: int = 10) -> None:
    """The chain (as built) turning through one cycle, the pen leaving its path behind."""
    theta, paths, built, pen = _curves(mech, 2000)
    fig, ax = plt.subplots(figsize=(5.5, 5.5), dpi=80)
    target = paths.get("full", paths["pruned"]) if mech.drawing is None else mech.drawing.samples
    ax.plot(target.real, target.imag, color="#bbb", lw=2)
    drawn, = ax.plot([], [], color="#e45756", lw=1.3)
    arm, = ax.plot([], [], "-o", color="#4c78a8", lw=1.5, ms=3)
    reach = np.abs(np.concatenate([target, pen]) - mech.chain.offset).max() + 20
    ax.set_xlim(mech.chain.offset.real - reach, mech.chain.offset.real + reach)
    ax.set_ylim(mech.chain.offset.imag - reach, mech.chain.offset.imag + reach)
    ax.set_aspect("equal")
    ax.set_axis_off()

    def frame(i):
        t = 2 * np.pi * i / frames
        J = _joints(built, t)
        arm.set_data(J[:, 0], J[:, 1])
        upto = int(len(theta) * i / frames) + 1
        drawn.set_data(pen.real[:upto], pen.imag[:upto])
        return arm, drawn

    FuncAnimation(fig, frame, frames=frames + 1, blit=True).save(gif, writer=PillowWriter(fps=fps))
    plt.close(fig)
