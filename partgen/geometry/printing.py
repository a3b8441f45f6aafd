"""How a part prints, measured on its triangle mesh (any mechanism's part): the area that needs
support beyond the printer's overhang angle, the area that rests flat on the bed, the shells (a
part is one shell; a second, inward-facing shell is a sealed void), the print orientation that
needs the least support, and whether a bore is open where its pin goes in.

Conventions: ``vertices`` (n, 3) float mm, ``faces`` (m, 3) int, outward winding (a solid's
signed volume is positive). "Down" is a unit vector; a part lies on the bed with its extreme
vertices along down at the bed. A face needs support when it faces down more steeply than the
overhang angle, measured from the vertical (a vertical wall is 0°, a flat ceiling 90°): its
outward normal n has n·down > sin(angle). Faces lying on the bed need none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import manifold3d as m3d
import numpy as np
import shapely
from shapely.geometry import Polygon

from ..design.graph import components
from .solid import mesh_arrays

__all__ = ["face_areas", "rotation_between", "overhang_area", "bed_contact_area", "shells", "Orientation",
           "flat_faces", "best_orientation", "least_support_flip", "MIN_BED_CONTACT_MM2", "bore_open", "footprint"]

MIN_BED_CONTACT_MM2 = 20.0  # mm²: the least flat contact with the bed a printed part may stand on
FLAT = 1e-6  # a face lies in a plane if its normal is within this (1 − cos) of the plane's
ON_BED = 1e-3  # mm: a vertex this close to the bed plane touches it (float32 STLs keep ~1e-5 mm)


def face_areas(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(m,) face areas mm² and (m, 3) unit outward normals (zero for degenerate faces)."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    cross = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    norm = np.linalg.norm(cross, axis=1)
    return norm / 2, cross / np.where(norm > 0, norm, 1.0)[:, None]


def rotation_between(a, b) -> np.ndarray:
    """(3, 3) the rotation that turns unit direction ``a`` onto ``b`` (half a turn about x or y if
    they are opposite)."""
    a = np.asarray(a, float) / np.linalg.norm(a)
    b = np.asarray(b, float) / np.linalg.norm(b)
    axis = np.cross(a, b)
    s, c = float(np.linalg.norm(axis)), float(a @ b)
    if s < 1e-12:
        if c > 0:
            return np.eye(3)
        # half a turn about any axis perpendicular to a
        p = np.cross(a, [1.0, 0, 0] if abs(a[0]) < 0.9 else [0, 1.0, 0])
        p /= np.linalg.norm(p)
        return 2 * np.outer(p, p) - np.eye(3)
    k = axis / s
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + s * K + (1 - c) * K @ K


def _on_bed(vertices, faces, normals, down) -> np.ndarray:
    """(m,) faces lying flat on the bed when the part rests along ``down``."""
    h = np.asarray(vertices, float) @ down
    bed = h.max()
    return (np.all(h[faces] >= bed - ON_BED, axis=1)) & (normals @ down > 1 - FLAT)


def _contact_and_overhang(vertices, faces, area, normals, down, angle_deg: float) -> tuple[float, float]:
    """mm² flat on the bed and mm² overhanging steeper than ``angle_deg`` (off the bed) of a part
    resting along unit ``down``, from its faces' areas and unit normals (``face_areas``)."""
    bed = _on_bed(vertices, faces, normals, down)
    steep = normals @ down > math.sin(math.radians(angle_deg))
    return float(area[bed].sum()), float(area[steep & ~bed].sum())


def overhang_area(vertices: np.ndarray, faces: np.ndarray, down=(0.0, 0.0, -1.0), angle_deg: float = 45.0) -> float:
    """mm² of faces steeper than ``angle_deg`` from the vertical facing down, those on the bed left out."""
    d = np.asarray(down, float) / np.linalg.norm(down)
    f = np.asarray(faces, np.int64)
    return _contact_and_overhang(vertices, f, *face_areas(vertices, f), d, angle_deg)[1]


def bed_contact_area(vertices: np.ndarray, faces: np.ndarray, down=(0.0, 0.0, -1.0)) -> float:
    """mm² of the part flat on the bed (0 for a point or a line contact)."""
    d = np.asarray(down, float) / np.linalg.norm(down)
    f = np.asarray(faces, np.int64)
    area, n = face_areas(vertices, f)
    return float(area[_on_bed(vertices, f, n, d)].sum())


def footprint(vertices: np.ndarray, faces: np.ndarray, down=(0.0, 0.0, -1.0)):
    """The region the part rests on, as a shapely shape in the bed's plane: the union of its faces flat
    on the bed, in coordinates (x, y) of the frame whose −z is ``down`` (the part's own x, y when
    down is −z). Empty for a point or line contact."""
    d = np.asarray(down, float) / np.linalg.norm(down)
    f = np.asarray(faces, np.int64)
    _, n = face_areas(vertices, f)
    R = rotation_between(d, (0.0, 0.0, -1.0))
    xy = (np.asarray(vertices, float) @ R.T)[:, :2]
    tris = [Polygon(xy[t]) for t in f[_on_bed(vertices, f, n, d)]]
    return shapely.union_all([t for t in tris if t.area > 0]) if tris else Polygon()


def shells(vertices: np.ndarray, faces: np.ndarray) -> list[float]:
    """Signed volume (mm³) of each shell (faces connected through shared vertices), largest first.
    A solid part has one positive shell; a negative one is a sealed void inside it."""
    f = np.asarray(faces, np.int64)
    v = np.asarray(vertices, float)
    label = components(len(v), np.concatenate([f[:, 0], f[:, 1]]), np.concatenate([f[:, 1], f[:, 2]]))
    _, shell = np.unique(label[f[:, 0]], return_inverse=True)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6
    out = np.bincount(shell.ravel(), weights=vol)
    return sorted((float(x) for x in out), key=lambda x: -abs(x))


@dataclass(frozen=True)
class Orientation:
    """A print orientation: ``rotation`` (3, 3) takes the part's frame to the print frame (z up,
    the bed at the part's lowest z); the support it needs and its flat contact with the bed, mm²."""

    rotation: np.ndarray
    down: tuple[float, float, float]  # in the part's frame: the direction that points at the bed
    overhang_mm2: float
    contact_mm2: float
    height_mm: float


def _resting_planes(v: np.ndarray, f: np.ndarray, top: int = 64) -> tuple[np.ndarray, np.ndarray]:
    """The planes the part can rest on — its convex hull's, the largest ``top`` hull facets — as
    outward unit normals (k, 3), and the area (k,) mm² of the part's own faces lying in each (0
    where it would rest on points or edges)."""
    area, n = face_areas(v, f)
    hv, hf = mesh_arrays(m3d.Manifold.hull_points(np.ascontiguousarray(v)))
    ha, hn = face_areas(hv, hf)
    keys, inv = np.unique(np.round(np.column_stack([hn, np.einsum("ij,ij->i", hn, hv[hf[:, 0]])]), 5), axis=0,
                          return_inverse=True)
    facet = np.bincount(inv.ravel(), weights=ha)
    keys = keys[np.argsort(-facet, kind="stable")[:top]]
    normals = keys[:, :3] / np.linalg.norm(keys[:, :3], axis=1)[:, None]
    h = v @ normals.T  # (vertices, planes): each plane's extreme is the hull's
    # a part face lies on a plane if it faces the same way and its vertices are at the plane's extreme
    on = (n @ normals.T > 1 - FLAT) & np.all(h[f] >= h.max(axis=0)[None, None, :] - ON_BED, axis=1)
    return normals, area @ on


def flat_faces(vertices: np.ndarray, faces: np.ndarray, top: int | None = None) -> list[tuple[np.ndarray, float]]:
    """The flat faces the part can rest on (planes of its convex hull that its own faces lie in):
    [(outward unit normal (3,), flat area mm²)], largest first, at most ``top``."""
    normals, contact = _resting_planes(np.asarray(vertices, float), np.asarray(faces, np.int64))
    order = [k for k in np.argsort(-contact, kind="stable") if contact[k] > 0]
    return [(normals[k], float(contact[k])) for k in order[:top]]


def best_orientation(vertices: np.ndarray, faces: np.ndarray, angle_deg: float = 45.0, min_contact_mm2: float = 0.0
                     ) -> Orientation:
    """The orientation that needs the least support of the part resting on any of its flat faces
    with a contact of at least ``min_contact_mm2``: it lies on its largest flat face unless another
    needs less support (ties: more contact, then lower). A part without a flat face that large
    rests in whichever hull plane needs the least support (it prints on its supports; the caller
    sees the small or zero contact)."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    normals, contact = _resting_planes(v, f)
    ok = np.flatnonzero(contact >= min_contact_mm2)
    if not len(ok):
        ok = np.arange(len(normals))
    area, n = face_areas(v, f)
    downs = normals[ok]
    h = v @ downs.T
    steep = n @ downs.T > math.sin(math.radians(angle_deg))  # (faces, candidates)
    on_bed = np.all(h[f] >= h.max(axis=0)[None, None, :] - ON_BED, axis=1) & (n @ downs.T > 1 - FLAT)
    over = area @ (steep & ~on_bed)
    height = h.max(axis=0) - h.min(axis=0)
    k = min(range(len(ok)), key=lambda i: (round(float(over[i]), 3), -round(float(contact[ok[i]]), 3),
                                           round(float(height[i]), 3), i))
    return Orientation(rotation_between(downs[k], (0.0, 0.0, -1.0)), tuple(float(x) for x in downs[k]),
                       float(over[k]), float(contact[ok[k]]), float(height[k]))


def least_support_flip(solid: m3d.Manifold, angle_deg: float = 45.0, min_contact_mm2: float = MIN_BED_CONTACT_MM2) -> bool:
    """Whether a part made along z (a stack of prisms, a cap on a flat base: the faces it can lie on
    are its bottom and its top) prints upside down (``Part.print_flip``): it lies on its larger flat
    z-face unless the other needs less support beyond ``angle_deg``. Faces with less than
    ``min_contact_mm2`` of flat contact are left out while the other has that much; ties: the
    larger contact, then as made."""
    v, f = mesh_arrays(solid)
    v, f = np.asarray(v, float), np.asarray(f, np.int64)
    area, n = face_areas(v, f)  # once for both sides
    cands = []
    for flip, down in ((False, (0.0, 0.0, -1.0)), (True, (0.0, 0.0, 1.0))):
        contact, over = _contact_and_overhang(v, f, area, n, np.asarray(down, float), angle_deg)
        cands.append((round(over, 1), -round(contact, 1), flip))
    ok = [c for c in cands if -c[1] >= min_contact_mm2] or cands
    return min(ok)[2]


def bore_open(solid: m3d.Manifold, point, direction, radius: float, length: float, segments: int = 32) -> float:
    """mm³ of ``solid`` inside a rod of ``radius`` from ``point`` along ``direction`` for ``length``
    mm: 0 when a pin of that radius can come in from there (the bore is open on that side)."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    R = rotation_between((0.0, 0.0, 1.0), d)
    rod = m3d.Manifold.cylinder(length, radius, -1.0, segments, False)
    rod = rod.transform(np.column_stack([R, np.asarray(point, float)]))
    return float((solid ^ rod).volume())
