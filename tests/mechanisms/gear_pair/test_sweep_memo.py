"""The spur pair's flank-play sweep: gear 2 placed in one pass exactly as shapely's rotate-then-
translate places it (bit for bit), and the in-memory memo of the last sweeps that `report` shares
between its check and its trace: a hit only for the very kit object, the same angles and the same
tolerance, bounded, and the caller's arrays its own."""

import dataclasses
import math

import numpy as np
import pytest
import shapely
from shapely import affinity

from partgen import pipeline
from partgen.mechanisms.gear_pair import checks
from helpers import ROOT


@pytest.fixture(scope="module")
def pair():
    loaded = pipeline.load(ROOT / "configs" / "gear_pair.yaml")
    return loaded.spec, pipeline.make_kit(loaded)


def test_gear2_is_placed_as_rotate_then_translate_bit_for_bit(pair):
    spec, kit = pair
    p2 = checks.outline(kit, "gear2")
    angles = [0.0, -0.0, 1e-17, -3e-16, math.pi / 2, math.pi, -math.pi, 3 * math.pi / 2, 0.1234567, -5.5,
              *np.random.default_rng(3).uniform(-8, 8, 12)]
    for a in angles:
        want = affinity.translate(affinity.rotate(p2, a, origin=(0, 0), use_radians=True), spec.centre_distance)
        got = checks._turned_and_moved(p2, a, spec.centre_distance)
        assert shapely.get_coordinates(got).tobytes() == shapely.get_coordinates(want).tobytes(), a
        assert shapely.equals_identical(got, want), a


def test_a_sweep_is_shared_only_by_the_same_kit_and_angles(pair, monkeypatch):
    spec, kit = pair
    calls = []
    real = checks.flank_play
    monkeypatch.setattr(checks, "flank_play", lambda k, t, *a: calls.append(len(t)) or real(k, t, *a))
    checks._SWEEPS.clear()
    thetas, first = checks.sweep(spec, kit, 4)
    assert calls == [4]
    first["ahead"][:] = 99.0  # the caller's own arrays: the memo keeps its copy
    again_thetas, again = checks.sweep(spec, kit, 4)
    assert calls == [4], "the same kit and angles swept again"
    fresh = real(kit, thetas)
    assert thetas.tobytes() == again_thetas.tobytes()
    assert all(again[k].tobytes() == fresh[k].tobytes() for k in fresh)
    checks.sweep(spec, kit, 5)  # other angles: a miss
    assert calls == [4, 5]
    twin = dataclasses.replace(kit)  # an equal kit, another object: a miss
    assert twin is not kit
    checks.sweep(spec, twin, 4)
    assert calls == [4, 5, 4]
    assert len(checks._SWEEPS) == checks._SWEEPS_KEPT == 2  # bounded: the oldest (kit, 4) went
    checks.sweep(spec, kit, 4)
    assert calls == [4, 5, 4, 4]
    checks._SWEEPS.clear()
