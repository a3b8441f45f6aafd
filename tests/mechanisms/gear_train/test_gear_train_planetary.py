"""Planetary sets of kind gear_train: teeth from a ratio under the coaxial and assembly conditions,
the ring's tooth spaces as involutes (measured on its printed section), planets phased so every one
meshes sun and ring (a planet half a pitch off overlaps), the carrier's ratio and backlash measured on
the printed outlines against the formula, and the assembly condition refused with what would work."""

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest
from helpers import modified

from partgen.cli.main import main
from partgen.design.planetary import assembly_whole, planet_angles, planetary_teeth
from partgen.geometry.measure import section
from partgen.mechanisms.gear_train.mechanism import MECHANISM
from partgen.mechanisms.gear_train.planetary.kit import build_planetary
from partgen.mechanisms.gear_train.planetary.motion import turn_planetary
from partgen.testing import measure_spur_gear

ROOT = Path(__file__).resolve().parents[3]
CFG = ROOT / "configs" / "gear_train_planetary.yaml"


def test_teeth_from_a_ratio_meet_coaxial_and_assembly_conditions():
    for ratio, n in ((5.0, 3), (4.2, 4), (7.0, 3)):
        t = planetary_teeth(ratio, n, 15, 60, 1.5, 1.3)
        assert t.ring == t.sun + 2 * t.planet and assembly_whole(t.sun, t.ring, n)
        best = min(abs(1 + (s + 2 * p) / s - ratio) for s in range(15, 61) for p in range(15, 61)
                   if (2 * s + 2 * p) % n == 0 and 2 * 0.75 * (s + p) * math.sin(math.pi / n) - 1.5 * (p + 2) >= 1.3)
        assert abs(t.ratio - ratio) == pytest.approx(best, abs=1e-12)
    # unequal spacing: planets where (z_s + z_r) γ / 2π is whole
    ang = planet_angles(18, 71, 3, equal=False)
    assert all(abs(a * 89 / (2 * math.pi) - round(a * 89 / (2 * math.pi))) < 1e-9 for a in ang)


@pytest.fixture(scope="module")
def planetary(kit_of):
    return kit_of("gear_train_planetary")


def test_ring_spaces_are_involutes_on_the_printed_section(planetary):
    s = planetary.loaded.spec
    assert (s.teeth.sun, s.teeth.planet, s.teeth.ring) == (18, 27, 72)
    sec = section(planetary.kit.part("frame_bottom").solid, s.gap + s.face_width / 2)
    ring = max(sec.geoms, key=lambda p: p.area)
    from shapely.geometry import Polygon
    space = Polygon(max(ring.interiors, key=lambda r: Polygon(r).area))  # the ring's inside: its space gear
    meas = measure_spur_gear(space, 72, 1.5, math.radians(20), centre=(0.0, 0.0))
    assert meas.teeth_found == 72
    assert meas.flank_deviation < 0.01  # the config's chord tolerance
    # a space is a pitch less the ring's tooth: π m / 2 widened by the ring's thinning (the config's backlash)
    assert meas.tooth_thickness == pytest.approx(math.pi * 1.5 / 2 + s.system.backlash_per_gear, abs=0.01)


def test_check_passes_and_the_carrier_turns_at_the_ratio(planetary):
    spec, kit = planetary.loaded.spec, planetary.kit
    result = MECHANISM.check(spec, kit, 8)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    assert result.figures["max_printed_overlap_mm2"] == 0.0
    tr = MECHANISM.trace(spec, kit, 12, None)
    assert tr.stats["ratio_measured"] == pytest.approx(5.0, rel=2e-4)
    # the sun held, the ring fixed: the carrier turns freely through both meshes' backlash (2 × the config's per gear
    # each) over r_sun + r_ring = 2a (the planet rolls on the sun: its ring side moves twice its centre). Not over
    # r_ring alone: that is the sun held still in the carrier's frame, 1 + z_s/z_r = 1.25 times as much
    j = 2 * spec.system.backlash_per_gear
    want = math.degrees((j + j) / (1.5 * (18 + 72) / 2)) * 60
    assert want * 0.98 < tr.stats["backlash_arcmin"]["min"] <= tr.stats["backlash_arcmin"]["max"] < want * 1.05


def test_a_planet_off_its_phase_overlaps(planetary):
    spec = planetary.loaded.spec
    off = list(spec.planet_phases)
    off[1] += math.pi / spec.teeth.planet  # half a pitch
    bad = dataclasses.replace(spec, planet_phases=tuple(off))
    turned = turn_planetary(build_planetary(bad), np.array([0.0, 0.3]), tol=1e-4)
    assert turned["overlap_mm2"][:, [1, 4]].min() > 0.5  # planet 1 against sun and ring
    assert turned["overlap_mm2"][:, [0, 2, 3, 5]].max() == 0.0


@pytest.mark.parametrize("change,key,words", [
    ({"teeth": [18, 27, 72], "planets": 4}, "planetary.planets", "unequal"),
    ({"teeth": [18, 27, 70]}, "planetary.teeth[2]", "72"),
    ({"teeth": [4, 5, 14]}, "planetary.teeth[1]", "interference"),
    ({"ratio": 1.2}, "planetary.ratio", "no sun"),
])
def test_bad_sets_are_exit_2(tmp_path, capsys, change, key, words):
    cfg = modified(CFG, tmp_path, {f"planetary.{k}": v for k, v in change.items()}, drop=["planetary.ratio"],
                   name="bad.yaml")
    assert main(["build", str(cfg), "-o", str(tmp_path / "out"), "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["key"] == key and words in err["message"], err


def test_unequal_spacing_builds_and_meshes(tmp_path):
    from partgen import pipeline
    cfg = modified(CFG, tmp_path, {"planetary": {"teeth": [18, 27, 72], "planets": 4, "spacing": "unequal"}},
                   name="unequal.yaml")
    spec = pipeline.load(cfg).spec
    assert not assembly_whole(18, 72, 4)
    turned = turn_planetary(build_planetary(spec), np.array([0.0, 0.7]), tol=1e-4)
    assert turned["overlap_mm2"].max() == 0.0
