"""Mass of a part as printed (shell + infill) from its mesh, against the arithmetic of boxes."""

import math

import manifold3d as m3d
import numpy as np
import pytest

from partgen.design.gearing import ToothSystem, make_gear
from partgen.geometry.gear import gear_body
from partgen.geometry.mass import PrintSettings, printed_mass, volume_centroid
from partgen.geometry.outline import circle

RHO = 1.04e-3  # g/mm³


def test_cube_shell_and_infill_by_arithmetic():
    s = PrintSettings(wall=1.2, skin=1.0, infill=0.2)
    m = printed_mass(m3d.Manifold.cube((20.0, 20.0, 20.0)), RHO, s)
    interior = (20 - 2.4) ** 2 * (20 - 2.0)
    assert m.solid_volume == pytest.approx(8000.0)
    assert m.interior_volume == pytest.approx(interior, rel=1e-9)
    assert m.mass == pytest.approx(RHO * (8000 - interior + 0.2 * interior), rel=1e-9)
    assert m.centre == pytest.approx((10.0, 10.0, 10.0), abs=1e-9)


def test_full_infill_is_the_solid_mass():
    spec = make_gear(30, ToothSystem(module=1.5, pressure_angle=math.radians(20), chord_tolerance=0.01))
    gear = gear_body(spec, 6.0, circle(5.1, 0.05, hole=True))
    m = printed_mass(gear, RHO, PrintSettings(infill=1.0, segments=16))
    assert m.mass == pytest.approx(m.solid_mass, rel=1e-9)
    assert m.interior_volume > 0.3 * m.solid_volume  # there is an interior for the infill to matter
    assert m.mass_if_infill(0.2, RHO) < 0.8 * m.solid_mass


def test_shell_heavy_part_shifts_its_centre_of_mass():
    """An L of two boxes: a thin arm (all shell) and a thick block (mostly infill). As printed the
    centre of mass moves toward the thin arm compared with the solid's — by the arithmetic."""
    block = m3d.Manifold.cube((20.0, 20.0, 20.0))
    arm = m3d.Manifold.cube((40.0, 2.0, 2.0)).translate((20.0, 9.0, 9.0))  # 2 mm thick: no interior
    part = block + arm
    s = PrintSettings(wall=1.2, skin=1.0, infill=0.1)
    m = printed_mass(part, RHO, s)
    vb, vi = 8000.0, (20 - 2.4) ** 2 * (20 - 2.0)
    va = 40 * 2 * 2
    # the arm is all shell; erosion also bites the block where the arm joins, a little: compare loosely
    mass = RHO * (vb - vi + s.infill * vi + va)
    assert m.mass == pytest.approx(mass, rel=0.01)
    x_solid = (vb * 10 + va * 40) / (vb + va)
    x_print = (RHO * ((vb - vi) * 10 + s.infill * vi * 10 + va * 40)) / mass
    assert m.solid_centre[0] == pytest.approx(x_solid, rel=1e-9)
    assert m.centre[0] == pytest.approx(x_print, abs=0.05)
    assert m.centre[0] - m.solid_centre[0] > 0.5  # shows (0.94 mm here)


def test_five_percent_infill_error():
    m = printed_mass(m3d.Manifold.cube((30.0, 30.0, 10.0)), RHO, PrintSettings(infill=0.2))
    dm = m.mass_if_infill(0.25, RHO) - m.mass
    assert dm == pytest.approx(RHO * 0.05 * m.interior_volume)


def test_volume_centroid_of_a_translated_box():
    v, c = volume_centroid(m3d.Manifold.cube((2.0, 4.0, 6.0)).translate((1.0, -2.0, 3.0)))
    assert v == pytest.approx(48.0) and np.allclose(c, (2.0, 0.0, 6.0))


def test_layers_agree_with_the_minkowski_erosion():
    """The layer-by-layer interior is the erosion by the wall × skin cylinder: checked against
    manifold3d's own Minkowski difference on a tilted bar joined to a boss with a bore."""
    from partgen.geometry.bennett_link import Bar, Boss, link_solid
    from partgen.geometry.mass import interior

    part = link_solid([Boss((0, 0, 0), (0.3, 0.2, 1.0), 0.0, 10.0, 8.0, 5.15)], [Bar((0, 0, 0), (50, 0, 25), 4.0)])
    s = PrintSettings(wall=1.2, skin=1.0)
    eroded = part.minkowski_difference(m3d.Manifold.cylinder(2 * s.skin, s.wall, -1.0, 24, True))
    ve, ce = volume_centroid(eroded)
    vi, ci = interior(part, s)
    assert vi == pytest.approx(ve, rel=0.01)
    assert np.linalg.norm(ci - ce) < 0.2
