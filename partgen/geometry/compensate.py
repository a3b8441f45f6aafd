"""XY compensation of a printed part for a printer's measured biases, the way a slicer's "XY hole /
contour compensation" works, but per feature kind and in the STL itself.

A printer's biases (``PrinterLimits.hole_bias``, ``pin_bias``, ``outline_bias``) are the mean
printed-minus-modelled size of a feature, as a diameter. A compensated part is modelled so that it
prints to its nominal size: in every z-slab of the part (between its vertex levels, where a part
made of z-prisms has a constant section),

* every hole is opened by ``-hole_bias / 2`` on its wall (a hole that prints 0.12 mm small is
  modelled 0.12 mm larger);
* every *round* outer contour (a pin, post, boss or disc: its area is within 0.5 % of its
  circumscribed circle's) is trimmed by ``pin_bias / 2``;
* every other outer contour (gear teeth, plates, links) is trimmed by ``outline_bias / 2``.

Offsets are shapely buffers with mitred joins (corners stay corners). Only a part that is a stack
of z-prisms is compensated (its slabs rebuild it to 1e-6 of its volume); a twisted or curved part
(a helical gear, a dome, a skew link) is left as designed and named, so the caller can say so.
"""

from __future__ import annotations

import math

import manifold3d as m3d
import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from .measure import slabs
from .solid import mesh_arrays, prisms

__all__ = ["ROUND", "is_round", "is_prism_stack", "offset_section", "compensate"]

ROUND = 0.995  # area / circumscribed circle area above which an outer contour is a pin
SNAP = 1e-4    # mm: an offset's vertices closer than this to their neighbours' line are dropped
GRID = 1e-5    # mm: the offset sections' vertices are rounded to this grid


def is_round(ring: Polygon) -> bool:
    """The contour is a circle (to its polygon's chords): a pin, post, boss or disc."""
    c = ring.centroid
    r = max(math.hypot(x - c.x, y - c.y) for x, y in ring.exterior.coords)
    return r > 0 and ring.area / (math.pi * r * r) > ROUND


def _grow(p: Polygon, d: float) -> Polygon:
    return p if d == 0 else p.buffer(d, join_style="mitre", mitre_limit=4.0)


def offset_section(shape, hole_bias: float, pin_bias: float, outline_bias: float):
    """A section (shapely) with its holes opened by -hole_bias/2, round outer contours trimmed by
    pin_bias/2 and other outer contours by outline_bias/2 (mm; negative biases grow the solid)."""
    polys = shape.geoms if isinstance(shape, MultiPolygon) else [shape]
    out = []
    for p in polys:
        if p.is_empty:
            continue
        outer = Polygon(p.exterior)
        outer = _grow(outer, -0.5 * (pin_bias if is_round(outer) else outline_bias))
        holes = [_grow(Polygon(r), -0.5 * hole_bias) for r in p.interiors]
        out.append(shapely.difference(outer, shapely.union_all(holes)) if holes else outer)
    # drop vertices an offset leaves within SNAP of a straight line, and put the rest on a GRID: two slabs'
    # offsets of one edge then share their vertices exactly (not 1e-8 mm apart: a float32 STL welds those
    # into zero-area faces)
    g = shapely.simplify(shapely.union_all(out), SNAP, preserve_topology=True)
    return shapely.set_precision(g, GRID)


def is_prism_stack(solid: m3d.Manifold, tol: float = 1e-9) -> bool:
    """Every face is horizontal or vertical (its unit normal's z is 0 or ±1): a stack of z-prisms."""
    v, f = mesh_arrays(solid)
    t = v[f]
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    length = np.linalg.norm(n, axis=1)
    ok = length > 1e-12
    nz = np.abs(n[ok, 2]) / length[ok]
    return bool(np.all((nz < tol) | (nz > 1 - tol)))


def compensate(solid: m3d.Manifold, hole_bias: float, pin_bias: float, outline_bias: float) -> m3d.Manifold | None:
    """The part modelled so it prints to size (see the module), or None when it is not a stack of
    z-prisms (then it cannot be compensated slab by slab)."""
    if hole_bias == 0 and pin_bias == 0 and outline_bias == 0:
        return solid
    if not is_prism_stack(solid):
        return None
    sl = slabs(solid)
    if not sl:
        return None
    rebuilt = prisms([(s.shape, s.z0, s.z1) for s in sl])
    v = solid.volume()
    if abs(rebuilt.volume() - v) > 1e-6 * max(v, 1.0):
        return None
    items = []
    for s in sl:
        g = offset_section(s.shape, hole_bias, pin_bias, outline_bias)
        if not g.is_empty:
            items.append((g, s.z0, s.z1))
    return prisms(items)
