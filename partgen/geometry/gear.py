"""Involute spur gear solids: the generated 2-D outline (design.involute) extruded, with a bore
and whatever hub the caller stacks on it."""

from __future__ import annotations

import manifold3d as m3d
import numpy as np
from shapely.geometry import Polygon

from ..design import involute
from ..design.gearing import GearSpec
from .solid import cross_section, extrude

__all__ = ["gear_outline", "gear_body"]


def gear_outline(spec: GearSpec) -> involute.GearOutline:
    """The rack-generated outline of ``spec``: tooth 0 centred on +x, ccw, mm."""
    s = spec.system
    return involute.gear_outline(spec.teeth, s.module, s.pressure_angle, spec.profile_shift, s.backlash_per_gear,
                                 s.addendum_coeff, s.dedendum_coeff, s.cutter_tip_coeff, s.chord_tolerance)


def gear_body(spec: GearSpec, face_width: float, hole: Polygon, z0: float = 0.0) -> m3d.Manifold:
    """The toothed prism of ``spec`` from z0 to z0 + face_width with ``hole`` cut through it."""
    outline = gear_outline(spec).points
    hole_xy = np.asarray(hole.exterior.coords)[:-1]
    if np.hypot(hole_xy[:, 0], hole_xy[:, 1]).max() >= spec.root_radius:
        raise ValueError(f"a {spec.teeth}-tooth gear's root circle (Ø{2 * spec.root_radius:.2f} mm) cannot hold its bore")
    cs = cross_section(outline) - cross_section(hole_xy)
    return extrude(cs, face_width, z0)
