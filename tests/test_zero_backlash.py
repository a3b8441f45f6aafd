"""A designed backlash of zero is met, not broken: the rule tolerates the arithmetic's ±1e-12 mm
at the centre distance as assembled, and still catches a centre distance a hundredth short."""

import math

from partgen.design import involute
from partgen.design.gearing import ToothSystem, centre_distance, make_gear
from partgen.design.rules import GearRules, mesh_breaches


def _pair(backlash):
    s = ToothSystem(module=1.7, pressure_angle=math.radians(19.2), backlash_per_gear=backlash, profile_shift=None)
    return make_gear(28, s), make_gear(29, s)


def test_zero_backlash_at_the_assembled_centre_distance_is_no_breach():
    g1, g2 = _pair(0.0)
    a = centre_distance(g1, g2)
    rules = GearRules(1.2, 0.381)
    for da in (0.0, 1e-12, -1e-12, 2e-11):  # poses composed in float64 place the axes this close
        j = involute.circumferential_backlash(28, 29, 1.7, math.radians(19.2), g1.profile_shift, g2.profile_shift,
                                              0.0, 0.0, a + da)
        assert abs(j) < 1e-9
        assert not [b for b in mesh_breaches(g1, g2, a + da, rules) if b.rule == "backlash"]
    short = [b for b in mesh_breaches(g1, g2, a - 0.01, rules) if b.rule == "backlash"]
    assert short and short[0].value < -1e-3
