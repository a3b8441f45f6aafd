"""The printer and the material a kit is printed in (mm, g/mm³): one definition for every mechanism."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["PrinterLimits", "Material"]


@dataclass(frozen=True)
class PrinterLimits:
    """A printer's profile as the rules read it (mm, degrees for ``overhang_deg``).

    envelope: build volume x, y, z. line_width: one extruded line (road); layer_height; nozzle.
    xy_accuracy: ± error of a printed outline. min_hole: the smallest hole that runs reliably on a
    pin or axle; min_hole_to_size: the smallest hole it holds to size (a press-fit D, a pen bore).
    min_wall_lines: the thinnest wall in lines (``min_wall`` = lines × line width). min_gear: the
    smallest reliable gear (pitch diameter); min_link: the smallest link. running_clearance,
    press_clearance: the fits the maker measured (diametral; None when the profile gives none).
    overhang_deg: the steepest overhang printed without supports, from the vertical. plate_edge: the
    room a build plate leaves between the parts and the bed's edge (the slicer's skirt or brim).
    hole_bias, pin_bias, outline_bias: mean deviation of a printed hole, pin and other outline
    (printed minus modelled, as a diameter; 0 when unmeasured). compensate: `build` opens holes and
    trims outlines by them. measured: the profile's values come from a calibration coupon.
    """

    name: str
    envelope: tuple[float, float, float]
    line_width: float
    min_hole: float
    min_gear: float
    min_link: float
    min_wall_lines: float
    min_hole_to_size: float = 3.0
    nozzle: float = 0.4
    layer_height: float = 0.2
    xy_accuracy: float = 0.1
    running_clearance: float | None = None
    press_clearance: float | None = None
    overhang_deg: float = 45.0
    plate_edge: float = 7.0
    hole_bias: float = 0.0
    pin_bias: float = 0.0
    outline_bias: float = 0.0
    compensate: bool = False
    measured: bool = False

    @property
    def min_wall(self) -> float:
        """The thinnest wall, mm: min_wall_lines × line_width."""
        return self.min_wall_lines * self.line_width

    @property
    def resolution(self) -> float:
        """Old name of ``line_width`` (mm)."""
        return self.line_width


@dataclass(frozen=True)
class Material:
    """What the printed parts are made of: its name and density (g/mm³, not g/cm³)."""

    name: str
    density: float
