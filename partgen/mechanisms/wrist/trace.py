"""The wrist pair's trace: the ratio i(θ) and the mating angle φ(θ) over the valid range, the tooth
rows, the cross gear's mate (``mate.trace_mate``); its CSV and its text."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...core.protocol import Trace
from ...design import spherical as sph
from .kit import workspace_theta_max
from .spec import WristSpec

__all__ = ["trace", "csv", "trace_text"]


def trace(kind: str, spec: WristSpec, kit, samples: int | None, out: Path | None, animate: bool = True) -> Trace:
    """The ratio i(θ) and the mating angle φ(θ) over the valid range, the tooth rows; wrist.png/.svg."""
    samples = samples or 2000
    pair = sph.tooth_rows(spec.I, spec.A, spec.long_pitch, spec.ring_teeth)
    theta_max = workspace_theta_max(spec.I, spec.max_bend)
    end = sph.valid_end(spec.I)
    ts, i_ode = sph.ratio_ode(end, spec.I, samples)
    t = np.linspace(0, end, samples + 1)
    stats = {"kind": kind, "nominal_ratio": spec.I, "valid_end_deg": round(float(np.degrees(end)), 6),
             "workspace_theta_max_deg": round(float(np.degrees(theta_max)), 6),
             "ode_vs_closed_form_max": float(np.abs(i_ode - sph.ratio(ts, spec.I)).max()),
             "mating_angle_methods_max_rad": float(np.abs(sph.mating_angle_meridian(t, spec.I)
                                                           - sph.mating_angle_latitude(t, spec.I)).max()),
             "rows": [{"k": r.k, "teeth": r.teeth, "theta_deg": round(float(np.degrees(r.theta)), 4),
                       "phi_deg": round(float(np.degrees(r.phi)), 4), "lat_pitch_mm": round(r.lat_pitch_1, 4),
                       "lat_pitch_off": round(r.lat_pitch_1 / spec.long_pitch - 1, 5) if r.k else None}
                      for r in pair.rows]}
    files = []
    if out is not None:
        from .plots import wrist_figure

        wrist_figure(spec.I, spec.A, theta_max, pair.rows, out / "wrist.png", out / "wrist.svg",
                     f"{spec.name}: I = {spec.I:g}, centre distance {spec.A:g} mm")
        files = ["wrist.png", "wrist.svg"]
    if spec.mate is not None:
        from .mate import trace_mate

        mate = trace_mate(spec)
        stats["mate"] = mate["stats"]
        if out is not None:
            from .plots import mate_figure

            mate_figure(spec, mate["rows"], out / "cross_mate.png")
            files.append("cross_mate.png")
    data = np.column_stack([t, sph.ratio(t, spec.I), sph.mating_angle(t, spec.I)])
    return Trace(stats, files, columns=("theta_rad", "ratio", "phi_rad"), data=data)


def csv(header: str, trace: Trace) -> str:
    return header + "".join(f"{t:.9f},{i:.9f},{p:.9f}\n" for t, i, p in trace.data)


def trace_text(spec: WristSpec, trace: Trace, folder) -> str:
    stats = trace.stats
    lines = [f"{spec.name}: I = {stats['nominal_ratio']:g}; valid range θ ≤ {stats['valid_end_deg']:.3f}° "
             f"(φ reaches 90°); workspace θ ≤ {stats['workspace_theta_max_deg']:.3f}°",
             f"  ODE vs closed form: {stats['ode_vs_closed_form_max']:.1e}; mating angle, meridian vs latitude: "
             f"{stats['mating_angle_methods_max_rad']:.1e} rad"]
    for r in stats["rows"][1:]:
        lines.append(f"  ring {r['k']}: {r['teeth']} teeth at θ = {r['theta_deg']:.3f}°, φ = {r['phi_deg']:.3f}°, "
                     f"latitudinal pitch {r['lat_pitch_mm']:.3f} mm ({100 * r['lat_pitch_off']:+.2f} % off the "
                     "longitudinal)")
    if "mate" in stats:
        m = stats["mate"]
        lines.append(f"  cross gear's mate (mid-plane): ratio {m['ratio']:.9f} (design {m['ratio_design']:g}, off by "
                     f"{m['ratio_error']:.1e}); transmission error {m['te_pp_um']:.2f} µm peak to peak at the cross "
                     f"gear's pitch circle; backlash {m['backlash_mid_mm']:.3f} mm")
    if folder:
        lines.append(f"plots: {folder}/{', '.join(trace.files)}")
    return "\n".join(lines)
