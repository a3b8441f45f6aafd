"""The rack and pinion's trace: the rack's travel against the pinion's angle over the travel, from the
printed sections (transmission error in µm at the rack, the measured mm per radian, the backlash),
what play costs at the rack (``play.py``), and the text ``trace`` prints."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....core.protocol import Trace
from ..common import KIND
from ..common.trace import figure
from .kit import RackKit
from .motion import turn_rack
from .play import lost_motion
from .resolve import RackSpec

__all__ = ["trace", "trace_text"]


def trace(spec: RackSpec, kit: RackKit, samples: int | None, out: Path | None) -> Trace:
    thetas = np.linspace(*spec.thetas_range, samples or 90)
    turned = turn_rack(kit, thetas)
    te = (turned["drive"] - turned["nominal"]) * 1000  # µm
    lash = turned["coast"] - turned["drive"]
    slope = np.polyfit(thetas, turned["drive"], 1)[0]
    stats = {"kind": KIND, "samples": len(thetas), "output": "rack",
             "ratio_design": spec.pinion.pitch_radius, "ratio_measured": float(slope),
             "ratio_unit": "mm of rack per rad of pinion",
             "ratio_measured_error": float(slope / spec.pinion.pitch_radius - 1),
             "transmission_error_um": {"peak_to_peak": float(np.ptp(te)), "mean": float(te.mean())},
             "backlash_mm": {"min": float(lash.min()), "max": float(lash.max()), "mean": float(lash.mean())},
             "max_overlap_mm2": float(turned["overlap_mm2"].max()),
             "lost_motion_mm": lost_motion(spec, kit, turned["drive"] - turned["nominal"],
                                           turned["coast"] - turned["nominal"])}
    files = []
    if out is not None:
        (out / "transmission.png").write_bytes(figure(spec, thetas, te, lash * 1000, "µm at the rack"))
        files = ["transmission.png"]
    return Trace(stats, files, columns=("input_rad", "output_mm", "transmission_error_um", "backlash_mm"),
                 data=np.column_stack([thetas, turned["drive"], te, lash]))


def trace_text(spec: RackSpec, trace: Trace, folder) -> str:
    s = trace.stats
    lines = [f"{spec.name}: {s['ratio_measured']:.5f} mm of rack per rad (design {s['ratio_design']:.5f}), "
             f"{s['samples']} angles over the travel",
             f"  transmission error {s['transmission_error_um']['peak_to_peak']:.2f} µm peak to peak at the "
             f"rack; backlash {s['backlash_mm']['min']:.3f}–{s['backlash_mm']['max']:.3f} mm"]
    lm = s.get("lost_motion_mm")
    if lm:
        band, at = lm["transmission_error_band_mm"], lm["pinion_arcmin"]
        lines += [f"  lost motion at the rack {lm['total']:.3f} mm ({at['total']:.1f} arcmin at the pinion; backlash "
                  f"{lm['backlash']:.3f}, bores' play {lm['bores']:.3f}); rack within {1000 * band['low']:.0f}…"
                  f"{1000 * band['high']:.0f} µm of nominal",
                  f"  over prints (±{lm['accuracy_mm']:g} mm): lost motion worst case {lm['worst_case']:.3f} mm, 95 % of "
                  f"prints under {lm['p95']:.3f} (median {lm['p50']:.3f}); transmission-error band "
                  f"{1000 * band['p95_width']:.0f} µm wide for 95 % of prints, {1000 * band['worst_case_width']:.0f} at worst"]
    return "\n".join(lines + ([f"plots: {folder}/{', '.join(trace.files)}"] if folder else []))
