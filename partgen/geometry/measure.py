"""Measuring solids: z-slab sections, exact intersection volumes and gaps (manifold3d), 2-D
section overlap and distance (shapely). Every part partgen builds is a stack of z-prisms, so its
slab sections describe it exactly — but a twisted one (a helical gear), whose slabs are envelopes:
the union of its sections at several heights of each slab.
"""

from __future__ import annotations

from dataclasses import dataclass

import manifold3d as m3d
import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from ..errors import DesignError
from .solid import mesh_arrays

__all__ = ["Slab", "section", "slabs", "to_shapely", "place2d", "intersection", "min_gap", "from_mesh", "oversize", "empty_parts", "shell_count",
           "refuse_oversize"]


@dataclass(frozen=True)
class Slab:
    """A z-interval of a part (local frame) over which its cross-section is constant.

    z0, z1 : mm; shape : the section (shapely, local xy); centre (2,), radius : its smallest
    bounding circle; disc : the section is (to 0.5 % of area) a full disc about that centre.
    """

    z0: float
    z1: float
    shape: Polygon | MultiPolygon
    centre: tuple[float, float]
    radius: float
    disc: bool = False


def to_shapely(cs: m3d.CrossSection) -> Polygon | MultiPolygon:
    """A CrossSection as shapely geometry (outer contours counter-clockwise, holes clockwise)."""
    rings = [np.asarray(r) for r in cs.to_polygons() if len(r) >= 3]
    signed = [0.5 * np.sum(r[:, 0] * np.roll(r[:, 1], -1) - np.roll(r[:, 0], -1) * r[:, 1]) for r in rings]
    outers = [Polygon(r) for r, a in zip(rings, signed) if a > 0]
    holes = [Polygon(r) for r, a in zip(rings, signed) if a <= 0]
    # a hole belongs to the smallest outer contour round it (an island inside a hole inside an island:
    # a ring gear round a track round a boss)
    by_area = sorted(outers, key=lambda p: p.area)
    mine: dict[int, list] = {id(o): [] for o in outers}
    for h in holes:
        pt = h.representative_point()
        parent = next((o for o in by_area if o.area > h.area and o.contains(pt)), None)
        if parent is not None:
            mine[id(parent)].append(h)
    polys = [Polygon(o.exterior.coords, [h.exterior.coords for h in mine[id(o)]])
             for o in sorted(outers, key=lambda p: -p.area)]
    return polys[0] if len(polys) == 1 else MultiPolygon(polys)


def section(solid: m3d.Manifold, z: float) -> Polygon | MultiPolygon:
    """The solid cut by the plane at height ``z`` (its local frame), as shapely geometry, mm."""
    return to_shapely(solid.slice(z))


ENVELOPE_INSET = 1e-6  # × slab height: a face's section is taken this far inside the slab (a slice on a
# vertex level is ambiguous)


def slabs(solid: m3d.Manifold, heights: int = 1, grow: float = 0.0) -> tuple[Slab, ...]:
    """The slabs of a solid between its vertex levels, bottom to top. ``heights`` 1: each slab's
    section at its middle (exact for a prism stack); more: the union of its sections at that many
    heights spread over the slab, both faces included, grown outward by ``grow`` mm (an envelope of
    a twisted solid: a helical gear's section turns across each slab of its twisted extrusion, and
    its facets between the sampled heights stray a little outside them)."""
    v, _ = mesh_arrays(solid)
    levels = np.unique(np.round(v[:, 2], 7))
    out = []
    for z0, z1 in zip(levels[:-1], levels[1:]):
        if heights <= 1:
            cs = solid.slice(float((z0 + z1) / 2))
            if cs.is_empty():
                continue
            shape = to_shapely(cs)
        else:
            e = ENVELOPE_INSET * (z1 - z0)
            cuts = [solid.slice(float(z)) for z in np.linspace(z0 + e, z1 - e, heights)]
            cuts = [to_shapely(c) for c in cuts if not c.is_empty()]
            if not cuts:
                continue
            shape = shapely.union_all(cuts)
            if grow > 0:
                shape = shape.buffer(grow, join_style="mitre", mitre_limit=2.0)
        circle = shapely.minimum_bounding_circle(shape)
        c = circle.centroid
        r = float(shapely.minimum_bounding_radius(shape))
        disc = isinstance(shape, Polygon) and not shape.interiors and shape.area >= 0.995 * np.pi * r * r
        out.append(Slab(float(z0), float(z1), shape, (c.x, c.y), r, disc))
    return tuple(out)


def place2d(shape, T: np.ndarray):
    """``shape`` moved by the xy part of a (4, 4) pose (rotation about z and translation)."""
    R, t = T[:2, :2], T[:2, 3]
    return shapely.transform(shape, lambda p: p @ R.T + t)


def intersection(a: m3d.Manifold, Ta: np.ndarray, b: m3d.Manifold, Tb: np.ndarray) -> tuple[float, np.ndarray | None]:
    """Exact volume (mm³) of the overlap of a at pose Ta and b at pose Tb, and its centre (world)."""
    common = a.transform(Ta[:3, :]) ^ b.transform(Tb[:3, :])
    vol = common.volume()
    if vol <= 0:
        return 0.0, None
    lo, hi = np.asarray(common.bounding_box()).reshape(2, 3)
    return float(vol), (lo + hi) / 2


def min_gap(a: m3d.Manifold, Ta: np.ndarray, b: m3d.Manifold, Tb: np.ndarray, search: float) -> float:
    """Closest distance (mm) between a at Ta and b at Tb, or ``search`` if farther."""
    return float(a.transform(Ta[:3, :]).min_gap(b.transform(Tb[:3, :]), search))


def from_mesh(vertices: np.ndarray, faces: np.ndarray) -> m3d.Manifold:
    """A solid from a watertight triangle mesh (vertices (n, 3) mm, faces (m, 3))."""
    mesh = m3d.Mesh(vert_properties=np.asarray(vertices, dtype=np.float32), tri_verts=np.asarray(faces, dtype=np.uint32))
    solid = m3d.Manifold(mesh)
    if solid.status() != m3d.Error.NoError:
        raise ValueError(f"not a manifold solid: {solid.status()}")
    return solid


def shell_count(solid: m3d.Manifold) -> int:
    """The number of separate shells of a solid (a sealed void inside it is one more)."""
    return len(solid.decompose())


def empty_parts(parts) -> list:
    """Printed parts whose solid came out empty (a design value left no material)."""
    return [p for p in parts if p.printed and (p.solid.is_empty() or p.solid.volume() <= 0.0)]


def oversize(parts, envelope, tol: float = 1e-9) -> list[tuple[object, np.ndarray]]:
    """Printed parts too big for the printer in any orientation: [(part, its extents sorted (3,) mm)].
    ``parts``: objects with ``.solid`` and ``.printed``; ``envelope``: (3,) mm, any order."""
    env = np.sort(np.asarray(envelope, dtype=float))
    out = []
    for p in parts:
        if not p.printed:
            continue
        v, _ = mesh_arrays(p.solid)
        if not len(v):
            continue
        ext = np.sort(v.max(axis=0) - v.min(axis=0))
        if np.any(ext > env + tol):
            out.append((p, ext))
    return out


def refuse_oversize(parts, envelope, key: str) -> None:
    """Raise ``DesignError`` naming ``key`` (the design value that sizes the parts) for the first printed
    part too big for the printer in every orientation (``oversize``): what ``build`` will not write."""
    for part, ext in oversize(parts, envelope):
        raise DesignError(f"{part.name} measures {ext.round(1)} mm and does not fit the printer in any orientation", key)
