"""A part of a kit as designed: its solid in its local frame, how it prints, and what it is."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Part"]


@dataclass(frozen=True)
class Part:
    """A part as designed: its solid in the local frame; ``print_flip`` prints it upside down;
    ``printed`` False for a bought part (a belt), modelled for the checks but not exported."""

    name: str
    role: str
    solid: object  # manifold3d.Manifold (core imports no mesh library)
    print_flip: bool = False
    gear: object = None  # design.gearing.GearSpec
    clocking: float = 0.0
    printed: bool = True
    info: tuple = ()
