"""``partgen calibrate --printer P RESULTS.yaml [-o my_printer.yaml]``: a printer profile from a coupon's results."""

from __future__ import annotations

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("calibrate", help="turn a printed coupon's results into a measured printer profile")
    p.add_argument("results", help="the coupon's results.yaml, filled in")
    p.add_argument("--printer", required=True, metavar="NAME|FILE", help="the profile the coupon was made for")
    p.add_argument("-o", "--out", default=None, help="profile to write (default my_<printer>.yaml)")
    p.add_argument("--json", action="store_true", help="print one JSON object and nothing else")
    p.set_defaults(run=run, usage=p.format_usage)


def run(args) -> int:
    raise NotImplementedError
