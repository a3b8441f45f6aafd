"""Builders of every kind of part in a kit. Each returns a manifold3d solid in the part's local
frame: z up as assembled, origin on the part's main axis. Numbers in mm, angles in rad.

Fixing against rotation uses D-shapes (a circle with a flat on the local -y side): a D-bore on a
D-flat axle, or a gear's D-boss pressed into a plate's D-hole. A gear's teeth can be clocked
relative to its D (``clocking``): that is how the tooth phase an assembly needs is built in.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import manifold3d as m3d
import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import Polygon, box

from ..core.parts import Part
from ..design.gearing import GearSpec
from .gear import gear_body
from .outline import circle, d_shape, hull_of_discs
from .solid import extrude, prisms, slab, union

__all__ = ["Part", "DFit", "fixed_gear", "bored_gear", "link_plate", "base_plate", "leg", "shaft", "drive_axle", "crank",
           "pen_holder"]

FLAT_DEPTH = 1.0  # mm: a D's flat sits this far inside its circle


@dataclass(frozen=True)
class DFit:
    """A D-shaped fit: shaft radius and the clearance (diametral) of the hole over it."""

    radius: float
    clearance: float

    def shaft(self, tol: float) -> Polygon:
        return d_shape(self.radius, self.radius - FLAT_DEPTH, tol)

    @property
    def pin_diameter(self) -> float:
        """mm: the largest round pin through its D-hole (twice the distance from the axis to the flat)."""
        return 2 * (self.radius - FLAT_DEPTH)

    def hole(self, tol: float) -> Polygon:
        c = self.clearance / 2
        return d_shape(self.radius + c, self.radius - FLAT_DEPTH + c, tol, hole=True)


def _annulus(r_in: float, r_out: float, tol: float, centre=(0.0, 0.0)) -> Polygon:
    return circle(r_out, tol, centre).difference(circle(r_in, tol, centre))


def bored_gear(spec: GearSpec, face_width: float, hole: Polygon) -> m3d.Manifold:
    """A plain gear (idler, D gear, drive gear): teeth from z = 0 to face_width around ``hole``."""
    return gear_body(spec, face_width, hole)


def fixed_gear(spec: GearSpec, face_width: float, bore_radius: float, collar: tuple[float, float],
               boss: DFit, boss_height: float, clocking: float, tol: float) -> m3d.Manifold:
    """A gear fixed to the plate above it (G_j): teeth [0, face_width], a collar
    (radius, height) that spaces the plate, and a D-boss of ``boss_height`` that presses into
    the plate's D-hole; one round bore runs through all of it. The boss is turned by -clocking so
    that, with the boss's flat aligned to the plate's, tooth 0 sits at ``clocking``."""
    bore = circle(bore_radius, max(tol, 0.005), hole=True)
    return fixed_hub(gear_body(spec, face_width, bore), face_width, bore_radius, collar, boss, boss_height, clocking, tol)


def fixed_hub(body: m3d.Manifold, face_width: float, bore_radius: float, collar: tuple[float, float], boss: DFit,
              boss_height: float, clocking: float, tol: float) -> m3d.Manifold:
    """``body`` (spanning [0, face_width], bored) with the collar and D-boss of a part fixed to
    the plate above it (see ``fixed_gear``)."""
    tol_f = max(tol, 0.005)
    bore = circle(bore_radius, tol_f, hole=True)
    collar_r, collar_h = collar
    boss_shape = affinity.rotate(boss.shaft(tol_f), -clocking, origin=(0, 0), use_radians=True)
    z1 = face_width + collar_h
    hub = prisms([(circle(collar_r, tol_f).difference(bore), face_width, z1),
                  (boss_shape.difference(bore), z1, z1 + boss_height)])
    return union([body, hub])


def pulley_outline(teeth: int, pitch: float, pitch_line_offset: float, groove_depth: float, groove_radius: float,
                   tol: float) -> Polygon:
    """A timing pulley's toothed section: its outside circle less ``teeth`` round-bottomed grooves
    (an arc of ``groove_radius`` whose bottom is ``groove_depth`` under the outside radius)."""
    r_out = teeth * pitch / (2 * math.pi) - pitch_line_offset
    grooves = [circle(groove_radius, tol, ((r_out - groove_depth + groove_radius) * math.cos(a),
                                           (r_out - groove_depth + groove_radius) * math.sin(a)))
               for a in 2 * math.pi * (np.arange(teeth) + 0.5) / teeth]
    return circle(r_out, tol).difference(shapely.union_all(grooves))


def pulley_body(section: Polygon, flange_radius: float, flange_thickness: float, face_width: float, hole: Polygon,
                tol: float) -> m3d.Manifold:
    """A flanged pulley [0, face_width]: flanges of ``flange_thickness`` either side of the toothed
    ``section``, ``hole`` through it all."""
    flange = circle(flange_radius, tol).difference(hole)
    return prisms([(flange, 0.0, flange_thickness), (section.difference(hole), flange_thickness, face_width - flange_thickness),
                   (flange, face_width - flange_thickness, face_width)])


def belt_band(path: np.ndarray, inside: float, outside: float, z0: float, z1: float) -> m3d.Manifold:
    """A closed belt between its pitch path ((n, 2) mm) offset ``inside`` inward and ``outside``
    outward, from z0 to z1 (a purchased part: modelled to keep it clear of the rest)."""
    loop = Polygon(path)
    band = loop.buffer(outside, join_style="round").difference(loop.buffer(-inside, join_style="round"))
    return prisms([(band, z0, z1)])


def link_plate(length: float, thickness: float, proximal_hole: Polygon, proximal_r: float,
               distal: tuple[float, float], idler: tuple[tuple[float, float], float] | None,
               features: list[tuple[Polygon, float, float]], tol: float,
               distal_hole: Polygon | None = None, solids: list[m3d.Manifold] = ()) -> m3d.Manifold:
    """A link plate in its link frame (proximal joint at the origin, distal at (length, 0), bottom
    at z = 0): the hull of its bosses (proximal radius, (distal radius), (idler centre, radius)),
    holes cut through, and ``features`` (outline, z0, z1) — pins, thrust rings — and ``solids``
    (posts, see ``shaft``) on top."""
    discs = [((0.0, 0.0), proximal_r), ((length, 0.0), distal[1])]
    if idler is not None:
        discs.append(idler)
    outline = hull_of_discs(discs, max(tol, 0.01)).difference(proximal_hole)
    if distal_hole is not None:
        outline = outline.difference(distal_hole)
    return union([extrude(outline, thickness)] + ([prisms(features)] if features else []) + list(solids))


def base_plate(outline: Polygon, thickness: float, features: list[tuple[Polygon, float, float]],
               solids: list[m3d.Manifold] = ()) -> m3d.Manifold:
    """The base: ``outline`` (holes included) from z = -thickness to 0, ``features`` and ``solids``
    (the ground post, see ``shaft``) above."""
    return union([extrude(outline, thickness, -thickness), prisms(features), *solids])


def leg(radius: float, height: float, peg_radius: float, peg_height: float, tol: float) -> m3d.Manifold:
    """A foot: a column of ``height`` whose top peg (``peg_height``) presses into the base."""
    return prisms([(circle(radius, tol), -height, 0.0), (circle(peg_radius, tol), 0.0, peg_height)])


def shaft(fit: DFit, sections: list[tuple[str, float, float]], tol: float, centre=(0.0, 0.0)) -> m3d.Manifold:
    """A shaft of radius ``fit.radius`` along z through ``centre``: consecutive sections ("round" |
    "D", z0, z1), the D ones with their flat (on the -y side, as ``DFit.shaft``).

    The flats are cut from one round prism by boxes, never a D prism stacked on a round one: a D's
    corners lie on the round prism's wall only to rounding, and their union leaves edges of 1e-10
    mm that fold once written as float32. A cutter's face ends inside the shaft, or 1 mm past its
    end, so no two faces are near-coincident."""
    r, flat = fit.radius, fit.radius - FLAT_DEPTH
    z_lo, z_hi = sections[0][1], sections[-1][2]
    cx, cy = centre
    cutters = [slab(box(cx - r - 1.0, cy - r - 1.0, cx + r + 1.0, cy - flat),
                    z0 - (1.0 if z0 == z_lo else 0.0), z1 + (1.0 if z1 == z_hi else 0.0))
               for kind, z0, z1 in sections if kind == "D"]
    round_ = slab(circle(r, tol, centre), z_lo, z_hi)
    return round_ - union(cutters) if cutters else round_


def drive_axle(fit: DFit, sections: list[tuple[str, float, float]], tol: float) -> m3d.Manifold:
    """A shaft along z: sections ("round" | "D", z0, z1) of radius ``fit.radius``."""
    return shaft(fit, sections, tol)


def crank(fit: DFit, radius: float, thickness: float, hub_r: float, handle_r: float, handle_len: float,
          tol: float) -> m3d.Manifold:
    """Crank arm from z = -thickness to 0, its D-hole on the axis, a handle pointing down at
    (radius, 0)."""
    arm = hull_of_discs([((0.0, 0.0), hub_r), ((radius, 0.0), handle_r + 2.0)], tol).difference(fit.hole(tol))
    return prisms([(arm, -thickness, 0.0), (circle(handle_r, tol, (radius, 0.0)), -thickness - handle_len, -thickness)])


def pen_holder(spigot: DFit, spigot_height: float, tube_r: float, height: float, pen_r: float, floor: float,
               tol: float) -> m3d.Manifold:
    """Pen holder: a D-spigot [0, spigot_height] into the last plate, a tube above it holding the
    pen in a blind bore (``floor`` of solid under the pen), pen pointing up."""
    z1 = spigot_height + height
    return prisms([(spigot.shaft(tol), 0.0, spigot_height), (circle(tube_r, tol), spigot_height, spigot_height + floor),
                   (_annulus(pen_r, tube_r, tol), spigot_height + floor, z1)])


def annulus(r_in: float, r_out: float, tol: float, centre=(0.0, 0.0)) -> Polygon:
    """Ring outline (thrust faces)."""
    return _annulus(r_in, r_out, tol, centre)


def disc(radius: float, tol: float, centre=(0.0, 0.0), hole: bool = False) -> Polygon:
    return circle(radius, tol, centre, hole)


def translate2d(geom: Polygon, dx: float, dy: float) -> Polygon:
    return affinity.translate(geom, dx, dy)


def union2d(geoms) -> Polygon:
    return shapely.union_all(list(geoms))
