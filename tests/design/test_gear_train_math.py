"""design/gear_train.py against first principles: ratios by brute force over whole teeth, profile
shifts against the working-pressure-angle relation solved independently, mesh phases on the
generated outlines (a phase that meshes overlaps 0; half a pitch off, it overlaps)."""

import math
from fractions import Fraction

import numpy as np
import pytest
from shapely import affinity
from shapely.geometry import Polygon

from partgen.design import involute
from partgen.design.gear_train import (StageTarget, TeethLimits, mesh_phase, shaft_speeds, shifts_for_centre_distance,
                                       solve_train, teeth_for_ratio, train_ratio)
from partgen.errors import DesignError

A20 = math.radians(20.0)


@pytest.mark.parametrize("ratio", [3.7, 2.5, 1.0, 4.31, 0.37])
def test_ratio_is_the_best_whole_teeth_can_do(ratio):
    lim = TeethLimits(12, 60)
    z1, z2 = teeth_for_ratio(ratio, lim)
    best = min(abs(b / a - ratio) for a in range(12, 61) for b in range(12, 61))
    assert abs(z2 / z1 - ratio) == pytest.approx(best, abs=1e-12)


def test_a_ratio_out_of_reach_is_refused_with_the_reach():
    with pytest.raises(DesignError) as e:
        teeth_for_ratio(7.77, TeethLimits(12, 60), key="train.stages[1].ratio")
    assert e.value.key_path == "train.stages[1].ratio" and "at most 5.000" in e.value.problem


def test_exact_ratio_or_the_nearest_named():
    assert teeth_for_ratio(2.5, TeethLimits(12, 80), exact=True) == (12, 30)
    with pytest.raises(DesignError) as e:
        teeth_for_ratio(3.14159, TeethLimits(12, 40), exact=True, key="train.stages[0].ratio")
    assert e.value.key_path == "train.stages[0].ratio" and "nearest" in e.value.problem


def test_overall_ratio_split_over_two_stages():
    lim = TeethLimits(12, 80)
    st = solve_train([StageTarget(), StageTarget()], lim, 1.5, A20, overall=12.0, overall_exact=True)
    assert train_ratio(st) == 12
    st = solve_train([StageTarget(), StageTarget()], lim, 1.5, A20, overall=13.7)
    assert abs(float(train_ratio(st)) - 13.7) / 13.7 < 2e-4
    # each stage near the even split √13.7 = 3.70
    assert all(2.5 < float(s.ratio) < 5.5 for s in st)
    with pytest.raises(DesignError) as e:
        solve_train([StageTarget()], TeethLimits(12, 30), 1.5, A20, overall=9.0)
    assert e.value.key_path == "train.ratio"


def _aw_by_bisection(y: float) -> float:
    lo, hi = 1e-6, 1.5
    for _ in range(200):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if math.tan(mid) - mid < y else (lo, mid)
    return lo


@pytest.mark.parametrize("z1,z2,m,a", [(17, 31, 2.0, 49.0), (12, 40, 1.5, 40.0), (20, 20, 1.0, 19.6), (13, 45, 2.0, 60.0)])
def test_shifts_meet_the_centre_distance(z1, z2, m, a):
    x1, x2 = shifts_for_centre_distance(z1, z2, m, A20, a)
    aw = _aw_by_bisection(math.tan(A20) - A20 + 2 * math.tan(A20) * (x1 + x2) / (z1 + z2))
    assert m * (z1 + z2) / 2 * math.cos(A20) / math.cos(aw) == pytest.approx(a, abs=1e-9)
    # unthinned, they mesh there without backlash
    assert involute.circumferential_backlash(z1, z2, m, A20, x1, x2, 0, 0, a) == pytest.approx(0, abs=1e-9)
    assert x1 >= involute.min_profile_shift(z1, A20) - 1e-12 or x2 >= involute.min_profile_shift(z2, A20) - 1e-12


def test_centre_distance_out_of_reach_names_the_range():
    with pytest.raises(DesignError) as e:
        solve_train([StageTarget(teeth=(17, 31), centre_distance=60.0)], TeethLimits(12, 80), 2.0, A20)
    assert e.value.key_path == "train.stages[0].centre_distance_mm" and "from" in e.value.problem


def test_idler_and_speeds():
    st = solve_train([StageTarget(teeth=(20, 30)), StageTarget(teeth=(30, 40), idler=True)], TeethLimits(12, 80), 1, A20)
    assert train_ratio(st) == Fraction(2)
    assert shaft_speeds(st) == [1, Fraction(-2, 3), Fraction(1, 2)]
    with pytest.raises(DesignError) as e:
        solve_train([StageTarget(teeth=(20, 30)), StageTarget(teeth=(25, 40), idler=True)], TeethLimits(12, 80), 1, A20)
    assert e.value.key_path == "train.stages[1].teeth[0]"


@pytest.mark.parametrize("z1,z2,psi,beta", [(17, 31, 0.3, 0.0), (12, 40, -1.1, 1.2), (25, 18, 2.0, -2.5)])
def test_mesh_phase_puts_a_tooth_in_a_space(z1, z2, psi, beta):
    m = 2.0
    o1 = involute.gear_outline(z1, m, A20, involute.auto_profile_shift(z1, A20), 0.1, tol=0.01)
    o2 = involute.gear_outline(z2, m, A20, involute.auto_profile_shift(z2, A20), 0.1, tol=0.01)
    a = involute.centre_distance(z1, z2, m, A20, o1.x, o2.x)
    c2 = (a * math.cos(beta), a * math.sin(beta))
    p1 = affinity.rotate(Polygon(o1.points), psi, origin=(0, 0), use_radians=True)

    def overlap(phi):
        return p1.intersection(affinity.translate(affinity.rotate(Polygon(o2.points), phi, origin=(0, 0),
                                                                   use_radians=True), *c2)).area
    phi = mesh_phase(psi, z1, z2, beta)
    assert overlap(phi) == 0.0
    assert overlap(phi + math.pi / z2) > 0.5  # half a pitch off: tooth on tooth
    # rolling keeps the mesh
    for d in np.linspace(0, 2 * math.pi / z1, 5):
        p1 = affinity.rotate(Polygon(o1.points), psi + d, origin=(0, 0), use_radians=True)
        assert overlap(phi - d * z1 / z2) == 0.0
