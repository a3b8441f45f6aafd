"""What play costs at the output of a train of stages (stages/play.py through common/play.py): the model
against the printed outlines turned until they touch (every body centred; every body where the model puts
it in its bore; bodies at other places in their bores; the bodies pushed apart along their lines of
centres, the old model's share), how the lost motion moves with backlash and running clearance (by the
model's amounts), the worst case by hand and the 95 % figure, and where they show (trace --json and its
text, the report, sweep's trade-off)."""

import json
import math

import numpy as np
import pytest

from partgen import pipeline
from partgen.cli.main import main
from partgen.core.findings import Result
from partgen.export.studies import play_cost
from partgen.mechanisms.gear_train.common.play import ARCMIN, te_band
from partgen.mechanisms.gear_train.stages import play
from partgen.mechanisms.gear_train.stages.motion import printed_sections, turn_train

TH = np.array([0.0, 0.37, 1.1])


def _kit(name: str, *sets: str):
    loaded = pipeline.load(f"configs/{name}.yaml", over=pipeline.overrides(sets))
    return loaded.spec, pipeline.make_kit(loaded)


def _built(name: str, *sets: str):
    spec, kit = _kit(name, *sets)
    return spec, kit, printed_sections(kit), play.lost_motion(spec, kit)


@pytest.fixture(scope="module")
def reducer():
    return _built("gear_train_reducer")  # two spur stages: a shaft, a compound gear on its pin, a shaft


@pytest.fixture(scope="module")
def idler():  # the reducer's second stage an idler: the middle gear in two meshes on one layer
    return _built("gear_train_reducer", "train.ratio=null", "train.stages=[{teeth: [20, 30]}, "
                  "{teeth: [30, 25], idler: true, angle_deg: 70}]")


@pytest.fixture(scope="module")
def herringbone():
    return _built("gear_train_herringbone")  # one pair, its output turning negative


def _out(spec, turned, key):
    """The output's angle (rad) in its own forward sense."""
    return math.copysign(1.0, float(spec.shafts[-1].speed)) * turned[key][:, len(spec.shafts) - 1]


@pytest.mark.parametrize("design", ["reducer", "herringbone", "idler"])
def test_model_agrees_with_the_printed_outlines(design, request):
    """Centred, the output turns through the meshes' backlash; with every body where the model puts it
    (``worst_shifts``: one place for the forward limit, another for the backward one) through the
    model's whole nominal lost motion; the transmission-error band holds those two extremes."""
    spec, kit, secs, lm = request.getfixturevalue(design)
    plain = turn_train(kit, TH, secs, 1e-7)
    assert (_out(spec, plain, "coast") - _out(spec, plain, "drive")) * ARCMIN == pytest.approx(
        np.full(3, lm["backlash"]), rel=0.04)
    where = play.worst_shifts(spec)
    fwd = turn_train(kit, TH, secs, 1e-7, shifts=where["coast"])
    back = turn_train(kit, TH, secs, 1e-7, shifts=where["drive"])
    assert fwd["overlap_mm2"].max() == back["overlap_mm2"].max() == 0.0  # the model's places are free
    exact = (_out(spec, fwd, "coast") - _out(spec, back, "drive")) * ARCMIN
    assert exact == pytest.approx(np.full(3, lm["total"]), rel=0.02)
    assert exact.mean() - lm["backlash"] > 2.5 * (exact.mean() - lm["total"])  # the bores' part, not the lash's
    o = len(spec.shafts) - 1
    ends = np.stack([fwd["coast"][:, o], back["drive"][:, o]]) - plain["nominal"][:, o]
    te = {k: (plain[k][:, o] - plain["nominal"][:, o]) * ARCMIN for k in ("drive", "coast")}
    band = play.lost_motion(spec, kit, te["drive"], te["coast"])["transmission_error_band_arcmin"]
    assert ends.min() * ARCMIN == pytest.approx(band["low"], abs=0.01 * lm["total"])
    assert ends.max() * ARCMIN == pytest.approx(band["high"], abs=0.01 * lm["total"])


def test_no_other_place_in_the_bores_turns_the_output_further(reducer):
    """Bodies at random places in their bores: each limit moves by the model's first-order amount
    (Σ d_k · w_k) and never beyond where the model's places put it."""
    spec, kit, secs, lm = reducer
    c = spec.running / 2
    reach = play.body_reach(spec)
    where = play.worst_shifts(spec)
    plain = turn_train(kit, TH[:1], secs, 1e-7)
    fwd = turn_train(kit, TH[:1], secs, 1e-7, shifts=where["coast"])
    back = turn_train(kit, TH[:1], secs, 1e-7, shifts=where["drive"])
    rng = np.random.default_rng(3)
    for _ in range(4):
        ang, rad = rng.uniform(0, 2 * math.pi, 3), c * np.sqrt(rng.uniform(0, 1, 3))
        d = {k: (rad[k] * math.cos(ang[k]), rad[k] * math.sin(ang[k])) for k in range(3)}
        q = turn_train(kit, TH[:1], secs, 1e-7, shifts=d)
        want_f = sum(np.dot(d[k], reach[k][0]) for k in d) * ARCMIN
        want_b = sum(np.dot(d[k], reach[k][1]) for k in d) * ARCMIN
        assert (_out(spec, q, "coast") - _out(spec, plain, "coast"))[0] * ARCMIN == pytest.approx(want_f, abs=1.0)
        assert (_out(spec, plain, "drive") - _out(spec, q, "drive"))[0] * ARCMIN == pytest.approx(want_b, abs=1.0)
        assert _out(spec, q, "coast")[0] <= _out(spec, fwd, "coast")[0] + 1e-5
        assert _out(spec, q, "drive")[0] >= _out(spec, back, "drive")[0] - 1e-5


def test_the_play_along_the_line_of_centres_alone_is_the_old_share(herringbone):
    """The two bodies pushed apart along their line of centres by their play: the range grows by
    2 tan α_w · 2c / r_w (what the model counted before); the bores' share is 1/sin α_w of that
    (≈ 2.3 at this pair's 25° operating pressure angle): a body across the line adds the rest."""
    spec, kit, secs, lm = herringbone
    m = play.mesh_terms(spec)[0]
    c, u = spec.running / 2, m["u"]
    plain = turn_train(kit, TH[:2], secs, 1e-7)
    apart = turn_train(kit, TH[:2], secs, 1e-7, shifts={0: tuple(-c * u), 1: tuple(c * u)})
    grew = ((_out(spec, apart, "coast") - _out(spec, apart, "drive")) - (_out(spec, plain, "coast")
                                                                          - _out(spec, plain, "drive"))) * ARCMIN
    old = 2 * math.tan(m["alpha_w"]) * 2 * c / m["r_w"] * m["refer"] * ARCMIN
    assert grew == pytest.approx(np.full(2, old), rel=0.03)
    assert lm["bores"] == pytest.approx(old / math.sin(m["alpha_w"]), rel=1e-3)
    assert lm["bores"] == pytest.approx(2 * 2 * c / m["r_b"] * m["refer"] * ARCMIN, rel=1e-3)


def test_lost_motion_moves_with_backlash_and_clearance(reducer):
    spec, kit, _, base = reducer
    ms = play.mesh_terms(spec)
    lash = play.lost_motion(*_kit("gear_train_reducer", "gears.backlash_per_gear_mm=0.2"))
    # each mesh's circumferential backlash grows by 2 × 0.1 mm of thinning at the reference circles, cos α/cos α_w
    # of it on the operating pitch circle, over its driven gear's r_w, to the output
    al = spec.system.pressure_angle
    assert lash["backlash"] - base["backlash"] == pytest.approx(
        sum(0.2 * math.cos(al) / math.cos(m["alpha_w"]) / m["r_w"] * m["refer"] for m in ms) * ARCMIN, rel=2e-3)
    assert lash["bores"] == pytest.approx(base["bores"], rel=1e-4)
    loose = play.lost_motion(*_kit("gear_train_reducer", "shafts.running_clearance_diametral_mm=0.5"))
    # each body's radial play grows by 0.1 mm: the input's and the output's by 2/(r_w cos α_w) each (to the
    # output), the compound gear's by its two meshes' parts added as vectors: less than their sum
    rows = {r["share"]: r for r in base["shares"]}
    simple = 2 / ms[0]["r_b"] * ms[0]["refer"] * ARCMIN, 2 / ms[1]["r_b"] * ARCMIN
    assert rows["shaft0 in the plates"]["at_output"] == pytest.approx(simple[0] * 0.15, rel=1e-3)
    assert rows["shaft2 in the plates"]["at_output"] == pytest.approx(simple[1] * 0.15, rel=1e-3)
    compound = rows["gears1 on its pin"]["at_output"] / 0.15
    assert abs(simple[1] - simple[0]) < compound < simple[0] + simple[1]
    assert loose["bores"] - base["bores"] == pytest.approx(0.1 * (sum(simple) + compound), rel=2e-3)
    assert loose["backlash"] == pytest.approx(base["backlash"], rel=1e-4)
    for lm in (base, lash, loose):
        assert lm["worst_case"] >= lm["p95"] >= lm["total"] > 0 and lm["p95"] > lm["p50"] > 0.9 * lm["total"]


def test_the_worst_case_is_the_stack_the_model_says(herringbone):
    """Every feature at ± A the way that adds play, by hand (one pair along x): both outlines (1/cos α_w
    each, on the mesh's gain), the four shaft holes' x (2 tan α_w × ½ each, A/√2 as a coordinate; the top
    plate's register moves both axes alike: nothing), each body's bore and shaft (½ each: A per body)."""
    spec, kit, _, lm = herringbone
    m = play.mesh_terms(spec)[0]
    A, aw = spec.printer.xy_accuracy, m["alpha_w"]
    g_mesh = m["refer"] / m["r_w"] * ARCMIN
    g_body = 2 / m["r_b"] * m["refer"] * ARCMIN
    want = lm["total"] + g_mesh * (2 * A / math.cos(aw) + 4 * 2 * math.tan(aw) * 0.5 * A / math.sqrt(2)) + 2 * A * g_body
    assert lm["worst_case"] == pytest.approx(want, rel=1e-3)
    assert lm["worst_case"] > lm["p95"] > lm["total"] > 0


def test_the_band_takes_either_sense():
    """An output that turns negative lags upwards: its drive errors above its coast errors; the band is
    the same (the herringbone's band was 6.7 arcmin wide before: its lost motion inside out)."""
    d, c = np.array([8.0, 9.0]), np.array([-9.0, -8.5])
    assert te_band(d, c, 10.0) == te_band(c, d, 10.0) == {"low": -14.0, "high": 14.0, "width": 28.0}
    assert te_band(c, d, 10.0, sides=(0.3, 0.7)) == {"low": -12.0, "high": 16.0, "width": 28.0}


# --- where they show ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["gear_train_reducer", "gear_train_herringbone"])
def test_trace_json_text_and_report_say_what_play_costs(name, capsys, reducer, herringbone):
    assert main(["trace", f"configs/{name}.yaml", "--samples", "16", "--no-plots", "--json"]) == 0
    stats = json.loads(capsys.readouterr().out)
    lm = stats["lost_motion_arcmin"]
    for k in ("total", "backlash", "bores", "worst_case", "p95", "p50", "radial_play_mm", "accuracy_mm"):
        assert isinstance(lm[k], (int, float)), k
    assert lm["worst_case"] >= lm["p95"] >= lm["total"] > lm["bores"] > lm["backlash"] > 0
    assert {r["kind"] for r in lm["shares"]} == {"backlash", "bores"} and all("mm" in r for r in lm["shares"])
    band = lm["transmission_error_band_arcmin"]
    assert band["low"] < 0 < band["high"] and band["worst_case_width"] >= band["p95_width"] >= band["width"]
    assert band["width"] == pytest.approx(lm["total"], rel=0.05)  # both senses of the output
    assert play_cost(stats) == {"lost_motion_arcmin": lm["total"]}  # sweep's trade-off
    assert main(["trace", f"configs/{name}.yaml", "--samples", "16", "--no-plots"]) == 0
    text = capsys.readouterr().out
    assert f"lost motion at the output {lm['total']:.1f} arcmin" in text
    assert f"95 % of prints under {lm['p95']:.1f}" in text and f"worst case {lm['worst_case']:.1f}" in text
    spec, kit, _, _ = reducer if name == "gear_train_reducer" else herringbone
    loaded = pipeline.load(f"configs/{name}.yaml")
    tr = loaded.mechanism.trace(spec, kit, 16, None, False)
    res = Result()
    res.figures["samples"] = 16
    html = dict(loaded.mechanism.report_sections(spec, kit, res, tr, {"transmission.png": b"\x89PNG"}))["What play costs"]
    lm = tr.stats["lost_motion_arcmin"]
    for k in ("total", "worst_case", "p95"):
        assert f"<b>{lm[k]:.1f} arcmin</b>" in html
    assert html.count("<tr>") == 1 + len(lm["shares"]) == 1 + len(spec.meshes) + len(spec.shafts)
