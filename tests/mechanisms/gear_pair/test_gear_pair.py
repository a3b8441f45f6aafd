"""kind: gear_pair — two spur gears on a base plate: the posts stand at the involute centre
distance (measured on the printed base), the check over one output turn measures the backlash the
tooth thinning designs, a pair pushed together fails, and the trace of its kit folder measures the
lag the backlash gives. (Every command on its design and its kit folder, a tampered kit:
tests/cli/test_contract.py.)"""

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
import trimesh
from shapely.geometry import Polygon

from partgen import pipeline
from partgen.cli.main import main
from partgen.design import involute
from partgen.mechanisms.gear_pair.kit import build_pair
from partgen.mechanisms.gear_pair.checks import flank_play
from partgen.mechanisms.gear_pair.mechanism import MECHANISM

ROOT = Path(__file__).resolve().parents[3]
CFG = ROOT / "configs" / "gear_pair.yaml"


@pytest.fixture(scope="module")
def kit_dir(kit_of):
    """The session's build of configs/gear_pair.yaml (read it, never write into it)."""
    return kit_of("gear_pair").dest


def test_posts_stand_at_the_involute_centre_distance(kit_dir):
    man = json.loads((kit_dir / "manifest.json").read_text())
    assert [p["name"] for p in man["parts"]] == ["base", "gear1", "gear2"]
    base = trimesh.load(kit_dir / "base.stl")
    z = base.bounds[1][2] - 1.0  # through the posts, above the plate
    sec = base.section(plane_origin=[0, 0, z], plane_normal=[0, 0, 1])
    posts = sorted((Polygon(loop[:, :2]) for loop in sec.discrete), key=lambda p: p.centroid.x)
    assert len(posts) == 2
    d = man["design"]
    expected = involute.centre_distance(17, 31, 2.0, np.radians(20.0), *d["profile_shift"])
    assert posts[1].centroid.distance(posts[0].centroid) == pytest.approx(expected, abs=2e-3)
    assert 2 * np.sqrt(posts[0].area / np.pi) == pytest.approx(10.0, abs=0.05)


def test_check_measures_the_designed_backlash_over_an_output_turn():
    loaded = pipeline.load(CFG)
    kit = pipeline.make_kit(loaded)
    result = MECHANISM.check(loaded.spec, kit, 48)
    assert result.ok, result.findings
    b = result.figures["backlash_mm"]
    # at the zero-backlash centre distance the circumferential backlash is the two gears' thinning
    assert b["designed"] == pytest.approx(0.2)
    assert 0.19 < b["min"] <= b["max"] < 0.22
    assert result.figures["max_overlap_mm2"] == 0.0


def test_a_pair_pushed_together_fails():
    loaded = pipeline.load(CFG)
    spec = dataclasses.replace(loaded.spec, centre_distance=loaded.spec.centre_distance - 0.4)
    kit = build_pair(spec)
    play = flank_play(kit, np.linspace(0, 0.4, 5))
    assert (play["overlap_mm2"] > 0.01).all()
    result = MECHANISM.check(spec, kit, 16)
    assert not result.ok and {f.check for f in result.findings if f.severity == "fail"} >= {"interference"}


def test_check_covers_one_output_turn(kit_dir, capsys):
    """(at the design's own 180 samples)"""
    assert main(["check", str(kit_dir), "--no-plates"]) == 0
    assert "180 angles over one turn of the output" in capsys.readouterr().out


def test_trace_of_the_kit_folder_lags_by_half_the_backlash(kit_dir, tmp_path, capsys):
    csv = tmp_path / "te.csv"
    assert main(["trace", str(kit_dir), "--samples", "32", "--csv", str(csv), "--no-plots", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["kind"] == "gear_pair"
    rows = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert rows.shape == (32, 4)
    # the driven flank's lag is half the backlash, within the transmission error
    assert np.allclose(rows[:, 2] * 31.0, rows[:, 3] / 2, atol=0.01)  # output pitch radius 31 mm
