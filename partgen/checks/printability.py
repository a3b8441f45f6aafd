"""Will each part print? Envelope in its print orientation, holes and walls against the printer's
minimums, gear tips against its resolution."""

from __future__ import annotations

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from ..assembly.kit import Kit
from .findings import Finding
from .motion import PartGeometry

__all__ = ["check_printability"]


def _polys(shape):
    return list(shape.geoms) if isinstance(shape, MultiPolygon) else [shape]


def features(shape) -> tuple[float, float]:
    """(smallest hole diameter, thinnest wall between a hole and any other boundary), mm."""
    hole, wall = np.inf, np.inf
    for p in _polys(shape):
        rings = [Polygon(r) for r in p.interiors]
        for i, r in enumerate(rings):
            hole = min(hole, 2 * shapely.minimum_bounding_radius(r))
            wall = min(wall, shapely.distance(r.exterior, p.exterior))
            for q in rings[i + 1:]:
                wall = min(wall, shapely.distance(r, q))
    return hole, wall


def check_printability(kit: Kit, geo: dict[str, PartGeometry], extents: dict[str, np.ndarray]) -> tuple[list[Finding], dict]:
    """``extents``: name -> (3,) printed extents of each distinct part."""
    pr = kit.params.printer
    findings, figures = [], {"smallest_hole_mm": np.inf, "thinnest_wall_mm": np.inf, "narrowest_tip_mm": np.inf}
    ez = float(pr.envelope[2])
    for name, ext in extents.items():
        # in its print orientation its height must be under the envelope's; whether its footprint fits
        # the bed (turned freely about z) is the plate layout's test (export.plates), which names it
        x, y, z = (float(v) for v in ext)
        if z > ez + 1e-9:
            findings.append(Finding("printability", "fail", f"{name} ({' × '.join(f'{v:.1f}' for v in ext)} mm as printed) "
                                    f"is taller than the {pr.name}'s {ez:g} mm build height", (name,), None, z, "mm"))
        hole, wall = np.inf, np.inf
        for s in geo[name].slabs:
            h, w = features(s.shape)
            hole, wall = min(hole, h), min(wall, w)
        figures["smallest_hole_mm"] = min(figures["smallest_hole_mm"], hole)
        figures["thinnest_wall_mm"] = min(figures["thinnest_wall_mm"], wall)
        if hole < pr.min_hole - 1e-6:
            findings.append(Finding("printability", "fail", f"{name}: a hole of Ø{hole:.2f} mm is under the printer's "
                                    f"smallest reliable hole Ø{pr.min_hole:g} mm", (name,), None, hole, "mm"))
        if wall < pr.min_wall - 1e-6:
            findings.append(Finding("printability", "fail", f"{name}: a wall of {wall:.2f} mm is under the printer's "
                                    f"{pr.min_wall:g} mm", (name,), None, wall, "mm"))
        gear = kit.part(name).gear
        if gear is not None:
            tip = gear.tip_thickness
            figures["narrowest_tip_mm"] = min(figures["narrowest_tip_mm"], tip)
            need = kit.params.checks.min_tip_width_roads * pr.resolution
            if tip < need:
                findings.append(Finding("printability", "fail", f"{name}: tooth tips {tip:.3f} mm wide, under "
                                        f"{kit.params.checks.min_tip_width_roads:g} roads of {pr.resolution:g} mm",
                                        (name,), None, tip, "mm"))
    figures = {k: round(float(v), 4) for k, v in figures.items() if np.isfinite(v)}
    return findings, figures
