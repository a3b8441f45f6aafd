"""Both butterfly kits as written to disk: every STL a printable solid that fits the printer,
the manifest true to the files, the gears as declared, the stack as documented."""

import json
import math

import numpy as np
import pytest
import trimesh

from partgen.testing import measure_spur_gear, mesh_problems, section_outline

KITS = ["butterfly", "butterfly_liu2017"]


def load_stl(folder, name):
    return trimesh.load(folder / name, file_type="stl", force="mesh", process=True)


@pytest.mark.parametrize("kit", KITS)
def test_every_part_is_a_printable_solid_that_fits(kit, built_kits):
    loaded, _, man, folder = built_kits[kit]
    env = loaded.spec.params.printer.envelope
    for p in man["parts"]:
        mesh = load_stl(folder, p["file"])
        assert mesh_problems(mesh, env) == [], p["name"]
        assert mesh.bounds[0][2] == pytest.approx(0.0, abs=1e-6), f"{p['name']} does not lie on the plate"


@pytest.mark.parametrize("kit", KITS)
def test_manifest_agrees_with_the_files(kit, built_kits):
    loaded, built, man, folder = built_kits[kit]
    on_disk = json.loads((folder / "manifest.json").read_text())
    assert on_disk == man
    files = {p.name for p in folder.iterdir()}
    assert files == {p["file"] for p in man["parts"]} | {"manifest.json", "assembly.glb", "design.yaml", "printer.yaml",
                         ".partgen"}
    for p in man["parts"]:
        mesh = load_stl(folder, p["file"])
        assert p["triangles"] == len(mesh.faces)
        assert p["volume_mm3"] == pytest.approx(mesh.volume, rel=1e-6)
        assert p["mass_g"] == pytest.approx(mesh.volume * loaded.spec.params.density, abs=5e-5)  # 0.1 mg
        assert p["bbox_mm"] == pytest.approx(list(mesh.extents), abs=1e-3)
        assert p["count"] == len(p["instances"]) == len(p["placement"])
        for T in np.asarray(p["placement"]):
            assert T.shape == (4, 4)
            assert np.allclose(T[:3, :3] @ T[:3, :3].T, np.eye(3), atol=1e-8)
            assert np.linalg.det(T[:3, :3]) == pytest.approx(1.0)
    # every part of the kit is in exactly one manifest entry
    names = sorted(n for p in man["parts"] for n in p["instances"])
    assert names == sorted(p.name for p in built.parts)


@pytest.mark.parametrize("kit", KITS)
def test_gear_count_and_roles(kit, built_kits):
    _, built, man, _ = built_kits[kit]
    n_links = len(built.mechanism.chain.links)
    count = {}
    for p in man["parts"]:
        count[p["role"]] = count.get(p["role"], 0) + p["count"]
    assert count["gear"] == 3 * (n_links - 1) + 2 == 32
    assert count["link"] == n_links
    assert count["base"] == 1 and count["crank"] == 1 and count["pen_holder"] == 1


@pytest.mark.parametrize("kit", KITS)
def test_gears_in_the_kit_measure_as_declared(kit, built_kits):
    _, _, man, folder = built_kits[kit]
    for p in man["parts"]:
        if p["role"] != "gear":
            continue
        g = p["gear"]
        mesh = load_stl(folder, p["file"])
        z_mid = 3.0  # every gear's teeth start on the plate (teeth printed first); face 6 mm
        sec = section_outline(mesh, z_mid)
        got = measure_spur_gear(sec, g["teeth"], g["module_mm"], math.radians(g["pressure_angle_deg"]))
        assert got.teeth_found == g["teeth"], p["name"]
        expected_tip = g["module_mm"] * (g["teeth"] + 2 + 2 * g["profile_shift"])
        assert got.tip_diameter == pytest.approx(expected_tip, abs=0.01), p["name"]
        assert g["tip_diameter_mm"] == pytest.approx(expected_tip, abs=1e-8)
        assert got.tooth_thickness == pytest.approx(g["tooth_thickness_mm"], abs=0.01), p["name"]
        assert got.flank_deviation < 0.005, p["name"]


@pytest.mark.parametrize("kit", KITS)
def test_stack_matches_the_documented_layers(kit, built_kits):
    """At crank angle 0 every part sits where the README's stacking says: plates at P_j, gears
    at L_j, layer j = D_j, M_j, G_{j+1}; no two plates share a z-range."""
    _, built, man, folder = built_kits[kit]
    st = built.stack
    z = {}
    for p in man["parts"]:
        mesh = load_stl(folder, p["file"])
        for name, T in zip(p["instances"], np.asarray(p["placement"])):
            world = mesh.copy().apply_transform(T)
            z[name] = (world.bounds[0][2], world.bounds[1][2])
    n = len(built.mechanism.chain.links)
    for j in range(1, n + 1):
        assert z[f"B{j}"][0] == pytest.approx(st.plate_z(j), abs=1e-4)
    for j in range(1, n):
        for g in (f"D{j}", f"M{j}"):
            assert z[g] == pytest.approx((st.layer(j), st.layer(j) + st.face), abs=1e-4)
        assert z[f"G{j + 1}"][0] == pytest.approx(st.layer(j), abs=1e-4)
        # G_{j+1}'s boss reaches through plate j+1 and stands one gap proud of it
        assert z[f"G{j + 1}"][1] == pytest.approx(st.plate_z(j + 1) + st.plate + st.gap, abs=1e-4)
    plates = sorted((z[f"B{j}"][0], z[f"B{j}"][0] + st.plate) for j in range(1, n + 1))
    assert all(a[1] < b[0] for a, b in zip(plates, plates[1:]))


def test_assembly_glb_opens_with_every_part(built_kits):
    _, built, man, folder = built_kits["butterfly"]
    scene = trimesh.load(folder / "assembly.glb")
    assert isinstance(scene, trimesh.Scene)
    nodes = set(scene.graph.nodes_geometry)
    assert {n for p in man["parts"] for n in p["instances"]} <= nodes
    # the scene's pen holder sits at the traced pen position at θ = 0
    from partgen.design.synthesis import trace
    pen = trace(built.mechanism.chain, np.array([0.0]))[0] - built.mechanism.chain.offset
    T, geom = scene.graph["pen_holder"]
    T = np.linalg.inv(scene.graph["assembly"][0]) @ T  # undo the root's metres and Y up: the kit's mm, Z up
    v = scene.geometry[geom].vertices
    flip = next(p for p in man["parts"] if p["name"] == "pen_holder")["print_flip"]
    end = v[:, 2].min() if flip else v[:, 2].max()  # the tube's end (the spigot's is a D)
    ring = v[np.abs(v[:, 2] - end) < 1e-6]  # the tube's end: full circles about the axis
    world = T @ np.append(ring.mean(axis=0), 1.0)
    assert world[:2] == pytest.approx([pen.real, pen.imag], abs=1e-3)


def test_default_kit_has_no_warnings_and_paper_kit_has_its_eq12_defect(built_kits):
    default = built_kits["butterfly"][2]["design"]["findings"]
    paper = built_kits["butterfly_liu2017"][2]["design"]["findings"]
    assert not [f for f in default if f["severity"] == "warn"]
    assert [f for f in paper if f["severity"] == "warn" and f["code"] == "eq12"]


def test_stacking_figure_renders(built_kits, tmp_path):
    """The README's section picture is drawn from the kit's meshes without a display."""
    from PIL import Image

    from partgen.mechanisms.gear_chain.plots import stack_section
    _, built, _, _ = built_kits["butterfly"]
    out = tmp_path / "stack.png"
    stack_section(built, out)
    img = Image.open(out)
    assert img.size[0] > 1000 and img.size[1] > 500
    colours = {c for _, c in img.convert("RGB").getcolors(1 << 20)}
    assert (0x4c, 0x78, 0xa8) in colours and (0xf5, 0x85, 0x18) in colours  # gears and plates were drawn
