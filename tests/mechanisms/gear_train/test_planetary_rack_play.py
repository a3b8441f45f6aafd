"""What play costs at the planetary set's carrier and at the rack (planetary/play.py, rack/play.py,
common/play.py): the model against the printed outlines turned until they touch (the bodies centred,
and each where the model says its bore's play costs most), how the lost motion moves with backlash
and running clearance (by the model's amounts), the worst case and 95 % figure, and where they show
(trace --json and its text, the report, sweep's trade-off)."""

import json
import math

import numpy as np
import pytest

from partgen import pipeline
from partgen.cli.main import main
from partgen.core.findings import Result
from partgen.export.studies import play_cost, tradeoff_rows
from partgen.mechanisms.gear_train.common.play import ARCMIN, Share, lost_motion as cost
from partgen.mechanisms.gear_train.planetary import play as pplay
from partgen.mechanisms.gear_train.planetary.motion import turn_planetary
from partgen.mechanisms.gear_train.rack import play as rplay
from partgen.mechanisms.gear_train.rack.motion import turn_rack


def _kit(name: str, *sets: str):
    loaded = pipeline.load(f"configs/{name}.yaml", over=pipeline.overrides(sets))
    return loaded.spec, pipeline.make_kit(loaded)


@pytest.fixture(scope="module")
def planetary():
    return _kit("gear_train_planetary")


@pytest.fixture(scope="module")
def rack():
    return _kit("gear_train_rack")


# --- the planetary set ------------------------------------------------------------------------------------

def test_planetary_model_agrees_with_the_printed_outlines(planetary):
    """Every body centred, the carrier turned on the printed outlines between its two contacts (the sun
    held): the model's backlash share. Every planet moved along its tangent by its pin's play, each way:
    the model's whole nominal lost motion (the radial direction costs nothing: it opens one mesh and closes
    the other)."""
    spec, kit = planetary
    lm = pplay.lost_motion(spec, kit)
    th = np.array([0.0, 0.37, 1.1])
    plain = turn_planetary(kit, th, tol=1e-6)
    measured = (plain["coast"] - plain["drive"]) * ARCMIN
    assert measured == pytest.approx(np.full(3, lm["backlash"]), rel=0.02)
    c = spec.running / 2
    fwd = turn_planetary(kit, th, tol=1e-6, planet_shift=(0.0, c))
    back = turn_planetary(kit, th, tol=1e-6, planet_shift=(0.0, -c))
    exact = (np.maximum(fwd["coast"], back["coast"]) - np.minimum(fwd["drive"], back["drive"])) * ARCMIN
    assert exact == pytest.approx(np.full(3, lm["total"]), rel=0.02)
    assert lm["bores"] == pytest.approx(2 * c / spec.centre_distance * ARCMIN, rel=1e-3)
    for r in (c, -c):  # a planet moved along the line of centres: the range stays within 2 %
        q = turn_planetary(kit, th[:2], tol=1e-6, planet_shift=(r, 0.0))
        assert (q["coast"] - q["drive"]) * ARCMIN == pytest.approx(measured[:2], rel=0.02)


def test_the_sun_floats_and_adds_no_lost_motion(planetary):
    """The sun moved off centre by its shaft's play: the carrier turns less, never more (the planets
    disagree), so a floating sun adds none — the model's 0 for the sun's and the carrier's bores."""
    spec, kit = planetary
    th = np.array([0.0, 0.6])
    plain = turn_planetary(kit, th, tol=1e-6)
    lash = plain["coast"] - plain["drive"]
    c = spec.running / 2
    for ang in (0.0, math.pi / 2, 2.0):
        q = turn_planetary(kit, th, tol=1e-6, sun_shift=(c * math.cos(ang), c * math.sin(ang)))
        assert (q["coast"] - q["drive"] <= lash * 1.005).all()
    rows = {r["share"]: r for r in pplay.lost_motion(spec, kit)["shares"]}
    assert rows["the sun's shaft in frame_bottom"]["at_output"] == 0.0
    assert rows["the carrier's shaft in frame_top"]["at_output"] == 0.0
    assert pplay.weights(spec.angles) == pytest.approx([1 / 3] * 3)
    assert pplay.weights([0.0, 0.5, 1.0]) is None  # within a half turn: no weights
    w = pplay.weights([0.0, 2.0, 4.0])
    assert w.sum() == pytest.approx(1.0) and abs((w * np.exp(1j * np.array([0.0, 2.0, 4.0]))).sum()) < 1e-6


def test_the_carrier_is_found_with_the_sun_held_in_the_world(planetary):
    """turn_planetary's carrier angle is self-consistent: the sun placed where a carrier at that angle
    puts it (in the carrier's frame), the ring then touches at the ring's fixed place."""
    spec, kit = planetary
    th = np.array([0.0, 0.37])
    o = turn_planetary(kit, th, tol=1e-6)
    lash = o["coast"] - o["drive"]
    for key in ("drive", "coast"):
        again = turn_planetary(kit, (th - o[key]) / (1 - 1 / spec.ratio), tol=1e-6)
        assert (np.abs(spec.ring_phase - again[f"ring_{key}"] - o[key]) < 0.01 * lash).all()


def test_planetary_lost_motion_moves_with_backlash_and_clearance(planetary):
    spec, kit = planetary
    base = pplay.lost_motion(spec, kit)
    a = spec.centre_distance
    lash = pplay.lost_motion(*_kit("gear_train_planetary", "gears.backlash_per_gear_mm=0.25"))
    # each mesh's backlash grows by 2 × 0.1 mm: both over 2a
    assert lash["backlash"] - base["backlash"] == pytest.approx(2 * 2 * 0.1 / (2 * a) * ARCMIN, rel=1e-3)
    assert lash["bores"] == pytest.approx(base["bores"])
    loose = pplay.lost_motion(*_kit("gear_train_planetary", "shafts.running_clearance_diametral_mm=0.5"))
    # each pin's radial play grows by 0.1 mm: twice it over a
    assert loose["bores"] - base["bores"] == pytest.approx(2 * 0.1 / a * ARCMIN, rel=1e-3)
    assert loose["backlash"] == pytest.approx(base["backlash"])
    for lm in (base, lash, loose):
        assert lm["worst_case"] >= lm["p95"] >= lm["total"] > 0 and lm["p95"] > lm["p50"] > 0.9 * lm["total"]


# --- the rack ---------------------------------------------------------------------------------------------

def test_rack_model_agrees_with_the_printed_outlines(rack):
    """The rack slid between its contacts on the printed outlines: the mesh's backlash with every body
    centred; with the pinion's centre at ± c (cos α, sin α) in its bore and the rack backed off to its
    rail, the model's whole nominal lost motion."""
    spec, kit = rack
    lm = rplay.lost_motion(spec, kit)
    th = np.linspace(*spec.thetas_range, 5)
    plain = turn_rack(kit, th)
    assert plain["coast"] - plain["drive"] == pytest.approx(np.full(5, lm["backlash"]), rel=0.05)
    al, c = spec.system.pressure_angle, spec.running / 2
    fwd = turn_rack(kit, th, pinion_at=(c * math.cos(al), c * math.sin(al)), rack_dy=-c)
    back = turn_rack(kit, th, pinion_at=(-c * math.cos(al), c * math.sin(al)), rack_dy=-c)
    assert fwd["coast"] - back["drive"] == pytest.approx(np.full(5, lm["total"]), rel=0.02)
    # no other place in the bore moves the rack further (the model's direction is the worst)
    for ang in np.linspace(0, 2 * math.pi, 8, endpoint=False):
        q = turn_rack(kit, th[:1], pinion_at=(c * math.cos(ang), c * math.sin(ang)), rack_dy=-c)
        assert q["coast"][0] <= fwd["coast"][0] + 1e-3


def test_rack_lost_motion_moves_with_backlash_and_clearance(rack):
    spec, kit = rack
    al = spec.system.pressure_angle
    base = rplay.lost_motion(spec, kit)
    lash = rplay.lost_motion(*_kit("gear_train_rack", "gears.backlash_per_gear_mm=0.2"))
    assert lash["total"] - base["total"] == pytest.approx(0.2, abs=1e-4)  # 2 × 0.1 mm of thinning
    loose = rplay.lost_motion(*_kit("gear_train_rack", "shafts.running_clearance_diametral_mm=0.5"))
    # the shaft's radial play and the rail's gap each grow by 0.1 mm
    assert loose["bores"] - base["bores"] == pytest.approx(0.1 * (2 / math.cos(al) + 2 * math.tan(al)), abs=1e-4)
    assert base["pinion_arcmin"]["total"] == pytest.approx(base["total"] / spec.pinion.pitch_radius * ARCMIN, rel=1e-3)


def test_the_worst_case_is_the_stack_the_model_says(rack):
    """Every feature at ± A the way that adds play, by hand: both outlines (1/cos α each), the shaft's
    bore and diameter (half each, 2/cos α), the rail's face and the shaft hole's y (2 tan α, A/√2 each
    as coordinates), the rack's back (half its outline, 2 tan α)."""
    spec, kit = rack
    lm = rplay.lost_motion(spec, kit)
    A, al = spec.printer.xy_accuracy, spec.system.pressure_angle
    want = lm["total"] + 2 * A / math.cos(al) + 2 * A / math.cos(al) + 2 * math.tan(al) * (2 * A / math.sqrt(2) + A / 2)
    assert lm["worst_case"] == pytest.approx(want, abs=2e-4)
    assert lm["worst_case"] > lm["p95"] > lm["total"] > 0
    # a perfect printer: every print nominal
    flat = cost(rplay.shares(kit), 0.0, "mm")
    assert flat["worst_case"] == flat["p95"] == flat["total"] == pytest.approx(lm["total"], abs=1e-4)
    # a share that a print can drive below zero is never credited negative
    neg = cost([Share("x", "x", "bores", 0.0, 1.0, {("x hole", "hole", "x"): 0.5})], 0.3, "mm")
    assert neg["total"] == 0.0 and 0 <= neg["p50"] < neg["p95"] < neg["worst_case"] == pytest.approx(0.15)


# --- where they show ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("name, key, unit", [("gear_train_planetary", "lost_motion_arcmin", "arcmin"),
                                             ("gear_train_rack", "lost_motion_mm", "mm")])
def test_trace_json_text_and_report_say_what_play_costs(name, key, unit, capsys, planetary, rack):
    assert main(["trace", f"configs/{name}.yaml", "--samples", "16", "--no-plots", "--json"]) == 0
    stats = json.loads(capsys.readouterr().out)
    lm = stats[key]
    for k in ("total", "backlash", "bores", "worst_case", "p95", "p50", "radial_play_mm", "accuracy_mm"):
        assert isinstance(lm[k], (int, float)), k
    band = lm[f"transmission_error_band_{unit}"]
    assert band["low"] < 0 < band["high"] and band["worst_case_width"] >= band["p95_width"] >= band["width"]
    assert band["width"] >= 0.95 * lm["total"]
    if unit == "mm":
        assert set(lm["pinion_arcmin"]) >= {"total", "worst_case", "p95"}
    assert play_cost(stats) == {key: lm["total"]}
    assert main(["trace", f"configs/{name}.yaml", "--samples", "16", "--no-plots"]) == 0
    text = capsys.readouterr().out
    assert "lost motion at the" in text and "95 % of prints under" in text and "worst case" in text
    spec, kit = planetary if unit == "arcmin" else rack
    loaded = pipeline.load(f"configs/{name}.yaml")
    tr = loaded.mechanism.trace(spec, kit, 16, None, False)
    res = Result()
    res.figures["samples"] = 16
    html = dict(loaded.mechanism.report_sections(spec, kit, res, tr, {"transmission.png": b"\x89PNG"}))["What play costs"]
    f = "{:.1f}" if unit == "arcmin" else "{:.3f}"
    lm = tr.stats[key]
    for k in ("total", "worst_case", "p95"):
        assert f"<b>{f.format(lm[k])} {unit}</b>" in html
    assert html.count("<tr>") == 1 + len(lm["shares"])


def test_sweep_tradeoff_takes_the_rack_in_mm():
    rows = [{"point": i, "values": {"k": i}, "status": "pass", "jam_probability": p, "jam_ci95_low": p,
             "jam_ci95_high": p, **play_cost({"lost_motion_mm": {"total": e}})}
            for i, (p, e) in enumerate([(0.01, 0.7), (0.2, 0.4)])]
    col, label, ordered = tradeoff_rows(rows)
    assert col == "lost_motion_mm" and "rack" in label and [r["point"] for r in ordered] == [1, 0]
