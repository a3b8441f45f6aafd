"""``partgen check CONFIG|KITDIR [--samples N] [--json]``: does the kit print, assemble and turn?

Exit 0 when every check holds, 1 when one fails, 2 for bad input."""

from __future__ import annotations

import math
import sys
import time

from .common import bounded_int, note, print_json

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    p = sub.add_parser("check", help="check a design or a built kit over its whole motion")
    p.add_argument("target", help="design YAML, or a kit folder written by `partgen build`")
    p.add_argument("--samples", type=bounded_int(4, 10_000), default=None,
                   help="crank angles over one cycle, 4 to 10,000 (default: the config's checks.samples)")
    p.add_argument("--json", action="store_true", help="print one JSON object (ok, findings, figures) and nothing else")
    p.add_argument("--plates", default=None, help="folder for the build plates (default: <kit>/plates)")
    p.add_argument("--no-plates", action="store_true", help="lay out the build plates but write nothing")
    p.set_defaults(run=run)


class Bar:
    """A progress bar on stderr while the motion is swept (only on a terminal)."""

    def __init__(self, enabled: bool):
        self.enabled = enabled and sys.stderr.isatty()
        self.t0 = time.perf_counter()

    def __call__(self, done: int, total: int) -> None:
        if not self.enabled:
            return
        w = 30
        k = int(w * done / max(total, 1))
        print(f"\r  sweeping the motion [{'#' * k}{'.' * (w - k)}] {done}/{total} angles "
              f"{time.perf_counter() - self.t0:5.1f} s", end="", file=sys.stderr, flush=True)
        if done >= total:
            print("\r" + " " * 78 + "\r", end="", file=sys.stderr, flush=True)


def _wrist_table(loaded, result, seconds: float) -> str:
    f = result.figures
    lines = [f"{loaded.params.name}: {f['poses']} poses over the workspace (bend ≤ {f['workspace_bend_deg']:g}°: a "
             f"{f['grid'][0]} × {f['grid'][1]} (θ, ψ) grid and {f['random']} random poses)",
             f"  largest overlap {f['max_overlap_mm3']:.4f} mm³, least tooth volume engaged {f['min_engaged_mm3']:.2f} mm³",
             f"  {'θ on gear 1':>12}{'twist play':>12}{'bend play':>11}"]
    lines += [f"  {r['theta_deg']:>11.1f}°{r['twist_play_deg']:>11.2f}°{r['bend_play_deg']:>10.2f}°" for r in f["play"]]
    lines += [f"  FAIL  {x.check}: {x.message}" for x in result.findings if x.severity == "fail"]
    lines.append(f"{'OK' if result.ok else 'FAILED'} in {seconds:.1f} s")
    return "\n".join(lines)


def _bennett_table(loaded, result, seconds: float) -> str:
    from ..pipeline_bennett import check_text

    return check_text(loaded, result, seconds)


def _table(loaded, result, folder, seconds: float) -> str:
    if getattr(loaded, "kind", "") == "bennett_butterfly":
        return _bennett_table(loaded, result, seconds)
    if loaded.mechanism is None:
        return _wrist_table(loaded, result, seconds)
    f = result.figures
    lines = [f"{loaded.params.name}: {f['parts']} parts, {f['pairs']} pairs, {f['samples']} crank angles over one turn"]
    counts = {}
    for x in result.findings:
        counts.setdefault(x.check, {"fail": 0, "warn": 0, "info": 0})[x.severity] += 1
    motion = f["motion"]
    close = motion.get("closest_approach")
    rows = [
        ("design", "Eq 11-13, printer minimums", ""),
        ("interference", "no overlap over the motion", f"{motion['narrow_phase_2d']} exact 2-D tests, {motion['exact_3d']} 3-D"),
        ("clearance", f"≥ {loaded.params.checks.min_clearance:g} mm between parts that must not touch",
         f"closest {close['mm']:.3f} mm: {close['parts'][0]}–{close['parts'][1]} at {close['theta_deg']:.0f}°" if close else ""),
        ("mesh", f"{len(f['meshes'])} meshing pairs", f"contact ratio ≥ {min(r['contact_ratio'] for r in f['meshes']):.2f}, "
         f"backlash {min(r['measured_backlash_mm'] for r in f['meshes']):.3f}–{max(r['measured_backlash_mm'] for r in f['meshes']):.3f} mm"
         if f["meshes"] else ""),
        ("fit", f"{f['fits']['count']} declared contacts", f"smallest radial gap {f['fits']['min_radial_gap_mm']:.3f} mm"
         if not math.isnan(f["fits"]["min_radial_gap_mm"]) else ""),
        ("printability", "envelope, holes, walls, tooth tips",
         f"hole ≥ Ø{f['printability'].get('smallest_hole_mm', 0):.2f}, wall ≥ {f['printability'].get('thinnest_wall_mm', 0):.2f}, "
         f"tip ≥ {f['printability'].get('narrowest_tip_mm', 0):.2f} mm; {f.get('plates', '?')} build plate(s)"),
    ]
    if "kit" in counts:
        rows.append(("kit", "files match the design", ""))
    lines.append(f"{'check':<14}{'result':<8}{'what':<44}figures")
    for name, what, figs in rows:
        c = counts.get(name, {})
        status = "FAIL" if c.get("fail") else ("warn" if c.get("warn") else "ok")
        lines.append(f"{name:<14}{status:<8}{what:<44}{figs}")
    fails = [x for x in result.findings if x.severity in ("fail", "warn")]
    if fails:
        lines.append("")
        for x in fails:
            where = f" @ ({', '.join(f'{c:.1f}' for c in x.location)}) mm" if x.location else ""
            lines.append(f"  {x.severity.upper():<5} {x.check}: {x.message}{where}")
    lines.append("")
    lines.append(f"{'OK' if result.ok else 'FAILED'}: {sum(x.severity == 'fail' for x in result.findings)} failures"
                 f" in {seconds:.1f} s" + (f"; build plates in {folder}/" if folder else ""))
    return "\n".join(lines)


def run(args) -> int:
    from .. import pipeline

    t0 = time.perf_counter()
    loaded, kit, result, folder = pipeline.check(args.target, args.samples, Bar(not args.json), args.plates,
                                                 not args.no_plates, note)
    seconds = time.perf_counter() - t0
    if args.json:
        out = {"ok": result.ok, "design": loaded.params.name, "config": str(loaded.path),
               "findings": [f.to_dict() for f in result.findings], "figures": result.figures,
               "plates_dir": str(folder) if folder else None, "seconds": round(seconds, 3)}
        print_json(out)
    else:
        print(_table(loaded, result, folder, seconds))
    return 0 if result.ok else 1
