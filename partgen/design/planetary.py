"""Internal (ring) gears and planetary sets (pure math: mm, rad).

An internal gear's tooth spaces are the teeth of an external gear of the same tooth count (its
*space gear* E): the ring is its rim less E. E's tip circle is the ring's root circle, E's root the
ring's tip (inner) circle, E's tooth thickness the ring's space width. A profile shift x_E moves the
ring's profile outward (into the rim), as it moves E's; the thinning of the ring's teeth (its
backlash share) widens E's teeth. The flanks are the same involutes, so the ring's outline is as
exact as E's.

Internal mesh of a pinion (z1, x1) in a ring (z2 > z1, x2 = x_E): rolling inside keeps the sense of
rotation, and the involute relations hold with z2 − z1 in place of z1 + z2:
inv α_w = inv α + 2 tan α (x2 − x1)/(z2 − z1), a = m (z2 − z1)/2 · cos α / cos α_w.
Contact ratio ε = (√(r_a1² − r_b1²) − √(r_a2² − r_b2²) + a sin α_w) / (π m cos α) with r_a2 the
ring's inner tip radius.

Planetary set (ring fixed, sun input, carrier output): i = 1 + z_r / z_s; coaxial with unshifted
teeth when z_r = z_s + 2 z_p; N equally spaced planets all mesh when (z_s + z_r) / N is whole
(otherwise planets go where z_s + z_r times their angle over 2π is whole: unequal spacing).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import DesignError
from . import involute

__all__ = ["internal_working_angle", "internal_centre_distance", "internal_contact_ratio", "ring_tip_radius",
           "ring_root_radius", "PlanetaryTeeth", "planetary_teeth", "assembly_whole", "planet_angles",
           "planet_clearance", "MIN_TOOTH_DIFFERENCE", "ring_contact_on_pinion"]

MAX_RATIO_ERROR = 0.02  # a planetary ratio farther than this from the one asked is refused, not built
MIN_TOOTH_DIFFERENCE = 10  # ring minus pinion, 20° full depth: below it tip and trochoidal interference set in


def ring_tip_radius(z: int, m: float, x: float = 0.0, ha: float = 1.0) -> float:
    """Inner (tip) radius of a ring of z teeth: its space gear's root, m (z/2 − ha + x), mm."""
    return m * (z / 2.0 - ha + x)


def ring_root_radius(z: int, m: float, x: float = 0.0, hf: float = 1.25) -> float:
    """Root radius of a ring: its space gear's tip, m (z/2 + hf + x), mm."""
    return m * (z / 2.0 + hf + x)


def internal_working_angle(z1: int, z2: int, alpha: float, x1: float, x2: float) -> float:
    """Working pressure angle (rad) of pinion (z1, x1) in ring (z2, x2), zero-backlash geometry."""
    if z2 <= z1:
        raise ValueError(f"a ring of {z2} teeth cannot hold a pinion of {z1}")
    y = involute.inv(alpha) + 2.0 * math.tan(alpha) * (x2 - x1) / (z2 - z1)
    if y <= 0:
        raise ValueError("x2 − x1 too negative: no working pressure angle")
    return involute.inv_inverse(y)


def internal_centre_distance(z1: int, z2: int, m: float, alpha: float, x1: float = 0.0, x2: float = 0.0) -> float:
    """Centre distance (mm) of pinion (z1, x1) in ring (z2, x2) meshing without backlash."""
    aw = internal_working_angle(z1, z2, alpha, x1, x2)
    return m * (z2 - z1) / 2.0 * math.cos(alpha) / math.cos(aw)


def internal_contact_ratio(z1: int, z2: int, m: float, alpha: float, x1: float, x2: float, a: float,
                           ha: float = 1.0, ring_involute_radius: float | None = None) -> float:
    """Transverse contact ratio of pinion (z1, x1) in ring (z2, x2) at centre distance ``a`` (mm).
    ``ring_involute_radius``: where the ring's involute ends towards its tip (its space gear's form
    radius: the tip corners are the cutter's fillets), default its tip radius."""
    rb1, rb2 = m * z1 / 2 * math.cos(alpha), m * z2 / 2 * math.cos(alpha)
    aw = math.acos((rb2 - rb1) / a)
    ra1 = m * (z1 / 2 + ha + x1)
    ra2 = ring_involute_radius or ring_tip_radius(z2, m, x2, ha)
    if ra2 <= rb2:
        return 0.0  # the ring's tips reach inside its base circle: no involute there (tip interference)
    return (math.sqrt(ra1 ** 2 - rb1 ** 2) - math.sqrt(ra2 ** 2 - rb2 ** 2) + a * math.sin(aw)) / (math.pi * m * math.cos(alpha))


def ring_contact_on_pinion(z1: int, z2: int, m: float, alpha: float, x2: float, a: float, ha: float = 1.0,
                           ring_involute_radius: float | None = None) -> float:
    """Radius (mm) on the pinion where the ring's involute ends on the line of action (the lowest
    point of the pinion's flank in contact; -1 inside the pinion's base circle: involute
    interference). ``ring_involute_radius`` as for ``internal_contact_ratio``."""
    rb1, rb2 = m * z1 / 2 * math.cos(alpha), m * z2 / 2 * math.cos(alpha)
    aw = math.acos((rb2 - rb1) / a)
    ra2 = ring_involute_radius or ring_tip_radius(z2, m, x2, ha)
    along = math.sqrt(max(ra2 ** 2 - rb2 ** 2, 0.0)) - a * math.sin(aw)
    return math.hypot(rb1, along) if along > 0 else -1.0


@dataclass(frozen=True)
class PlanetaryTeeth:
    sun: int
    planet: int
    ring: int
    planets: int

    @property
    def ratio(self) -> float:
        """Sun input, carrier output, ring fixed: 1 + z_r / z_s."""
        return 1.0 + self.ring / self.sun


def assembly_whole(zs: int, zr: int, n: int) -> bool:
    """(z_s + z_r) / N whole: N equally spaced planets all mesh."""
    return (zs + zr) % n == 0


def planet_angles(zs: int, zr: int, n: int, equal: bool = True) -> list[float]:
    """Carrier angles (rad) of the planets: equal (2π i / N, the assembly condition must hold) or
    the nearest where (z_s + z_r) γ / 2π is whole (unequal spacing; always assembles)."""
    if equal:
        return [2 * math.pi * i / n for i in range(n)]
    step = 2 * math.pi / (zs + zr)
    return [round(i * (zs + zr) / n) * step for i in range(n)]


def planet_clearance(angles: list[float], a: float, tip_radius: float) -> float:
    """Least gap (mm) between the tip circles of neighbouring planets on the radius ``a``."""
    gs = sorted(angles)
    gaps = [b - c for c, b in zip(gs, gs[1:] + [gs[0] + 2 * math.pi])]
    return 2 * a * math.sin(min(gaps) / 2) - 2 * tip_radius


def planetary_teeth(ratio: float, n: int, min_teeth: int, max_teeth: int, m: float, clearance: float,
                    equal: bool = True, exact: bool = False, ha: float = 1.0, key: str = "planetary.ratio"
                    ) -> PlanetaryTeeth:
    """Teeth for a ring-fixed planetary set of ``n`` planets nearest ``ratio`` (1 + z_r/z_s): coaxial
    (z_r = z_s + 2 z_p), assembling (equally spaced: (z_s + z_r)/n whole), neighbouring planets
    ``clearance`` mm apart, ring minus planet at least MIN_TOOTH_DIFFERENCE, every count in the
    limits (the ring up to max_teeth × 3). Smallest ratio error, then the smallest ring."""
    best, reach = None, [math.inf, -math.inf]
    for zs in range(min_teeth, max_teeth + 1):
        for zp in range(min_teeth, max_teeth + 1):
            zr = zs + 2 * zp
            if zr > 3 * max_teeth or zr - zp < MIN_TOOTH_DIFFERENCE:
                continue
            if equal and not assembly_whole(zs, zr, n):
                continue
            a = m * (zs + zp) / 2
            if planet_clearance(planet_angles(zs, zr, n, equal), a, m * (zp / 2 + ha)) < clearance:
                continue
            got = 1 + zr / zs
            reach = [min(reach[0], got), max(reach[1], got)]
            err = abs(got - ratio) / ratio
            if exact and err > 1e-12:
                continue
            score = (round(err, 12), zr, zs)
            if best is None or score < best[0]:
                best = (score, PlanetaryTeeth(zs, zp, zr, n))
    if best is None or best[0][0] > MAX_RATIO_ERROR:
        span = f"ratios from {reach[0]:.3f} to {reach[1]:.3f} can be met" if reach[0] < math.inf else "no ratio can be met"
        raise DesignError(f"no sun, planet and ring in {min_teeth}–{max_teeth} teeth give the ratio {ratio:g}"
                          f"{' exactly' if exact else f' within {100 * MAX_RATIO_ERROR:g} %'} with {n} planets"
                          f"{' equally spaced' if equal else ''} ({span}): another ratio, fewer planets, unequal "
                          "spacing or wider tooth limits", key)
    return best[1]
