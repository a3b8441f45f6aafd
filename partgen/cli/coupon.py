"""``partgen coupon --printer P [-o DIR]``: the calibration coupon of a printer."""

from __future__ import annotations

from .common import note, print_json

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("coupon", help="a small test print that measures your printer's fits and biases")
    p.add_argument("--printer", required=True, metavar="NAME|FILE",
                   help="printer profile: a shipped name (prusa_mk4, ender3_v3, ...) or a .yaml file")
    p.add_argument("-o", "--out", default=None, help="output folder (default out/coupon_<printer>/)")
    p.add_argument("-q", "--quiet", action="store_true", help="print only what was written")
    p.add_argument("--json", action="store_true", help="print one JSON object and nothing else")
    p.set_defaults(run=run, usage=p.format_usage)


def run(args) -> int:
    from ..calibration import coupon

    dest, s, ref = coupon(args.printer, args.out, None if (args.json or args.quiet) else note)
    if args.json:
        print_json({"ok": True, "coupon": str(dest), "printer": ref.printer.name, **s})
        return 0
    if args.quiet:
        print(f"wrote {dest}/")
        return 0
    parts = ", ".join(f"{n} ×{k}" for n, k in s["parts"].items())
    print(f"calibration coupon for the {ref.printer.name}: {parts}; plate {s['plate_mm'][0]:.1f} × "
          f"{s['plate_mm'][1]:.1f} mm, all on an 80 × 60 mm patch, {s['mass_pla_g']:.1f} g printed solid in PLA")
    if not ref.printer.measured:
        print("the profile's fits and accuracy are typical values, not measured on your machine: this coupon measures them")
    print(f"wrote {dest}/: coupon.3mf, the STLs, instructions.html (what to try and write down), results.yaml "
          f"(fill it in, then: partgen calibrate --printer {args.printer} {dest}/results.yaml -o my_printer.yaml)")
    return 0
