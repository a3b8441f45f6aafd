"""Helical and herringbone gears of kind gear_train: twisted extrusions whose every transverse
section is the rack-generated involute turned by the helix (measured on the float32 mesh at three
heights, within 1 µm), the shipped herringbone pair at exactly its 60 mm centre distance, and a
mesh check that is exact in 3-D: nominal 0 mm³, nudged or built with the wrong hand, it overlaps."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
from shapely import contains_xy

from partgen.design.gear_train import transverse_system, twist_over
from partgen.design.gearing import GearSpec, ToothSystem
from partgen.geometry.gear import helical_body
from partgen.geometry.outline import circle
from partgen.geometry.solid import mesh_arrays
from partgen.mechanisms.gear_train.stages.checks import exact_mesh_overlap
from partgen.mechanisms.gear_train.stages.kit import build_train
from partgen.mechanisms.gear_train.mechanism import MECHANISM
from partgen.testing import measure_spur_gear, section_outline

ROOT = Path(__file__).resolve().parents[3]
CFG = ROOT / "configs" / "gear_train_herringbone.yaml"


def test_transverse_system_of_a_normal_hob():
    beta, an = math.radians(30), math.radians(20)
    t = transverse_system(2.0, an, beta, "normal")
    assert t.module == pytest.approx(2.0 / math.cos(beta))
    assert math.tan(t.pressure_angle) == pytest.approx(math.tan(an) / math.cos(beta))
    assert t.addendum_coeff * t.module == pytest.approx(2.0)  # the addendum keeps its mm
    assert transverse_system(2.0, an, beta, "transverse").module == 2.0


@pytest.mark.parametrize("herringbone", [False, True])
def test_every_section_is_the_involute_turned_by_the_helix(herringbone):
    t = transverse_system(2.0, math.radians(20), math.radians(30), "normal")
    spec = GearSpec(19, ToothSystem(t.module, t.pressure_angle, t.addendum_coeff, t.dedendum_coeff, t.cutter_tip_coeff,
                                    0.05, None, 0.001), 0.0)
    face = 10.0
    twist = twist_over(face, math.radians(30), spec.pitch_radius)
    solid = helical_body(spec, face, circle(4.0, 0.01, hole=True), 0.0, twist, herringbone, 0.001)
    v, f = mesh_arrays(solid)
    mesh = trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)  # as the STL stores it
    assert mesh.is_watertight and mesh.is_volume
    for z in (0.5, 3.7, 8.9):
        m = measure_spur_gear(section_outline(mesh, z), 19, t.module, t.pressure_angle, centre=(0.0, 0.0))
        assert m.teeth_found == 19
        assert m.flank_deviation < 1e-3, (z, m.flank_deviation)
        assert m.tooth_thickness == pytest.approx(spec.tooth_thickness, abs=3e-3)
        # tooth 0's centre has turned by the helix: b tan β / r_p up to z (a herringbone's back above half)
        turned = twist * (min(z, face - z) if herringbone else z) / face
        r = spec.pitch_radius
        th = turned + np.linspace(-math.pi / 19, math.pi / 19, 20001)  # a pitch around it: one tooth
        hit = contains_xy(section_outline(mesh, z), r * np.cos(th), r * np.sin(th))
        centre = th[hit].mean()
        assert centre == pytest.approx(turned, abs=2e-4)


@pytest.fixture(scope="module")
def pair(kit_of):
    return kit_of("gear_train_herringbone")


def test_herringbone_pair_at_its_centre_distance_passes_exactly(pair):
    spec = pair.loaded.spec
    assert spec.herringbone and pair.manifest["design"]["stages"][0]["centre_distance_mm"] == pytest.approx(60.0, abs=1e-9)
    assert math.dist(spec.shafts[0].centre, spec.shafts[1].centre) == pytest.approx(60.0, abs=1e-9)
    result = MECHANISM.check(spec, pair.kit, 16)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    h = result.figures["helical_meshes"][0]
    assert h["max_overlap_mm3"] == 0.0 and h["overlap_ratio"] > 0.4


def test_the_exact_check_fails_nudged_or_with_the_wrong_hand(pair):
    spec, kit = pair.loaded.spec, pair.kit
    mesh = spec.meshes[0]
    r2 = spec.gear(mesh.driven).spec.pitch_radius
    assert exact_mesh_overlap(kit, mesh, 3, nudge=0.6 / r2).max() > 0.1  # 0.6 mm at the pitch circle, backlash 0.2
    same_hand = tuple(dataclasses.replace(g, hand=1) for g in spec.gears)
    wrong = dataclasses.replace(spec, gears=same_hand)
    assert exact_mesh_overlap(build_train(wrong), mesh, 3).max() > 1.0
