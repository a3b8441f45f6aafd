"""The report page of a kit: the mechanism's own sections with the shared ones put in — the bill of
parts with pictures and what to buy, the assembly steps, a tolerance study's result when one was
made of this very design, and the build plates. Knows only the Kit and Mechanism protocols."""

from __future__ import annotations

from ..core.findings import Result
from ..core.protocol import Kit, Mechanism, Trace
from . import report as R
from .assembly import steps_of
from .bill import bill_sections
from .gltf import motion_of
from .prints import printed_groups
from .studies import tolerance_section
from .viewer import viewer_section

__all__ = ["kit_page", "plates_section"]


def png_size(data: bytes) -> tuple[int, int]:
    """(width, height) in pixels of PNG bytes (its IHDR chunk)."""
    import struct

    return struct.unpack(">II", data[16:24])


def plates_section(pictures: list[bytes] | bytes, result: Result) -> tuple[str, str]:
    """("Build plates", html): each plate's picture on its own, shown at its own pixel width (the
    page's column is wider than the pictures: nothing is shrunk)."""
    pictures = [pictures] if isinstance(pictures, bytes) else list(pictures)
    n = len(pictures)
    figs = "".join(f"<figure>{R.img(png, f'build plate {i} of {n}', width=png_size(png)[0])}"
                   f"<figcaption>Build plate {i} of {n} (plate{i}.3mf).</figcaption></figure>"
                   for i, png in enumerate(pictures, 1))
    return ("Build plates", f"<p>{result.figures.get('plates', n)} build plate(s); `partgen check` writes their "
                            f"3MF files.</p>{figs}")


def kit_page(mech: Mechanism, spec, kit: Kit, result: Result, trace: Trace, files: dict[str, bytes],
             plates_png: bytes | None, tolerance: dict | None, glb: bytes | None = None,
             links: list[tuple[str, str]] = ()) -> str:
    """The whole HTML page: ``files`` are the trace's figures by name, ``plates_png`` the build
    plates' pictures (one per plate), ``tolerance`` the saved result of `partgen tolerance` (or None), ``glb`` the
    kit's animated assembly, shown first in the interactive 3-D view (``export.viewer``), ``links``
    (name, href) the kit's files, linked under it."""
    purchased = [p for p in kit.parts if not p.printed]
    sections = mech.report_sections(spec, kit, result, trace, files)
    own = {title for title, _ in sections}  # a mechanism's own bill (e.g. masses as sliced) stands
    sections[1:1] = [x for x in bill_sections(kit, mech.role_colours, purchased, printed_groups(kit),
                                              steps_of(mech, spec, kit)) if x[0] not in own]
    if tolerance is not None:
        sections.append(tolerance_section(tolerance))
    if plates_png:
        sections.append(plates_section(plates_png, result))
    if glb is not None:
        groups = printed_groups(kit)
        rows = {it.part.name: grp[0].part.name for grp in groups for it in grp}
        frames = {it.part.name: it.local_from_print for grp in groups for it in grp}
        sections.insert(0, viewer_section(glb, kit, motion_of(mech, spec, kit), result, rows, frames, links))
    return R.page(f"partgen report: {kit.name}", sections, mech.subtitle(spec))
