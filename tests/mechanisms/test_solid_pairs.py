"""The kinds whose two gears are solids checked and traced exactly in 3-D by the one kernel
(``mechanisms.solid_pair``): the shipped mitre pair (kind bevel) and crossed helical pair (kind
crossed_helical), each checked (0 mm³ at the designed backlash, the backlash the designed one to a
few µm, the frame's gaps), failing with the backlash made negative or gear 2 nudged, its contact
search finding the two flanks, traced (ratio within 1e-6), every STL one closed shell, and bad
input named by its key. The kind's own geometry (cones, helicoids, other shaft angles) is tested
in its folder's tests."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from pathlib import Path

import pytest
import trimesh
import yaml

from partgen.cli.main import main
from partgen.mechanisms import REGISTRY
from partgen.mechanisms.bevel import contact as bevel_contact
from partgen.mechanisms.bevel.kit import build_bevel
from partgen.mechanisms.crossed_helical import contact as crossed_contact
from partgen.mechanisms.crossed_helical.kit import build_crossed
from partgen.mechanisms.crossed_helical.resolve import gear_spec
from partgen.testing import mesh_problems

ROOT = Path(__file__).resolve().parents[2]


def _tight_bevel(spec):
    """The mitre pair with each tooth 0.1 mm thicker than backlash-free (backlash −0.1 mm per gear)."""
    pair = spec.pair
    return dataclasses.replace(spec, pair=dataclasses.replace(
        pair, gears=tuple(dataclasses.replace(g, backlash=-0.1) for g in pair.gears)))


def _tight_crossed(spec):
    return dataclasses.replace(spec, gear1=gear_spec(spec.pair, 0, -0.1, spec.tol),
                               gear2=gear_spec(spec.pair, 1, -0.1, spec.tol))


@dataclasses.dataclass(frozen=True)
class Case:
    kind: str
    contact: object  # the kind's contact module: mesh_overlaps, contact_angles
    tight: Callable  # spec -> the spec with the backlash made negative
    build: Callable  # spec -> kit
    check_samples: int
    backlash_over_mm: float  # the measured backlash's most above the designed (the facets' µm)
    nudge_phases: int
    flank_theta: float  # gear 1's turn where the contact search is tested (rad)
    trace_samples: int
    ratio: float
    te_max_mm: float
    instantaneous_max: float


CASES = {
    "bevel_mitre": Case("bevel", bevel_contact, _tight_bevel, build_bevel, 4, 0.005, 2, 0.05, 3, 1.0, 0.005, 0.01),
    "gear_train_crossed_helical": Case("crossed_helical", crossed_contact, _tight_crossed, build_crossed, 6, 0.006, 3,
                                       0.0, 4, 0.5, 0.02, 0.02),
}


@pytest.fixture(scope="module", params=list(CASES))
def shipped(request, kit_of):
    """(the case, the shipped kit built) for each kind."""
    return CASES[request.param], kit_of(request.param)


def test_shipped_pair_checks_exactly_in_3d(shipped):
    case, built = shipped
    spec, kit = built.loaded.spec, built.kit
    assert built.loaded.mechanism.kind == case.kind
    result = REGISTRY[case.kind].check(spec, kit, case.check_samples)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    f = result.figures
    assert f["max_overlap_mm3"] == 0.0 and f["samples"] == case.check_samples
    # the backlash along gear 2's (heel) pitch circle is the designed (0.1 + 0.1) mm, to the facets' few µm
    assert f["backlash_mm"]["designed"] == pytest.approx(0.2)
    assert 0.2 <= f["backlash_mm"]["min"] <= f["backlash_mm"]["max"] <= 0.2 + case.backlash_over_mm
    assert f["closest_mm"]["gear2-base"] >= spec.gap - 1e-3
    assert f["closest_mm"]["gear1-base"] == pytest.approx(spec.running / 2, abs=0.01)  # the bore round the post


def test_the_exact_check_fails_with_negative_backlash_or_nudged(shipped):
    case, built = shipped
    spec, kit = built.loaded.spec, built.kit
    overlaps = case.contact.mesh_overlaps
    assert overlaps(kit, case.nudge_phases, nudge=0.02).max() > 1.0  # gear 2 turned 0.02 rad (0.4 mm): teeth in teeth
    tight = case.tight(spec)
    tight_kit = case.build(tight)
    vols = overlaps(tight_kit, 3)
    assert (vols > 0.01).all(), vols
    assert not REGISTRY[case.kind].check(tight, tight_kit, 2).ok


def test_contact_angles_find_the_flanks(shipped):
    """Turning gear 2 ahead and back from nominal finds the two flanks: zero overlap between them,
    positive just beyond."""
    case, built = shipped
    kit, t = built.kit, case.flank_theta
    c = case.contact.contact_angles(kit, [t], 1e-6)
    ahead, behind = float(c["ahead"][0]), float(c["behind"][0])
    assert ahead > 0 > behind
    overlaps = case.contact.mesh_overlaps
    assert overlaps(kit, 1, nudge=ahead * 0.98, theta0=t)[0] == 0.0
    assert overlaps(kit, 1, nudge=ahead + 2e-4, theta0=t)[0] > 0.0
    assert overlaps(kit, 1, nudge=behind - 2e-4, theta0=t)[0] > 0.0


def test_trace_ratio_and_transmission_error(shipped):
    case, built = shipped
    stats = REGISTRY[case.kind].trace(built.loaded.spec, built.kit, case.trace_samples, None).stats
    assert stats["kind"] == case.kind and stats["samples"] == case.trace_samples + 1
    assert stats["ratio_design"] == case.ratio and stats["ratio_relative_error"] < 1e-6
    assert 0 < stats["transmission_error_mm"]["peak_to_peak"] < case.te_max_mm
    assert stats["instantaneous_ratio_deviation"] < case.instantaneous_max


def test_every_stl_is_one_closed_shell(shipped):
    _, built = shipped
    man = built.manifest
    assert {p["name"] for p in man["parts"]} == {"base", "gear1", "gear2", "pin2"}
    for p in man["parts"]:
        mesh = trimesh.load(built.dest / p["file"], file_type="stl")
        assert not mesh_problems(mesh, (250.0, 210.0, 220.0)), (p["name"], mesh_problems(mesh))
        assert len(mesh.split(only_watertight=False)) == 1, p["name"]


@pytest.mark.parametrize("config,change,key,fragment", [
    ("bevel_mitre", {"gears": {"face_width_mm": 12.0}}, "gears.face_width_mm", "third of the cone distance"),
    ("bevel_mitre", {"gears": {"teeth": [12, 40]}}, "gears.teeth[0]", "undercut"),  # 12.5 virtual teeth against 139
    ("bevel_mitre", {"shafts": {"diameter_mm": [8.0, 24.0]}}, "shafts.diameter_mm[1]", "wall"),
    ("bevel_mitre", {"shaft_angle_deg": 130.0, "gears": {"teeth": [15, 25]}}, "shaft_angle_deg",
     "below 126.87°"),  # δ_2 93.2°
    ("bevel_mitre", {"shaft_angle_deg": 160.0}, "shaft_angle_deg", "150"),
    ("bevel_mitre", {"shaft_angle_deg": 122.0, "gears": {"teeth": [15, 25], "face_width_mm": 7.0}}, "shaft_angle_deg",
     "at most 117.1°"),  # δ_2 85.3°: the toe at the apex
    ("gear_train_crossed_helical", {"gears": {"helix_angle_deg": [45.0, 40.0]}}, "gears.helix_angle_deg", "add up to"),
    ("gear_train_crossed_helical", {"gears": {"teeth": [30, 4]}}, "gears.teeth[1]", "undercut"),
    ("gear_train_crossed_helical", {"shafts": {"diameter_mm": [8.0, 40.0]}}, "shafts.diameter_mm[1]", "wall"),
])
def test_bad_input_names_the_key(tmp_path, capsys, config, change, key, fragment):
    d = yaml.safe_load((ROOT / "configs" / f"{config}.yaml").read_text())
    for k, v in change.items():
        d[k] = {**d[k], **v} if isinstance(v, dict) else v
    p = tmp_path / "bad.yaml"
    p.write_text(yaml.safe_dump(d, sort_keys=False))
    dest = tmp_path / "kit"
    assert main(["build", str(p), "-o", str(dest), "-q"]) == 2
    err = capsys.readouterr().err
    assert key in err and fragment in err and "Traceback" not in err, err
    assert not dest.exists()
