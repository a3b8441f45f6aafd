"""`partgen check`: the default design passes with no false positives; the paper's design fails
precisely; seeded faults each fail for their own reason; the checks can fail from both sides."""

import json
import math
from dataclasses import fields, replace
from pathlib import Path

import numpy as np
import pytest

from partgen import pipeline
from partgen.mechanisms.gear_chain.resolve import load as chain_load
from partgen.mechanisms.gear_chain.kit import Kit, build_kit
from partgen.checks.meshing import check_meshes
from partgen.checks.motion import prepare, sample_angles, sweep
from partgen.mechanisms.gear_chain.checks import check_kit
from partgen.cli.main import main

ROOT = Path(__file__).resolve().parents[3]
DESIGNS = Path(__file__).resolve().parents[2] / "designs"
SAMPLES = 72
FIT_SAMPLES = 24  # the seeded faults found at no crank angle (a fit's section, a part on the bed)


def fails(result, check=None):
    return [f for f in result.findings if f.severity == "fail" and (check is None or f.check == check)]


@pytest.fixture(scope="module")
def default_kit(kit_of):
    """The default design's kit as `partgen build` made it this session (the same build_kit call)."""
    return kit_of("butterfly").kit


def test_default_design_passes_with_no_false_positives(default_kit):
    result = check_kit(default_kit, SAMPLES)
    assert result.ok, [f.message for f in fails(result)]
    assert not [f for f in result.findings if f.severity in ("fail", "warn")]
    figs = result.figures
    assert figs["motion"]["closest_approach"]["mm"] >= default_kit.params.checks.min_clearance
    assert min(r["contact_ratio"] for r in figs["meshes"]) >= 1.2
    # every mesh runs with the designed backlash: measured on the outlines vs the formula
    for r in figs["meshes"]:
        assert r["measured_backlash_mm"] == pytest.approx(r["backlash_mm"], abs=0.005)
        assert r["centre_distance_mm"] == pytest.approx(r["design_centre_distance_mm"], abs=1e-9)
    # every fit measures its design clearance in the section through its middle: never tighter,
    # looser by at most one chord sagitta of the round features (shafts inside, holes outside)
    for r in figs["fits"]["rows"]:
        if "radial_gap_mm" in r:
            assert r["design_radial_gap_mm"] - 1e-6 <= r["radial_gap_mm"] <= r["design_radial_gap_mm"] + 0.0101, r


def test_paper_design_fails_exactly_on_link_10(kit_of, prime_kit_cache):
    """Table 3's D10/G11 = 21/15 at m = 1.5 on a 30 mm link: tip circles touch (Eq 12). The check
    reports that and the near-contact it causes over the motion, and nothing else. (check's kit is
    the session's build of the design.)"""
    prime_kit_cache(kit_of("butterfly_liu2017"))
    _, kit, result, _ = pipeline.check(ROOT / "configs" / "butterfly_liu2017.yaml", SAMPLES, write_plates=False)
    bad = fails(result)
    assert {f.check for f in bad} == {"design", "clearance"}
    assert any("Eq 12" in f.message and "teeth[9]" in f.message for f in fails(result, "design"))
    (clear,) = fails(result, "clearance")
    assert set(clear.parts) == {"D10", "G11"}
    assert clear.value < 0.05 and clear.theta is not None and clear.location is not None


def test_idler_moved_into_a_gear_fails_its_mesh():
    _, _, result, _ = pipeline.check(DESIGNS / "idler_into_gear.yaml", SAMPLES, write_plates=False)
    mesh = fails(result, "mesh")
    overlap = [f for f in mesh if "overlap" in f.message]
    assert overlap and set(overlap[0].parts) == {"D3", "M3"} and overlap[0].value > 0.1
    assert {p for f in mesh for p in f.parts} <= {"D3", "M3", "G4"}
    assert not fails(result, "interference") and not fails(result, "fit")


def test_negative_joint_clearance_jams_every_running_fit(default_kit):
    """(At FIT_SAMPLES crank angles: a fit is measured in its section, at no angle; the same fits jam
    at 72.)"""
    _, kit, result, _ = pipeline.check(DESIGNS / "negative_clearance.yaml", FIT_SAMPLES, write_plates=False)
    running = {frozenset((c.a, c.b)) for c in kit.contacts if c.kind == "running"}
    jammed = {frozenset(f.parts) for f in fails(result, "fit")}
    assert jammed == running
    assert not fails(result, "interference") and not fails(result, "mesh")


@pytest.fixture(scope="module")
def oversize():
    """pipeline.check of tests/designs/oversize.yaml (its kit is built once: the CLI test reuses it), at
    FIT_SAMPLES crank angles: a part's fit on the bed does not depend on the angle."""
    return pipeline.check(DESIGNS / "oversize.yaml", FIT_SAMPLES, write_plates=False)


def test_part_larger_than_the_printer_fails_printability(oversize):
    """B1 (230 mm long) on a 150 mm bed: it fits in no turn about z, not even on the diagonal."""
    _, _, result, _ = oversize
    bad = fails(result)
    assert {f.check for f in bad} == {"printability"}
    plates = [f for f in bad if "build plates" in f.message]
    assert [f.parts for f in plates] == [("B1",)] and "in any turn about z" in plates[0].message


def faulted(kit: Kit, **changes) -> Kit:
    return replace(kit, **changes)


def test_gear_clocked_half_a_tooth_off_fails_its_mesh(default_kit):
    """A manufacturing fault: G5 pressed onto plate 5 half a tooth off its clocking."""
    z = default_kit.part("G5").gear.teeth
    L = chain_load(ROOT / "configs" / "butterfly.yaml")
    kit = build_kit(L.mechanism, L.params, clock_error={"G5": math.pi / z})
    assert kit.clock["G5"] == pytest.approx(default_kit.clock["G5"] + math.pi / z)
    result = check_kit(kit, SAMPLES)
    mesh = fails(result, "mesh")
    assert mesh and all(set(f.parts) == {"M4", "G5"} for f in mesh)
    assert mesh[0].value > 1.0  # mm³ of tooth overlap
    assert not fails(result, "interference") and not fails(result, "fit")


class OneLayer(Kit):
    """An assembly fault: plate B5 put on plate B3's level (with nothing else moved)."""

    def poses_over(self, ts):
        p = super().poses_over(ts)
        p["B5"] = p["B5"].copy()
        p["B5"][:, 2, 3] = p["B3"][:, 2, 3]
        return p


def test_two_plates_on_one_layer_collide_only_at_some_angles(default_kit):
    kit = OneLayer(**{f.name: getattr(default_kit, f.name) for f in fields(default_kit) if f.init})
    findings, _ = sweep(kit, prepare(kit), sample_angles(SAMPLES))
    plates = [f for f in findings if f.check == "interference" and set(f.parts) == {"B3", "B5"}]
    assert plates, [f.message for f in findings]
    f = plates[0]
    k = int(f.message.split("overlapping at ")[1].split(" of")[0])
    assert 0 < k < SAMPLES  # only at some crank angles
    assert f.value > default_kit.params.checks.interference_tolerance
    # the count is the angles at which the two plates really overlap (exact, every angle)
    from partgen.geometry.measure import intersection
    a, b = kit.part("B3").solid, kit.part("B5").solid
    exact = sum(intersection(a, kit.poses(t)["B3"], b, kit.poses(t)["B5"])[0] > 0.001 for t in sample_angles(SAMPLES))
    assert k == exact


def test_meshing_pair_overlaps_zero_and_nudged_it_overlaps(default_kit):
    """Both sides: a correctly phased mesh overlaps 0; turn one gear 0.02 rad and it overlaps."""
    thetas = sample_angles(8)
    _, rows = check_meshes(default_kit, thetas)
    assert max(r["worst_overlap_mm3"] for r in rows) == 0.0
    for name in ("M2", "G7"):
        clock = dict(default_kit.clock)
        clock[name] += 0.02
        _, rows = check_meshes(faulted(default_kit, clock=clock), thetas)
        hit = [r for r in rows if name in r["pair"]]
        assert hit and max(r["worst_overlap_mm3"] for r in hit) > 0.001


def test_check_cli_json_and_exit_codes(tmp_path, capsys, kit_of, prime_kit_cache, oversize):
    prime_kit_cache(kit_of("butterfly"))  # check's kit is the session's build (make_kit shares one per process)
    code = main(["check", str(ROOT / "configs" / "butterfly.yaml"), "--samples", "24", "--json", "--plates",
                 str(tmp_path / "plates")])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["ok"] is True and [f for f in out["findings"] if f["severity"] != "info"] == []
    # the facts: the parts that need supports, the bores open where their pins enter
    assert {f["parts"][0] for f in out["findings"] if f.get("rule") == "needs-supports"} == {"drive_axle", "pen_holder"}
    kit = kit_of("butterfly").kit
    n = sum(len(p.bores) for p in {(id(p.solid), p.print_flip): p for p in kit.parts if p.printed}.values())
    assert n >= 43 and any(f.get("rule") == "bore-open" and f["message"].startswith(f"{n} of {n} bores")
                           for f in out["findings"])
    assert out["figures"]["plates"] >= 1
    assert sorted(p.name for p in (tmp_path / "plates").iterdir())[-1] == "plates.png"
    prime_kit_cache(oversize.kit, DESIGNS / "oversize.yaml")  # the kit pipeline.check built of the same file
    code = main(["check", str(DESIGNS / "oversize.yaml"), "--samples", "8", "--json", "--no-plates"])
    out = json.loads(capsys.readouterr().out)
    assert code == 1 and out["ok"] is False
    assert main(["check", str(tmp_path / "missing.yaml")]) == 2
    assert main(["check", str(ROOT / "configs" / "butterfly.yaml"), "--samples", "2"]) == 2


def test_sweep_samples_the_whole_cycle():
    t = sample_angles(360)
    assert t[0] == 0 and t[-1] == pytest.approx(2 * np.pi * 359 / 360) and len(np.unique(t)) == 360


def test_poses_over_is_poses_at_each_angle(default_kit):
    """The chain computes every pose at N angles at once (``poses_over``, what the sweep, the mesh
    check and the GLB read): the same poses as ``poses`` at each angle, bit for bit."""
    ts = sample_angles(48)
    many = default_kit.poses_over(ts)
    for i in (0, 7, 31, 47):
        one = default_kit.poses(float(ts[i]))
        assert set(one) == set(many)
        for name, T in one.items():
            assert np.array_equal(T, many[name][i]), name
