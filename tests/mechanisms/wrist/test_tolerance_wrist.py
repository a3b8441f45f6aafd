"""The wrist's tolerance model: each dome tooth in its socket over the workspace (docs/tolerance.md
"Wrist"). Runs with tests/mechanisms/wrist/test_wrist.py (its session kits, ``conftest.SHARED``)."""

from dataclasses import replace

import numpy as np

from partgen.core.findings import Result
from partgen.core.protocol import tolerance_hook
from partgen.design.tolerance import run_chunk, summarise
from partgen.mechanisms.wrist.tolerance import DIRECTIONS


def jam(model, n: int = 4000) -> float:
    return summarise(model, run_chunk(model, 0, 0, n))["overall"]["probability"]


def clear(kit, clearance=None) -> tuple:
    """The kit (with another clearance: its spec's, as the model reads it) and a check result that found
    the sockets clear."""
    r = Result()
    r.figures["max_overlap_mm3"] = 0.0
    return (kit if clearance is None else replace(kit, spec=replace(kit.spec, clearance=clearance))), r


def test_wrist_model_from_its_check(kit_of):
    b = kit_of("wrist_sphere")
    mech = b.loaded.mechanism
    result = mech.check(b.loaded.spec, b.kit, 8, None)
    assert result.figures["max_overlap_mm3"] == 0.0
    m = tolerance_hook(mech)(b.loaded.spec, b.kit, result, 0.127)
    assert len(m.units) == len(b.kit.domes) == 19 and len(m.margins) == 19 * (DIRECTIONS + 1)
    assert np.allclose(m.nominal, b.loaded.spec.clearance)
    p = jam(m)
    assert 0.0 < p < 0.5
    # a dome's side gap falls by as much as the dome moves towards that side, and by half its growth
    k = next(i for i, x in enumerate(m.margins) if x.unit == "dome 3" and x.what == "side gap 0°")
    col = {f.name: m.coeff[i, k] for i, f in enumerate(m.features) if m.coeff[i, k]}
    assert col == {"gear1 domes": -0.5, "gear2 sockets": 0.5, "gear1 dome 3 u": -1.0, "gear2 socket 3 u": 1.0}
    seated, centred = m, tolerance_hook(mech)(b.loaded.spec, b.kit, result, 0.127, seated=False)
    assert np.array_equal(seated.nominal, centred.nominal)  # no bores: the worst case is the headline


def test_more_clearance_fewer_jams_and_an_overlap_jams(kit_of):
    b = kit_of("wrist_sphere")
    hook = tolerance_hook(b.loaded.mechanism)
    p = [jam(hook(b.loaded.spec, *clear(b.kit, c), 0.127)) for c in (0.10, 0.15, 0.25)]
    assert p[0] > p[1] > p[2], p
    assert jam(hook(b.loaded.spec, *clear(b.kit), 0.3)) > p[1]  # a worse printer jams more
    r = Result()
    r.figures["max_overlap_mm3"] = 0.5  # the nominal check found the sockets too tight
    assert jam(hook(b.loaded.spec, b.kit, r, 0.127)) > 0.99
