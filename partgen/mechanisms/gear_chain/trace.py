"""The gear chain's trace: the pen of the chain as built over one crank turn (or one drawing) against
its targets (the full Fourier series, the pruned chain, the user's drawing), the pen's error band
from the kit's play, the figures (drawn by ``trace_plots``), the CSV and the text `trace` prints."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...core.quantise import r6
from ...core.protocol import Trace
from .kit import Kit
from .resolve import ChainSpec

__all__ = ["trace", "csv", "trace_text", "pen_error_band"]


def _drawing_deviation(mech) -> dict:
    """The pen of the chain as built (its teeth's speeds, its links' lengths) against the user's
    samples: at each sample's crank angle (max, RMS) and as curves (Hausdorff), mm."""
    from ...design.drawing import measure
    from ...design.synthesis import trace
    from ...design.trace import built_chain

    d = mech.drawing
    chain = built_chain(mech)
    h, mx, rms = measure(chain, d)
    same = np.abs(trace(chain, d.theta) - d.samples)
    return {"target": "drawing", "drawing": d.source, "drawing_samples": int(len(d.samples)),
            "parametrisation": d.parametrisation, "max_deviation_mm": r6(mx), "rms_mm": r6(rms),
            "hausdorff_mm": r6(h), "worst_theta_rad": r6(d.theta[int(np.argmax(same))]),
            "tradeoff": [{"links": r.links, "hausdorff_mm": r6(r.hausdorff_mm), "max_deviation_mm": r6(r.max_mm),
                          "rms_mm": r6(r.rms_mm), "shortest_link_mm": r6(r.shortest_mm)} for r in d.rows]}


def pen_error_band(spec: ChainSpec, theta: np.ndarray):
    """The pen's error band from the kit's backlash and running-fit play (``design.play``), on the
    design's printer."""
    from ...design.play import pen_band

    p = spec.params
    return pen_band(spec.mechanism, p.joints.running_clearance / 2, theta, p.printer.xy_accuracy)


def trace(spec: ChainSpec, kit: Kit | None, samples: int | None, out: Path | None,
          animate: bool = True) -> Trace:
    """The pen of the chain as built over one crank turn vs its targets; trace.png/.svg/.gif into ``out``."""
    from ...design.synthesis import trace as trace_chain
    from ...design.trace import built_chain, built_speeds, crank_turns, deviation, target_paths

    mech = spec.mechanism
    samples = samples or 3600
    theta = 2 * np.pi * np.arange(samples) / samples
    pen = trace_chain(built_chain(mech), theta)
    targets = target_paths(mech, theta)
    speeds = built_speeds(mech)
    stats = {"samples": samples, "speeds": [str(w) for w in speeds], "crank_turns_per_drawing": str(crank_turns(mech)),
             "closes_after_one_turn": all(w.denominator == 1 for w in speeds),
             "vs_pruned": deviation(pen, targets["pruned"], theta).to_dict()}
    if "full" in targets:
        stats.update(deviation(pen, targets["full"], theta).to_dict())
        stats["pruned_vs_full"] = deviation(targets["pruned"], targets["full"], theta).to_dict()
    if mech.drawing is not None:
        stats.update(_drawing_deviation(mech))
    band = pen_error_band(spec, theta)
    stats["pen_error_band_mm"] = band.to_dict()
    files = []
    if out is not None:
        from .trace_plots import band_figure, trace_animation, trace_figure

        head = {k: v for k, v in stats.items() if k.endswith("_mm") and not isinstance(v, dict)} or \
            {k: v for k, v in stats["vs_pruned"].items() if k.endswith("_mm")}
        if "worst_theta_rad" in stats:
            head["worst_theta_rad"] = stats["worst_theta_rad"]
        trace_figure(mech, head, out / "trace.png", out / "trace.svg",
                     f"{spec.params.name}: the pen over "
                     + ("one crank turn (mm)" if crank_turns(mech) == 1 else
                        f"one drawing, {crank_turns(mech)} crank turns (mm)"), band=band)
        band_figure(band, out / "pen_band.png", f"{spec.params.name}: the pen's error from the kit's backlash and "
                    f"running-fit play, on {spec.params.printer.name} (±{spec.params.printer.xy_accuracy:g} mm)")
        files = ["trace.png", "trace.svg", "pen_band.png"]
        if animate:
            trace_animation(mech, out / "trace.gif")
            files.append("trace.gif")
    return Trace(stats, files, columns=("theta_rad", "x_mm", "y_mm"),
                 data=np.column_stack([theta, pen.real, pen.imag]), animation=("trace.gif",))


def csv(header: str, trace: Trace) -> str:
    return header + "".join(f"{t:.9f},{x:.6f},{y:.6f}\n" for t, x, y in trace.data)


def trace_text(spec: ChainSpec, trace: Trace, folder) -> str:
    stats = trace.stats
    turns = stats.get("crank_turns_per_drawing", "1")
    over = "one crank turn" if turns == "1" else f"one drawing ({turns} crank turns)"
    lines = [f"{spec.params.name}: pen over {over}, {stats['samples']} samples; link speeds as built "
             f"{', '.join(stats['speeds'])}"
             + ("" if stats["closes_after_one_turn"] else " (fractional: the path does not close after one turn)"),
             f"{'traced vs':<28}{'max (same θ) mm':>16}{'rms mm':>10}{'Hausdorff mm':>14}"]
    rows = [("the design's chain (pruned)", stats["vs_pruned"])]
    if stats.get("target") == "drawing":
        rows.insert(0, (f"the drawing ({stats['drawing_samples']} pts)", stats))
    elif "max_deviation_mm" in stats:
        rows.insert(0, ("the full Fourier series", stats))
        rows.append(("(pruned vs full)", stats["pruned_vs_full"]))
    for label, d in rows:
        lines.append(f"{label:<28}{d['max_deviation_mm']:>16.3f}{d['rms_mm']:>10.3f}{d['hausdorff_mm']:>14.3f}")
    band = stats.get("pen_error_band_mm")
    if band:
        lines.append(f"play at the pen (backlash and fits taken up), across the path: worst case "
                     f"{band['path_worst_case_max']:.2f} mm, 95 % of prints within {band['path_p95_max']:.2f} mm; "
                     f"from the nominal point at the same crank angle (a lag along the path too): "
                     f"{band['worst_case_max']:.2f} / {band['p95_max']:.2f} mm ({band['prints']} prints)")
    if folder:
        lines.append(f"plots: {folder}/{', '.join(trace.files)}")
    return "\n".join(lines)
