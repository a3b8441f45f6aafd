"""What every sub-slice's kit shares: a hub's feature cut into the part it holds (``hubs.Hub``), a
turning shaft's gear with its hub, the turning shaft itself and the bought hardware (nut and threaded
rod, set screw and square nut) as parts with their contacts; the manifest's summary of a hub; and
``refuse``, ``kit_files`` and ``plate_margin``, the same for the stages, the planetary and the rack."""

from __future__ import annotations

import math

from ....config.loader import LoadedDesign
from ....config.yamlio import dump_yaml
from ....core.quantise import r6
from ....core.parts import Contact, Part
from ....design.gearing import GearSpec
from ....geometry.gear import gear_body
from ....geometry.hubs import hex_nut, key_ridge, keyway_hole, nut_trap, radial_cylinder, block, square_nut
from ....geometry.measure import refuse_oversize
from ....geometry.outline import circle
from ....geometry.parts import DFit, shaft as shaft_solid
from ....geometry.solid import prisms, slab, union
from .hubs import Hub

__all__ = ["FEATURE_TOL", "hub_cutters", "nut_and_rod", "screw_and_nut", "hub_hole", "hubbed_gear", "turning_shaft",
           "hub_contacts", "r6", "hub_summary", "refuse", "kit_files", "plate_margin"]

FEATURE_TOL = 0.01  # mm: chord tolerance of round features that are not gear flanks


def hub_cutters(h: Hub, z0: float, outer: float, running: float, turn: float = 0.0) -> list:
    """What a part loses for hub ``h``'s hardware, the part's bottom face at ``z0`` (its local frame, the
    bore on z): a nut trap sunk into that face, or a set screw's radial hole (along local +x turned by
    ``turn`` rad about z, out to ``outer``) and its nut's slot open at that face."""
    if h.kind == "hex":
        return [nut_trap(h.pocket_s, z0, h.pocket_depth)]
    if h.kind == "set_screw":
        zc = z0 + h.screw_z
        cut = [radial_cylinder((h.thread + running) / 2, 0.0, outer, zc, FEATURE_TOL),
               block(h.slot_x0, h.slot_x0 + h.pocket_depth, -h.pocket_s / 2, h.pocket_s / 2, z0 - 1.0,
                     zc + h.pocket_s / 2)]
        return [c.rotate((0.0, 0.0, math.degrees(turn))) for c in cut] if turn else cut
    return []


def nut_and_rod(h: Hub, rod: str, nut: str, z0: float, z1: float, nut_z: float) -> list[Part]:
    """A hex bore's bought parts: the threaded rod from z0 to z1 and its ISO 4032 nut from ``nut_z`` up
    (the rod and the nut's bore one polygon, so they touch exactly)."""
    thread = circle(h.radius, FEATURE_TOL)
    return [Part(rod, "threaded rod", slab(thread, z0, z1), printed=False,
                 info=(("item", f"{h.nut} threaded rod (DIN 976), cut to length"), ("thread", h.nut),
                       ("diameter_mm", h.thread), ("length_mm", round(z1 - z0, 1)))),
            Part(nut, "nut", hex_nut(h.nut_s, h.nut_m, thread, nut_z), printed=False,
                 info=(("item", f"{h.nut} hex nut (ISO 4032)"), ("thread", h.nut), ("across_flats_mm", h.nut_s),
                       ("height_mm", h.nut_m)))]


def screw_and_nut(h: Hub, screw: str, nut: str, z0: float, turn: float = 0.0) -> list[Part]:
    """A set screw's bought parts in the frame of the part it holds (its bottom face at ``z0``): the
    screw from the shaft's surface out along local +x turned by ``turn`` rad, its square nut in the slot."""
    zc = z0 + h.screw_z
    x0 = h.slot_x0 + (h.pocket_depth - h.nut_m) / 2
    a = radial_cylinder(h.thread / 2, h.radius, h.radius + h.screw_length, zc, FEATURE_TOL)
    b = square_nut(h.nut_s, h.nut_m, h.thread, x0, zc, FEATURE_TOL)
    if turn:
        a, b = (x.rotate((0.0, 0.0, math.degrees(turn))) for x in (a, b))
    return [Part(screw, "set screw", a, printed=False,
                 info=(("item", f"{h.nut} × {h.screw_length:g} set screw, flat point (ISO 4026)"), ("thread", h.nut),
                       ("length_mm", h.screw_length))),
            Part(nut, "nut", b, printed=False,
                 info=(("item", f"{h.nut} square nut (DIN 562)"), ("thread", h.nut), ("width_mm", h.nut_s),
                       ("height_mm", h.nut_m)))]


def hub_hole(h: Hub, press: float, tol: float):
    """The bore outline (a hole) of a part held by hub ``h`` on a turning shaft: a D (its flat on local
    -y), round with its keyway on local +y, or round (a nut trap's rod, a set screw's shaft)."""
    if h.kind == "d_flat":
        return DFit(h.radius, press).hole(tol)
    if h.kind == "keyway":
        return keyway_hole(h.bore, h.key_half, h.key_floor, tol)
    return circle(h.bore, tol, hole=True)


def hubbed_gear(gear: GearSpec, face: float, h: Hub, press: float, running: float, hub_radius: float,
                z_thrust: float, z_gear: float, raised: bool, tol: float):
    """A turning shaft's gear (the planetary's sun, the rack's pinion) with its bore feature: the gear
    at ``z_gear``; when ``raised``, its set screw's hub from its thrust ring (``z_thrust``) up to the
    gear; the hub's cutters (screw hole, nut slot or trap) taken out."""
    hole = hub_hole(h, press, max(tol, 0.005))
    solid = gear_body(gear, face, hole, z_gear)
    if raised:  # its set screw's hub, from its thrust ring up to the gear
        solid = union([solid, prisms([(circle(hub_radius, FEATURE_TOL).difference(hole), z_thrust, z_gear)])])
    cut = hub_cutters(h, z_thrust, hub_radius + 1.0, running)
    return solid - union(cut) if cut else solid


def turning_shaft(h: Hub, name: str, nut: str, z0: float, z1: float, fit: tuple[float, float]) -> list[Part]:
    """A turning shaft from z0 to z1 for hub ``h`` (not ``d_flat``, whose D the caller lays out), the part
    it holds spanning ``fit``: printed round (a set screw's), round with its integral key along ``fit``
    (a keyway's), or a bought threaded rod and its nut at the part's bottom face (a nut trap's)."""
    tol = FEATURE_TOL
    round_ = shaft_solid(DFit(h.radius, 0.0), [("round", z0, z1)], tol)
    if h.kind == "keyway":
        return [Part(name, "axle", union([round_, key_ridge(h.key_top_half, h.key_top, *fit)]))]
    if h.kind == "set_screw":
        return [Part(name, "axle", round_)]
    if h.kind == "hex":
        return nut_and_rod(h, name, nut, z0, z1, fit[0])
    raise ValueError(f"no turning shaft for a {h.kind!r} bore")


def hub_contacts(h: Hub, part: str, shaft: str, nut: str, screw: str, seat: str | None) -> list[Contact]:
    """The bought hardware's contacts with the part it holds and its shaft: a nut in its trap on its
    rod (resting on ``seat`` when the part stands on one), a set screw in its hole through its nut."""
    if h.kind == "hex":
        return [Contact(nut, part, "thrust"), Contact(nut, shaft, "thrust")] + \
            ([Contact(nut, seat, "thrust")] if seat else [])
    if h.kind == "set_screw":
        return [Contact(nut, part, "thrust"), Contact(screw, part, "thrust"), Contact(screw, nut, "thrust"),
                Contact(screw, shaft, "thrust")]
    return []


def hub_summary(h, running: float) -> dict:
    """The bore's feature as built (mm): a keyway's slot, a nut trap, a set screw's hole and nut slot
    (``h``: a hubs.Hub, or None for a round or D-flat bore; ``running``: the diametral running clearance)."""
    if h is None or h.kind in ("round", "d_flat"):
        return {}
    if h.kind == "keyway":
        return {"keyway": {"width_mm": r6(2 * h.key_half), "floor_from_axis_mm": r6(h.key_floor),
                           "key_width_mm": r6(2 * h.key_top_half), "key_top_from_axis_mm": r6(h.key_top)}}
    if h.kind == "hex":
        return {"nut_trap": {"nut": f"{h.nut} ISO 4032", "across_flats_mm": r6(h.pocket_s), "depth_mm": r6(h.pocket_depth),
                             "rod_diameter_mm": r6(h.thread)}}
    return {"set_screw": {"screw": f"{h.nut} × {h.screw_length:g} ISO 4026", "hole_diameter_mm": r6(h.thread + running),
                          "axis_above_part_bottom_mm": r6(h.screw_z), "nut": f"{h.nut} DIN 562",
                          "slot_mm": [r6(h.pocket_depth), r6(h.pocket_s)], "slot_inner_face_mm": r6(h.slot_x0)}}


def refuse(spec, kit) -> None:
    """DesignError when a part fits the printer in no orientation (``build`` writes no such kit)."""
    refuse_oversize(kit.parts, spec.printer.envelope, "gears.module_mm")


def kit_files(raw: LoadedDesign) -> dict[str, bytes]:
    """The kit folder's design.yaml (its printer pinned to the printer.yaml beside it) and printer.yaml."""
    data = raw.document()
    data["printer"] = "printer.yaml"
    return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}


def plate_margin(spec) -> float:
    return spec.checks.plate_margin
