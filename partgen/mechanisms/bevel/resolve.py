"""The straight bevel pair's resolver: the validated YAML (``config.loader.LoadedDesign``) →
``BevelSpec`` (deg → rad, diametral clearances, mm, g/mm³), and the spec's frame.

World frame (``design.bevel``): the base's top at z = 0, gear 1 about z through the origin, the
common apex at (0, 0, z_A); gear 2's axis u_2 = (−sin Σ, 0, cos Σ) through the apex, its body
beyond it along −u_2 (+x at Σ = 90°; up and out above 90°, its block then on a leg sloping down
square to u_2, behind gear 2's back). z_A is the lowest that keeps gear 2 (teeth and hub)
``frame.axial_gap_mm`` above the base, its block's hole a block wall above it, and gear 1 on a
hub at least a millimetre long that stands the axial gap above the base. The mesh's thrust pushes
each gear away from the apex: gear 1 onto nothing but its post (its hub's end is the gap above the
base, see the docs), gear 2 against its block.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...config.loader import LoadedDesign, printer_fit, printer_limits
from ...config.schema import AUTO_PLAY_START_MM
from ...core.printer import PrinterLimits
from ...core.transforms import pose, rot_z
from ...design.bevel import BevelPair, BevelTooth, bevel_pair
from ...errors import ConfigError

__all__ = ["BevelSpec", "resolve_bevel"]


@dataclass(frozen=True)
class BevelSpec:
    """A straight bevel pair ready to build (mm, rad, g/mm³)."""

    name: str
    pair: BevelPair
    shaft_radius: tuple[float, float]  # gear 1's post, gear 2's pin
    running: float  # diametral clearances: a gear's bore over its post or pin
    press: float  # the pin in its block
    gap: float
    base_thickness: float
    margin: float
    hub_length: float
    block_wall: float
    block_thickness: float
    z_apex: float
    samples: int
    plate_margin: float
    density: float
    material: str
    printer: PrinterLimits
    tol: float

    @property
    def gear1(self) -> BevelTooth:
        return self.pair.gears[0]

    @property
    def gear2(self) -> BevelTooth:
        return self.pair.gears[1]

    @property
    def apex(self) -> np.ndarray:
        return np.array([0.0, 0.0, self.z_apex])

    @property
    def phase2(self) -> float:
        """Gear 2's turn at θ = 0 (rad, about its local z) that puts a tooth space of it on gear 1's
        tooth 0 on the pitch line (both local +x point at it): half a pitch."""
        return math.pi / self.gear2.teeth

    def angle2(self, theta) -> np.ndarray:
        """Gear 2's nominal turn (rad, about its local z) when gear 1 has turned ``theta``."""
        return self.phase2 + np.asarray(theta) * self.pair.speed2()

    def hub_radius(self, i: int) -> float:
        """Gear i's hub: its bore plus a block wall, inside its back face's root radius by a module."""
        g = self.pair.gears[i]
        return min(float(g.heel_root[0]) - g.module, self.shaft_radius[i] + self.running / 2 + self.block_wall)

    def hub_end(self, i: int) -> float:
        """Where gear i's hub ends along its local axis (a < its back face): gear 1's the gap above the
        base, gear 2's ``hub_length`` behind its back face."""
        if i == 0:
            return self.gap - self.z_apex
        return float(self.pair.gears[1].heel_root[1]) - self.hub_length

    def pose2(self, angle: float) -> np.ndarray:
        """(4, 4) world-from-local pose of gear 2 turned ``angle`` about its axis."""
        return pose(self.pair.frame2() @ rot_z(angle), self.apex)

    @property
    def pin_frame(self) -> np.ndarray:
        return pose(self.pair.frame2(), self.apex)

    @property
    def block_span(self) -> tuple[float, float]:
        """(far, near) local a of gear 2's block along its axis: the axial gap behind the hub's end."""
        near = self.hub_end(1) - self.gap
        return near - self.block_thickness, near

    @property
    def block_reach(self) -> float:
        """The block's half-width round the pin's axis."""
        return self.shaft_radius[1] + self.press / 2 + self.block_wall

    @property
    def leg_direction(self) -> np.ndarray:
        """The way gear 2's block reaches down to the base: straight down up to Σ = 90°; above it gear 2
        leans over gear 1, its body above its block's side of the base, and a plumb leg would pass
        through it, so the leg slopes down square to gear 2's axis (−z less its part along u_2): it
        stays behind gear 2's back, within the block's span along the axis."""
        u = self.pair.axis2
        if u[2] >= 0:
            return np.array([0.0, 0.0, -1.0])
        d = np.array([0.0, 0.0, -1.0]) + u[2] * u
        return d / np.linalg.norm(d)

    @property
    def pin_span(self) -> tuple[float, float]:
        """(start, end) local a of gear 2's pin: 1 mm proud of the block's far face to gear 2's toe face."""
        return self.block_span[0] - 1.0, float(self.gear2.toe_root[1])


def _profile(tooth: BevelTooth, hub_radius: float, hub_end: float) -> np.ndarray:
    """(n, 2) (ρ, a) of the gear's outline as a solid of revolution (the blank and the hub)."""
    b = tooth.blank()
    return np.vstack([b, [[0.0, hub_end], [hub_radius, hub_end]]])


def _lowest(profile: np.ndarray, axis: np.ndarray, apex_z: float) -> float:
    """The lowest world z of the solid of revolution of ``profile`` about ``axis`` through the apex."""
    uz = float(axis[2])
    side = math.sqrt(max(1 - uz * uz, 0.0))
    return apex_z + float((profile[:, 1] * uz - profile[:, 0] * side).min())


def _clear_of_apex(pair: BevelPair) -> bool:
    """Both gears' tip cones below 90° and their toes (the blank's nearest point) at least 1 mm from the apex."""
    return all(t.tip_cone < math.pi / 2 - 1e-3 and float(t.blank()[:, 1].max()) <= -1.0 for t in pair.gears)


def resolve_bevel(loaded: LoadedDesign) -> BevelSpec:
    d, p = loaded.design, loaded.printer
    g = d.gears
    backlash = AUTO_PLAY_START_MM if g.backlash_per_gear_mm == "auto" else g.backlash_per_gear_mm  # auto: its start
    pair = bevel_pair(tuple(g.teeth), g.module_mm, math.radians(g.pressure_angle_deg), math.radians(d.shaft_angle_deg),
                      g.face_width_mm, backlash, g.addendum_coeff, g.dedendum_coeff)
    tol = g.chord_tolerance_mm
    make = lambda sigma: bevel_pair(tuple(g.teeth), g.module_mm, math.radians(g.pressure_angle_deg), sigma,  # noqa: E731
                                    g.face_width_mm, backlash, g.addendum_coeff, g.dedendum_coeff)
    if not _clear_of_apex(pair):
        lo, hi = math.radians(30.0), pair.shaft_angle  # the steepest shaft angle that keeps both toes off the apex
        if _clear_of_apex(make(lo)):
            for _ in range(40):
                mid = (lo + hi) / 2
                lo, hi = (mid, hi) if _clear_of_apex(make(mid)) else (lo, mid)
        i = max((0, 1), key=lambda k: pair.gears[k].pitch_angle)
        raise ConfigError(loaded.path, "shaft_angle_deg", f"gear {i + 1}'s pitch cone is "
                          f"{math.degrees(pair.gears[i].pitch_angle):.1f}° (nearly a crown gear): its tip cone "
                          f"({math.degrees(pair.gears[i].tip_cone):.1f}°) brings its toe within 1 mm of the apex; for "
                          f"these teeth and face the shaft angle must be at most {math.floor(10 * math.degrees(lo)) / 10:g}°")
    for i, tooth in enumerate(pair.gears):
        try:
            tooth.section(tol)
        except ValueError as e:
            raise ConfigError(loaded.path, f"gears.teeth[{i}]", f"gear {i + 1}'s teeth cannot be made: {e}") from None
    for i in pair.interference():
        t = pair.gears[i]
        raise ConfigError(loaded.path, f"gears.teeth[{i}]", f"gear {i + 1} ({t.teeth} teeth, pitch cone "
                          f"{math.degrees(t.pitch_angle):.1f}°) would be undercut: its mate's tip reaches below its "
                          "spherical involute; more teeth")
    if pair.contact_ratio() < 1.1:
        raise ConfigError(loaded.path, "gears.teeth", f"a contact ratio of {pair.contact_ratio():.2f} (under 1.1): "
                          "more teeth or a larger addendum")
    running = printer_fit(loaded, d.shafts.running_clearance_diametral_mm, "running",
                          "shafts.running_clearance_diametral_mm")
    press = printer_fit(loaded, d.shafts.press_fit_clearance_diametral_mm, "press_fit",
                        "shafts.press_fit_clearance_diametral_mm")
    radii = tuple(x / 2 for x in d.shafts.diameter_mm)
    wall = printer_limits(p).min_wall
    for i, (tooth, r) in enumerate(zip(pair.gears, radii)):
        toe = float(tooth.toe_root[0])  # the smallest root radius: the toe's
        if r + running / 2 + wall >= toe:
            raise ConfigError(loaded.path, f"shafts.diameter_mm[{i}]", f"a Ø{2 * r:g} mm shaft leaves gear {i + 1}'s "
                              f"toe root (Ø{2 * toe:.2f} mm) less than the printer's {wall:g} mm wall round its bore: "
                              "a thinner shaft, more teeth, a larger module or a narrower face")
        if 2 * (r + running / 2) < p.min_hole_diameter_mm:
            raise ConfigError(loaded.path, f"shafts.diameter_mm[{i}]", f"the bore (Ø{2 * r + running:.2f} mm) is below "
                              f"the printer's smallest reliable hole ({p.min_hole_diameter_mm:g} mm)")
    gap, f = d.frame.axial_gap_mm, d.frame
    spec = BevelSpec(d.name, pair, radii, running, press, gap, f.base_thickness_mm, f.margin_mm, f.hub_length_mm,
                     f.block_wall_mm, f.block_thickness_mm, 0.0, d.checks.samples, d.checks.plate_margin_mm,
                     d.material.density_g_cm3 / 1000.0, d.material.name, printer_limits(p), tol)
    # the apex's height: gear 1's hub at least 1 mm long; gear 2 and its block's hole above the base
    u2 = pair.axis2
    prof2 = _profile(pair.gears[1], spec.hub_radius(1), spec.hub_end(1))
    far, near = spec.block_span
    hole_low = min(a * u2[2] for a in (far, near)) - spec.block_reach * math.sqrt(1 - u2[2] ** 2)
    z_apex = max(gap + 1.0 - float(pair.gears[0].heel_root[1]), gap - _lowest(prof2, u2, 0.0),
                 spec.block_wall - hole_low)
    return replace(spec, z_apex=float(z_apex))

