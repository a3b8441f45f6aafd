"""assembly.glb as standard viewers read it: metres and Y up (one root node), one mesh per distinct
part instanced by its nodes, a PBR material per role, normals true to the faces, and one animation
that moves every moving part over the mechanism's input (keys true to the kit's poses, the
interpolation between keys within the stated error, the meshing gears apart at mid-key); valid by the
Khronos glTF validator."""

import json
import math
import os
import shutil
import subprocess
from pathlib import Path

import manifold3d
import numpy as np

from partgen.core.protocol import ParamsKit
import pytest

from partgen.core.parts import Part
from partgen.core.protocol import Motion
from partgen.export import gltf

ROOT = Path(__file__).resolve().parents[2]
NODE = shutil.which("node")
NPM = shutil.which("npm")


def accessor(doc, binary, i):
    a = doc["accessors"][i]
    v = doc["bufferViews"][a["bufferView"]]
    dt = {5126: np.float32, 5125: np.uint32, 5123: np.uint16}[a["componentType"]]
    width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[a["type"]]
    arr = np.frombuffer(binary, dt, a["count"] * width, v["byteOffset"] + a.get("byteOffset", 0))
    return arr.reshape(a["count"], width) if width > 1 else arr


def quat_matrix(q):
    return gltf._matrix(np.asarray(q, dtype=np.float64))


def slerp(a, b, f):
    a, b = np.asarray(a, float), np.asarray(b, float)
    if np.dot(a, b) < 0:
        b = -b
    om = math.acos(min(1.0, float(np.dot(a, b))))
    if om < 1e-12:
        return a
    return (math.sin((1 - f) * om) * a + math.sin(f * om) * b) / math.sin(om)


@pytest.fixture(scope="module")
def pair(kit_of):
    built = kit_of("gear_pair")
    doc, binary = gltf.read_glb((built.dest / "assembly.glb").read_bytes())
    return built, doc, binary


@pytest.fixture(scope="module")
def chain(kit_of):
    built = kit_of("butterfly")
    doc, binary = gltf.read_glb((built.dest / "assembly.glb").read_bytes())
    return built, doc, binary


def test_root_node_makes_metres_and_y_up(pair):
    _, doc, _ = pair
    root = doc["nodes"][doc["scenes"][0]["nodes"][0]]
    assert root["scale"] == [0.001] * 3
    r = quat_matrix(root["rotation"])
    assert r @ [0, 0, 1] == pytest.approx([0, 1, 0], abs=1e-12)  # the kit's up is glTF's +y
    assert r @ [1, 0, 0] == pytest.approx([1, 0, 0], abs=1e-12)
    assert len(root["children"]) == len(doc["nodes"]) - 1


def test_repeated_parts_are_one_mesh_used_by_several_nodes(chain):
    built, doc, _ = chain
    nodes = {n["name"]: n for n in doc["nodes"][1:]}
    assert set(nodes) == {p.name for p in built.kit.parts}
    assert len(doc["meshes"]) == len(built.manifest["parts"])  # one mesh per distinct STL
    repeated = [p for p in built.manifest["parts"] if p["count"] > 1]
    assert repeated  # the default chain prints M4 seven times, the legs four
    for p in repeated:
        assert len({nodes[n]["mesh"] for n in p["instances"]}) == 1, p["name"]


def test_materials_are_pbr_coloured_by_role(chain):
    built, doc, _ = chain
    colours = built.loaded.mechanism.role_colours
    for n in doc["nodes"][1:]:
        mat = doc["materials"][doc["meshes"][n["mesh"]]["primitives"][0]["material"]]
        assert mat["name"] == n["extras"]["role"]
        rgb = [int(colours[mat["name"]][i:i + 2], 16) / 255 for i in (1, 3, 5)]
        lin = [x / 12.92 if x <= 0.04045 else ((x + 0.055) / 1.055) ** 2.4 for x in rgb]
        assert mat["pbrMetallicRoughness"]["baseColorFactor"] == pytest.approx(lin + [1.0], abs=1e-6)
    assert len({json.dumps(m["pbrMetallicRoughness"]) for m in doc["materials"]}) == len(doc["materials"]) > 3


def test_normals_are_unit_and_agree_with_their_faces(pair):
    _, doc, binary = pair
    for mesh in doc["meshes"]:
        prim = mesh["primitives"][0]
        v = accessor(doc, binary, prim["attributes"]["POSITION"]).astype(float)
        n = accessor(doc, binary, prim["attributes"]["NORMAL"]).astype(float)
        f = accessor(doc, binary, prim["indices"]).reshape(-1, 3)
        assert np.linalg.norm(n, axis=1) == pytest.approx(1.0, abs=1e-5)
        face = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
        area = np.linalg.norm(face, axis=1)
        big = area > 1e-6
        face = face[big] / area[big, None]
        for k in range(3):  # a vertex's normal is within the crease angle of every face it belongs to
            cos = np.einsum("ij,ij->i", face, n[f[big, k]])
            assert cos.min() > math.cos(math.radians(gltf.CREASE_DEG)) - 1e-3, mesh["name"]
        assert accessor(doc, binary, prim["attributes"]["POSITION"]).min(axis=0) == pytest.approx(
            doc["accessors"][prim["attributes"]["POSITION"]]["min"])


def node_track(doc, binary, node):
    """(times, translations or None, rotations or None) of a node's channels."""
    anim = doc["animations"][0]
    out = {"translation": None, "rotation": None}
    times = None
    for ch in anim["channels"]:
        if ch["target"]["node"] == node:
            s = anim["samplers"][ch["sampler"]]
            assert s["interpolation"] == "LINEAR"
            times = accessor(doc, binary, s["input"])
            out[ch["target"]["path"]] = accessor(doc, binary, s["output"]).astype(float)
    return times, out["translation"], out["rotation"]


def test_one_animation_keys_exactly_the_moving_parts_at_their_poses(chain):
    built, doc, binary = chain
    kit, motion = built.kit, built.loaded.mechanism.motion
    assert len(doc["animations"]) == 1
    anim = doc["animations"][0]
    ex = anim["extras"]
    assert ex["input_label"] == motion.label == "crank angle" and ex["mode"] == "turn"
    assert ex["input_range"] == pytest.approx(list(motion.range))
    probe = [kit.poses(u) for u in np.linspace(*motion.range, 7)]
    moving = {p.name for p in kit.parts if any(np.abs(q[p.name] - probe[0][p.name]).max() > 1e-9 for q in probe)}
    keyed = {doc["nodes"][c["target"]["node"]]["name"] for c in anim["channels"]}
    assert moving and keyed == moving and "base" not in keyed
    local = {it.part.name: it.local_from_print for grp in _groups(built) for it in grp}
    names = [n["name"] for n in doc["nodes"]]
    for name in ("B5", "M7", "pen_holder"):  # M7: an instance of the M4 mesh
        i = names.index(name)
        times, t, q = node_track(doc, binary, i)
        n = len(times) - 1
        for k in (0, n // 3, n // 2, n - 1):
            u = motion.range[0] + (motion.range[1] - motion.range[0]) * k / n
            want = kit.poses(u)[name] @ local[name]
            node = doc["nodes"][i]
            got_t = t[k] if t is not None else node["translation"]
            got_q = q[k] if q is not None else node["rotation"]
            assert got_t == pytest.approx(want[:3, 3], abs=1e-3)
            assert quat_matrix(got_q) == pytest.approx(want[:3, :3], abs=1e-6)


def _groups(built):
    from partgen.export.prints import printed_groups
    return printed_groups(built.kit)


def test_between_keys_no_point_strays_beyond_the_rule(chain):
    """At the middle of key intervals, a link's vertices as a viewer interpolates them (lerp, slerp)
    are within MAX_ERROR_MM of where the mechanism puts them."""
    built, doc, binary = chain
    kit, motion = built.kit, built.loaded.mechanism.motion
    local = {it.part.name: it for grp in _groups(built) for it in grp}
    names = [n["name"] for n in doc["nodes"]]
    worst = 0.0
    for name in ("B11", "G11", "pen_holder"):
        i = names.index(name)
        times, t, q = node_track(doc, binary, i)
        v = local[name].mesh.vertices
        n = len(times) - 1
        for k in range(0, n, max(1, n // 40)):
            u = motion.range[0] + (motion.range[1] - motion.range[0]) * (k + 0.5) / n
            true = kit.poses(u)[name] @ local[name].local_from_print
            tm = (t[k] + t[k + 1]) / 2 if t is not None else np.array(doc["nodes"][i]["translation"])
            rm = quat_matrix(slerp(q[k], q[k + 1], 0.5)) if q is not None else quat_matrix(doc["nodes"][i]["rotation"])
            err = np.linalg.norm(v @ rm.T + tm - (v @ true[:3, :3].T + true[:3, 3]), axis=1).max()
            worst = max(worst, err)
    assert 0.0 < worst <= gltf.MAX_ERROR_MM


def test_gears_mesh_without_overlap_between_keys(pair):
    """The pair's gears at the middle of key intervals, as a viewer interpolates them, do not overlap."""
    built, doc, binary = pair
    names = [n["name"] for n in doc["nodes"]]
    solid = {it.part.name: (it.part.solid, it.local_from_print) for grp in _groups(built) for it in grp}
    tracks = {g: node_track(doc, binary, names.index(g)) for g in ("gear1", "gear2")}
    n = len(tracks["gear1"][0]) - 1
    for k in (0, n // 5, n // 2, n - 2):
        placed = []
        for g in ("gear1", "gear2"):
            _, t, q = tracks[g]
            node = doc["nodes"][names.index(g)]
            m = np.eye(4)
            m[:3, :3] = quat_matrix(slerp(q[k], q[k + 1], 0.5))
            m[:3, 3] = (t[k] + t[k + 1]) / 2 if t is not None else node["translation"]
            s, lfp = solid[g]
            world_from_local = m @ np.linalg.inv(lfp)  # the node's frame is the STL's; the solid is local
            placed.append(s.transform(world_from_local[:3, :4].tolist()))
        assert (placed[0] ^ placed[1]).volume() < 1e-6  # ^: intersection in manifold3d
        assert placed[0].volume() > 1000


class _Swing:
    """A fake kit: a bar whose far end (60 mm out) swings about a pivot 40 mm from its origin."""

    name, printer, density, material = "swing", None, 1.0, "PLA"

    def __init__(self):
        self.parts = (Part("bar", "link", manifold3d.Manifold.cube([60, 4, 4])),
                      Part("post", "base", manifold3d.Manifold.cube([4, 4, 4])))

    def poses(self, t=0.0):
        c, s = math.cos(t), math.sin(t)
        m = np.eye(4)
        m[:2, :2] = [[c, -s], [s, c]]
        m[:2, 3] = [40 * c, 40 * s]
        return {"bar": m, "post": np.eye(4)}

    poses_over = ParamsKit.poses_over  # the protocol's default: poses at each value


def _instances(kit):
    import trimesh
    out = []
    for p in kit.parts:
        mesh = p.solid.to_mesh()
        out.append(gltf.Instance(p, trimesh.Trimesh(mesh.vert_properties[:, :3], mesh.tri_verts), np.eye(4)))
    return out


def test_sampling_doubles_keys_until_the_error_bound_holds_and_plays_a_range_out_and_back():
    kit = _Swing()
    s = gltf.sample_motion(kit, _instances(kit), Motion("bend", "rad", (0.0, math.pi / 2)), max_error_mm=0.05,
                           min_keys=4)
    # the slerp of a turn about z is exact; the lerp of the origin cuts the chord of its 40 mm circle:
    # 40 (1 - cos(Δ/2)) at mid-key, Δ = (π/2)/n; keys double from 4 until that is ≤ 0.05 mm
    n = 4
    while 40 * (1 - math.cos(math.pi / 4 / n)) > 0.05:
        n *= 2
    assert s.mode == "out_and_back" and s.keys == n == 16
    assert s.max_error_mm == pytest.approx(40 * (1 - math.cos(math.pi / 4 / n)), rel=1e-6)
    assert s.inputs[0] == s.inputs[-1] == 0.0 and s.inputs[s.keys] == pytest.approx(math.pi / 2)
    assert np.all(np.diff(s.times) > 0)
    doc, binary = gltf.read_glb(gltf.assembly_glb(kit, _instances(kit), Motion("bend", "rad", (0.0, math.pi / 2))))
    anim = doc["animations"][0]
    assert {doc["nodes"][c["target"]["node"]]["name"] for c in anim["channels"]} == {"bar"}
    assert {c["target"]["path"] for c in anim["channels"]} == {"translation", "rotation"}
    assert anim["extras"]["mode"] == "out_and_back" and anim["extras"]["input_label"] == "bend"


def _validator():
    """(node, NODE_PATH) of an installed gltf-validator, or the reason there is none."""
    if NODE is None:
        return None, "node is not installed (scripts/install-browser.sh installs gltf-validator with npm)"
    paths = [str(ROOT / "node_modules")]
    if NPM:
        got = subprocess.run([NPM, "root", "-g"], capture_output=True, text=True, timeout=60).stdout.strip()
        paths.append(got)
    env = {**os.environ, "NODE_PATH": os.pathsep.join(paths)}
    r = subprocess.run([NODE, "-e", "require('gltf-validator')"], env=env, capture_output=True, timeout=60)
    if r.returncode != 0:
        return None, "the gltf-validator npm package is not installed (scripts/install-browser.sh installs it)"
    return env, ""


@pytest.mark.parametrize("name", ["gear_pair", "butterfly"])
def test_khronos_validator_finds_no_error(name, kit_of):
    env, why = _validator()
    if env is None:
        if os.environ.get("CI"):
            pytest.fail(why)
        pytest.skip(why)
    glb = kit_of(name).dest / "assembly.glb"
    r = subprocess.run([NODE, str(ROOT / "scripts" / "gltf-validate.js"), str(glb)], env=env, capture_output=True,
                       text=True, timeout=300)
    report = json.loads(r.stdout.splitlines()[-1])
    assert r.returncode == 0 and report["errors"] == 0, report
    assert report["warnings"] == 0, report


def test_creased_normals_split_at_the_edges_and_smooth_the_curves():
    """A box: 24 vertices, each normal its face's axis. A 64-sided prism (a faceted cylinder, 11.25°
    between sides, under the crease angle): each top or bottom ring vertex has two copies, one on
    its cap (±z) and one on the side, whose normal is radial; the patches are the ones
    trimesh.graph.smooth_shade makes (the same vertex count) on a gear."""
    import trimesh

    box = manifold3d.Manifold.cube([2.0, 3.0, 4.0]).to_mesh()
    v, n, f = gltf.creased_normals(box.vert_properties[:, :3], box.tri_verts)
    assert len(v) == 24
    assert np.allclose(np.abs(n).max(axis=1), 1.0) and np.allclose(np.abs(n).sum(axis=1), 1.0)
    r, h, sides = 5.0, 2.0, 64
    cyl = manifold3d.Manifold.cylinder(h, r, r, sides).to_mesh()
    v, n, f = gltf.creased_normals(cyl.vert_properties[:, :3], cyl.tri_verts)
    ring = np.isclose(np.hypot(v[:, 0], v[:, 1]), r)
    cap = np.isclose(np.abs(n[:, 2]), 1.0)
    side = ring & ~cap
    assert side.sum() == 2 * sides and (ring & cap).sum() == 2 * sides
    radial = v[side, :2] / r
    assert np.allclose(n[side, 2], 0.0, atol=1e-12) and np.allclose(n[side, :2], radial, atol=1e-9)
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0)
    # every face's corners keep its winding and its own side
    tri = v[f]
    face = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    assert (np.einsum("ij,ij->i", face, n[f[:, 0]]) > 0).all()
    from partgen.design import involute
    pts = np.asarray(involute.gear_outline(23, 2.0, math.radians(20)).points)[:, :2]
    gear = manifold3d.Manifold.extrude(manifold3d.CrossSection([pts]) - manifold3d.CrossSection.circle(5.0, 64), 6.0).to_mesh()
    gv, gf = gear.vert_properties[:, :3], gear.tri_verts
    v, n, f = gltf.creased_normals(gv, gf)
    ref = trimesh.graph.smooth_shade(trimesh.Trimesh(gv, gf, process=False), angle=math.radians(gltf.CREASE_DEG))
    assert len(v) == len(ref.vertices)
