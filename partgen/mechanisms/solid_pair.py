"""A pair of solid gears checked and traced exactly in 3-D, written once for every kind whose two
gears are posed solids (gear 1 on a post upright on the base, gear 2 on a pin held by the base's
block or blocks) and whose contact is found by turning gear 2 about its own axis until its solid
touches gear 1's (``checks.contact3d``): the check over a tooth pitch of gear 1 and its text, the
trace (the transmission error, the backlash and the measured ratio), its CSV and its text, the
report's check paragraph, and the schema block of the frame those kinds stand in (``PairFrame``).

What differs between kinds comes in as a ``SolidPair``: the kind's contact search, the radius
its play is measured along (and that circle in words), the designed backlash there, which contact
patterns its texts print and the finding that judges them. Of a kind's spec these read ``name``,
``samples``, ``running`` (the diametral running clearance), ``gear1.teeth``, ``angle2(θ)`` (gear 2's
nominal turn) and ``pair.ratio``, ``pair.speed2()``; of its kit, ``poses``, ``part`` and ``parts``.
This module knows no kind (tests/test_layers.py holds it).
"""

from __future__ import annotations

import html
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..checks.contact3d import pair_check
from ..checks.contact_pattern import pattern_text
from ..checks.footer import check_footer
from ..config.schema import Length, Strict
from ..core.findings import Finding, Result
from ..core.protocol import Trace
from ..export.report import transmission_figure

__all__ = ["SolidPair", "PairFrame", "check", "check_text", "check_html", "trace", "transmission_csv",
           "trace_text"]


@dataclass(frozen=True)
class SolidPair:
    """One kind's exact 3-D contact, as the shared check and trace use it."""

    contact_angles: Callable[..., dict]
    """``(kit, thetas, tol)`` -> how far gear 2 turns ahead and behind before it touches gear 1 (rad) and
    the overlap (mm³) at its nominal angle, at gear 1's turns ``thetas``."""
    measured_ratio: Callable[..., tuple]
    """``(kit)`` -> (the ratio measured after a turn of gear 1, the driven flank's lag at both ends)."""
    contact_along_face: Callable[..., dict]
    """``(kit, thetas, play)`` -> the contact pattern figure (``checks.contact_pattern``)."""
    pitch_radius: Callable[..., float]
    """``(spec)`` -> the radius of gear 2 (mm) its play and transmission error are measured along."""
    designed_backlash: Callable[..., float]
    """``(spec)`` -> the backlash (mm) the design leaves along that circle."""
    circle: str
    """That circle in words, as the texts and the figure say it: "gear 2's pitch circle"."""
    patterns: Callable[[dict], list[dict]]
    """The contact figure -> the patterns the texts print, in their order."""
    finding: Callable[..., Finding]
    """``(spec, contact)`` -> the finding that judges the contact along the face."""
    figures: Callable[..., dict | None] = lambda spec: None
    """``(spec)`` -> figures of the kind's own, placed after the phases (``checks.contact3d.pair_check``)."""


def _pitch_phases(spec, n: int, endpoint: bool) -> np.ndarray:
    """``n`` turns of gear 1 spread over one of its tooth pitches (and the pitch's end with ``endpoint``)."""
    pitch = 2 * math.pi / spec.gear1.teeth
    return pitch * np.arange(n + 1 if endpoint else n) / n


def check(pair: SolidPair, spec, kit, samples: int | None = None, progress=None) -> Result:
    """The gears never overlap at phases over a tooth pitch (exact 3-D), keep backlash both ways,
    clear the base, post, block(s) and pin over a turn, and each bore clears its shaft."""
    res = Result()
    n = samples or spec.samples
    thetas = _pitch_phases(spec, n, False)
    play = pair.contact_angles(kit, thetas, 1e-5)  # 1e-5 rad at gear 2: 0.2 µm on its pitch circle
    if progress:
        progress(n, n)
    contact = pair.contact_along_face(kit, thetas, play)
    pair_check(res, kit, thetas, play, pair.pitch_radius(spec), spec.running, pair.designed_backlash(spec), contact,
               pair.finding(spec, contact), pair.figures(spec))
    return res


def check_text(pair: SolidPair, spec, result: Result, folder, seconds: float, more: tuple[str, ...] = ()) -> str:
    """The text `check` prints: the phases, the overlap, the backlash and transmission error along
    ``pair.circle``, the contact patterns, the closest gaps, the kind's ``more`` lines, the footer."""
    f = result.figures
    b, te = f["backlash_mm"], f["transmission_error_mm"]
    lines = [f"{spec.name}: {f['samples']} phases over one tooth pitch of gear 1, exact 3-D",
             f"  largest overlap {f['max_overlap_mm3']:.6f} mm³; backlash {b['min']:.3f}–{b['max']:.3f} mm along "
             f"{pair.circle} (designed {b['designed']:.3f} mm); transmission error "
             f"{1000 * te['peak_to_peak']:.1f} µm peak to peak",
             *("  " + pattern_text(p) for p in pair.patterns(f["contact_along_face"])),
             "  closest: " + ", ".join(f"{k} {v:.2f} mm" for k, v in f["closest_mm"].items()),
             *("  " + m for m in more)]
    return "\n".join(lines + check_footer(result, seconds, folder))


def check_html(pair: SolidPair, result: Result, trace: Trace) -> str:
    """The report's check paragraph: the phases, the overlap, the backlash, the measured ratio, and
    a paragraph per contact pattern."""
    f, s = result.figures, trace.stats
    return (f'<p class="{"ok" if result.ok else "fail"}">{f["samples"]} phases over a tooth pitch, exact 3-D: '
            f'largest overlap {f["max_overlap_mm3"]:.6f} mm³, backlash {f["backlash_mm"]["min"]:.3f}–'
            f'{f["backlash_mm"]["max"]:.3f} mm; ratio measured {s["ratio_measured"]:.9f} '
            f'(relative error {s["ratio_relative_error"]:.1e}).</p>'
            + "".join(f'<p>{html.escape(pattern_text(p).capitalize())}.</p>'
                      for p in pair.patterns(f["contact_along_face"])))


def trace(pair: SolidPair, kind: str, spec, kit, samples: int | None, out: Path | None) -> Trace:
    """The transmission error over one tooth pitch of gear 1 (where gear 2's driven flank sits
    against its nominal angle, µm along ``pair.circle``), the backlash, and the ratio measured from
    gear 2's loaded angle after one whole turn of gear 1; transmission.png."""
    n = samples or spec.samples
    thetas = _pitch_phases(spec, n, True)
    play = pair.contact_angles(kit, thetas, 1e-7)
    r2 = pair.pitch_radius(spec)
    te, backlash = play["ahead"], (play["ahead"] - play["behind"]) * r2
    ratio, _, _ = pair.measured_ratio(kit)
    design = float(spec.pair.ratio)
    out_angle = spec.angle2(thetas) + te
    # the instantaneous ratio between samples: gear 2's loaded angle's slope, against the nominal
    slope = np.diff(out_angle) / np.diff(thetas)
    local = float(np.abs(slope / spec.pair.speed2() - 1).max())
    stats = {"kind": kind, "samples": len(thetas), "ratio_design": design, "ratio_measured": ratio,
             "ratio_relative_error": abs(ratio / design - 1), "instantaneous_ratio_deviation": local,
             "transmission_error_rad": {"mean": float(te.mean()), "peak_to_peak": float(np.ptp(te))},
             "transmission_error_mm": {"mean": float(te.mean() * r2), "peak_to_peak": float(np.ptp(te) * r2)},
             "backlash_mm": {"min": float(backlash.min()), "max": float(backlash.max()),
                             "designed": pair.designed_backlash(spec)},
             "contact_along_face": pair.contact_along_face(kit, thetas[:-1], {k: v[:-1] for k, v in play.items()})}
    files = []
    if out is not None:
        (out / "transmission.png").write_bytes(transmission_figure(
            f"{spec.name}: exact 3-D contact of the printed solids", thetas, te * r2, backlash,
            "gear 1 angle (°), one tooth pitch", f"µm along {pair.circle}"))
        files = ["transmission.png"]
    return Trace(stats, files, columns=("input_rad", "output_rad", "transmission_error_rad", "backlash_mm"),
                 data=np.column_stack([thetas, out_angle, te, backlash]))


def transmission_csv(header: str, trace: Trace) -> str:
    """A trace of (input, output, transmission error: rad; backlash: mm) as CSV rows under ``header``."""
    return header + "".join(f"{a:.9f},{b:.9f},{c:.9f},{d:.6f}\n" for a, b, c, d in trace.data)


def trace_text(pair: SolidPair, spec, trace: Trace, folder) -> str:
    """The text `trace` prints: the measured ratio, the transmission error and backlash along
    ``pair.circle``, the contact patterns, the plots."""
    s = trace.stats
    lines = [f"{spec.name}: ratio {s['ratio_measured']:.9f} measured after one turn of gear 1 (design "
             f"{s['ratio_design']:.9f}, relative error {s['ratio_relative_error']:.1e}); between phases within "
             f"{100 * s['instantaneous_ratio_deviation']:.3f} % of it",
             f"  transmission error {1000 * s['transmission_error_mm']['peak_to_peak']:.1f} µm peak to peak along "
             f"{pair.circle} over a tooth ({s['samples']} phases); backlash "
             f"{s['backlash_mm']['min']:.3f}–{s['backlash_mm']['max']:.3f} mm",
             *("  " + pattern_text(p) for p in pair.patterns(s["contact_along_face"]))]
    if folder:
        lines.append(f"plots: {folder}/{', '.join(trace.files)}")
    return "\n".join(lines)


class PairFrame(Strict):
    """The base: a plate carrying gear 1's post and the block(s) that hold gear 2's pin."""

    base_thickness_mm: Length = 5.0
    """Thickness of the base plate that carries gear 1's post and the block(s) holding gear 2's pin."""
    margin_mm: Length = 4.0
    """How far the base reaches beyond gear 1's largest tip circle and gear 2's block(s)."""
    axial_gap_mm: Length = 0.5
    """Gap between a gear (or its hub) and the base or a block; also gear 2's lowest point above the base."""
    block_wall_mm: Length = 4.0
    """Material round gear 2's pin in its block(s)."""
    block_thickness_mm: Length = 8.0
    """Thickness of each block along gear 2's axis: how deep the pin is held."""
