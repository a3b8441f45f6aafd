"""An ABENICS-style cross spherical gear: a 2-D involute gear profile revolved about an axis in its
plane (ring-involute teeth), intersected with itself turned 90° about the pole axis.

Tooth-count rule: the section through both ring axes (the equatorial plane) is the profile
intersected with itself turned 90°, which equals the profile only if the profile has fourfold
symmetry — the tooth count must be a multiple of 4 (tooth 0 on the x axis puts teeth on both
ring axes). The revolution also needs the profile symmetric about the axis, which that implies.
"""

from __future__ import annotations

import manifold3d as m3d
import numpy as np
import shapely
from shapely.geometry import Polygon, box

from ..design.gearing import GearSpec
from .gear import gear_outline
from .solid import SLIVER, cross_section

__all__ = ["tooth_count_ok", "ring_gear", "cross_gear", "equatorial_error"]

GROW = 0.01  # mm: the second ring set's profile is grown by this (see cross_gear)


def tooth_count_ok(teeth: int) -> bool:
    """The cross gear's rule: a multiple of 4."""
    return teeth % 4 == 0


def ring_gear(spec: GearSpec, segments: int, grow: float = 0.0) -> m3d.Manifold:
    """The profile of ``spec`` (in the xy plane, tooth 0 on +x), grown outward by ``grow`` mm,
    revolved about the x axis."""
    outline = Polygon(gear_outline(spec).points)
    if grow:
        outline = outline.buffer(grow, join_style="mitre")
    r = spec.tip_radius * 1.1 + grow
    upper = shapely.intersection(outline, box(-r, 0.0, r, r))  # y ≥ 0: the half that revolves
    pts = np.asarray(shapely.geometry.polygon.orient(upper, 1.0).exterior.coords)[:-1]
    # cross-section coordinates: X = distance from the axis (the gear's y), Y = along the axis (its x)
    swapped = pts[:, ::-1][::-1].copy()
    swapped[:, 0] = np.maximum(swapped[:, 0], 0.0)
    solid = cross_section(swapped).revolve(segments)  # revolved about its Y, which becomes z
    return solid.rotate((0.0, 90.0, 0.0))  # z → x: the ring axis on x


def cross_gear(spec: GearSpec, segments: int = 0, grow: float = GROW) -> m3d.Manifold:
    """The cross gear: the ring gear about x intersected with the ring gear about y.

    The two ring sets coincide wherever both are bounded by the same surface — the tip sphere
    where tooth tips of both sets meet, the root sphere where root lands meet, the flanks along the
    equator — and there two differently tessellated copies of one surface cross each other at
    random: a solid that pinches shut, or slivers thinner than a float32 STL resolves. So the set
    about y is grown by ``grow`` mm (default GROW, a tenth of the printer's road): wherever the
    two coincided the set about x bounds the gear alone, and the equatorial section stays the
    profile exactly (P ∩ P grown = P). Elsewhere the set about y bounds it, ``grow`` proud."""
    if not tooth_count_ok(spec.teeth):
        raise ValueError(f"a cross gear needs a multiple of 4 teeth (the section through both ring axes must be "
                         f"the 2-D profile), got {spec.teeth}")
    segments = segments or max(96, 4 * spec.teeth)
    rx = ring_gear(spec, segments)
    ry = ring_gear(spec, segments, grow).rotate((0.0, 0.0, 90.0))
    return (rx ^ ry).simplify(SLIVER)


def equatorial_error(solid: m3d.Manifold, spec: GearSpec) -> float:
    """Area (mm²) of the symmetric difference between the solid's section through both ring axes
    (z = 0) and the 2-D profile: 0 for a cross gear that keeps its profile."""
    from .measure import to_shapely
    sec = to_shapely(solid.slice(0.0))
    prof = Polygon(gear_outline(spec).points)
    return float(shapely.symmetric_difference(sec, prof).area)

