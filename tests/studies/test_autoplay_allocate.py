"""``auto`` play allocated per gear and per running joint (design.allocate.allocate_units,
mechanisms.autoplay): from the uniform choice, on the same fixed prints, the least total play with
P(jam) at most the target, and the worst case (no bore play credited) no worse than the uniform
choice's: held to that, the default chain keeps its uniform values; a mapping {default: mm, <name>:
mm} pinned in the kit's design.yaml rebuilds the same kit; each gear's own backlash reaches its teeth
(measured on the solid's section); bad names exit 2.

Cost: one chain search and one check of its pinned kit (module fixtures), gear pair builds, and
synthetic margin models."""

import math

import numpy as np
import pytest
import shapely
import yaml
from shapely.geometry import Point

from partgen import pipeline
from partgen.cli.main import main
from partgen.design import involute
from partgen.design.allocate import (Unit, allocate_units, gear_slopes, hole_slope, joint_slopes, least_allocation,
                                     play_weight)
from partgen.design.tolerance import Feature, Margin, MarginModel
from partgen.geometry.measure import section

BL = "gears.backlash_per_gear_mm"
RC = "joints.running_clearance_diametral_mm"
CHAIN = "configs/butterfly.yaml"
PAIR = "configs/gear_pair.yaml"


def _meshes(sds=(0.02, 0.02, 0.06, 0.02), seed=7):
    """Independent meshes a/b, each with its gears' teeth and a post position as features: mesh k's
    backlash moves 2 mm per mm of backlash per gear (1 per gear), its spread ``sds[k]``."""
    rng = np.random.default_rng(seed)
    feats, margins, cols = [], [], []
    n = len(sds)
    F = 3 * n
    for k, sd in enumerate(sds):
        a, b = f"A{k}", f"B{k}"
        feats += [Feature(f"{a} teeth", "tooth", a), Feature(f"{b} teeth", "tooth", b), Feature(f"post{k} x", "position", "base")]
        col = np.zeros(F)
        col[3 * k:3 * k + 3] = [-1.0, -1.0, 0.7 + 0.1 * rng.random()]
        cols.append(col * sd / 0.03)
        margins.append(Margin(f"{a}/{b}", "mesh", "backlash", 0.0, per_backlash=2.0))
    coeff = np.array(cols).T
    return MarginModel(tuple(feats), tuple(margins), coeff, np.full(F, 0.03), np.zeros(n), 0.3)


def _units(model, start_mm=0.0):
    return [Unit(BL, g, start_mm, s, 0.005, 1, 100) for g, s in gear_slopes(model).items()]


def _jams(model, units, values, samples=20_000, seed=0):
    """Jams among the fixed prints at per-unit ``values`` (mm), counted here from scratch."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(0,)))
    z = rng.standard_normal((samples, len(model.features)))
    m = model.nominal + z @ (model.coeff * model.sigma[:, None])
    m = m + sum((v - u.start) * u.slope for u, v in zip(units, values))
    return int((m < 0).any(axis=1).sum())


def test_the_units_split_the_keys_slopes():
    """Each gear carries half of each of its meshes' per_backlash; each bore its own coefficients:
    summed, they are the uniform keys' slopes."""
    model = _meshes()
    g = gear_slopes(model)
    assert list(g) == ["A0", "A1", "A2", "A3", "B0", "B1", "B2", "B3"]  # natural name order
    assert np.allclose(sum(g.values()), [m.per_backlash for m in model.margins])
    assert np.allclose(g["A2"], [0, 0, 1.0, 0])
    feats = (Feature("G2 bore", "hole", "G2"), Feature("G10 bore", "hole", "G10"), Feature("post", "pin", "B1"))
    margins = (Margin("G10 on B9", "joint", "radial gap", 0.1), Margin("G2 on B1", "joint", "radial gap", 0.1),
               Margin("M1/G2", "mesh", "backlash", 0.1, per_backlash=2.0))
    coeff = np.array([[0.0, 0.5, 0.3], [0.5, 0.0, 0.2], [-0.5, -0.5, 0.0]])
    jm = MarginModel(feats, margins, coeff, np.full(3, 0.01), np.full(3, 0.1), 0.03)
    j = joint_slopes(jm)
    assert list(j) == ["G2", "G10"] and np.allclose(j["G2"], [0, 0.5, 0.3]) and np.allclose(j["G10"], [0.5, 0, 0.2])
    assert np.allclose(sum(j.values()), hole_slope(jm))


def _analytic(model, units, values):
    """The union bound of the margins' normal tails at per-unit ``values`` (mm), computed here."""
    from statistics import NormalDist
    mu = model.nominal + sum((v - u.start) * u.slope for u, v in zip(units, values))
    sd = np.sqrt(((model.coeff * model.sigma[:, None]) ** 2).sum(axis=0))
    return sum(NormalDist().cdf(-m / s) for m, s in zip(mu, sd))


def test_allocation_moves_play_to_the_mesh_that_carries_the_jams():
    """Four meshes, one three times as scattered: the uniform choice gives every gear what that mesh
    needs; the allocation gives it more and the others less at no more model probability of a jam,
    costs less, jams about as often on fresh prints, and no gear can lose a step without raising the
    probability above the uniform's (a local least)."""
    model = _meshes()
    units = _units(model)
    slope = np.array([m.per_backlash for m in model.margins])
    from partgen.design.allocate import Knob
    uni = least_allocation(model, [Knob(BL, "backlash per gear", 0.0, slope, 0.005, 1, 100)], 0.01)
    b = uni["values"][BL]
    start = [round(b / 0.005)] * len(units)
    got = allocate_units(model, units, start)
    vals = dict(zip([u.name for u in units], got["values"]))
    assert got["jams"] == _jams(model, units, got["values"])
    budget = _analytic(model, units, [b] * len(units))
    assert _analytic(model, units, got["values"]) <= budget * (1 + 1e-9)
    assert vals["A2"] + vals["B2"] > 2 * b  # the scattered mesh got more than the uniform value
    assert all(vals[f"A{k}"] + vals[f"B{k}"] < 2 * b for k in (0, 1, 3))  # the others less
    w = [play_weight(model, u.slope) for u in units]
    assert math.isclose(got["cost_mm"], sum(x * v for x, v in zip(w, got["values"])), abs_tol=1e-6)
    assert got["cost_mm"] < uni["cost_mm"] - 0.05
    for i, u in enumerate(units):  # one step less of any gear raises the probability above the budget
        lower = list(got["values"])
        lower[i] = round(lower[i] - 0.005, 6)
        assert lower[i] < 0.005 or _analytic(model, units, lower) > budget * (1 - 1e-9), u.name
    # not fitted to the luck of any prints: on 100,000 others it jams as the uniform values do (±5 σ)
    fresh_u = _jams(model, units, [b] * len(units), 100_000, seed=5)
    fresh_a = _jams(model, units, got["values"], 100_000, seed=5)
    assert abs(fresh_a - fresh_u) < 5 * math.sqrt(fresh_u), (fresh_a, fresh_u)
    assert allocate_units(model, units, start)["values"] == got["values"]  # deterministic


def test_the_worst_case_guard_keeps_the_worst_case():
    """Mesh 0's bores' play is credited to it when the gears are seated (its margins 0.06 mm wider) and
    not in the worst case. Unbounded, the allocation thins mesh 0's gears, which the credit covers,
    and the worst case's probability rises; held to it, the worst case's probability stays at most the
    uniform choice's, the headline's too, and the play is no more than the uniform's."""
    worst = _meshes((0.03, 0.03, 0.03, 0.03))
    credit = np.array([0.06, 0.0, 0.0, 0.0])
    seated = MarginModel(worst.features, worst.margins, worst.coeff, worst.sigma, worst.nominal + credit,
                         worst.accuracy_mm)
    units, wunits = _units(seated), _units(worst)
    slope = np.array([m.per_backlash for m in seated.margins])
    from partgen.design.allocate import Knob
    uni = least_allocation(seated, [Knob(BL, "backlash per gear", 0.0, slope, 0.005, 1, 100)], 0.01)
    b = uni["values"][BL]
    start = [round(b / 0.005)] * len(units)
    w_budget = _analytic(worst, wunits, [b] * len(units))
    free = allocate_units(seated, units, start)
    assert _analytic(worst, wunits, free["values"]) > 1.5 * w_budget  # unbounded: the worst case rises
    held = allocate_units(seated, units, start, guard=(worst, wunits))
    assert _analytic(worst, wunits, held["values"]) <= w_budget * (1 + 1e-9)
    assert held["guard"]["end"] <= held["guard"]["start"] + 1e-12
    assert _analytic(seated, units, held["values"]) <= _analytic(seated, units, [b] * len(units)) * (1 + 1e-9)
    assert held["cost_mm"] <= uni["cost_mm"] + 1e-9 and held["cost_mm"] > free["cost_mm"]
    with pytest.raises(ValueError):
        allocate_units(seated, units, start, guard=(worst, wunits[::-1]))


def _perturbed(model, n):
    direction = math.inf if n > 0 else -math.inf
    nominal, coeff = model.nominal.copy(), model.coeff.copy()
    for _ in range(abs(n)):
        nominal = np.nextafter(nominal, direction)
        coeff = np.where(coeff != 0.0, np.nextafter(coeff, direction), 0.0)
    return MarginModel(model.features, model.margins, coeff, model.sigma, nominal, model.accuracy_mm)


def _pair_units(model):
    return ([Unit(BL, g, 0.05, s, 0.005, 1, 100) for g, s in gear_slopes(model).items()]
            + [Unit("axles.clearance_diametral_mm", g, 0.3, s, 0.01, 1, 100) for g, s in joint_slopes(model).items()])


@pytest.mark.parametrize("which", ["synthetic", "gear_pair"])
def test_allocation_survives_ulp_perturbations(which):
    """Every nominal margin and coefficient moved a few ulps (another machine's sums): the same
    values for every unit (integer jam counts, quantised costs, stated tie order)."""
    if which == "synthetic":
        model = _meshes((0.02, 0.03, 0.05, 0.025, 0.04, 0.02), seed=3)
        make = _units
        start = 12
    else:
        over = pipeline.overrides([f"{BL}=0.05", "axles.clearance_diametral_mm=0.3"], "ender3_v3")
        loaded = pipeline.load(PAIR, over=over)
        kit = pipeline.make_kit(loaded)
        result = loaded.mechanism.check(loaded.spec, kit, 24)
        model = loaded.mechanism.tolerance_model(loaded.spec, kit, result, kit.printer.xy_accuracy)
        make = _pair_units
        start = None
    units = make(model)
    idx = [start or (12 if u.key == BL else 30) for u in units]
    base = allocate_units(model, units, idx)
    assert which == "gear_pair" or base["values"] != [u.value(i) for u, i in zip(units, idx)]  # it moved
    for n in (-3, 2):
        moved = _perturbed(model, n)
        assert allocate_units(moved, make(moved), idx)["values"] == base["values"], n


# the chain with its own values for a few gears and joints, as an allocation pins them in design.yaml
OWN_BL = {"default": 0.1, "D4": 0.08, "G11": 0.12}
OWN_RC = {"default": 0.21, "G5": 0.24, "M3": 0.19}


@pytest.fixture(scope="module")
def chain_auto():
    """The default chain with its running clearance auto too (the backlash is auto in the file)."""
    return pipeline.load(CHAIN, over=pipeline.overrides([f"{RC}=auto"]))


@pytest.fixture(scope="module")
def chain_own():
    """The default chain with each key a mapping {default: mm, <name>: mm}."""
    return pipeline.load(CHAIN, over=pipeline.overrides([f"{BL}={OWN_BL}", f"{RC}={OWN_RC}"]))


@pytest.fixture(scope="module")
def pinned(chain_own, tmp_path_factory):
    """The kit's design.yaml and printer.yaml as build writes them, checked from that file (at 24 crank
    angles, not the design's 360: what the tests read, the fits, are measured in their sections)."""
    loaded = chain_own
    kit = pipeline.make_kit(loaded)
    d = tmp_path_factory.mktemp("pinned")
    for name, data in loaded.mechanism.kit_files(loaded.spec, kit, loaded.raw).items():
        (d / name).write_bytes(data)
    return d / "design.yaml", pipeline.check(str(d / "design.yaml"), 24, write_plates=False)


def test_the_default_chains_allocation_is_held_to_the_worst_case(chain_auto):
    """Both keys auto on the default chain: the uniform choice meets the target; moved gear by gear
    under the worst case's bound (no bore play credited, the uniform choice's), no step saves play, so
    the uniform values are kept and build says why. The allocation unbounded would save play by
    thinning gears whose bores' play is credited — and raise the worst case (shown on the model)."""
    a = chain_auto.auto
    pu = a["per_unit"]
    assert not pu["adopted"] and "worst case" in pu["why"], pu["why"]
    assert a["meshes"] == 21 and a["joints"] == 22
    assert a["probability"] <= 0.01 and a["jams"] <= math.floor(a["target"] * a["samples"])
    assert pu["analytic"]["end"] <= pu["analytic"]["start"]
    doc = chain_auto.raw.document()  # numbers, not mappings
    assert doc["gears"]["backlash_per_gear_mm"] == a["values"][BL]
    assert doc["joints"]["running_clearance_diametral_mm"] == a["values"][RC]


def test_the_pinned_design_rebuilds_the_kit(chain_own, pinned):
    path, checked = pinned
    data = yaml.safe_load(path.read_text())
    assert data["gears"]["backlash_per_gear_mm"] == OWN_BL
    assert data["joints"]["running_clearance_diametral_mm"] == OWN_RC
    again = checked.loaded
    assert again.auto is None  # numbers, no search
    assert again.spec.mechanism == chain_own.spec.mechanism and again.spec.params == chain_own.spec.params
    gears = dict(chain_own.spec.mechanism.gears)
    for name, v in OWN_BL.items():
        if name != "default":
            assert gears[name].system.backlash_per_gear == v
    # the running contacts carry each joint's own clearance
    runs = {c.a: c.radial_gap for c in checked.kit.contacts if c.kind == "running"}
    own_rc = {k: v for k, v in OWN_RC.items() if k != "default"}
    for name, v in own_rc.items():
        assert math.isclose(runs[name], v / 2)
        assert math.isclose(chain_own.spec.params.bore_of(name), chain_own.spec.params.joints.axle_diameter + v)
    rows = {tuple(r["parts"]): r.get("radial_gap_mm") for r in checked.result.figures["fits"]["rows"]}
    carrier = {c.a: c.b for c in checked.kit.contacts if c.kind == "running"}
    for name, v in own_rc.items():  # measured on the solids
        got = rows[(name, carrier[name])]
        assert abs(got - v / 2) < 0.003, (name, got, v)


def _thickness(poly, r: float, teeth: int) -> float:
    """Mean arc thickness of the teeth on the circle of radius ``r`` of a gear section (its own
    frame): the length of the circle inside the material over the number of teeth."""
    ring = Point(0.0, 0.0).buffer(r, quad_segs=4096).exterior
    return shapely.intersection(ring, poly).length / teeth


def test_a_gears_own_backlash_reaches_its_teeth():
    """The pair with gear2 thinned 0.3 mm and gear1 0.1 mm: each section's tooth thickness on its
    reference circle is the formula's with its own thinning."""
    over = pipeline.overrides([f"{BL}={{default: 0.1, gear2: 0.3}}"])
    loaded = pipeline.load(PAIR, over=over)
    kit = pipeline.make_kit(loaded)
    s = loaded.spec
    got = {}
    for name, g in (("gear1", s.gear1), ("gear2", s.gear2)):
        part = next(p for p in kit.parts if p.name == name)
        got[name] = _thickness(section(part.solid, s.face_width / 2), g.pitch_radius, g.teeth)
        want = involute.reference_tooth_thickness(g.teeth, g.module, g.system.pressure_angle, g.profile_shift,
                                                  g.system.backlash_per_gear)
        assert abs(got[name] - want) < 0.004, (name, got[name], want)
    g2 = s.gear2
    uniform = involute.reference_tooth_thickness(g2.teeth, g2.module, g2.system.pressure_angle, g2.profile_shift, 0.1)
    assert uniform - got["gear2"] > 0.19  # 0.2 mm thinner than with the default


def test_a_gears_own_clearance_reaches_its_bore():
    """The pair with gear1's bore 0.6 mm over its post and gear2's the default 0.4: measured on the
    sections, gear1's bore is 0.1 mm wider in radius; the check and the model read each gear's gap."""
    over = pipeline.overrides(["axles.clearance_diametral_mm={default: 0.4, gear1: 0.6}"])
    c = pipeline.check(PAIR, 24, write_plates=False, over=over)
    s = c.loaded.spec
    bore = {}
    for name in ("gear1", "gear2"):
        part = next(p for p in c.kit.parts if p.name == name)
        poly = section(part.solid, s.face_width / 2)
        ring = min((np.asarray(r.coords) for r in poly.interiors), key=lambda xy: np.hypot(*xy[:, :2].T).mean())
        bore[name] = float(np.hypot(*ring[:, :2].T).mean())
    assert abs(bore["gear1"] - (s.axle_radius + 0.3)) < 0.01 and abs(bore["gear2"] - (s.axle_radius + 0.2)) < 0.01
    assert c.result.figures["radial_gaps_mm"] == pytest.approx([0.3, 0.2])
    model = c.loaded.mechanism.tolerance_model(s, c.kit, c.result, c.kit.printer.xy_accuracy)
    gaps = {m.unit: m.nominal for m in model.margins if m.what == "radial gap"}
    assert gaps == pytest.approx({"gear1 on its post": 0.3, "gear2 on its post": 0.2})


def test_a_chain_gears_own_backlash_reaches_its_teeth(chain_own, pinned):
    """In the chain kit with its own values: a D gear with its own backlash has the teeth the formula
    gives for it; one thinner than the default has thicker teeth than it would with the default."""
    _, checked = pinned
    own = {k: v for k, v in OWN_BL.items() if k != "default"}
    name = next(n for n in own if n.startswith("D") and own[n] < OWN_BL["default"])
    part = next(p for p in checked.kit.parts if p.name == name)
    g = part.gear
    assert g.system.backlash_per_gear == own[name]
    got = _thickness(section(part.solid, checked.loaded.spec.params.face_width / 2), g.pitch_radius, g.teeth)
    want = involute.reference_tooth_thickness(g.teeth, g.module, g.system.pressure_angle, g.profile_shift, own[name])
    default = involute.reference_tooth_thickness(g.teeth, g.module, g.system.pressure_angle, g.profile_shift,
                                                 OWN_BL["default"])
    assert abs(got - want) < 0.004 and got > default + 0.003, (got, want, default)


@pytest.mark.parametrize("config, sets, key", [
    (PAIR, [f"{BL}={{default: 0.1, gear9: 0.2}}"], f"{BL}.gear9"),
    (PAIR, ["axles.clearance_diametral_mm={gear1: 0.3}"], "axles.clearance_diametral_mm.default"),
    (PAIR, [f"{BL}={{default: 0.1, gear1: -0.2}}"], f"{BL}.gear1"),
    (CHAIN, [f"{BL}={{default: 0.1, G99: 0.2}}"], f"{BL}.G99"),
    (CHAIN, [f"{RC}={{default: 0.2, B3: 0.3}}"], f"{RC}.B3"),
])
def test_bad_mapping_keys_exit_2(tmp_path, capsys, config, sets, key):
    dest = tmp_path / "kit"
    args = ["build", config, "-o", str(dest)]
    for s in sets:
        args += ["--set", s]
    code = main(args)
    out, err = capsys.readouterr()
    assert code == 2, err
    assert key in err and "Traceback" not in err + out
    assert not dest.exists()
