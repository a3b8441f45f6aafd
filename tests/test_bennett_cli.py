"""`partgen build / check / report` on a Bennett butterfly: the kit folder (watertight STLs, manifest
with the bill of masses, the layout pinned in design.yaml), exit codes for a held and a failed
balance, and bad input naming its key."""

import json
from pathlib import Path

import pytest
import trimesh
import yaml

from partgen.cli.main import main
from partgen.testing import mesh_problems

ROOT = Path(__file__).resolve().parents[1]
FIXED = ROOT / "tests" / "designs" / "bennett_fixed.yaml"


@pytest.fixture(scope="module")
def kit_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("bennett") / "kit"
    assert main(["build", str(FIXED), "-o", str(out), "-q"]) == 0
    return out


def test_kit_folder(kit_dir):
    man = json.loads((kit_dir / "manifest.json").read_text())
    names = {p["name"] for p in man["parts"]}
    assert names == {f"link{i:02d}" for i in range(1, 13)} | {"base"}
    assert len(man["purchased"]) == 18  # one steel pin per joint
    for p in man["parts"]:
        mesh = trimesh.load(kit_dir / p["file"])
        assert not mesh_problems(mesh), p["name"]
        assert mesh.volume == pytest.approx(p["volume_mm3"], rel=1e-6)
        assert max(mesh.extents) < 406
    bill = {r["part"]: r for r in man["design"]["bill"]}
    assert all(0 < bill[f"link{i:02d}"]["printed_g"] < bill[f"link{i:02d}"]["solid_g"] for i in range(1, 13))
    assert sum(r["fill_g"] > 0 for r in bill.values()) == 3
    pinned = yaml.safe_load((kit_dir / "design.yaml").read_text())["parts"]["layout"]
    assert set(pinned["layers"]) == set(range(1, 13))


def test_check_a_kit_folder_holds(kit_dir, capsys):
    assert main(["check", str(kit_dir), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ok"] and out["figures"]["balance_mm"]["fdm"] < 1e-3


def test_a_tampered_kit_folder_fails(kit_dir, tmp_path, capsys):
    import shutil
    copy = tmp_path / "kit"
    shutil.copytree(kit_dir, copy)
    mesh = trimesh.load(copy / "link03.stl")
    mesh.apply_scale(1.01)
    mesh.export(copy / "link03.stl")
    assert main(["check", str(copy), "--json"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert [f["parts"] for f in out["findings"] if f["check"] == "kit"] == [["link03"]]


def test_a_heavier_link_fails_the_check(capsys):
    assert main(["check", str(ROOT / "tests" / "designs" / "bennett_heavy_link.yaml"), "--json"]) == 1
    out = json.loads(capsys.readouterr().out)
    fails = [f for f in out["findings"] if f["severity"] == "fail"]
    assert fails and all(f["check"] == "balance" for f in fails)


def test_report_page(tmp_path):
    assert main(["report", str(FIXED), "-o", str(tmp_path / "rep")]) == 0
    page = (tmp_path / "rep" / "index.html").read_text()
    for words in ("Poses", "Balance", "Interference", "Bill of parts", "link12"):
        assert words in page
    assert page.count("data:image/png") >= 4


@pytest.mark.parametrize("edit,key", [
    (lambda d: d["linkage"].__setitem__("beta_deg", 50.0), "linkage.beta_deg"),
    (lambda d: d["linkage"].__setitem__("b_mm", 200.0), "linkage.b_mm"),
    (lambda d: d["parts"].__setitem__("bar_diameter_mm", 12.0), "parts.bar_diameter_mm"),
    (lambda d: d["pin"].__setitem__("diameter_mm", 4.0), "pin.diameter_mm"),
    (lambda d: d["linkage"].__setitem__("workspace_deg", [90.0, 60.0]), "linkage"),
    (lambda d: d["counterweights"].__setitem__("distance_mm", [-60.0, 60.0, 60.0]), "counterweights"),
])
def test_bad_input_exits_2_with_the_key(tmp_path, capsys, edit, key):
    d = yaml.safe_load(FIXED.read_text())
    edit(d)
    d["printer"] = "fortus450mc"
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(yaml.safe_dump(d))
    out = tmp_path / "out"
    assert main(["build", str(cfg), "-o", str(out), "-q"]) == 2
    err = capsys.readouterr().err
    assert str(cfg.name) in err and key in err
    assert not out.exists()
