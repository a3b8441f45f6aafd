"""Verify a part as a slicer reads it: the binary STL's bytes, vertices merged where their float32
positions are exactly equal, then one closed, oriented 2-manifold shell of positive volume.

What a slicer sees is the file, not the float64 solid it came from: two vertices 1e-9 mm apart are
distinct in the kernel but one vertex in the STL, and a face whose corners merge has no area. So
every count here is taken on the file's own numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..design.graph import components

__all__ = ["MeshReport", "read_stl", "mesh_report"]

_RECORD = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])


@dataclass(frozen=True)
class MeshReport:
    """Counts of one STL after a slicer's vertex merge.

    shells: edge-connected bodies; non_manifold_edges: edges of more than two faces;
    boundary_edges: edges of one face (holes in the skin); misoriented_edges: edges two faces
    traverse the same way (inconsistent winding); pinched_vertices: vertices whose faces form more
    than one fan (bodies touching at a point); zero_area_faces: faces with two corners merged or
    all three in a line; volume_mm3: signed volume (positive when the normals point out).
    """

    triangles: int
    vertices: int
    shells: int
    non_manifold_edges: int
    boundary_edges: int
    misoriented_edges: int
    pinched_vertices: int
    zero_area_faces: int
    volume_mm3: float

    @property
    def ok(self) -> bool:
        return (self.triangles > 0 and self.shells == 1 and self.non_manifold_edges == 0 and self.boundary_edges == 0
                and self.misoriented_edges == 0 and self.pinched_vertices == 0 and self.zero_area_faces == 0
                and self.volume_mm3 > 0)

    def problems(self) -> list[str]:
        """What is wrong, in words (empty when ``ok``)."""
        out = []
        if self.triangles == 0:
            out.append("no triangles")
        if self.shells != 1:
            out.append(f"{self.shells} shells")
        for n, what in ((self.non_manifold_edges, "edges shared by more than two faces"),
                        (self.boundary_edges, "open (boundary) edges"),
                        (self.misoriented_edges, "edges with inconsistent winding"),
                        (self.pinched_vertices, "vertices whose faces are not one fan (bodies touching there)"),
                        (self.zero_area_faces, "zero-area faces")):
            if n:
                out.append(f"{n} {what}")
        if not self.volume_mm3 > 0:
            out.append(f"volume {self.volume_mm3:.4g} mm³ (inside out)")
        return out


def read_stl(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """A binary STL's vertices merged as a slicer merges them (exactly equal float32 positions;
    -0.0 is 0.0): vertices (n, 3) float32, mm, and faces (m, 3) int64."""
    if len(data) < 84:
        raise ValueError("not a binary STL: shorter than its 84-byte header")
    count = int(np.frombuffer(data, "<u4", 1, 80)[0])
    if len(data) != 84 + 50 * count:
        raise ValueError(f"not a binary STL: {len(data)} bytes for {count} triangles")
    corners = np.frombuffer(data, _RECORD, count, 84)["v"].reshape(-1, 3) + np.float32(0.0)
    bits = corners.view("<u4")  # equal floats (after -0.0 -> 0.0) have equal bits
    xy = (bits[:, 0].astype(np.uint64) << np.uint64(32)) | bits[:, 1]  # (x, y) as one key: two sort keys, not three
    order = np.lexsort((bits[:, 2], xy))
    new = np.r_[True, np.any(bits[order[1:]] != bits[order[:-1]], axis=1)] if len(order) else np.zeros(0, bool)
    ids = np.empty(len(order), dtype=np.int64)
    ids[order] = np.cumsum(new) - 1
    return corners[order[new]], ids.reshape(-1, 3)


def mesh_report(verts: np.ndarray, faces: np.ndarray) -> MeshReport:
    """Count what makes a mesh (verts (n, 3) mm, faces (m, 3) int) other than one closed,
    oriented 2-manifold shell."""
    m = len(faces)
    if m == 0:
        return MeshReport(0, len(verts), 0, 0, 0, 0, 0, 0, 0.0)
    v = np.asarray(verts, dtype=np.float64)
    tri = v[faces]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    collapsed = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])
    zero = collapsed | ~np.any(cross != 0.0, axis=1)
    volume = float(np.einsum("ij,ij->i", tri[:, 0], cross).sum() / 6.0)

    # directed edges (a -> b) of every face, and the undirected edge each belongs to
    a = faces.reshape(-1)
    b = faces[:, [1, 2, 0]].reshape(-1)
    face_of = np.repeat(np.arange(m), 3)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    key = lo * np.int64(len(v)) + hi
    order = np.argsort(key, kind="stable")
    ks = key[order]
    starts = np.flatnonzero(np.r_[True, ks[1:] != ks[:-1]])
    counts = np.diff(np.r_[starts, len(ks)])
    boundary = int(np.sum(counts == 1))
    non_manifold = int(np.sum(counts > 2))
    # two-face edges: the faces must traverse them in opposite directions
    two = starts[counts == 2]
    e1, e2 = order[two], order[two + 1]
    misoriented = int(np.sum(a[e1] == a[e2]))

    # shells: faces joined across shared edges (bodies touching along an edge count as one here,
    # and are caught as non-manifold edges)
    same = ks[1:] == ks[:-1]
    shells_lbl = components(m, face_of[order[:-1][same]], face_of[order[1:][same]])
    shells = int(np.count_nonzero(shells_lbl == np.arange(m)))  # a component's label is its smallest face

    # pinched vertices: corners (face, vertex) joined across each two-face edge at both of its ends;
    # a vertex whose corners form more than one group has faces in more than one fan
    corner = np.arange(3 * m).reshape(m, 3)
    f1, f2 = face_of[e1], face_of[e2]
    ends = []
    for end in (lo[e1], hi[e1]):
        c1 = corner[f1, np.argmax(faces[f1] == end[:, None], axis=1)]
        c2 = corner[f2, np.argmax(faces[f2] == end[:, None], axis=1)]
        ends.append((c1, c2))
    ca = np.concatenate([e[0] for e in ends])
    cb = np.concatenate([e[1] for e in ends])
    lbl = components(3 * m, ca, cb)
    # a fan joins corners of one vertex only, and its label is its smallest corner: one root per fan
    per_vertex = np.bincount(faces.reshape(-1)[lbl == np.arange(3 * m)], minlength=len(v))
    pinched = int(np.sum(per_vertex > 1))
    return MeshReport(m, len(v), shells, non_manifold, boundary, misoriented, pinched, int(zero.sum()), volume)
