"""A gear train as parts: the resolver (validated YAML → ``TrainSpec``: teeth, shifts, shaft centres,
z-layers) and the kit (a frame of two plates with spacers, a shaft per gear axis, a gear part per
shaft — two gears on one hub where the stage is compound).

Stacking (z up, the bottom plate's top face at z = 0; g = axial gap, f = face width, t = plate
thickness): gear layer j spans [L_j, L_j + f], L_j = g + j(f + g); a stage's two gears share a
layer; a compound shaft's two gears sit in consecutive layers, joined by a web through the gap.
Each gear part rests on a thrust ring (height g, the hub's radius) of the bottom plate; a part whose
lowest gear is above layer 0 stands on a hub down to that ring. The top plate spans [Z_t, Z_t + t],
Z_t = L_last + f + g. Spacers stand on the bottom plate at the corners outside every tip circle and
press into the top plate. A shaft is a fixed pin pressed into both plates (its gear bore round,
running on it) or a shaft turning in both plates (its gear pressed on a D-flat).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ...config.loader import LoadedDesign, printer_limits
from ...core.parts import Bore, Contact, Part
from ...core.printer import PrinterLimits
from ...core.protocol import ParamsKit
from ...core.transforms import pose_z
from ...design.gear_train import (StageTarget, StageTeeth, TeethLimits, mesh_phase, shaft_speeds, solve_train,
                                  train_ratio, transverse_system, twist_over)
from ...design.gearing import GearSpec, ToothSystem, centre_distance, make_gear
from ...checks.settings import CheckSettings
from ...design.rules import ToothSystemError, check_generable
from ...errors import ConfigError, DesignError
from ...geometry.gear import gear_body, helical_body
from ...geometry.outline import circle, hull_of_discs
from ...geometry.parts import DFit, shaft as shaft_solid
from ...geometry.solid import prisms, slab, union
from .common.hubs import Hub, HubError, plan_hub, turning
from .common.hubs import sizes_within as hub_sizes_within
from .common.kit import FEATURE_TOL, hub_cutters, hub_hole, screw_and_nut, turning_shaft

__all__ = ["TrainGear", "Shaft", "Mesh", "TrainSpec", "TrainKit", "resolve_train", "build_train"]

FLAT_DEPTH = 1.0  # mm: a D's flat sits this far inside its circle (geometry.parts.FLAT_DEPTH)


@dataclass(frozen=True)
class TrainGear:
    """One gear of the train: on ``shaft``, in ``layer``; its name (``gear2.1``: shaft 2, layer 1)."""

    name: str
    shaft: int
    layer: int
    spec: GearSpec
    hand: int = 0  # +1 right-hand (its section turns counter-clockwise going up), -1 left-hand, 0 spur


@dataclass(frozen=True)
class Shaft:
    """A gear axis: its centre (x, y) mm, its bore kind, its speed per unit input speed (signed) and
    its angle at rest (rad), the layers of its gear part and the hub radius (mm)."""

    index: int
    centre: tuple[float, float]
    bore: str  # "round" (gear on a fixed pin), else the gear fixed on a turning shaft (see hubs.py)
    speed: Fraction
    phase: float
    layers: tuple[int, int]
    hub_radius: float
    fit: Hub | None = None  # the bore and hub feature (None: the shaft's own, round or d_flat, from the spec)


@dataclass(frozen=True)
class Mesh:
    """Stage ``stage``: gear ``driver`` meshing ``driven`` along ``direction`` (rad) at ``centre_distance`` mm."""

    stage: int
    driver: str
    driven: str
    direction: float
    centre_distance: float


@dataclass(frozen=True)
class TrainSpec:
    """A gear train ready to build (mm, rad, g/mm³)."""

    name: str
    system: ToothSystem
    face_width: float
    stages: tuple[StageTeeth, ...]
    target_ratio: float | None
    gears: tuple[TrainGear, ...]
    shafts: tuple[Shaft, ...]
    meshes: tuple[Mesh, ...]
    shaft_radius: float
    running: float  # diametral clearances
    press: float
    extension: float
    gap: float
    plate_thickness: float
    margin: float
    spacer_radius: float
    checks: CheckSettings
    density: float
    material: str
    printer: PrinterLimits
    tol: float
    helix: float = 0.0  # rad, at the reference cylinder (0: spur)
    herringbone: bool = False
    normal_module: float = 0.0  # mm (the transverse module × cos helix)
    base: float = 0.0  # mm: the hub height under the first layer a set screw's hub needs (0: none)

    def twist(self, g: TrainGear) -> float:
        """How far (rad, signed) gear ``g``'s section turns from the bottom of its face to the top
        (a herringbone's to its middle and back)."""
        return g.hand * twist_over(self.face_width, self.helix, g.spec.pitch_radius) if self.helix else 0.0

    @property
    def layers(self) -> int:
        return max(g.layer for g in self.gears) + 1

    def layer_z(self, j: int) -> float:
        return self.gap + self.base + j * (self.face_width + self.gap)

    @property
    def top_z(self) -> float:
        """Bottom of the top plate."""
        return self.layer_z(self.layers - 1) + self.face_width + self.gap

    @property
    def ratio(self) -> Fraction:
        return train_ratio(list(self.stages))

    def gear(self, name: str) -> TrainGear:
        return next(g for g in self.gears if g.name == name)

    def hub(self, s: Shaft) -> Hub:
        """Shaft ``s``'s bore and hub feature."""
        if s.fit is not None:
            return s.fit
        return Hub(s.bore, self.shaft_radius, self.bore_radius(s), 0.0, 0.0)

    def radius(self, s: Shaft) -> float:
        """Shaft ``s``'s radius (a hex bore's threaded rod: the nut's thread)."""
        return self.hub(s).radius if s.fit is not None else self.shaft_radius

    def bore_radius(self, s: Shaft) -> float:
        if s.fit is not None:
            return s.fit.bore
        return self.shaft_radius + (self.running if s.bore == "round" else self.press) / 2

    def angle(self, s: Shaft, theta: float) -> float:
        """Shaft ``s``'s angle (rad) when the input has turned ``theta`` (rad)."""
        return s.phase + float(s.speed) * theta

    @property
    def output_turn(self) -> float:
        """The input angle (rad) over which the slowest shaft turns once."""
        return 2 * math.pi / min(abs(float(s.speed)) for s in self.shafts)


def _fit(loaded: LoadedDesign, key: str, value) -> float:
    if value != "printer":
        return float(value)
    fits = loaded.printer.fits
    if fits is None:
        raise ConfigError(loaded.path, f"shafts.{key}", "the printer profile gives no measured fits: give a number")
    return fits.running_clearance_diametral_mm if key.startswith("running") else fits.press_fit_clearance_diametral_mm


def resolve_train(loaded: LoadedDesign) -> TrainSpec:
    d, p = loaded.design, loaded.printer
    g, t, fr = d.gears, d.train, d.frame
    beta = math.radians(g.helix_angle_deg)
    T = transverse_system(g.module_mm, math.radians(g.pressure_angle_deg), beta, g.helix_system, g.addendum_coeff,
                          g.dedendum_coeff)
    alpha, module = T.pressure_angle, T.module
    system = ToothSystem(module=module, pressure_angle=alpha, addendum_coeff=T.addendum_coeff,
                         dedendum_coeff=T.dedendum_coeff, cutter_tip_coeff=T.cutter_tip_coeff,
                         backlash_per_gear=g.backlash_per_gear_mm,
                         profile_shift=None if g.profile_shift == "auto" else float(g.profile_shift) * T.shift_factor,
                         chord_tolerance=g.chord_tolerance_mm)
    bed = min(p.build_envelope_mm[:2])
    lim = TeethLimits(g.min_teeth, g.max_teeth, bed - 2 * (g.addendum_coeff + 1.5) * module, module)
    targets = [StageTarget(tuple(s.teeth) if s.teeth else None, s.ratio, s.exact, s.centre_distance_mm, s.idler)
               for s in t.stages]
    try:
        stages = solve_train(targets, lim, module, alpha, t.ratio, t.ratio_exact,
                             tuple(x * T.shift_factor for x in g.shift_range), T.addendum_coeff, key="train",
                             default_shift=lambda z: make_gear(z, system).profile_shift)
    except DesignError as e:
        raise ConfigError(loaded.path, e.key_path, e.problem) from None
    n = len(stages)
    # layers: a stage shares its driver's layer when it is an idler stage, else the next one
    layer = [0]
    for k in range(1, n):
        layer.append(layer[-1] + (0 if stages[k].idler else 1))
    gears: list[TrainGear] = []
    by_shaft: dict[int, list[TrainGear]] = {}

    def add(shaft: int, lay: int, z: int, x: float | None, key: str, hand: int) -> TrainGear:
        for have in by_shaft.get(shaft, []):
            if have.layer == lay:
                return have
            hand = have.hand  # a compound shaft's gears share their hand: their axial thrusts oppose
        spec = make_gear(z, system) if x is None else GearSpec(int(z), system, float(x))
        try:
            check_generable(spec)
        except ToothSystemError as e:
            raise ConfigError(loaded.path, "gears.profile_shift" if e.field == "profile_shift" else key, e.problem) from None
        gear = TrainGear(f"gear{shaft}.{lay}", shaft, lay, spec, hand if beta else 0)
        gears.append(gear)
        by_shaft.setdefault(shaft, []).append(gear)
        return gear

    meshes = []
    direction = 0.0
    for k, s in enumerate(stages):
        x1, x2 = s.shifts if s.shifts else (None, None)
        a = add(k, layer[k], s.driver, x1, f"train.stages[{k}].teeth[0]", 1)
        b = add(k + 1, layer[k], s.driven, x2, f"train.stages[{k}].teeth[1]", -a.hand)
        direction += math.radians(t.stages[k].angle_deg)
        meshes.append(Mesh(k, a.name, b.name, direction, centre_distance(a.spec, b.spec)))
    # shaft centres, speeds and phases (each stage puts a tooth space of its driven gear on a tooth of its driver)
    bores = list(d.shafts.bores) if d.shafts.bores else ["d_flat"] + ["round"] * (n - 1) + ["d_flat"]
    if len(bores) != n + 1:
        raise ConfigError(loaded.path, "shafts.bores", f"the train has {n + 1} shafts (input first), the list {len(bores)}")
    speeds = shaft_speeds(stages)
    centres = [(0.0, 0.0)]
    phases = [0.0]
    for m in meshes:
        c = centres[-1]
        centres.append((c[0] + m.centre_distance * math.cos(m.direction), c[1] + m.centre_distance * math.sin(m.direction)))
        phases.append(mesh_phase(phases[-1], stages[m.stage].driver, stages[m.stage].driven, m.direction))
    running = _fit(loaded, "running_clearance_diametral_mm", d.shafts.running_clearance_diametral_mm)
    press = _fit(loaded, "press_fit_clearance_diametral_mm", d.shafts.press_fit_clearance_diametral_mm)
    r_shaft = d.shafts.diameter_mm / 2
    if r_shaft - FLAT_DEPTH < 1.0 and "d_flat" in bores:
        raise ConfigError(loaded.path, "shafts.diameter_mm", f"a D-flat {FLAT_DEPTH:g} mm deep needs a shaft of at least "
                          f"{2 * (FLAT_DEPTH + 1):g} mm")
    wall = printer_limits(p).min_wall
    f, gap = g.face_width_mm, fr.axial_gap_mm
    try:
        slack = max(g.chord_tolerance_mm, 0.005) + FEATURE_TOL  # a bore's polygon outside its circle, a hub's inside
        fits = [plan_hub(b, r_shaft, running, press, wall, gap, d.shafts.nut, d.shafts.set_screw, slack) for b in bores]
    except HubError as e:
        raise ConfigError(loaded.path, f"shafts.{e.key}", e.problem) from None

    def sizes_within(kind: str, what: str, radius: float) -> str:
        """The nut or set-screw sizes whose feature needs at most ``radius`` (``what``: room or hub_need)."""
        return hub_sizes_within(kind, what, radius, r_shaft, running, press, wall, gap, slack)

    lows = [min(x.layer for x in by_shaft[i]) for i in range(n + 1)]
    # a set screw's hub stands under its lowest gear: raise the layers if a part's hub would be too low
    base = max([0.0] + [h.height - lo * (f + gap) for h, lo in zip(fits, lows)])
    lz = lambda j: gap + base + j * (f + gap)  # noqa: E731
    shafts = []
    for i in range(n + 1):
        mine = by_shaft[i]
        lo, hi = min(x.layer for x in mine), max(x.layer for x in mine)
        hb = fits[i]
        bore = hb.bore
        for x in mine:
            # a keyway runs through every gear, a nut's trap or slot may reach into the lowest one
            room = hb.room if hb.kind == "keyway" or (hb.kind in ("hex", "set_screw") and x.layer == lo) \
                else bore + wall
            if room >= x.spec.root_radius:
                what = {"keyway": "its keyway", "hex": f"its {hb.nut} nut trap",
                        "set_screw": f"its {hb.nut} set screw's nut slot"}.get(hb.kind, f"its Ø{2 * bore:.2f} mm bore")
                fits_ = sizes_within(hb.kind, "room", x.spec.root_radius - 1e-9) if hb.kind in ("hex", "set_screw") else ""
                raise ConfigError(loaded.path, "shafts.diameter_mm" if hb.kind in ("round", "d_flat", "keyway")
                                  else f"shafts.{'nut' if hb.kind == 'hex' else 'set_screw'}",
                                  f"{x.name} ({x.spec.teeth} teeth): its root circle (Ø{2 * x.spec.root_radius:.2f} mm) "
                                  f"leaves less than the printer's {wall:g} mm wall around {what} (needs a root "
                                  f"Ø{2 * room:.2f} mm): a thinner shaft or smaller hardware{fits_}, more teeth or a "
                                  "larger module")
        if hb.kind == "hex" and hb.pocket_depth + wall > f + (lz(lo) - gap):
            raise ConfigError(loaded.path, "shafts.nut", f"shaft {i}'s {hb.nut} nut trap ({hb.pocket_depth:.2f} mm deep) "
                              f"and a {wall:g} mm wall need a part {hb.pocket_depth + wall:.2f} mm tall: a smaller nut or "
                              "a wider face (gears.face_width_mm)")
        # the hub and its thrust ring stand from z = 0 to the part's lowest gear: they must clear every
        # other shaft's gear in those layers by the check's clearance
        reach = lz(lo)
        limit = math.inf
        for other in gears:
            if other.shaft != i and lz(other.layer) <= reach + 1e-9:
                dist = math.dist(centres[i], centres[other.shaft])
                limit = min(limit, dist - other.spec.tip_radius - d.checks.min_clearance_mm)
        limit = min(limit, min(x.spec.root_radius for x in mine if x.layer == lo))
        want = fr.hub_diameter_mm / 2 if fr.hub_diameter_mm else max(bore + max(3 * wall, 2.5), hb.hub_need)
        hub = min(want, limit)
        if hb.kind != "d_flat" and hb.kind != "round" and lz(lo) > gap + 1e-9 and hub < hb.hub_need - 1e-9:
            key = {"keyway": "diameter_mm", "hex": "nut", "set_screw": "set_screw"}[hb.kind]
            raise ConfigError(loaded.path, "frame.hub_diameter_mm" if fr.hub_diameter_mm and limit >= hb.hub_need
                              else f"shafts.{key}",
                              f"shaft {i}'s hub (under {mine[0].name}) has room for Ø{2 * max(hub, 0):.2f} mm, its "
                              f"{hb.kind.replace('_', ' ')} needs Ø{2 * hb.hub_need:.2f} mm with the printer's {wall:g} mm "
                              "wall: smaller hardware" + (sizes_within(hb.kind, "hub_need", hub) if hb.kind != "keyway"
                                                          else "") + " or a thinner shaft, or turn a stage "
                              "(train.stages[].angle_deg) to move the neighbouring gears away")
        if hub < bore + wall - 1e-9:
            raise ConfigError(loaded.path, "frame.hub_diameter_mm", f"shaft {i}'s hub (under {mine[0].name}) has room for "
                              f"Ø{2 * max(hub, 0):.2f} mm only, less than its Ø{2 * bore:.2f} mm bore and a {wall:g} mm "
                              "wall: turn a stage (train.stages[].angle_deg) to move the neighbouring gears away")
        if fr.hub_diameter_mm and fr.hub_diameter_mm / 2 > limit + 1e-9:
            raise ConfigError(loaded.path, "frame.hub_diameter_mm", f"at most {2 * limit:.2f} mm at shaft {i}")
        shafts.append(Shaft(i, centres[i], bores[i], speeds[i], phases[i], (lo, hi), hub,
                            None if bores[i] in ("round", "d_flat") else hb))
    for i, b in enumerate(bores):
        dia = 2 * (r_shaft + (running if b == "round" else press) / 2)
        if b == "round" and dia < p.min_hole_diameter_mm - 1e-6:
            raise ConfigError(loaded.path, "shafts.diameter_mm", f"the gear bores (Ø{dia:.2f} mm) run on their pins and "
                              f"are below the printer's smallest reliable running hole ({p.min_hole_diameter_mm:g} mm)")
    c = d.checks
    checks = CheckSettings(c.samples, c.interference_tolerance_mm3, c.min_clearance_mm, c.min_contact_ratio,
                           c.min_tip_width_roads, c.plate_margin_mm)
    return TrainSpec(d.name, system, f, tuple(stages), t.ratio, tuple(gears), tuple(shafts), tuple(meshes), r_shaft,
                     running, press, d.shafts.extension_mm, gap, fr.plate_thickness_mm, fr.margin_mm,
                     fr.spacer_diameter_mm / 2, checks, d.material.density_g_cm3 / 1000.0, d.material.name,
                     printer_limits(p), g.chord_tolerance_mm, beta, g.herringbone, module * math.cos(beta), base)


@dataclass(frozen=True)
class TrainKit(ParamsKit):
    """The frame, the shafts and the gear parts; poses over the input's turn θ (rad)."""

    params: TrainSpec
    parts: tuple[Part, ...]
    contacts: tuple[Contact, ...]
    spacers: tuple[tuple[float, float], ...]

    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        s = self.params
        out = {"frame_bottom": np.eye(4), "frame_top": np.eye(4)}
        for sh in s.shafts:
            a = s.angle(sh, float(theta))
            out[f"gears{sh.index}"] = pose_z(sh.centre[0], sh.centre[1], 0.0, a)
            out[f"shaft{sh.index}"] = pose_z(sh.centre[0], sh.centre[1], 0.0, a if turning(sh.bore) else 0.0)
            if sh.bore in ("hex", "set_screw"):  # the bought nut (and screw) turn with the gear part
                out[f"nut{sh.index}"] = out[f"gears{sh.index}"]
                if sh.bore == "set_screw":
                    out[f"set_screw{sh.index}"] = out[f"gears{sh.index}"]
        return out


def _spacer_centres(s: TrainSpec) -> list[tuple[float, float]]:
    """Four spacers at the corners of the box around every tip circle, each outside every tip circle
    by at least the frame's margin (a corner is √2 (r + margin + spacer) from any circle's centre
    along the diagonal, at least r + margin + spacer in each axis)."""
    tips = [(s.shafts[g.shaft].centre, g.spec.tip_radius) for g in s.gears]
    d = s.margin + s.spacer_radius
    x0 = min(c[0] - r for c, r in tips) - d
    x1 = max(c[0] + r for c, r in tips) + d
    y0 = min(c[1] - r for c, r in tips) - d
    y1 = max(c[1] + r for c, r in tips) + d
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


def _bore(s: TrainSpec, sh: Shaft):
    """The gear part's bore: round over a fixed pin, a D over a turning shaft's flat (on local -y), a
    round bore with its keyway (on local +y), or round (a nut trap's, a set screw's)."""
    tol = max(s.tol, 0.005)
    if sh.bore == "d_flat":
        return DFit(s.shaft_radius, s.press).hole(tol)
    if sh.fit is not None:
        return hub_hole(sh.fit, s.press, tol)
    return circle(s.bore_radius(sh), tol, hole=True)


def _part_span(s: TrainSpec, sh: Shaft) -> tuple[float, float]:
    """The gear part's bottom and top (z, mm, world): from its thrust ring, or its lowest gear."""
    lo = s.layer_z(sh.layers[0])
    return (s.gap if lo > s.gap + 1e-9 else lo), s.layer_z(sh.layers[1]) + s.face_width


def _cutters(s: TrainSpec, sh: Shaft) -> list:
    """What the gear part loses for its hardware: a nut trap in its bottom face, or a set screw's
    radial hole (on local +x) and its nut's slot open at the bottom face."""
    z0, _ = _part_span(s, sh)
    return hub_cutters(s.hub(sh), z0, sh.hub_radius + 1.0, s.running)


def _gear_part(s: TrainSpec, sh: Shaft) -> Part:
    mine = sorted((g for g in s.gears if g.shaft == sh.index), key=lambda g: g.layer)
    hole = _bore(s, sh)
    tol = FEATURE_TOL
    solids = [helical_body(g.spec, s.face_width, hole, s.layer_z(g.layer), s.twist(g), s.herringbone,
                           s.system.chord_tolerance) if g.hand else gear_body(g.spec, s.face_width, hole, s.layer_z(g.layer))
              for g in mine]
    web = []
    lo = s.layer_z(mine[0].layer)
    if lo > s.gap + 1e-9:  # a hub down to the thrust ring
        web.append((circle(sh.hub_radius, tol).difference(hole), s.gap, lo))
    for a, b in zip(mine[:-1], mine[1:]):  # the web joining a compound shaft's two gears through the gap
        r = min(a.spec.root_radius, b.spec.root_radius)
        web.append((circle(r, tol).difference(hole), s.layer_z(a.layer) + s.face_width, s.layer_z(b.layer)))
    solid = union(solids + ([prisms(web)] if web else []))
    cut = _cutters(s, sh)
    if cut:
        solid = solid - union(cut)
    flip = lo > s.gap + 1e-9  # its lowest gear stands on a hub: print it upside down, top gear face on the bed
    z_lo, z_hi = _part_span(s, sh)
    pin = 2 * (s.shaft_radius - FLAT_DEPTH) if sh.bore == "d_flat" else 2 * s.radius(sh)
    return Part(f"gears{sh.index}", "gear", solid, print_flip=flip, gear=mine[0].spec if len(mine) == 1 else None,
                bores=(Bore("shaft", (0.0, 0.0, z_lo), (0.0, 0.0, 1.0), pin, z_hi - z_lo),))


def _shaft_parts(s: TrainSpec, sh: Shaft, z_lo: float, z_hi: float) -> list[Part]:
    """Shaft ``sh`` from under the bottom plate up (a fixed pin to the top plate's top, a turning shaft
    ``extension`` above it): printed — round, with a D-flat or with its integral key along the gear
    part — or bought: a hex bore's threaded rod and its nut; a set screw and its square nut."""
    t, zt, tol = s.plate_thickness, s.top_z, FEATURE_TOL
    fit, h, name = DFit(s.shaft_radius, 0.0), s.hub(sh), f"shaft{sh.index}"
    top = zt + t + (s.extension if turning(sh.bore) else 0.0)
    if sh.bore == "d_flat":  # round in the plates, D under the gear part, round above it through the top plate
        return [Part(name, "axle", shaft_solid(fit, [("round", -t, z_lo), ("D", z_lo, z_hi), ("round", z_hi, top)], tol))]
    if sh.bore == "round":
        return [Part(name, "axle", shaft_solid(fit, [("round", -t, top)], tol))]
    return turning_shaft(h, name, f"nut{sh.index}", -t, top, (z_lo, z_hi))


def _set_screw_parts(s: TrainSpec, sh: Shaft) -> list[Part]:
    """A set screw's bought parts, posed with the gear part: the screw (from the shaft's surface out,
    along local +x) and its square nut in the slot."""
    z0, _ = _part_span(s, sh)
    return screw_and_nut(s.hub(sh), f"set_screw{sh.index}", f"nut{sh.index}", z0)


def build_train(s: TrainSpec, progress=None) -> TrainKit:
    say = progress or (lambda name: None)
    tol = FEATURE_TOL
    t, zt = s.plate_thickness, s.top_z
    spacers = _spacer_centres(s)
    peg = s.spacer_radius / 2
    discs = [(sh.centre, max(g.spec.tip_radius for g in s.gears if g.shaft == sh.index) + s.margin) for sh in s.shafts]
    discs += [(c, s.spacer_radius + 2.0) for c in spacers]
    outline = hull_of_discs(discs, tol)
    hole_r = {sh.index: s.radius(sh) + (s.press if sh.bore == "round" else s.running) / 2 for sh in s.shafts}
    holes = [circle(hole_r[sh.index], tol, sh.centre, hole=True) for sh in s.shafts]
    bottom = outline
    for h in holes:
        bottom = bottom.difference(h)
    say("frame_bottom")
    rings = [(circle(sh.hub_radius, tol, sh.centre).difference(holes[sh.index]), 0.0, s.gap) for sh in s.shafts]
    columns = [(circle(s.spacer_radius, tol, c), 0.0, zt) for c in spacers]
    pegs = [(circle(peg, tol, c), zt, zt + t) for c in spacers]
    down, up = (0.0, 0.0, -1.0), (0.0, 0.0, 1.0)  # the round part of every shaft runs through both plates
    parts = [Part("frame_bottom", "frame", union([slab(bottom, -t, 0.0), prisms(rings + columns + pegs)]),
                  bores=tuple(Bore(f"shaft{sh.index}", (sh.centre[0], sh.centre[1], -t), up, 2 * s.radius(sh), t + s.gap)
                              for sh in s.shafts))]
    say("frame_top")
    top = outline
    for h in holes + [circle(peg + s.press / 2, tol, c, hole=True) for c in spacers]:
        top = top.difference(h)
    parts.append(Part("frame_top", "frame", slab(top, zt, zt + t),
                      bores=tuple(Bore(f"shaft{sh.index}", (sh.centre[0], sh.centre[1], zt + t), down, 2 * s.radius(sh), t)
                                  for sh in s.shafts)))
    contacts = []
    for sh in s.shafts:
        say(f"gears{sh.index}")
        gp = _gear_part(s, sh)
        parts.append(gp)
        z_lo, z_hi = _part_span(s, sh)
        say(f"shaft{sh.index}")
        parts += _shaft_parts(s, sh, z_lo, z_hi)
        if sh.bore == "set_screw":
            parts += _set_screw_parts(s, sh)
        g, sn = gp.name, f"shaft{sh.index}"
        if sh.bore == "round":
            contacts.append(Contact(g, sn, "running", (z_lo, z_hi), s.running / 2))
            contacts += [Contact(sn, "frame_bottom", "press", (-t, 0.0), s.press / 2),
                         Contact(sn, "frame_top", "press", (zt, zt + t), s.press / 2)]
        else:  # fixed to a turning shaft (a hex bore's rod: held by the nut, its bore a clearance)
            gap = (s.running if sh.bore == "hex" else s.press) / 2
            contacts.append(Contact(g, sn, "press", (z_lo, z_hi), gap))
            contacts += [Contact(sn, "frame_bottom", "running", (-t, 0.0), s.running / 2),
                         Contact(sn, "frame_top", "running", (zt, zt + t), s.running / 2)]
        contacts.append(Contact(g, "frame_bottom", "thrust"))
        if sh.bore == "hex":  # the nut: in its trap, on its rod, on the thrust ring with the gear part
            contacts += [Contact(f"nut{sh.index}", g, "thrust"), Contact(f"nut{sh.index}", sn, "thrust"),
                         Contact(f"nut{sh.index}", "frame_bottom", "thrust")]
        if sh.bore == "set_screw":  # the screw in its hole, through its nut, on the shaft; the nut in its slot
            n_, c_ = f"nut{sh.index}", f"set_screw{sh.index}"
            contacts += [Contact(n_, g, "thrust"), Contact(c_, g, "thrust"), Contact(c_, n_, "thrust"),
                         Contact(c_, sn, "thrust")]
    contacts.append(Contact("frame_top", "frame_bottom", "press", (zt, zt + t), s.press / 2))
    return TrainKit(s, tuple(parts), tuple(contacts), tuple(spacers))
