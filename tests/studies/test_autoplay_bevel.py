"""``auto`` play on the straight bevel pair (mechanisms.autoplay, its schema's ``AUTO_PLAY``): the
backlash per gear and the shafts' running clearance chosen together meet the design's
``tolerance.max_jam_probability`` on the kit's own quick study, the kit's design.yaml carries the
numbers, the search is deterministic, and bad values exit 2 naming the key.

Cheap: the mitre pair at 4 phases per check (one search, one kit, one check of it, one search again), made
cheap to build (tests/designs/bevel_small.yaml: configs/bevel_mitre.yaml at a 0.02 mm heel chord instead of
0.001): the same search, model and checks on a kit of a fraction of the triangles."""

import pytest
import yaml

from partgen import pipeline
from partgen.cli.main import main
from partgen.mechanisms import autoplay

CONFIG = "tests/designs/bevel_small.yaml"
BL, RC = "gears.backlash_per_gear_mm", "shafts.running_clearance_diametral_mm"
AUTO = [f"{BL}=auto", f"{RC}=auto", "checks.samples=4"]


@pytest.fixture(scope="module")
def auto_bevel():
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("PARTGEN_CACHE", "0")  # the search itself, not a remembered choice
        return pipeline.load(CONFIG, over=pipeline.overrides(AUTO))


def test_auto_bevel_play_meets_the_target_and_the_kit_carries_it(auto_bevel):
    a = auto_bevel.auto
    b, c = a["values"][BL], a["values"][RC]
    assert a["reached"] and a["probability"] <= 0.01 and a["joints"] == 2 and a["meshes"] == 1
    assert round(b / 0.005, 9) == round(b / 0.005) and round(c / 0.01, 9) == round(c / 0.01)  # on the grids
    assert 0 < b <= 0.3 and 0 < c <= 1.0
    d = auto_bevel.raw.design
    assert d.gears.backlash_per_gear_mm == b and d.shafts.running_clearance_diametral_mm == c
    assert auto_bevel.spec.running == c and auto_bevel.spec.gear1.backlash == pytest.approx(b)
    kit = pipeline.make_kit(auto_bevel)
    pinned = yaml.safe_load(auto_bevel.mechanism.kit_files(auto_bevel.spec, kit, auto_bevel.raw)["design.yaml"])
    assert pinned["gears"]["backlash_per_gear_mm"] == b and pinned["shafts"]["running_clearance_diametral_mm"] == c
    # the kit built with the numbers: its own quick study (the model of that kit's check) meets the target
    over = pipeline.overrides([f"{BL}={b}", f"{RC}={c}"])
    jam = pipeline.check(CONFIG, 4, write_plates=False, over=over).result.figures["jam"]
    assert jam["target"] == 0.01 and jam["probability"] <= 0.01 + 0.002
    # less clearance at that backlash misses it (the staircase's point is the least clearance)
    over = pipeline.overrides([f"{BL}={b}", f"{RC}={round(c - 0.02, 6)}"])
    assert pipeline.check(CONFIG, 4, write_plates=False, over=over).result.figures["jam"]["probability"] > 0.01


def test_auto_bevel_play_is_deterministic(auto_bevel, monkeypatch):
    """The search made again from nothing (no remembered choice, no choice of this process) picks the
    same numbers with the same jam count."""
    monkeypatch.setenv("PARTGEN_CACHE", "0")
    monkeypatch.setattr(autoplay, "_DONE", {})
    again = pipeline.load(CONFIG, over=pipeline.overrides(AUTO)).auto
    assert again["values"] == auto_bevel.auto["values"] and again["jams"] == auto_bevel.auto["jams"]


@pytest.mark.parametrize("setting, key", [
    (f"{RC}=autox", RC), (f"{RC}=nan", RC), (f"{RC}=9", RC),
    (f"{BL}=auto1", BL), (f"{BL}=-0.1", BL),
])
def test_bad_auto_play_values_exit_2_naming_the_key(tmp_path, capsys, setting, key):
    dest = tmp_path / "kit"
    assert main(["build", CONFIG, "-o", str(dest), "-q", "--set", setting]) == 2
    err = capsys.readouterr().err
    assert key in err and "Traceback" not in err, err
    assert not dest.exists()
