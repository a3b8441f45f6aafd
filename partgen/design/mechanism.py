"""A whole gear-coupled chain: links + the gear stages that couple them + the drive (pure math).

``synthesize`` takes the numbers a config resolved (mm, rad) and returns the design every later
layer works from: the chain, one ``Stage`` per coupled link, the drive pair, and findings.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Protocol

from ..core.printer import PrinterLimits
from ..errors import DesignError
from . import involute
from .belt import BeltProfile, BeltStage, design_belt_stage
from .belt import pitch_diameter as _pd
from .curve import FourierCurve
from .drawing import Drawing
from .drivetrain import (Finding, design_finding, Limits, Stage, choose_stage, eq11_ratios, make_stage, stage_breaches,
                         verify_stage)
from .gearing import GearSpec, ToothSystem, centre_distance, make_gear
from .rules import GearRules, check_generable, gear_breaches, gear_rules, hole_breach, mesh_breaches, wall_breach
from .synthesis import Chain

__all__ = ["ChainParams", "MechanismInputs", "ChainDesign", "synthesize",
           "TRIANGLE_BUDGET", "gear_triangles", "auto_module"]

TRIANGLE_BUDGET = 8_000_000  # triangles of all gear solids of a kit: about 2 GB of meshes while building


class ChainParams(Protocol):
    """What the chain's design math reads of a kit's parameters (mm, rad). The gear chain's
    resolver makes them (``partgen.mechanisms.gear_chain.params.ChainParams``, a frozen dataclass that
    ``dataclasses.replace`` can change); this layer only states what it reads."""

    system: ToothSystem
    printer: PrinterLimits
    joints: object  # axle_diameter, running_clearance, press_clearance (diametral), axial_gap
    checks: object  # min_contact_ratio, min_tip_width_roads, min_clearance
    hub_wall: float
    boss_wall: float
    pen_diameter: float
    drive_teeth: int
    drive_angle: float

    @property
    def bore(self) -> float: ...  # running bore on an axle (axle + running clearance)

    @property
    def min_root_diameter(self) -> float: ...  # the root circle that keeps the hub wall round the bore


@dataclass(frozen=True)
class BeltSettings:
    """Timing belts instead of idler gears (mm)."""

    profile: BeltProfile
    stock_teeth: tuple[int, ...]
    flange_height: float
    flange_thickness: float
    tensioner_radius: float
    tensioner_gap: float


@dataclass(frozen=True)
class MechanismInputs:
    """The chain (links in mm/rad), explicit teeth per stage or None for auto, stage margins."""

    chain: Chain
    teeth: tuple[tuple[int, int, int], ...] | None
    tip_gap: float
    idler_reach: float
    curve: FourierCurve | None = None
    scale: float = 1.0
    dropped: tuple[str, ...] = ()
    idlers: tuple[tuple[float, float] | None, ...] | None = None  # hand-placed idlers per stage
    source: str = "curve"  # "curve": links derived from ``curve``; "table": a design table (curve = its target);
    # "drawing": links fitted to ``drawing`` (the user's samples)
    belts: BeltSettings | None = None
    drawing: Drawing | None = None


@dataclass(frozen=True)
class ChainDesign:
    chain: Chain
    stages: tuple[Stage, ...]
    G1: GearSpec
    drive: GearSpec
    drive_centre: tuple[float, float]
    findings: tuple[Finding, ...] = field(default=())
    curve: FourierCurve | None = None
    scale: float = 1.0
    dropped: tuple[str, ...] = ()
    auto_teeth: bool = True
    source: str = "curve"
    belt_stages: tuple[BeltStage, ...] = ()
    design_chain: Chain | None = None  # the chain the design asks for (a belt stage may change a link)
    drawing: Drawing | None = None  # the user's samples the chain was fitted to (source "drawing")

    @property
    def couplings(self) -> list[tuple[int, int]]:
        """(T_D, T_G) of every stage, gear or belt, in chain order."""
        return [(s.D.teeth, s.G.teeth) for s in (self.stages or self.belt_stages)]

    @property
    def gears(self) -> list[tuple[str, GearSpec]]:
        """Every gear of the kit with its name: drive, G1, then D_j, M_j, G_{j+1} per stage."""
        out = [("drive", self.drive), ("G1", self.G1)]
        for s in self.stages:
            out += [(f"D{s.j}", s.D), (f"M{s.j}", s.M), (f"G{s.j + 1}", s.G)]
        return out


def pitch_diameter_belt(teeth: int, profile: BeltProfile) -> float:
    return _pd(teeth, profile.pitch)


def synthesize(inputs: MechanismInputs, params: ChainParams, advise: bool = True) -> ChainDesign:
    """Ratios, teeth (chosen or verified), idler placement, the drive pair and the findings.
    ``advise``: a refusal computes the settings that would work (a search turns it off)."""
    links = inputs.chain.links
    if len(links) < 1:
        raise DesignError("the chain has no links", "links")
    system = params.system
    limits = Limits(params.printer.min_gear, params.min_root_diameter, inputs.tip_gap, inputs.idler_reach,
                    gear_rules(params), params.joints.axle_diameter,
                    max(params.printer.min_hole - params.joints.running_clearance, 0.5), advise)
    findings: list[Finding] = []
    for j, link in enumerate(links, 1):
        if link.length < params.printer.min_link - 1e-9:
            findings.append(design_finding("warn", "short-link", f"link {j} ({link.name}) is {link.length:.2f} mm, "
                                    f"shorter than the printer's smallest link {params.printer.min_link:g} mm",
                                    f"links[{j - 1}].length_mm"))
    ratios = eq11_ratios(inputs.chain.speeds)
    stages = []
    if inputs.belts is not None:
        return _belt_mechanism(inputs, params, ratios, findings)
    if inputs.teeth is None:
        for j, (link, r) in enumerate(zip(links, ratios), 1):
            st = choose_stage(j, link.length, r, system, limits)
            stages.append(st)
            findings += [design_finding("warn", b.rule, f"link {j}: {b.message}", "gears.module_mm")
                         for b in stage_breaches(st.D, st.M, st.G, limits.rules)]  # what auto gave up: tip width
    else:
        if len(inputs.teeth) != len(ratios):
            raise DesignError(f"{len(inputs.teeth)} stages of teeth given for {len(links)} links: "
                              f"need one per link but the last ({len(ratios)})", "teeth")
        for j, (link, r, t) in enumerate(zip(links, ratios, inputs.teeth), 1):
            st = make_stage(j, link.length, r, t, system)
            placed = inputs.idlers[j - 1] if inputs.idlers else None
            if placed is not None:
                st = replace(st, idler=(float(placed[0]), float(placed[1])))
            stages.append(st)
            findings += verify_stage(st, limits, f"teeth[{j - 1}]")
    G1, drive, drive_centre = _drive(params)
    findings += drive_findings(G1, drive, limits.rules) + kit_findings(params)
    distinct = {(g.teeth, g.profile_shift): g for s in stages for g in (s.D, s.M, s.G)}
    for g in distinct.values():
        check_generable(g)
    _budget([G1, drive] + [g for s in stages for g in (s.D, s.M, s.G)])
    return ChainDesign(inputs.chain, tuple(stages), G1, drive, drive_centre, tuple(findings),
                     inputs.curve, inputs.scale, inputs.dropped, inputs.teeth is None, inputs.source, (),
                     inputs.chain, inputs.drawing)


GEAR_RULES = ("tip-root", "contact-ratio", "involute", "backlash", "tip-width")  # what a module changes


def auto_module(inputs: MechanismInputs, params: ChainParams, advise: bool = True) -> tuple[ChainDesign, ChainParams]:
    """``gears.module_mm: auto``: the largest module on the grid (``drivetrain.module_grid``) with which
    the chain synthesizes and every gear and mesh meets the rules `partgen check` holds it to on this
    printer (tip width in lines, tip-to-root, contact ratio, involute, backlash). Returns the
    mechanism and the kit parameters at that module; DesignError on ``gears.module_mm`` when none does,
    naming the first refusal at the largest and at the smallest module (with ``advise``, the
    settings that would work: a search that tries many designs turns it off)."""
    from dataclasses import replace

    from .drivetrain import MODULE_RANGE, module_grid

    first: dict[float, str] = {}
    for m in module_grid():
        p = replace(params, system=replace(params.system, module=m))
        try:
            mech = synthesize(inputs, p, advise=False)
        except DesignError as e:
            first[m] = e.problem
            continue
        bad = [f for f in mech.findings if f.severity == "warn" and f.rule in GEAR_RULES]
        if not bad:
            return mech, p
        first[m] = bad[0].message
    hi, lo = max(first), min(first)
    why = {}
    for m in (hi, lo):  # the refusal again, now with the settings that would work
        if not advise:
            why[m] = first[m]
            continue
        try:
            synthesize(inputs, replace(params, system=replace(params.system, module=m)))
            why[m] = first[m]
        except DesignError as e:
            why[m] = e.problem
    raise DesignError(f"no module from {MODULE_RANGE[0]:g} to {MODULE_RANGE[1]:g} mm builds this chain on the printer "
                      f"(every link must work at the same module): at {hi:g} mm: {why[hi]}; at {lo:g} mm: {why[lo]}",
                      "gears.module_mm")


@lru_cache(maxsize=4096)
def gear_triangles(gear: GearSpec) -> int:
    """Triangles of a gear's toothed prism: its outline's n vertices make 2n side triangles and
    about 2n in the two caps."""
    s = gear.system
    n = len(involute.gear_outline(gear.teeth, s.module, s.pressure_angle, gear.profile_shift, s.backlash_per_gear,
                                  s.addendum_coeff, s.dedendum_coeff, s.cutter_tip_coeff, s.chord_tolerance).points)
    return 4 * n


def _budget(gears: list[GearSpec]) -> None:
    """Refuse, before any solid is made, gears whose meshes would exceed TRIANGLE_BUDGET."""
    per = {}
    total = 0
    for g in gears:
        key = (g.teeth, g.profile_shift)
        if key not in per:
            per[key] = gear_triangles(g)
        total += per[key]
    if total > TRIANGLE_BUDGET:
        tol = gears[0].system.chord_tolerance
        need = tol * (total / TRIANGLE_BUDGET) ** 2  # vertices grow as tolerance^-1/2
        raise DesignError(f"the kit's gears would have {total / 1e6:.1f} million triangles (at most "
                          f"{TRIANGLE_BUDGET / 1e6:g} million): at a chord tolerance of {tol:g} mm their flanks drive it; "
                          f"use at least {need:.2g} mm", "gears.chord_tolerance_mm")


HOLE_EXCESS = 0.01  # mm: a hole's polygon circumscribes its circle by up to the features' chord tolerance
PEN_BORE_CLEARANCE = 0.2  # mm, diametral: the pen holder's bore over the pen


def kit_findings(params: ChainParams, belts: BeltSettings | None = None) -> list[Finding]:
    """Warnings for the printer's hole and wall rules (design.rules) that the given sizes break:
    the joints' bores, the holes held to size, the hub and boss walls, the tensioner rollers."""
    pr, jn = params.printer, params.joints
    out = []

    def add(b, key, hint):
        if b is not None:
            out.append(design_finding("warn", b.rule, f"{b.message}: {hint}", key))

    add(hole_breach(params.bore, True, pr.min_hole, pr.min_hole_to_size), "joints.axle_diameter_mm",
        f"gears and plates turn on the axles in bores of Ø{params.bore:.2f} mm (axle + running clearance); "
        f"use an axle of at least {pr.min_hole - jn.running_clearance:.2f} mm")
    add(hole_breach(jn.axle_diameter + jn.press_clearance, False, pr.min_hole, pr.min_hole_to_size),
        "joints.axle_diameter_mm", "the D-holes that press onto the axles")
    add(hole_breach(params.pen_diameter + PEN_BORE_CLEARANCE, False, pr.min_hole, pr.min_hole_to_size),
        "pen.diameter_mm", "the pen holder's bore")
    wall = params.hub_wall - max(0.0, jn.press_clearance - jn.running_clearance) / 2 - HOLE_EXCESS
    add(wall_breach(wall, pr.min_wall), "gears.hub_wall_mm",
        f"the gears' walls around their bores; use hub_wall_mm ≥ {pr.min_wall + params.hub_wall - wall:.2f}")
    wall = params.boss_wall - jn.press_clearance / 2 - HOLE_EXCESS
    add(wall_breach(wall, pr.min_wall), "plates.boss_wall_mm",
        f"the plates' and the crank's walls around their D-holes; use boss_wall_mm ≥ "
        f"{pr.min_wall + params.boss_wall - wall:.2f}")
    least = params.checks.min_clearance
    if jn.axial_gap < least - 1e-9:
        # stacked layers (a gear under the next link's plate) stand the axial gap apart: the check
        # holds every pair of parts that must not touch to its least clearance
        out.append(design_finding("warn", "clearance", f"the axial gap between stacked layers is {jn.axial_gap:g} mm, "
                                  f"under the {least:g} mm the check holds parts apart: use joints.axial_gap_mm ≥ "
                                  f"{least:g} (or checks.min_clearance_mm ≤ {jn.axial_gap:g})", "joints.axial_gap_mm"))
    if jn.running_clearance / 2 < HOLE_EXCESS:
        # a turning pin's facets sweep past its bore's: under the facets' depth they can meet
        out.append(design_finding("warn", "fit", f"running clearance {jn.running_clearance / 2:.3f} mm radial is under "
                                  f"the {HOLE_EXCESS:g} mm the round features' facets may stand proud: a turning joint "
                                  "can bind on its facets (the check measures it); use at least "
                                  f"{HOLE_EXCESS:g} mm radial ({2 * HOLE_EXCESS:g} mm diametral)", "joints"))
    if belts is not None:
        wall = belts.tensioner_radius - params.bore / 2 - HOLE_EXCESS
        add(wall_breach(wall, pr.min_wall), "belts.tensioner_radius_mm",
            f"the tensioner rollers' walls around their bores; use tensioner_radius_mm ≥ "
            f"{pr.min_wall + belts.tensioner_radius - wall:.2f}")
    return out


def drive_findings(G1: GearSpec, drive: GearSpec, rules: GearRules) -> list[Finding]:
    """Warnings for the drive pair (teeth given by ``drive.teeth``): the rules it breaks."""
    broken = gear_breaches(G1, rules, f"G1 and the drive gear ({G1.teeth})") + mesh_breaches(
        G1, drive, centre_distance(G1, drive), rules, ("G1", "the drive gear"))
    return [design_finding("warn", b.rule, f"drive: {b.message}", "drive.teeth") for b in broken]


def _drive(params: ChainParams) -> tuple[GearSpec, GearSpec, tuple[float, float]]:
    """G1 and the drive gear (same teeth: one crank turn per cycle) and where the drive sits."""
    G1 = make_gear(params.drive_teeth, params.system)
    check_generable(G1)
    if 2 * G1.root_radius < params.min_root_diameter:
        need = next(z for z in range(params.drive_teeth, 100_000)
                    if 2 * make_gear(z, params.system).root_radius >= params.min_root_diameter)
        raise DesignError(f"a {params.drive_teeth}-tooth drive gear and G1 at module {params.system.module:g} mm have a "
                          f"root circle of Ø{2 * G1.root_radius:.2f} mm, too small for the Ø{params.bore:.2f} mm bore "
                          f"and {params.hub_wall:g} mm hub wall: give at least {need} teeth", "drive.teeth")
    a = centre_distance(G1, G1)
    return G1, G1, (a * math.cos(params.drive_angle), a * math.sin(params.drive_angle))


def _belt_mechanism(inputs: MechanismInputs, params: ChainParams, ratios, findings) -> ChainDesign:
    """Belt stages for every coupled link; a link without room for a tensioner changes length."""
    from dataclasses import replace as _replace

    b = inputs.belts
    # the smallest pulley whose grooves leave a hub wall around the bore
    z_min = 10
    while True:
        root = pitch_diameter_belt(z_min, b.profile) / 2 - b.profile.pitch_line_offset - b.profile.groove_depth
        if root >= params.min_root_diameter / 2:
            break
        z_min += 1
    links = list(inputs.chain.links)
    stages = []
    for j, (link, r) in enumerate(zip(links, ratios), 1):
        side = -1 if (0 if j == 1 else links[j - 2].speed) - link.speed > 0 else 1  # the slack span
        st = _replace(design_belt_stage(j, link.length, r, b.profile, b.stock_teeth, z_min, b.flange_height,
                                        b.tensioner_radius, b.tensioner_gap, side), settings=b)
        stages.append(st)
        if st.tensioner is None:
            links[j - 1] = _replace(link, length=st.length)
            findings.append(design_finding("info", "belt-link", f"link {j} ({link.name}): no room for a tensioner; the link is "
                                    f"{st.link_change:+.3f} mm so a {st.belt_teeth}-tooth belt fits", "belts"))
    G1, drive, drive_centre = _drive(params)
    findings += drive_findings(G1, drive, gear_rules(params)) + kit_findings(params, b)
    chain = Chain(tuple(links), inputs.chain.offset)
    return ChainDesign(chain, (), G1, drive, drive_centre, tuple(findings), inputs.curve, inputs.scale, inputs.dropped,
                     True, inputs.source, tuple(stages), inputs.chain, inputs.drawing)
