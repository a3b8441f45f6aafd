"""The rack and pinion's report sections (design, trace, what play costs, check), its subtitle and the bill's
heading."""

from __future__ import annotations

from ....core.findings import Result
from ....core.protocol import Trace
from ..common import report as common
from .kit import RackKit
from .resolve import RackSpec

__all__ = ["report_sections", "subtitle", "bill_text"]


def report_sections(spec: RackSpec, kit: RackKit, result: Result, trace: Trace, files: dict) -> list[tuple[str, str]]:
    from ....export import report as R

    st = trace.stats
    design = (f"<p>A {spec.pinion.teeth}-tooth pinion (x = {spec.pinion.profile_shift:.3f}) and a "
              f"{spec.rack_teeth}-tooth rack, module {spec.system.module:g} mm, travel {spec.travel:g} mm; "
              f"the rack moves {spec.pinion.pitch_radius:.4f} mm per radian of the pinion.</p>")
    check = (f'<p class="{"ok" if result.ok else "fail"}">{result.figures["samples"]} angles over the travel; '
             f'measured {st["ratio_measured"]:.5f} mm/rad, transmission error '
             f'{st["transmission_error_um"]["peak_to_peak"]:.2f} µm peak to peak, backlash '
             f'{st["backlash_mm"]["min"]:.3f}–{st["backlash_mm"]["max"]:.3f} mm.</p>')
    sections = [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error"))]
    lm = st.get("lost_motion_mm")
    if lm:
        at = lm["pinion_arcmin"]
        sections.append(("What play costs", common.lost_motion_html(
            lm, "mm", "the rack", f"At the pinion (the rack held): {at['total']:.1f} arcmin, worst case "
            f"{at['worst_case']:.1f}, 95 % of prints under {at['p95']:.1f} arcmin. The pinion's shaft moves in its "
            "bore along the travel as well as away from the rack (2c / cos α of travel); the rack can back off to "
            "its rail.")))
    return sections + [("Check", check)]


def subtitle(spec: RackSpec) -> str:
    return f"rack and pinion, {spec.pinion.teeth} teeth, {spec.travel:g} mm travel"


def bill_text(spec: RackSpec, man: dict, dest, seconds: float) -> str:
    head = (f"{spec.name}: rack and pinion, {spec.pinion.teeth}-tooth pinion, {spec.rack_teeth}-tooth rack "
            f"({spec.rack_length:.1f} mm), module {spec.system.module:g} mm, {spec.pinion.pitch_radius:.4f} mm per rad")
    return common.bill_text(head, man, dest, seconds)
