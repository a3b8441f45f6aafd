"""The Bennett linkage's tolerance model: pins in their bores, the loops closing on the joints' play,
and the balance as printed (docs/tolerance.md "Bennett linkage"); ``pin.clearance_diametral_mm: auto``
(the least pin clearance that meets the jam target, on the shipped kit's pinned layout). Runs with tests/mechanisms/bennett_butterfly/test_bennett_cli.py
(the shipped kit, its costliest build, ``conftest.SHARED``)."""

import contextlib
import io
import json
import math
import re
import shutil
from dataclasses import replace

import numpy as np
import pytest
import yaml

from partgen import pipeline
from partgen.cli.main import main
from partgen.core.findings import Result
from partgen.core.protocol import tolerance_hook
from partgen.design import bennett_butterfly as bbf
from partgen.design.allocate import hole_slope, play_weight
from partgen.design.tolerance import run_chunk, summarise
from partgen.mechanisms import autoplay
from partgen.mechanisms.bennett_butterfly import kit as A
from partgen.mechanisms.bennett_butterfly.tolerance import cover


def study(model, n: int = 4000) -> dict:
    return summarise(model, run_chunk(model, 0, 0, n))


@pytest.fixture(scope="module")
def shipped(kit_of):
    b = kit_of("bennett_butterfly")
    return b.loaded.spec, b.kit, tolerance_hook(b.loaded.mechanism)


def group(r: dict, g: str) -> float:
    return r["groups"][g]["probability"]


def test_margins_of_the_shipped_kit(shipped):
    spec, kit, hook = shipped
    kit = replace(kit, params=replace(kit.params, tolerance=0.1))  # tighter than the shipped 0.3: some prints fail
    m = hook(spec, kit, Result(), 0.127)
    fits = [x for x in m.margins if x.what == "radial gap"]
    assert len(fits) == sum(len(kit.layout.members(j)) for j in bbf.JOINTS)
    assert np.allclose([x.nominal for x in fits], kit.params.bore_radius - kit.params.pin_radius)
    loops = [x for x in m.margins if x.unit.endswith("loop")]
    assert {x.unit for x in loops} == {f"Bennett {n} loop" for n in range(1, 5)}
    assert np.allclose([x.nominal for x in loops], 8 * (kit.params.bore_radius - kit.params.pin_radius))
    r = study(m)
    assert 0.0 < r["overall"]["probability"] < 1.0 and r["groups"]["balance"]["count"] == 1


def test_balance_linearisation_against_the_exact_centre_of_mass(shipped):
    """Every link's infill 5 points up (the check's own what-if): the model's centre of mass, at each
    pose it takes, agrees with the exact recomputation (com_deviation) to first order."""
    spec, kit, hook = shipped
    m = hook(spec, kit, Result(), 0.127)
    p = kit.params
    delta = np.array([0.05 if f.kind == "process" else 0.0 for f in m.features])
    value = m.nominal + delta @ m.coeff
    exact = A.com_deviation(kit, "fdm", *A.grid(p), infill=p.infill + 0.05)
    poses = {}
    for k, x in enumerate(m.margins):
        if x.group == "balance":
            g = int(re.search(r"pose (\d+)", x.what).group(1))
            poses.setdefault(g, []).append(k)
    c = cover()
    assert len(poses) >= 8
    for g, ks in poses.items():
        model_d = p.tolerance - value[ks].min()  # the largest projection of the moved centre
        assert c * exact[g] - 2e-3 <= model_d <= exact[g] + 2e-3, (g, model_d, exact[g])
    assert max(exact[g] for g in poses) > 0.03  # the what-if moves it measurably


def test_more_play_and_tolerance_fewer_failures(shipped):
    spec, kit, hook = shipped
    kit = replace(kit, params=replace(kit.params, tolerance=0.1))  # a balance that fails in some prints
    base = study(hook(spec, kit, Result(), 0.3))
    tight = replace(kit, params=replace(kit.params, pin_clearance=0.02))
    r = study(hook(spec, tight, Result(), 0.3))
    assert group(r, "joint") > group(base, "joint")  # 0.02 mm pins bind and loops stop closing
    lax = replace(kit, params=replace(kit.params, tolerance=0.3))
    assert group(study(hook(spec, lax, Result(), 0.3)), "balance") < group(base, "balance")
    rough = replace(kit, params=replace(kit.params, infill_error=0.2))
    assert group(study(hook(spec, rough, Result(), 0.3)), "balance") > group(base, "balance")


# --- `pin.clearance_diametral_mm: auto` (mechanisms.autoplay, role "running") ------------------------

KEY = "pin.clearance_diametral_mm"
START, STEP = autoplay.ROLES["running"][1:3]


def test_the_pins_clearance_moves_the_margins_as_hole_slope_says(shipped):
    """``design.allocate.hole_slope`` (what auto moves the margins by) is the model's own change with
    the pins' clearance: the kit's model at a clearance 0.1 mm wider (diametral) against the shipped
    one. Each pin fit's radial gap opens by half of it, each loop's play (eight bores) by four times
    it, the balance not at all (the counterweight pockets' bores are ``hole`` features of the balance
    margins only: not running bores)."""
    spec, kit, hook = shipped
    m = hook(spec, kit, Result(), 0.127)
    wider = replace(kit, params=replace(kit.params, pin_clearance=kit.params.pin_clearance + 0.1))
    m2 = hook(spec, wider, Result(), 0.127)
    slope = hole_slope(m)
    assert np.allclose((m2.nominal - m.nominal) / 0.1, slope, atol=1e-9)
    assert np.array_equal(m2.coeff, m.coeff)  # the clearance moves the nominal only: the slope is exact
    by = {}
    for x, s in zip(m.margins, slope):
        by.setdefault("fit" if x.what == "radial gap" else "loop" if x.unit.endswith("loop") else x.group, set()).add(
            round(float(s), 9))
    assert by == {"fit": {0.5}, "loop": {4.0}, "balance": {0.0}}
    pockets = [i for i, f in enumerate(m.features) if f.kind == "hole" and "pocket" in f.name]
    assert len(pockets) == 3 and np.count_nonzero(m.coeff[pockets]) > 0  # in the model, but not moved by the pins
    assert play_weight(m, slope) == pytest.approx(0.5 * sum(x.what == "radial gap" for x in m.margins))


@pytest.fixture(scope="module")
def auto_kit(kit_of, tmp_path_factory):
    """The shipped kit's own design.yaml (its layout pinned: no layout search, the same kit) with
    ``pin.clearance_diametral_mm: auto``, built by ``partgen build`` (nothing remembered: the search
    itself); then the kit rebuilt from the design.yaml that build pinned."""
    src = kit_of("bennett_butterfly").dest
    d = tmp_path_factory.mktemp("bennett_auto")
    data = yaml.safe_load((src / "design.yaml").read_text())
    data["pin"]["clearance_diametral_mm"] = "auto"
    (d / "design.yaml").write_text(yaml.safe_dump(data, sort_keys=False))
    shutil.copy(src / "printer.yaml", d / "printer.yaml")
    out = io.StringIO()
    with pytest.MonkeyPatch.context() as mp, contextlib.redirect_stdout(out):
        mp.setenv("PARTGEN_CACHE", "0")
        rc = main(["build", str(d / "design.yaml"), "-o", str(d / "kit")])
    loaded = pipeline.load(d / "design.yaml")  # the allocation build chose (this process's, no search)
    again = pipeline.build(d / "kit" / "design.yaml", d / "again")
    return rc, out.getvalue(), loaded, d / "kit", again


def _jams(model, shift: np.ndarray, n: int) -> int:
    """Jams of the linear study (seed 0, chunk 0: the prints auto chooses on) of ``model`` with every
    margin moved by ``shift``."""
    return summarise(model, run_chunk(replace(model, nominal=model.nominal + shift), 0, 0, n))["overall"]["jams"]


def test_auto_pin_clearance_is_the_least_that_meets_the_target(shipped, auto_kit):
    rc, text, loaded, _, again = auto_kit
    spec, kit, hook = shipped
    a = loaded.auto
    c, target, n = a["values"][KEY], a["target"], a["samples"]
    assert rc == 0 and a["reached"] and target == loaded.raw.design.tolerance.max_jam_probability == 0.01
    assert round(c / STEP, 9) == round(c / STEP) and STEP < c < START  # on the grid, inside it
    assert loaded.raw.design.pin.clearance_diametral_mm == c == loaded.spec.pin_clearance
    # the model auto searched on: the kit at the start value with the same layout (the shipped kit)
    assert kit.params.pin_clearance == START and again.kit.layout.layer == kit.layout.layer
    assert {j: s for j, s in again.kit.layout.shift.items() if s} == {j: s for j, s in kit.layout.shift.items() if s}
    m = hook(spec, kit, Result(), kit.printer.xy_accuracy)
    slope, allowed = hole_slope(m), math.floor(target * n + 1e-9)
    jams = _jams(m, (c - START) * slope, n)
    assert jams == a["jams"] <= allowed  # meets it, as reported
    assert _jams(m, (c - STEP - START) * slope, n) > allowed  # one step less misses it
    # the kit built with the number: its own model is the start model moved by the slope (the fits and
    # loops exactly; the balance is re-sized for the lighter links, at its own worst poses), and its own
    # study meets the target
    own = hook(again.loaded.spec, again.kit, Result(), kit.printer.xy_accuracy)
    joint, joint_own = ([x.group == "joint" for x in mm.margins] for mm in (m, own))
    assert [(x.unit, x.what) for x, j in zip(own.margins, joint_own) if j] == \
        [(x.unit, x.what) for x, j in zip(m.margins, joint) if j]
    assert np.allclose(own.nominal[joint_own], (m.nominal + (c - START) * slope)[joint], atol=1e-9)
    assert _jams(own, 0.0, n) <= allowed
    # build says so: the value, the fits it sets, the P(jam) it reaches and the target
    assert f"auto play: {KEY} = {c:g} mm (each of {a['joints']} running fits)" in text, text
    assert f"P(jam) {100 * a['probability']:.2f} %" in text and "target 1 %" in text
    assert a["joints"] == sum(x.what == "radial gap" for x in m.margins)


def test_an_auto_kit_rebuilds_from_its_pinned_design(auto_kit):
    """The kit's design.yaml carries the number (no search when it is built again) and builds the
    same kit, file for file."""
    _, _, loaded, first, again = auto_kit
    c = loaded.auto["values"][KEY]
    assert yaml.safe_load((first / "design.yaml").read_text())["pin"]["clearance_diametral_mm"] == c
    assert again.loaded.auto is None and again.loaded.spec == loaded.spec
    files = sorted(p.name for p in first.iterdir() if p.suffix in (".stl", ".glb", ".yaml"))
    assert sum(f.endswith(".stl") for f in files) == 13 and files == sorted(p.name for p in again.dest.iterdir() if p.suffix in (".stl", ".glb", ".yaml"))
    for name in files:
        assert (first / name).read_bytes() == (again.dest / name).read_bytes(), name
    m1, m2 = (json.loads((p / "manifest.json").read_text()) for p in (first, again.dest))
    assert m1["parts"] == m2["parts"] and m1["design"] == m2["design"]


@pytest.mark.parametrize("value", ["autox", "-0.1", "nan", "Auto"])
def test_a_bad_pin_clearance_exits_2_naming_the_key(tmp_path, capsys, value):
    dest = tmp_path / "kit"
    assert main(["build", "configs/bennett_butterfly.yaml", "-o", str(dest), "-q", "--set", f"{KEY}={value}"]) == 2
    err = capsys.readouterr().err
    assert KEY in err and "Traceback" not in err, err
    assert not dest.exists()
