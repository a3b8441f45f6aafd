"""partgen's command line: ``main(argv=None) -> int``; one module per subcommand.

Exit codes: 0 ok, 1 a check failed, 2 bad input (the message names the file and the key path),
3 an internal error (a bug: the traceback is shown).
"""

from __future__ import annotations

import argparse
import sys
import traceback

from ..errors import PartgenError
from . import build as build_cmd
from . import check as check_cmd
from . import report as report_cmd
from . import trace as trace_cmd

__all__ = ["main", "entry"]


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="partgen", description="Mechanism design tables to checked, print-ready part kits.")
    sub = ap.add_subparsers(dest="command", required=True)
    build_cmd.add_parser(sub)
    check_cmd.add_parser(sub)
    trace_cmd.add_parser(sub)
    report_cmd.add_parser(sub)
    return ap


def main(argv: list[str] | None = None) -> int:
    ap = parser()
    try:
        args = ap.parse_args(argv)
    except SystemExit as e:  # argparse's own usage errors are bad input
        return 0 if e.code == 0 else 2
    try:
        return args.run(args)
    except PartgenError as e:
        print(f"partgen: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("partgen: interrupted", file=sys.stderr)
        return 130
    except Exception:  # a bug in partgen, not the user's input: show it, exit 3
        traceback.print_exc()
        print("partgen: internal error (a bug in partgen, not in your design); please report it", file=sys.stderr)
        return 3


def entry() -> None:
    sys.exit(main())
