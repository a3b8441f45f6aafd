"""A part of a kit as designed: its solid in its local frame, how it prints, and what it is."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Part", "Bore", "Contact", "Stock"]


@dataclass(frozen=True)
class Bore:
    """A bore of a part that a pin, post or axle goes into, in the part's local frame (mm):
    ``point`` where the pin enters (on the part's outside), ``axis`` the direction it goes in
    (unit), ``diameter_mm`` the largest round pin that must pass (a D-hole: twice the distance from
    its axis to its flat), ``depth_mm`` how far the pin goes in from ``point``."""

    name: str
    point: tuple[float, float, float]
    axis: tuple[float, float, float]
    diameter_mm: float
    depth_mm: float


@dataclass(frozen=True)
class Stock:
    """One line of what to buy for a bought part, as the bill shows it: the item (what to ask a
    shop for), how many, its stock size, and the name in the kit it serves (default: the part's)."""

    item: str
    quantity: int
    size: str
    serves: str = ""


@dataclass(frozen=True)
class Part:
    """A part as designed: its solid in the local frame; ``print_flip`` prints it upside down;
    ``printed`` False for a bought part, modelled for the checks but not exported (``stock``
    says what to buy for it)."""

    name: str
    role: str
    solid: object  # manifold3d.Manifold (core imports no mesh library)
    print_flip: bool = False
    gear: object = None  # design.gearing.GearSpec
    clocking: float = 0.0
    printed: bool = True
    info: tuple = ()
    bores: tuple[Bore, ...] = ()  # what takes a pin or axle (checks.bores tests each is open)
    stock: tuple[Stock, ...] = ()  # a bought part: what to buy for it (the bill's lines)


@dataclass(frozen=True)
class Contact:
    """Two parts of a kit meant to touch, and how (``checks.fits`` measures each over the motion).

    kind: "running" (turns on it, radial gap = running clearance / 2), "press" (D-fit, gap = press
    clearance / 2), "thrust" (rests on it face to face), "mesh" (gears in mesh); any other kind
    is the mechanism's own, which it checks itself (the shared checks pass it by). window: world
    z-range where the fit is (the bore's length), None for thrust and mesh. radial_gap: the designed
    radial clearance, mm."""

    a: str
    b: str
    kind: str
    window: tuple[float, float] | None = None
    radial_gap: float = 0.0
