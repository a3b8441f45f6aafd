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

from . import involute

from .gear_train import Transverse, transverse_system, twist_over

__all__ = ["CrossedPair", "crossed_pair", "efficiency", "friction_angle", "ThreadSpec"]


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
        if not abs(b) < math.radians(85) + 1e-12:
            raise ValueError(f"a helix angle of {math.degrees(b):.1f}° (at most 85°)")
    systems = tuple(transverse_system(normal_module, normal_pressure_angle, abs(b), "normal", ha, hf, rho)
                    for b in (b1, b2))
    return CrossedPair((int(teeth[0]), int(teeth[1])), normal_module, normal_pressure_angle, (b1, b2), systems)


def efficiency(pair: CrossedPair, friction: float, backwards: bool = False) -> float:
    """Efficiency of the mesh with gear 1 driving (``backwards``: gear 2 driving gear 1) for a
    Coulomb friction coefficient ``friction`` sliding along the teeth: with the friction angle
    φ' = atan(μ / cos α_n) (the normal pressure angle wedges the contact),
    η = cos β_1 cos(β_2 + φ') / (cos β_2 cos(β_1 − φ')) (a worm: β_1 = 90° − γ, β_2 = γ gives
    tan γ / tan(γ + φ')), and backwards the roles swap. ≤ 0: the mesh locks (cannot be driven)."""
    phi = math.atan(friction / math.cos(pair.normal_pressure_angle))
    b1, b2 = (abs(pair.helix[1]), abs(pair.helix[0])) if backwards else (abs(pair.helix[0]), abs(pair.helix[1]))
    return math.cos(b1) * math.cos(b2 + phi) / (math.cos(b2) * math.cos(b1 - phi))


def friction_angle(pair: CrossedPair, friction: float) -> float:
    return math.atan(friction / math.cos(pair.normal_pressure_angle))


@dataclass(frozen=True)
class ThreadSpec:
    """Gear 1 of a pair whose transverse section the rack generator does not make (1–3 starts, or a
    transverse pressure angle of 45° and more: a worm): a ZI worm, the involute helicoid, whose
    transverse section is the involute of its base circle r_b = r_p cos α_t from the root (or the
    base circle, below which the flank runs radially to the root) to the tip. Same numbers as a
    ``GearSpec`` (mm, rad, transverse ``system``)."""

    teeth: int
    system: object  # gearing.ToothSystem (transverse)
    profile_shift: float = 0.0
    undercut: bool = False

    @property
    def module(self) -> float:
        return self.system.module

    @property
    def pitch_radius(self) -> float:
        return self.system.module * self.teeth / 2

    @property
    def base_radius(self) -> float:
        return self.pitch_radius * math.cos(self.system.pressure_angle)

    @property
    def tip_radius(self) -> float:
        return self.pitch_radius + self.system.addendum_coeff * self.module

    @property
    def root_radius(self) -> float:
        return self.pitch_radius - self.system.dedendum_coeff * self.module

    @property
    def tooth_thickness(self) -> float:
        """Transverse arc thickness at the reference pitch circle, thinning included, mm."""
        return math.pi * self.module / 2 - self.system.backlash_per_gear

    def flank_angle(self, r) -> np.ndarray:
        """Polar angle (rad) of the upper flank at radius r from the tooth's centre line (the lower: −)."""
        rb, rp = self.base_radius, self.pitch_radius
        a = self.system.pressure_angle
        psi_b = self.tooth_thickness / (2 * rp) + (math.tan(a) - a)
        r = np.maximum(np.asarray(r, dtype=float), rb)
        t = np.sqrt(np.maximum(r * r - rb * rb, 0.0)) / rb
        return psi_b - (t - np.arctan(t))

    def section(self, tol: float) -> np.ndarray:
        """(n, 2) mm counter-clockwise: the transverse section (root arcs, flanks, tip arcs).
        ValueError when the tooth comes to a point or the thread fills its space at the root."""
        z, ra, rr, rb = self.teeth, self.tip_radius, self.root_radius, self.base_radius
        if rr <= 0:
            raise ValueError(f"the root radius {rr:.3f} mm is not above the axis")
        psi_a = float(self.flank_angle(ra))
        psi_r = float(self.flank_angle(max(rr, rb)))
        if psi_a <= 0:
            raise ValueError(f"pointed thread: {2 * ra * psi_a:.3f} mm at the tip")
        if psi_r >= math.pi / z:
            raise ValueError("the thread fills its space at the root")

        def arc(r: float, a0: float, a1: float) -> np.ndarray:
            n = max(2, math.ceil(abs(a1 - a0) / (2 * math.acos(max(1 - tol / r, -1.0)))) + 1)
            a = np.linspace(a0, a1, n)
            return np.column_stack([r * np.cos(a), r * np.sin(a)])

        lo = max(rr, rb)
        # the involute's roll t (r = r_b √(1 + t²)): its radius of curvature is r_b t, so a chord of arc
        # length Δs = r_b t Δt sags Δs² / (8 r_b t) — steps Δt = 0.9 √(8 tol / (r_b t)) from the lower end
        t_lo, t_a = math.sqrt(max(lo * lo - rb * rb, 0.0)) / rb, math.sqrt(ra * ra - rb * rb) / rb
        ts = [t_lo]
        while ts[-1] < t_a:
            ts.append(min(t_a, ts[-1] + 0.9 * math.sqrt(8 * tol / (rb * max(ts[-1], 1e-3)))))
        rs = rb * np.sqrt(1 + np.asarray(ts) ** 2)
        ang = self.flank_angle(rs)
        upper = np.column_stack([rs * np.cos(ang), rs * np.sin(ang)])  # root (or base) → tip
        if rr < rb:  # radial below the base circle
            upper = np.vstack([[rr * math.cos(psi_r), rr * math.sin(psi_r)], upper])
        # counter-clockwise: root arc, lower flank root → tip, tip arc, upper flank tip → root, root arc
        tooth = np.vstack([arc(rr, -math.pi / z, -psi_r)[:-1], upper * np.array([1.0, -1.0]),
                           arc(ra, -psi_a, psi_a)[1:-1], upper[::-1], arc(rr, psi_r, math.pi / z)[1:-1]])
        return involute.repeat_tooth(tooth, z)
