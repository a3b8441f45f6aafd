"""``auto`` running clearance on the crossed helical pair and the worm drive (mechanisms.autoplay, the
crossed_helical schema's ``AUTO_PLAY``): the chosen clearance is on the 0.01 mm grid, the design and
spec carry it, the kit built with it meets ``tolerance.max_jam_probability`` by its own check's quick
study (a fresh model of that kit, not the search's), and the kit one grid step tighter misses it: the
least on the grid. A bad value exits 2 naming the key.

Cheap: 4 phases per check (one search, then the check of the kit at the chosen value and one step less),
on the shipped pairs made cheap to build (tests/designs/crossed_small.yaml, tests/designs/worm_small.yaml:
0.02 mm chords where configs/ flank at 0.003 and 0.005 mm): the same search, model and checks, the kits a
fraction of the triangles."""

import pytest

from partgen import pipeline
from partgen.cli.main import main
from partgen.mechanisms import autoplay

RC = "shafts.running_clearance_diametral_mm"
STEP = autoplay.RUNNING_STEP_MM


@pytest.mark.parametrize("config", ["tests/designs/crossed_small.yaml", "tests/designs/worm_small.yaml"])
def test_auto_running_clearance_is_the_least_that_meets_the_target(config, monkeypatch):
    monkeypatch.setenv("PARTGEN_CACHE", "0")  # the search itself, not a remembered choice
    loaded = pipeline.load(config, over=pipeline.overrides([f"{RC}=auto", "checks.samples=4"]))
    a = loaded.auto
    c = a["values"][RC]
    target = loaded.raw.design.tolerance.max_jam_probability
    assert target == a["target"] == 0.01 and a["reached"] and a["probability"] <= target
    assert round(c / STEP, 9) == round(c / STEP) and STEP < c < 1.0  # on the grid, above its first step
    assert a["joints"] == 2 and a["meshes"] == 1 and a["limited_by"] is None
    # the design, its pinned document and the spec carry the number
    assert loaded.raw.design.shafts.running_clearance_diametral_mm == c and loaded.spec.running == c
    assert loaded.raw.document()["shafts"]["running_clearance_diametral_mm"] == c

    def p_jam(clearance: float) -> float:
        over = pipeline.overrides([f"{RC}={round(clearance, 6)}"])
        jam = pipeline.check(config, 4, write_plates=False, over=over).result.figures["jam"]
        assert jam["target"] == target
        return jam["probability"]
    assert p_jam(c) <= target  # the kit built with it, by its own study
    assert p_jam(c - STEP) > target  # one step less misses it


def test_bad_auto_running_clearance_exits_2_naming_the_key(tmp_path, capsys):
    dest = tmp_path / "kit"
    assert main(["build", "configs/gear_train_crossed_helical.yaml", "-o", str(dest), "-q", "--set", f"{RC}=autox"]) == 2
    err = capsys.readouterr().err
    assert RC in err and "Traceback" not in err, err
    assert not dest.exists()
