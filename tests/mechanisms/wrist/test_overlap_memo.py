"""The wrist check's remembered overlaps (``checks._overlap``): the same two solids at the same poses
give ``geometry.measure.intersection``'s own figures without a second boolean; another solid, or a
pose one ulp away, is measured anew; the memo keeps only its last pairs (two cubes: milliseconds)."""

import manifold3d as m3d
import numpy as np
import pytest

from partgen.geometry import measure
from partgen.mechanisms.wrist import checks


@pytest.fixture
def counted(monkeypatch):
    """The booleans the memo runs: a list of the pose pairs handed to ``intersection``, on an empty memo."""
    calls = []

    def counting(a, Ta, b, Tb):
        calls.append((Ta.copy(), Tb.copy()))
        return measure.intersection(a, Ta, b, Tb)
    monkeypatch.setattr(checks, "intersection", counting)
    monkeypatch.setattr(checks, "_OVERLAPS", type(checks._OVERLAPS)())
    return calls


def _moved(x: float) -> np.ndarray:
    T = np.eye(4)
    T[0, 3] = x
    return T


def test_a_pose_seen_again_is_not_measured_again(counted):
    a, b = m3d.Manifold.cube((2.0, 2.0, 2.0)), m3d.Manifold.cube((2.0, 2.0, 2.0))
    first = checks._overlap(a, np.eye(4), b, _moved(1.5))
    assert first[0] == pytest.approx(2.0) and len(counted) == 1  # a 0.5 × 2 × 2 slab
    again = checks._overlap(a, np.eye(4), b, _moved(1.5))
    assert len(counted) == 1
    want = measure.intersection(a, np.eye(4), b, _moved(1.5))
    assert again[0] == first[0] == want[0] and np.array_equal(again[1], want[1])
    again[1][:] = 0.0  # the caller's copy: the memo keeps its own
    assert np.array_equal(checks._overlap(a, np.eye(4), b, _moved(1.5))[1], want[1])
    assert checks._overlap(a, np.eye(4), b, _moved(3.0)) == (0.0, None)  # apart: no centre


def test_another_solid_or_a_pose_an_ulp_away_misses(counted):
    a, b = m3d.Manifold.cube((2.0, 2.0, 2.0)), m3d.Manifold.cube((2.0, 2.0, 2.0))
    checks._overlap(a, np.eye(4), b, _moved(1.5))
    checks._overlap(a, np.eye(4), b, _moved(np.nextafter(1.5, 2.0)))  # gear 2's pose, one ulp on
    nudged = np.eye(4)
    nudged[2, 3] = 5e-324
    checks._overlap(a, nudged, b, _moved(1.5))  # gear 1's pose
    c = m3d.Manifold.cube((2.0, 2.0, 3.0))
    vol = checks._overlap(a, np.eye(4), c, _moved(1.5))[0]  # another solid in the same place
    assert vol == pytest.approx(2.0) and len(counted) == 4
    assert checks._overlap(c, np.eye(4), b, _moved(1.5))[0] == pytest.approx(2.0) and len(counted) == 5  # order


def test_the_memo_keeps_its_last_pairs_only(counted, monkeypatch):
    monkeypatch.setattr(checks, "_MEMO_PAIRS", 2)
    cubes = [m3d.Manifold.cube((2.0, 2.0, 2.0)) for _ in range(4)]
    for c in cubes[1:]:
        checks._overlap(cubes[0], np.eye(4), c, _moved(1.0))
    assert len(checks._OVERLAPS) == 2 and len(counted) == 3
    checks._overlap(cubes[0], np.eye(4), cubes[3], _moved(1.0))  # the newest pair: remembered
    assert len(counted) == 3
    checks._overlap(cubes[0], np.eye(4), cubes[1], _moved(1.0))  # the oldest: forgotten, measured anew
    assert len(counted) == 4
    monkeypatch.setattr(checks, "_MEMO_POSES", 2)
    for x in (0.5, 1.5, 1.7):  # a pair's poses beyond the bound: its poses forgotten, the memo bounded
        checks._overlap(cubes[0], np.eye(4), cubes[2], _moved(x))
    assert all(len(e[2]) <= 2 for e in checks._OVERLAPS.values())
