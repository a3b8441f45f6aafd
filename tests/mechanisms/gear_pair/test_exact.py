"""The exact Monte Carlo (`tolerance --exact N`) against the linear one on the gear pair at ±0.3 mm.

Cheap: 40 prints each (~0.05 s a print), in-process."""

import pytest

from partgen import pipeline, studies
from partgen.design.tolerance import run_chunk, summarise, wilson
from partgen.mechanisms.gear_pair.exact import exact_print, exact_shared

CONFIG = "configs/gear_pair.yaml"
ACC = 0.3
N = 40


@pytest.fixture(scope="module")
def pair():
    loaded = pipeline.load(CONFIG)
    kit = pipeline.make_kit(loaded)
    result = loaded.mechanism.check(loaded.spec, kit, 24, None)
    return loaded, kit, result


def _linear(loaded, kit, result, seated):
    m = loaded.mechanism.tolerance_model(loaded.spec, kit, result, ACC, seated=seated)
    return m, summarise(m, run_chunk(m, 0, 0, 20_000))["overall"]


def _overlap(a, b):
    return a[0] <= b[1] and b[0] <= a[1]


def test_exact_agrees_with_linear_both_ways(pair):
    """Seated (the headline: ~1 %) and centred (the worst case: ~12 %): the exact prints' 95 %
    interval overlaps the linear one, and the centred prints jam more often than the seated."""
    loaded, kit, result = pair
    jams = {}
    for seated in (True, False):
        m, lin = _linear(loaded, kit, result, seated)
        shared = exact_shared(kit, result, m, seated)
        rows = [exact_print(shared, 0, i) for i in range(N)]
        k = sum(r["jam"] for r in rows)
        assert _overlap(wilson(k, N), lin["ci95"]), (seated, k, lin)
        jams[seated] = k
    assert jams[False] > jams[True]


def test_a_perfect_printer_never_jams_exactly(pair):
    loaded, kit, result = pair
    m = loaded.mechanism.tolerance_model(loaded.spec, kit, result, 0.0)
    shared = exact_shared(kit, result, m, seated=False)
    assert not any(exact_print(shared, 0, i)["jam"] for i in range(3))


def test_the_cli_study_reports_exact_beside_linear():
    r = studies.tolerance(CONFIG, 2000, ACC, workers=1, processes=False, write=False, exact=N).result
    ex = r["exact"]
    assert ex["prints"] == N and 0 <= ex["jams"] <= N and ex["agrees"] is True
    assert ex["ci95"] == list(wilson(ex["jams"], N))
    with pytest.raises(Exception, match="no exact Monte Carlo"):
        studies.tolerance("configs/wrist_sphere.yaml", 100, workers=1, processes=False, write=False, exact=5)
