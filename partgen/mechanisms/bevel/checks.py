"""The straight bevel pair's check over a tooth pitch of gear 1 (exact 3-D, contact.py): the
gears never overlap and keep backlash both ways, clear the base, post, block and pin over a turn,
each bore clears its shaft, the contact along the face, the bed and bores; and the text `check`
prints."""

from __future__ import annotations

import math

import numpy as np

from ...checks.contact3d import pair_check
from ...checks.contact_pattern import pattern_finding, pattern_text
from ...checks.footer import check_footer
from ...core.findings import Result
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
    contact = contact_along_face(kit, thetas, play)
    pair_check(res, kit, thetas, play, spec.gear2.pitch_radius, spec.running, designed_backlash(spec), contact,
               pattern_finding(contact, ("gear1", "gear2"), "gears.teeth",
                               hint="the flanks are not conjugate along the face (the solids or their poses)"))
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
