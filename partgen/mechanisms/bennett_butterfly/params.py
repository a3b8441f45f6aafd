"""What a Bennett butterfly kit is built from (mm, rad, g/mm³): the resolver's output, the kit's input.
A parameter object of this mechanism, not of the design math (design/ takes plain numbers)."""

from __future__ import annotations

from dataclasses import dataclass

from ...core.printer import PrinterLimits
from ...design.bennett_butterfly import BennettButterfly

__all__ = ["BennettParams"]


@dataclass(frozen=True)
class BennettParams:
    """Everything the kit needs (mm, rad, g/mm³); the assembly layer builds it."""

    name: str
    bb: BennettButterfly
    home: float  # angle between links 1 and 4 at S (rad)
    workspace: tuple[float, float]  # range of that angle the kit must move through freely (rad)
    boss_radius: float
    boss_length: float
    axial_gap: float
    bar_radius: float
    pin_radius: float
    pin_clearance: float  # diametral
    pin_density: float
    pin_kind: str
    pin_stock: tuple[float, ...]  # the lengths a pin can be bought in, mm
    offset_step: float
    offset_max: float
    cw_links: tuple[int, ...]
    cw_distance: tuple[float, ...]
    cw_wall: float  # around and under a pocket
    cw_clearance: float  # diametral, the pocket's bore over the slugs
    slug_kind: str
    slug_diameter: float
    slug_lengths: tuple[float, ...]  # stock
    slug_density: float
    binder_name: str
    binder_density: float
    density: float
    material: str
    print_wall: float
    print_skin: float
    infill: float  # fraction 0..1
    overhang_angle: float  # rad from the vertical: steeper faces need support
    min_contact: float  # mm² of flat contact with the bed a part needs
    base_height: float  # the post from the base's top boss down to its foot
    foot_radius: float
    foot_thickness: float
    min_tip_angle: float  # rad: the kit stays up on its base tilted this far
    tolerance: float  # balance tolerance, mm
    grid: tuple[int, int]  # balance grid: q1 samples × shape samples
    infill_error: float  # fraction points, e.g. 0.05
    layers: int = 6
    fixed_layout: tuple | None = None  # (layers {link: layer}, shifts {joint: mm}) or None: automatic
    mass_scale: tuple = ()  # ((link, factor), ...): what-if heavier links, counterweights not re-sized
    printer: PrinterLimits | None = None
    segments: int = 40

    @property
    def pitch(self) -> float:
        """mm between the layers: a boss and the axial gap."""
        return self.boss_length + self.axial_gap

    @property
    def bore_radius(self) -> float:
        return self.pin_radius + self.pin_clearance / 2
