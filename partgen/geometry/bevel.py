"""A straight bevel gear as a solid (manifold3d; mm, rad): the cone of similar sections through the
apex (``Manifold.extrude`` with ``scale_top``: every vertex of the bottom section joined to its
scaled copy at the top by a straight line through the apex, so the flanks are exactly ruled cones),
cut to the face between the heel and toe back cones (a revolved ring), on a hub, with a bore."""

from __future__ import annotations


import manifold3d as m3d
import numpy as np

from ..design.bevel import BevelTooth
from .outline import circle, segments_for
from .solid import cross_section, extrude

__all__ = ["bevel_gear", "revolved", "hull_to_floor"]


def revolved(profile: np.ndarray, radius: float, tol: float) -> m3d.Manifold:
    """The solid of revolution about z of a (ρ, a) polygon (counter-clockwise), its facets within
    ``tol`` of the circle at ``radius`` (the largest it reaches)."""
    return m3d.Manifold.revolve(m3d.CrossSection([np.asarray(profile, dtype=float)]), segments_for(radius, tol))


def bevel_gear(tooth: BevelTooth, bore: float, hub_radius: float, hub_end: float, tol: float) -> m3d.Manifold:
    """Gear ``tooth`` in its local frame (apex at the origin, axis +z towards it, tooth 0 on +x):
    the teeth between the back cones, a hub of ``hub_radius`` from the back face down to
    z = ``hub_end`` (< the back face; none when it is not below it), a round bore of ``bore`` radius."""
    blank = tooth.blank()
    a0, a1 = float(blank[:, 1].min()) - 0.2, float(blank[:, 1].max()) + 0.2
    if a1 >= 0:
        raise ValueError("the toe reaches the apex")
    section = tooth.section(tol, -a0)  # the section at the bottom of the extrusion
    cone = m3d.Manifold.extrude(cross_section(section), a1 - a0, 0, 0.0, (a1 / a0, a1 / a0)).translate((0.0, 0.0, a0))
    ring = revolved(blank, float(blank[:, 0].max()), max(tol, 0.002))
    body = cone ^ ring
    back = float(blank[0, 1])
    if hub_end < back - 1e-9:
        hub = np.array([[0.0, hub_end], [hub_radius, hub_end], [hub_radius, back + 0.01], [0.0, back + 0.01]])
        body = body + revolved(hub, hub_radius, max(tol, 0.005))
    low = min(hub_end, back) - 1.0
    hole = extrude(circle(bore, max(tol, 0.005), hole=True), a1 - low + 2.0, low)
    return body - hole


def cone_height_span(tooth: BevelTooth) -> tuple[float, float]:
    """(a of the back face, a of the toe face): where the gear body starts and ends along its axis."""
    b = tooth.blank()
    return float(b[0, 1]), float(b[5, 1])


def hull_to_floor(points: np.ndarray, floor: float = -0.01, direction=(0.0, 0.0, -1.0)) -> m3d.Manifold:
    """The convex hull of ``points`` (n, 3) and their feet on the plane z = ``floor``, each reached along
    ``direction`` (pointing down; default straight down): a block and its leg down to there."""
    pts = np.asarray(points, dtype=float)
    d = np.asarray(direction, dtype=float)
    if d[2] >= 0:
        raise ValueError("the leg's direction must point down")
    feet = pts + ((floor - pts[:, 2]) / d[2])[:, None] * d
    feet[:, 2] = floor
    return m3d.Manifold.hull_points(np.vstack([pts, feet]))
