"""The spur gear pair's trace: the transmission error and the backlash over one output revolution
from the printed outlines, its figure (transmission.png), the CSV and the text `trace` prints."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...core.protocol import Trace
from ...export.report import transmission_figure
from ..solid_pair import transmission_csv
from .checks import sweep
from .kit import PairKit
from .resolve import PairSpec

__all__ = ["trace", "csv", "trace_text"]


def trace(kind: str, spec: PairSpec, kit: PairKit, samples: int | None, out: Path | None, animate: bool = True) -> Trace:
    """The transmission error over one output revolution from the printed outlines: how far the
    driven gear lags its nominal angle with gear 1's flank against it (rad at the output, and
    mm along its pitch circle), and the backlash; transmission.png."""
    thetas, play = sweep(spec, kit, samples)
    r2 = spec.centre_distance * spec.gear2.teeth / (spec.gear1.teeth + spec.gear2.teeth)
    te, backlash = play["ahead"], (play["ahead"] - play["behind"]) * r2
    out_angle = thetas * spec.gear1.teeth / spec.gear2.teeth
    stats = {"kind": kind, "samples": len(thetas), "ratio": spec.gear2.teeth / spec.gear1.teeth,
             "transmission_error_rad": {"mean": float(te.mean()), "peak_to_peak": float(np.ptp(te))},
             "transmission_error_mm": {"mean": float(te.mean() * r2), "peak_to_peak": float(np.ptp(te) * r2)},
             "backlash_mm": {"min": float(backlash.min()), "max": float(backlash.max()),
                             "designed": 2 * spec.gear1.system.backlash_per_gear}}
    files = []
    if out is not None:
        (out / "transmission.png").write_bytes(transmission_figure(
            f"{spec.name}: over one turn of the output, from the printed outlines", out_angle, te * r2, backlash,
            "output angle (°)", "µm along the output's pitch circle", markers=False))
        files = ["transmission.png"]
    return Trace(stats, files, columns=("input_rad", "output_rad", "transmission_error_rad", "backlash_mm"),
                 data=np.column_stack([thetas, out_angle, te, backlash]))


def csv(header: str, trace: Trace) -> str:
    return transmission_csv(header, trace)


def trace_text(spec: PairSpec, trace: Trace, folder) -> str:
    s = trace.stats
    lines = [f"{spec.name}: ratio {s['ratio']:.4f}, {s['samples']} angles over one output turn",
             f"  transmission error {1000 * s['transmission_error_mm']['peak_to_peak']:.1f} µm peak to peak along "
             f"the output's pitch circle; backlash {s['backlash_mm']['min']:.3f}–{s['backlash_mm']['max']:.3f} mm"]
    if folder:
        lines.append(f"plots: {folder}/{', '.join(trace.files)}")
    return "\n".join(lines)
