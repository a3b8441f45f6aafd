"""Gear solids measured as printed: write the STL, read it back, section it at mid-face and compare
with the formulas (tip diameter m(z + 2 + 2x), thickness at the pitch circle, involute flank)."""

import math

import numpy as np
import pytest
import trimesh

from partgen.design.gearing import ToothSystem, make_gear
from partgen.export.kit import printed
from partgen.geometry.gear import gear_body
from partgen.geometry.outline import circle, d_shape
from partgen.geometry.parts import DFit, Part, fixed_gear
from partgen.testing import measure_spur_gear, mesh_problems, section_outline

ALPHA = math.radians(20)


def as_printed(solid, flip=False) -> trimesh.Trimesh:
    return printed(Part("g", "gear", solid, print_flip=flip)).mesh


CASES = [  # (teeth, module, shift: None = auto, thinning)
    (15, 1.5, 0.0, 0.05),   # the paper's undercut 15-tooth gear
    (15, 1.5, None, 0.05),  # the same, shifted out of undercut
    (40, 1.25, None, 0.05),
    (80, 1.5, 0.0, 0.1),
    (9, 2.0, None, 0.0),
]


@pytest.mark.parametrize("z,m,x,thin", CASES)
def test_gear_section_matches_design(z, m, x, thin):
    spec = make_gear(z, ToothSystem(module=m, pressure_angle=ALPHA, profile_shift=x, backlash_per_gear=thin))
    face = 6.0
    mesh = as_printed(gear_body(spec, face, circle(3.0, 0.01)))
    assert mesh_problems(mesh) == []
    sec = section_outline(mesh, face / 2)
    got = measure_spur_gear(sec, z, m, ALPHA)
    assert got.teeth_found == z
    assert got.tip_diameter == pytest.approx(m * (z + 2 + 2 * spec.profile_shift), abs=0.01)
    assert got.tooth_thickness == pytest.approx(spec.tooth_thickness, abs=0.01)
    assert got.flank_deviation < 0.005
    assert got.centre == pytest.approx((0.0, 0.0), abs=1e-3)


def test_measurement_catches_a_wrong_involute():
    """The flank measurement can fail: a gear generated at 25° measured as a 20° gear is off by
    far more than 5 µm."""
    spec = make_gear(30, ToothSystem(module=1.5, pressure_angle=math.radians(25), profile_shift=0.0,
                                     cutter_tip_coeff=0.2))
    sec = section_outline(as_printed(gear_body(spec, 5.0, circle(3.0, 0.01))), 2.5)
    assert measure_spur_gear(sec, 30, 1.5, ALPHA).flank_deviation > 0.02


def test_flank_tolerance_follows_the_config():
    """A coarse chord tolerance gives a measurably coarser flank; the default is under 5 µm."""
    devs = {}
    for tol in (0.001, 0.1):
        spec = make_gear(40, ToothSystem(module=1.5, pressure_angle=ALPHA, profile_shift=0.0, chord_tolerance=tol))
        sec = section_outline(as_printed(gear_body(spec, 5.0, circle(3.0, 0.01))), 2.5)
        devs[tol] = measure_spur_gear(sec, 40, 1.5, ALPHA).flank_deviation
    assert devs[0.001] < 0.005
    assert devs[0.1] > 2 * devs[0.001]  # chords are capped at 0.5 mm, so coarse is still fine


@pytest.mark.parametrize("z,x", [(15, 0.0), (40, 0.0), (18, None)])
def test_gear_volume_between_root_and_tip_cylinders(z, x):
    spec = make_gear(z, ToothSystem(module=1.5, pressure_angle=ALPHA, profile_shift=x))
    face, bore_r = 6.0, 3.0
    mesh = as_printed(gear_body(spec, face, circle(bore_r, 0.001)))
    hole = math.pi * bore_r**2 * face
    assert math.pi * spec.root_radius**2 * face - hole < mesh.volume < math.pi * spec.tip_radius**2 * face - hole
    # about half the annulus between root and tip is tooth
    tooth = mesh.volume + hole - math.pi * spec.root_radius**2 * face
    annulus = math.pi * (spec.tip_radius**2 - spec.root_radius**2) * face
    assert 0.3 < tooth / annulus < 0.7


def test_fixed_gear_boss_is_a_clocked_d():
    """A G gear's boss is a D whose flat sits at -90° - clocking relative to tooth 0."""
    spec = make_gear(20, ToothSystem(module=1.5, pressure_angle=ALPHA, profile_shift=0.0))
    boss = DFit(6.35, 0.05)
    clock = 0.3
    solid = fixed_gear(spec, 6.0, 5.1, (7.5, 0.5), boss, 4.5, clock, 0.001)
    mesh = as_printed(solid)
    assert mesh_problems(mesh) == []
    sec = section_outline(mesh, 6.0 + 0.5 + 2.0)  # through the boss
    from shapely.geometry import Point
    from shapely.ops import nearest_points
    near = nearest_points(sec.exterior, Point(0, 0))[0]  # the middle of the flat
    closest = math.atan2(near.y, near.x)
    assert math.hypot(near.x, near.y) == pytest.approx(boss.radius - 1.0, abs=0.01)
    assert math.cos(closest - (-math.pi / 2 - clock)) > math.cos(0.2)
    assert len(sec.interiors) == 1  # the round bore
    assert sec.interiors[0].length == pytest.approx(2 * math.pi * 5.1, rel=1e-3)


def test_d_bore_keeps_the_gear_from_turning():
    """A D-bore gear on a D-flat shaft: turned by a few degrees they overlap, aligned they don't."""
    import manifold3d as m3d
    from partgen.geometry.solid import extrude
    spec = make_gear(24, ToothSystem(module=1.5, pressure_angle=ALPHA, profile_shift=0.0))
    fit = DFit(5.0, 0.05)
    gear = gear_body(spec, 6.0, fit.hole(0.005))
    shaft = extrude(fit.shaft(0.005), 6.0)
    assert (gear ^ shaft).volume() < 1e-6
    turned = gear.rotate((0.0, 0.0, 5.0))
    assert (turned ^ shaft).volume() > 0.01
