"""The Bennett layout's capsule sweep, as the search and the check use it (batched, pruned by bounding
spheres, remembered per part state), against brute force: every capsule pair of every pair of parts
measured, features at a shared joint left out."""

import itertools

import numpy as np
import pytest

from partgen.mechanisms.bennett_butterfly import kit as A
from partgen.mechanisms.bennett_butterfly import layout as L
from partgen.mechanisms.bennett_butterfly.resolve import resolve_bennett
from partgen.mechanisms import load_design
from partgen.geometry.capsules import capsule_clearance

P = resolve_bennett(load_design("tests/designs/bennett_fixed.yaml"))
BODIES = A.bbf.body_joints(P.bb)


def brute(caps, a, b):
    ca, cb = caps[a], caps[b]
    shared = L._shared(a, b)
    keep = np.array([[not (set(ta[1:]) & set(tb[1:]) & shared) for tb in cb.tags] for ta in ca.tags])
    if not keep.any():
        return None
    return float(np.where(keep[None], capsule_clearance(ca.ends, ca.radii, cb.ends, cb.radii), np.inf).min())


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_sweep_is_brute_force_under_its_threshold(seed):
    rng = np.random.default_rng(seed)
    lay = A.Layout({A.BASE: 0, **{i: int(rng.integers(1, 7)) for i in range(1, 13)}},
                   {j: float(rng.choice([-20, -10, 0, 10, 20])) for j in A.bbf.JOINTS})
    angles = np.linspace(*P.workspace, 6)
    sweep = L.Sweep(P, angles, BODIES, below=8.0)
    got = sweep.all(lay)
    caps = sweep.capsules(lay)
    least = min(v for v, _ in got.values())
    for a, b in itertools.combinations(range(13), 2):
        want = brute(caps, a, b)
        if want is None:
            assert (a, b) not in got
        elif want < 8.0:
            assert got[(a, b)][0] == pytest.approx(want, abs=1e-9), (a, b)
        else:
            assert 8.0 - 1e-9 <= got[(a, b)][0] <= want + 1e-9, (a, b)
    assert least == pytest.approx(min(x for a, b in itertools.combinations(range(13), 2)
                                      if (x := brute(caps, a, b)) is not None), abs=1e-9)
    # a trial that moves one stack is measured again only where it changed, to the same result
    trial = A.Layout(lay.layer, {**lay.shift, "B2": lay.shift["B2"] + 10.0})
    again = sweep.all(trial)
    fresh = L.Sweep(P, angles, BODIES, below=8.0).all(trial)
    assert again.keys() == fresh.keys()
    assert all(again[k][0] == pytest.approx(fresh[k][0], abs=1e-9) and again[k][1] == fresh[k][1] for k in again)
    # the per-angle profile's least is the pairs' least
    assert sweep.profile(lay).min() == pytest.approx(min(least, 8.0), abs=1e-9)
