"""The rack and pinion's kit: the base (its plate, the pinion's thrust ring, the rack's strip and its
rail), the pinion and its shaft (and hardware), the rack; their poses over the pinion's angle; the
manifest's design."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from shapely.geometry import Polygon, box

from ....core.parts import Contact, Part
from ....core.protocol import ParamsKit
from ....core.transforms import pose_z
from ....design.rack import rack_outline
from ....geometry.gear import gear_body
from ....geometry.outline import circle
from ....geometry.parts import DFit, shaft as shaft_solid
from ....geometry.solid import extrude, prisms, slab, union
from ..common import KIND
from ..common.kit import FEATURE_TOL, hub_contacts, hub_summary, hubbed_gear, r6, screw_and_nut, turning_shaft
from .resolve import RackSpec

__all__ = ["RackKit", "build_rack", "design_summary"]


@dataclass(frozen=True)
class RackKit(ParamsKit):
    params: RackSpec
    parts: tuple[Part, ...]
    contacts: tuple[Contact, ...]

    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        s = self.params
        a = -math.pi / 2 + float(theta)  # tooth 0 points down into a space of the rack at rest
        out = {"frame_bottom": np.eye(4), "pinion": pose_z(angle=a), "shaft": pose_z(angle=a),
               "rack": pose_z(s.rack_x(float(theta)), s.pitch_line, s.gear_z)}
        for n in ("nut", "set_screw"):  # a nut trap's nut, a set screw and its nut turn with the pinion
            if any(p.name == n for p in self.parts):
                out[n] = out["pinion"]
        return out


def build_rack(s: RackSpec, progress=None) -> RackKit:
    say = progress or (lambda name: None)
    tol = FEATURE_TOL
    g, f, t, m = s.gap, s.face_width, s.plate_thickness, s.system.module
    gz, h = s.gear_z, s.hub
    al = s.system.pressure_angle
    hf = s.system.dedendum_coeff * m
    root_y = s.pitch_line - hf
    back_y = root_y - s.back
    rail_w = max(3 * s.printer.min_wall, 3.0)
    gap = s.running / 2  # the rack's back face runs this far from the rail
    say("frame_bottom")
    half = s.rack_length / 2 + s.travel / 2 + s.margin  # the guide holds the rack over its whole travel
    plate = box(-half, back_y - gap - rail_w - s.margin, half, s.pinion.tip_radius + s.margin)
    hole = circle((h.radius if h else s.shaft_radius) + s.running / 2, tol, hole=True)
    ring = circle(min(s.pinion.root_radius - 0.5, s.shaft_radius + s.running / 2 + max(2 * s.printer.min_wall, 2.0)),
                  tol).difference(hole)
    strip = box(-half, back_y + 0.5, half, root_y - s.checks.min_clearance - 0.5)
    rail = box(-half, back_y - gap - rail_w, half, back_y - gap)
    base = union([slab(plate.difference(hole), -t, 0.0), prisms([(ring, 0.0, g), (strip, 0.0, gz), (rail, 0.0, gz + f)])])
    parts = [Part("frame_bottom", "frame", base)]
    say("pinion")
    if h is None or h.kind == "d_flat":
        parts.append(Part("pinion", "gear", gear_body(s.pinion, f, DFit(s.shaft_radius, s.press).hole(max(s.tol, 0.005)),
                                                      g), gear=s.pinion))
        parts.append(Part("shaft", "axle", shaft_solid(DFit(s.shaft_radius, 0.0), [("round", -t, g), ("D", g, g + f),
                                                                                    ("round", g + f, g + f + s.extension)],
                                                       tol)))
    else:
        pinion = hubbed_gear(s.pinion, f, h, s.press, s.running, s.hub_radius, g, gz, bool(s.base), s.tol)
        parts.append(Part("pinion", "gear", pinion, print_flip=s.base > 0, gear=s.pinion))
        parts += turning_shaft(h, "shaft", "nut", -t, gz + f + s.extension, (g, gz + f))
        if h.kind == "set_screw":
            parts += screw_and_nut(h, "set_screw", "nut", g)
    say("rack")
    outline = rack_outline(s.rack_teeth, m, al, s.system.backlash_per_gear, s.system.addendum_coeff,
                           s.system.dedendum_coeff, s.system.cutter_tip_coeff, s.back, s.system.chord_tolerance)
    parts.append(Part("rack", "rack", extrude(Polygon(outline), f)))
    held = (s.running if h is not None and h.kind == "hex" else s.press) / 2  # a threaded rod: a clearance
    contacts = (Contact("pinion", "shaft", "press", (g, gz + f), held),
                Contact("shaft", "frame_bottom", "running", (-t, 0.0), s.running / 2),
                Contact("pinion", "frame_bottom", "thrust"), Contact("rack", "frame_bottom", "thrust"))
    if h is not None:
        contacts += tuple(hub_contacts(h, "pinion", "shaft", "nut", "set_screw", "frame_bottom"))
    return RackKit(s, tuple(parts), contacts)


def design_summary(spec: RackSpec) -> dict:
    p = spec.pinion
    out = {"name": spec.name, "kind": KIND, "arrangement": "rack and pinion",
           "module_mm": spec.system.module, "pressure_angle_deg": r6(math.degrees(spec.system.pressure_angle)),
           "face_width_mm": spec.face_width, "pinion_teeth": p.teeth, "pinion_profile_shift": r6(p.profile_shift),
           "rack_teeth": spec.rack_teeth, "rack_length_mm": r6(spec.rack_length), "travel_mm": spec.travel,
           "mm_per_rad": r6(p.pitch_radius), "pitch_line_y_mm": r6(spec.pitch_line),
           "shaft_diameter_mm": 2 * spec.shaft_radius, "printer": spec.printer.name, "material": spec.material,
           "density_g_cm3": r6(spec.density * 1000)}
    if spec.hub is not None:
        out.update(bore={"bore": spec.hub.kind, **hub_summary(spec.hub, spec.running)}, hub_height_mm=r6(spec.base),
                   hub_diameter_mm=r6(2 * spec.hub_radius))
    return out
