"""A gear train's report says what its play costs: the output's lost motion (arc-minutes, per mesh and body)
and the transmission-error band, the figures trace measures (mechanisms/gear_train/stages/play.py)."""

import re

from partgen import pipeline


def _section(config: str, *sets: str) -> tuple[str, dict]:
    loaded = pipeline.load(config, over=pipeline.overrides(sets))
    kit = pipeline.make_kit(loaded)
    mech = loaded.mechanism
    result = mech.check(loaded.spec, kit, 8, None)
    tr = mech.trace(loaded.spec, kit, 24, None, False)
    sections = dict(mech.report_sections(loaded.spec, kit, result, tr, {"transmission.png": b"\x89PNG"}))
    return sections["What play costs"], tr.stats["lost_motion_arcmin"]


def test_report_shows_lost_motion_and_the_transmission_error_band():
    html, lm = _section("configs/gear_train_reducer.yaml")
    assert f"<b>{lm['total']:.1f} arcmin</b>" in html and f"backlash {lm['backlash']:.1f} arcmin" in html
    band = lm["transmission_error_band_arcmin"]
    assert f"{band['low']:.1f} … {band['high']:.1f} arcmin" in html and band["width"] > lm["bores"]
    assert html.count("<tr>") == 1 + len(lm["shares"])  # a row per mesh and per body in its bore
    # more running clearance: more lost motion, and the report says so
    looser, lm2 = _section("configs/gear_train_reducer.yaml", "shafts.running_clearance_diametral_mm=0.5")
    assert lm2["total"] > lm["total"] + 5
    got = float(re.search(r"<b>([0-9.]+) arcmin</b>", looser).group(1))
    assert abs(got - lm2["total"]) < 0.06
