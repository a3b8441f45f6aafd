"""Every bore that takes a pin, post or axle is open where the pin enters, measured on the part as it
prints (its print orientation, lowest point at z = 0). Any mechanism's check adds these findings
(``bore_findings``); a part declares its bores (``core.parts.Bore``: entry point, axis, the pin's
diameter, how deep it goes) and this knows no mechanism.

The test: a rod of the pin's radius less MARGIN_MM, from LEAD_MM outside the entry point along the
bore's axis to the pin's depth less MARGIN_MM, intersected with the part's solid. What of the part
lies inside the rod is in the pin's way: a bore sealed at its mouth (a skin over it, a dome), a bore
that stops short, or one that is not there. Rule ``bore-open`` fails when that exceeds
BLOCKED_MM3 (a 0.1 mm skin over a Ø3 mm bore is 0.7 mm³).
"""

from __future__ import annotations

import numpy as np

from ..core.findings import Finding
from ..core.parts import Bore
from ..geometry.printing import bore_open
from ..geometry.solid import print_arrays

__all__ = ["LEAD_MM", "MARGIN_MM", "BLOCKED_MM3", "bore_blocked", "entry_side", "bore_findings"]

LEAD_MM = 1.0  # mm: the rod starts this far outside the entry point
MARGIN_MM = 0.02  # mm: the rod is this much thinner (radially) and shorter than the pin (chords, rounding)
BLOCKED_MM3 = 1e-3  # mm³ of the part in the rod's way that closes the bore


def bore_blocked(solid, bore: Bore, print_from_local: np.ndarray | None = None) -> float:
    """mm³ of ``solid`` (a manifold3d solid in the part's local frame) in the way of ``bore``'s pin,
    the part laid as ``print_from_local`` ((4, 4), default none) puts it."""
    T = np.eye(4) if print_from_local is None else np.asarray(print_from_local, float)
    axis = T[:3, :3] @ (np.asarray(bore.axis, float) / np.linalg.norm(bore.axis))
    point = T[:3, :3] @ np.asarray(bore.point, float) + T[:3, 3]
    placed = solid.transform(T[:3]) if print_from_local is not None else solid
    return bore_open(placed, point - LEAD_MM * axis, axis, bore.diameter_mm / 2 - MARGIN_MM,
                     LEAD_MM + bore.depth_mm - MARGIN_MM)


def entry_side(axis_in_print: np.ndarray) -> str:
    """Where a pin going in along ``axis_in_print`` (print frame, z up) enters the printed part."""
    z = float(axis_in_print[2])
    return "from the bed side" if z > 0.7 else "from the top" if z < -0.7 else "from the side"


def bore_findings(parts) -> tuple[list[Finding], dict]:
    """Rule ``bore-open`` for every bore of every distinct printed part (``core.parts.Part`` with
    ``bores``; parts sharing a solid are measured once). Returns the findings and the figures:
    part -> {bore: {"blocked_mm3", "enters"}}."""
    found, figures, seen = [], {}, set()
    for p in parts:
        if not p.printed or not p.bores or (id(p.solid), p.print_flip) in seen:
            continue
        seen.add((id(p.solid), p.print_flip))
        _, _, T = print_arrays(p.solid, p.print_flip)
        table = {}
        for b in p.bores:
            blocked = bore_blocked(p.solid, b, T)
            enters = entry_side(T[:3, :3] @ np.asarray(b.axis, float))
            table[b.name] = {"blocked_mm3": round(blocked, 3), "enters": enters}
            if blocked > BLOCKED_MM3:
                found.append(Finding("printability", "fail", f"{p.name}: the {b.name} bore is closed where its pin enters "
                                     f"({enters} as it prints): {blocked:.2f} mm³ of the part in the way of a "
                                     f"Ø{b.diameter_mm:.2f} mm pin {b.depth_mm:.1f} mm deep", (p.name,), None, blocked,
                                     "mm³", rule="bore-open"))
        figures[p.name] = table
    n = sum(len(t) for t in figures.values())
    shut = sum(f.rule == "bore-open" for f in found)
    if n:
        found.append(Finding("printability", "info", f"{n - shut} of {n} bores in {len(figures)} parts open where their "
                             "pins enter", value=float(n - shut), rule="bore-open"))
    return found, figures
