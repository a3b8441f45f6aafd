"""Hub features of a gear part and the bought hardware they take, as outlines and manifold3d solids
in the part's local frame (z up as assembled, the bore's axis on z). mm.

A keyway is part of the bore's outline (a slot on the local +y side); a nut trap, a set-screw's
hole and its nut's slot are cutters the part's solid loses by a boolean difference. Every cutter
runs 1 mm past the face it opens, so no two faces are near-coincident."""

from __future__ import annotations

import math

import manifold3d as m3d
import shapely
from shapely.geometry import Polygon, box

from .outline import circle, segments_for
from .solid import slab

__all__ = ["keyway_hole", "key_ridge", "hexagon", "radial_cylinder", "block", "nut_trap", "square_nut", "hex_nut"]


def keyway_hole(bore_radius: float, half_width: float, floor: float, tol: float) -> Polygon:
    """A round bore of ``bore_radius`` with a keyway slot on its +y side: |x| ≤ ``half_width``,
    reaching ``floor`` from the axis (the slot's floor, y = floor)."""
    if not 0 < half_width < bore_radius < floor:
        raise ValueError(f"a keyway {2 * half_width:g} mm wide to {floor:g} mm does not fit a Ø{2 * bore_radius:g} mm bore")
    return shapely.union(circle(bore_radius, tol, hole=True), box(-half_width, 0.0, half_width, floor))


def key_ridge(half_width: float, top: float, z0: float, z1: float) -> m3d.Manifold:
    """A shaft's integral key from z0 to z1: |x| ≤ ``half_width``, from the axis to y = ``top``
    (its lower part lies inside the shaft it is joined to)."""
    return slab(box(-half_width, 0.0, half_width, top), z0, z1)


def hexagon(across_flats: float, centre=(0.0, 0.0)) -> Polygon:
    """A regular hexagon, two of its flats normal to x (at x = ±across_flats / 2)."""
    r = across_flats / math.sqrt(3.0)  # corner radius
    a = [math.radians(30 + 60 * k) for k in range(6)]
    return Polygon([(centre[0] + r * math.cos(t), centre[1] + r * math.sin(t)) for t in a])


def nut_trap(across_flats: float, z_face: float, depth: float) -> m3d.Manifold:
    """The cutter of a hexagonal nut trap sunk ``depth`` into the part from its bottom face at ``z_face``."""
    return slab(hexagon(across_flats), z_face - 1.0, z_face + depth)


def radial_cylinder(radius: float, x0: float, x1: float, z: float, tol: float) -> m3d.Manifold:
    """A cylinder along +x from x0 to x1 on the line y = 0 at height z (a set screw, or its hole)."""
    n = segments_for(radius, tol)
    c = m3d.Manifold.cylinder(x1 - x0, radius, radius, n)  # along z from 0 to x1 - x0
    return c.rotate((0.0, 90.0, 0.0)).translate((x0, 0.0, z))


def block(x0: float, x1: float, y0: float, y1: float, z0: float, z1: float) -> m3d.Manifold:
    """An axis-aligned box (a nut's slot)."""
    return slab(box(x0, y0, x1, y1), z0, z1)


def square_nut(side: float, height: float, thread: float, x0: float, z: float, tol: float) -> m3d.Manifold:
    """A square nut (DIN 562) standing in a slot: its axis along +x at height z, its faces normal to
    x at x0 and x0 + height, its sides ``side`` in y and z; bored ``thread`` (the screw's nominal Ø)."""
    body = block(x0, x0 + height, -side / 2, side / 2, z - side / 2, z + side / 2)
    return body - radial_cylinder(thread / 2, x0 - 1.0, x0 + height + 1.0, z, tol)


def hex_nut(across_flats: float, height: float, bore: Polygon, z0: float) -> m3d.Manifold:
    """A hexagonal nut (ISO 4032) on z from z0 to z0 + height, its thread ``bore`` (a hole outline)
    the same polygon as the rod it screws onto."""
    return slab(hexagon(across_flats).difference(bore), z0, z0 + height)
