"""The gear train's resolver: the validated design -> ``TrainSpec`` (the stages' teeth and shifts, the
gears on their shafts and layers, the meshes, the shafts' centres, speeds and phases, bores and hubs,
the fits), and the design findings."""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from ....checks.settings import CheckSettings
from ....config.loader import LoadedDesign, printer_limits
from ....core.findings import Finding
from ....core.printer import PrinterLimits
from ....design import rules
from ....design.gear_train import (StageTarget, StageTeeth, TeethLimits, mesh_phase, shaft_speeds, solve_train,
                                   train_ratio, transverse_system, twist_over)
from ....design.gearing import GearSpec, ToothSystem, centre_distance, make_gear
from ....design.rules import ToothSystemError, check_generable, gear_rules
from ....errors import ConfigError, DesignError
from ..common.hubs import Hub, HubError, plan_hub
from ..common.hubs import sizes_within as hub_sizes_within
from ..common.kit import FEATURE_TOL
from ..common.resolve import check_settings, gear_findings, shaft_fits

__all__ = ["FLAT_DEPTH", "TrainGear", "Shaft", "Mesh", "TrainSpec", "resolve_train", "findings"]

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
    running, press = shaft_fits(loaded)
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
    checks = check_settings(d.checks)
    return TrainSpec(d.name, system, f, tuple(stages), t.ratio, tuple(gears), tuple(shafts), tuple(meshes), r_shaft,
                     running, press, d.shafts.extension_mm, gap, fr.plate_thickness_mm, fr.margin_mm,
                     fr.spacer_diameter_mm / 2, checks, d.material.density_g_cm3 / 1000.0, d.material.name,
                     printer_limits(p), g.chord_tolerance_mm, beta, g.herringbone, module * math.cos(beta), base)


def findings(spec: TrainSpec) -> list[Finding]:
    """What `build` warns about (the rules `check` fails on) and notes (undercut gears)."""
    gr = gear_rules(spec)
    out = []
    for k, m in enumerate(spec.meshes):
        a, b = spec.gear(m.driver), spec.gear(m.driven)
        for x in rules.mesh_breaches(a.spec, b.spec, m.centre_distance, gr, (a.name, b.name)):
            out.append(Finding("design", "warn", x.message, (), key=f"train.stages[{k}]", rule=x.rule))
    return out + gear_findings(gr, [(g.name, g.spec) for g in spec.gears])
