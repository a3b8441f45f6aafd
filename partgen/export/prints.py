"""What a kit prints: its printed parts grouped by identical STL (made once per kit and shared by
check, report and the bill), the STLs of a kit folder that differ from them, and the build plates
(layout, 3MF per plate, picture). Knows only the Kit protocol."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from ..core.findings import Finding, Result
from ..core.protocol import Kit
from .kit import PrintedPart, laid_groups, printed

__all__ = ["printed_groups", "stale_files", "stale_finding", "plan_plates", "plates_png", "plate_pngs",
           "write_plate_files", "too_large"]

_GROUPS: dict = {}  # id(kit) -> (kit, its printed parts grouped): one kit at a time


def printed_groups(kit: Kit) -> list[list[PrintedPart]]:
    """The kit's printed parts laid on the plate and grouped by identical STL, made once per kit."""
    if id(kit) not in _GROUPS or _GROUPS[id(kit)][0] is not kit:
        _GROUPS.clear()
        _GROUPS[id(kit)] = (kit, laid_groups(kit))
    return _GROUPS[id(kit)][1]


def stale_files(kit: Kit, kit_dir: Path) -> list[str]:
    """The STLs of ``kit_dir`` missing or different (byte for byte) from what the kit prints."""
    return [f"{g[0].part.name}.stl" for g in printed_groups(kit) if not (kit_dir / f"{g[0].part.name}.stl").is_file()
            or (kit_dir / f"{g[0].part.name}.stl").read_bytes() != g[0].stl]


def stale_finding(kit: Kit, kit_dir: Path) -> Finding | None:
    """A failed finding if the STLs of ``kit_dir`` are not what ``kit`` prints (None if they are)."""
    stale = stale_files(kit, kit_dir)
    if not stale:
        return None
    return Finding("kit", "fail", f"{len(stale)} STL files in {kit_dir} are missing or differ from what its design.yaml "
                   f"builds ({', '.join(stale[:4])}{' …' if len(stale) > 4 else ''}): rebuild it",
                   tuple(s[:-4] for s in stale))


def too_large(kit: Kit, margin: float) -> list[tuple[object, np.ndarray]]:
    """The printed parts that print on the printer in no way: [(part, its extents sorted (3,) mm)].
    A part prints when it fits the envelope in some axis order (``geometry.measure.oversize``), or
    when, laid as the kit prints it, it fits the bed at some turn about z (``plates.fits_plate``,
    ``margin`` / 2 from the edge: a long link on the diagonal, as the plates place it) and is no
    taller than the envelope's height."""
    from ..geometry.measure import oversize

    env = kit.printer.envelope
    out = []
    for part, ext in oversize(kit.parts, env):
        from .plates import fits_plate  # only for a part larger than the envelope (plates: ~10 ms to import)

        mesh = printed(part, kit.printer).mesh
        tall = float(np.ptp(np.asarray(mesh.vertices)[:, 2]))
        if tall <= env[2] + 1e-9 and fits_plate(mesh, (env[0], env[1]), margin):
            continue
        out.append((part, ext))
    return out


def plan_plates(kit: Kit, margin: float, result: Result):
    """Pack the printed parts on build plates (``margin`` mm between them); a finding in ``result``
    if one cannot fit. Returns the layout (or None), the meshes by name and a function that draws
    the layout to a PNG path."""
    from .plates import footprint, layout, plate_picture

    groups = printed_groups(kit)
    env = kit.printer.envelope
    meshes = {g[0].part.name: g[0].mesh for g in groups}
    items = [(g[0].part.name, g[0].mesh, len(g)) for g in groups]
    edge = max(0.0, getattr(kit.printer, "plate_edge", 0.0) - margin / 2)  # beyond the margin's half the packer keeps
    try:
        lay = _inset(layout(items, (env[0] - 2 * edge, env[1] - 2 * edge), margin), edge, (env[0], env[1]))
    except ValueError:
        try:  # a part too large for the room a skirt needs still prints: on the whole bed, and we say so
            lay = layout(items, (env[0], env[1]), margin)
        except ValueError as e:
            result.add(Finding("printability", "fail", f"build plates: {e}", getattr(e, "parts", ())))
            return None, meshes, None
        result.add(Finding("printability", "info", f"build plates: a part leaves less than the "
                           f"{kit.printer.plate_edge:g} mm the slicer's skirt or brim needs from the bed's edge "
                           "(the printer profile's plate_edge_mm): print it without a skirt, or with the skirt closer"))
        edge = 0.0
    result.figures["plates"] = len(lay.plates)
    result.figures["plate_edge_mm"] = edge + margin / 2  # the least room from a part to the bed's edge

    def picture(path):
        plate_picture(lay, {n: footprint(m, margin) for n, m in meshes.items()}, path,
                      f"{kit.name}: {len(lay.plates)} build plate(s), {env[0]:g} × {env[1]:g} mm")
    return lay, meshes, picture


def _inset(lay, edge: float, size: tuple[float, float]):
    """A layout packed on a bed made ``edge`` mm smaller on every side, moved onto the whole bed."""
    from dataclasses import replace

    return replace(lay, size=size, plates=tuple(tuple(replace(p, x=p.x + edge, y=p.y + edge) for p in plate)
                                                for plate in lay.plates))


def plates_png(kit: Kit, margin: float, result: Result) -> bytes | None:
    """The build plates' picture as PNG bytes (None if the parts do not fit; ``result`` then says so)."""
    _, _, picture = plan_plates(kit, margin, result)
    if picture is None:
        return None
    with tempfile.TemporaryDirectory() as tmp:
        picture(Path(tmp) / "plates.png")
        return (Path(tmp) / "plates.png").read_bytes()


def plate_pngs(kit: Kit, margin: float, result: Result) -> list[bytes] | None:
    """One picture per build plate, each at the width the report shows it (``plates.PLATE_PX``), as
    PNG bytes (None if the parts do not fit; ``result`` then says so)."""
    from .plates import footprint, plate_pictures

    lay, meshes, _ = plan_plates(kit, margin, result)
    if lay is None:
        return None
    env = kit.printer.envelope
    return plate_pictures(lay, {n: footprint(m, margin) for n, m in meshes.items()},
                          f"{kit.name} on the {kit.printer.name}: {env[0]:g} × {env[1]:g} mm")


def write_plate_files(folder: Path, kit: Kit, lay, meshes: dict, picture) -> None:
    """plate<i>.3mf for every plate of ``lay`` and plates.png, into ``folder``."""
    from .plates import plate_3mf

    pr, n = kit.printer, len(lay.plates)
    for i, plate in enumerate(lay.plates, 1):
        (folder / f"plate{i}.3mf").write_bytes(plate_3mf(plate, meshes, kit.name, kit.material,
                                                         f"build plate {i} of {n} for the {pr.name} "
                                                         f"({lay.size[0]:g} x {lay.size[1]:g} mm)"))
    picture(folder / "plates.png")
