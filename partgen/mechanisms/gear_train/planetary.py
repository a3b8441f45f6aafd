"""A planetary set in a frame: the ring gear standing on the bottom plate (fixed), the sun pressed on
the input shaft (D-flat, turning in the bottom plate, reached from below), N planets running on the
pins of a carrier that hangs above them, its output shaft turning in the top plate. Resolver, kit,
check and trace.

Stacking (z up, the bottom plate's top at 0; g axial gap, f face width, t plate thickness): the
gears span [g, g + f]; the sun rests on a thrust ring round the input hole, the planets on a track
(an annulus on the radius of their centres), both [0, g]; the ring stands [0, g + f]; the carrier
plate spans [Z_c, Z_c + t], Z_c = g + f + g, its pins reach down through the planets; the top plate
[Z_t, Z_t + t], Z_t = Z_c + t + g, on spacers outside the ring.

Bores (``shafts.bores: [input, output]``, hubs.py): the sun held on its shaft by a D-flat, a keyway, a
nut trap in its bottom face on a bought threaded rod, or a set screw through a hub under it (then the
gears, the ring's teeth, the planets' track and the carrier are raised by the hub's height b: the
gears span [g + b, g + b + f]); the carrier by a D-flat, a keyway, a nut trap in its plate's bottom
face or a set screw through its plate, out to its rim between two pins.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
import shapely
from shapely.geometry import box

from ...checks.sequence import run_shared
from ...config.loader import LoadedDesign, printer_limits
from ...core.findings import Finding, Result
from ...core.parts import Contact, Part
from ...core.printer import PrinterLimits
from ...core.protocol import ParamsKit
from ...core.transforms import pose_z
from ...design import rules
from ...design.gear_train import mesh_phase
from ...design.gearing import GearSpec, ToothSystem, centre_distance
from ...checks.settings import CheckSettings
from ...design.planetary import (MIN_TOOTH_DIFFERENCE, PlanetaryTeeth, assembly_whole, internal_centre_distance,
                                 internal_contact_ratio, planet_angles, planet_clearance, planetary_teeth,
                                 ring_contact_on_pinion, ring_tip_radius)
from ...errors import ConfigError, DesignError
from ...geometry.gear import gear_body, ring_body
from ...geometry.measure import section
from ...geometry.outline import circle
from ...geometry.parts import DFit, shaft as shaft_solid
from ...geometry.solid import prisms, slab, union
from .common.hubs import DIN562_NUTS, HARDWARE_KEY, Hub, HubError, plan_hub, sizes_within
from .common.kit import (FEATURE_TOL, hub_contacts, hub_cutters, hub_hole, hubbed_gear, screw_and_nut,
                  turning_shaft)

__all__ = ["PlanetarySpec", "PlanetaryKit", "resolve_planetary", "build_planetary", "check_planetary",
           "turn_planetary"]


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


def _fit(loaded: LoadedDesign, which: str, value) -> float:
    if value != "printer":
        return float(value)
    if loaded.printer.fits is None:
        raise ConfigError(loaded.path, f"shafts.{which}", "the printer profile gives no measured fits: give a number")
    f = loaded.printer.fits
    return f.running_clearance_diametral_mm if which.startswith("running") else f.press_fit_clearance_diametral_mm


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
    running = _fit(loaded, "running_clearance_diametral_mm", d.shafts.running_clearance_diametral_mm)
    press = _fit(loaded, "press_fit_clearance_diametral_mm", d.shafts.press_fit_clearance_diametral_mm)
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
    c = d.checks
    checks = CheckSettings(c.samples, c.interference_tolerance_mm3, c.min_clearance_mm, c.min_contact_ratio,
                           c.min_tip_width_roads, c.plate_margin_mm)
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


@dataclass(frozen=True)
class _SunPlanetView(ParamsKit):
    """The sun and the planets as checks.meshing reads a kit (the ring mesh is checked here)."""

    kit: PlanetaryKit

    @property
    def params(self):
        return self.kit.params

    @property
    def parts(self):
        return tuple(p for p in self.kit.parts if p.name == "sun" or p.name.startswith("planet"))

    @property
    def contacts(self):
        return tuple(Contact("sun", f"planet{i}", "mesh") for i in range(len(self.params.angles)))

    def part(self, name):
        return self.kit.part(name)

    def poses(self, theta=0.0):
        s = self.params  # the sun's and the planets' poses as PlanetaryKit.poses has them, lifted to the gears
        lift = pose_z(0.0, 0.0, s.gear_z)
        out = {"sun": pose_z(angle=float(theta)) @ lift}
        for i in range(len(s.angles)):
            out[f"planet{i}"] = pose_z(*s.planet_centre(i, theta), 0.0, s.planet_angle(i, theta)) @ lift
        return out


def _place(geom, angle: float, centre) -> object:
    c, sn = math.cos(angle), math.sin(angle)
    R = np.array([[c, -sn], [sn, c]])
    return shapely.transform(geom, lambda p: p @ R.T + np.asarray(centre))


def _sections(kit: PlanetaryKit) -> dict:
    s = kit.params
    z = s.gear_z + s.face_width / 2
    ring = section(kit.part("frame_bottom").solid, z)
    r_out = s.space.tip_radius + 0.5 * s.system.module
    return {"sun": section(kit.part("sun").solid, z), "planet": section(kit.part("planet0").solid, z),
            "ring": shapely.intersection(ring, circle(r_out, 0.05))}


def _turner(geom, centre):
    """``geom`` turned about ``centre`` by an angle (rad): shapely.affinity.rotate's arithmetic, term for
    term (the same floats), without its per-call set-up — a bisection turns one piece many times."""
    x, y = shapely.get_coordinates(geom).T
    x0, y0 = float(centre[0]), float(centre[1])

    def turned(angle: float):
        cosp, sinp = math.cos(angle), math.sin(angle)
        if abs(cosp) < 2.5e-16:
            cosp = 0.0
        if abs(sinp) < 2.5e-16:
            sinp = 0.0
        xoff, yoff = x0 - x0 * cosp + y0 * sinp, y0 - x0 * sinp - y0 * cosp
        xy = np.stack([cosp * x + -sinp * y + xoff, sinp * x + cosp * y + yoff]).T
        return shapely.transform(geom, lambda _: xy)
    return turned


GUESS_SPAN = 5e-4  # rad: a bisection starts within this of a guess (the last angle's contact) when it brackets


def _contact(fixed, piece, centre, sense: float, reach: float, tol: float, guess: float | None = None) -> float:
    """How far (rad, ≥ 0) ``piece`` turns about ``centre`` in the ``sense`` ±1 before it touches ``fixed``
    (to ``tol``); ``guess``: where it likely is — the bisection starts within GUESS_SPAN of it when
    that brackets the contact (free at the low end, touching at the high end), else on [0, reach]."""
    shapely.prepare(fixed)  # indexed once: every step of the bisection tests it
    turn = _turner(piece, centre)

    def area(d: float) -> float:
        q = turn(sense * d)
        return fixed.intersection(q).area if fixed.intersects(q) else 0.0
    if area(0.0) > 1e-9:
        return 0.0
    lo, hi = 0.0, reach
    if guess is not None and GUESS_SPAN < guess < reach - GUESS_SPAN:
        a, b = guess - GUESS_SPAN, guess + GUESS_SPAN
        if area(b) > 1e-9:
            lo, hi = (a, b) if area(a) <= 1e-9 else (0.0, a)
        else:
            lo = b
    while hi - lo > tol:
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if area(mid) > 1e-9 else (mid, hi)
    return lo


def turn_planetary(kit: PlanetaryKit, thetas: np.ndarray, tol: float = 1e-7, sections=None) -> dict:
    """The carrier's angle against the sun's from the printed sections, in the carrier's frame (where
    sun, planet and ring turn about fixed axes: the sun drives the planet, the planet the ring): each
    planet turned until it touches the sun, then the ring until it touches the planet; the carrier is
    held by the planet that bears first (the least lag). ``drive``: the sun driving a loaded carrier
    forward; ``coast``: the other flanks. Also the overlap (mm²) of sun/planet and planet/ring
    sections at the nominal angles (every planet, whole outlines: tip and trochoidal interference
    included). Returns {"nominal", "drive", "coast"} carrier angles (n,) and "overlap_mm2" (n, 2N)."""
    s = kit.params
    secs = sections or _sections(kit)
    zp, zr = s.teeth.planet, s.teeth.ring
    n = len(thetas)
    N = len(s.angles)
    nominal = np.array([s.carrier(float(t)) for t in thetas])
    out = {"nominal": nominal, "drive": np.empty(n), "coast": np.empty(n), "overlap_mm2": np.zeros((n, 2 * N))}
    reach_p, reach_r = math.pi / zp, math.pi / zr
    h = 3.5 * s.system.module  # the teeth in mesh lie within this of a pitch point
    rr = s.space.pitch_radius
    # what may turn into a window within a bisection's reach: a point ρ from its axis moves ρ × reach
    grow_p = min(2 * h, 1.01 * reach_p * s.planet.tip_radius + 0.1)
    grow_r = min(2 * h, 1.01 * reach_r * (s.space.tip_radius + 0.5 * s.system.module) + 0.1)
    windows = []  # per planet: its centre, the window round the sun's pitch point and the ring's, the ring's grown
    for gm in s.angles:
        u = np.array([math.cos(gm), math.sin(gm)])
        w2 = box(*(rr * u - h), *(rr * u + h))
        windows.append(((s.centre_distance * u[0], s.centre_distance * u[1]),
                        box(*(s.sun.pitch_radius * u - h), *(s.sun.pitch_radius * u + h)), w2, w2.buffer(grow_r)))
    # what both senses share at each angle: the sun's flanks in each window, each planet at its
    # nominal angle and the part of it that meets the sun
    shared = []
    for k, th in enumerate(thetas):
        c = nominal[k]
        sun = _place(secs["sun"], th - c, (0.0, 0.0))
        ring0 = _place(secs["ring"], s.ring_phase - c, (0.0, 0.0))
        shapely.prepare(sun)  # indexed once per angle: each planet is tested against it
        shapely.prepare(ring0)
        row = []
        for i, (pc, w1, w2, _) in enumerate(windows):
            phi = s.planet_angle(i, float(th)) - c  # nominal, carrier frame
            planet = _place(secs["planet"], phi, pc)
            # whole outlines: tip and trochoidal interference anywhere
            out["overlap_mm2"][k, i] = sun.intersection(planet).area if sun.intersects(planet) else 0.0
            out["overlap_mm2"][k, N + i] = ring0.intersection(planet).area if ring0.intersects(planet) else 0.0
            fixed = shapely.intersection(sun, w1)
            shapely.prepare(fixed)
            row.append((phi, fixed, shapely.intersection(planet, w1.buffer(grow_p))))
        shared.append(row)
    for key, sense in (("drive", 1.0), ("coast", -1.0)):
        # in the carrier frame the sun turns positive, the planets and the ring negative; driven, each
        # lags: it is found turned from its nominal angle against its motion (positive) until it touches
        last: dict = {}  # (planet, sun or ring) -> the contact at the last angle: the next one's guess
        for k, th in enumerate(thetas):
            c = nominal[k]
            rings = []
            for i, (pc, w1, w2, w2_grown) in enumerate(windows):
                phi, fixed, piece = shared[k][i]
                last[i, 0] = _contact(fixed, piece, pc, sense, reach_p, tol, last.get((i, 0)))
                phi_act = phi + sense * last[i, 0]
                planet_act = shapely.intersection(_place(secs["planet"], phi_act, pc), w2)
                ring_nom = s.ring_phase - c + (zp / zr) * (phi_act - phi)
                ring = shapely.intersection(_place(secs["ring"], ring_nom, (0.0, 0.0)), w2_grown)
                last[i, 1] = _contact(planet_act, ring, (0.0, 0.0), sense, reach_r, tol, last.get((i, 1)))
                rings.append(ring_nom + sense * last[i, 1])
            # the carrier is held by the planet that bears first: the ring's least lag
            out[key][k] = s.ring_phase - (min(rings) if sense > 0 else max(rings))
    return out


def check_planetary(kit: PlanetaryKit, samples: int | None = None, progress=None) -> Result:
    s = kit.params
    res = Result()
    n = samples or s.checks.samples
    thetas = np.linspace(0.0, s.output_turn, n, endpoint=False)
    zs, zp, zr, N = s.teeth.sun, s.teeth.planet, s.teeth.ring, s.teeth.planets
    m, alpha = s.system.module, s.system.pressure_angle
    # the internal mesh's rules (the external sun/planet mesh: checks.meshing below)
    a = s.centre_distance
    need = rules.TIP_ROOT_COEFF * m
    r_ai = ring_tip_radius(zr, m, 0.0, s.system.addendum_coeff)
    r_inv = rules.form_radius(s.space)  # the ring's involute ends here, its tip corners are the cutter's fillets
    internal = {"teeth": [zp, zr], "tooth_difference": zr - zp, "centre_distance_mm": round(a, 6),
                "ring_involute_radius_mm": round(r_inv, 4),
                "contact_ratio": round(internal_contact_ratio(zp, zr, m, alpha, 0.0, 0.0, a, s.system.addendum_coeff,
                                                              r_inv), 4),
                "tip_root_mm": {"planet->ring": round(s.space.tip_radius - (a + s.planet.tip_radius), 4),
                                "ring->planet": round((r_ai - a) - s.planet.root_radius, 4)},
                "assembly": f"({zs} + {zr})/{N} = {(zs + zr) / N:g}"}
    for k, v in internal["tip_root_mm"].items():
        if v < need:
            res.add(Finding("mesh", "fail", f"planet/ring: tip clears root by {v:.3f} mm ({k})", ("planet0", "frame_bottom"),
                            None, v, "mm", rule="tip-root"))
    if internal["contact_ratio"] < s.checks.min_contact_ratio:
        res.add(Finding("mesh", "fail", f"planet/ring: contact ratio {internal['contact_ratio']:.3f} < "
                        f"{s.checks.min_contact_ratio:g}", ("planet0", "frame_bottom"), None, internal["contact_ratio"], "",
                        rule="contact-ratio"))
    r_c = ring_contact_on_pinion(zp, zr, m, alpha, 0.0, a, s.system.addendum_coeff, r_inv)
    if r_c < rules.form_radius(s.planet) - 1e-6:
        res.add(Finding("mesh", "fail", f"planet/ring: the ring's tip meets the planet at r = {r_c:.3f} mm, below its form "
                        "radius (involute interference)", ("planet0", "frame_bottom"), None, r_c, "mm", rule="involute"))
    gap = planet_clearance(list(s.angles), a, s.planet.tip_radius)
    internal["planet_tip_gap_mm"] = round(gap, 4)
    if gap < s.checks.min_clearance:
        res.add(Finding("clearance", "fail", f"neighbouring planets' tips come within {gap:.3f} mm", ("planet0", "planet1"),
                        None, gap, "mm"))
    for name, gear in (("sun", s.sun), ("planet0", s.planet)):
        if gear.undercut:
            res.add(Finding("design", "info", f"{name} ({gear.teeth} teeth) is undercut", (name,)))
    meshing = {frozenset(("sun", f"planet{i}")) for i in range(N)} | {frozenset((f"planet{i}", "frame_bottom"))
                                                                     for i in range(N)}
    got = run_shared(res, kit, thetas, "input angle", progress, mesh_view=_SunPlanetView(kit), mesh_owned=meshing,
                     prune=True, bores=False)
    # every planet against sun and ring on the printed sections (tip and trochoidal interference): both
    # meshes of a planet advance one planet tooth while the sun turns 2π / (z_s (1 − 1/i)) about the
    # carrier, so 8 angles over that span see every phase of every mesh
    few = np.linspace(0.0, 2 * math.pi / (zs * (1 - 1 / s.ratio)), 8, endpoint=False)
    turned = turn_planetary(kit, few, tol=1e-5)
    worst = turned["overlap_mm2"].max()
    if worst > 1e-6:
        k, j = np.unravel_index(np.argmax(turned["overlap_mm2"]), turned["overlap_mm2"].shape)
        what = f"sun/planet{j}" if j < N else f"planet{j - N}/ring"
        res.add(Finding("mesh", "fail", f"{what}: the printed teeth overlap by {worst:.4f} mm² of section (tip or "
                        "trochoidal interference)", (), float(few[k]), float(worst), "mm2"))
    lash = np.abs(turned["coast"] - turned["drive"])
    if lash.min() <= 0:
        res.add(Finding("mesh", "fail", "the set jams: no backlash at the carrier", (), None, float(lash.min()), "rad",
                        rule="backlash"))
    res.figures.update(parts=len(kit.parts), samples=n, input_turns=round(s.ratio, 6), motion=got.motion,
                       meshes=got.meshes, internal_mesh=internal, clearance_left_to_mesh_check=got.dropped,
                       fits={"count": len(got.fits), "rows": got.fits}, printability=got.printing,
                       output_backlash_arcmin={"min": round(float(np.degrees(lash.min()) * 60), 3),
                                               "max": round(float(np.degrees(lash.max()) * 60), 3), "angles": len(few)},
                       max_printed_overlap_mm2=float(worst))
    return res
