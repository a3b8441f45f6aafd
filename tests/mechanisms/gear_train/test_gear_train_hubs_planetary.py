"""Hub and bore variants on a planetary set's sun (input) and carrier (output) and a rack's pinion
(``shafts.bores``: [input, output] and [pinion]): each feature measured on the float32 mesh of its
part (sectioned, against its formula), the kits pass check, the bought hardware is in the bill, and
what does not fit is exit 2 naming the key with nothing written."""

import json
import math

import numpy as np
import pytest
import shapely
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

GEARS = {"module_mm": 1.5, "face_width_mm": 8.0, "backlash_per_gear_mm": 0.1, "min_teeth": 12}
MATERIAL = {"name": "PLA", "density_g_cm3": 1.24}
# sun on a set screw (its hub raises the gears), carrier on an M5 nut trap in its plate
SET_HEX = {"kind": "gear_train", "name": "pl_set_hex", "printer": "prusa_mk4", "gears": GEARS,
           "planetary": {"teeth": [18, 27, 72], "planets": 3},
           "shafts": {"diameter_mm": 8.0, "bores": ["set_screw", "hex"], "nut": "M5"},
           "frame": {"plate_thickness_mm": 6.0}, "checks": {"samples": 24, "min_tip_width_roads": 1.5},
           "material": MATERIAL}
# sun keyed, carrier on a set screw through its plate (out between two pins)
KEY_SET = {**SET_HEX, "name": "pl_key_set", "shafts": {"diameter_mm": 8.0, "bores": ["keyway", "set_screw"]},
           "frame": {"plate_thickness_mm": 7.0}}
RACK = {"kind": "gear_train", "name": "rk_set", "printer": "prusa_mk4",
        "gears": {"module_mm": 2.0, "face_width_mm": 8.0}, "rack": {"pinion_teeth": 18, "travel_mm": 40.0},
        "shafts": {"diameter_mm": 8.0, "bores": ["set_screw"]}, "checks": {"samples": 24, "min_tip_width_roads": 1.5},
        "material": MATERIAL}
RACK_HEX = {**RACK, "name": "rk_hex", "shafts": {"diameter_mm": 8.0, "bores": ["hex"], "nut": "M5"}}


def _write(tmp, design) -> str:
    p = tmp / f"{design['name']}.yaml"
    p.write_text(yaml.safe_dump(design))
    return str(p)


def _built(tmp_path_factory, design):
    loaded = pipeline.load(_write(tmp_path_factory.mktemp(design["name"]), design))
    return loaded.spec, MECHANISM.build(loaded.spec)


@pytest.fixture(scope="module")
def fortus(tmp_path_factory):
    """The shipped planetary set on the Fortus, its sun on a set screw, its carrier keyed."""
    cfg = modified("gear_train_planetary", tmp_path_factory.mktemp("pl_fortus"),
                   {"shafts.bores": ["set_screw", "keyway"], "frame.plate_thickness_mm": 8.0, "checks.samples": 24,
                    "name": "pl_fortus"})
    loaded = pipeline.load(cfg)
    return loaded.spec, MECHANISM.build(loaded.spec)


@pytest.fixture(scope="module")
def set_hex(tmp_path_factory):
    return _built(tmp_path_factory, SET_HEX)


@pytest.fixture(scope="module")
def key_set(tmp_path_factory):
    return _built(tmp_path_factory, KEY_SET)


@pytest.fixture(scope="module")
def rack_set(tmp_path_factory):
    return _built(tmp_path_factory, RACK)


@pytest.fixture(scope="module")
def rack_hex(tmp_path_factory):
    return _built(tmp_path_factory, RACK_HEX)


def _mesh(kit, name) -> trimesh.Trimesh:
    v, f = mesh_arrays(kit.part(name).solid)
    return trimesh.Trimesh(v.astype(np.float32).astype(np.float64), f, process=False)  # as the STL stores it


def _inner(outline: Polygon, near=(0.0, 0.0)) -> Polygon:
    """The hole of a section nearest ``near``."""
    return min((Polygon(r) for r in outline.interiors), key=lambda r: r.distance(Point(near)))


def _screw_hole(mesh, turn: float, x: float, zc: float) -> np.ndarray:
    """The set screw's hole in the plane normal to its axis (along ``turn``) ``x`` out from the shaft's
    axis: its loop as (n, 2) points (across the axis, z)."""
    u, v = np.array([math.cos(turn), math.sin(turn), 0.0]), np.array([-math.sin(turn), math.cos(turn), 0.0])
    sec = mesh.section(plane_origin=x * u, plane_normal=u)
    loops = [np.c_[np.asarray(p) @ v, np.asarray(p)[:, 2]] for p in sec.discrete]
    mid = lambda p: (p.max(axis=0) + p.min(axis=0)) / 2  # noqa: E731
    hole = min(loops, key=lambda p: np.hypot(mid(p)[0], mid(p)[1] - zc))
    assert np.hypot(mid(hole)[0], mid(hole)[1] - zc) < 0.011  # on the screw's axis (to a chord tolerance)
    return hole


def _assert_set_screw(spec, mesh, h, z0: float, turn: float, outer: float):
    """A set screw's hole (screw + running, its axis a gap + half the slot above the bottom face z0) and
    its square nut's slot (nut + press, its inner face a printer wall out from the bore)."""
    thread, s, m = DIN562_NUTS[h.nut]
    zc = z0 + spec.gap + (s + spec.press) / 2
    hole = _screw_hole(mesh, turn, (h.slot_x0 + h.pocket_depth + outer) / 2, zc)
    for axis in (0, 1):
        assert np.ptp(hole[:, axis]) == pytest.approx(thread + spec.running, abs=0.02)
    slot = shapely.affinity.rotate(section_outline(mesh, zc + (thread + spec.running) / 2 + 0.2), -turn, (0, 0),
                                   use_radians=True)
    x0, y0, x1, y1 = _inner(slot, (h.slot_x0 + 1, 0)).bounds
    assert x1 - x0 == pytest.approx(m + spec.press, abs=3e-3)
    assert y1 - y0 == pytest.approx(s + spec.press, abs=3e-3)
    assert x0 - h.bore >= spec.printer.min_wall
    return zc


def test_sun_set_screw_hub_raises_the_gears_and_measures_its_formula(set_hex):
    spec, kit = set_hex
    h = spec.hubs[0]
    g = spec.gap
    mesh = _mesh(kit, "sun")
    zc = _assert_set_screw(spec, mesh, h, g, 0.0, spec.hub_radius)
    # the hole comes out of the hub's side under the gear; the gears stand on the hub's height
    assert zc + (h.thread + spec.running) / 2 < spec.gear_z
    assert spec.gear_z == pytest.approx(g + zc - g + (h.thread + spec.running) / 2 + spec.printer.min_wall, abs=0.05)
    assert mesh.bounds[0][2] == pytest.approx(g, abs=1e-5) and mesh.bounds[1][2] == pytest.approx(spec.gear_z + 8.0, abs=1e-5)
    hub = section_outline(mesh, g + 0.2)
    assert Polygon(hub.exterior).hausdorff_distance(Point(0, 0).buffer(spec.hub_radius, 256)) < 0.02
    # the planets and the ring's teeth are raised with it: a planet's section at the sun's gear
    planet = _mesh(kit, "planet0")
    assert planet.bounds[0][2] == pytest.approx(spec.gear_z, abs=1e-5)
    # the bore: shaft + press, round
    bore = _inner(section_outline(mesh, spec.gear_z + 4.0))
    assert 2 * bore.exterior.distance(Point(0, 0)) == pytest.approx(8.0 + spec.press, abs=0.03)


def test_carrier_nut_trap_measures_the_iso_nut(set_hex):
    spec, kit = set_hex
    h = spec.hubs[1]
    thread, s, m = ISO4032_NUTS["M5"]
    zc = spec.carrier_z
    mesh = _mesh(kit, "carrier")
    trap = _inner(section_outline(mesh, zc + h.pocket_depth / 2))
    assert len(np.asarray(trap.simplify(1e-4).exterior.coords)[:-1]) == 6
    assert 2 * trap.exterior.distance(Point(0, 0)) == pytest.approx(s + spec.press, abs=2e-3)
    assert h.pocket_depth == pytest.approx(m + spec.running / 2)
    bore = _inner(section_outline(mesh, zc + h.pocket_depth + 0.3))  # above it: the rod's clearance
    assert 2 * bore.exterior.distance(Point(0, 0)) == pytest.approx(thread + spec.running, abs=0.03)
    assert spec.plate_thickness - h.pocket_depth >= spec.printer.min_wall  # a wall over the trap
    top = _inner(section_outline(_mesh(kit, "frame_top"), spec.top_z + 1.0))  # the rod turns in the top plate
    assert 2 * top.exterior.distance(Point(0, 0)) == pytest.approx(thread + spec.running, abs=0.03)


def test_sun_keyway_and_the_input_shafts_key(key_set):
    spec, kit = key_set
    h, d, r = spec.hubs[0], 8.0, 4.0
    z = spec.gear_z + 4.0
    bore = _inner(section_outline(_mesh(kit, "sun"), z))
    y = (h.bore + h.key_floor) / 2
    assert bore.intersection(LineString([(-10, y), (10, y)])).length == pytest.approx(d / 4 + spec.press, abs=2e-3)
    assert bore.bounds[3] == pytest.approx(r + d / 8 + spec.running / 2, abs=2e-3)
    shaft = section_outline(_mesh(kit, "shaft_in"), z)
    assert shaft.bounds[3] == pytest.approx(r + d / 8, abs=2e-3)
    assert shaft.intersection(LineString([(-10, r + d / 16), (10, r + d / 16)])).length == pytest.approx(d / 4, abs=2e-3)
    assert section_outline(_mesh(kit, "shaft_in"), -1.0).bounds[3] == pytest.approx(r, abs=0.011)  # round in the plate


def test_carrier_set_screw_runs_out_between_two_pins(key_set):
    spec, kit = key_set
    h = spec.hubs[1]
    gaps = sorted((spec.screw_turn - a) % (2 * math.pi) for a in spec.angles)
    assert min(min(gaps), 2 * math.pi - max(gaps)) == pytest.approx(math.pi / 3, abs=1e-9)  # halfway between pins
    plate_r = section_outline(_mesh(kit, "carrier"), spec.carrier_z + 0.1).exterior.distance(Point(0, 0))
    zc = _assert_set_screw(spec, _mesh(kit, "carrier"), h, spec.carrier_z, spec.screw_turn, plate_r)
    assert zc + (h.thread + spec.running) / 2 + spec.printer.min_wall <= spec.carrier_z + spec.plate_thickness + 1e-9


def test_rack_pinion_set_screw_and_nut_trap(rack_set, rack_hex):
    spec, kit = rack_set
    mesh = _mesh(kit, "pinion")
    zc = _assert_set_screw(spec, mesh, spec.hub, spec.gap, 0.0, spec.hub_radius)
    assert zc + (spec.hub.thread + spec.running) / 2 < spec.gear_z
    rack = kit.part("rack").solid.bounding_box()  # the rack rides on the raised strip, level with the pinion
    assert rack[2] + kit.poses(0.0)["rack"][2, 3] == pytest.approx(spec.gear_z, abs=1e-6)
    spec, kit = rack_hex
    thread, s, m = ISO4032_NUTS["M5"]
    trap = _inner(section_outline(_mesh(kit, "pinion"), spec.gap + spec.hub.pocket_depth / 2))
    assert 2 * trap.exterior.distance(Point(0, 0)) == pytest.approx(s + spec.press, abs=2e-3)
    bore = _inner(section_outline(_mesh(kit, "pinion"), spec.gap + spec.hub.pocket_depth + 0.3))
    assert 2 * bore.exterior.distance(Point(0, 0)) == pytest.approx(thread + spec.running, abs=0.03)


@pytest.mark.parametrize("which", ["set_hex", "key_set", "rack_set", "rack_hex", "fortus"])
def test_the_kits_pass_check_and_buy_their_hardware(request, which):
    spec, kit = request.getfixturevalue(which)
    result = MECHANISM.check(spec, kit, 24)
    assert result.ok, [f.message for f in result.findings if f.severity == "fail"]
    for p in kit.parts:
        if p.printed:
            assert len(p.solid.decompose()) == 1, p.name  # one closed shell
    bought = {p.name: dict(p.info)["item"] for p in kit.parts if not p.printed}
    assert bought == {"set_hex": {"set_screw_in": "M3 × 3 set screw, flat point (ISO 4026)",
                                  "nut_in": "M3 square nut (DIN 562)", "shaft_out": "M5 threaded rod (DIN 976), cut to length",
                                  "nut_out": "M5 hex nut (ISO 4032)"},
                      "key_set": {"set_screw_out": "M3 × 3 set screw, flat point (ISO 4026)",
                                  "nut_out": "M3 square nut (DIN 562)"},
                      "rack_set": {"set_screw": "M3 × 3 set screw, flat point (ISO 4026)", "nut": "M3 square nut (DIN 562)"},
                      "rack_hex": {"shaft": "M5 threaded rod (DIN 976), cut to length",
                                   "nut": "M5 hex nut (ISO 4032)"},
                      "fortus": {"set_screw_in": "M3 × 3 set screw, flat point (ISO 4026)",
                                 "nut_in": "M3 square nut (DIN 562)"}}[which]
    # the hardware turns with its part
    P = kit.poses(1.0)
    for name in bought:
        holder = {"in": "sun", "out": "carrier"}.get(name.rsplit("_", 1)[-1], "pinion")
        if kit.part(name).role != "threaded rod":
            assert np.allclose(P[name], P[holder])
    # the manifest's design names each bore and its feature as built
    summary = MECHANISM.design_summary(spec, kit)
    bores = summary["bores"] if "bores" in summary else {"pinion": summary["bore"]}
    assert [b["bore"] for b in bores.values()] == [h.kind for h in (spec.hubs if "bores" in summary else (spec.hub,))]
    for b in bores.values():
        if b["bore"] == "hex":
            assert b["nut_trap"]["across_flats_mm"] == pytest.approx(ISO4032_NUTS["M5"][1] + spec.press)
        if b["bore"] == "set_screw":
            assert b["set_screw"]["hole_diameter_mm"] == pytest.approx(3.0 + spec.running)


def test_a_nut_off_its_slot_overlaps_the_sun(set_hex):
    """The check can fail: the sun's square nut pushed 1 mm towards the bore, into the slot's wall."""
    from partgen.geometry.measure import intersection

    spec, kit = set_hex
    P = kit.poses(0.0)
    nut, sun = kit.part("nut_in"), kit.part("sun")
    assert intersection(nut.solid, P["nut_in"], sun.solid, P["sun"])[0] < 1e-6
    T = np.eye(4)
    T[0, 3] = -1.0
    assert intersection(nut.solid, P["nut_in"] @ T, sun.solid, P["sun"])[0] > 0.1


@pytest.mark.parametrize("design,change,key", [
    (SET_HEX, {"shafts": {"bores": ["keyway"]}}, "shafts.bores"),  # a planetary set takes [input, output]
    (SET_HEX, {"shafts": {"bores": ["round", "d_flat"]}}, "shafts.bores"),  # its shafts turn: no fixed pin
    (SET_HEX, {"frame": {"plate_thickness_mm": 4.0}}, "shafts.nut"),  # the M5 trap needs a 5.75 mm plate
    (KEY_SET, {"frame": {"plate_thickness_mm": 5.0}}, "frame.plate_thickness_mm"),  # the carrier's set screw
    (SET_HEX, {"shafts": {"set_screw": "M8"}}, "shafts.set_screw"),  # its slot through the 18-tooth sun's root
    (SET_HEX, {"shafts": {"nut": "M9"}}, "shafts.nut"),
    (RACK, {"shafts": {"bores": ["hex", "hex"]}}, "shafts.bores"),  # a rack takes [pinion]
    (RACK, {"shafts": {"set_screw": "M8"}, "rack": {"pinion_teeth": 13}}, "shafts.set_screw"),
    (RACK_HEX, {"shafts": {"nut": "M8"}, "gears": {"face_width_mm": 6.0}}, "shafts.nut"),  # the trap deeper than the face
])
def test_what_does_not_fit_is_exit_2_naming_the_key(tmp_path, capsys, design, change, key):
    d = json.loads(json.dumps(design))
    for k, v in change.items():
        d[k].update(v)
    assert main(["build", _write(tmp_path, d), "-o", str(tmp_path / "out"), "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["key"] == key, err
    assert not (tmp_path / "out").exists()
