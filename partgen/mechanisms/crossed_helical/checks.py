"""The crossed helical pair's check over a tooth pitch of gear 1 (exact 3-D, contact.py): the
gears never overlap and keep backlash both ways, clear the base, post, blocks and pin over a turn,
each bore clears its shaft, the contact along the faces, the bed and bores; and the text `check`
prints."""

from __future__ import annotations

import math

import numpy as np

from ...checks.contact3d import pair_check
from ...checks.contact_pattern import pattern_finding, pattern_text
from ...checks.footer import check_footer
from ...core.findings import Result
from .contact import contact_along_face, contact_angles, designed_backlash
from .kit import CrossedKit, locking_text
from .resolve import CrossedSpec, is_worm

__all__ = ["check", "check_text"]


def check(spec: CrossedSpec, kit: CrossedKit, samples: int | None = None, progress=None) -> Result:
    """The gears never overlap at phases over a tooth pitch (exact 3-D), keep backlash both ways,
    clear the base, post, blocks and pin over a turn, and each bore clears its shaft."""
    res = Result()
    n = samples or spec.samples
    pitch = 2 * math.pi / spec.gear1.teeth
    thetas = pitch * np.arange(n) / n
    play = contact_angles(kit, thetas, 1e-5)  # 1e-5 rad at gear 2: 0.2 µm on its pitch circle
    if progress:
        progress(n, n)
    contact = contact_along_face(kit, thetas, play)
    pair_check(res, kit, thetas, play, spec.pair.pitch_radius(1), spec.running, designed_backlash(spec),
               contact, pattern_finding(contact["gear2"], ("gear1", "gear2"), "gears.face_width_mm[1]",
                                        hint=_point_contact(spec)),
               {"centre_distance_mm": round(spec.centre_distance, 6)})
    return res


def _point_contact(spec: CrossedSpec) -> str:
    """What a short contact pattern means here (the finding's hint)."""
    if spec.throated:
        return "a throated wheel should bear across its face: its cut or the poses are off"
    if is_worm(spec.pair):
        return ("a plain helical wheel touches the worm at a point, which crosses little of the wheel's face "
                "over a turn (a throated wheel wraps round the worm)")
    return "crossed helical gears touch at a point: their path of contact crosses only part of the face"


def check_text(spec: CrossedSpec, result: Result, folder, seconds: float) -> str:
    f = result.figures
    b, te = f["backlash_mm"], f["transmission_error_mm"]
    lines = [f"{spec.name}: {f['samples']} phases over one tooth pitch of gear 1, exact 3-D",
             f"  largest overlap {f['max_overlap_mm3']:.6f} mm³; backlash {b['min']:.3f}–{b['max']:.3f} mm along "
             f"gear 2's pitch circle (designed {b['designed']:.3f} mm); transmission error "
             f"{1000 * te['peak_to_peak']:.1f} µm peak to peak",
             *("  " + pattern_text(f["contact_along_face"][g]) for g in ("gear2", "gear1")),
             "  closest: " + ", ".join(f"{k} {v:.2f} mm" for k, v in f["closest_mm"].items()),
             "  " + locking_text(spec)]
    return "\n".join(lines + check_footer(result, seconds, folder))
