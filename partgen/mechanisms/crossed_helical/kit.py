"""A crossed helical pair as parts: a base carrying gear 1's upright post and two pillow blocks
that hold gear 2's pin along the crossed axis, the two helical gears and the pin; the resolver from
the validated YAML (deg → rad, diametral clearances); poses over gear 1's turn θ (rad).

World frame (``design.crossed_helical``): the base's top at z = 0, gear 1 about z through the
origin, its face centred at z_c; gear 2's axis ``u2`` through (a, 0, z_c). z_c is the lowest that
keeps gear 2's tip circle ``frame.axial_gap_mm`` above the base and gear 1 on a collar at least
that gap above it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from shapely.geometry import box

from ...config.loader import LoadedDesign, printer_fit, printer_limits
from ...core.parts import Bore, Part
from ...core.printer import PrinterLimits
from ...core.protocol import SpecKit
from ...core.transforms import pose, pose_z, rot_z
from ...design.crossed_helical import CrossedPair, ThreadSpec, crossed_pair
from ...design.gearing import GearSpec, ToothSystem
from ...design.rules import ToothSystemError, check_generable
from ...errors import ConfigError
from ...geometry.helical import centred_helical, centred_thread, cylinder_along
from ...geometry.outline import circle
from ...geometry.printing import least_support_flip
from ...geometry.solid import extrude, union

__all__ = ["CrossedSpec", "CrossedKit", "resolve_crossed", "build_crossed", "gear_spec"]


WORM_PRESSURE_ANGLE = math.radians(40.0)  # transverse, at and above it gear 1 is a worm's thread


def is_worm(pair: CrossedPair, i: int = 0) -> bool:
    """Gear i is a worm (its section the ZI thread's, not the rack generator's): under 4 teeth
    (starts), or a transverse pressure angle of 40° or more."""
    return pair.teeth[i] < 4 or pair.systems[i].pressure_angle >= WORM_PRESSURE_ANGLE


def gear_spec(pair: CrossedPair, i: int, backlash: float, tol: float) -> GearSpec | ThreadSpec:
    """Gear i's transverse GearSpec (unshifted: the pair runs at r_1 + r_2), or a worm's ThreadSpec."""
    T = pair.systems[i]
    system = ToothSystem(T.module, T.pressure_angle, T.addendum_coeff, T.dedendum_coeff, T.cutter_tip_coeff, backlash,
                         0.0, tol)
    return ThreadSpec(pair.teeth[i], system) if is_worm(pair, i) else GearSpec(pair.teeth[i], system, 0.0)


@dataclass(frozen=True)
class CrossedSpec:
    """A crossed helical pair ready to build (mm, rad, g/mm³)."""

    name: str
    pair: CrossedPair
    gear1: GearSpec | ThreadSpec  # a ThreadSpec: gear 1 is a ZI worm
    gear2: GearSpec
    face_width: tuple[float, float]
    shaft_radius: tuple[float, float]  # gear 1's post, gear 2's pin
    running: float  # diametral clearances: a gear's bore over its post or pin
    press: float  # the pin in its blocks
    gap: float
    base_thickness: float
    margin: float
    block_wall: float
    block_thickness: float
    z_c: float
    samples: int
    friction: float
    plate_margin: float
    density: float
    material: str
    printer: PrinterLimits
    tol: float
    throated: bool = False  # gear 2 cut by gear 1's (a worm's) envelope

    @property
    def centre_distance(self) -> float:
        return self.pair.centre_distance

    @property
    def phase2(self) -> float:
        """Gear 2's turn at θ = 0 (rad, about its local z) that puts a tooth space of it on gear 1's
        tooth 0 at the pitch point (both centred there in their mid-planes): the pitch point is on
        gear 2's local +x, where its tooth 0 would be, so half a pitch."""
        return math.pi / self.gear2.teeth

    def angle2(self, theta) -> np.ndarray:
        """Gear 2's nominal turn (rad, about its local z) when gear 1 has turned ``theta``."""
        return self.phase2 + np.asarray(theta) * self.pair.speed2()

    @property
    def hub_radius(self) -> float:
        """Gear 1's collar: a bore's diameter plus a block wall round the post, inside its root circle by a module."""
        bore = self.shaft_radius[0] + self.running / 2
        return min(self.gear1.root_radius - self.pair.normal_module, 2 * bore + self.block_wall)

    def pose2(self, angle: float) -> np.ndarray:
        """(4, 4) world-from-local pose of gear 2 turned ``angle`` about its axis."""
        return pose(self.pair.frame2() @ rot_z(angle), (self.centre_distance, 0.0, self.z_c))

    @property
    def block_distance(self) -> float:
        """How far along gear 2's axis each block's middle is from gear 2's: the blocks' faces are
        planes y = const, and gear 2 (a disc of its tip radius and face width, square to u2) reaches
        b/2 sin Σ + r_a |cos Σ| along y; each face stands the axial gap beyond that."""
        return _block_distance(self.pair.shaft_angle, self.face_width[1], self.gear2.tip_radius, self.gap,
                               self.block_thickness)

    def block_centres(self) -> list[np.ndarray]:
        """Where gear 2's pin passes through the middle of each block (world)."""
        d = self.block_distance
        c = np.array([self.centre_distance, 0.0, self.z_c])
        return [c - d * self.pair.axis2, c + d * self.pair.axis2]

    @property
    def pin_length(self) -> float:
        """Through both blocks (their thickness along the slanted axis) and 1 mm proud of each."""
        return 2 * (self.block_distance + self.block_thickness / (2 * math.sin(self.pair.shaft_angle))) + 2.0


def _block_distance(sigma: float, face: float, tip: float, gap: float, thickness: float) -> float:
    return (face / 2 * math.sin(sigma) + tip * abs(math.cos(sigma)) + gap + thickness / 2) / math.sin(sigma)


def resolve_crossed(loaded: LoadedDesign) -> CrossedSpec:
    d, p = loaded.design, loaded.printer
    g = d.gears
    try:
        pair = crossed_pair(tuple(g.teeth), g.normal_module_mm, math.radians(g.normal_pressure_angle_deg),
                            math.radians(g.helix_angle_deg[0]), math.radians(d.shaft_angle_deg), g.addendum_coeff,
                            g.dedendum_coeff)
    except ValueError as e:
        raise ConfigError(loaded.path, "gears.helix_angle_deg", f"with the shafts at {d.shaft_angle_deg:g}°: {e}") from None
    if abs(math.degrees(pair.helix[1]) - g.helix_angle_deg[1]) > 1e-6:
        raise ConfigError(loaded.path, "gears.helix_angle_deg", f"the helix angles {g.helix_angle_deg[0]:g}° + "
                          f"{g.helix_angle_deg[1]:g}° must add up to the shaft angle {d.shaft_angle_deg:g}° "
                          f"(gear 2: {math.degrees(pair.helix[1]):g}°)")
    tol = g.chord_tolerance_mm
    gears = [gear_spec(pair, i, g.backlash_per_gear_mm, tol) for i in range(2)]
    if g.throated and abs(d.shaft_angle_deg - 90.0) > 1e-9:
        raise ConfigError(loaded.path, "gears.throated", f"a throated wheel is made for shafts at 90° (here "
                          f"{d.shaft_angle_deg:g}°)")
    if g.throated and not is_worm(pair):
        raise ConfigError(loaded.path, "gears.throated", f"only a worm's wheel is throated: gear 1 has {pair.teeth[0]} "
                          f"teeth at a transverse pressure angle of {math.degrees(pair.systems[0].pressure_angle):.1f}° "
                          "(a worm has 1-3 starts, or 40° or more)")
    for i, gear in enumerate(gears):
        if isinstance(gear, ThreadSpec):
            try:
                gear.section(tol)
            except ValueError as e:
                raise ConfigError(loaded.path, "gears.helix_angle_deg", f"gear 1's worm thread cannot be made: {e}") from None
            continue
        try:
            check_generable(gear)
        except ToothSystemError as e:
            raise ConfigError(loaded.path, f"gears.teeth[{i}]", e.problem) from None
        if gear.undercut:
            raise ConfigError(loaded.path, f"gears.teeth[{i}]", f"a {gear.teeth}-tooth gear at "
                              f"{math.degrees(pair.helix[i]):g}° helix is undercut (transverse pressure angle "
                              f"{math.degrees(gear.system.pressure_angle):.2f}°): more teeth or a larger helix angle")
    running = printer_fit(loaded, d.shafts.running_clearance_diametral_mm, "running",
                          "shafts.running_clearance_diametral_mm")
    press = printer_fit(loaded, d.shafts.press_fit_clearance_diametral_mm, "press_fit",
                        "shafts.press_fit_clearance_diametral_mm")
    radii = tuple(x / 2 for x in d.shafts.diameter_mm)
    wall = printer_limits(p).min_wall
    for i, (gear, r) in enumerate(zip(gears, radii)):
        if r + running / 2 + wall >= gear.root_radius - (pair.normal_module if i == 0 else 0.0):
            raise ConfigError(loaded.path, f"shafts.diameter_mm[{i}]", f"a Ø{2 * r:g} mm shaft leaves gear {i + 1}'s "
                              f"root circle (Ø{2 * gear.root_radius:.2f} mm) less than the printer's {wall:g} mm wall "
                              "round its bore: a thinner shaft, more teeth or a larger module")
        if 2 * (r + running / 2) < p.min_hole_diameter_mm:
            raise ConfigError(loaded.path, f"shafts.diameter_mm[{i}]", f"the bore (Ø{2 * r + running:.2f} mm) is below "
                              f"the printer's smallest reliable hole ({p.min_hole_diameter_mm:g} mm)")
    gap, b1, b2 = d.frame.axial_gap_mm, g.face_width_mm[0], g.face_width_mm[1]
    s = pair.shaft_angle
    # gear 2's lowest point: its tip circle tilted with its axis, and its face's corners
    drop2 = gears[1].tip_radius * math.sin(s) + b2 / 2 * abs(math.cos(s))
    block_reach = radii[1] + press / 2 + d.frame.block_wall_mm  # the block's material under the pin
    # the lower block's hole keeps a block wall of material above the base
    lower = _block_distance(s, b2, gears[1].tip_radius, gap, d.frame.block_thickness_mm) * abs(math.cos(s))
    z_c = max(gap + b1 / 2, gap + drop2, block_reach + gap + lower)
    spec = CrossedSpec(d.name, pair, gears[0], gears[1], (b1, b2), radii, running, press, gap, d.frame.base_thickness_mm,
                       d.frame.margin_mm, d.frame.block_wall_mm, d.frame.block_thickness_mm, z_c, d.checks.samples,
                       d.checks.friction_coefficient, d.checks.plate_margin_mm, d.material.density_g_cm3 / 1000.0, d.material.name, printer_limits(p),
                       tol, g.throated)
    # the blocks must clear gear 1's tip cylinder
    for c in spec.block_centres():
        near = math.hypot(max(c[0] - block_reach, 0.0), max(abs(c[1]) - d.frame.block_thickness_mm / 2, 0.0))
        if near < gears[0].tip_radius + gap:
            raise ConfigError(loaded.path, "frame.block_thickness_mm", f"gear 2's pin blocks come within {near:.2f} mm "
                              f"of gear 1's axis, inside its tip circle (Ø{2 * gears[0].tip_radius:.2f} mm) plus the "
                              f"{gap:g} mm gap: a larger gear 2, a wider face on gear 2 or thinner block walls")
    return spec


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
