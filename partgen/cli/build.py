"""``partgen build CONFIG [-o DIR]``: write the kit of a design."""

from __future__ import annotations

import sys
import time

from .common import add_common_options, note, overrides, print_json

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("build", help="build the STL kit, manifest and assembly of a design")
    p.add_argument("config", help="design YAML (one of configs/*.yaml, or your own)")
    add_common_options(p, "output folder (default out/<design name>/)",
                       json_help="print one JSON object (ok, kit folder, parts) and nothing else")
    p.set_defaults(run=run)


class Progress:
    """One status line on stderr, rewritten in place on a terminal."""

    def __init__(self, quiet: bool):
        self.quiet, self.n, self.tty = quiet, 0, sys.stderr.isatty()

    def __call__(self, name: str) -> None:
        self.n += 1
        if not self.quiet and self.tty:
            print(f"\r  building {self.n:3d}: {name:<14}", end="", file=sys.stderr, flush=True)

    def done(self) -> None:
        if not self.quiet and self.tty:
            print("\r" + " " * 40 + "\r", end="", file=sys.stderr, flush=True)


def auto_text(a: dict) -> str:
    """What ``auto`` play chose, and the P(jam) it reaches (mechanisms.autoplay)."""
    p, (lo, hi) = a["probability"], a["ci95"]
    line = (f"auto play: {a['key']} = {a['backlash_per_gear_mm']:g} mm (each of {a['meshes']} meshes) — P(jam) "
            f"{100 * p:.2f} % (95 % CI {100 * lo:.2f}–{100 * hi:.2f} %) on {a['printer']} at ±{a['accuracy_mm']:g} mm, "
            f"target {100 * a['target']:g} %, linear study of {a['samples']:,} prints, gears seated by their meshes")
    if not a["reached"]:
        why = a.get("limited_by")
        line += ("\n  warning: the target is not reached" + (f": it needs {why['needed_mm']:g} mm, and more than "
                 f"{a['backlash_per_gear_mm']:g} mm does not build ({why['problem']})" if why else
                 ": not even at the most play auto tries"))
    return line


def run(args) -> int:
    from .. import pipeline
    from ..export.bill import shopping_list

    t0 = time.perf_counter()
    progress = Progress(args.quiet or args.json)
    loaded, kit, man, dest = pipeline.build(args.config, args.out, progress, note, overrides(args))
    progress.done()
    mech, spec = loaded.mechanism, loaded.spec
    findings = mech.findings(spec)
    if args.json:
        print_json({"ok": True, "kit": str(dest), "kind": mech.kind, "design": man["design"].get("name", loaded.name),
                    "parts": [{k: p[k] for k in ("name", "role", "count", "file", "volume_mm3", "mass_g")}
                              for p in man["parts"]], "purchased": man.get("purchased", []),
                    "findings": [{"severity": f.severity, "key": f.key, "message": f.message} for f in findings],
                    "printer_values": "measured" if kit.printer.measured else "typical",
                    "auto_play": loaded.auto,
                    "seconds": round(time.perf_counter() - t0, 3)})
        return 0
    for f in findings:
        if f.severity == "warn" or not args.quiet:
            word = "warning" if f.severity == "warn" else "note"
            print(f"partgen: {word}: {loaded.path}: {f.key}: {f.message}", file=sys.stderr)
    if not kit.printer.measured:  # even with -q: every output that rests on typical values says so
        note(f"{kit.printer.name}: the profile's fits and accuracy are typical values, not measured on your printer "
             "(`partgen coupon --printer ...` prints a test that measures them; see docs/calibrate.md)")
    seconds = time.perf_counter() - t0
    if args.quiet:  # only what was written
        print(f"wrote {dest}/ ({len(man['parts'])} distinct parts, "
              f"{sum(p['count'] for p in man['parts'])} to print) in {seconds:.2f} s")
        return 0
    print(mech.bill_text(spec, man, dest, seconds))
    if loaded.auto:
        print(auto_text(loaded.auto))
    print(shopping_list(man, [p for p in kit.parts if not p.printed]))
    return 0
