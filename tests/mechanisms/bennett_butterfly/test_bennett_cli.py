"""`partgen build / check / report` on a Bennett butterfly: the kit folder (watertight STLs, manifest
with the bill of masses, what to buy and where it goes, the layout pinned in design.yaml), the
centre of mass recomputed from the kit folder alone, exit codes for a held and a failed balance, and
bad input naming its key (a twist all but planar refused before any geometry). (Every command on
the design and a kit folder, a tampered kit folder: tests/cli/test_contract.py.)"""

import json
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yaml
from helpers import modified

from partgen.cli.main import main
from partgen.design import bennett_butterfly as bbf
from partgen.errors import ConfigError
from partgen.mechanisms import load_design
from partgen.mechanisms.bennett_butterfly.resolve import MIN_TWIST_DEG, resolve_bennett
from partgen.testing import mesh_problems

ROOT = Path(__file__).resolve().parents[3]
SHIPPED = ROOT / "configs" / "bennett_butterfly.yaml"
FIXED = ROOT / "tests" / "designs" / "bennett_fixed.yaml"


@pytest.fixture(scope="module")
def built_shipped(kit_of):
    """(kit folder, kit) of `build configs/bennett_butterfly.yaml` (its layout search included), the
    session's: tests/mechanisms/bennett_butterfly/test_bennett_kit.py and the manifest schema test share it (one worker, ``SHARED``
    in conftest.py), so the suite builds the shipped Bennett kit once instead of that and FIXED."""
    b = kit_of("bennett_butterfly")
    return b.dest, b.kit


@pytest.fixture(scope="module")
def kit_dir(built_shipped):
    return built_shipped[0]


def test_fixed_is_the_shipped_design_with_the_searched_layout_pinned(kit_dir):
    """tests/designs/bennett_fixed.yaml (and bennett_heavy_link.yaml, FIXED with a what-if mass
    scale) stand for the shipped design without its search: the shipped kit folder's design.yaml
    pins the layout the search chose, and it is FIXED's, the rest of the design being the same."""
    ours, fixed = yaml.safe_load((kit_dir / "design.yaml").read_text()), yaml.safe_load(FIXED.read_text())
    assert ours.pop("printer") == "printer.yaml" and fixed["printer"] == "fortus450mc"  # the kit's own copy of it
    assert ours == {k: v for k, v in fixed.items() if k != "printer"}
    heavy = yaml.safe_load((ROOT / "tests" / "designs" / "bennett_heavy_link.yaml").read_text())
    assert heavy["checks"].pop("mass_scale") == {5: 1.15} and heavy == fixed


def test_kit_folder(kit_dir):
    man = json.loads((kit_dir / "manifest.json").read_text())
    names = {p["name"] for p in man["parts"]}
    assert names == {f"link{i:02d}" for i in range(1, 13)} | {"base"}
    pins = [b for b in man["purchased"] if b["role"] == "pin"]
    fills = [b for b in man["purchased"] if b["role"] == "counterweight fill"]
    assert len(pins) == 18 and len(fills) == 3  # one steel pin per joint, a fill per pocket
    stock = yaml.safe_load((kit_dir / "design.yaml").read_text())["pin"]["stock_lengths_mm"]
    assert all(b["length_mm"] in stock for b in pins)
    for p in man["parts"]:
        mesh = trimesh.load(kit_dir / p["file"])
        assert not mesh_problems(mesh), p["name"]
        assert mesh.volume == pytest.approx(p["volume_mm3"], rel=1e-6)
        assert max(mesh.extents) < 406
    bill = {r["part"]: r for r in man["design"]["bill"]}
    assert all(0 < bill[f"link{i:02d}"]["printed_g"] < bill[f"link{i:02d}"]["solid_g"] for i in range(1, 13))
    assert sum(r["fill_g"] > 0 for r in bill.values()) == 3
    assert all(r["support_mm2"] >= 0 and r["bed_contact_mm2"] >= 0 for r in bill.values())
    assert bill["base"]["bed_contact_mm2"] >= 100 and bill["base"]["support_mm2"] == 0
    assert {b["item"] for b in man["design"]["bought"]} >= {f"{pins[0]['material']} Ø10 × {L:g} mm"
                                                            for L in {b["length_mm"] for b in pins}}
    pinned = yaml.safe_load((kit_dir / "design.yaml").read_text())["parts"]["layout"]
    assert set(pinned["layers"]) == set(range(1, 13))


def test_centre_of_mass_from_the_kit_folder_alone(kit_dir):
    """Done-when of issue 13: read only the kit folder — each STL (its solid volume and centre by
    trimesh must be the manifest's), the manifest's mass and centre as printed per part, the fills
    (mass and centre in their part's STL frame) and the pins (stock length × Ø at the pin's density
    from the kit's design.yaml, centre in their part's frame) — place every moving part at poses over
    the workspace (its STL frame from the manifest's home placement, moved by the kinematics of the
    manifest's a, b, α, β and scales) and the common centre of mass stays at S within the tolerance."""
    man = json.loads((kit_dir / "manifest.json").read_text())
    cfg = yaml.safe_load((kit_dir / "design.yaml").read_text())
    d = man["design"]
    rho_pin = cfg["pin"]["density_g_cm3"] / 1000
    bill = {r["part"]: r for r in d["bill"]}
    home = {p["name"]: np.array(p["placement"][0]) for p in man["parts"]}
    masses = {}
    for p in man["parts"]:
        mesh = trimesh.load(kit_dir / p["file"])
        r = bill[p["name"]]
        assert np.allclose(mesh.center_mass, r["solid_centre_mm"], atol=2e-3), p["name"]
        assert mesh.volume * cfg["material"]["density_g_cm3"] / 1000 == pytest.approx(r["solid_g"], rel=1e-4)
        masses[p["name"]] = [(r["printed_g"], np.array(r["printed_centre_mm"]))]
    for b in man["purchased"]:
        if b["role"] == "pin":
            m = rho_pin * math.pi * (b["diameter_mm"] / 2) ** 2 * b["length_mm"]
            assert m == pytest.approx(b["mass_g"], rel=1e-6)
            masses[b["counted_with"]].append((m, np.array(b["centre_mm"])))
        else:
            s = b["slugs"]
            assert b["mass_g"] == pytest.approx(s["count"] * s["mass_g_each"] + b["binder"]["mass_g"], rel=1e-6)
            masses[b["part"]].append((b["mass_g"], np.array(b["centre_mm"])))
    bb = bbf.BennettButterfly(d["a_mm"], d["b_mm"], math.radians(d["alpha_deg"]), math.radians(d["beta_deg"]),
                              *d["scales"][1:])
    at_home = bbf.link_frames(bbf.pose(bb, 0.0, -math.radians(d["home_angle_deg"])))
    body_from_stl = {i: np.linalg.inv(at_home[i][0]) @ home[f"link{i:02d}"] for i in range(1, 13)}
    lo, hi = (math.radians(x) for x in d["workspace_deg"])
    q1, ang = (g.ravel() for g in np.meshgrid(np.linspace(0, 2 * np.pi, 12, endpoint=False), np.linspace(lo, hi, 9)))
    frames = bbf.link_frames(bbf.pose(bb, q1, q1 - ang))
    total, moment = 0.0, np.zeros((len(q1), 3))
    for i in range(1, 13):  # the moving parts (the base and the pin it holds stand still)
        T = frames[i] @ body_from_stl[i]
        for m, c in masses[f"link{i:02d}"]:
            total += m
            moment += m * (T[:, :3, :3] @ c + T[:, :3, 3])
    worst = np.linalg.norm(moment / total, axis=1).max()
    assert worst < d["balance_tolerance_mm"]
    assert worst < 1e-3  # and as tight as the kit says (its own figure: within 0.0001 mm)
    assert d["balance_mm"]["fdm"] < 1e-3


def test_check_a_kit_folder_holds(kit_dir, capsys):
    """The kit folder's check (its kit rebuilt from its own design.yaml, the STLs compared) holds. No
    plates: the folder is the session's, read only (a Bennett kit folder's plates: tests/cli/test_contract.py)."""
    assert main(["check", str(kit_dir), "--json", "--no-plates"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["ok"] and out["figures"]["balance_mm"]["fdm"] < 1e-3


def test_a_heavier_link_fails_the_check(capsys):
    assert main(["check", str(ROOT / "tests" / "designs" / "bennett_heavy_link.yaml"), "--json", "--no-plates"]) == 1
    out = json.loads(capsys.readouterr().out)
    fails = [f for f in out["findings"] if f["severity"] == "fail"]
    assert fails and all(f["check"] == "balance" for f in fails)


def test_report_page(tmp_path, built_shipped, prime_kit_cache):
    prime_kit_cache(built_shipped[1], SHIPPED)  # the report's kit is the one `build` made of the same design
    assert main(["report", str(SHIPPED), "-o", str(tmp_path / "rep")]) == 0
    page = (tmp_path / "rep" / "index.html").read_text()
    for words in ("Poses", "Balance", "Interference", "Base", "Bill of parts", "Bought parts", "link12", "support mm²",
                  "one slug short", "binder left out"):
        assert words in page
    assert page.count("data:image/png") >= 4


@pytest.mark.parametrize("change,key", [
    ({"linkage.beta_deg": 50.0}, "linkage.beta_deg"),
    ({"linkage.b_mm": 200.0}, "linkage.b_mm"),
    ({"parts.bar_diameter_mm": 12.0}, "parts.bar_diameter_mm"),
    ({"pin.diameter_mm": 4.0}, "pin.diameter_mm"),
    ({"linkage.workspace_deg": [90.0, 60.0]}, "linkage"),
    ({"counterweights.distance_mm": [-60.0, 60.0, 60.0]}, "counterweights"),
    ({"pin.stock_lengths_mm": [18.0, 20.0, 22.0]}, "pin.stock_lengths_mm"),
    ({"base.foot_diameter_mm": 12.0}, "base.foot_diameter_mm"),
    ({"counterweights.slugs.lengths_mm": []}, "counterweights.slugs.lengths_mm"),
])
def test_bad_input_exits_2_with_the_key(tmp_path, capsys, change, key):
    cfg = modified(FIXED, tmp_path, {**change, "printer": "fortus450mc"}, name="bad.yaml")
    out = tmp_path / "out"
    assert main(["build", str(cfg), "-o", str(out), "-q"]) == 2
    err = capsys.readouterr().err
    assert str(cfg.name) in err and key in err
    assert not out.exists()


def _twisted(tmp_path, **linkage):
    """The shipped design with ``linkage`` changed, as the loader reads it."""
    return load_design(modified("bennett_butterfly", tmp_path, {f"linkage.{k}": v for k, v in linkage.items()}))


@pytest.mark.parametrize("linkage, key", [
    ({"alpha_deg": 0.011}, "linkage.alpha_deg"),
    ({"alpha_deg": 179.5}, "linkage.alpha_deg"),
    ({"alpha_deg": 1.5, "b_mm": 50.0}, "linkage.b_mm"),  # β = asin(50/105 sin 1.5°) = 0.71°
])
def test_an_all_but_planar_twist_is_refused_on_its_key(tmp_path, linkage, key):
    """A Bennett linkage within a degree of planar is refused on the twist's key before any geometry
    (the bad-input run found α = 0.011° writing link04 as two touching bodies)."""
    with pytest.raises(ConfigError) as e:
        resolve_bennett(_twisted(tmp_path, **linkage))
    assert e.value.key_path == key and "all but planar" in e.value.problem


def test_the_smallest_twist_passes_the_rule(tmp_path):
    params = resolve_bennett(_twisted(tmp_path, alpha_deg=MIN_TWIST_DEG))
    assert params is not None
