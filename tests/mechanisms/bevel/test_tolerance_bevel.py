"""The straight bevel pair's tolerance model (kind bevel): its cone-geometry coefficients (gear 2 moved
off and into gear 1 along the pitch cones' common normal: heel and toe margins) against the exact 3-D
backlash the check measures with gear 2's solid moved so; the seat credits the bores and the axial
stops; less backlash means more jams."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from partgen.design.tolerance import run_chunk, summarise
from partgen.mechanisms.bevel.kit import BevelKit
from partgen.mechanisms.bevel.contact import contact_angles
from partgen.mechanisms.bevel.mechanism import MECHANISM
from partgen.mechanisms.bevel.tolerance import per_backlash, toe_ratio

SHIFT_MM = 0.05


@dataclasses.dataclass(frozen=True)
class _Moved(BevelKit):
    """The kit with gear 2's solid translated by ``move`` (world, mm) at every turn."""

    move: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def poses(self, theta: float = 0.0):
        P = dict(super().poses(theta))
        T = P["gear2"].copy()
        T[:3, 3] += np.asarray(self.move)
        P["gear2"] = T
        return P


def _exact_backlash(kit) -> float:
    c = contact_angles(kit, [0.0], 1e-6)
    return float(c["ahead"][0] - c["behind"][0]) * kit.spec.gear2.pitch_radius


@pytest.fixture(scope="module")
def pair(kit_of):
    built = kit_of("bevel_mitre")
    spec, kit = built.loaded.spec, built.kit
    return spec, kit, MECHANISM.check(spec, kit, 2), _exact_backlash(kit)


def _coeff(model, what: str, feature: str) -> float:
    k = next(i for i, m in enumerate(model.margins) if m.what == what)
    f = next(i for i, x in enumerate(model.features) if x.name == feature)
    return float(model.coeff[f, k])


def _moved(kit, move) -> float:
    return _exact_backlash(_Moved(kit.spec, kit.parts, tuple(float(x) for x in move)))


def test_cone_normal_coefficients_are_the_exact_geometry(pair):
    """Gear 2 moved 0.05 mm off gear 1 along the pitch cones' common normal n opens the exact backlash
    by 2 s tan α (the heel margin's coefficient per mm of s: gear 1's post moved the other way, over
    cos δ_1); moved 0.05 mm into it, closes it by that over k = (R − b)/R (the toe margin's: the
    same gap length is a larger angle at the toe). (A shift along the shaft also moves gear 2's apex
    off gear 1's along the pitch line, which costs backlash whichever way: not in the linear model,
    see docs/tolerance.md.)"""
    spec, kit, result, base = pair
    model = MECHANISM.tolerance_model(spec, kit, result, 0.1, seated=False)
    a, d1 = spec.pair.pressure_angle, spec.gear1.pitch_angle
    n = np.array([math.cos(d1), 0.0, math.sin(d1)])
    heel = -_coeff(model, "backlash (heel)", "base post x") / math.cos(d1)
    toe = -_coeff(model, "backlash (toe)", "base post x") / math.cos(d1)
    assert heel == pytest.approx(2 * math.tan(a))
    assert toe == pytest.approx(heel / toe_ratio(kit))
    opened = _moved(kit, SHIFT_MM * n) - base
    assert opened == pytest.approx(heel * SHIFT_MM, rel=0.05), (opened, heel * SHIFT_MM)
    closed = base - _moved(kit, -SHIFT_MM * n)
    assert closed == pytest.approx(toe * SHIFT_MM, rel=0.05), (closed, toe * SHIFT_MM)
    # the backlash the design thins both gears for, on gear 2's heel pitch circle, is the check's
    assert per_backlash(kit) * spec.gear1.backlash == pytest.approx(result.figures["backlash_mm"]["designed"])


def test_seated_credits_and_less_backlash_jams_more(pair):
    spec, kit, result, _ = pair
    seated = MECHANISM.tolerance_model(spec, kit, result, 0.3)
    worst = MECHANISM.tolerance_model(spec, kit, result, 0.3, seated=False)
    heel = next(i for i, m in enumerate(seated.margins) if m.what == "backlash (heel)")
    tan_a = math.tan(spec.pair.pressure_angle)
    d1, d2 = (g.pitch_angle for g in spec.pair.gears)
    gaps = [m.nominal for m in seated.margins if m.group == "joint"]
    # κ = 1: each bore's radial play, along the cone normal (cos δ_i), and each gear's axial gap (sin δ_i)
    credit = gaps[0] * math.cos(d1) + gaps[1] * math.cos(d2) + spec.gap * (math.sin(d1) + math.sin(d2))
    assert seated.nominal[heel] - worst.nominal[heel] == pytest.approx(2 * tan_a * credit)
    assert "seated" in seated.credits and "centred" in worst.credits

    def p(model):
        return summarise(model, run_chunk(model, 0, 0, 4000))["overall"]["probability"]
    assert p(seated) <= p(worst)
    assert 0.0 < p(worst) < 0.5
    # less backlash (the mesh's margins moved by per_backlash), more jams: the margin can fail
    tighter = dataclasses.replace(worst, nominal=worst.nominal - 0.04 * np.array([m.per_backlash for m in worst.margins]))
    assert p(tighter) > p(worst)
