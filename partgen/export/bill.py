"""The report's bill of parts for any kit: the assembly, each distinct printed part with its picture,
size, volume, mass and centre of mass (in its STL frame), and what to buy."""

from __future__ import annotations

import html

from ..core.protocol import Kit
from . import report as R
from .kit import group_parts, printed
from .render import render

__all__ = ["bill_sections"]


def bill_sections(kit: Kit, colours: dict[str, str], purchased: list[dict], groups=None) -> list[tuple[str, str]]:
    """[("Bill of parts", html)] and, when the kit has bought parts, [("Bought parts", html)];
    ``groups``: the kit's printed parts grouped (``export.kit.group_parts``), if made already."""
    groups = groups or group_parts([printed(p) for p in kit.parts if p.printed])
    colour = lambda role: colours.get(role, "#999")  # noqa: E731
    poses = kit.poses(0.0)
    scene = []
    for g in groups:
        for it in g:
            T = poses[it.part.name] @ it.local_from_print
            scene.append((g[0].mesh.vertices @ T[:3, :3].T + T[:3, 3], g[0].mesh.faces, colour(it.part.role)))
    assembly_png = render(scene, (1100, 720), elev=35, azim=-70)
    rows = []
    density = kit.density
    for g in groups:
        p, m = g[0].part, g[0].mesh
        pic = render([(m.vertices, m.faces, colour(p.role))], (300, 240))
        gear = p.gear
        com = m.center_mass if m.is_volume else m.centroid
        rows.append([R.img(pic, p.name), p.name, p.role, len(g), " × ".join(f"{x:.1f}" for x in m.extents),
                     round(m.volume / 1000, 3), round(m.volume * density, 3),
                     "(" + ", ".join(f"{c:.1f}" for c in com) + ")",
                     f"{gear.teeth} t, x = {gear.profile_shift:.3f}" if gear else ""])
    total = sum(len(g) * g[0].mesh.volume * density for g in groups)
    out = [("Bill of parts",
            f'<figure>{R.img(assembly_png, "assembly")}<figcaption>The assembly at rest '
            f"({sum(len(g) for g in groups)} printed parts, {total:.0f} g printed solid of "
            f"{html.escape(kit.material)}).</figcaption></figure>"
            '<div class="parts">' + R.table(["picture", "part", "role", "count", "size mm (as printed)", "volume cm³",
                                             "mass g (solid)", "centre of mass mm (STL frame)", "gear"], rows,
                                            left=3, raw={0}) + "</div>")]
    if purchased:
        buy = [[str(b.get("name", "")), str(b.get("role", "")),
                ", ".join(f"{k} {v}" for k, v in b.items() if k not in ("name", "role"))] for b in purchased]
        out.append(("Bought parts", R.table(["item", "role", "details"], buy, left=3)))
    return out
