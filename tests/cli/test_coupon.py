"""`partgen coupon`: the calibration print, measured on its own meshes."""

import json
import math

import numpy as np
import pytest
import shapely
import trimesh
from shapely.geometry import Point

from partgen.cli.main import main
from partgen.config.loader import printer_limits, shipped_printers
from partgen.calibration import load_printer
from partgen.design import involute
from partgen.design.coupon import (BAR, CALIPER_D, GEAR, GEAR_BACKLASH, GEAR_BORE_CLEARANCE_MM, HOLE_D, KEY_TAB,
                                   PRESS, RUNNING, coupon_design, gear_centre_distance)
from partgen.config.yamlio import read_yaml_file
from partgen.export.coupon import BED_MM, coupon_layout, coupon_meshes
from partgen.export.plates import placement_matrix
from partgen.export.verify import mesh_report, read_stl
from partgen.geometry.coupon import TOL, coupon_solids, engraving
from partgen.geometry.measure import from_mesh, section


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    dest = tmp_path_factory.mktemp("coupon") / "mk4"
    assert main(["coupon", "--printer", "prusa_mk4", "-o", str(dest)]) == 0
    return dest


def _mesh(folder, name):
    return trimesh.load(folder / f"{name}.stl", force="mesh")


def _section(mesh, z):
    """The STL's mesh cut at height z (shapely, mm)."""
    return section(from_mesh(np.asarray(mesh.vertices), np.asarray(mesh.faces)), z)


def _holes(section):
    polys = section.geoms if hasattr(section, "geoms") else [section]
    return [shapely.Polygon(r) for p in polys for r in p.interiors]


def _inscribed_diameter(ring_poly, centre):
    """Twice the least distance from the centre to the ring: a circumscribed hole's true size."""
    return 2 * Point(centre).distance(ring_poly.exterior)


def test_hole_rows_have_the_graded_clearances(written):
    c = coupon_design(0.45, 0.2)  # the MK4's line width and layer height
    assert printer_limits(load_printer("prusa_mk4").printer).line_width == 0.45
    plate = _mesh(written, "plate")
    holes = _holes(_section(plate, 0.5 * c.plate[2]))
    assert len(holes) == 21  # 13 running, 7 press, the caliper hole
    measured = {}
    for h in holes:
        cx, cy = h.centroid.x, h.centroid.y
        d_in = _inscribed_diameter(h, (cx, cy))
        d_out = 2 * max(math.dist((cx, cy), p) for p in h.exterior.coords)
        assert d_out - d_in < 4 * TOL + 1e-4
        measured[(round(cx, 1), round(cy, 1))] = d_in
    by_number = {}
    for hole in c.holes:
        key = min(measured, key=lambda k: math.dist(k, hole.centre))
        assert math.dist(key, hole.centre) < 0.1
        by_number[hole.number] = measured.pop(key)
    run = np.array([by_number[i] for i in range(1, 14)])
    press = np.array([by_number[i] for i in range(14, 21)])
    # the key's post, measured on its own mesh
    key = _mesh(written, "key")
    post = _section(key, KEY_TAB[2] + 3.0)
    d_post = 2 * max(math.dist((post.centroid.x, post.centroid.y), p) for p in post.exterior.coords)
    assert d_post == pytest.approx(HOLE_D, abs=2e-4)  # a post's vertices lie on its circle
    np.testing.assert_allclose(run - HOLE_D, RUNNING, atol=2e-4)
    np.testing.assert_allclose(press - HOLE_D, PRESS, atol=2e-4)
    np.testing.assert_allclose(np.diff(run), 0.05, atol=2e-4)
    assert by_number[22] == pytest.approx(CALIPER_D, abs=2e-4)


def test_gear_posts_are_set_for_the_graded_backlash(written):
    c = coupon_design(0.45, 0.2)
    plate = _mesh(written, "plate")
    sec = _section(plate, c.plate[2] + 0.5 * 7.0)  # through the boss and the posts
    discs = sorted((p for p in sec.geoms), key=lambda p: p.centroid.x)
    assert len(discs) == 5
    boss, posts = discs[0], discs[1:]
    assert 2 * max(math.dist((boss.centroid.x, boss.centroid.y), p) for p in boss.exterior.coords) == \
        pytest.approx(CALIPER_D, abs=2e-4)
    xs = np.array([p.centroid.x for p in posts])
    # pushed together, each bore takes up its clearance: the mesh runs at the post distance minus it
    for gap, j in zip(np.diff(xs), GEAR_BACKLASH):
        a = gap - GEAR_BORE_CLEARANCE_MM
        x = GEAR.shift
        assert involute.circumferential_backlash(10, 10, 1.0, GEAR.alpha, x, x, 0, 0, a) == pytest.approx(j, abs=1e-4)
    gear = _mesh(written, "gear")
    g = _section(gear, 2.0)
    assert 2 * max(math.hypot(*p) for p in g.exterior.coords) == pytest.approx(2 * GEAR.tip_radius, abs=2e-3)
    assert _inscribed_diameter(_holes(g)[0], (0, 0)) == pytest.approx(HOLE_D + GEAR_BORE_CLEARANCE_MM, abs=2e-4)


def test_backlash_distance_inverts_the_backlash():
    for j in (0.0, 0.1, 0.35):
        a = gear_centre_distance(j)
        x = GEAR.shift
        assert involute.circumferential_backlash(10, 10, 1.0, GEAR.alpha, x, x, 0, 0, a) == pytest.approx(j, abs=1e-9)


def test_numbers_are_engraved_and_clear_of_the_holes(written):
    c = coupon_design(0.45, 0.2)
    plate = _mesh(written, "plate")
    t = c.plate[2]
    below = _section(plate, t - 1.2 * c.style.depth)
    in_groove = _section(plate, t - 0.5 * c.style.depth)
    eng = engraving(c.labels, c.style)
    assert below.area - in_groove.area == pytest.approx(eng.area, rel=1e-3)
    assert c.style.stroke >= 2 * 0.45 - 1e-9  # two lines of the MK4 per stroke
    for h in c.holes:
        assert eng.distance(Point(h.centre).buffer(0.5 * h.diameter, 64)) > 0.3
    for p in c.posts:
        assert eng.distance(Point(p).buffer(0.5 * HOLE_D, 64)) > 0.25
    # one label per numbered feature on the plate: 1-20, 22-25 (21 sits on the boss's top)
    assert sorted(int(text) for text, _ in c.labels) == list(range(1, 21)) + [22, 23, 24, 25]


@pytest.mark.parametrize("name", shipped_printers())
def test_every_shipped_printer_gets_a_printable_coupon(name):
    lim = printer_limits(load_printer(name).printer)
    c = coupon_design(lim.line_width, lim.layer_height)
    meshes = coupon_meshes(coupon_solids(c))
    for part, (mesh, stl, _) in meshes.items():
        rep = mesh_report(*read_stl(stl))
        assert rep.ok and rep.shells == 1, (name, part, rep.problems())
        assert mesh.bounds[0][2] == 0.0  # on the bed
    lay = coupon_layout(meshes)
    assert len(lay.plates) == 1
    pts = np.vstack([trimesh.transform_points(meshes[p.name][0].vertices, placement_matrix(p))
                     for p in lay.plates[0]])
    assert pts[:, 0].min() >= 0 and pts[:, 1].min() >= 0
    assert pts[:, 0].max() <= BED_MM[0] and pts[:, 1].max() <= BED_MM[1]
    mass_pla = sum(m.volume * k for m, _, k in meshes.values()) * 1.24e-3
    assert 5.0 < mass_pla <= 20.0
    assert c.style.stroke >= min(2 * lim.line_width, 1.0) - 1e-9


def test_the_folder_holds_a_plate_a_sheet_and_a_template(written):
    names = sorted(p.name for p in written.iterdir())
    assert names == [".partgen", "bar.stl", "coupon.3mf", "coupon.png", "gear.stl", "instructions.html", "key.stl",
                     "plate.stl", "results.yaml"]
    tpl = read_yaml_file(written / "results.yaml")
    assert sorted(tpl["running"]) == list(range(1, 14)) and sorted(tpl["press"]) == list(range(14, 21))
    assert sorted(tpl["gears"]) == [23, 24, 25] and all(v is None for v in tpl["running"].values())
    assert set(tpl["calipers"]) == {"boss_21_diameter_mm", "hole_22_diameter_mm", "bar_26_length_mm",
                                    "bar_26_width_mm", "key_27_post_diameter_mm"}
    page = (written / "instructions.html").read_text()
    assert 'src="coupon.png"' in page and "typical values, not measurements" in page
    assert (written / "coupon.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    scene = trimesh.load(written / "coupon.3mf", force="scene")
    assert len(scene.graph.nodes_geometry) == 6  # plate, 2 keys, 2 gears, bar
    assert BAR[0] == pytest.approx(_mesh(written, "bar").extents[0], abs=1e-4)


def test_a_users_folder_is_never_overwritten(tmp_path, capsys):
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    assert main(["coupon", "--printer", "ender3_v3", "-o", str(mine)]) == 2
    assert sorted(p.name for p in mine.iterdir()) == ["notes.txt"]
    assert "did not make" in capsys.readouterr().err
    assert main(["coupon", "--printer", "no_such_printer", "-o", str(tmp_path / "x"), "--json"]) == 2
    err = json.loads(capsys.readouterr().out)
    assert err["ok"] is False and not (tmp_path / "x").exists()
