"""``partgen report CONFIG [-o DIR]``: one self-contained HTML page about a kit."""

from __future__ import annotations

import sys
import time

from .common import add_common_options, bounded_int, overrides, print_json

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("report", help="write DIR/index.html: design, parts, stacking, trace, check, plates")
    p.add_argument("config", help="design YAML, or a kit folder written by `partgen build`")
    p.add_argument("--samples", type=bounded_int(4, 10_000), default=None, help="samples of the motion for the check")
    add_common_options(p, "output folder (default out/<design name>/report, or KITDIR/report)",
                       json_help="print one JSON object (ok, report path) and nothing else")
    p.set_defaults(run=run)


def run(args) -> int:
    from .. import pipeline

    t0 = time.perf_counter()
    tty = sys.stderr.isatty() and not (args.json or args.quiet)

    def say(step):
        if tty:
            print(f"\r  report: {step:<12}", end="", file=sys.stderr, flush=True)
    out = pipeline.report(args.config, args.out, args.samples, say, overrides(args))
    if tty:
        print("\r" + " " * 30 + "\r", end="", file=sys.stderr)
    if args.json:
        print_json({"ok": True, "report": str(out / "index.html"), "seconds": round(time.perf_counter() - t0, 3)})
    else:
        print(f"wrote {out}/index.html in {time.perf_counter() - t0:.1f} s")
    return 0
