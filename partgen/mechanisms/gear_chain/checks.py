"""Run every check on a kit and gather the result."""

from __future__ import annotations

import math
import time


from .kit import Kit
from ...core.findings import Finding, Result
from ...checks.motion import sample_angles
from ...checks.sequence import run_shared
from .belts import check_belts

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
