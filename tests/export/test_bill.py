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
from partgen.core.parts import Part, Stock
from partgen.export.bill import bill_sections, shopping_list, stock_items

ROOT = Path(__file__).resolve().parents[2]
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


def _bought(name, *lines, role="bought", **info):
    return Part(name, role, None, printed=False, info=tuple(info.items()), stock=tuple(Stock(*l) for l in lines))


def test_stock_items_groups_each_parts_own_lines():
    """Each bought part says what to buy for it (``Part.stock``): equal items of equal size are
    one line with the quantities summed and the names they serve; a part with no lines is its
    ``item`` (or role) with its sizes in mm."""
    bought = [
        _bought("pin_a", ("steel pin", 1, "Ø10 × 40.0 mm")),
        _bought("pin_b", ("steel pin", 1, "Ø10 × 40.0 mm")),
        _bought("pin_c", ("steel pin", 1, "Ø10 × 55.5 mm")),
        _bought("fill_link01", ("steel shot slug", 7, "Ø4.5 × 4.5 mm", "link01"), ("epoxy", 1, "1.25 cm³", "link01")),
        _bought("fill_link02", ("steel shot slug", 3, "Ø4.5 × 4.5 mm", "link02"), ("epoxy", 1, "0.50 cm³", "link02")),
        _bought("rod1", item="M5 threaded rod", diameter_mm=5.0, length_mm=31.5),
    ]
    items = {(item, size): (q, used) for item, q, size, used in stock_items(bought)}
    assert items[("steel pin", "Ø10 × 40.0 mm")] == (2, ["pin_a", "pin_b"])
    assert items[("steel pin", "Ø10 × 55.5 mm")][0] == 1
    assert items[("steel shot slug", "Ø4.5 × 4.5 mm")] == (10, ["link01", "link02"])
    assert {k[1] for k in items if k[0] == "epoxy"} == {"1.25 cm³", "0.50 cm³"}
    assert items[("M5 threaded rod", "diameter 5 mm, length 31.5 mm")] == (1, ["rod1"])
    text = shopping_list({"parts": [{"name": "a", "count": 2, "mass_g": 1.5}], "design": {"material": "PLA"}}, bought)
    assert "print: 2 parts (1 distinct), 3 g of PLA" in text and "10 × steel shot slug" in text
    assert "buy: nothing" in shopping_list({"parts": [], "design": {}}, [])


def test_report_shows_filament_and_bought_parts():
    from partgen.pipeline import load, make_kit
    from partgen.export.prints import printed_groups

    loaded = load(CONFIGS / "gear_pair.yaml")
    kit = make_kit(loaded)
    bought = [_bought(f"pin_{c}", ("steel pin", 1, "Ø5 × 20.0 mm")) for c in "abc"]
    sections = dict(bill_sections(kit, {}, bought, printed_groups(kit)))
    groups = printed_groups(kit)
    total = sum(len(g) * g[0].mesh.volume * kit.density for g in groups)
    assert f"{round(total, 1)}" in sections["Filament"]
    assert "Ø5 × 20.0 mm" in sections["Bought parts"] and ">3<" in sections["Bought parts"]
