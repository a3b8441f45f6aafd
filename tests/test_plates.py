"""Build-plate layout: every copy placed once, inside the plate, ``margin`` apart (measured on the
moved meshes, not on the packer's bookkeeping); plate count near the area bound; 3MF and picture."""

import io
import itertools
import math
import struct
import time
import xml.etree.ElementTree as ET
import zipfile
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
import trimesh
from shapely.geometry import MultiPoint, box

from partgen.export import plates as P

ROOT = Path(__file__).parent.parent
FORTUS = (406.0, 355.0)  # Stratasys Fortus 450mc build plate, x × y
SMALL = (250.0, 210.0)  # a desktop printer: forces several plates
MARGIN = 5.0


@pytest.fixture(scope="module")
def items():
    """(name, print-oriented mesh, count) for every distinct part of the default kit."""
    from partgen import pipeline
    from partgen.assembly.kit import build_kit
    from partgen.export.kit import group_parts, printed

    loaded = pipeline.load(ROOT / "configs" / "butterfly.yaml")
    kit = build_kit(loaded.mechanism, loaded.params)
    groups = group_parts([printed(p) for p in kit.parts])
    return [(g[0].part.name, g[0].mesh, len(g)) for g in groups]


@pytest.fixture(scope="module")
def layouts(items):
    """plate size -> (Layout, seconds the layout took)."""
    out = {}
    for size in (FORTUS, SMALL):
        t = time.perf_counter()
        lay = P.layout(items, size, margin=MARGIN)
        out[size] = (lay, time.perf_counter() - t)
    return out


def _hull(mesh):
    return MultiPoint(np.asarray(mesh.vertices)[:, :2]).convex_hull


@pytest.mark.parametrize("size", [FORTUS, SMALL], ids=["fortus", "small"])
def test_every_copy_placed_once(items, layouts, size):
    lay, _ = layouts[size]
    assert lay.size == size
    placed = Counter((p.name, p.copy) for plate in lay.plates for p in plate)
    wanted = Counter((name, k) for name, _, count in items for k in range(1, count + 1))
    assert placed == wanted  # each copy exactly once, nothing extra
    for i, plate in enumerate(lay.plates):
        assert plate, f"plate {i} is empty"
        assert all(p.plate == i for p in plate)


@pytest.mark.parametrize("size", [FORTUS, SMALL], ids=["fortus", "small"])
def test_parts_inside_plate_and_margin_apart(items, layouts, size):
    lay, _ = layouts[size]
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
            hulls.append((name, _hull(m)))
        for (na, a), (nb, b) in itertools.combinations(hulls, 2):
            d = a.distance(b)
            assert d >= MARGIN - 1e-6, f"{na} and {nb} are {d:.4f} mm apart (< {MARGIN})"


@pytest.mark.parametrize("size", [FORTUS, SMALL], ids=["fortus", "small"])
def test_plate_count_near_area_bound(items, layouts, size):
    lay, seconds = layouts[size]
    W, H = size
    area = sum(P.footprint(mesh, MARGIN).area * count for _, mesh, count in items)
    bound = math.ceil(area / (W * H))
    n = len(lay.plates)
    print(f"\n{W:g} x {H:g} plate: {sum(map(len, lay.plates))} copies on {n} plate(s), "
          f"area bound {bound}, fill {area / (n * W * H):.3f}, layout {seconds:.3f} s")
    assert bound <= n <= bound + 2
    assert seconds < 3.0  # typically ~0.2 s for ~50 copies


def test_layout_is_deterministic(items, layouts):
    assert P.layout(items, FORTUS, margin=MARGIN) == layouts[FORTUS][0]


def test_part_larger_than_plate_raises(items):
    huge = trimesh.creation.box((500.0, 20.0, 10.0))
    huge.apply_translation(-huge.bounds[0])
    with pytest.raises(ValueError, match="slab"):
        P.layout(items[:3] + [("slab", huge, 1)], FORTUS)
    # too tall for y but fits turned a quarter: no error, and it is placed turned
    long = trimesh.creation.box((20.0, 380.0, 10.0))
    lay = P.layout([("rail", long, 1)], FORTUS)
    (p,), = lay.plates
    assert math.isclose(abs(math.sin(p.angle)), 1.0)
    with pytest.raises(ValueError, match="rail"):
        P.layout([("rail", long, 1)], FORTUS, angles=1)


def _read_3mf(data: bytes) -> list[tuple[str, trimesh.Trimesh]]:
    """Objects of a 3MF read with the standard library only (independent of the writer)."""
    ns = {"m": "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"}
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        assert {"[Content_Types].xml", "_rels/.rels", "3D/3dmodel.model"} <= set(z.namelist())
        root = ET.fromstring(z.read("3D/3dmodel.model"))
    assert root.get("unit") == "millimeter"
    objs = {}
    for o in root.find("m:resources", ns).findall("m:object", ns):
        v = np.array([[float(e.get(k)) for k in "xyz"] for e in o.iter(f"{{{ns['m']}}}vertex")])
        f = np.array([[int(e.get(k)) for k in ("v1", "v2", "v3")]
                      for e in o.iter(f"{{{ns['m']}}}triangle")])
        objs[o.get("id")] = (o.get("name"), trimesh.Trimesh(v, f, process=False))
    return [objs[i.get("objectid")] for i in root.find("m:build", ns).findall("m:item", ns)]


@pytest.fixture(scope="module")
def plate_3mf(items, layouts):
    """The first plate of the small-plate layout: (moved parts, 3MF bytes)."""
    lay, _ = layouts[SMALL]
    moved = P.plate_meshes(lay, {name: mesh for name, mesh, _ in items})[0]
    return moved, P.write_plate_3mf(moved)


def test_3mf_holds_every_part_as_its_own_object(plate_3mf):
    moved, data = plate_3mf
    back = _read_3mf(data)
    assert [n for n, _ in back] == [n for n, _ in moved]
    for (name, a), (_, b) in zip(moved, back):
        assert np.array_equal(a.faces, b.faces), name
        assert np.array_equal(a.vertices, b.vertices), name  # exact round trip
    assert P.write_plate_3mf(moved) == data  # deterministic bytes


def test_3mf_reloads_with_trimesh(plate_3mf):
    pytest.importorskip("lxml", reason="trimesh reads 3MF only with lxml installed")
    moved, data = plate_3mf
    scene = trimesh.load(io.BytesIO(data), file_type="3mf")
    assert isinstance(scene, trimesh.Scene)
    assert sorted(scene.geometry) == sorted(n for n, _ in moved)
    total = sum(g.volume for g in scene.dump())
    assert total == pytest.approx(sum(m.volume for _, m in moved), rel=1e-6)


def test_plate_picture(items, layouts, tmp_path):
    lay, _ = layouts[SMALL]
    fps = {name: P.footprint(mesh, MARGIN) for name, mesh, _ in items}
    path = P.plate_picture(lay, fps, tmp_path / "plates.png", "butterfly on 250 x 210")
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    w, h = struct.unpack(">II", data[16:24])  # IHDR
    assert 400 <= w <= 6000 and 200 <= h <= 6000, (w, h)
    assert w > h  # several plates side by side
    assert len(data) > 20_000  # something was drawn
