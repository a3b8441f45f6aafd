"""The report's bill of parts for any kit: the assembly, each distinct printed part with its picture,
size, volume, mass and centre of mass (in its STL frame), and what to buy."""

from __future__ import annotations

import html

from ..core.protocol import Kit
from . import report as R
from .kit import group_parts, printed
from ..geometry.solid import mesh_arrays
from .assembly import assembly_section

__all__ = ["bill_sections", "stock_items", "shopping_list", "printed_rows", "part_lines"]


def bill_sections(kit: Kit, colours: dict[str, str], purchased: list, groups=None,
                  steps: list | None = None) -> list[tuple[str, str]]:
    """[("Bill of parts", html), ("Filament", html)], when the kit has bought parts ("Bought parts",
    html), and with ``steps`` (``export.assembly.steps_of``) ("Assembly", html): the steps in order
    with the pictures of their parts. ``groups``: the kit's printed parts grouped
    (``export.kit.group_parts``), if made already."""
    from .render import render, render_cutaway  # matplotlib: only when a report draws
    groups = groups or group_parts([printed(p, kit.printer) for p in kit.parts if p.printed])
    colour = lambda role: colours.get(role, "#999")  # noqa: E731
    poses = kit.poses(0.0)
    scene = []
    for g in groups:
        for it in g:
            T = poses[it.part.name] @ it.local_from_print
            scene.append((g[0].mesh.vertices @ T[:3, :3].T + T[:3, 3], g[0].mesh.faces, colour(it.part.role),
                          it.part.name))
    assembly_png, see = render_cutaway([sc[:3] for sc in scene], (1100, 720), elev=35, azim=-70)
    cut = sorted({scene[i][3] for i in see})
    cut_note = (f" Cut-away: {', '.join(html.escape(n) for n in cut)} drawn see-through, as "
                f"{'they hide' if len(cut) > 1 else 'it hides'} most of what lies behind.") if cut else ""
    rows, pictures, printed_as = [], {}, {}
    density = kit.density
    for g in groups:
        p, m = g[0].part, g[0].mesh
        pic = render([(m.vertices, m.faces, colour(p.role))], (300, 240))
        pictures.update({it.part.name: pic for it in g})
        printed_as.update({it.part.name: p.name for it in g[1:]})  # the bill lists the copies under g's first name
        gear = p.gear
        com = m.center_mass if m.volume > 0 else m.triangles.mean(axis=(0, 1))  # no volume: the corners' mean
        rows.append([R.img(pic, p.name), p.name, p.role, len(g), " × ".join(f"{x:.1f}" for x in m.extents),
                     round(m.volume / 1000, 3), round(m.volume * density, 3),
                     "(" + ", ".join(f"{c:.1f}" for c in com) + ")",
                     f"{gear.teeth} t, x = {gear.profile_shift:.3f}" if gear else ""])
    total = sum(len(g) * g[0].mesh.volume * density for g in groups)
    out = [("Bill of parts",
            f'<figure>{R.img(assembly_png, "assembly")}<figcaption>The assembly at rest '
            f"({sum(len(g) for g in groups)} printed parts, {total:.0f} g printed solid of "
            f"{html.escape(kit.material)}).{cut_note}</figcaption></figure>"
            '<div class="parts">' + R.table(["picture", "part", "role", "count", "size mm (as printed)", "volume cm³",
                                             "mass g (solid)", "centre of mass mm (STL frame)", "gear"], rows,
                                            left=3, raw={0}) + "</div>")]
    filament = [[p.name, len(g), round(g[0].mesh.volume * density, 1), round(len(g) * g[0].mesh.volume * density, 1)]
                for g in groups for p in (g[0].part,)]
    filament.append(["total", sum(r[1] for r in filament), "", round(total, 1)])
    out.append(("Filament", "<p>Printed parts, each at full density (solid): infill below 100 % prints less.</p>"
                + R.table(["part", "count", "g each", "g total"], filament, left=1)))
    if purchased:
        buy = [[q, item, size, ", ".join(used[:6]) + (" …" if len(used) > 6 else "")]
               for item, q, size, used in stock_items(purchased)]
        out.append(("Bought parts", R.table(["quantity", "item", "stock size", "for"], buy, left=4)))
    if steps:
        for p in kit.parts:  # the bought parts as modelled
            if not p.printed and any(p.name in names for _, names in steps):
                pictures[p.name] = render([(*mesh_arrays(p.solid), colour(p.role))], (300, 240))
        out.append(assembly_section(steps, pictures, printed_as))
    return out


def _g(x) -> str:
    return f"{float(x):.4g}"


def stock_items(bought) -> list[tuple[str, int, str, list[str]]]:
    """What to buy, grouped: (item, quantity, stock size, the kit's names it serves), from the kit's
    bought parts (``core.parts.Part`` with ``printed`` False): each part's own ``stock`` lines; a
    part with none is one of its ``item`` (or its role) with the sizes its info gives in mm."""
    items: dict[tuple[str, str], list] = {}

    def add(item: str, qty: int, size: str, name: str) -> None:
        row = items.setdefault((item, size), [0, []])
        row[0] += qty
        row[1].append(name)

    for p in bought:
        for line in p.stock:
            add(line.item, line.quantity, line.size, line.serves or p.name)
        if not p.stock:
            info = dict(p.info)
            size = ", ".join(f"{k[:-3]} {_g(v)} mm" for k, v in info.items() if k.endswith("_mm") and
                             isinstance(v, (int, float)))
            add(str(info.get("item") or p.role or p.name), 1, size, p.name)  # "item": what to ask a shop for
    return [(item, q, size, used) for (item, size), (q, used) in items.items()]


def printed_rows(man: dict) -> list[tuple[str, int, float, float]]:
    """(part, count, g each, g total) of the manifest's printed parts (solid)."""
    return [(p["name"], int(p["count"]), float(p["mass_g"]), float(p["mass_g"]) * int(p["count"])) for p in man["parts"]]


def part_lines(man: dict) -> list[str]:
    """A line per distinct part of the manifest, as `build` prints it: name, role, triangles, volume
    (cm³), mass (g, solid) and bounding box (mm)."""
    return [f"{p['name']:<8}{p['role']:<6}{p['triangles']:>9} triangles {p['volume_mm3'] / 1000:8.2f} cm3 "
            f"{p['mass_g']:7.1f} g  {' x '.join(f'{x:.1f}' for x in p['bbox_mm'])} mm" for p in man["parts"]]


def shopping_list(man: dict, bought=()) -> str:
    """What `build` prints as the bill: printed parts (count, filament grams each and in total, solid,
    from the manifest) and the ``bought`` parts (quantity, stock size)."""
    rows = printed_rows(man)
    material = man.get("design", {}).get("material", "")
    total = sum(r[3] for r in rows)
    lines = [f"print: {sum(r[1] for r in rows)} parts ({len(rows)} distinct), {total:.0f} g of {material} "
             "filament in total (solid; infill below 100 % prints less)",
             f"  {'part':<14}{'count':>6}{'g each':>9}{'g total':>9}"]
    lines += [f"  {n:<14}{c:>6}{e:>9.1f}{t:>9.1f}" for n, c, e, t in rows]
    bought = stock_items(bought)
    if bought:
        lines.append("buy:")
        lines += [f"  {q:>4} × {item:<34} {size}" for item, q, size, _ in bought]
    else:
        lines.append("buy: nothing (every part prints)")
    return "\n".join(lines)
