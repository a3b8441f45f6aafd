"""What a wrist pair is built from (mm, rad, g/mm³): the resolver's output, the kit's input."""

from __future__ import annotations

from dataclasses import dataclass

from ...core.printer import PrinterLimits
from ...design.gearing import GearSpec
from ...geometry.cross_mate import MateSpec

__all__ = ["WristSpec"]


@dataclass(frozen=True)
class WristSpec:
    """A wrist pair's design numbers (mm, rad)."""

    name: str
    I: float
    A: float
    long_pitch: float
    ring_teeth: tuple[int, ...]
    dome_radius: float
    tooth_height: float
    clearance: float
    max_bend: float
    theta_steps: int
    psi_steps: int
    shaft_diameter: float
    press_clearance: float
    base_height: float
    tol: float
    density: float
    material: str
    printer: PrinterLimits
    cross: GearSpec | None = None  # an ABENICS-style cross gear on the spherical pitch, or None
    mate: MateSpec | None = None  # the cross gear's mate (an ABENICS monopole gear), or None
