"""The gear train of a serial chain: Eq 11 ratios, tooth counts, mesh conditions, idler placement.

Stage j (j = 1..n-1) lives on link B_j of centre distance S_j: gear D_j (fixed to B_{j-1}, D_1 to
the base) at the proximal joint drives G_{j+1} (fixed to B_{j+1}) at the distal joint through an
idler M_j on a pin of B_j. Positions are in the link frame: proximal joint at (0, 0), distal joint
at (S, 0), +v to the left of the link (counter-clockwise). mm, rad.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, replace
from functools import lru_cache
from fractions import Fraction
from typing import Sequence

from ..core.findings import Finding
from ..core.quantise import quantise
from ..errors import DesignError
from .gearing import GearSpec, ToothSystem, centre_distance, make_gear
from .rules import Breach, GearRules, ToothSystemError, check_generable, gear_breaches, mesh_breaches

__all__ = [
    "Limits", "Stage", "Finding", "eq11_ratios", "idler_centre", "make_stage",
    "choose_stage", "verify_stage", "stage_breaches", "module_grid", "MODULE_GRID", "MODULE_RANGE",
]


@dataclass(frozen=True)
class Limits:
    """What a printable stage must respect (mm).

    min_pitch_diameter : the printer's smallest reliable gear.
    min_root_diameter : room for a gear's bore and hub wall (bore + 2·hub wall).
    tip_gap : margin by which D's and G's tip circles must clear (Eq 12 with margin).
    idler_reach : margin by which a_DM + a_MG must exceed S (Eq 13 with margin: an idler
        exactly in line with D and G has no margin at all).
    rules : tip-to-root clearance, contact ratio, involute interference, tip width (design.rules).
    """

    min_pitch_diameter: float
    min_root_diameter: float
    tip_gap: float
    idler_reach: float
    rules: GearRules | None = None  # the mesh and gear rules `partgen check` holds the kit to
    axle_diameter: float = 0.0  # the joints' axle (``joints.axle_diameter_mm``): the bore grows with it
    min_axle_diameter: float = 0.0  # the smallest axle whose running bore the printer still makes
    advise: bool = True  # a refusal computes the settings that would work (off while a search tries many)


def design_finding(severity: str, rule: str, message: str, key: str = "") -> Finding:
    """A design rule's verdict as the one ``Finding``: check "design", severity "warn" (fails
    `check`) or "info", the rule's code and the config key it traces back to."""
    return Finding("design", severity, message, key=key, rule=rule)


@dataclass(frozen=True)
class Stage:
    """The gears of link B_j and where they sit in its frame."""

    j: int
    length: float
    ratio: Fraction
    D: GearSpec
    M: GearSpec
    G: GearSpec
    a_DM: float
    a_MG: float
    idler: tuple[float, float]

    @property
    def gears(self) -> dict[str, GearSpec]:
        return {"D": self.D, "M": self.M, "G": self.G}


def eq11_ratios(speeds: Sequence[int]) -> tuple[Fraction, ...]:
    """T_D,j / T_G,j+1 = (ω_{j+1} - ω_j)/(ω_{j-1} - ω_j), ω_0 = 0 (the base), for j = 1..n-1.

    Raises DesignError for a ratio that no pair of gears gives (zero, infinite or negative: an
    idler keeps the direction, so D and G must turn the same way relative to the link).
    """
    w = [0, *speeds]
    out = []
    for j in range(1, len(speeds)):
        num, den = w[j + 1] - w[j], w[j - 1] - w[j]
        if den == 0 or num == 0:
            raise DesignError(f"links {j} and {j + 1 if den else j - 1} turn at the same speed "
                              f"({w[j]}): Eq 11 gives no finite, non-zero gear ratio", f"links[{j - 1}].speed")
        r = Fraction(num, den)
        if r < 0:
            raise DesignError(f"Eq 11 ratio {r} on link {j} is negative: D and G would turn opposite "
                              "ways, which an idler train cannot do", f"links[{j - 1}].speed")
        out.append(r)
    return tuple(out)


def idler_centre(length: float, a_dm: float, a_mg: float, side: int = 1) -> tuple[float, float] | None:
    """Idler centre in the link frame by intersecting circles of radius a_dm about (0, 0) and a_mg
    about (length, 0); ``side`` +1 left, -1 right. None when the circles do not meet."""
    u = (length**2 + a_dm**2 - a_mg**2) / (2 * length)
    h2 = a_dm**2 - u**2
    if h2 < -1e-9 * max(a_dm, 1.0) ** 2:
        return None
    return (u, side * math.sqrt(max(h2, 0.0)))


def _clearance(centre: tuple[float, float], radius: float, obstacles) -> float:
    return min((math.dist(centre, c) - radius - r for c, r in obstacles), default=math.inf)


def make_stage(j: int, length: float, ratio: Fraction, teeth: tuple[int, int, int], system: ToothSystem,
               obstacles: Sequence[tuple[tuple[float, float], float]] = ()) -> Stage:
    """Place a stage's gears. ``obstacles`` are other circles (centre, radius) in the idler's layer,
    link frame; the idler goes on the side that keeps clearest of them (left on a tie).
    Raises DesignError when the idler cannot reach both gears."""
    D, M, G = (make_gear(t, system) for t in teeth)
    a_dm, a_mg = centre_distance(D, M), centre_distance(M, G)
    sides = [p for p in (idler_centre(length, a_dm, a_mg, s) for s in (1, -1)) if p is not None]
    if not sides:
        raise DesignError(
            f"link {j}: an idler of {M.teeth} teeth cannot reach both D ({D.teeth} teeth) and G "
            f"({G.teeth} teeth) {length:.3f} mm apart: a_DM + a_MG = {a_dm + a_mg:.3f} mm "
            f"< S (or |a_DM - a_MG| > S)", f"teeth[{j - 1}].M")
    obstacles = [((0.0, 0.0), D.tip_radius), ((length, 0.0), G.tip_radius), *obstacles]
    best = max(sides, key=lambda p: (round(_clearance(p, M.tip_radius, obstacles[2:]), 9), p[1] >= 0))
    return Stage(j, length, ratio, D, M, G, a_dm, a_mg, best)


def ratio_multiples(ratio: Fraction, min_teeth: int):
    """(T_D, T_G) = n·(numerator, denominator) for n = 1, 2, …, skipping pairs under min_teeth."""
    n = 1
    while True:
        td, tg = ratio.numerator * n, ratio.denominator * n
        n += 1
        if min(td, tg) >= min_teeth:
            yield td, tg


def _min_teeth(limits: Limits, system: ToothSystem) -> int:
    """Smallest tooth count whose pitch and root diameters respect the limits (with its shift)."""
    for z in range(4, 1000):
        g = make_gear(z, system)
        if 2 * g.pitch_radius >= limits.min_pitch_diameter - 1e-9 and 2 * g.root_radius >= limits.min_root_diameter - 1e-9:
            return z
    raise DesignError("no tooth count makes a gear large enough for its bore", "gears.module_mm")


def stage_breaches(D: GearSpec, M: GearSpec, G: GearSpec, rules: GearRules | None,
                   names: tuple[str, str, str] = ("D", "M", "G")) -> list[Breach]:
    """The rules of ``rules`` a stage breaks: its meshes D–M and M–G at their design centre
    distances, and each gear's tooth tips."""
    if rules is None:
        return []
    out = []
    for g, n in ((D, names[0]), (M, names[1]), (G, names[2])):
        out += gear_breaches(g, rules, f"{n} ({g.teeth})")
    out += mesh_breaches(D, M, centre_distance(D, M), rules, (f"{names[0]} ({D.teeth})", f"{names[1]} ({M.teeth})"))
    out += mesh_breaches(M, G, centre_distance(M, G), rules, (f"{names[1]} ({M.teeth})", f"{names[2]} ({G.teeth})"))
    return out


IDLER_TRIES = 6  # larger idlers tried when the smallest that reaches breaks a rule


@lru_cache(maxsize=65536)
def _gear_broken(g: GearSpec, rules: GearRules) -> tuple[str, ...]:
    """The rules a gear breaks on its own (a pointed tooth has a tip narrower than any rule)."""
    return tuple(b.rule for b in gear_breaches(g, rules))


@lru_cache(maxsize=65536)
def _mesh_broken(g1: GearSpec, g2: GearSpec, rules: GearRules) -> tuple[str, ...]:
    return tuple(b.rule for b in mesh_breaches(g1, g2, centre_distance(g1, g2), rules))


def _search(length: float, ratio: Fraction, system: ToothSystem, limits: Limits):
    """(best teeth or None, zmin, Counter of the rules that turned candidates away). Pure: remembered
    by what it reads (``_searched``), the Counter a fresh copy each time."""
    best, zmin, turned = _searched(length, ratio, system, limits.min_pitch_diameter, limits.min_root_diameter,
                                   limits.tip_gap, limits.idler_reach, limits.rules)
    return best, zmin, Counter(dict(turned))


@lru_cache(maxsize=16384)
def _searched(length: float, ratio: Fraction, system: ToothSystem, min_pitch_diameter: float,
              min_root_diameter: float, tip_gap: float, idler_reach: float, rules: GearRules | None):
    """``_search`` of the Limits made of these fields (the rest it does not read); the Counter as
    (rule, count) pairs in the order they were counted."""
    limits = Limits(min_pitch_diameter, min_root_diameter, tip_gap, idler_reach, rules)
    zmin = _min_teeth(limits, system)
    rules = limits.rules
    if rules is not None:  # a rack that cannot generate a gear (fillets that overlap) is the design's error
        try:
            check_generable(make_gear(zmin, system))
        except ToothSystemError as e:
            if e.field != "profile_shift":  # a pointed tooth is one gear's: tip-width
                raise
    best, best_key, turned = None, None, Counter()
    for td, tg in ratio_multiples(ratio, zmin):
        D, G = make_gear(td, system), make_gear(tg, system)
        if quantise(D.tip_radius + G.tip_radius + limits.tip_gap) > quantise(length):
            break  # Eq 12 fails from here on: every larger n only grows the gears
        if best_key is not None and max(td, tg) > best_key[0]:
            break  # every larger n only makes a larger largest gear
        if rules is not None:
            broken = _gear_broken(D, rules) or _gear_broken(G, rules)
            if broken:
                turned.update(broken)
                continue
        # the reach grows with T_M by about one module per tooth: start a little under the
        # unshifted estimate m/2 (T_D + 2 T_M + T_G) = S + reach instead of at zmin
        guess = math.floor(((length + limits.idler_reach) * 2 / system.module - td - tg) / 2) - 3
        first = None
        for tm in range(max(zmin, guess), 1000):
            if first is not None and tm > first + IDLER_TRIES:
                break
            M = make_gear(tm, system)
            if quantise(centre_distance(D, M) + centre_distance(M, G)) < quantise(length + limits.idler_reach):
                continue
            first = tm if first is None else first
            key = (max(td, tm, tg), td + tm + tg)
            if best_key is not None and key >= best_key:
                break
            if rules is not None:
                broken = _gear_broken(M, rules) or _mesh_broken(D, M, rules) or _mesh_broken(M, G, rules)
                if broken:
                    turned.update(broken)
                    continue
            best, best_key = (td, tm, tg), key
            break
    return best, zmin, tuple(turned.items())


PRINTER_RULES = {"tip-width"}  # rules of the printer, not of the gears: auto builds past them, with a warning


def choose_stage(j: int, length: float, ratio: Fraction, system: ToothSystem, limits: Limits) -> Stage:
    """``teeth: auto`` for one stage: T_D/T_G equal to the Eq 11 ratio exactly, Eq 12 and the idler's
    reach met with the margins of ``limits``, every gear at least the printable minimum, and every
    rule of ``limits.rules`` (tip-to-root clearance, contact ratio, involute interference, tip
    width) met by both meshes and all three gears — the rules `partgen check` holds the kit to.

    Among feasible choices, the one with the smallest largest gear (then the fewest teeth) wins:
    it keeps plates and gears small. (On the paper's link 1 this objective without margins gives
    exactly the paper's 80/80/40.) When the smallest idler that reaches breaks a rule, larger ones
    are tried. When only the printer's rules (``PRINTER_RULES``: tips under its lines) turn every
    candidate away, the best sound gears are chosen anyway and the caller warns (``stage_breaches``).
    Raises DesignError when no integers work, naming the rules that turned candidates away and
    settings that would work.
    """
    best, zmin, turned = _search(length, ratio, system, limits)
    if best is None and turned and set(turned) <= PRINTER_RULES:
        # only the printer's rules (tips under its lines) turned the candidates away: the gears are
        # sound, so the best of them is built and the caller warns (``stage_breaches``) with the rule
        # and the module that prints; the gears' own rules and Eq 11–13 are never given up
        best = _search(length, ratio, system, replace(limits, rules=replace(limits.rules, min_tip_width=0.0)))[0]
    if best is None:
        counts = ", ".join(f"{r} × {n}" for r, n in turned.most_common())
        why = f"; the teeth that met them broke rules `partgen check` holds the kit to ({counts})" if turned else ""
        raise DesignError(
            f"link {j} (S = {length:.3f} mm): no whole teeth give the Eq 11 ratio {ratio} with D and G "
            f"at least {zmin} teeth and their tips {limits.tip_gap:g} mm apart at module "
            f"{system.module:g} mm{why}" + (f"; {_what_works(length, ratio, system, limits)}" if limits.advise else ""),
            "teeth")
    return make_stage(j, length, ratio, best, system)


MODULE_GRID = 0.05  # mm: the step of the modules tried (``gears.module_mm: auto`` and the refusals' ranges)
MODULE_RANGE = (0.3, 5.0)  # mm: the modules tried


def module_grid(lo: float = MODULE_RANGE[0], hi: float = MODULE_RANGE[1]) -> list[float]:
    """The modules tried, largest first (mm, multiples of MODULE_GRID)."""
    n0, n1 = math.ceil(lo / MODULE_GRID - 1e-9), math.floor(hi / MODULE_GRID + 1e-9)
    return [round(n * MODULE_GRID, 4) for n in range(n1, n0 - 1, -1)]


def _ranges(values: list[float]) -> str:
    """Sorted grid values as ranges: ``0.95–1.35 mm, 2–2.2 mm``."""
    values = sorted(values)
    runs, start, prev = [], values[0], values[0]
    for v in values[1:]:
        if v - prev > MODULE_GRID * 1.5:
            runs.append((start, prev))
            start = v
        prev = v
    runs.append((start, prev))
    return ", ".join(f"{a:g} mm" if a == b else f"{a:g}–{b:g} mm" for a, b in runs)


def _what_works(length: float, ratio: Fraction, system: ToothSystem, limits: Limits) -> str:
    """Settings that would let ``choose_stage`` find teeth for this link, computed: the ISO 53 tooth
    proportions (when the rules need them), the modules that work (any direction: tip width wants a
    larger one, the bore a smaller one), the smallest scale of the link, the largest axle."""
    from dataclasses import replace

    def works(length_: float, system_: ToothSystem, limits_: Limits = limits) -> bool:
        try:
            return _search(length_, ratio, system_, limits_)[0] is not None
        except DesignError:
            return False

    std = replace(system, addendum_coeff=1.0, dedendum_coeff=1.25, cutter_tip_coeff=0.38)
    if std != system and works(length, std):  # the proportions are what breaks the rules
        return "would work: ISO 53 tooth proportions (addendum_coeff 1, dedendum_coeff 1.25, cutter_tip_radius_coeff 0.38)"
    found = []
    modules = [m for m in module_grid() if works(length, replace(system, module=m))]
    if modules:
        found.append(f"gears.module_mm in {_ranges(modules)} (or gears.module_mm: auto)")
    for f in (1.05, 1.1, 1.15, 1.2, 1.25, 1.3, 1.4, 1.5, 1.75, 2.0, 2.5, 3.0):
        if works(length * f, system):
            found.append(f"the link {f:g}× as long ({length * f:.1f} mm: the design's scale or link lengths {f:g}× larger)")
            break
    if limits.axle_diameter > 0:
        d = limits.axle_diameter
        while d - 0.5 >= limits.min_axle_diameter - 1e-9:
            d = round(d - 0.5, 4)
            if works(length, system, replace(limits, min_root_diameter=limits.min_root_diameter - (limits.axle_diameter - d),
                                             axle_diameter=d)):
                found.append(f"joints.axle_diameter_mm ≤ {d:g} (a smaller bore lets smaller gears carry it; the "
                             f"printer runs axles down to {limits.min_axle_diameter:.3g} mm)")
                break
    return ("would work: " + "; or ".join(found)) if found else \
        ("no module from {0:g} to {1:g} mm, no link up to 3× as long, no smaller axle works".format(*MODULE_RANGE))


def verify_stage(stage: Stage, limits: Limits, key: str) -> list[Finding]:
    """Every condition ``choose_stage`` guarantees, checked on a stage given explicitly."""
    out: list[Finding] = []
    D, M, G, S = stage.D, stage.M, stage.G, stage.length
    given = Fraction(D.teeth, G.teeth)
    if given != stage.ratio:
        out.append(design_finding("warn", "eq11", f"link {stage.j}: T_D/T_G = {D.teeth}/{G.teeth} = {float(given):.6f}, "
                           f"Eq 11 needs {stage.ratio} = {float(stage.ratio):.6f}: the pen will not trace the curve", key))
    gap = S - D.tip_radius - G.tip_radius
    if gap <= 0:
        out.append(design_finding("warn", "eq12", f"link {stage.j}: tip circles of D ({D.teeth}) and G ({G.teeth}) "
                           f"{'touch' if abs(gap) < 1e-9 else 'overlap'}: m/2(T_D+T_G) + 2a = {S - gap:.3f} mm, "
                           f"not < S = {S:.3f} mm (Eq 12)", key))
    elif gap < limits.tip_gap:
        out.append(design_finding("warn", "eq12-margin", f"link {stage.j}: tip circles of D and G clear by only {gap:.3f} mm "
                           f"(< {limits.tip_gap:g} mm)", key))
    m = D.module
    if not (m / 2 * (3 * D.teeth + G.teeth) >= S or m / 2 * (D.teeth + 3 * G.teeth) >= S):
        out.append(design_finding("warn", "eq13", f"link {stage.j}: Eq 13 fails, no idler as large as D or G reaches both", key))
    for name, centre, a in (("D", (0.0, 0.0), stage.a_DM), ("G", (S, 0.0), stage.a_MG)):
        d = math.dist(stage.idler, centre)
        if abs(d - a) > 1e-6:
            out.append(design_finding("warn", "idler-place", f"link {stage.j}: the idler stands {d:.3f} mm from {name}, "
                               f"the mesh needs {a:.3f} mm", key + ".idler_mm"))
    reach = stage.a_DM + stage.a_MG - S
    if reach < limits.idler_reach:
        out.append(design_finding("warn", "idler-reach", f"link {stage.j}: idler {M.teeth} reaches with {reach:.3f} mm to spare "
                           f"(< {limits.idler_reach:g} mm; 0 means D, M, G stand in one line)", key))
    for name, g in stage.gears.items():
        if 2 * g.pitch_radius < limits.min_pitch_diameter - 1e-9:
            out.append(design_finding("warn", "small-gear", f"link {stage.j}: {name} ({g.teeth} teeth) pitch diameter "
                               f"{2 * g.pitch_radius:.2f} mm < printer's smallest gear {limits.min_pitch_diameter:g} mm", key))
        if 2 * g.root_radius < limits.min_root_diameter - 1e-9:
            out.append(design_finding("warn", "bore", f"link {stage.j}: {name} ({g.teeth} teeth) root diameter "
                               f"{2 * g.root_radius:.2f} mm leaves no room for its bore and hub "
                               f"(needs {limits.min_root_diameter:g} mm)", key))
        if g.undercut:
            out.append(design_finding("info", "undercut", f"link {stage.j}: {name} ({g.teeth} teeth, x = {g.profile_shift:g}) "
                               "is undercut: the cutter removes the foot of the involute", key))
    for b in stage_breaches(D, M, G, limits.rules):
        out.append(design_finding("warn", b.rule, f"link {stage.j}: {b.message}", key))
    return out
