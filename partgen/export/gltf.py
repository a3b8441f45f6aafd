"""The kit's assembly as a binary glTF 2.0 (GLB) that standard viewers open the right way up and play.

What a viewer gets:

* **Units and axes.** Vertices stay in millimetres, as the STLs have them; one root node
  (``assembly``) scales by 0.001 (glTF counts metres) and turns the kit's Z-up world into glTF's
  Y-up one (−90° about x).
* **Meshes.** One mesh per distinct solid (a part the kit prints several times — the same STL — is
  one mesh that several nodes use), each with normals: faces meeting at a sharp edge (over
  ``CREASE_DEG``) get their own vertices, so flats stay flat and involute flanks stay smooth.
* **Materials.** One PBR material per role, coloured by the mechanism's role colours (the report's
  bill uses the same); a role without one takes the next colour of a fixed palette in kit order.
* **Motion.** One animation, ``motion``, over the mechanism's input (``Motion``: label, unit,
  range): an input that makes a whole turn plays forward over it once (``turn``); any other range
  is played out and back (``out_and_back``), so the loop has no jump. Each part whose placement
  changes has its node keyed (translation and/or rotation, LINEAR; a rotation key's quaternion
  keeps the sign of the one before, so viewers interpolate the short way, which is the way the part
  goes); parts that stay put have no channel. The animation's ``extras`` say the input's label,
  unit, range, mode, and the sampling's figures.
* **Sampling rule.** Keys are evenly spaced in the input; their number is doubled (from
  ``MIN_KEYS``) until, at the middle of every key interval, no point of any part lies more than
  ``MAX_ERROR_MM`` from where the mechanism puts it (bound: the translation's error plus the
  rotation's error angle times the part's radius about its node's origin). Two gears turning about
  fixed axes are interpolated exactly (slerp about one axis is the turn at a steady rate); the
  rule bounds what the chord of a link's arc or a planet's orbit adds, so teeth mesh between keys
  without a visible overlap (``MAX_ERROR_MM`` is well under every design's least clearance).

Written with numpy (trimesh's exporter writes no animation); checked by the Khronos glTF
validator in the tests.
"""

from __future__ import annotations

import json
import math
import struct
from dataclasses import dataclass

import numpy as np

from ..core.background import SharedMap
from ..core.parts import Part
from ..core.protocol import Kit, Motion
from ..design.graph import components
from .stl import Mesh

__all__ = ["MAX_ERROR_MM", "MIN_KEYS", "MAX_KEYS", "CREASE_DEG", "Instance", "assembly_glb", "distinct_meshes", "shaded",
           "read_glb",
           "role_palette", "Sampling", "sample_motion", "motion_of"]

MAX_ERROR_MM = 0.05      # the farthest any point may stray from its true place between two keys
MIN_KEYS = 64            # keys over the input's range, at least
MAX_KEYS = 4096          # and at most (a design that needs more says so in the animation's extras)
CREASE_DEG = 30.0        # faces meeting at more than this get split normals (a sharp edge)
TURN_SECONDS = 8.0       # one whole turn of the input plays in this long; out-and-back: there in half
PALETTE = ("#4c78a8", "#f58518", "#54a24b", "#e45756", "#72b7b2", "#eeca3b", "#b279a2", "#ff9da6", "#9d755d",
           "#bab0ac")
UP_Y = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]  # (x, y, z, w): −90° about x, Z up → Y up

_FLOAT, _UINT16, _UINT32 = 5126, 5123, 5125
_ARRAY_BUFFER, _ELEMENT_ARRAY_BUFFER = 34962, 34963


@dataclass(frozen=True)
class Instance:
    """One node of the assembly: the part, its mesh (vertices in the node's frame, mm), and the
    node-from-part-local transform (the printed STL's frame is the node's: ``local_from_print``)."""

    part: Part
    mesh: Mesh
    local_from_mesh: np.ndarray


def role_palette(roles, colours: dict[str, str] | None) -> dict[str, str]:
    """role -> '#rrggbb': the mechanism's colour of each role; the other roles take the palette's
    colours the mechanism does not use, in the order the roles come."""
    colours = dict(colours or {})
    free = [c for c in PALETTE if c not in colours.values()] or list(PALETTE)
    out: dict[str, str] = {}
    extra = 0
    for r in roles:
        if r not in out:
            if r in colours:
                out[r] = colours[r]
            else:
                out[r] = free[extra % len(free)]
                extra += 1
    return out


def _linear(hex_colour: str) -> list[float]:
    """sRGB '#rrggbb' -> linear RGBA (glTF's baseColorFactor is linear)."""
    c = [int(hex_colour[i:i + 2], 16) / 255.0 for i in (1, 3, 5)]
    return [round(x / 12.92 if x <= 0.04045 else ((x + 0.055) / 1.055) ** 2.4, 6) for x in c] + [1.0]


# -- rigid transforms ---------------------------------------------------------------------------------------

def _quat(r: np.ndarray) -> np.ndarray:
    """(N, 3, 3) rotation matrices -> (N, 4) unit quaternions (x, y, z, w), by the largest of the four
    candidates (w, x, y or z) so no division is near zero."""
    r = np.asarray(r, dtype=np.float64)
    m00, m11, m22 = r[:, 0, 0], r[:, 1, 1], r[:, 2, 2]
    cand = np.stack([1 + m00 + m11 + m22, 1 + m00 - m11 - m22, 1 - m00 + m11 - m22, 1 - m00 - m11 + m22], 1)
    pick = np.argmax(cand, axis=1)
    s = 2 * np.sqrt(np.maximum(cand[np.arange(len(r)), pick], 1e-300))
    d21, d02, d10 = r[:, 2, 1] - r[:, 1, 2], r[:, 0, 2] - r[:, 2, 0], r[:, 1, 0] - r[:, 0, 1]
    s21, s02, s10 = r[:, 2, 1] + r[:, 1, 2], r[:, 0, 2] + r[:, 2, 0], r[:, 1, 0] + r[:, 0, 1]
    q = np.where((pick == 0)[:, None], np.stack([d21 / s, d02 / s, d10 / s, s / 4], 1),
        np.where((pick == 1)[:, None], np.stack([s / 4, s10 / s, s02 / s, d21 / s], 1),
        np.where((pick == 2)[:, None], np.stack([s10 / s, s / 4, s21 / s, d02 / s], 1),
                 np.stack([s02 / s, s21 / s, s / 4, d10 / s], 1))))
    q = np.where((q[:, 3] < 0)[:, None], -q, q)  # w ≥ 0
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def _continuous(q: np.ndarray) -> np.ndarray:
    """Flip signs so each quaternion is on the side of the one before (slerp takes the short way)."""
    if len(q) < 2:
        return q.copy()
    step = np.where(np.einsum("ij,ij->i", q[1:], q[:-1]) < 0, -1.0, 1.0)  # each key against the one before, as given
    return q * np.r_[1.0, np.cumprod(step)][:, None]  # a flip carries on to every key after it


def _rot_angle(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angle (rad) of the rotation between (…, 3, 3) rotations a and b."""
    c = (np.einsum("...ij,...ij->...", a, b) - 1.0) / 2.0
    return np.arccos(np.clip(c, -1.0, 1.0))


def _slerp_mid(qa: np.ndarray, qb: np.ndarray) -> np.ndarray:
    """The quaternion halfway between (…, 4) qa and qb, the short way (as viewers interpolate)."""
    qb = np.where((np.sum(qa * qb, axis=-1) < 0)[..., None], -qb, qb)
    m = qa + qb
    return m / np.linalg.norm(m, axis=-1, keepdims=True)


def _matrix(q: np.ndarray) -> np.ndarray:
    """(…, 4) quaternions (x, y, z, w) -> (…, 3, 3) rotation matrices."""
    x, y, z, w = np.moveaxis(q, -1, 0)
    return np.stack([np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
                     np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
                     np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1)], -2)


# -- the motion ---------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Sampling:
    """The keys of the animation: ``inputs`` (the motion parameter at each key, in order of time),
    ``times`` (s), node transforms ``poses`` (K, P, 4, 4), the mode, and the figures of the rule."""

    inputs: np.ndarray
    times: np.ndarray
    poses: np.ndarray
    mode: str
    keys: int  # keys over the range one way
    max_error_mm: float  # the largest mid-interval error found
    max_step_mm: float  # the farthest any point moves from one key to the next


def motion_of(mechanism, spec, kit: Kit) -> Motion:
    """The input a kit's assembly animates over: the mechanism's ``animation_motion(spec, kit)``
    where it has one, else its ``motion``."""
    own = getattr(mechanism, "animation_motion", None)
    return own(spec, kit) if callable(own) else mechanism.motion


def _node_poses(kit: Kit, instances: list[Instance], us: np.ndarray) -> np.ndarray:
    poses = kit.poses_over(np.asarray(us, dtype=float))
    return np.stack([poses[it.part.name] @ it.local_from_mesh for it in instances], axis=1)


def sample_motion(kit: Kit, instances: list[Instance], motion: Motion, max_error_mm: float = MAX_ERROR_MM,
                  min_keys: int = MIN_KEYS, max_keys: int = MAX_KEYS) -> Sampling:
    """The keys over ``motion``'s range by the sampling rule (module docstring)."""
    lo, hi = (float(x) for x in motion.range)
    turn = motion.unit == "rad" and abs(abs(hi - lo) - 2 * math.pi) < 1e-9
    radius = np.array([float(np.max(np.linalg.norm(it.mesh.vertices, axis=1))) if len(it.mesh.vertices) else 0.0
                       for it in instances])
    n = max(2, int(min_keys))
    cache: dict[float, np.ndarray] = {}

    def at(us: np.ndarray) -> np.ndarray:
        todo = [u for u in us if float(u) not in cache]
        if todo:
            got = _node_poses(kit, instances, np.array(todo))
            for u, p in zip(todo, got):
                cache[float(u)] = p
        return np.stack([cache[float(u)] for u in us])

    while True:
        us = np.linspace(lo, hi, n + 1)
        keys = at(us)
        mids = at((us[:-1] + us[1:]) / 2)
        q = _quat(keys[..., :3, :3].reshape(-1, 3, 3)).reshape(len(us), len(instances), 4)
        r_mid = _matrix(_slerp_mid(q[:-1], q[1:]))
        t_mid = (keys[:-1, :, :3, 3] + keys[1:, :, :3, 3]) / 2
        err = (np.linalg.norm(t_mid - mids[..., :3, 3], axis=-1)
               + _rot_angle(r_mid, mids[..., :3, :3]) * radius)
        worst = float(err.max()) if err.size else 0.0
        if worst <= max_error_mm or n >= max_keys:
            break
        n *= 2
    step = (np.linalg.norm(keys[1:, :, :3, 3] - keys[:-1, :, :3, 3], axis=-1)
            + _rot_angle(keys[1:, :, :3, :3], keys[:-1, :, :3, :3]) * radius)
    span = TURN_SECONDS if turn else TURN_SECONDS / 2
    times = np.linspace(0.0, span, n + 1)
    if turn:
        return Sampling(us, times, keys, "turn", n, worst, float(step.max()) if step.size else 0.0)
    return Sampling(np.concatenate([us, us[-2::-1]]), np.concatenate([times, span + times[1:]]),
                    np.concatenate([keys, keys[-2::-1]]), "out_and_back", n, worst,
                    float(step.max()) if step.size else 0.0)


# -- writing ------------------------------------------------------------------------------------------------

class _Bin:
    """The binary chunk and its buffer views / accessors as they are added."""

    def __init__(self):
        self.chunks: list[bytes] = []
        self.size = 0
        self.views: list[dict] = []
        self.accessors: list[dict] = []

    def add(self, data: np.ndarray, kind: str, ctype: int, target: int | None = None, minmax: bool = False) -> int:
        raw = np.ascontiguousarray(data).tobytes()
        view = {"buffer": 0, "byteOffset": self.size, "byteLength": len(raw)}
        if target is not None:
            view["target"] = target
        self.chunks.append(raw)
        pad = (-len(raw)) % 4
        if pad:
            self.chunks.append(b"\0" * pad)
        self.size += len(raw) + pad
        self.views.append(view)
        acc = {"bufferView": len(self.views) - 1, "componentType": ctype, "count": int(len(data)), "type": kind}
        if minmax:
            acc["min"] = [float(x) for x in np.min(data, axis=0).reshape(-1)]
            acc["max"] = [float(x) for x in np.max(data, axis=0).reshape(-1)]
        self.accessors.append(acc)
        return len(self.accessors) - 1


def creased_normals(vertices: np.ndarray, faces: np.ndarray, crease_deg: float = CREASE_DEG
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split normals at the creases: faces joined across an edge whose normals differ by less than
    ``crease_deg`` form one smooth patch (connected components over such edges, as
    ``trimesh.graph.smooth_shade`` makes them, in numpy: ``design.graph.components``); each vertex
    gets one copy per patch round it, with the corner-angle weighted mean of that patch's face
    normals there. Returns vertices (n', 3) mm, unit normals (n', 3) and faces (m, 3) int64, for an
    edge-manifold mesh (vertices (n, 3), faces (m, 3))."""
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    m, nv = len(f), len(v)
    tri = v[f]
    fu = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    fu /= np.maximum(np.linalg.norm(fu, axis=1, keepdims=True), 1e-300)
    out_edge, in_edge = tri[:, [1, 2, 0]] - tri, tri[:, [2, 0, 1]] - tri  # the two edges at each corner
    cos_corner = np.einsum("ijk,ijk->ij", out_edge, in_edge) / np.maximum(
        np.linalg.norm(out_edge, axis=2) * np.linalg.norm(in_edge, axis=2), 1e-300)
    corner_angle = np.arccos(np.clip(cos_corner, -1.0, 1.0)).reshape(-1)
    a, b = f.reshape(-1), f[:, [1, 2, 0]].reshape(-1)
    face_of = np.repeat(np.arange(m), 3)
    key = np.minimum(a, b) * nv + np.maximum(a, b)
    order = np.argsort(key, kind="stable")
    shared = np.flatnonzero(key[order][1:] == key[order][:-1])  # an edge's two faces sit side by side
    f1, f2 = face_of[order[shared]], face_of[order[shared + 1]]
    smooth = np.einsum("ij,ij->i", fu[f1], fu[f2]) >= math.cos(math.radians(crease_deg))
    patch = components(m, f1[smooth], f2[smooth])
    uniq, corner_vertex = np.unique(patch[face_of] * nv + a, return_inverse=True)
    w = fu[face_of] * corner_angle[:, None]
    nrm = np.stack([np.bincount(corner_vertex, weights=w[:, i], minlength=len(uniq)) for i in range(3)], axis=1)
    nrm /= np.maximum(np.linalg.norm(nrm, axis=1, keepdims=True), 1e-300)
    return v[uniq % nv], nrm, corner_vertex.reshape(m, 3)


def shaded(mesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A mesh as the GLB stores it: vertices, normals split at the creases, triangles (float32, uint)."""
    v, nrm, f = creased_normals(mesh.vertices, mesh.faces)
    return v.astype(np.float32), nrm.astype(np.float32), f.astype(np.uint16 if len(v) < 65535 else np.uint32)


def _trs(m: np.ndarray) -> tuple[list[float], list[float]]:
    return [float(x) for x in m[:3, 3]], [float(x) for x in _quat(m[None, :3, :3])[0]]


def distinct_meshes(instances: list[Instance]) -> list:
    """The instances' meshes, each once, in the order they first come (the GLB's meshes)."""
    return list({id(it.mesh): it.mesh for it in instances}.values())


def assembly_glb(kit: Kit, instances: list[Instance], motion: Motion | None = None,
                 colours: dict[str, str] | None = None, max_error_mm: float = MAX_ERROR_MM,
                 shaded_meshes: list | None = None, sampling: Sampling | None = None) -> bytes:
    """The GLB of the kit's ``instances`` (module docstring); animated over ``motion`` when given,
    else at rest (motion parameter 0). ``shaded_meshes`` (``shaded`` of each of ``distinct_meshes``)
    and ``sampling`` (``sample_motion``'s) when the caller has made them already."""
    for it in instances:
        r = it.local_from_mesh[:3, :3]
        if abs(np.linalg.det(r) - 1.0) > 1e-6:
            raise ValueError(f"{it.part.name}: its frame is not a rotation (det {np.linalg.det(r):.6g})")
    palette = role_palette([it.part.role for it in instances], colours)
    roles = list(dict.fromkeys(it.part.role for it in instances))
    materials = [{"name": role, "pbrMetallicRoughness": {"baseColorFactor": _linear(palette[role]),
                                                         "metallicFactor": 0.0, "roughnessFactor": 0.6}}
                 for role in roles]
    b = _Bin()
    meshes, mesh_of = [], {}
    distinct = distinct_meshes(instances)
    if shaded_meshes is None:
        with SharedMap(shaded, distinct) as job:  # shared with a forked child (core.background), as write_kit does
            shaded_meshes = job.results()
    shading = dict(zip(map(id, distinct), shaded_meshes))
    for it in instances:
        key = id(it.mesh)
        if key in mesh_of:
            continue
        v, nrm, f = shading[key]
        pos = b.add(v, "VEC3", _FLOAT, _ARRAY_BUFFER, minmax=True)
        nor = b.add(nrm, "VEC3", _FLOAT, _ARRAY_BUFFER)
        idx = b.add(f.reshape(-1), "SCALAR", _UINT16 if f.dtype == np.uint16 else _UINT32, _ELEMENT_ARRAY_BUFFER)
        mesh_of[key] = len(meshes)
        meshes.append({"name": it.part.name, "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nor},
                                                             "indices": idx, "mode": 4,
                                                             "material": roles.index(it.part.role)}]})
    if motion is not None:
        sampling = sampling or sample_motion(kit, instances, motion, max_error_mm)
        rest = sampling.poses[0]
    else:
        sampling = None
        poses = kit.poses(0.0)
        rest = np.stack([poses[it.part.name] @ it.local_from_mesh for it in instances])
    nodes = [{"name": "assembly", "children": list(range(1, len(instances) + 1)), "scale": [0.001] * 3,
              "rotation": UP_Y}]
    for i, it in enumerate(instances):
        t, q = _trs(rest[i])
        nodes.append({"name": it.part.name, "mesh": mesh_of[id(it.mesh)], "translation": t, "rotation": q,
                      "extras": {"role": it.part.role, "printed": bool(it.part.printed)}})
    gltf = {"asset": {"version": "2.0", "generator": "partgen"}, "scene": 0,
            "scenes": [{"name": kit.name, "nodes": [0]}], "nodes": nodes, "meshes": meshes, "materials": materials}
    anim = _animation(b, sampling, instances, motion) if sampling is not None else None
    if anim is not None:  # a kit where nothing moves has no animation (glTF allows no empty one)
        gltf["animations"] = [anim]
    gltf["buffers"] = [{"byteLength": b.size}]
    gltf["bufferViews"] = b.views
    gltf["accessors"] = b.accessors
    return _pack(gltf, b"".join(b.chunks))


def _animation(b: _Bin, s: Sampling, instances: list[Instance], motion: Motion) -> dict | None:
    time_acc = None
    samplers, channels = [], []
    for i, it in enumerate(instances):
        track = s.poses[:, i]
        t = track[:, :3, 3]
        moves_t = float(np.ptp(t, axis=0).max()) > 1e-9
        moves_r = float(_rot_angle(track[:, :3, :3], track[:1, :3, :3]).max()) > 1e-9
        if not (moves_t or moves_r):
            continue
        if time_acc is None:
            time_acc = b.add(s.times.astype(np.float32), "SCALAR", _FLOAT, minmax=True)
        if moves_t:
            samplers.append({"input": time_acc, "interpolation": "LINEAR",
                             "output": b.add(t.astype(np.float32), "VEC3", _FLOAT)})
            channels.append({"sampler": len(samplers) - 1, "target": {"node": i + 1, "path": "translation"}})
        if moves_r:
            q = _continuous(_quat(track[:, :3, :3])).astype(np.float32)
            samplers.append({"input": time_acc, "interpolation": "LINEAR", "output": b.add(q, "VEC4", _FLOAT)})
            channels.append({"sampler": len(samplers) - 1, "target": {"node": i + 1, "path": "rotation"}})
    if not channels:
        return None
    lo, hi = (float(x) for x in motion.range)
    return {"name": "motion", "samplers": samplers, "channels": channels,
            "extras": {"input_label": motion.label, "input_unit": motion.unit, "input_range": [lo, hi],
                       "mode": s.mode, "duration_s": float(s.times[-1]), "keys": s.keys,
                       "max_error_mm": round(s.max_error_mm, 6), "max_error_rule_mm": MAX_ERROR_MM,
                       "max_step_mm": round(s.max_step_mm, 4)}}


def _pack(gltf: dict, binary: bytes) -> bytes:
    js = json.dumps(gltf, separators=(",", ":"), allow_nan=False).encode()
    js += b" " * ((-len(js)) % 4)
    binary += b"\0" * ((-len(binary)) % 4)
    total = 12 + 8 + len(js) + (8 + len(binary) if binary else 0)
    out = [struct.pack("<4sII", b"glTF", 2, total), struct.pack("<I4s", len(js), b"JSON"), js]
    if binary:
        out += [struct.pack("<I4s", len(binary), b"BIN\0"), binary]
    return b"".join(out)


def read_glb(data: bytes) -> tuple[dict, bytes]:
    """(the glTF JSON, the binary chunk) of a GLB."""
    magic, version, total = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF" or version != 2 or total != len(data):
        raise ValueError("not a GLB 2.0")
    n, kind = struct.unpack_from("<I4s", data, 12)
    gltf = json.loads(data[20:20 + n])
    binary = b""
    off = 20 + n
    if off < len(data):
        m, _ = struct.unpack_from("<I4s", data, off)
        binary = data[off + 8:off + 8 + m]
    return gltf, binary
