"""Straight bevel pairs (kind bevel): the cone geometry and the rolling kinematics at any shaft
angle, the shipped mitre pair built, checked exactly in 3-D (0 mm³ at the designed backlash,
overlapping with the backlash made negative), its flanks measured on the float32 mesh against the
analytic conical Tredgold tooth (µm), traced (ratio within 1e-6), every STL one closed shell; a 75°
pair; bad input."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml

from partgen.cli.main import main
from partgen.design.bevel import bevel_pair
from partgen.geometry.solid import mesh_arrays
from partgen.mechanisms.bevel.kit import build_bevel
from partgen.mechanisms.bevel.mechanism import MECHANISM, contact_angles, mesh_overlaps
from partgen.testing import mesh_problems, section_outline

ROOT = Path(__file__).resolve().parents[1]
CFG = ROOT / "configs" / "bevel_mitre.yaml"


@pytest.mark.parametrize("z1,z2,sigma", [(20, 20, 90.0), (15, 25, 75.0), (18, 30, 50.0)])
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


def test_shipped_pair_checks_exactly_in_3d(shipped):
    spec, kit = shipped.loaded.spec, shipped.kit
    result = MECHANISM.check(spec, kit, 4)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    f = result.figures
    assert f["max_overlap_mm3"] == 0.0
    # the backlash along gear 2's heel pitch circle is the designed (0.1 + 0.1) mm to a few µm
    assert f["backlash_mm"]["designed"] == pytest.approx(0.2)
    assert 0.2 <= f["backlash_mm"]["min"] <= f["backlash_mm"]["max"] <= 0.2 + 0.005
    assert f["closest_mm"]["gear2-base"] >= spec.gap - 1e-3
    assert f["closest_mm"]["gear1-base"] == pytest.approx(spec.running / 2, abs=0.01)  # the bore round the post


def test_the_exact_check_fails_with_negative_backlash_or_nudged(shipped):
    spec, kit = shipped.loaded.spec, shipped.kit
    assert mesh_overlaps(kit, 2, nudge=0.02).max() > 1.0  # gear 2 turned 0.02 rad (0.4 mm): teeth in teeth
    pair = spec.pair
    tight_pair = dataclasses.replace(pair, gears=tuple(dataclasses.replace(g, backlash=-0.1) for g in pair.gears))
    tight = dataclasses.replace(spec, pair=tight_pair)
    tight_kit = build_bevel(tight)
    vols = mesh_overlaps(tight_kit, 3)
    assert (vols > 0.01).all(), vols
    assert not MECHANISM.check(tight, tight_kit, 2).ok


def test_contact_angles_find_the_flanks(shipped):
    """Turning gear 2 ahead and back from nominal finds the two flanks: zero overlap between them,
    positive just beyond."""
    kit = shipped.kit
    c = contact_angles(kit, [0.05], 1e-6)
    ahead, behind = float(c["ahead"][0]), float(c["behind"][0])
    assert ahead > 0 > behind
    assert mesh_overlaps(kit, 1, nudge=ahead * 0.98, theta0=0.05)[0] == 0.0
    assert mesh_overlaps(kit, 1, nudge=ahead + 2e-4, theta0=0.05)[0] > 0.0
    assert mesh_overlaps(kit, 1, nudge=behind - 2e-4, theta0=0.05)[0] > 0.0


def _tredgold_flank(z, m, alpha, delta, thinning, h, rad):
    """The analytic flank in the plane ``h`` from the apex, written out here from the tooth form's
    definition (not the code under test): the point at radius ``rad`` there lies on the ray from the
    apex through the back-cone point u = H (q − r) / (H cos δ + q sin δ), q = rad H / h, of virtual
    radius ρ = r/cos δ + u; the involute of the virtual base circle puts the flank at developed
    half-angle ψ = s / (2 r_v) + inv α − inv α_ρ, azimuth ψ / cos δ."""
    r = m * z / 2
    H = r / math.tan(delta)  # R cos δ
    q = rad * H / h
    u = H * (q - r) / (H * math.cos(delta) + q * math.sin(delta))
    rv = r / math.cos(delta)
    rho = rv + u
    a_rho = np.arccos(np.minimum(rv * math.cos(alpha) / rho, 1.0))  # below the base circle: masked out
    s = math.pi * m / 2 - thinning
    psi = s / (2 * rv) + (math.tan(alpha) - alpha) - (np.tan(a_rho) - a_rho)
    return psi / math.cos(delta), rho - rv


def test_flanks_are_the_conical_tredgold_tooth(shipped):
    """Each gear's mesh (float32, as the STL stores it) cut by planes square to its axis at three
    distances from the apex where whole teeth are (between the back cones, tip to root): every
    vertex and edge midpoint of the section on the involute part of a flank lies within a µm or so
    (circumferentially) of the analytic flank (1.2 µm; 0.7 measured), the same scaled outline at each distance."""
    spec, kit = shipped.loaded.spec, shipped.kit
    worst = 0.0
    for name, tooth in (("gear1", spec.gear1), ("gear2", spec.gear2)):
        z, m, a, d = tooth.teeth, tooth.module, tooth.pressure_angle, tooth.pitch_angle
        R, b = m * z / (2 * math.sin(d)), tooth.face_width
        ta, tf = math.atan(tooth.addendum / R), math.atan(tooth.dedendum / R)
        lo = max((R - b) / math.cos(ta) * math.cos(d + ta), (R - b) / math.cos(tf) * math.cos(d - tf))
        hi = min(R / math.cos(ta) * math.cos(d + ta), R / math.cos(tf) * math.cos(d - tf))
        assert hi - lo > 2.0
        v, f = mesh_arrays(kit.part(name).solid)
        mesh = trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)
        rv, rb = m * z / (2 * math.cos(d)), m * z / (2 * math.cos(d)) * math.cos(a)
        for h in np.linspace(lo + 0.3, hi - 0.3, 3):
            ring = np.asarray(section_outline(mesh, -h).exterior.coords)
            pts = np.vstack([ring, (ring[1:] + ring[:-1]) / 2])
            rad = np.hypot(pts[:, 0], pts[:, 1])
            ang = np.arctan2(pts[:, 1], pts[:, 0])
            flank, u = _tredgold_flank(z, m, a, d, tooth.backlash, h, rad)
            # the involute part: above the virtual base circle and 0.15 mm (virtual) inside the tip
            on = (u + rv > rb + 0.05) & (u < tooth.addendum - 0.15)
            pitch = 2 * math.pi / z
            folded = np.abs((ang + pitch / 2) % pitch - pitch / 2)  # angle from the nearest tooth's centre
            teeth_seen = len(np.unique(np.round((ang[on] / pitch)).astype(int) % z))
            assert teeth_seen == z, (name, h, teeth_seen)
            dev = rad[on] * (folded[on] - flank[on])  # mm along the circle: + outside the analytic flank
            worst = max(worst, float(np.abs(dev).max()))
    assert worst < 1.2e-3, worst  # µm: the shipped mitre pair measures 0.7


def test_trace_ratio_and_transmission_error(shipped):
    stats = MECHANISM.trace(shipped.loaded.spec, shipped.kit, 3, None).stats
    assert stats["ratio_design"] == 1.0 and stats["ratio_relative_error"] < 1e-6
    assert 0 < stats["transmission_error_mm"]["peak_to_peak"] < 0.005
    assert stats["instantaneous_ratio_deviation"] < 0.01


def test_every_stl_is_one_closed_shell(shipped):
    man = shipped.manifest
    assert {p["name"] for p in man["parts"]} == {"base", "gear1", "gear2", "pin2"}
    for p in man["parts"]:
        mesh = trimesh.load(shipped.dest / p["file"], file_type="stl")
        assert not mesh_problems(mesh, (250.0, 210.0, 220.0)), (p["name"], mesh_problems(mesh))
        assert len(mesh.split(only_watertight=False)) == 1, p["name"]


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


@pytest.mark.parametrize("change,key,fragment", [
    ({"gears": {"face_width_mm": 12.0}}, "gears.face_width_mm", "third of the cone distance"),
    ({"gears": {"teeth": [12, 40]}}, "gears.teeth[0]", "undercut"),  # 12.5 virtual teeth against 139
    ({"shafts": {"diameter_mm": [8.0, 24.0]}}, "shafts.diameter_mm[1]", "wall"),
    ({"shaft_angle_deg": 100.0}, "shaft_angle_deg", "90"),
])
def test_bad_input_names_the_key(tmp_path, capsys, change, key, fragment):
    d = yaml.safe_load(CFG.read_text())
    for k, v in change.items():
        d[k] = {**d[k], **v} if isinstance(v, dict) else v
    p = tmp_path / "bad.yaml"
    p.write_text(yaml.safe_dump(d, sort_keys=False))
    dest = tmp_path / "kit"
    assert main(["build", str(p), "-o", str(dest), "-q"]) == 2
    err = capsys.readouterr().err
    assert key in err and fragment in err and "Traceback" not in err, err
    assert not dest.exists()
