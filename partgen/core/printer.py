"""The printer and the material a kit is printed in (mm, g/mm³): one definition for every mechanism."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["PrinterLimits", "Material"]


@dataclass(frozen=True)
class PrinterLimits:
    """A printer's profile (mm). ``min_hole``: the smallest hole that runs reliably on a pin or
    axle; ``min_hole_to_size``: the smallest hole it holds to size (a press-fit D, a pen bore)."""

    name: str
    envelope: tuple[float, float, float]
    resolution: float
    min_hole: float
    min_gear: float
    min_link: float
    min_wall: float
    min_hole_to_size: float = 3.0


@dataclass(frozen=True)
class Material:
    """What the printed parts are made of: its name and density (g/mm³, not g/cm³)."""

    name: str
    density: float
