"""A triangle mesh as a binary STL stores it, its STL bytes and its mass properties, in numpy.

``Mesh`` holds what the export layer needs of a part's mesh (vertices, faces, volume, centre of mass,
extents); ``stl_bytes`` writes it. Both compute exactly what trimesh 5 computes, operation for
operation (``trimesh.exchange.stl.export_stl``, ``Trimesh.face_normals``, ``triangles.mass_properties``
by Eberly's polyhedral mass properties), so a kit's STL bytes and manifest are the ones trimesh
wrote; tests/export/test_stl.py holds them equal on every distinct part of the shipped kits. They
are written here because importing trimesh (with the scipy and networkx it imports) is about half a
second, more than building a kit's parts: ``partgen build`` does not import it.

Units: whatever the vertices are in (mm in partgen); volume in those units cubed.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

__all__ = ["Mesh", "stored_mesh", "stl_bytes"]

_HEADER = np.dtype([("header", np.void, 80), ("face_count", "<u4")])
_RECORD = np.dtype([("normals", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attributes", "<u2")])
# a cross product no longer than this has no normal (trimesh's util.TOL_ZERO): its face's normal is 0
_TOL_ZERO = float(np.finfo(np.float64).resolution * 100)


@dataclass(frozen=True, eq=False)
class Mesh:
    """vertices (n, 3) float64, faces (m, 3) int64 (counter-clockwise seen from outside). The derived
    figures are computed once, on first use."""

    vertices: np.ndarray
    faces: np.ndarray

    def __post_init__(self):
        v = np.asarray(self.vertices, dtype=np.float64)
        f = np.asarray(self.faces, dtype=np.int64)
        if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
            raise ValueError(f"a mesh is vertices (n, 3) and faces (m, 3), not {v.shape} and {f.shape}")
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "faces", f)

    @cached_property
    def triangles(self) -> np.ndarray:
        """(m, 3, 3) corners of every face."""
        return self.vertices[self.faces]

    @cached_property
    def _crosses(self) -> np.ndarray:
        t = self.triangles
        e = t[:, 1:, :] - t[:, :2, :]
        return np.cross(e[:, 0], e[:, 1])

    @cached_property
    def face_normals(self) -> np.ndarray:
        """(m, 3) unit normals; (0, 0, 0) for a face with no area."""
        c = self._crosses
        norm = np.sqrt(np.dot(c * c, [1.0, 1.0, 1.0]))
        valid = norm > _TOL_ZERO
        norm[valid] **= -1
        unit = c * norm.reshape((-1, 1))
        out = np.zeros((len(c), 3), dtype=np.float64)
        out[valid] = unit[valid]
        return out

    @cached_property
    def _integrals(self) -> np.ndarray:
        """The volume and first moments (4,) of the closed surface (divergence theorem, per face)."""
        t, c = self.triangles, self._crosses
        f1 = t[:, 0, :] + t[:, 1, :] + t[:, 2, :]
        f2 = t[:, 0, :] ** 2 + t[:, 1, :] ** 2 + t[:, 0, :] * t[:, 1, :] + t[:, 2, :] * f1
        integral = np.zeros((4, len(f1)))
        integral[0] = c[:, 0] * f1[:, 0]
        integral[1:4] = (c * f2).T
        return integral.sum(axis=1) / np.array([6, 24, 24, 24], dtype=np.float64)

    @property
    def volume(self) -> float:
        """Enclosed volume (positive when the faces wind outwards)."""
        return self._integrals[0]

    @property
    def center_mass(self) -> np.ndarray:
        """(3,) centre of the enclosed volume (uniform density)."""
        return self._integrals[1:4] / self._integrals[0]

    @cached_property
    def bounds(self) -> np.ndarray | None:
        """(2, 3) min and max corner of the vertices the faces use; None without any."""
        used = np.zeros(len(self.vertices), dtype=bool)
        used[self.faces] = True
        v = self.vertices[used]
        return np.array([v.min(axis=0), v.max(axis=0)]) if len(v) else None

    @property
    def extents(self) -> np.ndarray | None:
        """(3,) size of the axis-aligned bounding box; None for an empty mesh."""
        b = self.bounds
        return None if b is None else np.ptp(b, axis=0)


def stored_mesh(vertices: np.ndarray, faces: np.ndarray) -> Mesh:
    """The mesh exactly as a binary STL stores it: vertices rounded to float32 (and held as float64)."""
    return Mesh(np.asarray(vertices).astype(np.float32).astype(np.float64), faces)


def stl_bytes(mesh: Mesh) -> bytes:
    """A binary STL: 80 zero bytes, the face count, then per face its unit normal and corners
    (float32, little-endian) and a zero attribute word."""
    header = np.zeros(1, dtype=_HEADER)
    header["face_count"] = len(mesh.faces)
    packed = np.zeros(len(mesh.faces), dtype=_RECORD)
    packed["normals"] = mesh.face_normals
    packed["vertices"] = mesh.triangles
    return header.tobytes() + packed.tobytes()
