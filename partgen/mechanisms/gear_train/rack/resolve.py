"""The rack and pinion's resolver: the validated design -> ``RackSpec`` (the pinion, the rack's teeth
and length, the travel, the fits, the pinion's bore and hub), and the design findings."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ....checks.settings import CheckSettings
from ....config.loader import LoadedDesign, printer_limits
from ....core.findings import Finding
from ....core.printer import PrinterLimits
from ....design.gearing import GearSpec, ToothSystem, make_gear
from ....design.rules import ToothSystemError, check_generable, gear_rules
from ....errors import ConfigError
from ..common.hubs import HARDWARE_KEY, Hub, HubError, plan_hub, sizes_within
from ..common.kit import FEATURE_TOL
from ..common.resolve import check_settings, gear_findings, shaft_fits

__all__ = ["RackSpec", "resolve_rack", "findings"]


@dataclass(frozen=True)
class RackSpec:
    name: str
    system: ToothSystem
    face_width: float
    pinion: GearSpec
    rack_teeth: int
    back: float
    travel: float
    shaft_radius: float
    running: float
    press: float
    extension: float
    gap: float
    plate_thickness: float
    margin: float
    checks: CheckSettings
    density: float
    material: str
    printer: PrinterLimits
    tol: float
    hub: Hub | None = None  # the pinion's bore (None: a D-flat, as given no shafts.bores)
    base: float = 0.0  # the pinion's set-screw hub under its gear: the pinion and the rack raised by it (mm)
    hub_radius: float = 0.0  # that hub's radius (mm; 0: none)

    @property
    def gear_z(self) -> float:
        """The pinion's and the rack's bottom face (z, mm)."""
        return self.gap + self.base

    @property
    def pitch_line(self) -> float:
        """y of the rack's pitch line, mm (the pinion's centre at the origin)."""
        return -(self.pinion.pitch_radius + self.pinion.profile_shift * self.system.module)

    @property
    def rack_offset(self) -> float:
        """x of the rack at rest so that a space of it lies under the pinion's tooth 0 (pointing down)."""
        return 0.0 if self.rack_teeth % 2 == 0 else math.pi * self.system.module / 2

    def rack_x(self, theta: float) -> float:
        return self.rack_offset + self.pinion.pitch_radius * theta

    @property
    def thetas_range(self) -> tuple[float, float]:
        h = self.travel / 2 / self.pinion.pitch_radius
        return -h, h

    @property
    def rack_length(self) -> float:
        return self.rack_teeth * math.pi * self.system.module


def resolve_rack(loaded: LoadedDesign) -> RackSpec:
    d, p = loaded.design, loaded.printer
    g, r, fr = d.gears, d.rack, d.frame
    m = g.module_mm
    system = ToothSystem(module=m, pressure_angle=math.radians(g.pressure_angle_deg), addendum_coeff=g.addendum_coeff,
                         dedendum_coeff=g.dedendum_coeff, backlash_per_gear=g.backlash_per_gear_mm,
                         profile_shift=None if g.profile_shift == "auto" else float(g.profile_shift),
                         chord_tolerance=g.chord_tolerance_mm)
    pinion = make_gear(r.pinion_teeth, system)
    try:
        check_generable(pinion)
    except ToothSystemError as e:
        raise ConfigError(loaded.path, "gears.profile_shift" if e.field == "profile_shift" else "rack.pinion_teeth",
                          e.problem) from None
    # the rack keeps every tooth in mesh over the travel: the travel plus the mesh zone either side
    teeth = math.ceil((r.travel_mm + 8 * m) / (math.pi * m)) + 1
    length = teeth * math.pi * m
    if length > math.hypot(*p.build_envelope_mm[:2]):
        raise ConfigError(loaded.path, "rack.travel_mm", f"the rack comes out {length:.0f} mm long: longer than the "
                          "printer's bed even on its diagonal")
    running, press = shaft_fits(loaded)
    r_shaft = d.shafts.diameter_mm / 2
    wall = printer_limits(p).min_wall
    if r_shaft + press / 2 + wall >= pinion.root_radius:
        raise ConfigError(loaded.path, "shafts.diameter_mm", f"a {pinion.teeth}-tooth pinion (root Ø"
                          f"{2 * pinion.root_radius:.2f} mm) leaves no {wall:g} mm wall round its D-bore")
    if 2 * r_shaft + running < p.min_hole_diameter_mm - 1e-6:
        raise ConfigError(loaded.path, "shafts.diameter_mm", f"the shaft's running hole (Ø{2 * r_shaft + running:.2f} mm)"
                          f" is below the printer's smallest running hole ({p.min_hole_diameter_mm:g} mm)")
    hub, base, hub_r = _hub(loaded, pinion, r_shaft, running, press, wall)
    checks = check_settings(d.checks)
    return RackSpec(d.name, system, g.face_width_mm, pinion, teeth, r.back_mm, r.travel_mm, r_shaft, running, press,
                    d.shafts.extension_mm, fr.axial_gap_mm, fr.plate_thickness_mm, fr.margin_mm, checks,
                    d.material.density_g_cm3 / 1000.0, d.material.name, printer_limits(p), g.chord_tolerance_mm, hub,
                    base, hub_r)


def _hub(loaded: LoadedDesign, pinion: GearSpec, r_shaft: float, running: float, press: float, wall: float):
    """The pinion's bore from ``shafts.bores`` ([pinion]) and, for a set screw, its hub under the gear
    (height: the pinion and the rack raised by it; radius). None when ``shafts.bores`` is absent."""
    d, g = loaded.design, loaded.design.gears
    if not d.shafts.bores:
        return None, 0.0, 0.0
    gap, f = d.frame.axial_gap_mm, g.face_width_mm
    slack = max(g.chord_tolerance_mm, 0.005) + FEATURE_TOL
    try:
        h = plan_hub(d.shafts.bores[0], r_shaft, running, press, wall, gap, d.shafts.nut, d.shafts.set_screw, slack)
    except HubError as e:
        raise ConfigError(loaded.path, f"shafts.{e.key}", e.problem) from None
    fits = lambda what, radius: sizes_within(h.kind, what, radius, r_shaft, running, press, wall, gap, slack)  # noqa: E731
    key = f"shafts.{HARDWARE_KEY[h.kind]}"
    what = {"keyway": "its keyway", "hex": f"its {h.nut} nut trap", "d_flat": "its D-bore",
            "set_screw": f"its {h.nut} set screw's nut slot"}[h.kind]
    root = pinion.root_radius
    if h.kind != "d_flat" and h.room >= root:
        raise ConfigError(loaded.path, key, f"a {pinion.teeth}-tooth pinion (root Ø{2 * root:.2f} mm) leaves less than "
                          f"the printer's {wall:g} mm wall around {what} (needs a root Ø{2 * h.room:.2f} mm): a thinner "
                          f"shaft or smaller hardware{fits('room', root)}, or more pinion teeth (rack.pinion_teeth)")
    if h.kind == "hex" and h.pocket_depth + wall > f:
        raise ConfigError(loaded.path, "shafts.nut", f"the pinion's {h.nut} nut trap ({h.pocket_depth:.2f} mm deep) and a "
                          f"{wall:g} mm wall need a face {h.pocket_depth + wall:.2f} mm wide: a smaller nut"
                          f"{fits('pocket_depth', f - wall)} or a wider face (gears.face_width_mm)")
    if h.kind != "set_screw":
        return h, 0.0, 0.0
    # a hub under the pinion (the rack and its strip are raised with it): within the pinion's root
    hub_r = min(max(h.bore + max(3 * wall, 2.5), h.hub_need), root)
    if hub_r < h.hub_need - 1e-9:
        raise ConfigError(loaded.path, "shafts.set_screw", f"the pinion's hub has room for Ø{2 * root:.2f} mm (its root "
                          f"circle), its {h.nut} set screw needs Ø{2 * h.hub_need:.2f} mm: a smaller screw"
                          f"{fits('hub_need', root)}, a thinner shaft or more pinion teeth (rack.pinion_teeth)")
    return h, h.height, hub_r


def findings(spec: RackSpec) -> list[Finding]:
    """What `build` warns about (the rules `check` fails on) and notes (an undercut pinion)."""
    return gear_findings(gear_rules(spec), [("pinion", spec.pinion)])
