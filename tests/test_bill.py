"""The bill a maker shops from (issue 12): `build` prints, and the report shows, the printed parts
(count, filament grams each and in total) and the bought parts (quantity and stock size)."""

from __future__ import annotations

import json
import re
from collections import Counter
from pathlib import Path

import pytest
import trimesh

from partgen.cli.main import main
from partgen.export.bill import bill_sections, shopping_list, stock_items

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "configs"


@pytest.fixture(scope="module")
def belt_kit(tmp_path_factory):
    dest = tmp_path_factory.mktemp("bill") / "kit"
    return dest


def test_build_prints_the_bill(belt_kit, capsys):
    assert main(["build", str(CONFIGS / "butterfly_belt.yaml"), "-o", str(belt_kit)]) == 0
    out = capsys.readouterr().out
    man = json.loads((belt_kit / "manifest.json").read_text())
    density = man["design"]["density_g_cm3"] / 1000
    # grams measured from the STLs written, not from the manifest
    grams = {p["name"]: trimesh.load(belt_kit / p["file"]).volume * density for p in man["parts"]}
    total = sum(grams[p["name"]] * p["count"] for p in man["parts"])
    m = re.search(r"print: (\d+) parts \((\d+) distinct\), (\d+) g of", out)
    assert m, out
    assert int(m[1]) == sum(p["count"] for p in man["parts"]) and int(m[2]) == len(man["parts"])
    assert abs(int(m[3]) - total) <= 1
    for p in man["parts"]:
        row = re.search(rf"^  {re.escape(p['name'])}\s+(\d+)\s+([0-9.]+)\s+([0-9.]+)$", out, re.M)
        assert row, p["name"]
        assert int(row[1]) == p["count"] and float(row[2]) == pytest.approx(grams[p["name"]], abs=0.06)
        assert float(row[3]) == pytest.approx(grams[p["name"]] * p["count"], abs=0.06 * p["count"])
    # every belt is bought: the quantities add up to the belts, one line per distinct size
    belts = [b for b in man["purchased"] if b["role"] == "belt"]
    assert belts
    bought = re.findall(r"^\s+(\d+) × (.+? closed timing belt)\s+(\d+) teeth", out, re.M)
    assert sum(int(q) for q, _, _ in bought) == len(belts)
    assert Counter({int(t): int(q) for q, _, t in bought}) == Counter(b["teeth"] for b in belts)


def test_stock_items_groups_pins_and_fill():
    purchased = [
        {"name": "pin_a", "role": "pin", "diameter_mm": 10.0, "length_mm": 40.0, "material": "steel"},
        {"name": "pin_b", "role": "pin", "diameter_mm": 10.0, "length_mm": 40.0, "material": "steel"},
        {"name": "pin_c", "role": "pin", "diameter_mm": 10.0, "length_mm": 55.5, "material": "steel"},
        {"name": "fill_link01", "role": "counterweight fill", "part": "link01",
         "slugs": {"count": 7, "kind": "steel shot", "diameter_mm": 4.5, "length_mm": 4.5},
         "binder": {"name": "epoxy", "volume_cm3": 1.25}},
        {"name": "fill_link02", "role": "counterweight fill", "part": "link02",
         "slugs": {"count": 3, "kind": "steel shot", "diameter_mm": 4.5, "length_mm": 4.5},
         "binder": {"name": "epoxy", "volume_cm3": 0.5}},
    ]
    items = {(item, size): (q, used) for item, q, size, used in stock_items(purchased)}
    assert items[("steel pin", "Ø10 × 40.0 mm")] == (2, ["pin_a", "pin_b"])
    assert items[("steel pin", "Ø10 × 55.5 mm")][0] == 1
    assert items[("steel shot slug", "Ø4.5 × 4.5 mm")] == (10, ["link01", "link02"])
    assert {k[1] for k in items if k[0] == "epoxy"} == {"1.25 cm³", "0.50 cm³"}
    text = shopping_list({"parts": [{"name": "a", "count": 2, "mass_g": 1.5}], "purchased": purchased,
                          "design": {"material": "PLA"}})
    assert "print: 2 parts (1 distinct), 3 g of PLA" in text and "10 × steel shot slug" in text


def test_report_shows_filament_and_bought_parts():
    from partgen.pipeline import load, make_kit
    from partgen.export.prints import printed_groups

    loaded = load(CONFIGS / "gear_pair.yaml")
    kit = make_kit(loaded)
    bought = [{"name": "pin_a", "role": "pin", "diameter_mm": 5.0, "length_mm": 20.0, "material": "steel"}] * 3
    sections = dict(bill_sections(kit, {}, bought, printed_groups(kit)))
    groups = printed_groups(kit)
    total = sum(len(g) * g[0].mesh.volume * kit.density for g in groups)
    assert f"{round(total, 1)}" in sections["Filament"]
    assert "Ø5 × 20.0 mm" in sections["Bought parts"] and ">3<" in sections["Bought parts"]
