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
    """What ``auto`` play chose (each key's value: the allocation between the meshes' backlash and the
    joints' running clearance), the P(jam) it reaches, and where one more step would buy most
    (mechanisms.autoplay, design.allocate)."""
    p, (lo, hi) = a["probability"], a["ci95"]
    counts = {"backlash per gear": f"each gear of {a['meshes']} mesh{'es' * (a['meshes'] != 1)}",
              "running clearance, diametral": f"each of {a['joints']} running fits"}
    parts = [f"{k} = {v:g} mm ({counts.get(a['labels'][k], a['labels'][k])})" for k, v in a["values"].items()]
    line = (f"auto play: {'; '.join(parts)} — P(jam) {100 * p:.2f} % (95 % CI {100 * lo:.2f}–{100 * hi:.2f} %) on "
            f"{a['printer']} at ±{a['accuracy_mm']:g} mm, target {100 * a['target']:g} %, linear study of "
            f"{a['samples']:,} prints, {a.get('credits') or 'gears seated by their meshes'}")
    if len(a["values"]) > 1:
        line += (f"\n  allocation: the least total play ({a.get('uniform', a)['cost_mm']:g} mm over every mesh's backlash and every "
                 f"fit's radial gap) among {len(a['frontier'])} pairs that meet the target")
    pu = a.get("per_unit") or {}
    if pu.get("adopted"):
        u = a["uniform"]
        line += (f"\n  allocated per gear and joint: total play {pu['cost_mm']:.3f} mm against {pu['uniform_cost_mm']:.3f} mm "
                 f"with one value per key ({pu['saving_mm']:.3f} mm, {pu['saving_pct']:.1f} % less; uniform P(jam) "
                 f"{100 * u['probability']:.2f} %); the values that differ from the default:")
        for k, own in pu["own"].items():
            line += (f"\n    {a['labels'][k]}: default {a['values'][k]:g} mm; "
                     + ", ".join(f"{n} {v:g}" for n, v in own.items()))
    elif pu.get("why"):
        line += f"\n  one value per key (not allocated per gear and joint: {pu['why']})"
    if a.get("buys"):
        line += "\n  one more step would save: " + ", ".join(
            f"{k} {n} of {a['samples']:,} prints" for k, n in a["buys"].items())
    left = [f"{u['unit']} ({u['group']}) {u['jams']}" for u in a.get("units", [])[:3]]
    if left:
        line += "\n  jams left at: " + ", ".join(left)
    if not a["reached"]:
        why = a.get("limited_by")
        line += "\n  warning: the target is not reached" + (": " + "; ".join(
            f"{k} needs {w['needed_mm']:g} mm, and more than {a['values'][k]:g} mm does not build ({w['problem']})"
            for k, w in why.items()) if why else ": not even at the most play auto tries (margins no play key "
            "moves jam more often)")
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
