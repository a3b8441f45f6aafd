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
import trimesh

__all__ = ["face_areas", "rotation_between", "overhang_area", "bed_contact_area", "shells", "Orientation",
           "flat_faces", "best_orientation", "bore_open"]

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


def overhang_area(vertices: np.ndarray, faces: np.ndarray, down=(0.0, 0.0, -1.0), angle_deg: float = 45.0) -> float:
    """mm² of faces steeper than ``angle_deg`` from the vertical facing down, those on the bed left out."""
    d = np.asarray(down, float) / np.linalg.norm(down)
    f = np.asarray(faces, np.int64)
    area, n = face_areas(vertices, f)
    steep = n @ d > math.sin(math.radians(angle_deg))
    return float(area[steep & ~_on_bed(vertices, f, n, d)].sum())


def bed_contact_area(vertices: np.ndarray, faces: np.ndarray, down=(0.0, 0.0, -1.0)) -> float:
    """mm² of the part flat on the bed (0 for a point or a line contact)."""
    d = np.asarray(down, float) / np.linalg.norm(down)
    f = np.asarray(faces, np.int64)
    area, n = face_areas(vertices, f)
    return float(area[_on_bed(vertices, f, n, d)].sum())


def shells(vertices: np.ndarray, faces: np.ndarray) -> list[float]:
    """Signed volume (mm³) of each shell (faces connected through shared vertices), largest first.
    A solid part has one positive shell; a negative one is a sealed void inside it."""
    f = np.asarray(faces, np.int64)
    v = np.asarray(vertices, float)
    edges = np.concatenate([f[:, [0, 1]], f[:, [1, 2]]])
    comps = trimesh.graph.connected_components(edges, nodes=np.unique(f))
    label = np.empty(len(v), np.int64)
    for k, c in enumerate(comps):
        label[np.asarray(c, np.int64)] = k
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6
    out = np.bincount(label[f[:, 0]], weights=vol, minlength=len(comps))
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


def flat_faces(vertices: np.ndarray, faces: np.ndarray, top: int = 12) -> list[tuple[np.ndarray, float]]:
    """The part's largest flat faces it can rest on (planes with every vertex on one side):
    [(outward unit normal (3,), flat area mm²)], largest first, at most ``top``."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    area, n = face_areas(v, f)
    keep = area > 0
    key = np.round(n[keep], 6)
    normals, inv = np.unique(key, axis=0, return_inverse=True)
    totals = np.bincount(inv.ravel(), weights=area[keep])
    out = []
    for k in np.argsort(-totals)[:4 * top]:  # curved surfaces: many normals, each of little area
        d = normals[k] / np.linalg.norm(normals[k])
        a = bed_contact_area(v, f, d)
        if a > 0:
            out.append((d, a))
        if len(out) == top:
            break
    return sorted(out, key=lambda t: -t[1])


def best_orientation(vertices: np.ndarray, faces: np.ndarray, angle_deg: float = 45.0, min_contact_mm2: float = 0.0,
                     top: int = 12) -> Orientation:
    """The orientation that needs the least support among the part resting on each of its ``top``
    largest flat faces (contact at least ``min_contact_mm2``): it lies on its largest flat face
    unless another needs less support (ties: more contact, then lower). Without a flat face of
    that size, the largest one."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    cands = flat_faces(v, f, top)
    if not cands:
        raise ValueError("the part has no flat face to rest on")
    ok = [c for c in cands if c[1] >= min_contact_mm2] or cands[:1]
    best = None
    for d, a in ok:
        over = overhang_area(v, f, d, angle_deg)
        R = rotation_between(d, (0.0, 0.0, -1.0))
        z = v @ R[2]
        key = (round(over, 3), -round(a, 3), round(float(z.max() - z.min()), 3))
        if best is None or key < best[0]:
            best = (key, Orientation(R, tuple(float(x) for x in d), over, a, float(z.max() - z.min())))
    return best[1]


def bore_open(solid: m3d.Manifold, point, direction, radius: float, length: float, segments: int = 32) -> float:
    """mm³ of ``solid`` inside a rod of ``radius`` from ``point`` along ``direction`` for ``length``
    mm: 0 when a pin of that radius can come in from there (the bore is open on that side)."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    R = rotation_between((0.0, 0.0, 1.0), d)
    rod = m3d.Manifold.cylinder(length, radius, -1.0, segments, False)
    rod = rod.transform(np.column_stack([R, np.asarray(point, float)]))
    return float((solid ^ rod).volume())
