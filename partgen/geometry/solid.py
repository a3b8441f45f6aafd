"""manifold3d solids from shapely outlines; the one bridge between the 2-D and 3-D kernels."""

from __future__ import annotations

import numpy as np
import manifold3d as m3d
import shapely
from shapely.geometry import MultiPolygon, Polygon

__all__ = ["cylinder", "cross_section", "extrude", "slab", "union", "prisms", "mesh_arrays", "FLIP", "print_arrays",
           "float32_sound", "pack", "unpack"]


def _rings(geom) -> list[np.ndarray]:
    polys = geom.geoms if isinstance(geom, MultiPolygon) else [geom]
    out = []
    for p in polys:
        if p.is_empty:
            continue
        p = shapely.geometry.polygon.orient(p, 1.0)
        out.append(np.asarray(p.exterior.coords)[:-1])
        out += [np.asarray(r.coords)[:-1] for r in p.interiors]
    return out


def cylinder(height: float, radius: float, segments: int = 0, center: bool = False) -> m3d.Manifold:
    """A cylinder along z, ``height`` and ``radius`` mm (centred on z = 0 if ``center``)."""
    return m3d.Manifold.cylinder(height, radius, -1.0, segments, center)


def cross_section(geom: Polygon | MultiPolygon | np.ndarray) -> m3d.CrossSection:
    """A CrossSection of a shapely (multi)polygon or of one (n, 2) ccw contour, mm."""
    contours = [np.asarray(geom, dtype=float)] if isinstance(geom, np.ndarray) else _rings(geom)
    return m3d.CrossSection(contours, m3d.FillRule.EvenOdd)


def extrude(geom, height: float, z0: float = 0.0) -> m3d.Manifold:
    """Prism of the outline from z0 to z0 + height, mm."""
    cs = geom if isinstance(geom, m3d.CrossSection) else cross_section(geom)
    return m3d.Manifold.extrude(cs, height).translate((0.0, 0.0, z0))


def slab(geom, z0: float, z1: float) -> m3d.Manifold:
    """Prism of the outline from exactly z0 to exactly z1 (z1 > z0), mm.

    Stacked prisms must share their faces exactly: z0 + (z1 - z0) can miss z1 by an ulp, and a
    prism whose top is an ulp under the next one's bottom is a separate shell touching it, which
    a float32 STL welds into non-manifold edges. Such a top is snapped onto z1."""
    solid = extrude(geom, z1 - z0, z0)
    if z0 + (z1 - z0) == z1:
        return solid
    mid = 0.5 * (z0 + z1)

    def snap(v):
        v = np.array(v, dtype=np.float64)
        v[:, 2] = np.where(v[:, 2] > mid, z1, z0)
        return v
    return solid.warp_batch(snap)


SLIVER = 1e-6  # mm: edges shorter than this, left where solids meet face to face, are collapsed


def union(solids) -> m3d.Manifold:
    """Union of solids. Solids stacked face to face leave vertices ~1e-9 mm apart, which merge
    into non-manifold edges once written as float32 STL; collapsing edges under SLIVER fixes it."""
    solids = list(solids)
    if len(solids) == 1:
        return solids[0]
    return m3d.Manifold.batch_boolean(solids, m3d.OpType.Add).simplify(SLIVER)


def mesh_arrays(solid: m3d.Manifold) -> tuple[np.ndarray, np.ndarray]:
    """vertices (n, 3) float64 mm and faces (m, 3) int64 of a solid."""
    mesh = solid.to_mesh64() if hasattr(solid, "to_mesh64") else solid.to_mesh()
    return np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3], np.asarray(mesh.tri_verts, dtype=np.int64)


_MESH_FIELDS = ("vert_properties", "tri_verts", "merge_from_vert", "merge_to_vert", "run_index", "run_original_id",
                "run_transform", "run_flags", "face_id", "halfedge_tangent")


def pack(solid: m3d.Manifold) -> dict:
    """A solid as plain numpy arrays (its float64 mesh, every field), to pickle across processes;
    ``unpack`` makes the same solid again (the same vertices and triangles in the same order)."""
    mesh = solid.to_mesh64()
    return {k: np.array(getattr(mesh, k)) for k in _MESH_FIELDS}


def unpack(data: dict) -> m3d.Manifold:
    """The solid ``pack`` packed."""
    return m3d.Manifold(m3d.Mesh64(**{k: np.ascontiguousarray(v) if v.size or k in _MESH_FIELDS[:2] else None
                                      for k, v in data.items()}))


def prisms(items) -> m3d.Manifold:
    """Union of prisms; items: iterable of (outline, z0, z1) with z1 > z0, mm."""
    return union([slab(g, z0, z1) for g, z0, z1 in items])


FLIP = np.diag([1.0, -1.0, -1.0, 1.0])  # half a turn about x: prints a part upside down


def print_arrays(solid: m3d.Manifold, flip: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A solid laid on the build plate (flipped if it prints upside down, lowest point at z = 0):
    vertices (n, 3) float64 mm, faces (m, 3), and the (4, 4) print-from-local pose."""
    v, f = mesh_arrays(solid)
    print_from_local = FLIP.copy() if flip else np.eye(4)
    v = v @ print_from_local[:3, :3].T
    print_from_local[2, 3] = -v[:, 2].min()
    v[:, 2] -= v[:, 2].min()
    return v, f, print_from_local


def float32_sound(verts: np.ndarray, faces: np.ndarray) -> bool:
    """Whether a manifold mesh (verts (n, 3) mm, faces (m, 3)) stays one as a float32 STL: no two
    vertices round to the same float32 point and no face to three points in a line. (A 3-D
    boolean of curved solids leaves, now and then, two intersection vertices 1e-7 mm apart.)"""
    v32 = np.asarray(verts).astype(np.float32) + np.float32(0.0)
    if len(np.unique(v32, axis=0)) != len(v32):
        return False
    t = v32[faces].astype(np.float64)
    return bool(np.all(np.any(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]) != 0.0, axis=1)))

