"""The planetary set's resolver: the validated design -> ``PlanetarySpec`` (the teeth, the planets'
angles and phases, the fits, the sun's and the carrier's bores and hubs), and the design findings."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ....checks.settings import CheckSettings
from ....config.loader import LoadedDesign, printer_limits
from ....core.findings import Finding
from ....core.printer import PrinterLimits
from ....design.gear_train import mesh_phase
from ....design.gearing import GearSpec, ToothSystem, centre_distance
from ....design.planetary import (MIN_TOOTH_DIFFERENCE, PlanetaryTeeth, assembly_whole, internal_centre_distance,
                                  planet_angles, planet_clearance, planetary_teeth)
from ....design.rules import gear_rules
from ....errors import ConfigError, DesignError
from ..common.hubs import DIN562_NUTS, HARDWARE_KEY, Hub, HubError, plan_hub, sizes_within
from ..common.kit import FEATURE_TOL
from ..common.resolve import check_settings, gear_findings, shaft_fits

__all__ = ["PlanetarySpec", "resolve_planetary", "findings"]


@dataclass(frozen=True)
class PlanetarySpec:
    """A planetary set ready to build (mm, rad, g/mm³). ``space``: the ring's space gear."""

    name: str
    system: ToothSystem
    face_width: float
    teeth: PlanetaryTeeth
    sun: GearSpec
    planet: GearSpec
    ring: GearSpec  # the ring's own numbers: teeth, profile shift (x_E), for the manifest
    space: GearSpec
    centre_distance: float
    angles: tuple[float, ...]  # planet carrier angles at rest
    planet_phases: tuple[float, ...]
    ring_phase: float
    target_ratio: float | None
    shaft_radius: float
    pin_radius: float
    running: float
    press: float
    extension: float
    gap: float
    plate_thickness: float
    margin: float
    spacer_radius: float
    rim: float
    checks: CheckSettings
    density: float
    material: str
    printer: PrinterLimits
    tol: float
    hubs: tuple[Hub, Hub] | None = None  # the input (sun) and output (carrier) bores; None: D-flats
    base: float = 0.0  # the sun's set-screw hub under its gear: every gear raised by it (mm)
    hub_radius: float = 0.0  # the sun's hub (mm; 0: none)
    screw_turn: float = 0.0  # the carrier's set screw: its hole's direction (rad), between two pins

    @property
    def ratio(self) -> float:
        return self.teeth.ratio

    @property
    def bores(self) -> tuple[str, str]:
        return (self.hubs[0].kind, self.hubs[1].kind) if self.hubs else ("d_flat", "d_flat")

    @property
    def gear_z(self) -> float:
        """The gears' bottom face (z, mm)."""
        return self.gap + self.base

    @property
    def track_width(self) -> float:
        """Half the width of the planets' track on the bottom plate (mm)."""
        return min(self.pin_radius + self.running / 2 + 2 * self.printer.min_wall,
                   self.planet.pitch_radius - self.system.module - self.checks.min_clearance)

    @property
    def carrier_z(self) -> float:
        return 2 * self.gap + self.face_width + self.base

    @property
    def top_z(self) -> float:
        return self.carrier_z + self.plate_thickness + self.gap

    @property
    def rim_radius(self) -> float:
        return self.space.tip_radius + self.rim

    @property
    def output_turn(self) -> float:
        """The input (sun) angle over one turn of the carrier, rad."""
        return 2 * math.pi * self.ratio

    def carrier(self, theta: float) -> float:
        return theta / self.ratio

    def planet_angle(self, i: int, theta: float) -> float:
        """Planet i's own angle (rad, world) at sun angle θ: the carrier's turn plus its turn on the carrier."""
        c = self.carrier(theta)
        return self.planet_phases[i] + c - self.teeth.sun / self.teeth.planet * (theta - c)

    def planet_centre(self, i: int, theta: float) -> tuple[float, float]:
        g = self.angles[i] + self.carrier(theta)
        return (self.centre_distance * math.cos(g), self.centre_distance * math.sin(g))


def resolve_planetary(loaded: LoadedDesign) -> PlanetarySpec:
    d, p = loaded.design, loaded.printer
    g, pl, fr = d.gears, d.planetary, d.frame
    alpha = math.radians(g.pressure_angle_deg)
    m = g.module_mm
    system = ToothSystem(module=m, pressure_angle=alpha, addendum_coeff=g.addendum_coeff,
                         dedendum_coeff=g.dedendum_coeff, backlash_per_gear=g.backlash_per_gear_mm,
                         profile_shift=0.0, chord_tolerance=g.chord_tolerance_mm)
    n, equal = pl.planets, pl.spacing == "equal"
    if pl.teeth is not None:
        zs, zp, zr = pl.teeth
        if zr != zs + 2 * zp:
            raise ConfigError(loaded.path, "planetary.teeth[2]", f"the ring must have z_sun + 2 z_planet = {zs + 2 * zp} "
                              "teeth for the planets to mesh sun and ring on one radius (unshifted teeth)")
        if zr - zp < MIN_TOOTH_DIFFERENCE:
            raise ConfigError(loaded.path, "planetary.teeth[1]", f"ring minus planet is {zr - zp} teeth, under "
                              f"{MIN_TOOTH_DIFFERENCE}: tip and trochoidal interference of the internal mesh; use a "
                              f"planet of at most {zr - MIN_TOOTH_DIFFERENCE} teeth with a ring to match")
        if equal and not assembly_whole(zs, zr, n):
            ok = [k for k in range(2, 9) if assembly_whole(zs, zr, k)]
            near = [zs + dz for dz in range(-n, n + 1) if dz and assembly_whole(zs + dz, zr + dz, n)][:2]
            raise ConfigError(loaded.path, "planetary.planets", f"(z_sun + z_ring)/N = {zs + zr}/{n} is not whole: "
                              f"{n} equally spaced planets cannot all mesh; {ok or 'no count'} planets would, or suns of "
                              f"{near} teeth (ring to match), or planetary.spacing: unequal")
        teeth = PlanetaryTeeth(zs, zp, zr, n)
    else:
        try:
            teeth = planetary_teeth(pl.ratio, n, g.min_teeth, g.max_teeth, m, d.checks.min_clearance_mm + 1.0, equal,
                                    pl.exact, g.addendum_coeff)
        except DesignError as e:
            raise ConfigError(loaded.path, e.key_path, e.problem) from None
    zs, zp, zr = teeth.sun, teeth.planet, teeth.ring
    sun, planet = GearSpec(zs, system, 0.0), GearSpec(zp, system, 0.0)
    # the ring's space gear: its teeth are the ring's spaces, reaching its root; its thinning widens them
    space_sys = replace(system, addendum_coeff=g.dedendum_coeff, dedendum_coeff=g.addendum_coeff,
                        backlash_per_gear=-g.backlash_per_gear_mm)
    space = GearSpec(zr, space_sys, 0.0)
    a = centre_distance(sun, planet)
    a_ring = internal_centre_distance(zp, zr, m, alpha, 0.0, 0.0)
    assert abs(a - a_ring) < 1e-9
    angles = tuple(planet_angles(zs, zr, n, equal))
    if planet_clearance(list(angles), a, planet.tip_radius) < d.checks.min_clearance_mm:
        raise ConfigError(loaded.path, "planetary.planets", f"{n} planets of {zp} teeth on a {a:.2f} mm radius touch "
                          "each other: fewer planets, or a larger sun")
    phases = tuple(mesh_phase(0.0, zs, zp, gm) for gm in angles)
    ring_phase = mesh_phase(phases[0], zp, zr, angles[0], internal=True)
    running, press = shaft_fits(loaded)
    r_shaft = d.shafts.diameter_mm / 2
    r_pin = (pl.pin_diameter_mm or d.shafts.diameter_mm) / 2
    wall = printer_limits(p).min_wall
    if 2 * r_pin + running < p.min_hole_diameter_mm - 1e-6:
        raise ConfigError(loaded.path, "planetary.pin_diameter_mm", f"the planets' bores (Ø{2 * r_pin + running:.2f} mm) "
                          f"run on their pins and are below the printer's smallest running hole ({p.min_hole_diameter_mm:g} mm)")
    if r_pin + running / 2 + wall >= planet.root_radius:
        raise ConfigError(loaded.path, "planetary.pin_diameter_mm", f"a {zp}-tooth planet (root Ø{2 * planet.root_radius:.2f}"
                          f" mm) leaves no {wall:g} mm wall round its pin's bore: a thinner pin or larger planets")
    if r_shaft + press / 2 + wall >= sun.root_radius:
        raise ConfigError(loaded.path, "shafts.diameter_mm", f"a {zs}-tooth sun (root Ø{2 * sun.root_radius:.2f} mm) "
                          f"leaves no {wall:g} mm wall round its D-bore: a thinner shaft or a larger sun")
    hubs, base, hub_r, turn = _hubs(loaded, sun, planet, a, angles, r_shaft, r_pin, running, press, wall)
    checks = check_settings(d.checks)
    return PlanetarySpec(d.name, system, g.face_width_mm, teeth, sun, planet, GearSpec(zr, system, 0.0), space, a,
                         angles, phases, ring_phase, pl.ratio, r_shaft, r_pin, running, press, d.shafts.extension_mm,
                         fr.axial_gap_mm, fr.plate_thickness_mm, fr.margin_mm, fr.spacer_diameter_mm / 2, pl.rim_mm,
                         checks, d.material.density_g_cm3 / 1000.0, d.material.name, printer_limits(p),
                         g.chord_tolerance_mm, hubs, base, hub_r, turn)


def _hubs(loaded: LoadedDesign, sun: GearSpec, planet: GearSpec, a: float, angles, r_shaft: float, r_pin: float,
          running: float, press: float, wall: float):
    """The input (sun) and output (carrier) bores from ``shafts.bores``, and where they need it the sun's
    hub under its gear (its height, the gears raised by it, and radius) and the carrier's set-screw
    direction. None (D-flats, as built before bores were given) when ``shafts.bores`` is absent."""
    d, fr, g = loaded.design, loaded.design.frame, loaded.design.gears
    if not d.shafts.bores:
        return None, 0.0, 0.0, 0.0
    gap, t, f = fr.axial_gap_mm, fr.plate_thickness_mm, g.face_width_mm
    slack = max(g.chord_tolerance_mm, 0.005) + FEATURE_TOL
    try:
        hubs = tuple(plan_hub(b, r_shaft, running, press, wall, gap, d.shafts.nut, d.shafts.set_screw, slack)
                     for b in d.shafts.bores)
    except HubError as e:
        raise ConfigError(loaded.path, f"shafts.{e.key}", e.problem) from None
    h_in, h_out = hubs
    fits = lambda h, what, radius: sizes_within(h.kind, what, radius, r_shaft, running, press, wall, gap, slack)  # noqa: E731
    key = lambda h: f"shafts.{HARDWARE_KEY[h.kind]}"  # noqa: E731
    what = lambda h: {"keyway": "its keyway", "hex": f"its {h.nut} nut trap", "d_flat": "its D-bore",  # noqa: E731
                      "set_screw": f"its {h.nut} set screw's nut slot"}[h.kind]
    # the sun: every feature within its root circle and a printer wall
    if h_in.kind != "d_flat" and h_in.room >= sun.root_radius:
        raise ConfigError(loaded.path, key(h_in), f"a {sun.teeth}-tooth sun (root Ø{2 * sun.root_radius:.2f} mm) leaves "
                          f"less than the printer's {wall:g} mm wall around {what(h_in)} (needs a root Ø"
                          f"{2 * h_in.room:.2f} mm): a thinner shaft or smaller hardware{fits(h_in, 'room', sun.root_radius)}"
                          ", or a larger sun")
    if h_in.kind == "hex" and h_in.pocket_depth + wall > f:
        raise ConfigError(loaded.path, "shafts.nut", f"the sun's {h_in.nut} nut trap ({h_in.pocket_depth:.2f} mm deep) and "
                          f"a {wall:g} mm wall need a face {h_in.pocket_depth + wall:.2f} mm wide: a smaller nut"
                          f"{fits(h_in, 'pocket_depth', f - wall)} or a wider face (gears.face_width_mm)")
    base, hub_r = 0.0, 0.0
    if h_in.kind == "set_screw":  # a hub under the sun, inside the planets' track, the gears raised over it
        base = h_in.height
        track = min(r_pin + running / 2 + 2 * wall, planet.pitch_radius - g.module_mm - d.checks.min_clearance_mm)
        limit = min(sun.root_radius, a - track - d.checks.min_clearance_mm)
        hub_r = min(max(h_in.bore + max(3 * wall, 2.5), h_in.hub_need), limit)
        if hub_r < h_in.hub_need - 1e-9:
            raise ConfigError(loaded.path, "shafts.set_screw", f"the sun's hub has room for Ø{2 * limit:.2f} mm inside "
                              f"the planets' track, its {h_in.nut} set screw needs Ø{2 * h_in.hub_need:.2f} mm: a smaller "
                              f"screw{fits(h_in, 'hub_need', limit)}, a thinner shaft or a larger sun")
    # the carrier: its plate holds the feature (a nut trap or a set screw's hole and slot within its thickness)
    plate_r = a + r_pin + running / 2 + 2 * wall
    if h_out.room >= plate_r:
        raise ConfigError(loaded.path, key(h_out), f"the carrier's plate (Ø{2 * plate_r:.2f} mm) leaves less than the "
                          f"printer's {wall:g} mm wall around {what(h_out)}: a thinner shaft or smaller hardware"
                          f"{fits(h_out, 'room', plate_r)}")
    turn = 0.0
    if h_out.kind == "hex" and h_out.pocket_depth + wall > t:
        raise ConfigError(loaded.path, "shafts.nut", f"the carrier's {h_out.nut} nut trap ({h_out.pocket_depth:.2f} mm "
                          f"deep) and a {wall:g} mm wall need a plate {h_out.pocket_depth + wall:.2f} mm thick: a smaller "
                          f"nut{fits(h_out, 'pocket_depth', t - wall)} or frame.plate_thickness_mm "
                          f"≥ {h_out.pocket_depth + wall:.2f}")
    if h_out.kind == "set_screw":
        def plate_need(h: Hub) -> float:  # the hole's wall and the slot's top under the plate's top face
            return max(h.height, h.screw_z + h.pocket_s / 2 + wall)
        need = plate_need(h_out)
        if need > t + 1e-9:
            ok = [m for m in DIN562_NUTS if plate_need(plan_hub("set_screw", r_shaft, running, press, wall, gap, None, m,
                                                                slack)) <= t + 1e-9]
            raise ConfigError(loaded.path, "frame.plate_thickness_mm", f"the carrier's {h_out.nut} set screw (its hole "
                              f"and its nut's slot in the plate, with a {wall:g} mm wall) needs a plate at least "
                              f"{need:.2f} mm thick, got {t:g}: a thicker plate or a smaller screw"
                              + (f" ({', '.join(ok)} would fit)" if ok else " (no size fits this plate)"))
        # the hole runs out to the plate's rim through the widest space between two pins
        gs = sorted(angles)
        k = max(range(len(gs)), key=lambda i: (gs[(i + 1) % len(gs)] - gs[i]) % (2 * math.pi) or 2 * math.pi)
        span = (gs[(k + 1) % len(gs)] - gs[k]) % (2 * math.pi) or 2 * math.pi
        turn = gs[k] + span / 2
        miss = a * math.sin(span / 2) - r_pin - (h_out.thread + running) / 2
        if miss < wall:
            raise ConfigError(loaded.path, "shafts.set_screw", f"the carrier's {h_out.nut} set-screw hole passes its pins "
                              f"{max(miss, 0):.2f} mm apart, under the printer's {wall:g} mm wall: fewer planets or a "
                              "smaller screw")
    return hubs, base, hub_r, turn


def findings(spec: PlanetarySpec) -> list[Finding]:
    """What `build` warns about (the rules `check` fails on) and notes (undercut gears)."""
    return gear_findings(gear_rules(spec), [("sun", spec.sun), ("planet", spec.planet)])
