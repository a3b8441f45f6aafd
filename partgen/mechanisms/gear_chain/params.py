"""The gear chain's kit parameters (mm, rad, g/mm³): what its resolver makes of the YAML and its kit,
checks and design math read (``design.mechanism.ChainParams`` states what the design math needs;
``checks.settings.CheckSettings`` what the shared checks hold it to)."""

from __future__ import annotations

from dataclasses import dataclass

from ...checks.settings import CheckSettings
from ...core.printer import PrinterLimits
from ...design.gearing import ToothSystem

__all__ = ["Joints", "KitParams"]


@dataclass(frozen=True)
class Joints:
    """Axles and fits (mm). Clearances are diametral: hole diameter minus pin diameter."""

    axle_diameter: float
    running_clearance: float
    press_clearance: float
    axial_gap: float
    running_by: tuple[tuple[str, float], ...] = ()  # (part that turns in the bore, its own running clearance)

    def running_of(self, name: str) -> float:
        """The running clearance of the joint ``name`` turns in (its own, else the default), diametral."""
        return dict(self.running_by).get(name, self.running_clearance)


@dataclass(frozen=True)
class KitParams:
    """Everything the geometry needs besides the mechanism (mm, rad, g/mm³)."""

    name: str
    system: ToothSystem
    face_width: float
    plate_thickness: float
    boss_wall: float
    hub_wall: float
    joints: Joints
    base_thickness: float
    leg_height: float
    crank_radius: float
    pen_diameter: float
    pen_holder_height: float
    density: float
    material: str
    printer: PrinterLimits
    drive_teeth: int
    drive_angle: float
    checks: CheckSettings = CheckSettings()
    backlash_by: tuple[tuple[str, float], ...] = ()  # (gear, its own backlash per gear, mm): the others the system's

    def bore_of(self, name: str) -> float:
        """Running bore (mm) of the joint the part ``name`` turns in: its own clearance, else the default."""
        return self.joints.axle_diameter + self.joints.running_of(name)

    @property
    def bore(self) -> float:
        """Running bore of a gear or plate on an axle, mm."""
        return self.joints.axle_diameter + self.joints.running_clearance

    @property
    def min_root_diameter(self) -> float:
        """Root circle that keeps ``hub_wall`` around a gear's largest hole: its running bore or its
        press-fit D-hole, mm."""
        return max(self.bore, self.joints.axle_diameter + self.joints.press_clearance) + 2 * self.hub_wall
