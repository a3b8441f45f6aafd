"""``partgen calibrate --printer P RESULTS.yaml [-o my_printer.yaml]``: a printer profile from a coupon's results.

Exit 0, or 2 when the results are malformed or contradict themselves (a looser fit binds while a
tighter one turns; a reading no caliper would give): the message names the entry."""

from __future__ import annotations

from .common import print_json

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("calibrate", help="turn a printed coupon's results into a measured printer profile")
    p.add_argument("results", help="the coupon's results.yaml, filled in")
    p.add_argument("--printer", required=True, metavar="NAME|FILE", help="the profile the coupon was made for")
    p.add_argument("-o", "--out", default=None, help="profile to write (default my_<printer>.yaml; never a file "
                   "partgen did not write)")
    p.add_argument("-q", "--quiet", action="store_true", help="print only what was written")
    p.add_argument("--json", action="store_true", help="print one JSON object and nothing else")
    p.set_defaults(run=run, usage=p.format_usage)


def run(args) -> int:
    from ..calibration import calibrate_profile

    dest, cal, diff, _ = calibrate_profile(args.printer, args.results, args.out)
    if args.json:
        print_json({"ok": True, "profile": str(dest), "running_clearance_diametral_mm": cal.running_clearance,
                    "press_fit_clearance_diametral_mm": cal.press_clearance, "xy_accuracy_mm": cal.xy_accuracy,
                    "biases": {"hole_diametral_mm": cal.hole_bias, "pin_diametral_mm": cal.pin_bias,
                               "outline_diametral_mm": cal.outline_bias},
                    "gear_backlash_circumferential_mm": cal.gear_backlash, "changes": [d.strip() for d in diff]})
        return 0
    if args.quiet:
        print(f"wrote {dest}")
        return 0
    print(f"wrote {dest}: measured on your printer (changes against {args.printer}):")
    print("\n".join(diff) if diff else "  (no change)")
    print(f"build with --printer {dest}; partgen now compensates holes, pins and outlines: set the slicer's XY "
          "hole and contour compensation to 0")
    return 0
