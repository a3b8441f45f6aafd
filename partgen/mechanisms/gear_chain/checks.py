"""Run every check on a kit and gather the result."""

from __future__ import annotations

import math
import time


from .kit import Kit
from .resolve import ChainSpec
from ...core.findings import Finding, Result
from ...checks.motion import sample_angles
from ...checks.sequence import run_shared
from .belts import check_belts

__all__ = ["check_kit", "check_text", "MEASURED_ON_KIT", "BED_RULES"]

BED_RULES = ("bed-contact", "shells", "bore-open", "needs-supports")  # checks.bed and checks.bores
MEASURED_ON_KIT = {"tip-width"}  # design rules a later check measures on the kit itself (printability: tooth tips)


def check_kit(kit: Kit, samples: int | None = None, progress=None) -> Result:
    """Design verification, interference and clearance over the motion, meshes, fits, printability."""
    res = Result()
    t0 = time.perf_counter()
    for f in kit.mechanism.findings:
        if f.rule in MEASURED_ON_KIT:
            continue  # printability measures it on every gear as built: one finding per defect, not two
        res.add(Finding("design", "fail" if f.severity == "warn" else "info", f"{f.key}: {f.message}", key=f.key,
                        rule=f.rule))
    thetas = sample_angles(samples or kit.params.checks.samples)
    design_s = time.perf_counter() - t0
    got = run_shared(res, kit, thetas, "crank angle", progress, mesh_view=kit)
    t = time.perf_counter()
    found, belts = check_belts(kit)
    res.add(*found)
    if belts:
        res.figures["belts"] = belts
    seconds = {**got.seconds, "prepare": round(got.seconds["prepare"] + design_s, 3),
               "fits_and_printability": round(got.seconds["fits_and_printability"] + time.perf_counter() - t, 3)}
    pairs = len(kit.parts) * (len(kit.parts) - 1) // 2
    fits = got.fits
    res.figures.update(
        parts=len(kit.parts), pairs=pairs, samples=len(thetas), motion=got.motion, meshes=got.meshes,
        fits={"count": len(fits), "min_radial_gap_mm": min((r["radial_gap_mm"] for r in fits if "radial_gap_mm" in r),
                                                           default=math.nan), "rows": fits},
        printability=got.printing, seconds=seconds,
        pair_tests_per_second=round(pairs * len(thetas) / max(got.seconds["motion"], 1e-9)))
    return res


def check_text(spec: ChainSpec, result: Result, folder, seconds: float) -> str:
    from ...design.trace import crank_turns

    f = result.figures
    turns = crank_turns(spec.mechanism)
    lines = [f"{spec.params.name}: {f['parts']} parts, {f['pairs']} pairs, {f['samples']} crank angles over "
             + ("one turn" if turns == 1 else f"one drawing ({turns} crank turns)")]
    counts: dict = {}
    for x in result.findings:
        counts.setdefault(x.check, {"fail": 0, "warn": 0, "info": 0})[x.severity] += 1
    motion = f["motion"]
    close = motion.get("closest_approach")
    meshes = f["meshes"]
    rows = [
        ("design", "Eq 11-13, printer minimums", ""),
        ("interference", "no overlap over the motion",
         f"{motion['narrow_phase_2d']} exact 2-D tests, {motion['exact_3d']} 3-D"),
        ("clearance", f"≥ {spec.params.checks.min_clearance:g} mm between parts that must not touch",
         f"closest {close['mm']:.3f} mm: {close['parts'][0]}–{close['parts'][1]} at {close['theta_deg']:.0f}°"
         if close else ""),
        ("mesh", f"{len(meshes)} meshing pairs",
         f"contact ratio ≥ {min(r['contact_ratio'] for r in meshes):.2f}, backlash "
         f"{min(r['measured_backlash_mm'] for r in meshes):.3f}–{max(r['measured_backlash_mm'] for r in meshes):.3f} mm"
         if meshes else ""),
        ("fit", f"{f['fits']['count']} declared contacts", f"smallest radial gap {f['fits']['min_radial_gap_mm']:.3f} mm"
         if not math.isnan(f["fits"]["min_radial_gap_mm"]) else ""),
        ("printability", "envelope, holes, walls, tooth tips",
         f"hole ≥ Ø{f['printability'].get('smallest_hole_mm', 0):.2f}, wall ≥ "
         f"{f['printability'].get('thinnest_wall_mm', 0):.2f}, tip ≥ {f['printability'].get('narrowest_tip_mm', 0):.2f}"
         f" mm; {f.get('plates', '?')} build plate(s)"),
        ("bed", "flat on the bed, one shell, bores open",
         f"contact ≥ {f['printability'].get('least_bed_contact_mm2', 0):.0f} mm², "
         f"{sum(len(b) for b in f['printability'].get('bores', {}).values())} bores, "
         f"{len(f['printability'].get('needs_supports_mm2', {}))} part(s) need supports"),
    ]
    if "kit" in counts:
        rows.append(("kit", "files match the design", ""))
    lines.append(f"{'check':<14}{'result':<8}{'what':<44}figures")
    for name, what, figs in rows:
        c = counts.get(name, {})
        if name in ("printability", "bed"):  # the bed's rules apart from the other printability rules
            c = {sev: sum(x.check == "printability" and x.severity == sev and (x.rule in BED_RULES) == (name == "bed")
                          for x in result.findings) for sev in ("fail", "warn")}
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
