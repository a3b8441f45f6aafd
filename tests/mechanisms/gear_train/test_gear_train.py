"""kind: gear_train, spur: the shipped reducer from its overall ratio. The shafts' holes in the printed
top plate stand at the involute centre distances; check passes (Fortus and a desktop printer) and
measures at the output the backlash the stages' thinning gives; a shaft moved in fails; the trace
measures the design ratio; bad tables are exit 2 naming the key."""

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
from helpers import modified
from shapely.geometry import Polygon

from partgen import pipeline
from partgen.cli.main import main
from partgen.design import involute
from partgen.mechanisms.gear_train.stages.kit import build_train
from partgen.mechanisms.gear_train.mechanism import MECHANISM

ROOT = Path(__file__).resolve().parents[3]
CFG = ROOT / "configs" / "gear_train_reducer.yaml"


@pytest.fixture(scope="module")
def reducer(kit_of):
    return kit_of("gear_train_reducer")


def test_shaft_holes_stand_at_the_involute_centre_distances(reducer):
    d = reducer.manifest["design"]
    assert d["ratio"] == "10/1" and len(d["stages"]) == 2
    top = trimesh.load(reducer.dest / "frame_top.stl")
    sec = top.section(plane_origin=[0, 0, top.bounds[1][2] / 2], plane_normal=[0, 0, 1])
    holes = [Polygon(loop[:, :2]) for loop in sec.discrete]
    shaft_holes = sorted((h for h in holes if 9 < 2 * math.sqrt(h.area / math.pi) < 11), key=lambda h: h.centroid.x)
    assert len(shaft_holes) == 3
    c = [np.array(h.centroid.coords[0]) for h in shaft_holes]
    for st, (i, j) in zip(d["stages"], ((0, 1), (1, 2))):
        a = involute.centre_distance(*st["teeth"], 2.0, math.radians(20), *st["profile_shift"])
        assert np.linalg.norm(c[j] - c[i]) == pytest.approx(a, abs=2e-3)
    # the second stage turned 60° from the first
    v1, v2 = c[1] - c[0], c[2] - c[1]
    assert math.degrees(math.atan2(v2[1], v2[0]) - math.atan2(v1[1], v1[0])) == pytest.approx(60, abs=0.01)


def _output_backlash_arcmin(spec):
    """Σ over stages of the circumferential backlash on the driven gear's pitch circle, carried to the output."""
    total = 0.0
    for m in spec.meshes:
        gd, gn = spec.gear(m.driver), spec.gear(m.driven)
        s = spec.system
        j = involute.circumferential_backlash(gd.spec.teeth, gn.spec.teeth, s.module, s.pressure_angle,
                                              gd.spec.profile_shift, gn.spec.profile_shift, s.backlash_per_gear,
                                              s.backlash_per_gear, m.centre_distance)
        r_w = m.centre_distance * gn.spec.teeth / (gd.spec.teeth + gn.spec.teeth)
        total += j / r_w * abs(float(spec.shafts[-1].speed / spec.shafts[gn.shaft].speed))
    return math.degrees(total) * 60


def test_check_passes_and_measures_the_output_backlash(reducer):
    loaded, kit = reducer.loaded, reducer.kit
    result = MECHANISM.check(loaded.spec, kit, 24)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    f = result.figures
    assert f["input_turns"] == pytest.approx(10.0)
    b = f["output_backlash_arcmin"]
    want = _output_backlash_arcmin(loaded.spec)
    assert 17 < want < 20
    assert want * 0.98 < b["min"] <= b["max"] < want * 1.06
    for row in f["meshes"]:
        assert row["worst_overlap_mm3"] == 0 and row["contact_ratio"] > 1.4


def test_a_shaft_moved_in_fails(reducer):
    spec = reducer.loaded.spec
    sh = spec.shafts[2]
    d = np.array(sh.centre) - np.array(spec.shafts[1].centre)
    moved = dataclasses.replace(sh, centre=tuple(np.array(sh.centre) - 0.4 * d / np.linalg.norm(d)))
    bad = dataclasses.replace(spec, shafts=(*spec.shafts[:2], moved))
    result = MECHANISM.check(bad, build_train(bad), 8)
    fails = {f.check for f in result.findings if f.severity == "fail"}
    assert not result.ok and "mesh" in fails


def test_trace_measures_the_ratio(reducer, prime_kit_cache, capsys):
    """(the session's kit; every command on a gear train's design and kit folder: tests/cli/test_contract.py)"""
    prime_kit_cache(reducer)
    assert main(["trace", str(CFG), "--samples", "24", "--no-plots", "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["kind"] == "gear_train" and s["ratio_measured"] == pytest.approx(10.0, rel=2e-4)
    assert 0 < s["transmission_error_arcmin"]["peak_to_peak"] < 2.0


def test_check_on_a_desktop_printer():
    loaded = pipeline.load(CFG, over=pipeline.overrides(printer="prusa_mk4"))
    kit = MECHANISM.build(loaded.spec)
    result = MECHANISM.check(loaded.spec, kit, 8)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    assert loaded.spec.running == 0.3  # the printer's measured fit


@pytest.mark.parametrize("change,key", [
    ({"train": {"ratio": 10.0, "ratio_exact": True, "stages": [{"ratio": 3.14159, "exact": True}, {}]}},
     "train.stages[0].ratio"),
    ({"train": {"stages": [{"ratio": 9.0}]}}, "train.stages[0].ratio"),
    ({"train": {"stages": [{"teeth": [16, 50], "centre_distance_mm": 90.0}]}}, "train.stages[0].centre_distance_mm"),
    ({"train": {"stages": [{"teeth": [16, 50], "ratio": 3.0}]}}, "train.stages[0].ratio"),
    ({"train": {"ratio": 10.0, "stages": [{}, {"angel_deg": 60}]}}, "train.stages[1].angel_deg"),
    ({"shafts": {"bores": ["round", "round"]}}, "shafts.bores"),
])
def test_bad_tables_are_exit_2_naming_the_key(tmp_path, capsys, change, key):
    cfg = modified(CFG, tmp_path, change, name="bad.yaml")  # whole sections replaced
    assert main(["build", str(cfg), "-o", str(tmp_path / "out"), "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["key"] == key, err
    assert not (tmp_path / "out").exists()


def test_every_shaft_runs_through_open_bores_and_a_plugged_one_fails(reducer):
    """Each shaft's way through its gear part and both frame plates is open where it enters (a
    rod of the shaft's size pushed in as the part prints); a gear part with its bore plugged fails."""
    import manifold3d as m3d

    from partgen.checks.bores import bore_findings
    kit = reducer.kit
    found, table = bore_findings(kit.parts)
    assert not [f for f in found if f.severity == "fail"]
    shafts = [p for p in kit.parts if p.name.startswith("shaft")]
    assert sum(len(t) for t in table.values()) == 3 * len(shafts)  # the gear part and two plates per shaft
    g = next(p for p in kit.parts if p.name == "gears1")
    b = g.bores[0]
    plug = m3d.Manifold.cylinder(1.0, b.diameter_mm).translate((0.0, 0.0, b.point[2] + b.depth_mm / 2))
    found, _ = bore_findings([dataclasses.replace(g, solid=g.solid + plug)])
    assert [f.rule for f in found if f.severity == "fail"] == ["bore-open"]
