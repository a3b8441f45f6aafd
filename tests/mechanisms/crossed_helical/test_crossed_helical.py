"""A crossed helical pair on skew shafts (kind crossed_helical): the kinematics (teeth parallel at the
pitch point exactly when Σ = β1 + β2, the ratio z2/z1, the sliding), the shipped 90° pair's flanks
against the analytic helicoid (sections of the float32 mesh vs the turned transverse involute, µm),
a 60° pair. The shipped pair's exact check (0 mm³ at the designed backlash, overlapping with the
backlash made negative), trace, shells and bad input: with the mitre pair's in
tests/mechanisms/test_solid_pairs.py."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml
from shapely import contains_xy

from partgen.design.crossed_helical import crossed_pair
from partgen.geometry.solid import mesh_arrays
from partgen.mechanisms.crossed_helical.contact import contact_angles, designed_backlash, mesh_overlaps
from partgen.mechanisms.crossed_helical.kit import build_crossed
from partgen.testing import measure_spur_gear, section_outline

ROOT = Path(__file__).resolve().parents[3]
CFG = ROOT / "configs" / "gear_train_crossed_helical.yaml"


def _helix_tangent(pair, i: int, hand: int = 1) -> np.ndarray:
    """The tooth line through the pitch point of gear i, differentiated numerically from the twist
    parametrisation (the section turns by twist(b)·z/b) and mapped to the world."""
    r = pair.pitch_radius(i)
    rate = hand * pair.twist(i, 1.0)  # rad per mm of face
    h = 1e-6
    pts = [np.array([r * math.cos(rate * z), r * math.sin(rate * z), z]) for z in (-h, h)]
    t = (pts[1] - pts[0]) / (2 * h)
    R = np.eye(3) if i == 0 else pair.frame2()
    t = R @ t
    return t / np.linalg.norm(t)


@pytest.mark.parametrize("sigma,beta1", [(90.0, 45.0), (90.0, 30.0), (60.0, 20.0)])
def test_teeth_are_parallel_at_the_pitch_point_and_the_ratio_is_the_teeth(sigma, beta1):
    pair = crossed_pair((17, 29), 1.5, math.radians(20), math.radians(beta1), math.radians(sigma))
    t1, t2 = _helix_tangent(pair, 0), _helix_tangent(pair, 1)
    assert abs(abs(t1 @ t2) - 1) < 1e-9  # one tooth line at P
    assert np.allclose(t1, pair.tooth_direction(), atol=1e-9)
    F = pair.frame2()
    assert np.allclose(F.T @ F, np.eye(3)) and np.linalg.det(F) == pytest.approx(1.0)
    assert pair.centre_distance == pytest.approx(1.5 / 2 * (17 / math.cos(pair.helix[0]) + 29 / math.cos(pair.helix[1])))
    # the normal components of the two velocities at P agree for gear 2 at speed2 (rigid-body velocities)
    P = np.array([pair.pitch_radius(0), 0.0, 0.0])
    C2 = np.array([pair.centre_distance, 0.0, 0.0])
    v1 = np.cross([0.0, 0.0, 1.0], P)
    v2 = pair.speed2() * np.cross(pair.axis2, P - C2)
    n = np.cross([1.0, 0.0, 0.0], t1)
    assert v1 @ n == pytest.approx(v2 @ n, rel=1e-12)
    assert abs(pair.speed2()) == pytest.approx(17 / 29)
    # what is left of the relative velocity lies along the teeth: the sliding speed
    slide = v1 - v2
    assert np.linalg.norm(slide - (slide @ t1) * t1) < 1e-9
    assert abs(slide @ t1) == pytest.approx(pair.sliding_speed(), rel=1e-12)
    # the wrong hand (gear 2 left-handed) leaves the teeth crossed
    assert abs(abs(_helix_tangent(pair, 1, hand=-1) @ t1) - 1) > 1e-3


@pytest.fixture(scope="module")
def shipped(kit_of):
    return kit_of("gear_train_crossed_helical")


def test_flanks_are_the_helicoid(shipped):
    """Each gear's mesh (float32, as the STL stores it) sectioned at three heights: the flanks are
    the transverse involute within a µm, and tooth 0's centre has turned by the helix."""
    spec, kit = shipped.loaded.spec, shipped.kit
    worst = 0.0
    for i, name in enumerate(("gear1", "gear2")):
        gear, b = (spec.gear1, spec.gear2)[i], spec.face_width[i]
        v, f = mesh_arrays(kit.part(name).solid)
        mesh = trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)
        twist = spec.pair.twist(i, b)
        for z in (-0.4 * b, 0.05 * b, 0.45 * b):
            out = section_outline(mesh, z)
            m = measure_spur_gear(out, gear.teeth, gear.module, gear.system.pressure_angle, centre=(0.0, 0.0))
            assert m.teeth_found == gear.teeth
            worst = max(worst, m.flank_deviation)
            assert m.tooth_thickness == pytest.approx(gear.tooth_thickness, abs=3e-3)  # chords: a µm or two thin
            turned = twist * z / b  # the mid-plane has tooth 0 on +x; the section turns b tan β / r per face
            r = gear.pitch_radius
            th = turned + np.linspace(-math.pi / gear.teeth, math.pi / gear.teeth, 20001)
            centre = th[contains_xy(out, r * np.cos(th), r * np.sin(th))].mean()
            assert centre == pytest.approx(turned, abs=2e-4)
    assert worst < 2e-3, worst  # mm: 2 µm


def test_a_60_degree_pair_meshes_with_its_designed_backlash(tmp_path):
    """Shafts at 60° (30° + 30°): the same model, another frame; the blocks stand clear of the slanted
    gear (the check's frame test) and the backlash measured in 3-D is the designed one."""
    from partgen import pipeline

    d = yaml.safe_load(CFG.read_text())
    d["shaft_angle_deg"], d["gears"]["helix_angle_deg"] = 60.0, [30.0, 30.0]
    p = tmp_path / "ch60.yaml"
    p.write_text(yaml.safe_dump(d, sort_keys=False))
    spec = pipeline.load(p).spec
    kit = build_crossed(spec)
    assert spec.pair.shaft_angle == pytest.approx(math.radians(60))
    assert mesh_overlaps(kit, 2).max() == 0.0
    c = contact_angles(kit, [0.0], 1e-5)
    backlash = float(c["ahead"][0] - c["behind"][0]) * spec.pair.pitch_radius(1)
    assert designed_backlash(spec) == pytest.approx(0.2)
    assert 0.2 <= backlash <= 0.206
    from partgen.geometry.measure import intersection

    P = kit.poses(0.3)
    assert intersection(kit.part("gear2").solid, P["gear2"], kit.part("base").solid, P["base"])[0] == 0.0
