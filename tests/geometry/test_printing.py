"""How a part prints, measured on meshes against formulas: overhang beyond 45°, flat contact with the
bed, shells and sealed voids, the orientation that needs the least support, open and sealed bores."""

import math

import manifold3d as m3d
import numpy as np
import pytest

from partgen.geometry.printing import (bed_contact_area, best_orientation, bore_open, footprint, overhang_area,
                                       rotation_between, shells)
from partgen.geometry.solid import mesh_arrays

UP, DOWN = (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)


def arrays(solid):
    return mesh_arrays(solid)


def tee():
    """A 10 × 10 × 20 column with a 30 × 10 × 2 slab on top, overhanging 10 mm on either side."""
    column = m3d.Manifold.cube((10.0, 10.0, 20.0)).translate((10.0, 0.0, 0.0))
    slab = m3d.Manifold.cube((30.0, 10.0, 2.0)).translate((0.0, 0.0, 20.0))
    return column + slab


def test_cube_needs_no_support_and_sits_on_a_face():
    v, f = arrays(m3d.Manifold.cube((20.0, 20.0, 20.0)))
    assert overhang_area(v, f, DOWN) == 0.0
    assert bed_contact_area(v, f, DOWN) == pytest.approx(400.0)
    assert shells(v, f) == [pytest.approx(8000.0)]


def test_overhanging_slab_by_arithmetic():
    """The slab's underside beyond the column, 2 × 10 × 10 mm², needs support; upside down none does."""
    v, f = arrays(tee())
    assert overhang_area(v, f, DOWN) == pytest.approx(200.0)
    assert bed_contact_area(v, f, DOWN) == pytest.approx(100.0)
    assert overhang_area(v, f, UP) == 0.0  # lying on the slab: the column stands on it
    assert bed_contact_area(v, f, UP) == pytest.approx(300.0)
    o = best_orientation(v, f)
    assert o.overhang_mm2 == 0.0 and o.contact_mm2 == pytest.approx(300.0)
    w = v @ o.rotation.T
    assert bed_contact_area(w, f, DOWN) == pytest.approx(300.0) and overhang_area(w, f, DOWN) == 0.0


@pytest.mark.parametrize("slope_deg", [30.0, 44.0, 46.0, 60.0])
def test_the_overhang_angle_is_from_the_vertical(slope_deg):
    """A wedge whose underside rises at ``slope`` from the horizontal (its other faces vertical or up):
    the underside is 90° − slope from the vertical and needs support when that exceeds 45°; its
    area is W·L / cos(slope)."""
    L, W = 30.0, 10.0
    H = L * math.tan(math.radians(slope_deg))
    pts = [(0, y, 0) for y in (0, W)] + [(0, y, H) for y in (0, W)] + [(L, y, H) for y in (0, W)]
    v, f = arrays(m3d.Manifold.hull_points(np.array(pts, float)))
    under = W * L / math.cos(math.radians(slope_deg))
    assert overhang_area(v, f, DOWN) == pytest.approx(under if 90 - slope_deg > 45 else 0.0)
    assert overhang_area(v, f, DOWN, angle_deg=90 - slope_deg + 1) == 0.0
    assert overhang_area(v, f, DOWN, angle_deg=90 - slope_deg - 1) == pytest.approx(under)


def test_sealed_cavity_is_a_second_shell():
    outer = m3d.Manifold.cube((20.0, 20.0, 20.0), True)
    v, f = arrays(outer - m3d.Manifold.cube((8.0, 8.0, 8.0), True))
    s = shells(v, f)
    assert len(s) == 2 and s[0] == pytest.approx(8000.0) and s[1] == pytest.approx(-512.0)
    # the same cavity opened to the top is one shell
    hole = m3d.Manifold.cylinder(20.0, 3.0, -1.0, 32).translate((0.0, 0.0, 0.0))
    v, f = arrays(outer - m3d.Manifold.cube((8.0, 8.0, 8.0), True) - hole)
    assert len(shells(v, f)) == 1


def test_a_sphere_touches_the_bed_at_a_point():
    v, f = arrays(m3d.Manifold.sphere(20.0, 128))
    assert bed_contact_area(v, f, DOWN) == 0.0  # on its pole: a point contact
    # its best face is one facet, far under a 100 mm² rule
    assert best_orientation(v, f, min_contact_mm2=100.0).contact_mm2 < 4.0
    # the southern hemisphere beyond 45° from the vertical: a cap of height r(1 − cos 45°)
    cap = 2 * math.pi * 20.0 * 20.0 * (1 - math.cos(math.radians(45)))
    assert overhang_area(v, f, DOWN) == pytest.approx(cap, rel=0.005)


def test_blind_bore_open_on_one_side_only():
    block = m3d.Manifold.cube((30.0, 30.0, 30.0), True) - m3d.Manifold.cylinder(20.0, 5.15, -1.0, 48).translate((0, 0, -5.0))
    # the bore runs from z = -5 to the top face: a pin comes in from above, not from below
    assert bore_open(block, (0, 0, 15.0), UP, 4.9, 20.0) < 1e-9
    assert bore_open(block, (0, 0, 14.0), DOWN, 4.9, 18.0) < 1e-9
    assert bore_open(block, (0, 0, -15.0), DOWN, 4.9, 20.0) < 1e-9  # outside, below: nothing
    assert bore_open(block, (0, 0, -15.0), UP, 4.9, 20.0) > 100.0  # from below it is sealed


def test_rotation_between():
    rng = np.random.default_rng(1)
    for _ in range(20):
        a, b = rng.normal(size=3), rng.normal(size=3)
        R = rotation_between(a, b)
        assert np.allclose(R @ (a / np.linalg.norm(a)), b / np.linalg.norm(b), atol=1e-12)
        assert np.allclose(R @ R.T, np.eye(3), atol=1e-12) and np.linalg.det(R) == pytest.approx(1.0)
    R = rotation_between((0, 0, 1.0), (0, 0, -1.0))
    assert np.allclose(R @ (0, 0, 1.0), (0, 0, -1.0)) and np.linalg.det(R) == pytest.approx(1.0)


def test_footprint_of_a_stand():
    """A post on a disc foot: the footprint is the foot's disc; a centre 10 mm off the axis is
    r − 10 from its edge."""
    foot = m3d.Manifold.cylinder(4.0, 40.0, -1.0, 128)
    post = m3d.Manifold.cylinder(60.0, 8.0, -1.0, 64)
    v, f = arrays(foot + post)
    fp = footprint(v, f)
    area = 0.5 * 128 * 40.0 ** 2 * math.sin(2 * math.pi / 128)  # the 128-gon
    assert fp.area == pytest.approx(area, rel=1e-9)
    from shapely.geometry import Point
    assert fp.exterior.distance(Point(10.0, 0.0)) == pytest.approx(40.0 * math.cos(math.pi / 128) - 10.0, abs=0.05)
    assert footprint(*arrays(m3d.Manifold.sphere(10.0, 64))).area == 0.0
