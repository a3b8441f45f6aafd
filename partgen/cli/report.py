"""``partgen report CONFIG [-o DIR]``: one self-contained HTML page about a kit."""

from __future__ import annotations

import sys
import time

from .. import pipeline

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("report", help="write DIR/index.html: design, parts, stacking, trace, check, plates")
    p.add_argument("config", help="design YAML")
    p.add_argument("-o", "--out", default=None, help="output folder (default out/<design name>/report)")
    p.add_argument("--samples", type=int, default=None, help="crank angles for the check")
    p.set_defaults(run=run)


def run(args) -> int:
    t0 = time.perf_counter()
    tty = sys.stderr.isatty()

    def say(step):
        if tty:
            print(f"\r  report: {step:<12}", end="", file=sys.stderr, flush=True)
    out = pipeline.report(args.config, args.out, args.samples, say)
    if tty:
        print("\r" + " " * 30 + "\r", end="", file=sys.stderr)
    print(f"wrote {out}/index.html in {time.perf_counter() - t0:.1f} s")
    return 0
