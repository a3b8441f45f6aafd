"""The crossed helical pair's tolerance model (kind crossed_helical: the crossed pair and the worm
drive): its centre-distance coefficient against the exact 3-D contact of the printed solids with
gear 2's axis moved out, the seat credits both bores, and more play means fewer jams."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from partgen.design.tolerance import run_chunk, summarise
from partgen.mechanisms.crossed_helical.contact import contact_angles
from partgen.mechanisms.crossed_helical.kit import CrossedKit
from partgen.mechanisms.crossed_helical.mechanism import MECHANISM
from partgen.mechanisms.crossed_helical.resolve import CrossedSpec
from partgen.mechanisms.crossed_helical.tolerance import per_backlash

SHIFT_MM = 0.05


class _Moved(CrossedSpec):
    """The spec with gear 2's axis ``SHIFT_MM`` farther from gear 1's (the poses read centre_distance)."""

    @property
    def centre_distance(self) -> float:
        return self.pair.centre_distance + SHIFT_MM


def _exact_backlash(kit) -> float:
    c = contact_angles(kit, [0.0], 1e-6)
    return float(c["ahead"][0] - c["behind"][0]) * kit.spec.pair.pitch_radius(1)


@pytest.fixture(scope="module", params=["gear_train_crossed_helical", "gear_train_worm"])
def pair(request, kit_of):
    built = kit_of(request.param)
    spec, kit = built.loaded.spec, built.kit
    return spec, kit, MECHANISM.check(spec, kit, 2)


def _coeff(model, what: str, feature: str) -> float:
    k = next(i for i, m in enumerate(model.margins) if m.what == what)
    f = next(i for i, x in enumerate(model.features) if x.name == feature)
    return float(model.coeff[f, k])


def test_centre_distance_coefficient_is_the_exact_geometry(pair):
    """Gear 2's axis 0.05 mm farther out opens the exact backlash (along gear 2's pitch circle) by what
    the model's coefficient of gear 2's axis says: 2 tan α_n / cos β_2 per mm (45°: 1.03; the worm's
    wheel at 5°: 0.73)."""
    spec, kit, result = pair
    model = MECHANISM.tolerance_model(spec, kit, result, 0.1, seated=False)
    per_mm = 2 * _coeff(model, "backlash", "base block1 hole x")  # the pin: the mean of its two holes
    assert per_mm == pytest.approx(-_coeff(model, "backlash", "base post x"))
    moved = CrossedKit(_Moved(**{f.name: getattr(spec, f.name) for f in dataclasses.fields(spec)}), kit.parts)
    opened = _exact_backlash(moved) - _exact_backlash(kit)
    assert opened == pytest.approx(per_mm * SHIFT_MM, rel=0.05), (opened, per_mm * SHIFT_MM)
    # the backlash the design thins both gears for, on gear 2's pitch circle, is the check's
    assert per_backlash(kit) * spec.gear1.system.backlash_per_gear == pytest.approx(
        result.figures["backlash_mm"]["designed"])


def test_seated_credits_both_bores_and_play_buys_fewer_jams(pair):
    spec, kit, result = pair
    seated = MECHANISM.tolerance_model(spec, kit, result, 0.3)
    worst = MECHANISM.tolerance_model(spec, kit, result, 0.3, seated=False)
    lash = next(i for i, m in enumerate(seated.margins) if m.what == "backlash")
    slope = 2 * math.tan(spec.pair.normal_pressure_angle) / math.cos(spec.pair.helix[1])
    # each gear has one mesh: it takes up both bores' radial play (κ = 1 each)
    assert seated.nominal[lash] - worst.nominal[lash] == pytest.approx(slope * sum(m.nominal for m in seated.margins if m.group == "joint"))
    assert {m.unit for m in seated.margins} >= {"gear1 on the post", "gear2 on pin2", "gear1/gear2"}

    def p(model):
        return summarise(model, run_chunk(model, 0, 0, 4000))["overall"]["probability"]
    assert p(seated) < p(worst)
    # less backlash (the mesh's margins moved by per_backlash), more jams: the margin can fail
    tighter = dataclasses.replace(worst, nominal=worst.nominal - 0.08 * np.array([m.per_backlash for m in worst.margins]))
    assert p(tighter) > p(worst)


def test_each_model_says_what_it_credits(pair):
    """The result line names what the model credits: the crossed pair both bores, the worst case
    centred; a model that credits nothing (the wrist's, the Bennett's) prints no separate worst case."""
    from partgen.cli.tolerance import text

    spec, kit, result = pair
    seated = MECHANISM.tolerance_model(spec, kit, result, 0.3)
    worst = MECHANISM.tolerance_model(spec, kit, result, 0.3, seated=False)
    assert "seated" in seated.credits and "centred" in worst.credits

    def study(model, worst_model):
        r = summarise(model, run_chunk(model, 0, 0, 100))
        return {**r, "design": "x", "accuracy_source": "test", "seat": model.credits, "chunks": 1, "workers": 1,
                "resumed_chunks": 0, "worst_case": {"seat": worst_model.credits, **r["overall"]},
                "seconds": {"samples": 0.0, "nominal_check": 0.0, "cluster_wait": 0.0}}
    lines = text(study(seated, worst)).splitlines()
    assert seated.credits in lines[1] and lines[2].startswith(f"worst case, {worst.credits}")
    nothing = dataclasses.replace(seated, credits="no gear runs in a bore")
    lines = text(study(nothing, nothing)).splitlines()
    assert "no gear runs in a bore" in lines[1] and not any(x.startswith("worst case") for x in lines)
