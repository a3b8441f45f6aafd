"""``partgen sweep CONFIG --vary KEY=START:STOP:STEPS [--vary ...] [--random N] -o DIR``: a
design-space study; every point built and checked on a Dask cluster, a table and a page of plots.

Exit 0 when the sweep ran (whatever its points found), 2 for bad input (nothing written)."""

from __future__ import annotations

from .common import add_common_options, bounded_int, overrides, print_json
from .tolerance import _accuracy, add_workers_options

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("sweep", help="build and check a grid (or random points) of design values")
    p.add_argument("config", help="design YAML")
    p.add_argument("--vary", action="append", default=[], metavar="KEY=START:STOP:STEPS",
                   help="a design value (key path as --set) from START to STOP in STEPS points; repeatable (a grid)")
    p.add_argument("--random", type=bounded_int(1, 100_000), default=None, metavar="N",
                   help="N random points in the box the --vary ranges span, instead of the grid")
    p.add_argument("--tolerance-samples", type=bounded_int(1, 10_000_000), default=None, metavar="M",
                   help="also the probability that a print jams, from M simulated prints per point")
    p.add_argument("--accuracy-mm", type=_accuracy, default=None, help="± printer accuracy for --tolerance-samples")
    p.add_argument("--seed", type=bounded_int(0, 2 ** 63 - 1), default=0, help="random seed (default 0)")
    p.add_argument("--check-samples", type=bounded_int(4, 10_000), default=None,
                   help="samples of the motion in each point's check (default: the config's checks.samples)")
    add_common_options(p, "output folder (default out/<name>/sweep)")
    add_workers_options(p)
    p.set_defaults(run=run)


def run(args) -> int:
    from .. import studies

    r = studies.sweep(args.config, args.vary, args.out, args.random, args.tolerance_samples, args.accuracy_mm,
                      args.seed, args.workers, args.scheduler, args.check_samples, overrides(args),
                      progress=not (args.json or args.quiet))
    if args.json:
        print_json({"ok": True, **r})
        return 0
    from ..export.studies import tradeoff_rows

    keys = r["keys"]
    trade = tradeoff_rows(r["rows"])
    heads = {"pen_error_p95_mm": "pen p95 mm", "lost_motion_arcmin": "lost '", "lost_motion_mm": "lost mm"}
    cost, head = (trade[0], heads[trade[0]]) if trade else (None, "")
    lines = [f"{r['design']}: {r['points']} points ({', '.join(keys)}): {r['pass']} pass, {r['fail']} fail, "
             f"{r['refused']} refused; {r['workers']} worker(s), {r['seconds']:.1f} s",
             "  ".join(f"{k:>18}" for k in keys) + f"{'status':>9}{'mass g':>9}{'part mm':>9}{'clear mm':>9}{'P(jam)':>9}"
             + (f"{head:>12}" if cost else "")]
    for row in r["rows"][:40]:
        jp = row.get("jam_probability")
        lines.append("  ".join(f"{row['values'][k]:>18}" for k in keys) + f"{row['status']:>9}"
                     + "".join(f"{'' if row.get(c) is None else format(row[c], '.2f'):>9}"
                               for c in ("mass_g", "size_mm", "least_clearance_mm"))
                     + f"{'' if jp is None else format(100 * jp, '.1f') + ' %':>9}"
                     + (f"{'' if row.get(cost) is None else format(row[cost], '.2f'):>12}" if cost else ""))
    if len(r["rows"]) > 40:
        lines.append(f"  … {len(r['rows']) - 40} more in points.csv")
    lines.append(f"wrote {r['dest']}/points.csv, index.html" + (", tradeoff.csv, tradeoff.png (P(jam) against "
                                                                 "what play costs)" if trade else ""))
    print("\n".join([lines[0], lines[-1]] if args.quiet else lines))
    return 0
