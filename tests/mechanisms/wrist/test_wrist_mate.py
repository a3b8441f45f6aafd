"""The cross gear's mate (an ABENICS monopole gear): one closed shell, clear of the cross gear over
the workspace (exact 3-D intersections), a wrong mate caught, the ratio and the mid-plane's
conjugate section measured."""

import math
from dataclasses import replace

import numpy as np
import pytest
import shapely
import trimesh

from partgen.core.findings import Result
from partgen.geometry.cross_mate import cross_pose, mate_gear, mate_pose, mate_section
from partgen.geometry.measure import intersection, shell_count
from partgen.mechanisms.wrist.mate import INTERFERENCE_MM3, check_mate, trace_mate
from partgen.testing import mesh_problems


@pytest.fixture(scope="module")
def pair(kit_of):
    """(spec, cross gear solid, mate solid, manifest, folder) of the shipped wrist_sphere kit."""
    loaded, kit, man, folder = kit_of("wrist_sphere")
    by = {p.name: p.solid for p in kit.parts}
    return kit.spec, by["cross_gear"], by["cross_mate"], man, folder, kit


def test_mate_is_one_closed_shell_in_the_kit(pair):
    spec, cs, mp, man, folder, kit = pair
    entry = next(p for p in man["parts"] if p["name"] == "cross_mate")
    mesh = trimesh.load(folder / entry["file"], file_type="stl", force="mesh")
    assert mesh_problems(mesh, kit.params.printer.envelope) == []
    assert mesh.is_watertight and mesh.volume > 0 and len(mesh.split(only_watertight=False)) == 1
    assert shell_count(mp) == 1
    # its face width and tip radius as designed, measured on the mesh
    lo, hi = np.asarray(mp.bounding_box()).reshape(2, 3)
    assert hi[2] - lo[2] == pytest.approx(spec.mate.face_width, abs=1e-4)
    v = np.asarray(mp.to_mesh().vert_properties)[:, :3]
    assert np.hypot(v[:, 0], v[:, 1]).max() == pytest.approx(spec.mate.tip_radius(spec.cross), abs=0.02)
    assert "cross_mate" in kit.poses()


def test_mate_mid_plane_is_the_generated_section(pair):
    """The mesh's section by its mid-plane is the 2-D generating cut (within the loft's sampling)."""
    spec, cs, mp, *_ = pair
    from partgen.geometry.measure import to_shapely

    sec = to_shapely(mp.slice(0.0))
    exact = shapely.difference(mate_section(spec.cross, spec.mate),
                               shapely.Point(0, 0).buffer(spec.mate.bore_diameter / 2, 64))
    assert shapely.symmetric_difference(sec, exact).area < 0.01 * exact.length  # < 10 µm on average along the outline


def test_pair_clear_over_the_workspace_and_a_wrong_mate_caught(pair):
    spec, cs, mp, *_ = pair
    c, m = spec.cross, spec.mate
    p = 2 * math.pi / m.teeth
    for psi in np.linspace(-p, p, 7):
        for tilt in (0.0, math.radians(-35)):
            assert intersection(cs, cross_pose(psi, c, m, tilt), mp, mate_pose(psi, c, m))[0] <= INTERFERENCE_MM3
    # half a pitch out of phase: the teeth sit on each other
    assert intersection(cs, cross_pose(0.0, c, m), mp, mate_pose(p / 2, c, m))[0] > 10.0
    # a mate cut with negative clearance overlaps the cross gear, and check says so
    tight, _ = mate_gear(c, replace(m, clearance=-0.1), slices=2, per_pitch=120)
    assert intersection(cs, cross_pose(0.0, c, m), tight, mate_pose(0.0, c, m))[0] > INTERFERENCE_MM3
    parts = tuple(replace(q, solid=tight) if q.name == "cross_mate" else q for q in pair[5].parts)
    res = Result()
    check_mate(replace(pair[5], parts=parts), res, psi_samples=3, backlash_poses=1)
    assert any(f.check == "interference" and f.severity == "fail" for f in res.findings)


def test_check_measures_the_backlash_of_the_clearance(pair):
    """The free turn of the mate equals the clearance on both flanks, c / cos α each, at the
    mid-plane (the faces add more: the rings falling away)."""
    spec, *_ , kit = pair
    res = Result()
    check_mate(kit, res, psi_samples=3, backlash_poses=1)
    assert res.ok
    f = res.figures["mate"]
    assert f["max_overlap_mm3"] <= INTERFERENCE_MM3
    flanks = 2 * spec.mate.clearance / math.cos(spec.cross.system.pressure_angle)
    assert f["backlash_min_mm"] == pytest.approx(flanks, rel=0.1)


def test_trace_ratio_and_transmission_error(pair):
    spec = pair[0]
    t = trace_mate(spec, pitches=1, per_pitch=6)["stats"]
    assert t["ratio"] == pytest.approx(spec.cross.teeth / spec.mate.teeth, abs=1e-6)
    assert t["te_pp_um"] < 10.0
    assert t["backlash_mid_mm"] == pytest.approx(2 * spec.mate.clearance / math.cos(spec.cross.system.pressure_angle),
                                                 rel=0.05)


@pytest.mark.parametrize("key,value,why", [("teeth", 30, "at most the cross gear's"),
                                           ("bore_diameter_mm", 40, "1.5 mm wall"),
                                           ("face_width_mm", 40, "pitch radius"),
                                           ("clearance_normal_mm", 1.0, "quarter")])
def test_bad_mate_is_a_config_error(tmp_path, capsys, key, value, why):
    from partgen.cli.main import main

    code = main(["build", "configs/wrist_sphere.yaml", "-o", str(tmp_path / "k"), "-q",
                 "--set", f"wrist.cross_gear.mate.{key}={value}"])
    err = capsys.readouterr().err
    assert code == 2 and f"wrist.cross_gear.mate.{key}" in err and why in err
    assert not (tmp_path / "k").exists()
