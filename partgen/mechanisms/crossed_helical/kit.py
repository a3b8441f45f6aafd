"""A crossed helical pair as parts: a base carrying gear 1's upright post and two pillow blocks
that hold gear 2's pin along the crossed axis, the two helical gears and the pin; poses over gear
1's turn θ (rad) (the frame: resolve.py); the throated wheel's cut; what the kit folder holds (the
manifest's design, design.yaml, printer.yaml) and the pair's efficiency and self-locking.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from shapely.geometry import box

from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.parts import Bore, Part
from ...core.protocol import SpecKit
from ...core.quantise import r6
from ...core.transforms import pose, pose_z
from ...design.crossed_helical import ThreadSpec, efficiency, friction_angle
from ...design.gearing import GearSpec, ToothSystem
from ...errors import DesignError
from ...geometry.helical import centred_helical, centred_thread, cylinder_along
from ...geometry.measure import refuse_oversize
from ...geometry.outline import circle
from ...geometry.printing import least_support_flip
from ...geometry.solid import extrude, union
from .resolve import CrossedSpec, is_worm

__all__ = ["CrossedKit", "build_crossed", "build", "refuse", "cutter_spec", "generating_phases", "design_numbers",
           "locking", "locking_text", "design_summary", "kit_files"]


@dataclass(frozen=True)
class CrossedKit(SpecKit):
    """The base (post and pin blocks), gear 1, gear 2 and gear 2's pin; poses over gear 1's turn θ."""

    spec: CrossedSpec
    parts: tuple[Part, ...]


    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        s = self.spec
        pin = pose(s.pair.frame2(), (s.centre_distance, 0.0, s.z_c))
        return {"base": np.eye(4), "gear1": pose_z(0.0, 0.0, s.z_c, float(theta)),
                "gear2": s.pose2(float(s.angle2(theta))), "pin2": pin}


GENERATING_STEPS = 12  # the throated wheel's cut: cutter poses per tooth pitch of the worm (a scallop between two
# is ~(p_t2 sin α_t / 12)² / (8 ρ), under a µm on the shipped worm's wheel)


def cutter_spec(s: CrossedSpec) -> ThreadSpec:
    """The worm as the throated wheel's cutter (a hob): its thread thickened by the wheel's thinning (j_2
    along the wheel's pitch circle is j_2 cos β_2 along the normal, j_2 cos β_2 / cos β_1 along the worm's
    transverse pitch circle), its tip the wheel's dedendum above its pitch cylinder (the wheel's root
    clearance), its root as the worm's."""
    p = s.pair
    T1, T2 = p.systems
    j = s.gear2.system.backlash_per_gear * math.cos(p.helix[1]) / math.cos(p.helix[0])
    system = ToothSystem(T1.module, T1.pressure_angle, T2.dedendum_coeff * T2.module / T1.module, T1.dedendum_coeff,
                         T1.cutter_tip_coeff, -j, 0.0, s.tol)
    return ThreadSpec(p.teeth[0], system)


def generating_phases(s: CrossedSpec) -> np.ndarray:
    """Gear 1's turns (rad) at which the cutter is posed: every 1/GENERATING_STEPS of its tooth pitch while
    the wheel's tooth 0 (± a pitch and a half) is within the worm's length (± half of it and a module)."""
    z1, z2 = s.pair.teeth
    reach = math.asin(min(1.0, (s.face_width[0] / 2 + s.pair.normal_module) / s.gear2.root_radius)) + 3 * math.pi / z2
    step = 2 * math.pi / z1 / GENERATING_STEPS
    lo, hi = (s.phase2 - reach) * z2 / z1, (s.phase2 + reach) * z2 / z1  # angle2(θ) = phase2 − θ z1/z2 within ±reach
    return step * np.arange(math.floor(lo / step), math.ceil(hi / step) + 1)


def _throated(s: CrossedSpec):
    """Gear 2 cut by the worm's envelope (``geometry.throated``): the cutter posed in the wheel's frame as the
    kit poses them, worm turned θ, wheel angle2(θ)."""
    from ...geometry.throated import throated_wheel

    c = cutter_spec(s)
    b1, b2 = s.face_width
    cutter = centred_thread(c.section(s.tol), c.tip_radius, b1, s.pair.twist(0, b1), 0.5 * c.root_radius, s.tol)
    # at θ the cutter's pose in the wheel's frame is rot_z(−angle2(θ)) · pose2(0)⁻¹ · P1(θ); P1(θ) repeats
    # every tooth pitch of the worm, so the phases fall into GENERATING_STEPS orientations
    pitch1 = 2 * math.pi / s.pair.teeth[0]
    phases = generating_phases(s)
    steps = np.round(phases / (pitch1 / GENERATING_STEPS)).astype(int) % GENERATING_STEPS
    inv0 = np.linalg.inv(s.pose2(0.0))
    orientations = [(inv0 @ pose_z(0.0, 0.0, s.z_c, float(j * pitch1 / GENERATING_STEPS)),
                     [float(s.angle2(t)) for t in phases[steps == j]]) for j in range(GENERATING_STEPS)]
    return throated_wheel(cutter, orientations, s.gear2.teeth, s.gear2.tip_radius, s.centre_distance, c.tip_radius, b2,
                          s.shaft_radius[1] + s.running / 2, s.tol)


def build_crossed(s: CrossedSpec, progress=None) -> CrossedKit:
    say = progress or (lambda name: None)
    pair, tol = s.pair, s.tol
    b1, b2 = s.face_width
    r1s, r2s = s.shaft_radius
    ftol = max(tol, 0.005)
    # gear 1: the helical teeth and a collar down to the axial gap above the base
    say("gear1")
    if isinstance(s.gear1, ThreadSpec):
        g1 = centred_thread(s.gear1.section(tol), s.gear1.tip_radius, b1, pair.twist(0, b1), r1s + s.running / 2, tol)
    else:
        g1 = centred_helical(s.gear1, b1, pair.twist(0, b1), r1s + s.running / 2, tol)
    low = s.gap - s.z_c  # the collar's bottom, local
    if low < -b1 / 2 - 1e-9:
        collar = extrude(circle(s.hub_radius, ftol).difference(circle(r1s + s.running / 2, ftol, hole=True)),
                         -b1 / 2 - low + 0.01, low)  # 0.01 mm into the teeth: one solid
        g1 = union([g1, collar])
    say("gear2")
    if s.throated:
        g2 = _throated(s)
    else:
        g2 = centred_helical(s.gear2, b2, pair.twist(1, b2), r2s + s.running / 2, tol)
    # the base: a plate under everything, gear 1's post, two blocks round gear 2's pin
    say("base")
    reach = r2s + s.press / 2 + s.block_wall
    top1 = s.z_c + b1 / 2 + 1.0
    post = extrude(circle(r1s, ftol), top1 + 0.01, -0.01)
    blocks, holes = [], []
    u = pair.axis2
    for c in s.block_centres():  # the blocks' thickness runs along y
        height = c[2] + reach
        w = box(c[0] - reach, c[1] - s.block_thickness / 2, c[0] + reach, c[1] + s.block_thickness / 2)
        blocks.append(extrude(w, height + 0.01, -0.01))
    hole_T = pose(pair.frame2(), (s.centre_distance, 0.0, s.z_c))
    holes.append(cylinder_along(r2s + s.press / 2, s.pin_length + 20.0, ftol, hole_T))
    xs = [-s.gear1.tip_radius - s.margin, s.centre_distance + reach + s.margin]
    ys = [min(c[1] for c in s.block_centres()) - s.block_thickness / 2 - s.margin,
          max(c[1] for c in s.block_centres()) + s.block_thickness / 2 + s.margin]
    ys = [min(ys[0], -s.gear1.tip_radius - s.margin), max(ys[1], s.gear1.tip_radius + s.margin)]
    plate = extrude(box(xs[0], ys[0], xs[1], ys[1]), s.base_thickness, -s.base_thickness)
    base = union([plate, post, *blocks]) - union(holes)
    say("pin2")
    pin = extrude(circle(r2s, ftol), s.pin_length, -s.pin_length / 2)
    parts = [Part("base", "base", base, bores=tuple(
                 Bore(f"block{k + 1}", tuple(float(v) for v in (c - (s.block_thickness / 2 + 0.5) * u)),
                      tuple(float(v) for v in u), 2 * r2s, s.block_thickness + 1.0)
                 for k, c in enumerate(s.block_centres()))),
             Part("gear1", "gear", g1, gear=s.gear1 if isinstance(s.gear1, GearSpec) else None,
                  bores=(Bore("post", (0.0, 0.0, low), (0.0, 0.0, 1.0), 2 * r1s, b1 / 2 - low),)),
             Part("gear2", "gear", g2, gear=s.gear2,
                  bores=(Bore("pin", (0.0, 0.0, -b2 / 2), (0.0, 0.0, 1.0), 2 * r2s, b2),)),
             Part("pin2", "axle", pin)]
    # each lies on the flat face that needs the least support (gear 1: its teeth down, the collar up)
    return CrossedKit(s, tuple(replace(p, print_flip=least_support_flip(p.solid, s.printer.overhang_deg))
                               for p in parts))


def build(spec: CrossedSpec, progress=None) -> CrossedKit:
    try:
        return build_crossed(spec, progress)
    except ValueError as e:
        raise DesignError(str(e), "shafts.diameter_mm") from None


def refuse(spec: CrossedSpec, kit: CrossedKit) -> None:
    refuse_oversize(kit.parts, spec.printer.envelope, "gears.normal_module_mm")


def design_numbers(spec: CrossedSpec) -> dict:
    """The pair's numbers, as the manifest and the report give them."""
    p = spec.pair
    return {"teeth": list(p.teeth), "normal_module_mm": p.normal_module,
            "normal_pressure_angle_deg": r6(math.degrees(p.normal_pressure_angle)),
            "helix_angle_deg": [r6(math.degrees(b)) for b in p.helix], "hand": "right",
            "shaft_angle_deg": r6(math.degrees(p.shaft_angle)),
            "transverse_module_mm": [r6(s.module) for s in p.systems],
            "transverse_pressure_angle_deg": [r6(math.degrees(s.pressure_angle)) for s in p.systems],
            "pitch_diameter_mm": [r6(2 * p.pitch_radius(i)) for i in range(2)],
            "tip_diameter_mm": [r6(2 * spec.gear1.tip_radius), r6(2 * spec.gear2.tip_radius)],
            "centre_distance_mm": r6(spec.centre_distance), "ratio": f"{p.teeth[1]}/{p.teeth[0]}",
            "face_width_mm": list(spec.face_width), "shaft_height_mm": r6(spec.z_c),
            "sliding_per_rolling": r6(p.sliding_speed() / p.pitch_radius(0)), "throated_wheel": spec.throated,
            **locking(spec)}


def locking(spec: CrossedSpec) -> dict:
    """Efficiency both ways and the self-locking answer for the stated friction (gear 1 a worm:
    lead angle γ = 90° − β_1 against the friction angle φ' = atan(μ / cos α_n))."""
    p, mu = spec.pair, spec.friction
    fwd, back = efficiency(p, mu), efficiency(p, mu, backwards=True)
    out = {"worm": "ZI (involute helicoid)" if is_worm(p) else None,
           "friction_coefficient": mu, "friction_angle_deg": round(math.degrees(friction_angle(p, mu)), 4),
           "efficiency_gear1_driving": round(fwd, 4), "efficiency_gear2_driving": round(back, 4),
           "self_locking": back <= 0}
    if is_worm(p):
        out["lead_angle_deg"] = round(90.0 - math.degrees(abs(p.helix[0])), 6)
    return out


def locking_text(spec: CrossedSpec) -> str:
    """The efficiency and self-locking in words (the bill, the check's text, the report)."""
    k = locking(spec)
    lead = (f"worm {k['worm']}, lead angle {k['lead_angle_deg']:g}°; " if k["worm"] else "")
    return (f"{lead}friction μ {k['friction_coefficient']:g} (stated, checks.friction_coefficient): friction angle "
            f"{k['friction_angle_deg']:.2f}°, efficiency {100 * k['efficiency_gear1_driving']:.0f} % driving gear 1, "
            + ("self-locking: gear 2 cannot drive gear 1" if k["self_locking"] else
               f"{100 * k['efficiency_gear2_driving']:.0f} % driving gear 2: not self-locking"))


def design_summary(kind: str, spec: CrossedSpec, kit: CrossedKit) -> dict:
    return {"name": spec.name, "kind": kind, "printer": spec.printer.name,
            "material": spec.material, "density_g_cm3": float(round(spec.density * 1000, 6)), **design_numbers(spec)}


def kit_files(spec: CrossedSpec, kit: CrossedKit, raw: LoadedDesign) -> dict[str, bytes]:
    data = raw.document()
    data["printer"] = "printer.yaml"
    return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}
