"""The crossed helical pair's report: the bill `build` prints, the report's sections (design, trace,
check), its subtitle and the assembly steps."""

from __future__ import annotations

import math

from ...core.findings import Result
from ...core.protocol import Trace
from ...export.bill import part_lines
from .. import solid_pair
from .contact import PAIR
from .kit import CrossedKit, design_numbers, locking_text
from .resolve import CrossedSpec, is_worm

__all__ = ["bill_text", "report_sections", "subtitle", "assembly_steps"]


def bill_text(spec: CrossedSpec, man: dict, dest, seconds: float) -> str:
    p = spec.pair
    wheel = "throated wheel (cut by the worm's envelope)" if spec.throated else "helical wheel"
    what = (f"a {p.teeth[0]}-start ZI worm and a {p.teeth[1]}-tooth {wheel}" if is_worm(p) else
            f"crossed helical pair {p.teeth[0]}/{p.teeth[1]} teeth")
    lines = [f"{spec.name}: {what}, normal module {p.normal_module:g} mm, helix {math.degrees(p.helix[0]):g}° + "
             f"{math.degrees(p.helix[1]):g}° (right hand) on shafts at {math.degrees(p.shaft_angle):g}°, "
             f"{spec.centre_distance:.3f} mm apart; ratio {p.teeth[1]}:{p.teeth[0]} (input turns per output turn)"]
    lines.append(locking_text(spec))
    lines += part_lines(man)
    lines.append(f"wrote {dest}/ in {seconds:.2f} s")
    return "\n".join(lines)


def report_sections(spec: CrossedSpec, kit: CrossedKit, result: Result, trace: Trace,
                    files: dict) -> list[tuple[str, str]]:
    from ...export import report as R

    d = design_numbers(spec)
    design = R.table(["", "gear 1 (input)", "gear 2 (output)"],
                     [["teeth", *d["teeth"]], ["helix angle °", *d["helix_angle_deg"]],
                      ["transverse module mm", *d["transverse_module_mm"]],
                      ["pitch diameter mm", *d["pitch_diameter_mm"]], ["tip diameter mm", *d["tip_diameter_mm"]],
                      ["face width mm", *d["face_width_mm"]]]) \
        + (f"<p>Normal module {d['normal_module_mm']:g} mm, normal pressure angle "
           f"{d['normal_pressure_angle_deg']:g}°, shafts at {d['shaft_angle_deg']:g}°, "
           f"{d['centre_distance_mm']:.3f} mm apart; ratio {d['ratio']}; both right hand. Sliding at the pitch "
           f"point {d['sliding_per_rolling']:.3f} mm per mm of gear 1's pitch circle. "
           f"{locking_text(spec).capitalize()}.</p>")
    check = solid_pair.check_html(PAIR, result, trace)
    return [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error")),
            ("Check", check)]


def subtitle(spec: CrossedSpec) -> str:
    if is_worm(spec.pair):
        return f"{spec.gear1.teeth}-start worm and {spec.gear2.teeth}-tooth wheel"
    return f"{spec.gear1.teeth}/{spec.gear2.teeth} crossed helical pair"


def assembly_steps(spec: CrossedSpec, kit: CrossedKit) -> list[tuple[str, tuple[str, ...]]]:
    return [("Stand the base on the table: gear 1's post up, gear 2's two blocks beside it.", ("base",)),
            (f"Slide gear1 ({spec.gear1.teeth} teeth) down over the post until its collar rests on the base.",
             ("gear1",)),
            (f"Hold gear2 ({spec.gear2.teeth} teeth) between the blocks, its teeth in gear1's, and press the pin "
             "through the first block, the gear and the second block; turn gear1 by hand: both turn freely.",
             ("gear2", "pin2"))]
