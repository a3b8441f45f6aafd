"""What every subcommand shares: bounded numeric options, notes on stderr."""

from __future__ import annotations

import argparse
import json
import math
import sys

__all__ = ["bounded_int", "note", "print_json", "json_safe"]


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
