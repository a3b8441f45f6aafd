"""``partgen build CONFIG [-o DIR]``: write the kit of a design."""

from __future__ import annotations

import sys
import time

from .common import note, print_json

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("build", help="build the STL kit, manifest and assembly of a design")
    p.add_argument("config", help="design YAML (configs/butterfly.yaml)")
    p.add_argument("-o", "--out", default=None, help="output folder (default out/<design name>/)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress")
    p.add_argument("--json", action="store_true", help="print one JSON object (ok, kit folder, parts) and nothing else")
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


def run(args) -> int:
    from .. import pipeline

    t0 = time.perf_counter()
    progress = Progress(args.quiet or args.json)
    loaded, kit, man, dest = pipeline.build(args.config, args.out, progress, note)
    progress.done()
    if args.json:
        findings = [{"severity": f.severity, "key": f.key, "message": f.message}
                    for f in getattr(loaded.mechanism, "findings", ())]
        print_json({"ok": True, "kit": str(dest), "design": man["design"].get("name", loaded.params.name),
                    "parts": [{k: p[k] for k in ("name", "role", "count", "file", "volume_mm3", "mass_g")}
                              for p in man["parts"]], "findings": findings,
                    "seconds": round(time.perf_counter() - t0, 3)})
        return 0
    mech = loaded.mechanism
    if getattr(loaded, "kind", "") == "bennett_butterfly":
        print(bennett_table(man, dest, time.perf_counter() - t0))
        return 0
    if mech is None:  # a wrist pair
        for p in man["parts"]:
            print(f"{p['name']:<8}{p['triangles']:>9} triangles {p['volume_mm3'] / 1000:8.2f} cm3 {p['mass_g']:7.1f} g  "
                  f"{' x '.join(f'{x:.1f}' for x in p['bbox_mm'])} mm")
        print(f"wrote {dest}/ in {time.perf_counter() - t0:.2f} s")
        return 0
    for f in mech.findings:
        if f.severity == "warn":
            print(f"partgen: warning: {loaded.path}: {f.key}: {f.message}", file=sys.stderr)
        else:
            print(f"partgen: note: {loaded.path}: {f.key}: {f.message}", file=sys.stderr)
    parts = man["parts"]
    n_gears = sum(p["count"] for p in parts if p["role"] == "gear")
    mass = sum(p["mass_g"] * p["count"] for p in parts)
    print(f"{loaded.params.name}: {len(mech.chain.links)} links, {n_gears} gears, "
          f"{sum(p['count'] for p in parts)} parts ({len(parts)} distinct), {mass:.0f} g of {loaded.params.material}")
    print(f"{'part':<12}{'role':<11}{'count':>5}{'triangles':>11}{'volume cm3':>12}{'mass g':>9}  bbox mm")
    for p in parts:
        print(f"{p['name']:<12}{p['role']:<11}{p['count']:>5}{p['triangles']:>11}{p['volume_mm3'] / 1000:>12.2f}"
              f"{p['mass_g']:>9.1f}  {' x '.join(f'{x:.1f}' for x in p['bbox_mm'])}")
    warn = sum(f.severity == "warn" for f in mech.findings)
    print(f"wrote {dest}/ ({len(parts)} STL, manifest.json, assembly.glb) in {time.perf_counter() - t0:.2f} s"
          + (f"; {warn} warning{'s' if warn != 1 else ''} above (`partgen check` will fail)" if warn else ""))
    return 0


def bennett_table(man: dict, dest, seconds: float) -> str:
    """The bill of a Bennett butterfly kit (``pipeline_bennett.bill_text``)."""
    from ..pipeline_bennett import bill_text

    return bill_text(man, dest, seconds)
