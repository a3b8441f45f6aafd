"""``partgen trace CONFIG [--csv FILE] [--json]``: the pen path of the kit as built vs its target."""

from __future__ import annotations

from .common import bounded_int, print_json

CSV_HEADER = "theta_rad,x_mm,y_mm\n"

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("trace", help="trace the pen of the kit as built and compare it with the target curve")
    p.add_argument("config", help="design YAML")
    p.add_argument("--csv", default=None, help="write the path: theta_rad, x_mm, y_mm")
    p.add_argument("--json", action="store_true", help="print one JSON object and nothing else")
    p.add_argument("--samples", type=bounded_int(16, 36_000), default=3600, help="crank angles over one turn, 16 to 36,000 [3600]")
    p.add_argument("--plots", default=None, help="folder for trace.png/.svg/.gif (default out/<name>/trace)")
    p.add_argument("--no-plots", action="store_true")
    p.set_defaults(run=run)


def run(args) -> int:
    import numpy as np

    from .. import pipeline
    from ..export.outputs import check_text_target, write_text_file

    if args.csv:
        check_text_target(args.csv, "--csv", CSV_HEADER, (args.config,))
    loaded, theta, pen, stats, folder = pipeline.trace_design(args.config, args.samples,
                                                              False if args.no_plots else args.plots)
    if stats.get("kind") == "wrist":
        if args.json:
            print_json({"ok": True, "design": loaded.params.name, **stats, "plots_dir": str(folder) if folder else None})
            return 0
        print(f"{loaded.params.name}: I = {stats['nominal_ratio']:g}; valid range θ ≤ {stats['valid_end_deg']:.3f}° "
              f"(φ reaches 90°); workspace θ ≤ {stats['workspace_theta_max_deg']:.3f}°")
        print(f"  ODE vs closed form: {stats['ode_vs_closed_form_max']:.1e}; mating angle, meridian vs latitude: "
              f"{stats['mating_angle_methods_max_rad']:.1e} rad")
        for r in stats["rows"][1:]:
            print(f"  ring {r['k']}: {r['teeth']} teeth at θ = {r['theta_deg']:.3f}°, φ = {r['phi_deg']:.3f}°, latitudinal "
                  f"pitch {r['lat_pitch_mm']:.3f} mm ({100 * r['lat_pitch_off']:+.2f} % off the longitudinal)")
        if folder:
            print(f"plots: {folder}/wrist.png, wrist.svg")
        return 0
    if args.csv:
        rows = np.column_stack([theta, pen.real, pen.imag])
        write_text_file(args.csv, CSV_HEADER + "".join(f"{t:.9f},{x:.6f},{y:.6f}\n" for t, x, y in rows), "--csv",
                        (args.config,))
    if args.json:
        print_json({"ok": True, "design": loaded.params.name, **stats, "plots_dir": str(folder) if folder else None})
        return 0
    name = loaded.params.name
    print(f"{name}: pen over one crank turn, {args.samples} samples; link speeds as built {', '.join(stats['speeds'])}"
          + ("" if stats["closes_after_one_turn"] else " (fractional: the path does not close after one turn)"))
    print(f"{'traced vs':<28}{'max (same θ) mm':>16}{'rms mm':>10}{'Hausdorff mm':>14}")
    rows = [("the design's chain (pruned)", stats["vs_pruned"])]
    if "max_deviation_mm" in stats:
        rows.insert(0, ("the full Fourier series", stats))
        rows.append(("(pruned vs full)", stats["pruned_vs_full"]))
    for label, d in rows:
        print(f"{label:<28}{d['max_deviation_mm']:>16.3f}{d['rms_mm']:>10.3f}{d['hausdorff_mm']:>14.3f}")
    if folder:
        print(f"plots: {folder}/trace.png, trace.svg, trace.gif")
    if args.csv:
        print(f"path: {args.csv}")
    return 0
