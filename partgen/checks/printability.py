"""Will each part print? Envelope in its print orientation, holes and walls against the printer's
minimums (each hole against the rule that fits it), gear tips against its resolution — the rules
of design.rules, which `teeth: auto` chooses by and `build` warns about."""

from __future__ import annotations

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Point, Polygon

from ..core.protocol import CheckedKit as Kit  # what the shared checks read of a kit
from ..design import rules
from ..design.rules import gear_rules
from ..core.findings import Finding
from ..geometry.solid import mesh_arrays
from .motion import PartGeometry

__all__ = ["check_printability", "printed_extents"]


def printed_extents(kit: Kit) -> dict[str, np.ndarray]:
    """(3,) x, y, z extents of each printed part as it lies on the build plate, mm (printing it
    flipped about x keeps them); bought parts are not printed and have none."""
    out = {}
    for p in kit.parts:
        if not p.printed:
            continue
        v, _ = mesh_arrays(p.solid)
        out[p.name] = v.max(axis=0) - v.min(axis=0)
    return out


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


def holes(shape) -> list[tuple[Polygon, float]]:
    """Every hole of a section: (its ring as a polygon, its diameter mm)."""
    return [(Polygon(r), 2 * shapely.minimum_bounding_radius(Polygon(r))) for p in _polys(shape) for r in p.interiors]


def running_axes(kit: Kit) -> dict[str, list[tuple[float, float]]]:
    """name -> the running axes (x, y in the part's frame) through it: a hole around one runs on a
    pin or axle. A running contact (a, b) is part a turning on b, about a's own axis (its origin)."""
    poses = kit.poses(0.0)
    out: dict[str, list[tuple[float, float]]] = {}
    for c in kit.contacts:
        if c.kind != "running":
            continue
        out.setdefault(c.a, []).append((0.0, 0.0))
        p = np.linalg.inv(poses[c.b]) @ poses[c.a] @ np.array([0.0, 0.0, 0.0, 1.0])
        out.setdefault(c.b, []).append((float(p[0]), float(p[1])))
    return out


def check_printability(kit: Kit, geo: dict[str, PartGeometry], extents: dict[str, np.ndarray]) -> tuple[list[Finding], dict]:
    """``extents``: name -> (3,) printed extents of each distinct part. Holes are held to the rule
    that fits them (design.rules): one around the axis of a part it runs on (a bore on a pin or
    axle) to the printer's smallest joint hole, any other (a press-fit D, the pen's bore, a leg's
    socket) to the smallest hole it holds to size."""
    pr = kit.params.printer
    gear_rule = gear_rules(kit.params)
    axes = running_axes(kit)
    findings, figures = [], {"smallest_hole_mm": np.inf, "thinnest_wall_mm": np.inf, "narrowest_tip_mm": np.inf}
    ez = float(pr.envelope[2])
    for name, ext in extents.items():
        # in its print orientation its height must be under the envelope's; whether its footprint fits
        # the bed (turned freely about z) is the plate layout's test (export.plates), which names it
        x, y, z = (float(v) for v in ext)
        if z > ez + 1e-9:
            findings.append(Finding("printability", "fail", f"{name} ({' × '.join(f'{v:.1f}' for v in ext)} mm as printed) "
                                    f"is taller than the {pr.name}'s {ez:g} mm build height", (name,), None, z, "mm"))
        wall = np.inf
        worst = {}  # rule -> the smallest hole breaking it
        for s in geo[name].slabs:
            wall = min(wall, features(s.shape)[1])
            for ring, d in holes(s.shape):
                figures["smallest_hole_mm"] = min(figures["smallest_hole_mm"], d)
                runs = any(ring.contains(Point(q)) for q in axes.get(name, ()))
                b = rules.hole_breach(d, runs, pr.min_hole, pr.min_hole_to_size)
                if b is not None and (b.rule not in worst or b.value < worst[b.rule].value):
                    worst[b.rule] = b
        for b in worst.values():
            findings.append(Finding("printability", "fail", f"{name}: {b.message}", (name,), None, b.value, "mm",
                                    rule=b.rule))
        figures["thinnest_wall_mm"] = min(figures["thinnest_wall_mm"], wall)
        b = rules.wall_breach(wall, pr.min_wall)
        if b is not None:
            findings.append(Finding("printability", "fail", f"{name}: {b.message}", (name,), None, wall, "mm", rule=b.rule))
        gear = kit.part(name).gear
        if gear is not None:
            figures["narrowest_tip_mm"] = min(figures["narrowest_tip_mm"], gear.tip_thickness)
            for b in rules.gear_breaches(gear, gear_rule, name):
                findings.append(Finding("printability", "fail", f"{b.message} ({kit.params.checks.min_tip_width_roads:g} "
                                        f"lines of {pr.line_width:g} mm, the printer's line_width_mm)", (name,), None, b.value, "mm", rule=b.rule))
    figures = {k: round(float(v), 4) for k, v in figures.items() if np.isfinite(v)}
    return findings, figures
