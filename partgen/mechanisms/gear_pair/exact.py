"""The gear pair's exact Monte Carlo: one perturbed print of the real geometry per task.

A print draws every printed feature's deviation from the linear model's distributions (the same
features and σ, ``design.tolerance``; the posts also move in y, which the linear model leaves out
as second order), and then, on the kit's own sections (shapely):

* each gear's section is offset by half its outline deviation (tip, root and flanks move out);
* each bore's radial play is ``(bore − post)/2`` + half the bore's deviation − half the post's: a
  print whose play is below 0 grips its post (a jam);
* the posts stand at their moved positions; ``seated`` (docs/tolerance.md): the mesh pushes the
  two gears apart along the line of centres by both plays, so the centre distance is the posts'
  distance + play₁ + play₂; otherwise each gear is centred on its post;
* at ``ANGLES`` positions of gear 1 over one tooth pitch, gear 2 must have an angle at which the
  outlines do not overlap: the least overlap over gear 2's angle within ± 0.45 of its pitch (a
  golden-section search of a function that is zero on the free window and grows either side) must
  be zero. A print jams when any of these fails.
"""

from __future__ import annotations

import math
import time

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import box

from ...checks.free_angle import free_angle as _free

__all__ = ["ANGLES", "exact_shared", "exact_print"]

ANGLES = 12  # positions of gear 1 over one tooth pitch


def exact_shared(kit, result, model, seated: bool = True, angles: int = ANGLES) -> dict:
    """What every print task needs (picklable: sections as WKB, numbers)."""
    from .checks import outline

    s = kit.spec
    return {"p1": shapely.to_wkb(outline(kit, "gear1")), "p2": shapely.to_wkb(outline(kit, "gear2")),
            "a": float(s.centre_distance), "z1": s.gear1.teeth, "z2": s.gear2.teeth, "module": s.gear1.system.module,
            "phase2": float(s.phase2), "gap": float(result.figures["radial_gap_mm"]),
            "gaps": [float(x) for x in result.figures.get("radial_gaps_mm", [result.figures["radial_gap_mm"]] * 2)],
            "features": [f.name for f in model.features], "sigma": model.sigma.tolist(),
            "pos_sigma": model.accuracy_mm / 3 / math.sqrt(2), "seated": bool(seated), "angles": int(angles)}


def exact_print(shared: dict, seed: int, index: int) -> dict:
    """Print ``index`` of the study with ``seed`` (its generator ``SeedSequence(seed, spawn_key=(1, index))``):
    {"index", "jam", "why", "seconds"}."""
    t0 = time.perf_counter()
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(1, index)))
    d = dict(zip(shared["features"], rng.standard_normal(len(shared["features"])) * np.asarray(shared["sigma"])))
    dy1, dy2 = rng.standard_normal(2) * shared["pos_sigma"]
    why = None
    plays = [gap + 0.5 * d.get(f"{g} bore", 0.0) - 0.5 * d.get(f"base {g} post", 0.0)
             for g, gap in zip(("gear1", "gear2"), shared.get("gaps", [shared["gap"]] * 2))]
    if min(plays) < 0:
        why = "a bore grips its post"
    else:
        dx = shared["a"] + d.get("base gear2 post x", 0.0) - d.get("base gear1 post x", 0.0)
        a = math.hypot(dx, dy2 - dy1) + (sum(plays) if shared["seated"] else 0.0)
        p1 = shapely.from_wkb(shared["p1"]).buffer(0.5 * d.get("gear1 teeth", 0.0), quad_segs=4)
        p2 = shapely.from_wkb(shared["p2"]).buffer(0.5 * d.get("gear2 teeth", 0.0), quad_segs=4)
        z1, z2, m = shared["z1"], shared["z2"], shared["module"]
        r1 = a * z1 / (z1 + z2)
        window = box(r1 - 3 * m, -3 * m, r1 + 3 * m, 3 * m)
        reach = 0.45 * 2 * math.pi / z2
        for t in np.linspace(0.0, 2 * math.pi / z1, shared["angles"], endpoint=False):
            g1 = shapely.intersection(affinity.rotate(p1, float(t), origin=(0, 0), use_radians=True), window)
            shapely.prepare(g1)
            phi = shared["phase2"] - float(t) * z1 / z2
            if not _free(g1, p2, a, phi, reach):
                why = "the teeth bind"
                break
    return {"index": index, "jam": why is not None, "why": why, "seconds": time.perf_counter() - t0}
