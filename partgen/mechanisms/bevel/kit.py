"""A straight bevel pair as parts: a base carrying gear 1's upright post and a block that holds gear
2's pin along the other shaft, the two bevel gears and the pin; poses over gear 1's turn θ (rad)
(the frame: resolve.py); what the kit folder holds (the manifest's design, design.yaml,
printer.yaml).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from shapely.geometry import box

from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.parts import Bore, Part
from ...core.quantise import r6
from ...core.protocol import SpecKit
from ...core.transforms import pose_z
from ...errors import DesignError
from ...geometry.bevel import bevel_gear, hull_to_floor
from ...geometry.measure import refuse_oversize
from ...geometry.outline import circle
from ...geometry.printing import least_support_flip
from ...geometry.solid import extrude, union
from .resolve import BevelSpec

__all__ = ["BevelKit", "build_bevel", "build", "refuse", "design_numbers", "design_summary", "kit_files"]


@dataclass(frozen=True)
class BevelKit(SpecKit):
    """The base (post and pin block), gear 1, gear 2 and gear 2's pin; poses over gear 1's turn θ."""

    spec: BevelSpec
    parts: tuple[Part, ...]


    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        s = self.spec
        return {"base": np.eye(4), "gear1": pose_z(0.0, 0.0, s.z_apex, float(theta)),
                "gear2": s.pose2(float(s.angle2(theta))), "pin2": s.pin_frame}


def build_bevel(s: BevelSpec, progress=None) -> BevelKit:
    say = progress or (lambda name: None)
    pair, tol = s.pair, s.tol
    r1s, r2s = s.shaft_radius
    ftol = max(tol, 0.005)
    say("gear1")
    g1 = bevel_gear(s.gear1, r1s + s.running / 2, s.hub_radius(0), s.hub_end(0), tol)
    say("gear2")
    g2 = bevel_gear(s.gear2, r2s + s.running / 2, s.hub_radius(1), s.hub_end(1), tol)
    say("base")
    # gear 1's post: from inside the base to gear 1's toe face
    top1 = s.z_apex + float(s.gear1.toe_root[1])
    post = extrude(circle(r1s, ftol), top1 + 0.01, -0.01)
    # gear 2's block: a square prism round the pin's axis, and everything under it down into the base
    far, near = s.block_span
    k = s.block_reach
    corners = np.array([[x, y, a] for x in (-k, k) for y in (-k, k) for a in (far, near)])
    T = s.pin_frame
    world = corners @ T[:3, :3].T + T[:3, 3]
    block = hull_to_floor(world, direction=s.leg_direction)
    feet = world + ((-0.01 - world[:, 2]) / s.leg_direction[2])[:, None] * s.leg_direction
    world = np.vstack([world, feet])
    hole = extrude(circle(r2s + s.press / 2, ftol, hole=True), near - far + 20.0, far - 10.0).transform(T[:3, :])
    foot1 = float(s.gear1.blank()[2, 0]) + s.margin  # gear 1's heel tip circle, and the margin
    xs = [min(-foot1, float(world[:, 0].min()) - s.margin), max(foot1, float(world[:, 0].max()) + s.margin)]
    ys = [min(-foot1, float(world[:, 1].min()) - s.margin), max(foot1, float(world[:, 1].max()) + s.margin)]
    plate = extrude(box(xs[0], ys[0], xs[1], ys[1]), s.base_thickness, -s.base_thickness)
    base = union([plate, post, block]) - hole
    say("pin2")
    a0, a1 = s.pin_span
    pin = extrude(circle(r2s, ftol), a1 - a0, a0)
    u = pair.axis2
    entry = T[:3, :3] @ np.array([0.0, 0.0, far - 0.5]) + T[:3, 3]
    back1 = s.hub_end(0)
    parts = [Part("base", "base", base, bores=(Bore("block", tuple(float(v) for v in entry), tuple(float(v) for v in u),
                                                    2 * r2s, s.block_thickness + 1.0),)),
             Part("gear1", "gear", g1, bores=(Bore("post", (0.0, 0.0, back1), (0.0, 0.0, 1.0), 2 * r1s,
                                                   float(s.gear1.toe_root[1]) - back1),)),
             Part("gear2", "gear", g2, bores=(Bore("pin", (0.0, 0.0, s.hub_end(1)), (0.0, 0.0, 1.0), 2 * r2s,
                                                   float(s.gear2.toe_root[1]) - s.hub_end(1)),)),
             Part("pin2", "axle", pin)]
    return BevelKit(s, tuple(replace(p, print_flip=least_support_flip(p.solid, s.printer.overhang_deg)) for p in parts))


def build(spec: BevelSpec, progress=None) -> BevelKit:
    try:
        return build_bevel(spec, progress)
    except ValueError as e:
        raise DesignError(str(e), "gears.teeth") from None


def refuse(spec: BevelSpec, kit: BevelKit) -> None:
    refuse_oversize(kit.parts, spec.printer.envelope, "gears.module_mm")


def design_numbers(spec: BevelSpec) -> dict:
    """The pair's numbers, as the manifest and the report give them."""
    p = spec.pair
    g = p.gears
    return {"teeth": list(p.teeth), "module_mm": p.module, "pressure_angle_deg": r6(math.degrees(p.pressure_angle)),
            "shaft_angle_deg": r6(math.degrees(p.shaft_angle)),
            "tooth_form": "spherical involute (exact; straight teeth through the apex)",
            "pitch_angle_deg": [r6(math.degrees(t.pitch_angle)) for t in g],
            "pitch_diameter_mm": [r6(2 * t.pitch_radius) for t in g],
            "tip_diameter_mm": [r6(2 * t.blank(0.0)[2, 0]) for t in g],
            "base_angle_deg": [r6(math.degrees(t.base_angle)) for t in g],
            "cone_distance_mm": r6(p.cone_distance), "face_width_mm": g[0].face_width,
            "contact_ratio": r6(p.contact_ratio()), "ratio": f"{p.teeth[1]}/{p.teeth[0]}",
            "apex_height_mm": r6(spec.z_apex)}


def design_summary(kind: str, spec: BevelSpec, kit: BevelKit) -> dict:
    return {"name": spec.name, "kind": kind, "printer": spec.printer.name,
            "material": spec.material, "density_g_cm3": float(round(spec.density * 1000, 6)), **design_numbers(spec)}


def kit_files(spec: BevelSpec, kit: BevelKit, raw: LoadedDesign) -> dict[str, bytes]:
    data = raw.document()
    data["printer"] = "printer.yaml"
    return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}
