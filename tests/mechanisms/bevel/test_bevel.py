"""Straight bevel pairs (kind bevel): the cone geometry and the rolling kinematics at any shaft
angle, the shipped mitre pair's flanks measured on the float32 mesh against the exact spherical
involute surface (µm); a 75° pair and a 120° one (gear 2 leaning over gear 1). The shipped pair's
exact check, trace, shells and bad input (a crown or internal bevel refused): with the crossed
helical pair's in tests/mechanisms/test_solid_pairs.py."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml

from partgen.design.bevel import bevel_pair
from partgen.geometry.solid import mesh_arrays
from partgen.mechanisms.bevel.kit import build_bevel
from partgen.mechanisms.bevel.contact import contact_angles, mesh_overlaps
from partgen.mechanisms.bevel.mechanism import MECHANISM
from partgen.testing import measure_bevel_flanks

ROOT = Path(__file__).resolve().parents[3]
CFG = ROOT / "configs" / "bevel_mitre.yaml"


@pytest.mark.parametrize("z1,z2,sigma", [(20, 20, 90.0), (15, 25, 75.0), (18, 30, 50.0), (15, 25, 120.0), (20, 20, 140.0)])
def test_pitch_cones_share_the_apex_and_roll(z1, z2, sigma):
    p = bevel_pair((z1, z2), 2.0, math.radians(20), math.radians(sigma), 6.0)
    g1, g2 = p.gears
    assert g1.pitch_angle + g2.pitch_angle == pytest.approx(math.radians(sigma))
    # one cone distance: both heel pitch circles lie on the sphere R round the apex
    assert g1.pitch_radius / math.sin(g1.pitch_angle) == pytest.approx(g2.pitch_radius / math.sin(g2.pitch_angle))
    F = p.frame2()
    assert np.allclose(F.T @ F, np.eye(3)) and np.linalg.det(F) == pytest.approx(1.0)
    u1, u2 = np.array([0.0, 0.0, 1.0]), F[:, 2]
    assert math.degrees(math.acos(u1 @ u2)) == pytest.approx(sigma)
    # the pitch line is δ_i from each gear's body axis (−u_i), and gear 2's local +x leans to it
    line = p.pitch_line
    assert math.acos(line @ -u1) == pytest.approx(g1.pitch_angle)
    assert math.acos(line @ -u2) == pytest.approx(g2.pitch_angle)
    assert line @ F[:, 0] > 0 and abs(line @ F[:, 1]) < 1e-12
    # rolling: at every point of the pitch line the two rigid-body velocities agree (no slip)
    for s in (0.7, 1.0):
        P = s * p.cone_distance * line
        v1 = np.cross(u1, P)
        v2 = p.speed2() * np.cross(u2, P)
        assert np.allclose(v1, v2, atol=1e-12)
    assert p.speed2() == pytest.approx(-z1 / z2)
    # and the wrong sense slips
    assert not np.allclose(np.cross(u1, line), -p.speed2() * np.cross(u2, line))


@pytest.fixture(scope="module")
def shipped(kit_of):
    return kit_of("bevel_mitre")


def _flanks(kit, name, tooth, thinning=None):
    v, f = mesh_arrays(kit.part(name).solid)
    mesh = trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)  # as the STL stores it
    t = tooth
    return measure_bevel_flanks(mesh, t.teeth, t.module, t.pressure_angle, t.pitch_angle,
                                t.backlash if thinning is None else thinning, t.face_width, t.addendum, t.dedendum)


def test_flanks_are_the_spherical_involute(shipped):
    """Each gear's mesh (float32, as the STL stores it), every triangle sampled on a barycentric grid
    (corners, edges and inside: the flat facets between the exact rays through the apex are measured
    too), against the exact spherical involute surface written in ``partgen.testing`` from the
    rolling great circle (not the design code's closed form): every point on the involute part of a
    flank, over the whole face from toe to heel and on every tooth, lies within a µm of it along
    the flank's normal (0.63 µm measured; the chords sag inside: mean < 0). The same mesh measured
    against a tooth 2 µm thinner than designed fails the bound: the measure can fail."""
    spec, kit = shipped.loaded.spec, shipped.kit
    for name, tooth in (("gear1", spec.gear1), ("gear2", spec.gear2)):
        m = _flanks(kit, name, tooth)
        assert m.teeth_seen == tooth.teeth and len(m.deviation) > 1000 * tooth.teeth // 20
        R, b = tooth.cone_distance, tooth.face_width
        assert m.radii[0] < R - b + 3.0 and m.radii[1] > R - 3.0  # the points span the face
        assert m.worst < 1.0e-3, (name, m.worst)  # mm: 0.63 µm measured on the shipped pair
        assert -0.8e-3 < float(m.deviation.mean()) < 0.0  # chords inside the curve, never outside
        assert _flanks(kit, name, tooth, tooth.backlash - 0.002).worst > 1.0e-3


def test_a_75_degree_pair_meshes_with_its_designed_backlash(tmp_path):
    """Shafts at 75°, 15/25 teeth: the same model in another frame; the gears clear the frame and
    the backlash measured in 3-D is the designed one."""
    from partgen import pipeline

    d = yaml.safe_load(CFG.read_text())
    d["shaft_angle_deg"], d["gears"]["teeth"], d["gears"]["chord_tolerance_mm"] = 75.0, [15, 25], 0.003
    p = tmp_path / "bevel75.yaml"
    p.write_text(yaml.safe_dump(d, sort_keys=False))
    spec = pipeline.load(p).spec
    kit = build_bevel(spec)
    assert mesh_overlaps(kit, 2).max() == 0.0
    c = contact_angles(kit, [0.0, 0.2], 1e-5)
    backlash = (c["ahead"] - c["behind"]) * spec.gear2.pitch_radius
    assert (0.2 <= backlash).all() and (backlash <= 0.208).all(), backlash
    from partgen.geometry.measure import intersection

    for t in (0.0, 2.0):
        P = kit.poses(t)
        for g in ("gear1", "gear2"):
            assert intersection(kit.part(g).solid, P[g], kit.part("base").solid, P["base"])[0] == 0.0


def test_a_120_degree_pair_leans_over_and_checks(tmp_path):
    """Shafts at 120° (pitch cones 60° + 60°): gear 2 leans over gear 1, its block on a leg sloping
    down square to its axis; the exact check passes (no overlap, the designed backlash, the gears clear
    the base, the leg stays behind gear 2's back), the flanks are the spherical involute, and every
    part is one closed shell."""
    from partgen import pipeline

    d = yaml.safe_load(CFG.read_text())
    d["shaft_angle_deg"], d["gears"]["face_width_mm"], d["gears"]["chord_tolerance_mm"] = 120.0, 7.0, 0.003
    p = tmp_path / "bevel120.yaml"
    p.write_text(yaml.safe_dump(d, sort_keys=False))
    spec = pipeline.load(p).spec
    assert [math.degrees(g.pitch_angle) for g in spec.pair.gears] == pytest.approx([60.0, 60.0])
    kit = build_bevel(spec)
    assert spec.pair.axis2[2] < 0 and spec.leg_direction @ spec.pair.axis2 == pytest.approx(0.0, abs=1e-12)
    result = MECHANISM.check(spec, kit, 2)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    f = result.figures
    assert f["max_overlap_mm3"] == 0.0 and 0.2 <= f["backlash_mm"]["min"] <= f["backlash_mm"]["max"] <= 0.206
    assert f["closest_mm"]["gear2-base"] >= spec.gap - 1e-3
    # the block's leg: every vertex of the base above the plate lies behind gear 2's hub along its axis
    v, _ = mesh_arrays(kit.part("base").solid)
    up = v[v[:, 2] > 0.01]
    a = (up - spec.apex) @ spec.pair.axis2
    post = np.hypot(up[:, 0], up[:, 1]) <= spec.shaft_radius[0] + 1e-6  # gear 1's post
    assert (a[~post] <= spec.block_span[1] + 1e-6).all()
    m = _flanks(kit, "gear2", spec.gear2)
    assert m.teeth_seen == 20 and m.worst < 3.0e-3  # chord tolerance 0.003 here
    for part in kit.parts:
        vv, ff = mesh_arrays(part.solid)
        mesh = trimesh.Trimesh(vv, ff)
        assert mesh.is_watertight and len(mesh.split(only_watertight=False)) == 1, part.name
