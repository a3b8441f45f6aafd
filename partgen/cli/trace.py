"""``partgen trace CONFIG|KITDIR [--csv FILE] [--json]``: the mechanism's motion as built (each
mechanism's own figure and table)."""

from __future__ import annotations

from .common import add_common_options, bounded_int, overrides, print_json, quiet_text

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("trace", help="trace the motion of the kit as built (the pen path, the ratio, the centre of mass)")
    p.add_argument("config", help="design YAML, or a kit folder written by `partgen build`")
    p.add_argument("--csv", default=None, help="write the path: theta_rad, x_mm, y_mm")
    p.add_argument("--samples", type=bounded_int(16, 36_000), default=None, help="samples of the motion, 16 to 36,000 (default: the mechanism's)")
    p.add_argument("--no-plots", action="store_true", help="trace, but write no plots")
    add_common_options(p, "folder for the plots (default out/<name>/trace, or KITDIR/trace; old name --plots)",
                       "--plots")
    p.set_defaults(run=run)


def run(args) -> int:
    from .. import pipeline
    from ..export.outputs import check_text_target, write_text_file

    loaded = pipeline.load(args.config, over=overrides(args))
    mech = loaded.mechanism
    if args.csv:
        check_text_target(args.csv, "--csv", mech.csv_header, (loaded.path,))
    _, tr, folder = pipeline.trace(loaded, args.samples, False if args.no_plots else args.out)
    if args.csv:
        write_text_file(args.csv, mech.csv(tr), "--csv", (loaded.path,))
    if args.json:
        print_json({"ok": True, "kind": mech.kind, "design": loaded.name, **tr.stats,
                    "plots_dir": str(folder) if folder else None})
        return 0
    text = mech.trace_text(loaded.spec, tr, folder)
    print(quiet_text(text) if args.quiet else text)
    if args.csv:
        print(f"path: {args.csv}")
    return 0
