"""The rules a printable gear kit is held to, in one place: what every automatic choice (``teeth:
auto``, the automatic profile shift) chooses by, what ``build`` warns about for a design given by
hand, and what ``partgen check`` measures the built kit against (pure math: mm, rad).

Each rule has a code (the ``rule`` of a check's finding and the ``code`` of a build warning, so a
check failure can be traced to the warning that announced it):

==================== ============================================================================
tip-root             the tip of each gear of a mesh clears the root of its mate by ≥ 0.05 module
contact-ratio        a mesh's transverse contact ratio is ≥ ``checks.min_contact_ratio``
involute             the mate's tip meets a gear's flank on its involute, not below its form radius
backlash             a mesh has backlash ≥ 0 at its centre distance (to 1e-6 mm)
tip-width            a gear's tooth tip is ≥ ``checks.min_tip_width_roads`` printer roads wide
wall                 the material between a hole and the part's edge is ≥ min_wall_lines × line_width_mm
hole                 a hole that runs on a pin or axle is ≥ the printer's min_hole_diameter_mm
hole-to-size         a hole held to size (a press-fit D, a pen bore, a pocket) is ≥
                     min_hole_to_size_diameter_mm
==================== ============================================================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

from ..core.quantise import quantise
from ..errors import DesignError
from . import involute
from .gearing import GearSpec

__all__ = ["TIP_ROOT_COEFF", "CODES", "GearRules", "Breach", "check_generable", "ToothSystemError", "tip_root_clearance", "contact_ratio", "form_radius",
           "mate_contact_radius", "mesh_breaches", "gear_breaches", "hole_breach", "wall_breach", "gear_rules"]

TIP_ROOT_COEFF = 0.05  # × module: the least clearance between a tip and its mate's root
BACKLASH_TOL = 1e-6  # mm: backlash this close to zero is zero, not interference

CODES = ("tip-root", "contact-ratio", "involute", "backlash", "tip-width", "wall", "hole", "hole-to-size")


@dataclass(frozen=True)
class GearRules:
    """What a gear and a mesh must meet (mm).

    min_contact_ratio : ``checks.min_contact_ratio``.
    min_tip_width : ``checks.min_tip_width_roads`` × the printer's line_width_mm.
    tip_root_coeff : least tip-to-root clearance, × module.
    """

    min_contact_ratio: float
    min_tip_width: float
    tip_root_coeff: float = TIP_ROOT_COEFF


@dataclass(frozen=True)
class Breach:
    """A rule a design breaks: its code, the words for it, the value found and the limit."""

    rule: str
    message: str
    value: float
    limit: float


def tip_root_clearance(tip: GearSpec, root: GearSpec, a: float) -> float:
    """Radial clearance between ``tip``'s tip circle and ``root``'s root circle at centre
    distance ``a``, mm."""
    return a - tip.tip_radius - root.root_radius


def contact_ratio(g1: GearSpec, g2: GearSpec, a: float) -> float:
    """Transverse contact ratio of the pair at centre distance ``a`` (0 if they cannot mesh)."""
    s = g1.system
    try:
        return involute.contact_ratio(g1.teeth, g2.teeth, s.module, s.pressure_angle, g1.profile_shift,
                                      g2.profile_shift, a, s.addendum_coeff)
    except ValueError:
        return 0.0


@lru_cache(maxsize=4096)
def _coarse_outline(g: GearSpec) -> involute.GearOutline | involute.OutlineError | ValueError:
    s = g.system
    try:
        return involute.gear_outline(g.teeth, s.module, s.pressure_angle, g.profile_shift, s.backlash_per_gear,
                                     s.addendum_coeff, s.dedendum_coeff, s.cutter_tip_coeff, tol=0.05)
    except ValueError as e:
        return e


class ToothSystemError(DesignError):
    """A gear the tooth system cannot make; ``field``: the ``ToothSystem`` field to change ("" if none)."""

    def __init__(self, problem: str, field: str = ""):
        super().__init__(problem)
        self.field = field


def check_generable(gear: GearSpec) -> None:
    """Raise ``ToothSystemError`` (naming the ``ToothSystem`` field, which the mechanism's resolver
    maps to its config key) if the rack cannot generate this gear: cutter tip fillets that overlap,
    a tip inside the base circle, a pointed tooth."""
    out = _coarse_outline(gear)
    if isinstance(out, ValueError):
        raise ToothSystemError(f"a {gear.teeth}-tooth gear (x = {gear.profile_shift:.4g}) cannot be generated: {out}",
                               getattr(out, "field", ""))


def form_radius(g: GearSpec) -> float:
    """Radius where ``g``'s generated involute flank starts (above the fillet or the undercut), mm.

    The rack's straight flank ends where its tip fillet (radius ρm) meets it, ρm(1 − sin α) above
    its tip line: w_f = (x − h_f + ρ(1 − sin α))·m from the gear's pitch circle. That point is in
    contact on the line of action −w_f/sin α from the pitch point, so the flank starts at
    √(r_b² + (r_p sin α + w_f / sin α)²) (equal to design.involute.gear_outline's to 1e-14 mm).
    When that falls inside the base circle the gear is undercut, and the crossing of trochoid and
    involute is found on the generated outline. Raises DesignError for a gear the rack cannot
    generate."""
    s = g.system
    sa = math.sin(s.pressure_angle)
    w_f = (g.profile_shift - s.dedendum_coeff + s.cutter_tip_coeff * (1.0 - sa)) * s.module
    along = g.pitch_radius * sa + w_f / sa
    if along > 1e-9:
        return math.hypot(g.pitch_radius * math.cos(s.pressure_angle), along)
    check_generable(g)
    return _coarse_outline(g).form_radius


def mate_contact_radius(g: GearSpec, mate: GearSpec, a: float) -> float:
    """Radius on ``g`` where the mate's tip meets the line of action at centre distance ``a``
    (the lowest point of ``g``'s flank in contact), mm; -1 when it falls inside g's base circle."""
    s = g.system
    rb, rb_m = g.pitch_radius * math.cos(s.pressure_angle), mate.pitch_radius * math.cos(s.pressure_angle)
    aw = math.acos(min(1.0, (rb + rb_m) / a))
    along = a * math.sin(aw) - math.sqrt(max(mate.tip_radius ** 2 - rb_m ** 2, 0.0))
    return math.hypot(rb, along) if along > 0 else -1.0


def mesh_breaches(g1: GearSpec, g2: GearSpec, a: float, rules: GearRules, names: tuple[str, str] = ("", "")
                  ) -> list[Breach]:
    """The mesh rules the pair (g1, g2) at centre distance ``a`` breaks: tip-root both ways,
    backlash, contact ratio, involute interference both ways. ``names`` label the gears."""
    n1, n2 = (n or f"{g.teeth} teeth" for n, g in zip(names, (g1, g2)))
    s = g1.system
    out = []
    need = rules.tip_root_coeff * s.module
    for (tn, tg), (rn, rg) in (((n1, g1), (n2, g2)), ((n2, g2), (n1, g1))):
        c = tip_root_clearance(tg, rg, a)
        if quantise(c) < quantise(need):  # at 1e-6 mm: a clearance designed equal to the rule meets it on any machine
            out.append(Breach("tip-root", f"tip of {tn} clears the root of {rn} by only {c:.3f} mm "
                              f"(< {need:.3f} mm, {rules.tip_root_coeff:g} module)", c, need))
    try:
        j = involute.circumferential_backlash(g1.teeth, g2.teeth, s.module, s.pressure_angle, g1.profile_shift,
                                              g2.profile_shift, s.backlash_per_gear, g2.system.backlash_per_gear, a)
    except ValueError:
        j = -math.inf
    if j < -BACKLASH_TOL:  # a designed backlash of 0 is met (exact arithmetic leaves ±1e-12 mm)
        out.append(Breach("backlash", f"no backlash ({j:.3f} mm) at centre distance {a:.3f} mm", j, 0.0))
        return out
    eps = contact_ratio(g1, g2, a)
    if quantise(eps) < quantise(rules.min_contact_ratio):
        out.append(Breach("contact-ratio", f"contact ratio {eps:.3f} < {rules.min_contact_ratio:g}", eps,
                          rules.min_contact_ratio))
    for (gn, g), mate in (((n1, g1), g2), ((n2, g2), g1)):
        r_c, r_f = mate_contact_radius(g, mate, a), form_radius(g)
        if r_c < r_f - 1e-6:
            out.append(Breach("involute", f"the mate's tip meets {gn} at r = {r_c:.3f} mm, below its form "
                              f"radius {r_f:.3f} mm (involute interference)", r_c - r_f, 0.0))
    return out


def gear_breaches(g: GearSpec, rules: GearRules, name: str = "") -> list[Breach]:
    """The rules one gear breaks on its own: the tooth tip's width in printer roads."""
    tip = g.tip_thickness
    if tip < rules.min_tip_width - 1e-9:
        return [Breach("tip-width", f"{name or f'{g.teeth} teeth'}: tooth tips {tip:.3f} mm wide, under "
                       f"{rules.min_tip_width:.3f} mm: use gears.module_mm ≥ {module_for_tip(g, rules.min_tip_width):.3g} "
                       "(tips grow with the module), or fewer checks.min_tip_width_roads, or a printer with a "
                       "narrower line", tip, rules.min_tip_width)]
    return []


def module_for_tip(g: GearSpec, width: float) -> float:
    """The module (mm) at which ``g``'s tooth tips are ``width`` mm wide, its teeth and profile shift
    kept: the tip thickness is affine in the module (the backlash share is fixed in mm)."""
    from dataclasses import replace

    m = g.system.module
    t1 = g.tip_thickness
    t2 = replace(g, system=replace(g.system, module=2 * m)).tip_thickness
    slope = (t2 - t1) / m
    return m + (width - t1) / slope if slope > 0 else math.inf


def hole_breach(diameter: float, runs: bool, min_hole: float, min_hole_to_size: float) -> Breach | None:
    """A hole of ``diameter`` mm against its rule: ``runs`` (on a pin or axle) → the printer's
    smallest reliable joint hole; otherwise (a press-fit D, a pen bore, a pocket) → the smallest
    hole it holds to size."""
    if runs and diameter < min_hole - 1e-6:
        return Breach("hole", f"a hole of Ø{diameter:.2f} mm that runs on a pin is under the printer's smallest "
                      f"reliable joint hole Ø{min_hole:g} mm (its min_hole_diameter_mm)", diameter, min_hole)
    if not runs and diameter < min_hole_to_size - 1e-6:
        return Breach("hole-to-size", f"a hole of Ø{diameter:.2f} mm is under the smallest hole the printer holds "
                      f"to size, Ø{min_hole_to_size:g} mm (its min_hole_to_size_diameter_mm)", diameter, min_hole_to_size)
    return None


def wall_breach(wall: float, min_wall: float) -> Breach | None:
    """A wall of ``wall`` mm against the printer's thinnest wall."""
    if wall < min_wall - 1e-6:
        return Breach("wall", f"a wall of {wall:.2f} mm is under the printer's {min_wall:g} mm (min_wall_lines × "
                      "line_width_mm)", wall, min_wall)
    return None


def gear_rules(params) -> GearRules:
    """The gear and mesh rules of any kit with gears: its check settings (``params.checks``:
    ``min_contact_ratio``, ``min_tip_width_roads``) on its printer (``params.printer.line_width``, mm)."""
    return GearRules(params.checks.min_contact_ratio, params.checks.min_tip_width_roads * params.printer.line_width)
