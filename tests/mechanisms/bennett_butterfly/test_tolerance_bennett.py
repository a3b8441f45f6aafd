"""The Bennett linkage's tolerance model: pins in their bores, the loops closing on the joints' play,
and the balance as printed (docs/tolerance.md "Bennett linkage"). Runs with tests/mechanisms/bennett_butterfly/test_bennett_cli.py
(the shipped kit, its costliest build, ``conftest.SHARED``)."""

import re
from dataclasses import replace

import numpy as np
import pytest

from partgen.core.findings import Result
from partgen.core.protocol import tolerance_hook
from partgen.design import bennett_butterfly as bbf
from partgen.design.tolerance import run_chunk, summarise
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
