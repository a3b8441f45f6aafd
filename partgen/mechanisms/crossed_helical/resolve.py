"""The crossed helical pair's resolver: the validated YAML (``config.loader.LoadedDesign``) →
``CrossedSpec`` (deg → rad, diametral clearances, mm, g/mm³), and the spec's frame.

World frame (``design.crossed_helical``): the base's top at z = 0, gear 1 about z through the
origin, its face centred at z_c; gear 2's axis ``u2`` through (a, 0, z_c). z_c is the lowest that
keeps gear 2's tip circle ``frame.axial_gap_mm`` above the base and gear 1 on a collar at least
that gap above it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...config.loader import LoadedDesign, printer_fit, printer_limits
from ...core.printer import PrinterLimits
from ...core.transforms import pose, rot_z
from ...design.crossed_helical import CrossedPair, ThreadSpec, crossed_pair
from ...design.gearing import GearSpec, ToothSystem
from ...design.rules import ToothSystemError, check_generable
from ...errors import ConfigError

__all__ = ["CrossedSpec", "resolve_crossed", "gear_spec", "is_worm", "WORM_PRESSURE_ANGLE"]


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
