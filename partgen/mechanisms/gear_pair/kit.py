"""A spur gear pair as parts: a base plate carrying two posts at the pair's centre distance, and two
gears turning on them; what the kit folder holds (the manifest's design, design.yaml, printer.yaml)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.parts import Bore, Part
from ...core.quantise import r6
from ...core.protocol import SpecKit
from ...core.transforms import pose_z
from ...errors import DesignError
from ...geometry.measure import refuse_oversize
from ...geometry.outline import circle, hull_of_discs
from ...geometry.parts import DFit, base_plate, bored_gear, shaft
from ...geometry.printing import least_support_flip
from .resolve import PairSpec

__all__ = ["PairKit", "build_pair", "build", "refuse", "design_summary", "kit_files"]


@dataclass(frozen=True)
class PairKit(SpecKit):
    """The base with its two posts and the two gears; poses over gear 1's turn θ (rad)."""

    spec: PairSpec
    parts: tuple[Part, ...]


    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        s = self.spec
        z = s.axial_gap
        return {"base": np.eye(4), "gear1": pose_z(0.0, 0.0, z, float(theta)),
                "gear2": pose_z(s.centre_distance, 0.0, z, float(s.output_angle(theta)))}


def build_pair(s: PairSpec, progress=None) -> PairKit:
    say = progress or (lambda name: None)
    top = s.axial_gap + s.face_width + 1.0  # the posts stand 1 mm proud of the gears
    post = DFit(s.axle_radius, 0.0)
    posts = [shaft(post, [("round", 0.0, top)], s.tol, (x, 0.0)) for x in (0.0, s.centre_distance)]
    outline = hull_of_discs([((0.0, 0.0), s.gear1.tip_radius + s.base_margin),
                             ((s.centre_distance, 0.0), s.gear2.tip_radius + s.base_margin)], s.tol)
    say("base")
    base = base_plate(outline, s.base_thickness, [], posts)
    parts = [Part("base", "base", base)]
    for name, gear in (("gear1", s.gear1), ("gear2", s.gear2)):
        say(name)
        parts.append(Part(name, "gear", bored_gear(gear, s.face_width, circle(s.bore_of(name), s.tol, hole=True)),
                          gear=gear, bores=(Bore("post", (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 2 * s.axle_radius,
                                                 s.face_width),)))
    # each lies on its larger flat face unless the other needs less support
    parts = [replace(p, print_flip=least_support_flip(p.solid, s.printer.overhang_deg)) for p in parts]
    return PairKit(s, tuple(parts))


def build(spec: PairSpec, progress=None) -> PairKit:
    try:
        return build_pair(spec, progress)
    except ValueError as e:
        raise DesignError(str(e), "axles.diameter_mm") from None


def refuse(spec: PairSpec, kit: PairKit) -> None:
    refuse_oversize(kit.parts, spec.printer.envelope, "gears.module_mm")


def design_summary(kind: str, spec: PairSpec, kit: PairKit) -> dict:
    g1, g2 = spec.gear1, spec.gear2
    return {"name": spec.name, "kind": kind, "module_mm": g1.system.module,
            "pressure_angle_deg": r6(math.degrees(g1.system.pressure_angle)), "teeth": [g1.teeth, g2.teeth],
            "ratio": f"{g2.teeth}/{g1.teeth}", "profile_shift": [r6(g1.profile_shift), r6(g2.profile_shift)],
            "centre_distance_mm": r6(spec.centre_distance), "face_width_mm": spec.face_width,
            "axle_diameter_mm": 2 * spec.axle_radius, "bore_diameter_mm": r6(2 * spec.bore_radius),
            "printer": spec.printer.name, "material": spec.material, "density_g_cm3": r6(spec.density * 1000)}


def kit_files(spec: PairSpec, kit: PairKit, raw: LoadedDesign) -> dict[str, bytes]:
    data = raw.document()
    data["printer"] = "printer.yaml"
    return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}
