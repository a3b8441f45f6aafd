"""The planetary set's kit: the frame (the bottom plate with the ring, the sun's thrust ring and the
planets' track; the top plate on spacers), the sun and its input shaft, the planets, the carrier and
its output shaft (and their hardware); their poses over the sun's angle; the manifest's design."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ....core.parts import Contact, Part
from ....core.protocol import ParamsKit
from ....core.transforms import pose_z
from ....geometry.gear import gear_body, ring_body
from ....geometry.outline import circle
from ....geometry.parts import DFit, shaft as shaft_solid
from ....geometry.solid import prisms, slab, union
from ..common import KIND
from ..common.kit import (FEATURE_TOL, hub_contacts, hub_cutters, hub_hole, hub_summary, hubbed_gear, r6, screw_and_nut,
                          turning_shaft)
from .resolve import PlanetarySpec

__all__ = ["PlanetaryKit", "build_planetary", "design_summary"]


@dataclass(frozen=True)
class PlanetaryKit(ParamsKit):
    params: PlanetarySpec
    parts: tuple[Part, ...]
    contacts: tuple[Contact, ...]

    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        s = self.params
        c = s.carrier(float(theta))
        out = {"frame_bottom": pose_z(angle=s.ring_phase), "frame_top": np.eye(4), "sun": pose_z(angle=float(theta)),
               "shaft_in": pose_z(angle=float(theta)), "carrier": pose_z(angle=c), "shaft_out": pose_z(angle=c)}
        for i in range(len(s.angles)):
            out[f"planet{i}"] = pose_z(*s.planet_centre(i, theta), 0.0, s.planet_angle(i, theta))
        for n, part in self._hardware:  # bought nuts and screws turn with their part
            out[n] = out[part]
        return out

    @cached_property
    def _hardware(self) -> tuple[tuple[str, str], ...]:
        """(bought part, the part it turns with) of the kit's nuts and set screws."""
        names = {p.name for p in self.parts}
        return tuple((n, part) for end, part in (("in", "sun"), ("out", "carrier"))
                     for n in (f"nut_{end}", f"set_screw_{end}") if n in names)


def _spacers(s: PlanetarySpec) -> list[tuple[float, float]]:
    d = s.rim_radius + s.margin + s.spacer_radius
    return [(d * math.cos(a), d * math.sin(a)) for a in (math.pi / 4 + k * math.pi / 2 for k in range(4))]


def build_planetary(s: PlanetarySpec, progress=None) -> PlanetaryKit:
    say = progress or (lambda name: None)
    tol = FEATURE_TOL
    g, f, t, zc, zt = s.gap, s.face_width, s.plate_thickness, s.carrier_z, s.top_z
    gz = s.gear_z  # the gears' bottom face (g, or over the sun's set-screw hub)
    spacers = _spacers(s)
    peg = s.spacer_radius / 2
    wall = s.printer.min_wall
    h_in, h_out = s.hubs or (None, None)
    in_hole = (h_in.radius if h_in else s.shaft_radius) + s.running / 2
    # the bottom plate is turned by the ring's phase (poses): its features are placed in its own frame
    rot = lambda p: (p[0] * math.cos(-s.ring_phase) - p[1] * math.sin(-s.ring_phase),  # noqa: E731
                     p[0] * math.sin(-s.ring_phase) + p[1] * math.cos(-s.ring_phase))
    sp_local = [rot(c) for c in spacers]
    outline = circle(s.rim_radius + s.margin + 2 * s.spacer_radius + 2.0, tol)
    say("frame_bottom")
    sun_ring = circle(min(s.sun.root_radius - 0.5, in_hole + max(2 * wall, 2.0)), tol).difference(
        circle(in_hole, tol, hole=True))
    # the planets' track: under their faces, clear of the sun's and the ring's tips
    track_w = s.track_width
    track = circle(s.centre_distance + track_w, tol).difference(circle(s.centre_distance - track_w, tol))
    bottom = union([slab(outline.difference(circle(in_hole, tol, hole=True)), -t, 0.0),
                    ring_body(s.space, s.rim_radius, gz + f, 0.0),
                    prisms([(sun_ring, 0.0, g), (track, 0.0, gz)]
                           + [(circle(s.spacer_radius, tol, c), 0.0, zt) for c in sp_local]
                           + [(circle(peg, tol, c), zt, zt + t) for c in sp_local])])
    parts = [Part("frame_bottom", "frame", bottom)]
    say("frame_top")
    top = outline.difference(circle((h_out.radius if h_out else s.shaft_radius) + s.running / 2, tol, hole=True))
    for c in spacers:
        top = top.difference(circle(peg + s.press / 2, tol, c, hole=True))
    parts.append(Part("frame_top", "frame", slab(top, zt, zt + t)))
    say("sun")
    if h_in is None or h_in.kind == "d_flat":
        d_hole = DFit(s.shaft_radius, s.press).hole(max(s.tol, 0.005))
        parts.append(Part("sun", "gear", gear_body(s.sun, f, d_hole, g), gear=s.sun))
        parts.append(Part("shaft_in", "axle", shaft_solid(DFit(s.shaft_radius, 0.0), [("round", -t - s.extension, g),
                                                                                       ("D", g, g + f)], tol)))
    else:
        sun = hubbed_gear(s.sun, f, h_in, s.press, s.running, s.hub_radius, g, gz, bool(s.base), s.tol)
        # a sun standing on its hub prints upside down, its top face on the bed
        parts.append(Part("sun", "gear", sun, print_flip=s.base > 0, gear=s.sun))
        parts += turning_shaft(h_in, "shaft_in", "nut_in", -t - s.extension, gz + f, (g, gz + f))
        if h_in.kind == "set_screw":
            parts += screw_and_nut(h_in, "set_screw_in", "nut_in", g)
    say("planets")
    planet = gear_body(s.planet, f, circle(s.pin_radius + s.running / 2, max(s.tol, 0.005), hole=True), gz)
    for i in range(len(s.angles)):
        parts.append(Part(f"planet{i}", "gear", planet, gear=s.planet))
    say("carrier")
    pins = [(circle(s.pin_radius, tol, (s.centre_distance * math.cos(a), s.centre_distance * math.sin(a))),
             gz + min(0.25, g / 2), zc) for a in s.angles]
    plate_r = s.centre_distance + s.pin_radius + s.running / 2 + 2 * wall
    if h_out is None or h_out.kind == "d_flat":
        plate = circle(plate_r, tol).difference(DFit(s.shaft_radius, s.press).hole(max(s.tol, 0.005)))
    else:
        plate = circle(plate_r, tol).difference(hub_hole(h_out, s.press, max(s.tol, 0.005)))
    carrier = union([slab(plate, zc, zc + t), prisms(pins)])
    cut = hub_cutters(h_out, zc, plate_r + 1.0, s.running, s.screw_turn) if h_out else []
    if cut:  # a nut trap or a set screw's slot in the plate's bottom face, the screw's hole out to its rim
        carrier = carrier - union(cut)
    parts.append(Part("carrier", "carrier", carrier, print_flip=True))  # its plate's top on the bed, pins up
    if h_out is None or h_out.kind == "d_flat":
        parts.append(Part("shaft_out", "axle", shaft_solid(DFit(s.shaft_radius, 0.0), [("D", zc, zc + t),
                                                                                        ("round", zc + t, zt + t + s.extension)], tol)))
    else:
        parts += turning_shaft(h_out, "shaft_out", "nut_out", zc, zt + t + s.extension, (zc, zc + t))
        if h_out.kind == "set_screw":
            parts += screw_and_nut(h_out, "set_screw_out", "nut_out", zc, s.screw_turn)
    held = lambda h: (s.running if h is not None and h.kind == "hex" else s.press) / 2  # noqa: E731 (a rod: clearance)
    contacts = [Contact("sun", "shaft_in", "press", (g, gz + f), held(h_in)),
                Contact("shaft_in", "frame_bottom", "running", (-t, 0.0), s.running / 2),
                Contact("shaft_out", "frame_top", "running", (zt, zt + t), s.running / 2),
                Contact("shaft_out", "carrier", "press", (zc, zc + t), held(h_out)),
                Contact("sun", "frame_bottom", "thrust"),
                Contact("frame_top", "frame_bottom", "press", (zt, zt + t), s.press / 2)]
    for i in range(len(s.angles)):
        # the sun/planet meshes are left out of the pairwise sweep, as the planet/ring ones (the ring is
        # the frame's, met on the track by the thrust contact): their whole sections are checked
        # against each other at every mesh phase (checks.meshing, turn_planetary)
        contacts += [Contact(f"planet{i}", "carrier", "running", (gz + 0.25, gz + f), s.running / 2),
                     Contact(f"planet{i}", "frame_bottom", "thrust"), Contact("sun", f"planet{i}", "mesh")]
    if h_in is not None:
        contacts += hub_contacts(h_in, "sun", "shaft_in", "nut_in", "set_screw_in", "frame_bottom")
        contacts += hub_contacts(h_out, "carrier", "shaft_out", "nut_out", "set_screw_out", None)
    return PlanetaryKit(s, tuple(parts), tuple(contacts))


def design_summary(spec: PlanetarySpec) -> dict:
    t = spec.teeth
    out = {"name": spec.name, "kind": KIND, "arrangement": "planetary: ring fixed, sun input, carrier output",
           "module_mm": spec.system.module, "pressure_angle_deg": r6(math.degrees(spec.system.pressure_angle)),
           "face_width_mm": spec.face_width, "teeth": {"sun": t.sun, "planet": t.planet, "ring": t.ring},
           "planets": t.planets, "ratio": f"1 + {t.ring}/{t.sun}", "ratio_value": r6(t.ratio),
           "assembly": f"({t.sun} + {t.ring})/{t.planets} = {(t.sun + t.ring) / t.planets:g}",
           "planet_angles_deg": [r6(math.degrees(a)) for a in spec.angles],
           "planet_phases_deg": [r6(math.degrees(a)) for a in spec.planet_phases],
           "ring_phase_deg": r6(math.degrees(spec.ring_phase)), "centre_distance_mm": r6(spec.centre_distance),
           "ring_tip_diameter_mm": r6(2 * (spec.space.root_radius)), "ring_root_diameter_mm": r6(2 * spec.space.tip_radius),
           "shaft_diameter_mm": 2 * spec.shaft_radius, "pin_diameter_mm": 2 * spec.pin_radius,
           "printer": spec.printer.name, "material": spec.material, "density_g_cm3": r6(spec.density * 1000)}
    if spec.target_ratio is not None:
        out["target_ratio"] = spec.target_ratio
        out["ratio_error"] = r6(t.ratio / spec.target_ratio - 1)
    if spec.hubs is not None:
        out["bores"] = {end: {"bore": h.kind, **hub_summary(h, spec.running)}
                        for end, h in zip(("input", "output"), spec.hubs)}
        out.update(hub_height_mm=r6(spec.base), sun_hub_diameter_mm=r6(2 * spec.hub_radius))
    return out
