"""The straight bevel pair's check over a tooth pitch of gear 1 (exact 3-D, contact.py): the
gears never overlap and keep backlash both ways, clear the base, post, block and pin over a turn,
each bore clears its shaft, the contact along the face, the bed and bores; and the text `check`
prints."""

from __future__ import annotations

import math

import numpy as np

from ...checks.contact3d import VOLUME_EPS
from ...checks.contact_pattern import pattern_finding, pattern_text
from ...checks.footer import check_footer
from ...core.findings import Finding, Result
from ...geometry.measure import intersection, min_gap
from .contact import contact_along_face, contact_angles, designed_backlash
from .kit import BevelKit
from .resolve import BevelSpec

__all__ = ["check", "check_text"]


def check(spec: BevelSpec, kit: BevelKit, samples: int | None = None, progress=None) -> Result:
    """The gears never overlap at phases over a tooth pitch (exact 3-D), keep backlash both ways,
    clear the base, post, block and pin over a turn, and each bore clears its shaft."""
    res = Result()
    n = samples or spec.samples
    pitch = 2 * math.pi / spec.gear1.teeth
    thetas = pitch * np.arange(n) / n
    play = contact_angles(kit, thetas, 1e-5)  # 1e-5 rad at gear 2: 0.2 µm on its pitch circle
    if progress:
        progress(n, n)
    r2 = spec.gear2.pitch_radius
    bad = np.flatnonzero(play["overlap_mm3"] > VOLUME_EPS)
    if len(bad):
        k = bad[np.argmax(play["overlap_mm3"][bad])]
        res.add(Finding("interference", "fail", f"gear1 and gear2 overlap by {play['overlap_mm3'][k]:.4f} mm³ at "
                        f"{len(bad)} of {n} phases", ("gear1", "gear2"), float(thetas[k]),
                        float(play["overlap_mm3"][k]), "mm3", key="gears.backlash_per_gear_mm"))
    backlash = (play["ahead"] - play["behind"]) * r2
    if backlash.min() <= 0:
        res.add(Finding("mesh", "fail", "the teeth jam: no backlash left", ("gear1", "gear2"),
                        float(thetas[np.argmin(backlash)]), float(backlash.min()), "mm",
                        key="gears.backlash_per_gear_mm"))
    # the frame: the gears against the base (post, block) and the pin, exact 3-D, over a turn of gear 1
    closest = {}
    for t in np.linspace(0.0, 2 * math.pi, 4, endpoint=False):
        P = kit.poses(float(t))
        for g in ("gear1", "gear2"):
            for other in ("base", "pin2"):
                v = intersection(kit.part(g).solid, P[g], kit.part(other).solid, P[other])[0]
                if v > VOLUME_EPS:
                    res.add(Finding("interference", "fail", f"{g} and {other} overlap by {v:.4f} mm³",
                                    (g, other), float(t), v, "mm3", key="frame"))
                gap = min_gap(kit.part(g).solid, P[g], kit.part(other).solid, P[other], 5.0)
                closest[f"{g}-{other}"] = min(closest.get(f"{g}-{other}", math.inf), gap)
    radial = spec.running / 2
    if radial <= 0:
        res.add(Finding("fit", "fail", f"the bores grip their shafts ({radial:.3f} mm radial gap)", ("gear1", "base"),
                        value=radial, unit="mm", key="shafts.running_clearance_diametral_mm"))
    contact = contact_along_face(kit, thetas, play)
    res.add(pattern_finding(contact, ("gear1", "gear2"), "gears.teeth",
                            hint="the flanks are not conjugate along the face (the solids or their poses)"))
    te = play["ahead"] * r2
    res.figures.update(samples=n, phases_over="one tooth pitch of gear 1",
                       max_overlap_mm3=float(play["overlap_mm3"].max()), contact_along_face=contact,
                       backlash_mm={"min": float(backlash.min()), "max": float(backlash.max()),
                                    "designed": designed_backlash(spec)},
                       transmission_error_mm={"peak_to_peak": float(np.ptp(te)), "mean": float(te.mean())},
                       closest_mm={k: float(round(v, 4)) for k, v in closest.items()}, radial_gap_mm=float(radial))
    from ...checks.bed import bed_findings
    from ...checks.bores import bore_findings

    found, on_bed = bed_findings(kit.parts, kit.printer)
    res.add(*found)
    found, bores = bore_findings(kit.parts)
    res.add(*found)
    res.figures["printability"] = {**on_bed, "bores": bores}
    return res


def check_text(spec: BevelSpec, result: Result, folder, seconds: float) -> str:
    f = result.figures
    b, te = f["backlash_mm"], f["transmission_error_mm"]
    lines = [f"{spec.name}: {f['samples']} phases over one tooth pitch of gear 1, exact 3-D",
             f"  largest overlap {f['max_overlap_mm3']:.6f} mm³; backlash {b['min']:.3f}–{b['max']:.3f} mm along "
             f"gear 2's heel pitch circle (designed {b['designed']:.3f} mm); transmission error "
             f"{1000 * te['peak_to_peak']:.1f} µm peak to peak",
             "  " + pattern_text(f["contact_along_face"]),
             "  closest: " + ", ".join(f"{k} {v:.2f} mm" for k, v in f["closest_mm"].items())]
    return "\n".join(lines + check_footer(result, seconds, folder))
