"""Write a kit: one binary STL per distinct part in its print orientation, manifest.json, and the
assembly (GLB, animated over the mechanism's motion: ``export.gltf``) — all or nothing (built in a
temporary folder, then moved)."""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core.background import SharedMap
from ..core.protocol import Kit, Motion
from ..geometry.parts import Part
from ..errors import MeshError
from ..geometry.compensate import compensate
from ..geometry.solid import mesh_arrays, print_arrays
from . import gltf
from .gltf import Instance
from .outputs import OutputClaim, atomic_dir
from .stl import Mesh, stl_bytes, stored_mesh
from .verify import MeshReport, mesh_report, read_stl

__all__ = ["PrintedPart", "printed", "group_parts", "laid_groups", "glb_instances", "manifest", "built_with", "verify_parts", "stl_report", "write_kit", "atomic_dir"]


@dataclass(frozen=True)
class PrintedPart:
    """A part as printed: its STL bytes, the mesh read back from them and local-from-print pose."""

    part: Part
    stl: bytes
    mesh: Mesh
    local_from_print: np.ndarray


_COMPENSATED: dict = {}  # (id(solid), biases) -> (solid, compensated solid or None): one kit's parts at a time


def biases(printer) -> tuple[float, float, float] | None:
    """(hole, pin, outline) biases (mm, as a diameter) ``build`` compensates for a printer profile,
    or None when it compensates nothing (no biases measured, or ``compensate: false``)."""
    if printer is None or not getattr(printer, "compensate", False):
        return None
    b = (printer.hole_bias, printer.pin_bias, printer.outline_bias)
    return b if any(b) else None


def compensated(part: Part, printer) -> tuple[object, bool | None]:
    """The solid a part is printed from: compensated for the printer's biases
    (``geometry.compensate``), and whether it was (None: nothing to compensate; False: the part is
    not a stack of z-prisms and is printed as designed)."""
    b = biases(printer)
    if b is None:
        return part.solid, None
    key = (id(part.solid), b)
    if key not in _COMPENSATED or _COMPENSATED[key][0] is not part.solid:
        if len(_COMPENSATED) > 256:
            _COMPENSATED.clear()
        _COMPENSATED[key] = (part.solid, compensate(part.solid, *b))
    got = _COMPENSATED[key][1]
    return (part.solid, False) if got is None else (got, True)


def printed(part: Part, printer=None) -> PrintedPart:
    """Lay a part on the build plate (flipped if it prints upside down, lowest point at z = 0),
    compensated for ``printer``'s measured biases when its profile asks for it."""
    solid, _ = compensated(part, printer)
    v, f, print_from_local = print_arrays(solid, part.print_flip)
    # the mesh exactly as the STL stores it (float32), so the manifest describes the file
    mesh = stored_mesh(v, f)
    return PrintedPart(part, stl_bytes(mesh), mesh, np.linalg.inv(print_from_local))


def group_parts(items: list[PrintedPart]) -> list[list[PrintedPart]]:
    """Identical STLs (same bytes) are one distinct part printed ``count`` times; first-seen order."""
    groups: dict[str, list[PrintedPart]] = {}
    for it in items:
        groups.setdefault(hashlib.sha256(it.stl).hexdigest(), []).append(it)
    return list(groups.values())


def _r(x, nd=6):
    return float(round(float(x), nd))


def _gear_entry(part: Part) -> dict:
    g = part.gear
    s = g.system
    return {
        "teeth": g.teeth,
        "module_mm": s.module,
        "pressure_angle_deg": _r(math.degrees(s.pressure_angle), 9),
        "profile_shift": _r(g.profile_shift, 9),
        "tooth_thickness_mm": _r(g.tooth_thickness, 9),
        "tip_diameter_mm": _r(2 * g.tip_radius, 9),
        "root_diameter_mm": _r(2 * g.root_radius, 9),
        "backlash_per_gear_mm": s.backlash_per_gear,
        "undercut": bool(g.undercut),
        "clocking_deg": _r(math.degrees(part.clocking), 6),
    }


def manifest(kit: Kit, groups: list[list[PrintedPart]], design: dict) -> dict:
    """The manifest of a kit: {"design": ..., "parts": [...]}; placements at rest (motion parameter 0).
    Per part: its mass printed solid (``mass_g``) and as printed (``printed_mass_g``: the kit's own
    print model, e.g. infill, or solid), and the centre of mass of its STL (``centre_of_mass_mm``, in
    the STL's frame, solid). See docs/manifest.schema.json."""
    poses = kit.poses(0.0)
    density = kit.density
    model = getattr(kit, "printed_mass", None)  # a kit that models its print (infill) says what a part weighs

    def printed_mass(name: str, solid_g: float) -> float:
        got = model(name) if model else None
        return solid_g if got is None else got
    parts = []
    for grp in groups:
        first = grp[0]
        m = first.mesh
        entry = {
            "name": first.part.name,
            "role": first.part.role,
            "count": len(grp),
            "instances": [it.part.name for it in grp],
            "file": f"{first.part.name}.stl",
            "triangles": int(len(m.faces)),
            "volume_mm3": _r(m.volume, 4),
            "mass_g": _r(m.volume * density, 4),
            "printed_mass_g": _r(printed_mass(first.part.name, m.volume * density), 4),
            "centre_of_mass_mm": [_r(c, 4) for c in m.center_mass],
            "bbox_mm": [_r(x, 4) for x in m.extents],
            "print_flip": first.part.print_flip,
            "placement": [[[_r(x, 9) for x in row] for row in poses[it.part.name] @ it.local_from_print] for it in grp],
        }
        if first.part.gear is not None:
            entry["gear"] = _gear_entry(first.part)
        parts.append(entry)
    return {"design": design, "parts": parts, "built_with": built_with()}


# the versions a manifest records: the libraries whose arithmetic makes the parts (numpy, manifold3d, shapely), and
# trimesh and scipy, kept so every manifest has one shape (export.stl writes STLs as trimesh does, held equal to it
# by tests/export/test_manifest_schema.py; build imports neither)
BUILT_WITH = ("numpy", "manifold3d", "shapely", "trimesh", "scipy")


def built_with() -> dict[str, str]:
    """The versions that build a kit (the manifest's ``built_with``): partgen, Python and
    ``BUILT_WITH``. A kit's choices and dimensions do not depend on them; its STL bytes may."""
    import platform
    from importlib.metadata import PackageNotFoundError, version

    from .. import __version__

    out = {"partgen": __version__, "python": platform.python_version()}
    for name in BUILT_WITH:
        try:
            out[name] = version(name)
        except PackageNotFoundError:  # pragma: no cover - every one is a dependency
            out[name] = "unknown"
    return out


def assembly_glb(kit: Kit, groups: list[list[PrintedPart]], bought: list[Part] = (), motion: Motion | None = None,
                 colours: dict[str, str] | None = None) -> bytes:
    """The GLB of every part (``export.gltf``: metres, Y up, one mesh per distinct STL instanced by
    its nodes, coloured by role), bought parts included; animated over ``motion`` when given."""
    return gltf.assembly_glb(kit, glb_instances(groups, bought), motion, colours)


def glb_instances(groups: list[list[PrintedPart]], bought: list[Part] = ()) -> list[Instance]:
    """The GLB's nodes: every bought part (as modelled) and every printed part (its STL's mesh)."""
    instances, solids = [], {}
    for p in bought:
        if id(p.solid) not in solids:
            v, f = mesh_arrays(p.solid)
            solids[id(p.solid)] = Mesh(v, f)
        instances.append(Instance(p, solids[id(p.solid)], np.eye(4)))
    for grp in groups:
        for it in grp:
            instances.append(Instance(it.part, grp[0].mesh, it.local_from_print))
    return instances


def verify_parts(groups: list[list[PrintedPart]], design_name: str, reports: list | None = None) -> None:
    """Read every distinct STL back as a slicer does (export.verify) and raise ``MeshError``, naming
    the design and each bad part, unless every one is a single closed, oriented manifold shell
    (``reports``: each group's ``stl_report``, when the caller has them already)."""
    bad = []
    for g, report in zip(groups, reports if reports is not None else map(stl_report, groups)):
        if not report.ok:
            bad.append(f"{g[0].part.name} ({', '.join(report.problems())})")
    if bad:
        raise MeshError(f"design {design_name}: {len(bad)} part(s) would be written as a mesh that is not one closed, "
                        f"oriented manifold shell: {'; '.join(bad)} — a bug in partgen; nothing was written")


def stl_report(group: list[PrintedPart]) -> MeshReport:
    """What a slicer reads in a distinct part's STL (``export.verify``)."""
    return mesh_report(*read_stl(group[0].stl))


def write_kit(kit: Kit, dest: Path | OutputClaim, design: dict, extra_files: dict[str, bytes] | None = None,
              progress=None, motion: Motion | None = None, colours: dict[str, str] | None = None) -> dict:
    """Write the kit into ``dest`` (a folder, or an ``OutputClaim`` checked before the build)
    atomically; returns the manifest. Every distinct STL is verified first (``verify_parts``): a bad
    part raises ``MeshError`` and nothing is written. ``motion`` animates assembly.glb over the
    mechanism's input; ``colours`` (role -> '#rrggbb') colour its parts."""
    groups = laid_groups(kit, progress)
    bought = [p for p in kit.parts if not p.printed]
    instances = glb_instances(groups, bought)
    distinct = gltf.distinct_meshes(instances)
    # the independent pieces of work — assembly.glb's motion and shaded meshes, each STL's report —
    # shared with a forked child (core.background, from the front) while the manifest is made here
    first = [("motion", None)] if motion is not None else []
    work = first + [("shade", m) for m in distinct] + [("verify", g) for g in groups]
    with SharedMap(lambda item: _piece(kit, instances, motion, *item), work) as made:
        man = _manifest_of(kit, groups, design, bought)
        got = made.results()
    sampling = got[0] if first else None
    meshes, reports = got[len(first):len(first) + len(distinct)], got[len(first) + len(distinct):]
    verify_parts(groups, str(design.get("name", kit.name)), reports)
    files = {f"{g[0].part.name}.stl": g[0].stl for g in groups}
    files["manifest.json"] = (json.dumps(man, indent=1, allow_nan=False) + "\n").encode()
    files["assembly.glb"] = gltf.assembly_glb(kit, instances, motion, colours, shaded_meshes=meshes, sampling=sampling)
    files.update(extra_files or {})
    with atomic_dir(dest) as tmp:
        for name, data in files.items():
            (tmp / name).write_bytes(data)
    return man


def laid_groups(kit: Kit, progress=None) -> list[list[PrintedPart]]:
    """Every printed part laid on the plate (``printed``; parts sharing a solid once), grouped by
    identical STL; ``progress(name)`` as each is laid."""
    say = progress or (lambda name: None)
    items, done = [], {}
    for p in (p for p in kit.parts if p.printed):
        say(p.name)
        key = (id(p.solid), p.print_flip)  # parts sharing a solid are laid on the plate once
        if key not in done:
            done[key] = printed(p, kit.printer)
        items.append(PrintedPart(p, done[key].stl, done[key].mesh, done[key].local_from_print))
    return group_parts(items)


def _piece(kit: Kit, instances: list[Instance], motion: Motion | None, what: str, item):
    """One piece of write_kit's work: the GLB's motion, a shaded mesh, or an STL's report."""
    if what == "motion":
        return gltf.sample_motion(kit, instances, motion)
    return gltf.shaded(item) if what == "shade" else stl_report(item)


def _manifest_of(kit: Kit, groups: list[list[PrintedPart]], design: dict, bought: list[Part]) -> dict:
    """The manifest, with what was compensated and the purchased parts."""
    b = biases(kit.printer)
    if b is not None:  # say what was compensated, and what was printed as designed
        state = {p.name: compensated(p, kit.printer)[1] for p in kit.parts if p.printed}
        design = {**design, "compensation": {
            "hole_diametral_mm": b[0], "pin_diametral_mm": b[1], "outline_diametral_mm": b[2],
            "what": "holes opened by -hole/2, round outer contours (pins, posts, bosses) trimmed by pin/2, "
                    "other outer contours (teeth, plates) by outline/2, in every z-slab",
            "compensated": sorted(n for n, s in state.items() if s),
            "as_designed": sorted(n for n, s in state.items() if not s)}}
    man = manifest(kit, groups, design)
    if bought:
        man["purchased"] = [{"name": p.name, "role": p.role, **dict(p.info)} for p in bought]
    return man
