"""`partgen sweep`: a grid over --set keys, each point built and checked; bad input writes nothing."""

import csv
import json
from pathlib import Path

import pytest

from partgen.cli.main import main
from partgen.studies import parse_vary, sweep_points

CONFIGS = Path(__file__).resolve().parents[2] / "configs"


def test_grid_and_random_points():
    v = [parse_vary("gears.module_mm=1.5:2.5:3"), parse_vary("gears.teeth[0]=15:19:3")]
    pts = sweep_points(v)
    assert len(pts) == 9 and pts[0] == {"gears.module_mm": 1.5, "gears.teeth[0]": 15}
    assert {p["gears.teeth[0]"] for p in pts} == {15, 17, 19}
    assert parse_vary("gears.teeth[0]=15:17:9").values() == [15, 16, 17]  # whole numbers: each once
    r = sweep_points(v, random=20, seed=4)
    assert r == sweep_points(v, random=20, seed=4) and len(r) == 20
    assert all(1.5 <= p["gears.module_mm"] <= 2.5 and isinstance(p["gears.teeth[0]"], int) for p in r)


def test_sweep_builds_and_checks_every_point(tmp_path, capsys):
    out = tmp_path / "sweep"
    code = main(["sweep", str(CONFIGS / "gear_pair.yaml"), "--vary", "gears.module_mm=1.5:2.5:3", "--vary",
                 "gears.teeth[0]=6:17:2", "--workers", "1", "--check-samples", "8", "--json", "-o", str(out)])
    r = json.loads(capsys.readouterr().out)
    assert code == 0 and r["points"] == 6
    rows = list(csv.DictReader((out / "points.csv").open()))
    assert [(float(x["gears.module_mm"]), int(x["gears.teeth[0]"])) for x in rows] == \
        [(1.5, 6), (1.5, 17), (2.0, 6), (2.0, 17), (2.5, 6), (2.5, 17)]
    # a 6-tooth gear is refused, with the reason; the 17-tooth ones build, pass and grow with the module
    assert [x["status"] for x in rows] == ["refused", "pass"] * 3
    assert "6-tooth gear" in rows[0]["first_failure"]
    mass = [float(x["mass_g"]) for x in rows if x["status"] == "pass"]
    assert mass == sorted(mass) and mass[0] > 0
    page = (out / "index.html").read_text()
    assert page.count("<img") == 2 * 2 and "Against gears.module_mm" in page  # mass and size against each key
    assert len((out / "points.jsonl").read_text().splitlines()) == 6


@pytest.mark.parametrize("args, what", [
    (["--vary", "gears.modulus_mm=1:2:3"], "modulus_mm"),             # no such key
    (["--vary", "gears.module_mm=a:2:3"], "START and STOP"),           # a range of the wrong type
    (["--vary", "gears.module_mm=1:2:2.5"], "STEPS"),
    (["--vary", "name=1:2:2"], "name"),                               # a key that is not a number
    (["--vary", "gears.module_mm=-1:2:3"], "module_mm"),              # outside the schema's range
    (["--vary", "gears.module_mm=1:2:3", "--tolerance-samples", "0"], "tolerance-samples"),
    (["--vary", "gears.module_mm=1:2:3", "--random", "0"], "random"),
    # 10,000 × 11 × 10,000 points: refused by their count, before any grid is made (it hung)
    (["--vary", "gears.module_mm=1.5:2.5:10000", "--vary", "gears.teeth[0]=15:25:10000", "--vary",
      "gears.face_width_mm=6:10.5:10000"], "1,100,000,000 points: at most 100,000"),
])
def test_bad_input_writes_nothing(tmp_path, capsys, args, what):
    out = tmp_path / "sweep"
    assert main(["sweep", str(CONFIGS / "gear_pair.yaml"), *args, "-o", str(out)]) == 2
    assert what in capsys.readouterr().err
    assert not out.exists()


def test_the_jam_probability_column(tmp_path, capsys):
    """--tolerance-samples adds P(jam) with its 95 % interval to every point: on the gear pair at ±0.3 mm,
    no backlash jams in a share of simulated prints (the bores' play, taken up by the mesh, is all
    that frees it: docs/tolerance.md), 0.2 mm per gear in almost none. Without the option the
    column stays empty."""
    key = "gears.backlash_per_gear_mm"
    out = tmp_path / "sweep"
    assert main(["sweep", str(CONFIGS / "gear_pair.yaml"), "--vary", f"{key}=0.0:0.2:2", "--tolerance-samples",
                 "2000", "--workers", "1", "--check-samples", "8", "--accuracy-mm", "0.3", "-o", str(out)]) == 0
    rows = list(csv.DictReader((out / "points.csv").open()))
    assert [float(r[key]) for r in rows] == [0.0, 0.2]
    p = [float(r["jam_probability"]) for r in rows]
    lo, hi = [float(r["jam_ci95_low"]) for r in rows], [float(r["jam_ci95_high"]) for r in rows]
    assert all(a <= x <= b for a, x, b in zip(lo, p, hi)) and all(b - a < 0.1 for a, b in zip(lo, hi))
    assert p[0] > 0.03 and p[1] < 0.01 and hi[1] < lo[0]
    assert "P(jam)" in (out / "index.html").read_text()
    capsys.readouterr()
    plain = tmp_path / "plain"
    assert main(["sweep", str(CONFIGS / "gear_pair.yaml"), "--vary", "gears.module_mm=2:2.5:2", "--workers", "1",
                 "--check-samples", "8", "-o", str(plain)]) == 0
    assert all(r["jam_probability"] == "" for r in csv.DictReader((plain / "points.csv").open()))


def test_tolerance_samples_on_a_kind_with_no_model_is_refused(tmp_path, capsys, monkeypatch):
    from partgen.mechanisms import REGISTRY

    monkeypatch.delattr(type(REGISTRY["wrist"]), "tolerance_model")  # every shipped kind has one: a kind without
    out = tmp_path / "sweep"
    assert main(["sweep", str(CONFIGS / "wrist_sphere.yaml"), "--vary", "wrist.centre_distance_mm=58:62:2",
                 "--tolerance-samples", "100", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "--tolerance-samples" in err and "gear_chain, " in err and "gear_pair" in err and not out.exists()
