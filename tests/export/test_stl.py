"""export.stl: the numpy mesh partgen writes and weighs its parts with, measured on solids whose
figures are known, and against trimesh where a face has no area (tests/export/test_manifest_schema.py
holds it equal to trimesh on every shipped kit's parts)."""

import manifold3d as m3d
import numpy as np
import pytest
import trimesh

from partgen.export.stl import Mesh, stl_bytes, stored_mesh
from partgen.export.verify import read_stl
from partgen.geometry.solid import mesh_arrays


def test_a_box_weighs_as_its_formula():
    v, f = mesh_arrays(m3d.Manifold.cube((10.0, 20.0, 30.0)).translate((1.0, -2.0, 3.0)))
    m = stored_mesh(v, f)
    assert m.volume == pytest.approx(6000.0, rel=1e-12)
    assert m.center_mass == pytest.approx([6.0, 8.0, 18.0], abs=1e-9)
    assert list(m.extents) == [10.0, 20.0, 30.0]
    assert np.allclose(np.linalg.norm(m.face_normals, axis=1), 1.0)
    # every normal points out of the box: along the face's outward axis
    centres = m.triangles.mean(axis=1) - m.center_mass
    assert np.all(np.einsum("ij,ij->i", centres, m.face_normals) > 0)


def test_stl_bytes_read_back_as_the_mesh():
    v, f = mesh_arrays(m3d.Manifold.cylinder(5.0, 3.0, 3.0, 24))
    m = stored_mesh(v, f)
    data = stl_bytes(m)
    assert len(data) == 84 + 50 * len(f) and data[:80] == bytes(80)
    verts, faces = read_stl(data)
    assert len(faces) == len(f) and np.array_equal(np.sort(verts, axis=0), np.sort(m.vertices.astype(np.float32), axis=0))


def test_a_face_without_area_has_a_zero_normal_as_in_trimesh():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0]], dtype=float)
    f = np.array([[0, 1, 2], [0, 1, 3]])  # the second face's corners lie on one line
    m = Mesh(v, f)
    assert np.array_equal(m.face_normals, [[0, 0, 1], [0, 0, 0]])
    assert stl_bytes(m) == trimesh.exchange.stl.export_stl(trimesh.Trimesh(v, f, process=False))


def test_a_mesh_is_vertices_and_faces():
    with pytest.raises(ValueError, match=r"\(n, 3\)"):
        Mesh(np.zeros((4, 2)), np.zeros((1, 3), dtype=int))
