"""Solids for gears on crossed axes: a helical gear centred on its mid-plane, a wedge that cuts a
gear to the teeth near a point, a cylinder along a pose's z (manifold3d; mm, rad)."""

from __future__ import annotations

import math

import manifold3d as m3d
import numpy as np

from ..design.gearing import GearSpec
from .gear import helical_body, twist_divisions
from .outline import circle
from .solid import cross_section, extrude

__all__ = ["centred_helical", "centred_thread", "sector_prism", "cylinder_along"]


def centred_helical(spec: GearSpec, face: float, twist: float, bore: float, tol: float) -> m3d.Manifold:
    """A helical gear from z = −face/2 to face/2 whose mid-plane section has tooth 0 on +x, turning
    counter-clockwise by ``twist`` (rad) from its bottom face to its top; a round bore of ``bore`` radius."""
    body = helical_body(spec, face, circle(bore, max(tol, 0.005), hole=True), -face / 2, twist, False, tol)
    return body.rotate((0.0, 0.0, -math.degrees(twist / 2)))


def centred_thread(section: np.ndarray, tip_radius: float, face: float, twist: float, bore: float,
                   tol: float) -> m3d.Manifold:
    """A worm's thread (or any twisted prism) from z = −face/2 to face/2: the transverse
    ``section`` (n, 2) mm extruded turning counter-clockwise by ``twist`` (rad) over the face, its
    mid-plane section as given; the slices close enough that a tip point's helix stays within
    ``tol``; a round bore of ``bore`` radius."""
    n = twist_divisions(tip_radius, twist, tol)
    body = m3d.Manifold.extrude(cross_section(section), face, n, math.degrees(twist))
    hole = extrude(circle(bore, max(tol, 0.005)), face + 2.0, -1.0)
    return (body - hole).translate((0.0, 0.0, -face / 2)).rotate((0.0, 0.0, -math.degrees(twist / 2)))


def sector_prism(radius: float, centre: float, half: float, height: float) -> m3d.Manifold:
    """A wedge prism round z: angles centre ± half (rad), out to ``radius``, z ± height."""
    a = centre + np.linspace(-half, half, max(8, int(math.ceil(2 * half / 0.05)) + 1))
    pts = np.vstack([[0.0, 0.0], np.column_stack([radius * np.cos(a), radius * np.sin(a)])])
    return m3d.Manifold.extrude(cross_section(pts), 2 * height).translate((0.0, 0.0, -height))


def cylinder_along(radius: float, length: float, tol: float, T: np.ndarray) -> m3d.Manifold:
    """A cylinder of ``radius`` and ``length`` along the local z of pose T (4, 4), centred on its origin."""
    return extrude(circle(radius, tol), length, -length / 2).transform(T[:3, :])
