"""Hub and bore variants of kind gear_train (``shafts.bores``): a keyway over the printed shaft's
integral key, a nut trap for an ISO nut on a bought threaded rod, a set screw through the hub into a
captive square nut. Each feature measured on the mesh of its part (sectioned, against its formula);
the kit passes check; the bought hardware is in the bill; bad sizes are exit 2 naming the key."""

import json
import math

import numpy as np
import pytest
import trimesh
import yaml
from helpers import modified
from shapely.geometry import LineString, Point, Polygon

from partgen import pipeline
from partgen.cli.main import main
from partgen.geometry.solid import mesh_arrays
from partgen.mechanisms.gear_train.common.hubs import DIN562_NUTS, ISO4032_NUTS
from partgen.mechanisms.gear_train.mechanism import MECHANISM
from partgen.testing import section_outline

# a small two-stage train: the input keyed, the compound shaft on a set screw, the output on an M5 nut
DESIGN = {"kind": "gear_train", "name": "hubs", "printer": "prusa_mk4",
          "gears": {"module_mm": 1.5, "face_width_mm": 6.0, "chord_tolerance_mm": 0.02},
          "train": {"stages": [{"teeth": [18, 30]}, {"teeth": [16, 28], "angle_deg": 70}]},
          "shafts": {"diameter_mm": 8.0, "bores": ["keyway", "set_screw", "hex"], "nut": "M5"},
          "checks": {"samples": 24, "min_tip_width_roads": 1.5}, "material": {"name": "PLA", "density_g_cm3": 1.24}}


def _write(tmp, design) -> str:
    p = tmp / f"{design['name']}.yaml"
    p.write_text(yaml.safe_dump(design))
    return str(p)


@pytest.fixture(scope="module")
def hubs(tmp_path_factory):
    loaded = pipeline.load(_write(tmp_path_factory.mktemp("hubs"), DESIGN))
    return loaded.spec, MECHANISM.build(loaded.spec)


def _mesh(kit, name) -> trimesh.Trimesh:
    v, f = mesh_arrays(kit.part(name).solid)
    return trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)  # as the STL stores it


def _inner(outline: Polygon, near=(0.0, 0.0)) -> Polygon:
    """The hole of a section that contains (or is nearest) ``near``."""
    rings = [Polygon(r) for r in outline.interiors]
    return min(rings, key=lambda r: r.distance(Point(near)))


def test_keyway_and_the_shafts_key_measure_their_formula(hubs):
    spec, kit = hubs
    sh = spec.shafts[0]
    d, r = 8.0, 4.0
    z0, z1 = spec.layer_z(sh.layers[0]), spec.layer_z(sh.layers[1]) + spec.face_width
    z = (z0 + z1) / 2
    bore = _inner(section_outline(_mesh(kit, "gears0"), z))
    # across the slot, between the bore's circle and its floor: the keyway's width
    y = (spec.bore_radius(sh) + spec.hub(sh).key_floor) / 2
    cut = bore.intersection(LineString([(-10, y), (10, y)]))
    assert cut.length == pytest.approx(d / 4 + spec.press, abs=2e-3)
    assert bore.bounds[3] == pytest.approx(r + d / 8 + spec.running / 2, abs=2e-3)  # its floor from the axis
    assert bore.bounds[1] == pytest.approx(-spec.bore_radius(sh), abs=0.03)  # the round side: r + press/2 (a polygon round it)
    # the printed shaft's key along the gear part: d/4 wide, d/8 proud
    shaft = section_outline(_mesh(kit, "shaft0"), z)
    assert shaft.bounds[3] == pytest.approx(r + d / 8, abs=2e-3)
    key = shaft.intersection(LineString([(-10, r + d / 16), (10, r + d / 16)]))
    assert key.length == pytest.approx(d / 4, abs=2e-3)
    # below the gear part (in the bottom plate) the shaft is round: it passes the plate's hole
    assert section_outline(_mesh(kit, "shaft0"), -1.0).bounds[3] == pytest.approx(r, abs=0.011)  # a chord tolerance


def test_nut_trap_measures_the_iso_nut(hubs):
    spec, kit = hubs
    sh = spec.shafts[2]
    h = spec.hub(sh)
    thread, s, m = ISO4032_NUTS["M5"]
    z_lo = spec.gap  # the part stands on its thrust ring (a hub under its lowest gear)
    mesh = _mesh(kit, "gears2")
    trap = _inner(section_outline(mesh, z_lo + h.pocket_depth / 2))
    ring = np.asarray(trap.simplify(1e-4).exterior.coords)[:-1]  # its corners (edges come split in the mesh)
    assert len(ring) == 6
    across = 2 * trap.exterior.distance(Point(0, 0))
    assert across == pytest.approx(s + spec.press, abs=2e-3)
    assert np.hypot(*ring.T).max() == pytest.approx((s + spec.press) / math.sqrt(3), abs=2e-3)
    # above the trap: the rod's clearance bore; the trap's depth holds the whole nut
    bore = _inner(section_outline(mesh, z_lo + h.pocket_depth + 0.3))
    assert 2 * bore.exterior.distance(Point(0, 0)) == pytest.approx(thread + spec.running, abs=0.03)
    assert h.pocket_depth == pytest.approx(m + spec.running / 2)
    assert _inner(section_outline(mesh, z_lo + h.pocket_depth - 0.05)).area == pytest.approx(trap.area, rel=1e-6)


def test_set_screw_hole_and_nut_slot_measure_their_formula(hubs):
    spec, kit = hubs
    sh = spec.shafts[1]
    h = spec.hub(sh)
    thread, s, m = DIN562_NUTS["M3"]
    zc = spec.gap + h.screw_z
    mesh = _mesh(kit, "gears1")
    # the hole through the hub wall outside the nut's slot, seen in the plane normal to the screw
    x = (h.slot_x0 + h.pocket_depth + sh.hub_radius) / 2
    sec = mesh.section(plane_origin=[x, 0, 0], plane_normal=[1, 0, 0])
    loops = [np.asarray(p) for p in sec.discrete]
    mid = lambda p: (p.max(axis=0) + p.min(axis=0)) / 2  # noqa: E731
    hole = min(loops, key=lambda p: np.hypot(mid(p)[1], mid(p)[2] - zc))
    assert np.hypot(mid(hole)[1], mid(hole)[2] - zc) < 0.011  # on the screw's axis (to a chord tolerance)
    for axis in (1, 2):
        assert np.ptp(hole[:, axis]) == pytest.approx(thread + spec.running, abs=0.02)
    # the hole comes out through the hub's surface, under the lowest gear
    assert zc + (thread + spec.running) / 2 < spec.layer_z(sh.layers[0])
    # the slot: square nut + press, its inner face a printer wall out from the bore
    slot = _inner(section_outline(mesh, zc + (thread + spec.running) / 2 + 0.2), (h.slot_x0 + 1, 0))
    x0, y0, x1, y1 = slot.bounds
    assert x1 - x0 == pytest.approx(m + spec.press, abs=2e-3)
    assert y1 - y0 == pytest.approx(s + spec.press, abs=2e-3)
    assert x0 - spec.bore_radius(sh) >= spec.printer.min_wall
    # the bought screw reaches from the shaft through the whole nut, its end inside the hub
    screw = kit.part("set_screw1").solid.bounding_box()
    nut = kit.part("nut1").solid.bounding_box()
    assert screw[0] == pytest.approx(4.0, abs=1e-6) and screw[3] >= nut[3] and screw[3] < sh.hub_radius


def test_the_kit_passes_check_and_buys_its_hardware(hubs, tmp_path):
    spec, kit = hubs
    result = MECHANISM.check(spec, kit, 24)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    kinds = {tuple(r["parts"]): r["kind"] for r in result.figures["fits"]["rows"]}
    assert kinds[("gears0", "shaft0")] == "press" and kinds[("set_screw1", "nut1")] == "thrust"
    for p in kit.parts:
        if p.printed:
            assert len(p.solid.decompose()) == 1, p.name  # one closed shell
    bought = {p.name: dict(p.info) for p in kit.parts if not p.printed}
    assert bought["set_screw1"]["item"].startswith("M3 × ") and bought["nut1"]["item"] == "M3 square nut (DIN 562)"
    assert bought["nut2"]["item"] == "M5 hex nut (ISO 4032)" and bought["shaft2"]["diameter_mm"] == 5.0


def test_a_nut_off_its_slot_overlaps_the_gear(hubs):
    """The check can fail: the set screw's nut pushed 1 mm towards the bore, into the slot's wall."""
    from partgen.geometry.measure import intersection

    spec, kit = hubs
    P = kit.poses(0.0)
    nut, gear = kit.part("nut1"), kit.part("gears1")
    assert intersection(nut.solid, P["nut1"], gear.solid, P["gears1"])[0] < 1e-6
    T = np.eye(4)
    T[0, 3] = -1.0
    assert intersection(nut.solid, P["nut1"] @ T, gear.solid, P["gears1"])[0] > 0.1


@pytest.mark.parametrize("change,key", [
    ({"nut": "M7"}, "shafts.nut"),
    ({"nut": None}, "shafts.nut"),
    ({"set_screw": "M20"}, "shafts.set_screw"),
    ({"set_screw": "M8", "bores": ["set_screw", "set_screw", "hex"]}, "shafts.set_screw"),  # its slot: 18 teeth's root
    ({"diameter_mm": 18.0}, "shafts.diameter_mm"),
    # the output's hub (under its gear in the second layer) meets the 30-tooth gear of the first: no room for M5
    ({"set_screw": "M5", "bores": ["keyway", "set_screw", "set_screw"]}, "shafts.set_screw"),  # the keyway's corner through the 18-tooth root
])
def test_bad_hub_sizes_are_exit_2_naming_the_key(tmp_path, capsys, change, key):
    d = json.loads(json.dumps(DESIGN))
    d["shafts"].update(change)
    d["shafts"] = {k: v for k, v in d["shafts"].items() if v is not None}
    assert main(["build", _write(tmp_path, d), "-o", str(tmp_path / "out"), "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["key"] == key, err
    assert not (tmp_path / "out").exists()


def test_planetary_sets_refuse_a_round_bore(tmp_path, capsys):
    """A planetary set's input and output shafts turn: ``round`` (a fixed pin) is refused (the other
    kinds: tests/mechanisms/gear_train/test_gear_train_hubs_planetary.py)."""
    cfg = modified("gear_train_planetary", tmp_path, {"shafts.bores": ["keyway", "round"]})
    assert main(["build", str(cfg), "-o", str(tmp_path / "out"), "--json"]) == 2
    assert json.loads(capsys.readouterr().out)["error"]["key"] == "shafts.bores"
