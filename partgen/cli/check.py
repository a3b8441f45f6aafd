"""``partgen check CONFIG|KITDIR [--samples N] [--json]``: does the kit print, assemble and turn?

Exit 0 when every check holds, 1 when one fails, 2 for bad input."""

from __future__ import annotations

import sys
import time

from .common import add_common_options, bounded_int, note, overrides, print_json, quiet_text
from .tolerance import _unit_float

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("check", help="check a design or a built kit over its whole motion")
    p.add_argument("target", help="design YAML, or a kit folder written by `partgen build`")
    p.add_argument("--samples", type=bounded_int(4, 10_000), default=None,
                   help="samples of the motion over one cycle, 4 to 10,000 (default: the config's checks.samples)")
    p.add_argument("--no-plates", action="store_true", help="lay out the build plates but write nothing")
    p.add_argument("--max-jam-probability", type=_unit_float, default=None, metavar="P",
                   help="fail (exit 1) when the quick tolerance study's P(jam) is above P")
    add_common_options(p, "folder for the build plates (default: <kit>/plates; old name --plates)", "--plates",
                       json_help="print one JSON object (ok, findings, figures) and nothing else")
    p.set_defaults(run=run)


class Bar:
    """A progress bar on stderr while the motion is swept (only on a terminal)."""

    def __init__(self, enabled: bool):
        self.enabled = enabled and sys.stderr.isatty()
        self.t0 = time.perf_counter()

    def __call__(self, done: int, total: int) -> None:
        if not self.enabled:
            return
        w = 30
        k = int(w * done / max(total, 1))
        print(f"\r  sweeping the motion [{'#' * k}{'.' * (w - k)}] {done}/{total} angles "
              f"{time.perf_counter() - self.t0:5.1f} s", end="", file=sys.stderr, flush=True)
        if done >= total:
            print("\r" + " " * 78 + "\r", end="", file=sys.stderr, flush=True)


def run(args) -> int:
    from .. import pipeline

    t0 = time.perf_counter()
    loaded, kit, result, folder = pipeline.check(args.target, args.samples, Bar(not (args.json or args.quiet)), args.out,
                                                 not args.no_plates, note, overrides(args),
                                                 args.max_jam_probability)
    seconds = time.perf_counter() - t0
    if args.json:
        out = {"ok": result.ok, "kind": loaded.mechanism.kind, "design": loaded.name, "config": str(loaded.path),
               "findings": [f.to_dict() for f in result.findings], "figures": result.figures,
               "plates_dir": str(folder) if folder else None, "seconds": round(seconds, 3)}
        print_json(out)
    else:
        text = loaded.mechanism.check_text(loaded.spec, result, folder, seconds)
        if "P(jam)" not in text:  # a mechanism's text that does not list every finding: before its verdict
            head, _, verdict = text.rstrip("\n").rpartition("\n")
            extra = [f"  {dict(fail='FAIL', warn='WARN', info='ok').get(f.severity)}  tolerance: {f.message}"
                     for f in result.findings if f.check == "tolerance"]
            text = "\n".join([head, *extra, verdict]) if head else "\n".join([*extra, verdict])
        print(quiet_text(text) if args.quiet else text)
    return 0 if result.ok else 1
