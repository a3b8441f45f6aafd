"""Build plates: every copy placed once, inside the plate, ``margin`` apart (measured on the moved
meshes and on the written 3MF, not on the packer's bookkeeping); a long part goes on the diagonal
and "does not fit" is exact; plate count near the area bound; the 3MF holds each distinct part once
with its copies as build items, as the manifest says (read back with zipfile + ElementTree, and by
PrusaSlicer when it is installed); the picture."""

import io
import itertools
import math
import re
import shutil
import struct
import subprocess
import xml.etree.ElementTree as ET
import zipfile
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
import trimesh
from shapely.geometry import MultiPoint, box

from partgen.export import plates as P
from partgen.testing import as_trimesh

ROOT = Path(__file__).resolve().parents[2]
DESIGNS = Path(__file__).resolve().parents[1] / "designs"
FORTUS = (406.0, 355.0)  # Stratasys Fortus 450mc build plate, x × y
SMALL = (250.0, 210.0)  # a desktop printer: forces several plates
DESK220 = (220.0, 220.0)  # a 220 mm bed: B1 (230 mm long) fits only on the diagonal
SIZES = [FORTUS, SMALL, DESK220]
IDS = ["fortus", "small", "desk220"]
MARGIN = 5.0
NS = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}


@pytest.fixture(scope="module")
def items(kit_of):
    """(name, print-oriented mesh, count) for every distinct part of the default kit (the session's build)."""
    from partgen.export.kit import group_parts, printed

    kit = kit_of("butterfly").kit
    groups = group_parts([printed(p) for p in kit.parts if p.printed])
    return [(g[0].part.name, g[0].mesh, len(g)) for g in groups]


@pytest.fixture(scope="module")
def layouts(items):
    """plate size -> Layout of the default kit."""
    return {size: P.layout(items, size, margin=MARGIN) for size in SIZES}


def _hull(xy):
    return MultiPoint(np.asarray(xy)[:, :2]).convex_hull


def _slab(length, width, height=4.0):
    m = trimesh.creation.box((length, width, height))
    m.apply_translation(-m.bounds[0])
    return m


# --- layout ------------------------------------------------------------------------------------

@pytest.mark.parametrize("size", SIZES, ids=IDS)
def test_every_copy_placed_once(items, layouts, size):
    lay = layouts[size]
    assert lay.size == size
    placed = Counter((p.name, p.copy) for plate in lay.plates for p in plate)
    wanted = Counter((name, k) for name, _, count in items for k in range(1, count + 1))
    assert placed == wanted  # each copy exactly once, nothing extra
    for i, plate in enumerate(lay.plates):
        assert plate, f"plate {i} is empty"
        assert all(p.plate == i for p in plate)


@pytest.mark.parametrize("size", SIZES, ids=IDS)
def test_parts_inside_plate_and_margin_apart(items, layouts, size):
    lay = layouts[size]
    W, H = size
    meshes = {name: mesh for name, mesh, _ in items}
    plate_box = box(-1e-6, -1e-6, W + 1e-6, H + 1e-6)
    for plate, moved in zip(lay.plates, P.plate_meshes(lay, meshes)):
        assert [n for n, _ in moved] == [f"{p.name}#{p.copy}" for p in plate]
        hulls = []
        for (name, m), p in zip(moved, plate):
            src = meshes[p.name]
            # a rigid motion about z: same faces, same heights, same volume, still on the plate
            assert np.array_equal(m.faces, src.faces)
            assert np.allclose(m.vertices[:, 2], src.vertices[:, 2])
            assert m.volume == pytest.approx(src.volume, rel=1e-9)
            fp = P.footprint(m, MARGIN)
            assert plate_box.contains(fp), f"{name} sticks out of the plate: {fp.bounds}"
            hulls.append((name, _hull(m.vertices)))
        for (na, a), (nb, b) in itertools.combinations(hulls, 2):
            d = a.distance(b)
            assert d >= MARGIN - 1e-6, f"{na} and {nb} are {d:.4f} mm apart (< {MARGIN})"


@pytest.mark.parametrize("size", SIZES, ids=IDS)
def test_plate_count_near_area_bound(items, layouts, size):
    lay = layouts[size]
    W, H = size
    area = sum(P.footprint(mesh, MARGIN).area * count for _, mesh, count in items)
    bound = math.ceil(area / (W * H))
    n = len(lay.plates)
    print(f"\n{W:g} x {H:g} plate: {sum(map(len, lay.plates))} copies on {n} plate(s), "
          f"area bound {bound}, fill {area / (n * W * H):.3f}")
    assert bound <= n <= bound + 2


@pytest.mark.parametrize("size", [FORTUS, DESK220], ids=["fortus", "desk220"])
def test_layout_is_deterministic(items, layouts, size):
    assert P.layout(items, size, margin=MARGIN) == layouts[size]


def test_long_link_goes_on_the_diagonal_of_a_220_bed(items, layouts):
    """B1 is longer than the 220 mm bed along either axis (measured on its mesh); the packer turns it
    onto the diagonal instead of refusing it, and the 4-quarter-turn packer of before refuses it."""
    mesh = dict((n, m) for n, m, _ in items)["B1"]
    assert np.ptp(mesh.vertices[:, 0]) + MARGIN > DESK220[0]  # too long along x ...
    assert np.ptp(mesh.vertices[:, 1]) + MARGIN < DESK220[1]  # ... and y is its short side
    (p,) = [p for plate in layouts[DESK220].plates for p in plate if p.name == "B1"]
    q = (p.angle / (math.pi / 2)) % 1.0
    assert 0.2 < q < 0.8, f"B1 turned {math.degrees(p.angle):.2f}°, not across the diagonal"
    with pytest.raises(P.DoesNotFit, match="B1"):
        P.layout(items, DESK220, margin=MARGIN, free=False)


def test_does_not_fit_is_exact_for_a_slab_on_a_square_bed():
    """A slab L × w grown by g = margin/2 (round corners) turned by 45° spans (L + w)/√2 + 2g each
    way, and 45° is its best turn on a square bed: it fits a 220 mm bed iff L + w <= 215·√2."""
    limit = (DESK220[0] - MARGIN) * math.sqrt(2)  # L + w at the limit, 304.06 mm
    w = 20.0
    lay = P.layout([("slab", _slab(limit - w - 0.01, w), 1)], DESK220, margin=MARGIN)
    (p,), = lay.plates
    assert math.isclose(math.degrees(p.angle) % 90.0, 45.0, abs_tol=0.5)
    moved = P.plate_meshes(lay, {"slab": _slab(limit - w - 0.01, w)})[0][0][1]
    assert box(0, 0, *DESK220).contains(P.footprint(moved, MARGIN))
    with pytest.raises(P.DoesNotFit, match="'slab' does not fit") as e:
        P.layout([("slab", _slab(limit - w + 0.01, w), 1)], DESK220, margin=MARGIN)
    assert e.value.parts == ("slab",)
    assert e.value.overhang == pytest.approx(0.01 / math.sqrt(2), abs=2e-3)


def test_does_not_fit_on_a_rectangular_bed_matches_brute_force():
    """On a 250 × 210 bed the longest 20 mm wide slab that fits in some turn, found by brute force
    over 400,000 turns of the formula L|cos t| + w|sin t| + 2g <= W, L|sin t| + w|cos t| + 2g <= H."""
    W, H = SMALL
    w, g = 20.0, MARGIN / 2
    t = np.linspace(0.0, math.pi / 2, 400_001)
    c, s = np.cos(t), np.sin(t)
    # the longest L at each turn: both constraints are linear in L
    lmax = np.minimum((W - 2 * g - w * s) / np.maximum(c, 1e-300), (H - 2 * g - w * c) / np.maximum(s, 1e-300))
    L = float(lmax.max())
    assert L > math.hypot(W, H) * 0.9 and L > W  # a diagonal fit, longer than the bed
    lay = P.layout([("slab", _slab(L - 0.05, w), 1)], SMALL, margin=MARGIN)
    moved = P.plate_meshes(lay, {"slab": _slab(L - 0.05, w)})[0][0][1]
    assert box(-1e-9, -1e-9, W + 1e-9, H + 1e-9).contains(P.footprint(moved, MARGIN))
    with pytest.raises(P.DoesNotFit, match="slab"):
        P.layout([("slab", _slab(L + 0.05, w), 1)], SMALL, margin=MARGIN)


def test_best_turn_of_a_disc_and_its_limits():
    """A disc's room does not depend on the turn: the search must settle it fast and say exactly
    whether it fits (a 2000-gon of radius 50 is 100 mm wide across vertices)."""
    a = np.linspace(0.0, 2 * math.pi, 2000, endpoint=False)
    disc = np.column_stack([50 * np.cos(a), 50 * np.sin(a)])
    width = np.ptp(disc @ np.array([[1.0], [0.0]]))
    _, room = P.best_turn(disc, (width + 5.0, 130.0), grow=2.5)
    assert 0 <= room < 2e-3
    least = 100 * math.cos(math.pi / 2000)  # its width across two edges
    _, room = P.best_turn(disc, (least - 0.001, 130.0))
    assert -0.001 - 2e-3 < room < 0  # narrower than the 2000-gon in every turn
    _, room = P.best_turn(disc, (least + 0.001, 130.0))
    assert room >= 0


def test_part_larger_than_plate_raises(items):
    huge = _slab(550.0, 20.0, 10.0)  # longer than the plate's diagonal (539 mm)
    assert 550.0 > math.hypot(*FORTUS)
    with pytest.raises(P.DoesNotFit, match="'slab' does not fit on a 406 x 355 mm plate in any turn"):
        P.layout(items[:3] + [("slab", huge, 1)], FORTUS)
    # too tall for y but fits turned a quarter: no error, and it is placed turned
    rail = _slab(20.0, 380.0, 10.0)
    lay = P.layout([("rail", rail, 1)], FORTUS)
    (p,), = lay.plates
    assert math.isclose(abs(math.sin(p.angle)), 1.0)
    with pytest.raises(P.DoesNotFit, match="rail"):
        P.layout([("rail", rail, 1)], FORTUS, angles=1, free=False)


# --- 3MF ---------------------------------------------------------------------------------------

def _read_3mf(data: bytes) -> dict:
    """A 3MF read with the standard library only (independent of the writer): model metadata,
    objects (id -> name, partnumber, metadata, vertices (n, 3), faces (m, 3)) and build items
    (objectid, (4, 4) transform, partnumber)."""
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        assert {"[Content_Types].xml", "_rels/.rels", "3D/3dmodel.model"} <= set(z.namelist())
        root = ET.fromstring(z.read("3D/3dmodel.model"))
    assert root.tag == f"{{{NS['m']}}}model" and root.get("unit") == "millimeter"
    objects = {}
    for o in root.find("m:resources", NS).findall("m:object", NS):
        mesh = o.find("m:mesh", NS)
        v = np.array([[float(e.get(k)) for k in "xyz"] for e in mesh.iter(f"{{{NS['m']}}}vertex")])
        f = np.array([[int(e.get(k)) for k in ("v1", "v2", "v3")]
                      for e in mesh.iter(f"{{{NS['m']}}}triangle")])
        group = o.find("m:metadatagroup", NS)
        meta = {e.get("name"): e.text for e in group.findall("m:metadata", NS)} if group is not None else {}
        objects[o.get("id")] = dict(name=o.get("name"), partnumber=o.get("partnumber"), meta=meta,
                                    type=o.get("type"), vertices=v, faces=f)
    items = []
    for it in root.find("m:build", NS).findall("m:item", NS):
        m = np.array([float(x) for x in it.get("transform").split()]).reshape(4, 3)
        t = np.eye(4)
        t[:3, :3], t[:3, 3] = m[:3].T, m[3]  # the spec's row-vector matrix -> column-vector
        items.append((it.get("objectid"), t, it.get("partnumber")))
    meta = {e.get("name"): e.text for e in root.findall("m:metadata", NS)}
    return dict(meta=meta, objects=objects, items=items)


def _volume(v: np.ndarray, f: np.ndarray) -> float:
    """Enclosed volume of a closed outward triangle mesh (divergence theorem), mm³."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def test_3mf_holds_each_part_once_with_its_copies_as_items(items, layouts):
    lay = layouts[SMALL]
    meshes = {name: mesh for name, mesh, _ in items}
    for plate in lay.plates:
        data = P.plate_3mf(plate, meshes, "butterfly", "ABS-M30", "a test plate")
        assert P.plate_3mf(plate, meshes, "butterfly", "ABS-M30", "a test plate") == data  # same bytes
        back = _read_3mf(data)
        assert back["meta"] == {"Title": "butterfly", "Application": "partgen", "Description": "a test plate"}
        names = [o["name"] for o in back["objects"].values()]
        assert sorted(names) == sorted({p.name for p in plate})  # one object per distinct part
        for o in back["objects"].values():
            src = meshes[o["name"]]
            assert o["partnumber"] == o["name"] and o["type"] == "model"
            assert o["meta"] == {"partgen:part": o["name"], "partgen:design": "butterfly",
                                 "partgen:material": "ABS-M30",
                                 "partgen:copies": str(sum(p.name == o["name"] for p in plate))}
            # float32 decimals: exactly the STL's float32 vertices
            assert np.array_equal(o["vertices"].astype(np.float32), np.asarray(src.vertices, np.float32))
            assert np.array_equal(o["faces"], src.faces)
        placed = {f"{p.name}#{p.copy}": p for p in plate}
        assert sorted(pn for _, _, pn in back["items"]) == sorted(placed)
        for oid, t, pn in back["items"]:
            p = placed[pn]
            assert back["objects"][oid]["name"] == p.name
            assert np.allclose(t, P.placement_matrix(p), rtol=0, atol=1e-12)
            # a turn about z and a move in xy: orthonormal, det +1, z untouched
            assert np.allclose(t[:3, :3] @ t[:3, :3].T, np.eye(3), atol=1e-12)
            assert np.linalg.det(t[:3, :3]) == pytest.approx(1.0)
            assert t[2, 2] == 1.0 and t[2, 3] == 0.0


def test_3mf_reloads_with_trimesh(items, layouts):
    """Another reader (trimesh, with lxml): one geometry per distinct part, one node per copy."""
    pytest.importorskip("lxml", reason="trimesh reads 3MF only with lxml installed")
    meshes = {name: mesh for name, mesh, _ in items}
    plate = layouts[SMALL].plates[0]
    scene = trimesh.load(io.BytesIO(P.plate_3mf(plate, meshes, "butterfly")), file_type="3mf")
    assert isinstance(scene, trimesh.Scene)
    assert sorted(scene.geometry) == sorted({p.name for p in plate})
    placed = scene.dump()
    assert len(placed) == len(plate)
    assert sum(g.volume for g in placed) == pytest.approx(sum(meshes[p.name].volume for p in plate), rel=1e-6)
    moved = trimesh.util.concatenate([as_trimesh(m) for _, m in P.plate_meshes(P.Layout((plate,), SMALL), meshes)[0]])
    assert np.allclose(trimesh.util.concatenate(placed).bounds, moved.bounds, atol=1e-4)


def test_3mf_is_much_smaller_than_a_mesh_per_copy(items, layouts):
    """Seven M4s and four legs on one plate: one mesh each, not one per copy."""
    meshes = {name: mesh for name, mesh, _ in items}
    (plate,) = layouts[FORTUS].plates
    data = P.plate_3mf(plate, meshes, "butterfly")
    xml_size = zipfile.ZipFile(io.BytesIO(data)).getinfo("3D/3dmodel.model").file_size
    triangles = sum(len(meshes[p.name].faces) for p in plate)
    distinct = sum(len(meshes[n].faces) for n in {p.name for p in plate})
    print(f"\nFortus plate: {len(data) / 1e6:.2f} MB 3MF, {xml_size / 1e6:.2f} MB XML, "
          f"{distinct} of {triangles} triangles written")
    assert distinct < triangles
    # triangles dominate the XML: at most ~80 bytes per written triangle (vertex and triangle lines)
    assert xml_size < 80 * distinct


@pytest.fixture(scope="module")
def checked_kits(tmp_path_factory, checked_default_kit):
    """design -> (manifest, plates folder, loaded): each design built into a kit, then `check KITDIR`
    writes its plates (default chain on the Fortus: 1 plate; on a 220 mm bed: several, B1 on the
    diagonal). The default's is the session's `check KITDIR` of a copy of its kit (conftest's
    ``checked_default_kit``)."""
    import json

    from partgen import pipeline

    out = {}
    kit = checked_default_kit["folder"]
    assert checked_default_kit["code"] == 0 and checked_default_kit["out"]["ok"] is True
    assert not [f for f in checked_default_kit["out"]["findings"] if "build plates" in f["message"]]
    out["butterfly"] = (json.loads((kit / "manifest.json").read_text()), kit / "plates", pipeline.load(kit))
    kit = tmp_path_factory.mktemp("desktop220") / "kit"
    pipeline.build(DESIGNS / "desktop220.yaml", kit)
    loaded, _, result, folder = pipeline.check(kit, samples=4)
    assert not [f for f in result.findings if "build plates" in f.message], result.findings
    out["desktop220"] = (json.loads((kit / "manifest.json").read_text()), folder, loaded)
    return out


@pytest.mark.parametrize("design", ["butterfly", "desktop220"])
def test_written_plates_match_the_manifest(checked_kits, design):
    """Every written plate read back: object names, per-object volume (from the 3MF's own vertices
    and triangles) and build items per part, summed over the plates, equal the manifest's; the
    placed footprints stay on the bed and do not overlap."""
    man, folder, loaded = checked_kits[design]
    parts = {p["name"]: p for p in man["parts"]}
    files = sorted(folder.glob("plate*.3mf"), key=lambda f: int(re.findall(r"\d+", f.stem)[0]))
    assert [f.name for f in files] == [f"plate{i}.3mf" for i in range(1, len(files) + 1)]
    W, H = loaded.spec.params.printer.envelope[:2]
    margin = loaded.spec.params.checks.plate_margin
    copies = Counter()
    for f in files:
        back = _read_3mf(f.read_bytes())
        assert back["meta"]["Title"] == man["design"]["name"] == loaded.spec.params.name
        objs = back["objects"]
        assert len({o["name"] for o in objs.values()}) == len(objs)
        for o in objs.values():
            entry = parts[o["name"]]
            assert o["meta"]["partgen:material"] == man["design"]["material"]
            assert len(o["faces"]) == entry["triangles"]
            assert _volume(o["vertices"], o["faces"]) == pytest.approx(entry["volume_mm3"], rel=1e-6)
        footprints = []
        for oid, t, pn in back["items"]:
            copies[objs[oid]["name"]] += 1
            # the vertices are float32 decimals (the STL's precision): read them as float32
            v = objs[oid]["vertices"].astype(np.float32).astype(float) @ t[:3, :3].T + t[:3, 3]
            assert v[:, 2].min() == pytest.approx(0.0, abs=1e-9)  # still on the bed
            footprints.append((pn, _hull(v)))
        bed = box(-1e-6, -1e-6, W + 1e-6, H + 1e-6)
        edge = max(margin / 2, loaded.spec.params.printer.plate_edge)  # the room a slicer's skirt needs
        for pn, hull in footprints:
            fp = hull.buffer(margin / 2, quad_segs=16)
            assert bed.contains(fp), f"{f.name}: {pn} sticks out of the {W:g} x {H:g} bed"
            assert min(hull.bounds[0], hull.bounds[1], W - hull.bounds[2], H - hull.bounds[3]) >= edge - 1e-6, \
                f"{f.name}: {pn} is closer than {edge:g} mm to the bed's edge"
        # footprints (hull + margin/2) may touch, never overlap: grown 10 nm less, they are disjoint,
        # and the hulls themselves are the margin apart
        for (na, a), (nb, b) in itertools.combinations(footprints, 2):
            assert not a.buffer(margin / 2 - 1e-5, quad_segs=16).intersects(b.buffer(margin / 2 - 1e-5, quad_segs=16)), \
                f"{f.name}: {na} and {nb} overlap"
            assert a.distance(b) >= margin - 1e-6, f"{f.name}: {na} and {nb} closer than {margin:g} mm"
    assert copies == Counter({n: p["count"] for n, p in parts.items()})
    if design == "desktop220":
        assert len(files) >= 2  # a 220 mm bed takes more than one plate, B1 among them
        assert copies["B1"] == 1


def _prusa_info(path: Path) -> list[dict]:
    out = subprocess.run(["prusa-slicer", "--loglevel", "1", "--info", str(path)], capture_output=True,
                         text=True, timeout=600, check=True).stdout
    blocks = []
    for line in out.splitlines():
        if line.strip() == f"[{path.name}]":  # one block per object (not the log's [date] lines)
            blocks.append({})
        elif "=" in line and blocks:
            k, v = (s.strip() for s in line.split("=", 1))
            blocks[-1][k] = v
    return blocks


@pytest.mark.skipif(shutil.which("prusa-slicer") is None, reason="prusa-slicer is not installed")
@pytest.mark.parametrize("design", ["butterfly", "desktop220"])
def test_prusa_slicer_reads_the_plates(checked_kits, design, tmp_path):
    """PrusaSlicer reads every plate: one object per copy (its CLI splits instances into objects),
    every one manifold with its part's manifest volume; and, re-saved by PrusaSlicer, the objects
    carry the part names."""
    man, folder, _ = checked_kits[design]
    parts = {p["name"]: p for p in man["parts"]}
    for f in sorted(folder.glob("plate*.3mf")):
        back = _read_3mf(f.read_bytes())
        names = [back["objects"][oid]["name"] for oid, _, _ in back["items"]]
        info = _prusa_info(f)
        assert len(info) == len(names), f"{f.name}: PrusaSlicer sees {len(info)} objects"
        assert all(b["manifold"] == "yes" for b in info), f"{f.name}: not every object is manifold"
        seen = sorted(float(b["volume"]) for b in info)
        want = sorted(parts[n]["volume_mm3"] for n in names)
        assert np.allclose(seen, want, rtol=2e-5), f"{f.name}: volumes differ"
        resaved = tmp_path / f"ps_{f.name}"
        subprocess.run(["prusa-slicer", "--loglevel", "1", "--dont-arrange", "--export-3mf", "-o", str(resaved),
                        str(f)], capture_output=True, timeout=600, check=True)
        with zipfile.ZipFile(resaved) as z:
            cfg = ET.fromstring(z.read("Metadata/Slic3r_PE_model.config"))
        ps_names = [m.get("value") for o in cfg.findall("object") for m in o.findall("metadata")
                    if m.get("type") == "object" and m.get("key") == "name"]
        assert sorted(ps_names) == sorted(names)


# --- picture -----------------------------------------------------------------------------------

def test_plate_picture(items, layouts, tmp_path):
    lay = layouts[SMALL]
    fps = {name: P.footprint(mesh, MARGIN) for name, mesh, _ in items}
    path = P.plate_picture(lay, fps, tmp_path / "plates.png", "butterfly on 250 x 210")
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    w, h = struct.unpack(">II", data[16:24])  # IHDR
    assert 400 <= w <= 6000 and 200 <= h <= 6000, (w, h)
    assert w > h  # several plates side by side
    assert len(data) > 20_000  # something was drawn


def test_too_large_is_what_no_plate_and_no_orientation_takes(kit_of):
    """``export.prints.too_large`` (what `build` refuses): the default kit's B1 (about 230 × 32 mm flat,
    rounded ends, 21.5 mm tall) on smaller printers. A 185 mm cube: longer than every side, it lies on
    the diagonal (its rounded ends: (230 − 32) / √2 + 32 + the margin < 185): printable. A 165 mm
    cube: not even there. A bed of 260 mm but 15 mm of height: its footprint fits, its height does
    not. Measured against ``plates.fits_plate`` and the part's own print height."""
    from dataclasses import replace
    from types import SimpleNamespace

    from partgen.export.kit import printed
    from partgen.export.plates import fits_plate
    from partgen.export.prints import too_large

    kit = kit_of("butterfly").kit
    b1 = next(p for p in kit.parts if p.name == "B1")
    mesh = printed(b1, kit.printer).mesh
    flat = np.ptp(np.asarray(mesh.vertices), axis=0)
    assert flat[0] > 185 or flat[1] > 185  # longer than the 185 mm bed's side: only the diagonal takes it

    def big(env):
        k = SimpleNamespace(parts=kit.parts, printer=replace(kit.printer, envelope=env))
        return {p.name for p, _ in too_large(k, 5.0)}
    assert "B1" not in big((185.0, 185.0, 185.0)) and fits_plate(mesh, (185.0, 185.0), 5.0)
    assert "B1" in big((165.0, 165.0, 165.0)) and not fits_plate(mesh, (165.0, 165.0), 5.0)
    assert "B1" in big((260.0, 260.0, 15.0)) and fits_plate(mesh, (260.0, 260.0), 5.0) and flat[2] > 15.0
    assert not big((406.0, 355.0, 406.0))  # the Fortus takes the whole kit
