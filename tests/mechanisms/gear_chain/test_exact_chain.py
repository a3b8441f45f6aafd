"""The gear chain's exact Monte Carlo (`tolerance --exact N`) against its linear model on the default
chain at ±0.2 mm, where it jams at its meshes (~24 % seated, ~54 % centred, linear).

Cheap: 20 prints each way (~0.2 s a print), in-process, one built and checked kit."""

import numpy as np
import pytest

from partgen import pipeline
from partgen.design.tolerance import run_chunk, summarise, wilson
from partgen.mechanisms.gear_chain.exact import ANGLES, _mesh_jams, exact_print, exact_shared

CONFIG = "configs/butterfly.yaml"
ACC = 0.2
N = 20


@pytest.fixture(scope="module")
def chain():
    """The default chain with its backlash given as the number auto chooses for it on the Fortus
    (0.1 mm: the same spec and kit, bit for bit), so the fixture does not run auto play's search
    (tests/studies/test_autoplay.py's subject)."""
    loaded = pipeline.load(CONFIG, over=pipeline.overrides(["gears.backlash_per_gear_mm=0.1"]))
    kit = pipeline.make_kit(loaded)
    result = loaded.mechanism.check(loaded.spec, kit, 24, None)
    return loaded, kit, result


def _overlap(a, b):
    return a[0] <= b[1] and b[0] <= a[1]


def test_exact_agrees_with_linear_and_seating_only_frees(chain):
    """Seated and centred, the exact prints' 95 % interval overlaps the linear one; the same prints
    centred jam whenever they jam seated (the seat only opens the meshes), and more of them do."""
    loaded, kit, result = chain
    jams = {}
    for seated in (True, False):
        m = loaded.mechanism.tolerance_model(loaded.spec, kit, result, ACC, seated=seated)
        lin = summarise(m, run_chunk(m, 0, 0, 20_000))["overall"]
        shared = exact_shared(kit, result, m, seated)
        assert len(shared["meshes"]) == len(result.figures["meshes"])  # every mesh decided exactly
        assert all(g != "mesh" for g in shared["groups"])  # and none by its linear margins
        rows = [exact_print(shared, 0, i) for i in range(N)]
        jams[seated] = {r["index"] for r in rows if r["jam"]}
        assert _overlap(wilson(len(jams[seated]), N), lin["ci95"]), (seated, len(jams[seated]), lin)
        # print by print: the linear verdict on the very deviations each exact print drew (its first
        # draws are the model's features, in order) is the exact one but for a borderline print or two
        paired = set()
        for i in range(N):
            rng = np.random.default_rng(np.random.SeedSequence(0, spawn_key=(1, i)))
            z = rng.standard_normal(len(m.features)) * m.sigma
            if ((m.nominal + z @ m.coeff) < 0).any():
                paired.add(i)
        assert len(paired ^ jams[seated]) <= 2, (seated, sorted(paired), sorted(jams[seated]))
    assert jams[True] <= jams[False] and len(jams[False]) > len(jams[True])


def test_a_perfect_printer_never_jams_exactly(chain):
    loaded, kit, result = chain
    m = loaded.mechanism.tolerance_model(loaded.spec, kit, result, 0.0)
    shared = exact_shared(kit, result, m, seated=False)
    assert not any(exact_print(shared, 0, i)["jam"] for i in range(2))


def test_fat_teeth_and_a_near_pin_bind_exactly(chain):
    """The exact search sees tooth overlap: D1/M1 binds when both its gears come out 0.6 mm fat
    (diametral; the nominal mesh has ~0.2 mm of backlash) or when B1's idler pin prints 0.3 mm
    nearer its proximal hole, and runs free with no deviation."""
    loaded, kit, result = chain
    m = loaded.mechanism.tolerance_model(loaded.spec, kit, result, 0.0)
    shared = exact_shared(kit, result, m, seated=False)
    mesh = next(x for x in shared["meshes"] if x["pair"] == ("D1", "M1"))
    zero = {f.name: 0.0 for f in m.features}
    assert not _mesh_jams(mesh, zero, ANGLES)
    assert _mesh_jams(mesh, {**zero, "D1 teeth": 0.6, "M1 teeth": 0.6}, ANGLES)
    u = mesh["vec"] / np.linalg.norm(mesh["vec"])
    near = {**zero, "B1 idler pin x": -0.3 * u[0], "B1 idler pin y": -0.3 * u[1]}
    assert _mesh_jams(mesh, near, ANGLES)
    assert not _mesh_jams(mesh, {**zero, "B1 idler pin x": 0.3 * u[0], "B1 idler pin y": 0.3 * u[1]}, ANGLES)
