"""The throated worm wheel (``gears.throated: true``): the shipped worm's wheel cut by the worm's
envelope instead of a plain helical wheel (here at a 0.03 mm chord tolerance: one build and check of ~5 s,
shared by the module; at 0.02 mm it took half again as long and the figures tested hold at both:
the backlash ~0.09 mm at 0.03 against ~0.095 mm at 0.02, over its 0.08 mm floor). Its STL is one closed shell, its root is the torus the cutter's tip
sweeps (measured on sections of the mesh), the exact check passes (no overlap, backlash both ways)
and its contact runs across the whole face where the plain wheel's covers under half; bad input."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml

from partgen import pipeline
from partgen.cli.main import main
from partgen.geometry.solid import mesh_arrays
from partgen.mechanisms.crossed_helical.kit import cutter_spec
from partgen.testing import mesh_problems, section_outline

ROOT = Path(__file__).resolve().parents[3]
WORM = ROOT / "configs" / "gear_train_worm.yaml"
PHASES = 4


def _design(tmp: Path, name: str, **gears) -> Path:
    d = yaml.safe_load(WORM.read_text())
    d["name"] = name
    d["gears"].update(gears)
    p = tmp / f"{name}.yaml"
    p.write_text(yaml.safe_dump(d, sort_keys=False))
    return p


@pytest.fixture(scope="module")
def throated(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("throated")
    built = pipeline.build(_design(tmp, "worm_throated", throated=True, chord_tolerance_mm=0.03), tmp / "kit")
    return built, built.loaded.mechanism.check(built.loaded.spec, built.kit, PHASES)


def test_the_throated_wheel_is_one_closed_shell(throated):
    built, _ = throated
    assert built.manifest["design"]["throated_wheel"] is True
    for p in built.manifest["parts"]:
        mesh = trimesh.load(built.dest / p["file"], file_type="stl")
        assert not mesh_problems(mesh, (250.0, 210.0, 220.0)), (p["name"], mesh_problems(mesh))
        assert len(mesh.split(only_watertight=False)) == 1, p["name"]


def test_its_root_is_the_torus_the_cutters_tip_sweeps(throated):
    """Sections of the wheel's mesh square to its axis: the smallest radius (the roots) is
    a − √(r_c² − z²) (r_c the cutter's tip: the worm's pitch radius plus the wheel's dedendum), 0.02 mm
    higher where the hub's top shows (the spaces' middles): deepest at the mid-plane, 0.8 mm shallower
    at the face's ends — where a plain wheel's root is one cylinder."""
    built, _ = throated
    spec = built.loaded.spec
    v, f = mesh_arrays(built.kit.part("gear2").solid)
    mesh = trimesh.Trimesh(v, f, process=False)
    a, rc = spec.centre_distance, cutter_spec(spec).tip_radius
    roots = {}
    for z in (-4.5, -2.0, 0.0, 2.5, 4.5):
        out = section_outline(mesh, z)
        ring = np.asarray(out.geoms[0].exterior.coords if hasattr(out, "geoms") else out.exterior.coords)
        roots[z] = float(np.hypot(ring[:, 0], ring[:, 1]).min())
        assert roots[z] == pytest.approx(a - math.sqrt(rc * rc - z * z), abs=0.03), (z, roots[z])
    assert roots[4.5] - roots[0.0] > 0.7


def test_the_throated_wheel_checks_and_bears_across_its_face(throated, kit_of):
    """Exact 3-D at the phases: no overlap, backlash both ways near the designed 0.109 mm (the cutter's
    chords sag inside its thread, leaving the wheel's teeth a little thicker at this tolerance), and the
    flanks within 0.02 mm across the whole face at every phase — line contact — where the plain wheel's
    pattern is under half of it (measured, not assumed)."""
    built, result = throated
    assert result.ok, [x.message for x in result.findings if x.severity == "fail"]
    f = result.figures
    assert f["max_overlap_mm3"] == 0.0
    assert 0.08 <= f["backlash_mm"]["min"] <= f["backlash_mm"]["max"] <= f["backlash_mm"]["designed"] + 0.005
    wheel = f["contact_along_face"]["gear2"]
    assert wheel["fraction"] >= 0.95 and wheel["instantaneous"]["min"] >= 0.9 and wheel["sits"] == "centred", wheel
    assert [x.severity for x in result.findings if x.check == "contact"] == ["info"]
    plain = kit_of("gear_train_worm")
    p = plain.loaded.mechanism.check(plain.loaded.spec, plain.kit, 2).figures["contact_along_face"]["gear2"]
    assert p["fraction"] < 0.5 and wheel["fraction"] > p["fraction"] + 0.5


@pytest.mark.parametrize("cfg,change,fragment", [
    ("gear_train_crossed_helical", {}, "only a worm's wheel"),
    ("gear_train_worm", {"shaft_angle_deg": 80.0, "helix_angle_deg": [75.0, 5.0]}, "90°"),
])
def test_a_throated_wheel_needs_a_worm_at_90_degrees(tmp_path, capsys, cfg, change, fragment):
    d = yaml.safe_load((ROOT / "configs" / f"{cfg}.yaml").read_text())
    d["gears"]["throated"] = True
    if "shaft_angle_deg" in change:
        d["shaft_angle_deg"] = change["shaft_angle_deg"]
        d["gears"]["helix_angle_deg"] = change["helix_angle_deg"]
    p = tmp_path / "bad.yaml"
    p.write_text(yaml.safe_dump(d, sort_keys=False))
    dest = tmp_path / "kit"
    assert main(["build", str(p), "-o", str(dest), "-q"]) == 2
    err = capsys.readouterr().err
    assert "gears.throated" in err and fragment in err and "Traceback" not in err, err
    assert not dest.exists()
