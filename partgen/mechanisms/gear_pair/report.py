"""The spur gear pair's report: the bill `build` prints, the report's sections (design, trace,
check), its subtitle and the assembly steps."""

from __future__ import annotations

import math

from ...core.findings import Result
from ...core.protocol import Trace
from ...export.bill import part_lines
from .kit import PairKit
from .resolve import PairSpec

__all__ = ["bill_text", "report_sections", "subtitle", "assembly_steps"]


def bill_text(spec: PairSpec, man: dict, dest, seconds: float) -> str:
    lines = [f"{spec.name}: {spec.gear1.teeth}/{spec.gear2.teeth} teeth, module {spec.gear1.system.module:g} mm, "
             f"centre distance {spec.centre_distance:.3f} mm"]
    lines += part_lines(man)
    lines.append(f"wrote {dest}/ in {seconds:.2f} s")
    return "\n".join(lines)


def report_sections(spec: PairSpec, kit: PairKit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
    from ...export import report as R

    f = result.figures
    design = R.table(["", "gear 1 (input)", "gear 2 (output)"],
                     [["teeth", spec.gear1.teeth, spec.gear2.teeth],
                      ["profile shift", round(spec.gear1.profile_shift, 4), round(spec.gear2.profile_shift, 4)],
                      ["tip diameter mm", round(2 * spec.gear1.tip_radius, 3), round(2 * spec.gear2.tip_radius, 3)]]) \
        + (f"<p>Module {spec.gear1.system.module:g} mm, pressure angle "
           f"{math.degrees(spec.gear1.system.pressure_angle):g}°, centre distance {spec.centre_distance:.3f} mm, "
           f"face width {spec.face_width:g} mm, posts Ø{2 * spec.axle_radius:g} mm.</p>")
    check = (f'<p class="{"ok" if result.ok else "fail"}">{f["samples"]} angles over one output turn: backlash '
             f'{f["backlash_mm"]["min"]:.3f}–{f["backlash_mm"]["max"]:.3f} mm, transmission error '
             f'{1000 * f["transmission_error_mm"]["peak_to_peak"]:.1f} µm peak to peak.</p>')
    return [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error")),
            ("Check", check)]


def subtitle(spec: PairSpec) -> str:
    return f"{spec.gear1.teeth}/{spec.gear2.teeth} spur gear pair"


def assembly_steps(spec: PairSpec, kit: PairKit) -> list[tuple[str, tuple[str, ...]]]:
    """The base, gear 1 on its post, gear 2 on the other post in mesh."""
    return [("Stand the base on the table, its two posts up.", ("base",)),
            (f"Slide gear1 ({spec.gear1.teeth} teeth) down over its post until it rests on the base.", ("gear1",)),
            (f"Slide gear2 ({spec.gear2.teeth} teeth) down over the other post, turning it until its teeth drop into "
             "mesh with gear1's; "
             "turn gear1 by hand: both turn freely.", ("gear2",))]
