"""Involute spur gear solids: the generated 2-D outline (design.involute) extruded, with a bore
and whatever hub the caller stacks on it."""

from __future__ import annotations

import math

import manifold3d as m3d
import numpy as np
from shapely.geometry import Polygon

from ..design import involute
from ..design.gearing import GearSpec
from .solid import cross_section, extrude, union

__all__ = ["gear_outline", "gear_body", "helical_body", "twist_divisions"]


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


def twist_divisions(radius: float, twist: float, tol: float) -> int:
    """Divisions of a twisted extrusion so the straight edge a tip point at ``radius`` (mm) follows
    between two divisions stays within ``tol`` (mm) of its helix: a chord of angle Δφ has sagitta
    r (1 − cos Δφ/2) ≤ tol."""
    if twist == 0.0:
        return 0
    step = 2.0 * math.acos(max(1.0 - tol / radius, -1.0))
    return max(1, math.ceil(abs(twist) / step))


def helical_body(spec: GearSpec, face_width: float, hole: Polygon, z0: float, twist: float, herringbone: bool,
                 tol: float) -> m3d.Manifold:
    """A helical gear from z0 to z0 + face_width: the transverse outline of ``spec`` (its transverse
    tooth system) extruded turning by ``twist`` rad over the face, counter-clockwise for a positive
    twist (= face_width tan β / r_p, signed by the hand); ``herringbone``: the first half turns by
    twist / 2 and the second half back (two mirrored helical halves, unioned). ``tol``: the edges
    between divisions stay within it of the helices (``twist_divisions`` at the tip radius). The
    bore ``hole`` is cut straight through afterwards."""
    cs = cross_section(gear_outline(spec).points)
    if herringbone:
        half = face_width / 2
        n = twist_divisions(spec.tip_radius, twist / 2, tol)
        lower = m3d.Manifold.extrude(cs, half, n, math.degrees(twist / 2))
        upper = m3d.Manifold.extrude(cs.rotate(math.degrees(twist / 2)), half, n, -math.degrees(twist / 2))
        body = union([lower, upper.translate((0.0, 0.0, half))])
    else:
        body = m3d.Manifold.extrude(cs, face_width, twist_divisions(spec.tip_radius, twist, tol), math.degrees(twist))
    hole_xy = np.asarray(hole.exterior.coords)[:-1]
    if np.hypot(hole_xy[:, 0], hole_xy[:, 1]).max() >= spec.root_radius:
        raise ValueError(f"a {spec.teeth}-tooth gear's root circle (Ø{2 * spec.root_radius:.2f} mm) cannot hold its bore")
    bore = m3d.Manifold.extrude(cross_section(hole_xy), face_width + 2.0).translate((0.0, 0.0, -1.0))
    return (body - bore).translate((0.0, 0.0, z0))


def ring_body(space: GearSpec, rim_radius: float, face_width: float, z0: float = 0.0) -> m3d.Manifold:
    """An internal (ring) gear from z0 to z0 + face_width: the disc of ``rim_radius`` less the
    outline of its space gear ``space`` (design.planetary: an external gear whose teeth are the
    ring's tooth spaces), mm."""
    if rim_radius <= space.tip_radius:
        raise ValueError(f"a rim of radius {rim_radius:.2f} mm does not hold a ring whose root radius is "
                         f"{space.tip_radius:.2f} mm")
    from .outline import circle_points

    cs = cross_section(circle_points(rim_radius, space.system.chord_tolerance * 10)) - cross_section(
        gear_outline(space).points)
    return extrude(cs, face_width, z0)
