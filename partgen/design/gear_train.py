"""Gear trains from a table of stages (pure math: numpy and the standard library; mm, rad).

A train is a row of shafts 0..n joined by n stages; stage k meshes a driver on shaft k with a driven
gear on shaft k+1. A stage gives its tooth counts, or a ratio to meet (whole teeth, the smallest
error or exactly, within tooth-count limits), or a centre distance to meet (the profile shifts that
make the working centre distance exactly it), and an overall ratio may be split over the stages that
give nothing. Consecutive stages are *compound* (the driven gear of stage k and the driver of stage
k+1 are two gears fixed on one shaft) unless a stage says ``idler``: then the driven gear of stage k
drives stage k+1 itself (an idler: it turns the sense back and adds no ratio of its own).

Ratios are speed ratios input / output (> 1 reduces speed). A stage's ratio is z_driven / z_driver.

Profile shifts for a centre distance (ISO 21771's relations): at centre distance a the working
pressure angle is cos α_w = (m (z1 + z2) / 2) cos α / a, and a zero-backlash mesh there needs
x1 + x2 = (inv α_w − inv α)(z1 + z2) / (2 tan α). The sum is split with the pinion taking more
(``split_shift``), each gear kept at least at its undercut-free shift.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from ..core.quantise import quantise
from ..errors import DesignError
from . import involute

__all__ = ["TeethLimits", "StageTarget", "StageTeeth", "teeth_for_ratio", "split_ratio", "shift_sum_for_centre_distance",
           "split_shift", "shifts_for_centre_distance", "centre_distance_range", "solve_train", "train_ratio",
           "shaft_speeds", "mesh_phase", "Transverse", "transverse_system", "overlap_ratio", "twist_over"]


@dataclass(frozen=True)
class TeethLimits:
    """Tooth counts a stage may use (inclusive) and, optionally, the largest reference pitch diameter (mm)."""

    min_teeth: int = 12
    max_teeth: int = 100
    max_pitch_diameter: float = math.inf
    module: float = 1.0

    def allowed(self, z: int) -> bool:
        return self.min_teeth <= z <= self.max_teeth and self.module * z <= self.max_pitch_diameter + 1e-9

    @property
    def top(self) -> int:
        return min(self.max_teeth, int(math.floor(self.max_pitch_diameter / self.module + 1e-9))
                   if math.isfinite(self.max_pitch_diameter) else self.max_teeth)


@dataclass(frozen=True)
class StageTarget:
    """What the table asks of one stage (``None``: not given).

    teeth : (z_driver, z_driven); ratio : z_driven / z_driver to meet; exact : meet it exactly;
    centre_distance : mm, met by profile shift; idler : the previous stage's driven gear drives this
    stage itself (its ``teeth[0]`` must be that gear's).
    """

    teeth: tuple[int, int] | None = None
    ratio: float | None = None
    exact: bool = False
    centre_distance: float | None = None
    idler: bool = False


@dataclass(frozen=True)
class StageTeeth:
    """A resolved stage: tooth counts, and the profile shifts a centre distance asks for (None: the
    tooth system's own)."""

    driver: int
    driven: int
    shifts: tuple[float, float] | None = None
    idler: bool = False

    @property
    def ratio(self) -> Fraction:
        return Fraction(self.driven, self.driver)


def _pairs_for_ratio(ratio: float, lim: TeethLimits):
    """Every (z1, z2) within the limits with z2 the nearest whole teeth to ratio·z1 (and the one
    either side), as (relative error, size z1 + z2, z1, z2)."""
    out = []
    for z1 in range(lim.min_teeth, lim.top + 1):
        base = ratio * z1
        for z2 in {math.floor(base), math.ceil(base)}:
            if lim.allowed(z2):
                out.append((quantise(abs(z2 / z1 - ratio) / ratio, 1e-12), z1 + z2, z1, z2))  # error to 1e-12
    return sorted(out)


def teeth_for_ratio(ratio: float, lim: TeethLimits, exact: bool = False, key: str = "") -> tuple[int, int]:
    """(z_driver, z_driven) with z_driven / z_driver nearest ``ratio``: the smallest relative error,
    then the smallest pair. ``exact``: the ratio (a decimal, read as the fraction it writes) must be
    met exactly. DesignError naming ``key`` and the nearest ratios that work when none can."""
    if not (math.isfinite(ratio) and ratio > 0):
        raise DesignError(f"a ratio must be a positive number, got {ratio!r}", key)
    pairs = _pairs_for_ratio(ratio, lim)
    if exact:
        target = Fraction(str(ratio)).limit_denominator(10 ** 6)
        hit = [p for p in pairs if Fraction(p[3], p[2]) == target]
        if hit:
            return hit[0][2], hit[0][3]
        near = sorted({Fraction(p[3], p[2]) for p in pairs[:40]}, key=lambda f: abs(f - target))[:3]
        raise DesignError(f"no whole teeth in {lim.min_teeth}–{lim.top} give the ratio {target} exactly "
                          f"(nearest: {', '.join(f'{f} = {float(f):.4f}' for f in near)}); drop exact, or widen the "
                          "tooth-count limits", key)
    if not pairs:
        raise DesignError(f"no whole teeth in {lim.min_teeth}–{lim.top} reach the ratio {ratio:g} (at most "
                          f"{lim.top / lim.min_teeth:.3f} per stage): more stages or wider tooth-count limits", key)
    return pairs[0][2], pairs[0][3]


def split_ratio(total: float, stages: int) -> list[float]:
    """An overall ratio split evenly (geometrically) over ``stages`` stages: total ** (1 / stages) each."""
    return [total ** (1.0 / stages)] * stages


def _best_product(ratios: list[float], total: float, lim: TeethLimits, exact: bool, keep: int = 12):
    """Teeth for the free stages so that their product of ratios is nearest ``total`` (the earlier
    stages from their ``keep`` best candidates near their share, the last one solved for the rest)."""
    target = Fraction(str(total)).limit_denominator(10 ** 6) if exact else None
    best = None

    def walk(k: int, acc: Fraction, chosen: list):
        nonlocal best
        if k == len(ratios) - 1:
            rest = total / float(acc)
            pairs = _pairs_for_ratio(rest, lim)
            if target is not None:
                pairs = [p for p in pairs if acc * Fraction(p[3], p[2]) == target]
            if not pairs:
                return
            p = pairs[0]
            got = float(acc) * p[3] / p[2]
            score = (quantise(abs(got - total) / total, 1e-12), sum(a + b for a, b in chosen) + p[1])  # ties: fewer teeth, then the first found
            if best is None or score < best[0]:
                best = (score, chosen + [(p[2], p[3])])
            return
        for p in _pairs_for_ratio(ratios[k], lim)[:keep]:
            walk(k + 1, acc * Fraction(p[3], p[2]), chosen + [(p[2], p[3])])

    walk(0, Fraction(1), [])
    return None if best is None else best[1]


def shift_sum_for_centre_distance(z1: int, z2: int, m: float, alpha: float, a: float, internal: bool = False) -> float:
    """x1 + x2 (x2 − x1 for an internal mesh, z2 the ring) a zero-backlash mesh needs to run at
    centre distance ``a`` (mm): (inv α_w − inv α)(z2 ± z1) / (2 tan α), cos α_w = a₀ cos α / a."""
    zs = (z2 - z1) if internal else (z1 + z2)
    a0 = m * zs / 2.0
    c = a0 * math.cos(alpha) / a
    if not 0.0 < c < 1.0:
        raise ValueError(f"a = {a!r} mm is inside the base circles' reach ({a0 * math.cos(alpha):.4f} mm)")
    aw = math.acos(c)
    return (involute.inv(aw) - involute.inv(alpha)) * zs / (2.0 * math.tan(alpha))


def split_shift(total: float, z1: int, z2: int, alpha: float, ha: float = 1.0) -> tuple[float, float]:
    """Split x1 + x2 = ``total``: the pinion takes more, x1 = total/2 + 0.5 (z2 − z1)/(z1 + z2) ·
    min(1, |total| + 0.5) (ratio-weighted, evening out the specific sliding as the usual charts
    do), then both are lifted to their undercut-free shift if the sum allows."""
    lean = 0.5 * (z2 - z1) / (z1 + z2) * min(1.0, abs(total) + 0.5)
    x1 = total / 2.0 + lean
    x2 = total - x1
    m1, m2 = involute.min_profile_shift(z1, alpha, ha), involute.min_profile_shift(z2, alpha, ha)
    if x1 < m1:
        x1, x2 = m1, total - m1
    if x2 < m2:
        x2, x1 = m2, total - m2
    return x1, x2


def shifts_for_centre_distance(z1: int, z2: int, m: float, alpha: float, a: float, fixed1: float | None = None,
                               ha: float = 1.0) -> tuple[float, float]:
    """(x1, x2) with which the pair (z1, z2) meshes without backlash at exactly ``a`` mm (then
    thinning alone gives the backlash). ``fixed1``: x1 is given (an idler's shift, set by its other
    mesh); only x2 is solved."""
    total = shift_sum_for_centre_distance(z1, z2, m, alpha, a)
    if fixed1 is not None:
        return fixed1, total - fixed1
    return split_shift(total, z1, z2, alpha, ha)


def centre_distance_range(z1: int, z2: int, m: float, alpha: float, x_min: float, x_max: float) -> tuple[float, float]:
    """The centre distances (mm) the pair reaches with each shift in [x_min, x_max]."""
    def cd(x: float) -> float | None:
        try:
            return involute.centre_distance(z1, z2, m, alpha, x, x)
        except ValueError:
            return None
    lo = cd(x_min)
    x = x_min
    while lo is None and x < x_max:  # a sum so negative no working pressure angle exists: the least that has one
        x = min(x + 0.01, x_max)
        lo = cd(x)
    return lo if lo is not None else math.inf, cd(x_max) or -math.inf


def _cd_pair(target: StageTarget, m: float, alpha: float, lim: TeethLimits, x_range, key: str) -> tuple[int, int]:
    """Teeth for a stage that gives a centre distance and a ratio: the pair nearest the ratio whose
    reference centre distance m(z1 + z2)/2 the allowed shifts can move onto the target, preferring
    a pair the shifts spread apart (x1 + x2 ≥ 0) and then the least shift."""
    a = target.centre_distance
    cands = []
    for err, size, z1, z2 in _pairs_for_ratio(target.ratio, lim):
        if target.exact and Fraction(z2, z1) != Fraction(str(target.ratio)).limit_denominator(10 ** 6):
            continue
        lo, hi = centre_distance_range(z1, z2, m, alpha, *x_range)
        if lo - 1e-9 <= a <= hi + 1e-9:
            a0 = m * (z1 + z2) / 2  # a pair spread apart (x1 + x2 ≥ 0) before one pulled in: a negative sum
            cands.append((err, a0 > a + 1e-9, quantise(abs(a0 - a)), z1, z2))  # thins the teeth and lowers α_w
    if not cands:
        zs = 2 * a / m
        raise DesignError(f"no whole teeth near the ratio {target.ratio:g} reach the centre distance {a:g} mm with "
                          f"shifts in [{x_range[0]:g}, {x_range[1]:g}] (module {m:g} mm wants z1 + z2 near "
                          f"{zs:.1f}): change the ratio, the centre distance or the module", key)
    cands.sort()
    return cands[0][3], cands[0][4]


def solve_train(targets: list[StageTarget], lim: TeethLimits, m: float, alpha: float, overall: float | None = None,
                overall_exact: bool = False, x_range: tuple[float, float] = (-0.5, 1.0), ha: float = 1.0,
                key: str = "train", default_shift=None) -> list[StageTeeth]:
    """Tooth counts (and shifts for centre distances) of every stage.

    targets : one per stage; overall : the train's ratio, split over the stages that give neither
    teeth nor a ratio (``overall_exact``: met exactly). Raises DesignError naming the key path
    (``train.stages[1].ratio``) with the nearest values that work. ``default_shift(z)``: the shift
    of a gear whose stage solves none (an idler's, whose next stage gives a centre distance)."""
    if not targets:
        raise DesignError("a train needs at least one stage", f"{key}.stages")
    fixed: dict[int, tuple[int, int]] = {}
    free = []
    for k, t in enumerate(targets):
        kk = f"{key}.stages[{k}]"
        if t.idler and k == 0:
            raise DesignError("the first stage has no stage before it to be an idler of", f"{kk}.idler")
        if t.teeth is not None:
            z1, z2 = t.teeth
            for z, which in ((z1, 0), (z2, 1)):
                if not lim.allowed(z):
                    raise DesignError(f"{z} teeth is outside the tooth-count limits {lim.min_teeth}–{lim.top}",
                                      f"{kk}.teeth[{which}]")
            fixed[k] = (z1, z2)
        elif t.ratio is not None and t.centre_distance is not None:
            fixed[k] = _cd_pair(t, m, alpha, lim, x_range, f"{kk}.centre_distance_mm")
        elif t.ratio is not None:
            fixed[k] = teeth_for_ratio(t.ratio, lim, t.exact, f"{kk}.ratio")
        elif t.centre_distance is not None:
            raise DesignError("a centre distance alone does not say the teeth: give teeth or a ratio too",
                              f"{kk}.centre_distance_mm")
        elif t.idler:
            raise DesignError("an idler stage needs its teeth or a ratio", kk)
        else:
            free.append(k)
    if free:
        if overall is None:
            raise DesignError(f"stage {free[0]} gives no teeth and no ratio, and the train gives no overall ratio to "
                              "split", f"{key}.stages[{free[0]}]")
        done = 1.0
        for k, (z1, z2) in fixed.items():
            done *= z2 / z1
        rest = overall / done
        got = _best_product(split_ratio(rest, len(free)), rest, lim, overall_exact) if overall_exact else \
            _best_product(split_ratio(rest, len(free)), rest, lim, False)
        if got is None:
            raise DesignError(f"no whole teeth in {lim.min_teeth}–{lim.top} over {len(free)} free stage(s) give the "
                              f"overall ratio {overall:g} exactly: drop ratio_exact, add a stage or widen the limits",
                              f"{key}.ratio")
        for k, zz in zip(free, got):
            fixed[k] = zz
    elif overall is not None:
        got = train_ratio([StageTeeth(*fixed[k], idler=t.idler) for k, t in enumerate(targets)])
        if overall_exact and got != Fraction(str(overall)).limit_denominator(10 ** 6):
            raise DesignError(f"the stages give {got} = {float(got):.5f}, not {overall:g}", f"{key}.ratio")
    out: list[StageTeeth] = []
    for k, t in enumerate(targets):
        z1, z2 = fixed[k]
        kk = f"{key}.stages[{k}]"
        if t.idler and z1 != out[-1].driven:
            raise DesignError(f"an idler stage is driven by the previous stage's driven gear ({out[-1].driven} teeth), "
                              f"not {z1}", f"{kk}.teeth[0]")
        shifts = None
        if t.centre_distance is not None:
            x1_fixed = out[-1].shifts[1] if (t.idler and out and out[-1].shifts) else None
            if t.idler and x1_fixed is None:
                x1_fixed = default_shift(z1) if default_shift else max(0.0, involute.min_profile_shift(z1, alpha, ha))
            try:
                shifts = shifts_for_centre_distance(z1, z2, m, alpha, t.centre_distance, x1_fixed, ha)
            except ValueError as e:
                raise DesignError(str(e), f"{kk}.centre_distance_mm") from None
            lo, hi = centre_distance_range(z1, z2, m, alpha, *x_range)
            if not (x_range[0] - 1e-9 <= min(shifts) and max(shifts) <= x_range[1] + 1e-9):
                raise DesignError(f"{z1}/{z2} teeth reach {t.centre_distance:g} mm only with shifts "
                                  f"{shifts[0]:.3f}/{shifts[1]:.3f}, outside [{x_range[0]:g}, {x_range[1]:g}]: centre "
                                  f"distances from {lo:.3f} to {hi:.3f} mm work", f"{kk}.centre_distance_mm")
        out.append(StageTeeth(z1, z2, shifts, t.idler))
    return out


def train_ratio(stages: list[StageTeeth]) -> Fraction:
    """The train's speed ratio input / output (magnitude): the product of the stages' ratios."""
    r = Fraction(1)
    for s in stages:
        r *= s.ratio
    return r


def shaft_speeds(stages: list[StageTeeth], internal: tuple[bool, ...] = ()) -> list[Fraction]:
    """Signed speed of every shaft per unit speed of the input (shaft 0): an external mesh turns the
    sense, an internal one keeps it. An idler shaft is still one shaft."""
    out = [Fraction(1)]
    for k, s in enumerate(stages):
        sign = 1 if (k < len(internal) and internal[k]) else -1
        out.append(out[-1] * sign * Fraction(s.driver, s.driven))
    return out


def mesh_phase(psi_driver: float, z_driver: int, z_driven: int, direction: float, internal: bool = False) -> float:
    """The driven gear's angle (rad) that puts a tooth space of it on a tooth of the driver, for the
    driver at ``psi_driver`` (tooth 0 of each gear on its local +x).

    External: ``direction`` (rad) is the driven centre's from the driver's. With u = (ψ_d − β) z_d / 2π
    (the driver's tooth phase on the line of centres) and v = (ψ_n − β − π) z_n / 2π (the driven's,
    facing back), rolling keeps u + v; a tooth in a space is u + v ≡ ½.
    Internal (the driven is a ring round the driver, its tooth *space* 0 on its local +x, see
    design.planetary): ``direction`` is the driver's centre seen from the ring's, which is where they
    mesh; the ring's space must face the driver's tooth along it, v = (ψ_n − β) z_n / 2π, and rolling
    inside keeps u − v: u − v ≡ 0."""
    u = (psi_driver - direction) * z_driver / (2 * math.pi)
    if internal:
        return direction + 2 * math.pi * u / z_driven
    return direction + math.pi + 2 * math.pi * (0.5 - u) / z_driven


@dataclass(frozen=True)
class Transverse:
    """A helical gear's tooth system in its transverse plane (the plane the outline is generated in):
    module (mm), pressure angle (rad), addendum, dedendum and cutter tip radius coefficients (× the
    transverse module), and the factor a normal profile shift coefficient is multiplied by."""

    module: float
    pressure_angle: float
    addendum_coeff: float
    dedendum_coeff: float
    cutter_tip_coeff: float
    shift_factor: float


def transverse_system(module: float, alpha: float, beta: float, system: str = "normal", ha: float = 1.0,
                      hf: float = 1.25, rho: float = 0.38) -> Transverse:
    """The transverse tooth system of a helical gear of helix angle ``beta`` (rad, at the reference
    cylinder). ``system`` says what ``module`` and ``alpha`` are: ``normal`` (a standard hob's: m_t =
    m_n / cos β, tan α_t = tan α_n / cos β; addendum, dedendum and shift keep their mm, so their
    coefficients × cos β; the cutter's tip fillet keeps its radius in mm (its transverse section is
    an ellipse: the fillet is the one approximation, the flanks are exact involutes)) or
    ``transverse`` (already the transverse values)."""
    if system == "transverse" or beta == 0.0:
        return Transverse(module, alpha, ha, hf, rho, 1.0)
    c = math.cos(beta)
    return Transverse(module / c, math.atan(math.tan(alpha) / c), ha * c, hf * c, rho * c, c)


def overlap_ratio(face_width: float, beta: float, normal_module: float) -> float:
    """Overlap (face) contact ratio ε_β = b sin β / (π m_n) of a helical mesh of face width b (mm)."""
    return face_width * math.sin(abs(beta)) / (math.pi * normal_module)


def twist_over(face_width: float, beta: float, pitch_radius: float) -> float:
    """How far (rad) a helical gear's transverse section turns over ``face_width`` mm: b tan β / r."""
    return face_width * math.tan(beta) / pitch_radius
