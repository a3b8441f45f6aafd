"""The spur gear pair's resolver: the validated YAML (``config.loader.LoadedDesign``) → ``PairSpec``
(deg → rad, diametral clearance, mm, g/mm³)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...config.loader import LoadedDesign, printer_fit, printer_limits
from ...config.schema import AUTO_PLAY_START_MM
from ...core.printer import PrinterLimits
from ...design.gearing import GearSpec, ToothSystem, centre_distance, make_gear
from ...design.rules import ToothSystemError, check_generable
from ...errors import ConfigError

__all__ = ["PairSpec", "resolve_pair"]


@dataclass(frozen=True)
class PairSpec:
    """A gear pair ready to build (mm, rad, g/mm³)."""

    name: str
    gear1: GearSpec  # the driver (input)
    gear2: GearSpec  # the driven gear (output)
    centre_distance: float
    face_width: float
    axle_radius: float
    bore_radius: float
    axial_gap: float
    base_thickness: float
    base_margin: float
    samples: int
    plate_margin: float
    density: float
    material: str
    printer: PrinterLimits
    tol: float
    bore_radii: tuple[float, float] | None = None  # each gear's own bore (its own clearance); None: bore_radius

    def bore_of(self, gear: str) -> float:
        """The bore radius of ``gear`` ("gear1", "gear2"), mm."""
        return self.bore_radii[("gear1", "gear2").index(gear)] if self.bore_radii else self.bore_radius

    @property
    def phase2(self) -> float:
        """Gear 2's turn at rest (rad) so a tooth space of it faces gear 1's tooth 0 on the line of centres."""
        return 0.0 if self.gear2.teeth % 2 else math.pi / self.gear2.teeth

    def output_angle(self, theta) -> np.ndarray:
        """Gear 2's nominal angle (rad) when gear 1 has turned ``theta`` (rad)."""
        return self.phase2 - np.asarray(theta) * self.gear1.teeth / self.gear2.teeth


def resolve_pair(loaded: LoadedDesign) -> PairSpec:
    d, p = loaded.design, loaded.printer
    g = d.gears
    backlash, fit = _own(loaded, "gears.backlash_per_gear_mm", g.backlash_per_gear_mm), \
        _own(loaded, "axles.clearance_diametral_mm", d.axles.clearance_diametral_mm)
    system = ToothSystem(module=g.module_mm, pressure_angle=math.radians(g.pressure_angle_deg),
                         backlash_per_gear=AUTO_PLAY_START_MM if backlash[0] == "auto" else backlash[0],
                         profile_shift=None if g.profile_shift == "auto" else float(g.profile_shift),
                         chord_tolerance=g.chord_tolerance_mm)
    g1, g2 = (make_gear(z, system if own is None else replace(system, backlash_per_gear=own))
              for z, own in zip(g.teeth, backlash[1:]))
    for i, gear in enumerate((g1, g2)):
        try:
            check_generable(gear)
        except ToothSystemError as e:
            raise ConfigError(loaded.path, "gears.profile_shift" if e.field == "profile_shift" else f"gears.teeth[{i}]",
                              e.problem) from None
    bore = d.axles.diameter_mm / 2 + printer_fit(loaded, fit[0], "running", "axles.clearance_diametral_mm") / 2
    bores = tuple(bore if own is None else d.axles.diameter_mm / 2 + own / 2 for own in fit[1:])
    for i, gear in enumerate((g1, g2)):
        if bores[i] + p.min_wall >= gear.root_radius:
            raise ConfigError(loaded.path, f"gears.teeth[{i}]", f"a {gear.teeth}-tooth gear's root circle "
                              f"(Ø{2 * gear.root_radius:.2f} mm) leaves less than the printer's {p.min_wall:g} mm wall "
                              f"around its Ø{2 * bores[i]:.2f} mm bore: more teeth, a larger module or a thinner axle")
    if 2 * min(bores) < p.min_hole_diameter_mm:
        raise ConfigError(loaded.path, "axles.diameter_mm", f"the bore (Ø{2 * min(bores):.2f} mm) is below the printer's "
                          f"smallest reliable hole ({p.min_hole_diameter_mm:g} mm)")
    a = centre_distance(g1, g2)
    span = a + g1.tip_radius + g2.tip_radius + 2 * d.base.margin_mm
    if span > math.hypot(*p.build_envelope_mm[:2]):
        raise ConfigError(loaded.path, "gears.module_mm", f"the base comes out {span:.0f} mm long: no plate that long "
                          "fits the printer")
    return PairSpec(d.name, g1, g2, a, g.face_width_mm, d.axles.diameter_mm / 2, bore, d.axles.axial_gap_mm,
                    d.base.thickness_mm, d.base.margin_mm, d.checks.samples, d.checks.plate_margin_mm,
                    d.material.density_g_cm3 / 1000.0, d.material.name, printer_limits(p), g.chord_tolerance_mm,
                    bores if fit[1:] != (None, None) else None)


def _own(loaded: LoadedDesign, key: str, value) -> tuple:
    """(the default, gear1's own or None, gear2's own or None) of a play that may be a mapping per gear."""
    if not isinstance(value, dict):
        return value, None, None
    for name in value:
        if name not in ("default", "gear1", "gear2"):
            raise ConfigError(loaded.path, f"{key}.{name}", f"the pair has no gear {name!r}: it has gear1, gear2")
    return value["default"], value.get("gear1"), value.get("gear2")
