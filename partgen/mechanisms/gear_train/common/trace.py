"""What the trace of every sub-slice shares: the output against the input of a turning train (the
stages' output shaft, the planetary's carrier) from its printed outlines — transmission error in
arcminutes, the ratio measured, the backlash at the output — its plot, ``trace --csv``'s rows and
the text ``trace`` prints for a turning train (the rack's: ``rack/trace.py``)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ....core.protocol import Trace
from ....export.report import figure_png
from . import KIND

__all__ = ["ARCMIN", "output_trace", "figure", "csv", "trace_text"]

ARCMIN = 60 * 180 / math.pi  # arcminutes per radian


def output_trace(spec, thetas: np.ndarray, drive: np.ndarray, nominal: np.ndarray, coast: np.ndarray,
                 overlap_mm2: np.ndarray, output: str, out: Path | None, lost_motion=None) -> Trace:
    """The trace of a turning train from the ``output``'s angles at the input angles ``thetas`` (rad) as
    its printed outlines turn it (``drive``, ``coast``) and as designed (``nominal``), with the outlines'
    overlap (mm²) at the nominal angles; ``lost_motion``: ``(spec, te_drive, te_coast)`` (arcmin) -> what
    play costs at the output (the stages'), or None; the plot into ``out``."""
    te = (drive - nominal) * ARCMIN
    lash = np.abs(coast - drive) * ARCMIN
    slope = np.polyfit(thetas, drive, 1)[0]
    stats = {"kind": KIND, "samples": len(thetas), "ratio_design": float(spec.ratio), "output": output,
             "ratio_measured": float(1.0 / abs(slope)),
             "ratio_measured_error": float((1.0 / abs(slope)) / float(spec.ratio) - 1),
             "transmission_error_arcmin": {"peak_to_peak": float(np.ptp(te)), "mean": float(te.mean())},
             "backlash_arcmin": {"min": float(lash.min()), "max": float(lash.max()), "mean": float(lash.mean())},
             "max_overlap_mm2": float(overlap_mm2.max())}
    if lost_motion is not None:
        stats["lost_motion_arcmin"] = lost_motion(spec, te, (coast - nominal) * ARCMIN)
    files = []
    if out is not None:
        (out / "transmission.png").write_bytes(figure(spec, thetas, te, lash))
        files = ["transmission.png"]
    return Trace(stats, files, columns=("input_rad", "output_rad", "transmission_error_arcmin", "backlash_arcmin"),
                 data=np.column_stack([thetas, drive, te, lash]))


def figure(spec, thetas: np.ndarray, te: np.ndarray, lash: np.ndarray, unit: str = "arcmin at the output"
            ) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 4))
    deg = np.degrees(thetas)
    ax.plot(deg, te, label=f"transmission error (drive flanks), {unit}")
    ax.plot(deg, lash, label=f"backlash, {unit}")
    ax.set_xlabel("input angle (°)")
    ax.set_ylabel(unit)
    ax.set_title(f"{spec.name}: over one turn of the output, from the printed outlines")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return figure_png(fig, 110)


def csv(header: str, trace: Trace) -> str:
    """``trace --csv``'s file: ``header``, then a row per input angle."""
    return header + "".join(f"{a:.9f},{b:.9f},{c:.6f},{d:.6f}\n" for a, b, c, d in trace.data)


def trace_text(spec, trace: Trace, folder) -> str:
    s = trace.stats
    lines = [f"{spec.name}: ratio measured {s['ratio_measured']:.5f} (design {s['ratio_design']:.5f}), "
             f"{s['samples']} angles over one output turn",
             f"  transmission error {s['transmission_error_arcmin']['peak_to_peak']:.2f} arcmin peak to peak at the "
             f"output; backlash {s['backlash_arcmin']['min']:.1f}–{s['backlash_arcmin']['max']:.1f} arcmin"]
    lm = s.get("lost_motion_arcmin")
    if lm:
        band = lm["transmission_error_band_arcmin"]
        lines.append(f"  lost motion at the output {lm['total']:.1f} arcmin (backlash {lm['backlash']:.1f}, bores' play "
                     f"{lm['bores']:.1f}); output within {band['low']:.1f}…{band['high']:.1f} arcmin of nominal")
        if "worst_case" in lm:
            lines.append(f"  over prints (±{lm['accuracy_mm']:g} mm): lost motion worst case {lm['worst_case']:.1f} arcmin, "
                         f"95 % of prints under {lm['p95']:.1f} (median {lm['p50']:.1f}); transmission-error band "
                         f"{band['p95_width']:.1f} arcmin wide for 95 % of prints, {band['worst_case_width']:.1f} at worst")
    if folder:
        lines.append(f"plots: {folder}/{', '.join(trace.files)}")
    return "\n".join(lines)
