"""Running clearances ``auto`` with the backlash (mechanisms.autoplay, design.allocate): the pair of
values meets the target, is the least total play on its grid, more play jams less, the kit carries
the numbers, and the choice survives ulp perturbations of its inputs.

Cheap: the gear pair on a desktop printer (one build and check), and synthetic margin models."""

import math

import numpy as np
import pytest
import yaml

from partgen import pipeline
from partgen.design.allocate import Knob, hole_slope, least_allocation
from partgen.design.tolerance import Feature, Margin, MarginModel

CONFIG = "configs/gear_pair.yaml"
AUTO = ["gears.backlash_per_gear_mm=auto", "axles.clearance_diametral_mm=auto"]
PRINTER = "ender3_v3"
BL, RC = "gears.backlash_per_gear_mm", "axles.clearance_diametral_mm"


def _two_margins(mesh0=0.0, fit0=0.0, sd=0.03):
    """A mesh's backlash (2 mm per mm of backlash, +0.5 per mm of the bore's diameter: its play
    credited) and a fit's radial gap (0.5 per mm of its bore), at backlash 0.05, clearance 0.3."""
    feats = (Feature("teeth", "tooth", "g"), Feature("bore", "hole", "g"), Feature("post", "pin", "base"))
    margins = (Margin("g/p", "mesh", "backlash", mesh0, per_backlash=2.0), Margin("g on post", "joint", "radial gap", fit0))
    coeff = np.array([[-2.0, 0.0], [0.5, 0.5], [-0.5, -0.5]])
    return MarginModel(feats, margins, coeff, np.full(3, sd), np.array([mesh0, fit0]), 0.3)


def _knobs(model, most=(100, 100)):
    return [Knob(BL, "backlash per gear", 0.05, np.array([m.per_backlash for m in model.margins]), 0.005, 1, most[0]),
            Knob(RC, "running clearance, diametral", 0.3, hole_slope(model), 0.01, 1, most[1])]


def _jams(model, values, samples=20_000, seed=0):
    """Jams among the allocation's fixed prints, counted here independently of the search."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(0,)))
    z = rng.standard_normal((samples, len(model.features)))
    m = model.nominal + z @ (model.coeff * model.sigma[:, None])
    m = m + (values[0] - 0.05) * np.array([x.per_backlash for x in model.margins]) + (values[1] - 0.3) * hole_slope(model)
    return int((m < 0).any(axis=1).sum())


def test_hole_slope_is_the_bores_share():
    """A clearance Δ wider is the bore printed Δ larger: the fit's gap opens by Δ/2, and the mesh its
    play is credited to by the credit's coefficient."""
    assert np.allclose(hole_slope(_two_margins()), [0.5, 0.5])


def test_two_knobs_staircase_is_exact_and_least():
    """Every frontier pair meets the target and one step less of the clearance does not; the choice
    is the least cost of them; more of either knob never jams more."""
    model = _two_margins(-0.02, -0.05)
    got = least_allocation(model, _knobs(model), 0.01)
    allowed = math.floor(0.01 * 20_000)
    assert got["reached"] and got["jams"] <= allowed
    assert got["jams"] == _jams(model, (got["values"][BL], got["values"][RC]))
    costs = []
    for point in got["frontier"]:
        b, c = point[BL], point[RC]
        assert _jams(model, (b, c)) <= allowed
        if c > 0.01 + 1e-9:
            assert _jams(model, (b, round(c - 0.01, 6))) > allowed
        costs.append(2.0 * b + (0.5 + 0.5) * c)  # weights: backlash margin 2/mm; the clearance: 0.5 (gap) + 0.5 (credit)
    assert math.isclose(got["cost_mm"], min(costs), abs_tol=1e-6)
    assert got["weights"] == {BL: 2.0, RC: 1.0}
    b, c = got["values"][BL], got["values"][RC]
    seq = [_jams(model, (b + 0.005 * k, c)) for k in range(4)] + [_jams(model, (b, c + 0.01 * k)) for k in range(4)]
    assert seq[:4] == sorted(seq[:4], reverse=True) and seq[4:] == sorted(seq[4:], reverse=True)
    assert seq[3] < seq[0] and seq[7] < seq[4]  # more play: strictly fewer jams here
    # a tighter target takes more play
    tighter = least_allocation(model, _knobs(model), 0.002)
    assert tighter["cost_mm"] > got["cost_mm"]


def test_unreachable_target_says_so():
    """A margin no knob moves jams 50 %: the target cannot be reached; the least play reaching the
    floor is chosen, and it says so."""
    feats = (Feature("teeth", "tooth", "g"), Feature("bore", "hole", "g"), Feature("rim", "outline", "g"))
    margins = (Margin("g/p", "mesh", "backlash", 0.0, per_backlash=2.0), Margin("g on post", "joint", "radial gap", 0.0),
               Margin("g–h", "clearance", "gap", 0.0))
    coeff = np.array([[-2.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.0, 0.0, -0.5]])
    model = MarginModel(feats, margins, coeff, np.full(3, 0.03), np.zeros(3), 0.3)
    got = least_allocation(model, _knobs(model), 0.01, samples=4000)
    assert not got["reached"] and 0.45 < got["probability"] < 0.55


@pytest.fixture(scope="module")
def auto_pair():
    return pipeline.load(CONFIG, over=pipeline.overrides(AUTO, PRINTER))


def test_auto_clearance_meets_the_target_and_the_kit_carries_it(auto_pair):
    a = auto_pair.auto
    b, c = a["values"][BL], a["values"][RC]
    assert a["reached"] and a["probability"] <= 0.01 and a["printer"] and a["joints"] == 2 and a["meshes"] == 1
    assert round(c / 0.01, 9) == round(c / 0.01) and round(b / 0.005, 9) == round(b / 0.005)  # on the grid
    d = auto_pair.raw.design
    assert d.axles.clearance_diametral_mm == c and d.gears.backlash_per_gear_mm == b
    kit = pipeline.make_kit(auto_pair)
    pinned = yaml.safe_load(auto_pair.mechanism.kit_files(auto_pair.spec, kit, auto_pair.raw)["design.yaml"])
    assert pinned["axles"]["clearance_diametral_mm"] == c and pinned["gears"]["backlash_per_gear_mm"] == b
    # the kit built with the numbers: its own quick study (a model of that kit) meets the target too
    over = pipeline.overrides([f"{BL}={b}", f"{RC}={c}"], PRINTER)
    jam = pipeline.check(CONFIG, 24, write_plates=False, over=over).result.figures["jam"]
    assert jam["probability"] <= 0.01 + 0.002
    # less clearance at that backlash misses it (the staircase's point is the least clearance)
    over = pipeline.overrides([f"{BL}={b}", f"{RC}={round(c - 0.02, 6)}"], PRINTER)
    assert pipeline.check(CONFIG, 24, write_plates=False, over=over).result.figures["jam"]["probability"] > 0.01


def test_auto_allocation_survives_ulp_perturbations():
    """The search on the kit's own model with every nominal margin and coefficient moved a few ulps
    (another machine's sums) chooses the same pair."""
    over = pipeline.overrides(["gears.backlash_per_gear_mm=0.05", "axles.clearance_diametral_mm=0.3"], PRINTER)
    loaded = pipeline.load(CONFIG, over=over)
    kit = pipeline.make_kit(loaded)
    result = loaded.mechanism.check(loaded.spec, kit, 24)
    model = loaded.mechanism.tolerance_model(loaded.spec, kit, result, kit.printer.xy_accuracy)
    base = least_allocation(model, _knobs(model), 0.01)
    for n in (-3, 2):
        direction = math.inf if n > 0 else -math.inf
        nominal, coeff = model.nominal.copy(), model.coeff.copy()
        for _ in range(abs(n)):
            nominal = np.nextafter(nominal, direction)
            coeff = np.where(coeff != 0.0, np.nextafter(coeff, direction), 0.0)
        moved = MarginModel(model.features, model.margins, coeff, model.sigma, nominal, model.accuracy_mm)
        assert least_allocation(moved, _knobs(moved), 0.01)["values"] == base["values"], n


def test_a_gear_train_chooses_its_shafts_clearance():
    """The reducer with its shafts' running clearance and backlash auto: the pair meets the target on
    its printer, and the kit built with it (its own quick study) does too."""
    sets = ["shafts.running_clearance_diametral_mm=auto", "gears.backlash_per_gear_mm=auto"]
    loaded = pipeline.load("configs/gear_train_reducer.yaml", over=pipeline.overrides(sets))
    a = loaded.auto
    c, b = a["values"]["shafts.running_clearance_diametral_mm"], a["values"][BL]
    assert a["reached"] and a["probability"] <= 0.01 and a["joints"] >= 4 and a["meshes"] >= 2
    assert loaded.raw.design.shafts.running_clearance_diametral_mm == c and loaded.raw.design.gears.backlash_per_gear_mm == b
    over = pipeline.overrides([f"shafts.running_clearance_diametral_mm={c}", f"{BL}={b}"])
    jam = pipeline.check("configs/gear_train_reducer.yaml", 8, write_plates=False, over=over).result.figures["jam"]
    assert jam["probability"] <= 0.01 + 0.002 and jam["target"] == 0.01
