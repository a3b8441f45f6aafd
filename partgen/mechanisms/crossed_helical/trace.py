"""The crossed helical pair's trace over a tooth pitch of gear 1 (exact 3-D, contact.py): the
transmission error, the backlash, the measured ratio and the contact along the faces; the figure,
the CSV and the text `trace` prints."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...checks.contact_pattern import pattern_text
from ...core.protocol import Trace
from ...export.report import transmission_figure
from .contact import contact_along_face, contact_angles, designed_backlash, measured_ratio
from .kit import CrossedKit
from .resolve import CrossedSpec

__all__ = ["trace", "csv", "trace_text"]


def trace(kind: str, spec: CrossedSpec, kit: CrossedKit, samples: int | None, out: Path | None,
          animate: bool = True) -> Trace:
    """The transmission error over one tooth pitch of gear 1 (where gear 2's driven flank sits
    against its nominal angle, µm along its pitch circle), the backlash, and the ratio measured
    from gear 2's loaded angle after one whole turn of gear 1; transmission.png."""
    n = samples or spec.samples
    pitch = 2 * math.pi / spec.gear1.teeth
    thetas = pitch * np.arange(n + 1) / n
    play = contact_angles(kit, thetas, 1e-7)
    r2 = spec.pair.pitch_radius(1)
    te, backlash = play["ahead"], (play["ahead"] - play["behind"]) * r2
    ratio, _, _ = measured_ratio(kit)
    design = float(spec.pair.ratio)
    out_angle = spec.angle2(thetas) + te
    # the instantaneous ratio between samples: gear 2's loaded angle's slope, against the nominal
    slope = np.diff(out_angle) / np.diff(thetas)
    local = float(np.abs(slope / spec.pair.speed2() - 1).max())
    stats = {"kind": kind, "samples": len(thetas), "ratio_design": design, "ratio_measured": ratio,
             "ratio_relative_error": abs(ratio / design - 1), "instantaneous_ratio_deviation": local,
             "transmission_error_rad": {"mean": float(te.mean()), "peak_to_peak": float(np.ptp(te))},
             "transmission_error_mm": {"mean": float(te.mean() * r2), "peak_to_peak": float(np.ptp(te) * r2)},
             "backlash_mm": {"min": float(backlash.min()), "max": float(backlash.max()),
                             "designed": designed_backlash(spec)},
             "contact_along_face": contact_along_face(kit, thetas[:-1], {k: v[:-1] for k, v in play.items()})}
    files = []
    if out is not None:
        (out / "transmission.png").write_bytes(transmission_figure(
            f"{spec.name}: exact 3-D contact of the printed solids", thetas, te * r2, backlash,
            "gear 1 angle (°), one tooth pitch", "µm along gear 2's pitch circle"))
        files = ["transmission.png"]
    return Trace(stats, files, columns=("input_rad", "output_rad", "transmission_error_rad", "backlash_mm"),
                 data=np.column_stack([thetas, out_angle, te, backlash]))


def csv(header: str, trace: Trace) -> str:
    return header + "".join(f"{a:.9f},{b:.9f},{c:.9f},{d:.6f}\n" for a, b, c, d in trace.data)


def trace_text(spec: CrossedSpec, trace: Trace, folder) -> str:
    s = trace.stats
    lines = [f"{spec.name}: ratio {s['ratio_measured']:.9f} measured after one turn of gear 1 (design "
             f"{s['ratio_design']:.9f}, relative error {s['ratio_relative_error']:.1e}); between phases within "
             f"{100 * s['instantaneous_ratio_deviation']:.3f} % of it",
             f"  transmission error {1000 * s['transmission_error_mm']['peak_to_peak']:.1f} µm peak to peak along "
             f"gear 2's pitch circle over a tooth ({s['samples']} phases); backlash "
             f"{s['backlash_mm']['min']:.3f}–{s['backlash_mm']['max']:.3f} mm",
             *("  " + pattern_text(s["contact_along_face"][g]) for g in ("gear2", "gear1"))]
    if folder:
        lines.append(f"plots: {folder}/{', '.join(trace.files)}")
    return "\n".join(lines)
