"""geometry.solid.pack/unpack: a solid sent across processes as arrays comes back as the same
solid — the same vertices and triangles in the same order, and a boolean on it gives what the same
boolean on the original gives (the chain's fixed gears are made in a forked child this way)."""

import pickle

import manifold3d as m3d
import numpy as np

from partgen.design.gearing import ToothSystem, make_gear
from partgen.geometry.parts import DFit, fixed_gear
from partgen.geometry.solid import mesh_arrays, pack, unpack


def _same(a, b) -> bool:
    (va, fa), (vb, fb) = mesh_arrays(a), mesh_arrays(b)
    return np.array_equal(va, vb) and np.array_equal(fa, fb)


def test_a_fixed_gear_comes_back_the_same():
    spec = make_gear(20, ToothSystem(module=1.5, pressure_angle=np.radians(20.0), profile_shift=0.0))
    solid = fixed_gear(spec, 6.0, 3.2, (7.5, 0.5), DFit(6.35, 0.05), 4.5, 0.3, 0.001)
    back = unpack(pickle.loads(pickle.dumps(pack(solid))))
    assert back.status() == m3d.Error.NoError
    assert _same(solid, back)
    cut = m3d.Manifold.cube((40.0, 40.0, 3.0), True)
    assert _same(solid - cut, back - cut)  # it behaves as the original in a later boolean
    assert back.volume() == solid.volume()


def test_an_empty_solid_comes_back_empty():
    assert unpack(pack(m3d.Manifold())).is_empty()
