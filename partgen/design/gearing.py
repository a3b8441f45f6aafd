"""Gear value objects: a tooth system shared by the kit and one gear's design numbers (pure math)."""

from __future__ import annotations

from dataclasses import dataclass

from . import involute

__all__ = ["ToothSystem", "GearSpec", "make_gear", "centre_distance"]


@dataclass(frozen=True)
class ToothSystem:
    """What every gear of a kit shares. Lengths mm, angles rad.

    backlash_per_gear : circumferential thinning of each gear's tooth at its reference pitch
        circle (mm); a pair at its zero-backlash centre distance runs with the sum of its two
        gears' thinning as circumferential backlash.
    profile_shift : a fixed shift coefficient for every gear, or None for "auto" (the smallest
        shift that avoids undercut, 0 at and above the undercut limit).
    """

    module: float
    pressure_angle: float
    addendum_coeff: float = 1.0
    dedendum_coeff: float = 1.25
    cutter_tip_coeff: float = 0.38
    backlash_per_gear: float = 0.0
    profile_shift: float | None = 0.0
    chord_tolerance: float = 0.001


@dataclass(frozen=True)
class GearSpec:
    """One spur gear's design numbers (mm, rad)."""

    teeth: int
    system: ToothSystem
    profile_shift: float

    @property
    def module(self) -> float:
        return self.system.module

    @property
    def pitch_radius(self) -> float:
        return self.system.module * self.teeth / 2

    @property
    def tip_radius(self) -> float:
        return involute.tip_diameter(self.teeth, self.module, self.profile_shift, self.system.addendum_coeff) / 2

    @property
    def root_radius(self) -> float:
        return involute.root_diameter(self.teeth, self.module, self.profile_shift, self.system.dedendum_coeff) / 2

    @property
    def tooth_thickness(self) -> float:
        """Arc thickness at the reference pitch circle, as designed (thinning included), mm."""
        s = self.system
        return involute.reference_tooth_thickness(self.teeth, s.module, s.pressure_angle, self.profile_shift, s.backlash_per_gear)

    @property
    def undercut(self) -> bool:
        return involute.is_undercut(self.teeth, self.system.pressure_angle, self.profile_shift, self.system.addendum_coeff)

    @property
    def tip_thickness(self) -> float:
        """Arc thickness at the tip circle, mm."""
        s = self.system
        return involute.tooth_thickness_at(self.tip_radius, self.teeth, s.module, s.pressure_angle, self.profile_shift, s.backlash_per_gear)


def make_gear(teeth: int, system: ToothSystem) -> GearSpec:
    """A gear of the system, with the system's profile shift (or the automatic one)."""
    if system.profile_shift is None:
        x = involute.auto_profile_shift(teeth, system.pressure_angle, system.addendum_coeff)
    else:
        x = system.profile_shift
    return GearSpec(int(teeth), system, float(x))


def centre_distance(a: GearSpec, b: GearSpec) -> float:
    """Operating centre distance of a mesh of two gears with zero-backlash geometry, mm."""
    s = a.system
    return involute.centre_distance(a.teeth, b.teeth, s.module, s.pressure_angle, a.profile_shift, b.profile_shift)
