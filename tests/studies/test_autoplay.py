"""`gears.backlash_per_gear_mm: auto` and check's quick tolerance study (docs/tolerance.md).

Cheap: the gear pair on a desktop printer with a tight bore fit, so the mesh needs backlash."""

import math

import numpy as np
import pytest

from partgen import pipeline
from partgen.design.tolerance import Feature, Margin, MarginModel, least_play

CONFIG = "configs/gear_pair.yaml"
TIGHT = ["axles.clearance_diametral_mm=0.2"]  # 0.1 mm radial: the mesh needs backlash besides (auto: 0.045 mm)


def _one_mesh(nominal, sigma, slope):
    feats = (Feature("t", "tooth", "g"),)
    return MarginModel(feats, (Margin("m", "mesh", "backlash", nominal, per_backlash=slope),), np.array([[1.0]]),
                       np.array([sigma]), np.array([nominal]), 0.3)


def test_least_play_is_the_normal_tail_on_its_grid():
    """One margin N(m0 + 2(b − 0.05), 0.03²): the least b on the 0.005 mm grid with P ≤ 1 % is the
    first grid value past 0.05 + (2.326·0.03 − m0)/2."""
    m0, sd = 0.01, 0.03
    got = least_play(_one_mesh(m0, sd, 2.0), 0.05, 0.01, samples=200_000)
    exact = 0.05 + (2.3263 * sd - m0) / 2
    assert got["reached"] and got["probability"] <= 0.01
    assert exact - 0.005 <= got["backlash_per_gear_mm"] <= exact + 0.01  # the tail at 1 % sampled: ±1 step
    assert round(got["backlash_per_gear_mm"] / 0.005, 9) == int(round(got["backlash_per_gear_mm"] / 0.005))
    tighter = least_play(_one_mesh(m0, sd, 2.0), 0.05, 0.001, samples=200_000)
    assert tighter["backlash_per_gear_mm"] > got["backlash_per_gear_mm"]
    assert least_play(_one_mesh(m0, sd, 2.0), 0.05, 0.01, samples=200_000) == got  # deterministic
    never = least_play(_one_mesh(-5.0, sd, 2.0), 0.05, 0.01, samples=2000)
    assert not never["reached"] and never["probability"] == 1.0 and never["backlash_per_gear_mm"] == 0.005


@pytest.fixture(scope="module")
def auto_pair():
    return pipeline.load(CONFIG, over=pipeline.overrides(TIGHT + ["gears.backlash_per_gear_mm=auto"], "ender3_v3"))


def _check(value, sets=TIGHT):
    over = pipeline.overrides(sets + [f"gears.backlash_per_gear_mm={value}"], "ender3_v3")
    c = pipeline.check(CONFIG, 24, write_plates=False, over=over)
    return c.result.figures["jam"]


def test_auto_meets_the_target_and_is_the_least(auto_pair):
    a = auto_pair.auto
    b = a["backlash_per_gear_mm"]
    assert a["reached"] and a["probability"] <= a["target"] == 0.01 and a["accuracy_mm"] == 0.15
    assert auto_pair.raw.design.gears.backlash_per_gear_mm == b  # the kit is built with the number
    # the quick study of the kit auto built meets it; one grid step less does not
    assert _check(b)["probability"] <= 0.01 + 0.002
    assert _check(round(b - 0.005, 6))["probability"] > 0.01


def test_check_p_jam_moves_the_right_way():
    """More backlash: fewer jams; more bore play: fewer jams (the fits, and the mesh seated further
    apart); the worst case (centred) never below the seated figure."""
    lo, hi = _check(0.0), _check(0.08)
    assert hi["probability"] < lo["probability"]
    loose = _check(0.0, ["axles.clearance_diametral_mm=0.3"])
    assert loose["probability"] < lo["probability"]
    for j in (lo, hi, loose):
        assert j["worst_case"] >= j["probability"]


def test_check_fails_above_max_jam_probability():
    over = pipeline.overrides(TIGHT + ["gears.backlash_per_gear_mm=0"], "ender3_v3")
    c = pipeline.check(CONFIG, 24, write_plates=False, over=over, max_jam=0.05)
    f = next(f for f in c.result.findings if f.check == "tolerance")
    assert c.result.figures["jam"]["probability"] > 0.05 and f.severity == "fail" and not c.result.ok
    assert math.isclose(f.value, c.result.figures["jam"]["probability"])


def test_auto_verifies_its_choice_on_the_kit_it_builds():
    """The search chooses on the model of the kit built at the start values; the kit built with the
    choice has margins of its own. The desktop chain at 27 mm per unit on the Ender-3 V3 is a case
    where they part: 0.105 mm per gear meets the target on the start kit's model but jams more
    than allowed on its own kit's, so auto searches again from that kit (upwards only) and stands
    at a value whose own kit meets it — what `check` of the built kit then reports."""
    from partgen.mechanisms import autoplay

    over = pipeline.overrides(["curve.scale_mm_per_unit=27"], "ender3_v3")
    loaded = pipeline.load("configs/butterfly_desktop.yaml", over=over)
    a = loaded.auto
    rounds = a["verified"]
    assert 2 <= len(rounds) <= autoplay.VERIFY_ROUNDS  # (this case needs the second round)
    assert rounds[-1]["jams"] <= rounds[-1]["allowed"] and rounds[-1]["values"] == a["values"]
    assert rounds[0]["jams"] > rounds[0]["allowed"]  # the first choice missed on its own kit, the next is larger
    key = "gears.backlash_per_gear_mm"
    assert rounds[-1]["values"][key] > rounds[0]["values"][key]
    kit = pipeline.make_kit(loaded)
    result = loaded.mechanism.check(loaded.spec, kit, None, None)
    jam = pipeline.jam_finding(loaded, kit, result)
    assert result.figures["jam"]["probability"] <= a["target"], jam


def test_build_writes_the_kit_its_search_built_and_checked(tmp_path, monkeypatch):
    """The search builds and checks its choice's kit; `build` of that design writes that very kit
    (``autoplay.searched_kit``, handed to ``make_kit`` once: one build fewer) and its files are
    those of the kit built anew, byte for byte. Any other design misses the hand-over: another
    path, another document (digest), another kind, another resolved design object; and it is
    handed over once. (24 crank angles: the search's checks are the cost, the hand-over is the same.)"""
    from dataclasses import replace

    from partgen.mechanisms import REGISTRY, autoplay

    monkeypatch.setenv("PARTGEN_CACHE", "0")
    monkeypatch.setattr(autoplay, "_DONE", {})
    mech = REGISTRY["gear_pair"]
    real, builds = type(mech).build, []
    monkeypatch.setattr(type(mech), "build", lambda self, spec, progress=None: builds.append(spec) or real(self, spec, progress))
    over = pipeline.overrides(TIGHT + ["gears.backlash_per_gear_mm=auto", "checks.samples=24"], "ender3_v3")
    loaded = pipeline.load(CONFIG, over=over)
    assert len(loaded.auto["verified"]) == 1 and not loaded.auto["per_unit"]["adopted"]
    assert len(builds) == 2 and builds[1] is loaded.spec  # the start values' kit, the choice's kit
    raw, spec = loaded.raw, loaded.spec
    assert autoplay.searched_spec(raw, mech) is spec
    other = replace(raw, data={**raw.data, "name": raw.data["name"] + "_b"})
    assert other.digest() != raw.digest() and autoplay.searched_spec(other, mech) is None
    assert autoplay.searched_kit(other, mech, spec) is None
    assert autoplay.searched_kit(replace(raw, path=tmp_path / "elsewhere.yaml"), mech, spec) is None
    assert autoplay.searched_kit(raw, REGISTRY["gear_chain"], spec) is None
    again = mech.resolve(raw)
    assert again is not spec and autoplay.searched_kit(raw, mech, again) is None
    a = pipeline.build(CONFIG, tmp_path / "a", over=over)  # the search remembered: its kit handed over
    assert len(builds) == 2 and a.loaded.spec is spec
    assert autoplay.searched_kit(raw, mech, spec) is None  # once
    b = pipeline.build(CONFIG, tmp_path / "b", over=over)
    assert len(builds) == 3 and b.kit is not a.kit  # built anew
    files = sorted(p.relative_to(a.dest) for p in a.dest.rglob("*") if p.is_file())
    assert files == sorted(p.relative_to(b.dest) for p in b.dest.rglob("*") if p.is_file()) and len(files) > 3
    for f in files:
        assert (a.dest / f).read_bytes() == (b.dest / f).read_bytes(), f


def test_a_choice_at_the_start_values_is_verified_on_the_start_kit(monkeypatch):
    """When the search chooses the start values (0.05 mm here: a 0.195 mm bore fit), the kit it
    verifies on is the start kit, built and checked once; the allocation is the one a search that
    builds and checks that kit again gives, figure for figure."""
    import json

    from partgen.mechanisms import REGISTRY, autoplay

    monkeypatch.setenv("PARTGEN_CACHE", "0")
    mech = REGISTRY["gear_pair"]
    real, builds = type(mech).build, []
    monkeypatch.setattr(type(mech), "build", lambda self, spec, progress=None: builds.append(spec) or real(self, spec, progress))
    over = pipeline.overrides(["axles.clearance_diametral_mm=0.195", "gears.backlash_per_gear_mm=auto",
                               "checks.samples=24"], "ender3_v3")
    got = []
    for memo in (True, False):
        monkeypatch.setattr(autoplay, "_DONE", {})
        if not memo:  # every design resolved anew: the choice is another object than the start's, built again
            monkeypatch.setattr(autoplay, "_spec", lambda raw, mech, values, memo=None: mech.resolve(autoplay._with(raw, values)))
        builds.clear()
        loaded = pipeline.load(CONFIG, over=over)
        got.append((len(builds), loaded.auto))
    assert got[0][1]["values"] == {"gears.backlash_per_gear_mm": autoplay.ROLES["backlash"][1]}
    assert [n for n, _ in got] == [1, 2]
    assert json.dumps(got[0][1], sort_keys=True) == json.dumps(got[1][1], sort_keys=True)


def test_check_of_the_searched_kit_is_the_searchs_own(monkeypatch):
    """The search checked its choice's kit at the design's own samples; `check` of that design in the
    same process reads that check (``autoplay.searched_check``, through ``pipeline.checked``) instead
    of checking again, and it is the check a new one gives, figure for figure and finding for
    finding. Another kit object (even of the same design) gets nothing from it."""
    from partgen.mechanisms import REGISTRY, autoplay

    monkeypatch.setenv("PARTGEN_CACHE", "0")
    monkeypatch.setattr(autoplay, "_DONE", {})
    monkeypatch.setattr(pipeline, "_KITS", {})  # no kit of this design built before in this process
    mech = REGISTRY["gear_pair"]
    real, checks = type(mech).check, []
    monkeypatch.setattr(type(mech), "check", lambda self, *a: checks.append(a[1]) or real(self, *a))
    over = pipeline.overrides(TIGHT + ["gears.backlash_per_gear_mm=auto", "checks.samples=24"], "ender3_v3")
    loaded = pipeline.load(CONFIG, over=over)
    kit = pipeline.make_kit(loaded)  # the kit the search built and checked (handed over)
    assert checks[-1] is kit
    pipeline._CHECKS.clear()
    n = len(checks)
    got = pipeline.checked(loaded, kit)
    assert len(checks) == n  # not checked again
    fresh = real(mech, loaded.spec, kit, None, None)
    assert [(f.check, f.severity, f.message, f.value) for f in got.findings] == \
        [(f.check, f.severity, f.message, f.value) for f in fresh.findings]
    drop = lambda fig: {k: v for k, v in fig.items() if k != "seconds"}  # noqa: E731
    assert drop(got.figures) == drop(fresh.figures)
    other = mech.build(loaded.spec, None)
    raw = loaded.raw
    assert autoplay.searched_check(raw, mech, other) is None and autoplay.searched_check(raw, mech, kit) is not None
    assert autoplay.searched_check(raw, REGISTRY["gear_chain"], kit) is None  # another kind's key
