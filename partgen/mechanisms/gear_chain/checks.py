"""Run every check on a kit and gather the result."""

from __future__ import annotations

import math
import time


from .kit import Kit
from ...core.findings import Finding, Result
from ...checks.fits import check_fits
from ...checks.meshing import check_meshes
from ...checks.motion import prepare, sample_angles, sweep
from .belts import check_belts
from ...checks.bed import bed_findings
from ...checks.bores import bore_findings
from ...checks.printability import check_printability, printed_extents

__all__ = ["check_kit", "MEASURED_ON_KIT"]

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
    geo = prepare(kit)
    t1 = time.perf_counter()
    found, motion = sweep(kit, geo, thetas, progress, label="crank angle")
    res.add(*found)
    t2 = time.perf_counter()
    found, meshes = check_meshes(kit, thetas, "crank angle")
    res.add(*found)
    t3 = time.perf_counter()
    found, fits = check_fits(kit, geo, thetas)
    res.add(*found)
    found, printing = check_printability(kit, geo, printed_extents(kit))
    res.add(*found)
    found, on_bed = bed_findings(kit.parts, kit.params.printer)
    res.add(*found)
    found, bores = bore_findings(kit.parts)
    res.add(*found)
    printing = {**printing, **on_bed, "bores": bores}
    found, belts = check_belts(kit)
    res.add(*found)
    if belts:
        res.figures["belts"] = belts
    t4 = time.perf_counter()
    pairs = len(kit.parts) * (len(kit.parts) - 1) // 2
    res.figures.update(
        parts=len(kit.parts), pairs=pairs, samples=len(thetas), motion=motion, meshes=meshes,
        fits={"count": len(fits), "min_radial_gap_mm": min((r["radial_gap_mm"] for r in fits if "radial_gap_mm" in r),
                                                           default=math.nan), "rows": fits},
        printability=printing,
        seconds={"prepare": round(t1 - t0, 3), "motion": round(t2 - t1, 3), "meshes": round(t3 - t2, 3),
                 "fits_and_printability": round(t4 - t3, 3)},
        pair_tests_per_second=round(pairs * len(thetas) / max(t2 - t1, 1e-9)))
    return res
