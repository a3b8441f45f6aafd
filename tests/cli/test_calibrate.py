"""`partgen calibrate`: the shipped example's profile, checked against values computed by hand."""

import json
import math
from pathlib import Path

import pytest

from partgen.cli.main import main
from partgen.config.loader import printer_limits, validate
from partgen.config.schema import Printer
from partgen.config.yamlio import read_yaml_file

EXAMPLE = Path(__file__).resolve().parents[2] / "configs" / "calibration" / "example_results.yaml"


@pytest.fixture(scope="module")
def profile(tmp_path_factory):
    out = tmp_path_factory.mktemp("cal") / "my_printer.yaml"
    assert main(["calibrate", "--printer", "prusa_mk4", str(EXAMPLE), "-o", str(out)]) == 0
    return out


def test_the_example_gives_the_hand_computed_profile(profile):
    p = read_yaml_file(profile)
    # by hand, from the example: hole 22 reads 9.87, 9.89 -> 9.88 -> bias -0.12; boss 21 10.03, 10.05 -> +0.04 and
    # key 27 5.03, 5.05 -> +0.04 -> pin +0.04; bar 30.10, 30.12 -> +0.11 and 10.09, 10.11 -> +0.10 -> outline +0.105
    b = p["biases"]
    assert b["hole_diametral_mm"] == pytest.approx(-0.12, abs=1e-9)
    assert b["pin_diametral_mm"] == pytest.approx(0.04, abs=1e-9)
    assert b["outline_diametral_mm"] == pytest.approx(0.105, abs=1e-9)
    assert b["compensate"] is True
    f = p["fits"]
    # hole 6 (0.25 modelled) is the first free one: as printed 0.25 - 0.12 - 0.04 = 0.09
    assert f["running_clearance_diametral_mm"] == pytest.approx(0.09, abs=1e-9)
    # hole 16 (-0.05 modelled) is the first that holds: -0.05 - 0.12 - 0.04 = -0.21
    assert f["press_fit_clearance_diametral_mm"] == pytest.approx(-0.21, abs=1e-9)
    assert f["gear_backlash_circumferential_mm"] == pytest.approx(0.20, abs=1e-9)  # grade 24, the first smooth one
    # ten readings in pairs 0.02 apart: residuals all ±0.01, five features -> 5 degrees of freedom;
    # 3 * sqrt(10 * 0.01**2 / 5) = 0.0424 -> 0.042
    assert p["xy_accuracy_mm"] == pytest.approx(round(3 * math.sqrt(10 * 1e-4 / 5), 3), abs=1e-12)
    assert p["calibration"]["printed_on"] == "2025-06-01" and p["calibration"]["from_profile"] == "prusa_mk4.yaml"
    text = profile.read_text()
    assert text.startswith("# partgen calibrate") and "coupon example_results.yaml, printed 2025-06-01" in text
    lim = printer_limits(validate(Printer, p, profile))
    assert lim.measured and lim.compensate and lim.hole_bias == pytest.approx(-0.12)
    # the rest of the profile is the MK4's
    mk4 = read_yaml_file(Path(__file__).resolve().parents[2] / "partgen" / "printers" / "prusa_mk4.yaml")
    for k in ("build_envelope_mm", "line_width_mm", "layer_height_mm", "min_hole_diameter_mm", "min_wall_lines"):
        assert p[k] == mk4[k]


def test_the_diff_is_printed(tmp_path, capsys):
    out = tmp_path / "p.yaml"
    assert main(["calibrate", "--printer", "prusa_mk4", str(EXAMPLE), "-o", str(out)]) == 0
    said = capsys.readouterr().out
    assert "fits.running_clearance_diametral_mm: 0.3 -> 0.09" in said
    assert "biases.hole_diametral_mm: 0.0 -> -0.12" in said
    # again over its own file: allowed; over a user's file: refused, the file untouched
    assert main(["calibrate", "--printer", "prusa_mk4", str(EXAMPLE), "-o", str(out), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["ok"] and got["running_clearance_diametral_mm"] == pytest.approx(0.09)
    mine = tmp_path / "mine.yaml"
    mine.write_text("name: mine\n")
    assert main(["calibrate", "--printer", "prusa_mk4", str(EXAMPLE), "-o", str(mine)]) == 2
    assert mine.read_text() == "name: mine\n"


def _with(tmp_path, edit):
    text = EXAMPLE.read_text()
    for old, new in edit:
        assert old in text
        text = text.replace(old, new, 1)
    p = tmp_path / "results.yaml"
    p.write_text(text)
    return p


@pytest.mark.parametrize("edit, key", [
    ([("  9: free", "  9: binds")], "running.9"),              # a looser hole binds while 6-8 turn freely
    ([("  17: holds", "  17: too_tight")], "press.17"),        # looser than 16, which holds
    ([("  25: smooth", "  25: binds")], "gears.25"),
    ([("hole_22_diameter_mm: [9.87, 9.89]", "hole_22_diameter_mm: [9.87, 98.9]")], "calipers.hole_22_diameter_mm"),
    ([("  6: free", "  6: freely")], "running.6"),
    ([("  1: binds               # 5.00 mm", "  31: binds               # 5.00 mm")], "running.31"),
    ([("  bar_26_width_mm: [10.09, 10.11]\n", "")], "calipers.bar_26_width_mm"),
    ([("coupon: 1 ", "coupon: 2 ")], "coupon"),
    ([(f"  {n}: free", f"  {n}: stiff") for n in range(6, 14)], "running"),  # nothing turns freely
])
def test_inconsistent_results_are_exit_2_naming_the_entry(tmp_path, capsys, edit, key):
    res = _with(tmp_path, edit)
    out = tmp_path / "out.yaml"
    assert main(["calibrate", "--printer", "prusa_mk4", str(res), "-o", str(out), "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["key"] == key and err["file"] == str(res)
    assert not out.exists()


def test_results_for_another_printer_are_refused(tmp_path, capsys):
    out = tmp_path / "out.yaml"
    assert main(["calibrate", "--printer", "ender3_v3", str(EXAMPLE), "-o", str(out)]) == 2
    assert "for 'prusa_mk4'" in capsys.readouterr().err and not out.exists()
