"""partgen's command line: ``main(argv=None) -> int``; one module per subcommand.

Exit codes: 0 ok, 1 a check failed, 2 bad input (one message naming the file and the key path, or
the option), 3 an internal error (a bug: the traceback is shown), 130/143 interrupted by SIGINT/
SIGTERM (nothing half-written is left: outputs are swapped in whole), 141 stdout closed (``| head``).
With ``--json`` every outcome prints one JSON object on stdout, bad input included.
"""

from __future__ import annotations

import argparse
import os
import re
import signal
import sys
import threading
import traceback

from ..errors import MeshError, OptionError, PartgenError
from . import build as build_cmd
from . import calibrate as calibrate_cmd
from . import coupon as coupon_cmd
from . import check as check_cmd
from . import report as report_cmd
from . import trace as trace_cmd
from . import tolerance as tolerance_cmd
from . import sweep as sweep_cmd
from .common import print_json

__all__ = ["main", "entry", "Interrupted"]


def _spawned_worker() -> None:
    """A ^C at the terminal reaches every process of its group, the local Dask cluster's worker
    processes too, and each printed its own tracebacks. A worker is a process multiprocessing
    spawned, and spawning imports the parent's main module there first — the ``partgen`` script,
    which imports this module — so here, and only in such a process, SIGINT is ignored: the partgen
    process the user started takes the ^C and stops its workers. (An ignored SIGINT is kept by the
    worker's Python and asyncio, which then install no handler of their own.)"""
    # multiprocessing runs the parent's main module in a spawned child as ``__mp_main__`` (and only there)
    if "__mp_main__" in sys.modules and threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)


_spawned_worker()


class Interrupted(BaseException):
    """SIGTERM (or SIGINT) arrived: unwinds like KeyboardInterrupt, so temporary outputs are removed."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


class _UsageError(Exception):
    def __init__(self, parser: argparse.ArgumentParser, message: str):
        super().__init__(message)
        self.parser = parser


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # raise instead of exiting, so main() decides how to report it
        raise _UsageError(self, message)


def parser() -> argparse.ArgumentParser:
    from .. import __version__
    ap = _Parser(prog="partgen", description="Mechanism design tables to checked, print-ready part kits.")
    ap.add_argument("--version", action="version", version=f"partgen {__version__}")
    sub = ap.add_subparsers(dest="command", required=True, parser_class=_Parser)
    build_cmd.add_parser(sub)
    check_cmd.add_parser(sub)
    trace_cmd.add_parser(sub)
    report_cmd.add_parser(sub)
    tolerance_cmd.add_parser(sub)
    sweep_cmd.add_parser(sub)
    coupon_cmd.add_parser(sub)
    calibrate_cmd.add_parser(sub)
    return ap


def error_json(e: Exception) -> dict:
    """The ``{"ok": false, "error": {...}}`` object of a bad input."""
    if isinstance(e, OptionError):
        err = {"file": None, "key": e.option, "message": str(e)}
    else:
        f = getattr(e, "file", None)
        err = {"file": f or None, "key": getattr(e, "key_path", None) or None, "message": str(e)}
    return {"ok": False, "error": err}


def _quiet_stdout() -> None:
    """stdout's reader went away: send further output to /dev/null so the exit is quiet."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        pass


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    want_json = "--json" in argv
    in_main = threading.current_thread() is threading.main_thread()
    previous = {}
    if in_main:
        def _raise(signum, frame):
            raise Interrupted(signum)
        for sig in (signal.SIGINT, signal.SIGTERM):
            previous[sig] = signal.signal(sig, _raise)
    try:
        return _run(argv, want_json)
    except Interrupted as e:
        print(f"partgen: interrupted; {_kept(e)}", file=sys.stderr)
        return 128 + e.signum
    except KeyboardInterrupt as e:
        print(f"partgen: interrupted; {_kept(e)}", file=sys.stderr)
        return 130
    except BrokenPipeError:
        _quiet_stdout()
        return 141
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)


def _kept(e: BaseException) -> str:
    """What an interruption left: by default nothing (outputs are swapped in whole); a study written
    as it goes (tolerance's chunks.jsonl) says what it kept and how to resume."""
    return getattr(e, "partgen_note", None) or "nothing half-written was left"


def _import_guarded() -> None:
    """Import the heavy modules with SIGINT/SIGTERM only noted: some libraries catch BaseException
    around optional imports, which would swallow a Ctrl-C and let the command run on. A signal
    that arrived meanwhile is raised once the imports are done."""
    if threading.current_thread() is not threading.main_thread():
        from .. import pipeline  # noqa: F401
        return
    got: list[int] = []
    handlers = {s: signal.signal(s, lambda signum, frame: got.append(signum)) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        from .. import pipeline  # noqa: F401
    finally:
        for s, h in handlers.items():
            signal.signal(s, h)
    if got:
        raise Interrupted(got[0])


def _run(argv: list[str], want_json: bool) -> int:
    ap = parser()
    try:
        args = ap.parse_args(argv)
    except SystemExit as e:  # --help, --version
        return 0 if e.code in (0, None) else 2
    except _UsageError as e:
        if want_json:
            found = re.match(r"argument ([^:/ ]+)", str(e))
            print_json({"ok": False, "error": {"file": None, "key": found[1] if found else None, "message": str(e)}})
        else:
            e.parser.print_usage(sys.stderr)
            print(f"{e.parser.prog}: error: {e}", file=sys.stderr)
        return 2
    _import_guarded()
    try:
        return args.run(args)
    except PartgenError as e:
        if getattr(args, "json", False):
            print_json(error_json(e))
        elif getattr(e, "usage", False) and getattr(args, "usage", None):  # a bad --set or --printer
            print(args.usage(), end="", file=sys.stderr)
        print(f"partgen: error: {e}", file=sys.stderr)
        return 2
    except MeshError as e:  # partgen made a broken part: a bug, named, never written
        if getattr(args, "json", False):
            print_json({"ok": False, "error": {"file": None, "key": None, "message": str(e)}, "internal": True})
        print(f"partgen: internal error: {e}", file=sys.stderr)
        return 3
    except (Interrupted, KeyboardInterrupt, BrokenPipeError):
        raise
    except Exception:  # a bug in partgen, not the user's input: show it, exit 3
        traceback.print_exc()
        print("partgen: internal error (a bug in partgen, not in your design); please report it", file=sys.stderr)
        return 3


def entry() -> None:
    code = main()
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _quiet_stdout()
        code = 141
    sys.exit(code)
