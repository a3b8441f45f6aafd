"""A crossed helical pair: two helical gears on skew shafts (pure math: numpy; mm, rad).

Both gears are cut by one rack (same normal module m_n and normal pressure angle α_n); gear i has
helix angle β_i at its reference cylinder and its own transverse system (m_t = m_n / cos β_i,
tan α_t = tan α_n / cos β_i: ``gear_train.transverse_system``). The shafts cross at
Σ = β_1 + β_2 (both helices of one hand, right-handed here; β_2 < 0 would be the other hand).

Frame (world): gear 1 turns about z through the origin; the common perpendicular of the two axes is
the x axis; gear 2's axis is ``u2 = (0, sin Σ, cos Σ)`` through ``(a, 0, z_c)``, a = r_1 + r_2 the
sum of the reference radii r_i = z_i m_n / (2 cos β_i): the pitch cylinders touch at the pitch
point P = (r_1, 0, z_c), where both helices run along t = (0, sin β_1, cos β_1).

Gear 2's local frame: x → −x (towards gear 1: P is on its local +x), z → u2, y = z × x =
(0, −cos Σ, sin Σ). A helix turning counter-clockwise (about +z) as z grows is right-handed; with
both gears right-handed their teeth are parallel at P exactly when Σ = β_1 + β_2.

Kinematics: the normal components (along n = x × t) of the two gears' velocities at P agree:
ω_1 r_1 cos β_1 = −ω_2 r_2 cos β_2, and r_i cos β_i = z_i m_n / 2, so ω_2 = −ω_1 z_1 / z_2
about u2: the ratio is the tooth ratio whatever the helix angles. The sliding speed at P (along t)
is v_s = ω_1 r_1 sin Σ / cos β_2 (the relative velocity's component along the teeth).

Zero-backlash centre distance: unshifted gears of one rack at a = r_1 + r_2 mesh without backlash
(each tooth is half the normal pitch thick at its reference cylinder, and the normal sections of
the two pitch helices match at P); each gear's transverse thinning ``backlash_per_gear`` is the
backlash it adds along its own pitch circle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from .gear_train import Transverse, transverse_system, twist_over

__all__ = ["CrossedPair", "crossed_pair"]


@dataclass(frozen=True)
class CrossedPair:
    """The pair's design numbers (mm, rad). ``teeth`` (z_1 driver, z_2 driven); ``helix`` (β_1,
    β_2) at the reference cylinders; ``systems`` the two transverse systems."""

    teeth: tuple[int, int]
    normal_module: float
    normal_pressure_angle: float
    helix: tuple[float, float]
    systems: tuple[Transverse, Transverse]

    @property
    def shaft_angle(self) -> float:
        return self.helix[0] + self.helix[1]

    def pitch_radius(self, i: int) -> float:
        return self.teeth[i] * self.normal_module / (2 * math.cos(self.helix[i]))

    @property
    def centre_distance(self) -> float:
        """The shortest distance between the axes, zero backlash: r_1 + r_2."""
        return self.pitch_radius(0) + self.pitch_radius(1)

    @property
    def ratio(self) -> Fraction:
        """Speed ratio input / output, z_2 / z_1."""
        return Fraction(self.teeth[1], self.teeth[0])

    def twist(self, i: int, face_width: float) -> float:
        """How far gear i's transverse section turns (rad, counter-clockwise: right hand) over its face."""
        return twist_over(face_width, self.helix[i], self.pitch_radius(i))

    @property
    def axis2(self) -> np.ndarray:
        s = self.shaft_angle
        return np.array([0.0, math.sin(s), math.cos(s)])

    def frame2(self) -> np.ndarray:
        """(3, 3) columns: gear 2's local x, y, z in the world."""
        s = self.shaft_angle
        return np.column_stack([[-1.0, 0.0, 0.0], [0.0, -math.cos(s), math.sin(s)], [0.0, math.sin(s), math.cos(s)]])

    def speed2(self) -> float:
        """Gear 2's turn about its local z per turn of gear 1 about z: −z_1 / z_2."""
        return -self.teeth[0] / self.teeth[1]

    def sliding_speed(self, omega1: float = 1.0) -> float:
        """Sliding speed at the pitch point (mm per unit time) for gear 1 at ``omega1`` rad per unit time."""
        return abs(omega1) * self.pitch_radius(0) * math.sin(self.shaft_angle) / math.cos(self.helix[1])

    def tooth_direction(self) -> np.ndarray:
        """The helices' common direction t at the pitch point (world)."""
        b = self.helix[0]
        return np.array([0.0, math.sin(b), math.cos(b)])


def crossed_pair(teeth: tuple[int, int], normal_module: float, normal_pressure_angle: float, helix1: float,
                 shaft_angle: float, ha: float = 1.0, hf: float = 1.25, rho: float = 0.38) -> CrossedPair:
    """The pair of ``teeth`` cut by a rack of ``normal_module`` and ``normal_pressure_angle``,
    gear 1 at ``helix1`` and the shafts at ``shaft_angle`` (β_2 = Σ − β_1). ValueError for a helix
    angle whose cosine leaves no transverse system."""
    b1, b2 = helix1, shaft_angle - helix1
    for b in (b1, b2):
        if not abs(b) < math.radians(75):
            raise ValueError(f"a helix angle of {math.degrees(b):.1f}° (at most 75°)")
    systems = tuple(transverse_system(normal_module, normal_pressure_angle, abs(b), "normal", ha, hf, rho)
                    for b in (b1, b2))
    return CrossedPair((int(teeth[0]), int(teeth[1])), normal_module, normal_pressure_angle, (b1, b2), systems)
