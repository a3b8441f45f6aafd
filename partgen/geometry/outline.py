"""2-D outlines of parts (shapely): circles to a chord tolerance, D-shapes, hulls of bosses.

Coordinates mm. A D-shape is a circle with a flat: the flat is the chord at distance ``flat``
from the centre, on the -y side. Fixing a gear with a D keeps it from turning on its axle.
"""

from __future__ import annotations

import math
from typing import Iterable, Sequence

import numpy as np
import shapely
from shapely.geometry import Polygon, box

__all__ = ["circle_points", "circle", "d_shape", "hull_of_discs", "segments_for"]


def segments_for(radius: float, tol: float, minimum: int = 16) -> int:
    """Polygon sides so a circle of ``radius`` deviates by at most ``tol`` (sagitta), mm."""
    if radius <= tol:
        return minimum
    return max(minimum, math.ceil(math.pi / math.acos(1 - tol / radius)))


def circle_points(radius: float, tol: float, centre: Sequence[float] = (0.0, 0.0), hole: bool = False) -> np.ndarray:
    """(n, 2) float, mm: counter-clockwise vertices of a circle. A solid's vertices lie on the
    circle; a ``hole``'s polygon circumscribes it (its edges touch the circle), so a hole is
    never smaller than its nominal size and a fit never tighter than designed."""
    n = segments_for(radius, tol)
    t = 2 * np.pi * np.arange(n) / n
    r = radius / np.cos(np.pi / n) if hole else radius
    return np.column_stack([centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)])


def circle(radius: float, tol: float, centre: Sequence[float] = (0.0, 0.0), hole: bool = False) -> Polygon:
    return Polygon(circle_points(radius, tol, centre, hole))


def d_shape(radius: float, flat: float, tol: float, centre: Sequence[float] = (0.0, 0.0), hole: bool = False) -> Polygon:
    """Circle of ``radius`` cut by the line y = cy - ``flat`` (the flat on the -y side)."""
    if not 0 < flat < radius:
        raise ValueError(f"D-shape flat {flat} must lie inside the radius {radius}")
    c = circle(radius, tol, centre, hole)
    keep = box(centre[0] - 2 * radius, centre[1] - flat, centre[0] + 2 * radius, centre[1] + 2 * radius)
    return shapely.intersection(c, keep)


def hull_of_discs(discs: Iterable[tuple[Sequence[float], float]], tol: float) -> Polygon:
    """Convex hull of discs ((x, y), r): a link plate's outline around its bosses."""
    pts = np.vstack([circle_points(r, tol, c) for c, r in discs])
    return shapely.convex_hull(shapely.MultiPoint(pts))
