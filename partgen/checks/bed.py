"""How every printed part of a kit meets the print bed, measured on the part as it lies there (its
print orientation, lowest point at z = 0): the flat contact it stands on, that it is one shell (no
sealed void inside, no loose piece), and the overhang area steeper than the printer's overhang angle
(what needs supports). Any mechanism's check adds these findings (``bed_findings``).

Rules: ``bed-contact`` fail: the faces lying on the bed (normal straight down, every corner at z = 0)
cover less than MIN_BED_CONTACT_MM2 (a point or a line contact); ``shells`` fail: more than one
shell; ``needs-supports`` info (a fact, not a failure: the slicer adds them), and the figure
``needs_supports_mm2``: per part, the downward faces off the bed steeper than ``overhang_deg`` from
the vertical, their area (mm²). The figure ``orientation``: per part, the face it lies on (the kit
chose it: ``geometry.printing.least_support_flip``), its contact and support areas.
"""

from __future__ import annotations

import math

import numpy as np

from ..core.findings import Finding
from ..core.printer import PrinterLimits
from ..geometry.measure import shell_count
from ..geometry.printing import MIN_BED_CONTACT_MM2
from ..geometry.solid import print_arrays

__all__ = ["MIN_BED_CONTACT_MM2", "bed_contact_and_overhang", "bed_findings", "bed_summary", "add_bed_and_bores"]

ON_BED_TOL = 1e-4  # mm: a face within this of z = 0 lies on the bed
FLAT_COS = 0.9999  # a face whose normal is within 0.8° of straight down is flat


def bed_contact_and_overhang(vertices: np.ndarray, faces: np.ndarray, overhang_deg: float) -> tuple[float, float]:
    """(bed contact, overhang) areas in mm² of a part lying on the bed.

    vertices : (n, 3) float, mm, lowest point at z = 0; faces : (m, 3) int, outward (counter-
    clockwise seen from outside). A face lies on the bed when its normal points straight down and
    its three corners are at z = 0; it overhangs when it faces down more steeply than
    ``overhang_deg`` from the vertical (-n_z > sin overhang) and is not on the bed."""
    t = np.asarray(vertices, float)[np.asarray(faces)]
    cross = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    area2 = np.linalg.norm(cross, axis=1)
    ok = area2 > 0
    nz = np.zeros(len(t))
    nz[ok] = cross[ok, 2] / area2[ok]
    on_bed = (nz < -FLAT_COS) & (t[:, :, 2].max(axis=1) <= ON_BED_TOL)
    over = (-nz > math.sin(math.radians(overhang_deg)) + 1e-9) & ~on_bed
    return float(area2[on_bed].sum() / 2), float(area2[over].sum() / 2)


def bed_findings(parts, printer: PrinterLimits) -> tuple[list[Finding], dict]:
    """The bed rules for every distinct printed part (``core.parts.Part``; parts sharing a solid are
    measured once). Returns the findings and figures: the least bed contact, the parts that need
    supports with their overhang areas (mm²), each part's print orientation."""
    found, figures = [], {"least_bed_contact_mm2": math.inf, "needs_supports_mm2": {}, "orientation": {}}
    seen = set()
    for p in parts:
        if not p.printed or (id(p.solid), p.print_flip) in seen:
            continue
        seen.add((id(p.solid), p.print_flip))
        v, f, _ = print_arrays(p.solid, p.print_flip)
        bed, over = bed_contact_and_overhang(v, f, printer.overhang_deg)
        figures["least_bed_contact_mm2"] = min(figures["least_bed_contact_mm2"], round(bed, 1))
        if bed < MIN_BED_CONTACT_MM2:
            found.append(Finding("printability", "fail", f"{p.name} stands on {bed:.1f} mm² of flat contact with the "
                                 f"bed in its print orientation (at least {MIN_BED_CONTACT_MM2:g} mm²: a point or a line "
                                 "contact comes loose)", (p.name,), None, bed, "mm²", rule="bed-contact"))
        n = shell_count(p.solid)
        if n != 1:
            found.append(Finding("printability", "fail", f"{p.name} is {n} shells, not one: a sealed void or a loose "
                                 "piece inside it (a bore closed at both ends prints as a cavity)", (p.name,), None,
                                 float(n), "", rule="shells"))
        figures["orientation"][p.name] = {"lies_on": "top (printed upside down)" if p.print_flip else "bottom",
                                          "contact_mm2": round(bed, 1), "support_mm2": round(over, 1)}
        if over > 0.5:  # a fact, not a failure: the slicer adds the supports
            figures["needs_supports_mm2"][p.name] = round(over, 1)
            found.append(Finding("printability", "info", f"{p.name} needs supports: {over:.0f} mm² faces down more "
                                 f"steeply than {printer.overhang_deg:g}° from the vertical, lying on its "
                                 f"{'top (printed upside down)' if p.print_flip else 'bottom'}", (p.name,), None, over,
                                 "mm²", rule="needs-supports"))
    if not math.isfinite(figures["least_bed_contact_mm2"]):
        del figures["least_bed_contact_mm2"]
    return found, figures


def add_bed_and_bores(res, parts, printer: PrinterLimits) -> None:
    """Add the bed rules (``bed_findings``) and the open bores (``checks.bores.bore_findings``) of the
    printed ``parts`` to ``res`` (a ``core.findings.Result``), in that order, and their figures as
    ``res.figures["printability"]``: the bed's, with ``bores``."""
    from .bores import bore_findings

    found, on_bed = bed_findings(parts, printer)
    res.add(*found)
    found, bores = bore_findings(parts)
    res.add(*found)
    res.figures["printability"] = {**on_bed, "bores": bores}


def bed_summary(figures: dict) -> str:
    """One line for a check's table from ``bed_findings``' figures (and ``checks.bores``' under
    "bores"): the least contact, how many bores are open, which parts lie upside down, which need
    supports and how much."""
    flipped = [n for n, o in figures.get("orientation", {}).items() if o["lies_on"] != "bottom"]
    bores = figures.get("bores", {})
    shut = sum(b["blocked_mm3"] > 0.001 for t in bores.values() for b in t.values())
    need = figures.get("needs_supports_mm2", {})
    return (f"printing: contact ≥ {figures.get('least_bed_contact_mm2', 0):.0f} mm²; "
            f"{sum(len(t) for t in bores.values()) - shut} of {sum(len(t) for t in bores.values())} bores open; "
            + (f"upside down: {', '.join(flipped)}; " if flipped else "")
            + ("needs supports: " + ", ".join(f"{n} {a:.0f} mm²" for n, a in need.items()) if need else "no supports"))
