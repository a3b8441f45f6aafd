"""What every subcommand shares: bounded numeric options, notes on stderr."""

from __future__ import annotations

import argparse
import json
import math
import sys

__all__ = ["bounded_int", "note", "print_json", "json_safe", "add_design_options", "add_common_options", "overrides",
           "quiet_text"]


def bounded_int(lo: int, hi: int):
    """An argparse type: a whole number in [lo, hi] (a clear usage error otherwise)."""
    def parse(text: str) -> int:
        try:
            value = int(text, 10)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
        if not lo <= value <= hi:
            raise argparse.ArgumentTypeError(f"{value} is out of range: give {lo} to {hi:,}")
        return value
    parse.__name__ = "count"
    return parse


def note(text: str) -> None:
    """One ``partgen: note:`` line on stderr (what an output swap did besides writing)."""
    print(f"partgen: note: {text}", file=sys.stderr)


def print_json(obj) -> None:
    """One strict JSON object (non-finite numbers become null) on stdout."""
    print(json.dumps(json_safe(obj), indent=1, allow_nan=False))


def json_safe(v):
    if isinstance(v, dict):
        return {str(k): json_safe(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [json_safe(x) for x in v]
    if hasattr(v, "item") and not isinstance(v, (str, bytes)):
        v = v.item()
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def add_design_options(p: argparse.ArgumentParser) -> None:
    """``--printer NAME|FILE`` and ``--set KEY=VALUE`` (repeatable): what every command may change
    in the design before it is validated."""
    p.add_argument("--printer", default=None, metavar="NAME|FILE",
                   help="printer profile instead of the design's: a shipped name (prusa_mk4, ender3_v3, ...) or a .yaml file")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="sets",
                   help="change one design value as if written in the YAML (gears.module_mm=1.5); repeatable")
    p.set_defaults(usage=p.format_usage)


def add_common_options(p: argparse.ArgumentParser, out_help: str, *out_aliases: str, json_help: str | None = None
                       ) -> None:
    """The options every command has, with one meaning: ``-o/--out DIR`` (where its output goes;
    ``out_aliases`` keep a command's older name for it, e.g. ``--plates``), ``-q/--quiet`` (no
    progress, only the result: what was written, the verdict and what failed), ``--json`` (one JSON
    object on stdout and nothing else), and the design options ``--printer`` and ``--set``."""
    p.add_argument("-o", "--out", *out_aliases, dest="out", default=None, metavar="DIR", help=out_help)
    p.add_argument("-q", "--quiet", action="store_true", help="no progress; print only the result")
    p.add_argument("--json", action="store_true", help=json_help or "print one JSON object and nothing else")
    add_design_options(p)


def quiet_text(text: str) -> str:
    """What ``-q`` keeps of a command's text: the lines that say something failed or warn, and the
    last line (what was written, or the verdict)."""
    lines = [ln for ln in text.rstrip("\n").split("\n") if ln.strip()]
    keep = [ln for ln in lines[:-1] if ln.lstrip().startswith(("FAIL", "WARN", "warning", "error"))]
    return "\n".join(keep + lines[-1:])


def overrides(args):
    """The command line's overrides of the design (``config.overrides.Overrides``); a malformed
    --set raises the usage error."""
    from ..pipeline import overrides as make

    return make(getattr(args, "sets", []) or [], getattr(args, "printer", None))
