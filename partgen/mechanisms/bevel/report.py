"""The straight bevel pair's report: the bill `build` prints, the report's sections (design, trace,
check), its subtitle and the assembly steps."""

from __future__ import annotations

import math

from ...core.findings import Result
from ...core.protocol import Trace
from ...export.bill import part_lines
from .. import solid_pair
from .contact import PAIR
from .kit import BevelKit, design_numbers
from .resolve import BevelSpec

__all__ = ["bill_text", "report_sections", "subtitle", "assembly_steps"]


def bill_text(spec: BevelSpec, man: dict, dest, seconds: float) -> str:
    p = spec.pair
    what = "mitre pair" if p.teeth[0] == p.teeth[1] and abs(p.shaft_angle - math.pi / 2) < 1e-9 else "bevel pair"
    lines = [f"{spec.name}: straight {what} {p.teeth[0]}/{p.teeth[1]} teeth, module {p.module:g} mm at the heel, "
             f"shafts at {math.degrees(p.shaft_angle):g}°, pitch cones {math.degrees(p.gears[0].pitch_angle):.3f}° "
             f"+ {math.degrees(p.gears[1].pitch_angle):.3f}°, cone distance {p.cone_distance:.3f} mm, face "
             f"{p.gears[0].face_width:g} mm; ratio {p.teeth[1]}:{p.teeth[0]} (input turns per output turn)",
             "teeth: spherical involute (exact), straight through the apex (conical)"]
    lines += part_lines(man)
    lines.append(f"wrote {dest}/ in {seconds:.2f} s")
    return "\n".join(lines)


def report_sections(spec: BevelSpec, kit: BevelKit, result: Result, trace: Trace,
                    files: dict) -> list[tuple[str, str]]:
    from ...export import report as R

    d = design_numbers(spec)
    design = R.table(["", "gear 1 (input)", "gear 2 (output)"],
                     [["teeth", *d["teeth"]], ["pitch cone angle °", *d["pitch_angle_deg"]],
                      ["heel pitch diameter mm", *d["pitch_diameter_mm"]],
                      ["heel tip diameter mm", *d["tip_diameter_mm"]],
                      ["base cone angle °", *d["base_angle_deg"]]]) \
        + (f"<p>Module {d['module_mm']:g} mm at the heel, pressure angle {d['pressure_angle_deg']:g}°, shafts at "
           f"{d['shaft_angle_deg']:g}°, cone distance {d['cone_distance_mm']:.3f} mm, face width "
           f"{d['face_width_mm']:g} mm, contact ratio {d['contact_ratio']:.2f}; ratio {d['ratio']}. Teeth: "
           f"{d['tooth_form']}.</p>")
    check = solid_pair.check_html(PAIR, result, trace)
    return [("Design", design), ("Trace", R.img(files["transmission.png"], "transmission error")),
            ("Check", check)]


def subtitle(spec: BevelSpec) -> str:
    p = spec.pair
    return f"{p.teeth[0]}/{p.teeth[1]} straight bevel pair at {math.degrees(p.shaft_angle):g}°"


def assembly_steps(spec: BevelSpec, kit: BevelKit) -> list[tuple[str, tuple[str, ...]]]:
    return [("Stand the base on the table: gear 1's post up, gear 2's block beside it.", ("base",)),
            (f"Slide gear1 ({spec.gear1.teeth} teeth) down over the post, its teeth up.", ("gear1",)),
            (f"Push the pin into the block's hole, slide gear2 ({spec.gear2.teeth} teeth) onto it, hub first, "
             "until its teeth sit in gear1's; turn gear1 by hand: both turn freely." +
             (" Gear2 leans over gear1 (shafts past 90°): its weight slides it down the pin into the mesh "
              "at rest; driven, the mesh's thrust pushes it back against its block." if spec.pair.axis2[2] < 0
              else ""), ("pin2", "gear2"))]
