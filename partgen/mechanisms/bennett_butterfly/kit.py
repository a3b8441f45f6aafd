"""The balanced Bennett butterfly as a kit: twelve printed links, a base, stock steel pins, and
counterweight pockets holding whole stock slugs, placed so the common centre of mass stays at S in
every pose.

``build_bennett`` lays the stacks out (``bennett_layout``), builds every part, chooses how each
link prints (``geometry.printing.best_orientation``: the least support), weighs it as printed
(``geometry.mass``, layers in that orientation), then sizes the counterweights: the fill masses
that need the smallest offsets, rounded to whole stock slugs (``Fill``: the pocket exactly as deep
as its slugs, binder in the clearance, so the fill's centre is the pocket's), and how far each
pocket sits off its nominal point for those masses to balance. The pockets change their own
links' mass, so it places them, rebuilds those links and places them again (a Newton step on the
links' moment) until no pocket moves 0.001 mm.
"""

from __future__ import annotations

import math
import pickle
from collections import OrderedDict
from dataclasses import dataclass, field

import numpy as np

from ...config.loader import LoadedDesign
from ...config.yamlio import dump_yaml
from ...core.cache import recall, remember
from ...core.protocol import ParamsKit
from ...core.transforms import frame_z
from ...core.quantise import quantise
from ...design import bennett_butterfly as bbf
from .params import BennettParams
from ...geometry.bennett_link import LINK_PHASES, Cup, base_solid, link_solid, pin_solid
from ...geometry.mass import printed_mass
from ...geometry.parts import Part
from ...core.parts import Stock
from ...errors import DesignError
from ...geometry.printing import best_orientation
from ...geometry.solid import cylinder, float32_sound, mesh_arrays, print_arrays
from .layout import (Sweep, choose_offsets, coarse_samples, link_capsules, own_clearance, part_capsules,
                             part_reach, point_speed, search_layout, shape_samples, sweep_clearance)
from .parts import (BASE, Fill, Layout, base_features, choose_fill, cup_of, cw_nominal, default_layout,
                            home_inputs, link_features, print_settings, stack)

Solid = object  # a manifold3d.Manifold, made by geometry/

__all__ = ["BennettKit", "LinkMass", "PrintPose", "build_bennett", "com_deviation", "fill_points", "grid",
           # the protocol's kit members and what the kit folder holds
           "build", "refuse", "design_summary", "kit_files", "bill", "bought", "layout_yaml",
           # the layout and the parts, for the checks and the tests
           "BASE", "Layout", "Sweep", "choose_offsets", "coarse_samples", "default_layout", "home_inputs",
           "link_capsules", "link_features", "own_clearance", "part_capsules", "part_reach", "point_speed", "shape_samples",
           "stack", "sweep_clearance"]


@dataclass(frozen=True)
class LinkMass:
    """A part's mass (g) and centre (3,) mm in its body frame, solid and as printed (FDM, layers in
    its print orientation)."""

    solid_mass: float
    solid_centre: np.ndarray
    fdm_mass: float
    fdm_centre: np.ndarray
    shell_volume: float
    interior_volume: float
    interior_centre: np.ndarray


@dataclass(frozen=True)
class PrintPose:
    """How a part lies on the bed: ``body_from_print`` (4, 4) takes the STL's frame (z up, the bed
    at z = 0) to the part's body frame; the area that needs support beyond the overhang angle and
    the flat contact with the bed, mm²; the height as printed, mm."""

    body_from_print: np.ndarray
    overhang_mm2: float
    contact_mm2: float
    height_mm: float


@dataclass(frozen=True)
class _Built:
    solid: Solid  # body frame
    printed: Solid  # print frame
    pose: PrintPose
    mass: LinkMass
    cup: Cup | None
    moving: float = 0.0  # g (solid) of the cup and the bar that carries it: what moves with the pocket


@dataclass(frozen=True)
class BennettKit(ParamsKit):
    params: BennettParams
    layout: Layout
    parts: tuple[Part, ...]
    bodies: dict
    masses: dict[int, LinkMass]
    pins: dict[int, list[tuple[float, np.ndarray]]]  # link -> [(mass g, body point)]
    cups: dict[int, Cup]
    fills: dict[int, Fill]
    delta: dict[int, np.ndarray]  # link -> (3,) mm: its pocket's offset from the nominal point
    solids: dict[int, Solid]  # part (0 = base) -> solid in its body frame
    printing: dict[str, PrintPose]  # printed part name -> how it prints
    base_mass: LinkMass
    figures: dict = field(default_factory=dict)

    def printed_mass(self, name: str) -> float | None:
        """Grams of a printed part as printed (the FDM shell-and-infill model)."""
        if name == "base":
            return self.base_mass.fdm_mass
        if name.startswith("link") and name[4:].isdigit():
            return self.masses[int(name[4:])].fdm_mass
        return None

    @property
    def pockets(self) -> dict[int, tuple[np.ndarray, Fill]]:
        return {i: (self.delta[i], self.fills[i]) for i in self.fills}

    def frames(self, q1, q4) -> dict[int, np.ndarray]:
        return bbf.link_frames(bbf.pose(self.params.bb, q1, q4))

    def poses(self, theta: float = 0.0) -> dict[str, np.ndarray]:
        """Placement (4, 4) of every part at the home pose (``theta`` turns the linkage about S)."""
        return self.placements(*home_inputs(self.params.home, theta))

    def placements(self, q1: float, q4: float) -> dict[str, np.ndarray]:
        """Placement (4, 4) of every part's STL frame (printed parts) or own frame (pins, fills) at
        inputs (q1, q4) rad."""
        fr = self.frames(q1, q4)
        out = {f"link{i:02d}": fr[i][0] @ self.printing[f"link{i:02d}"].body_from_print for i in range(1, 13)}
        out["base"] = self.printing["base"].body_from_print
        for j in bbf.JOINTS:
            owner = self.layout.members(j)[0]
            lo, hi = stack(self.params, self.layout, j).pin
            pt, ax = (np.zeros(3), np.array([0.0, 0.0, 1.0])) if owner == BASE else self.bodies[owner][j]
            local = frame_z(pt + (lo + hi) / 2 * ax, ax)
            out[f"pin_{j}"] = (np.eye(4) if owner == BASE else fr[owner][0]) @ local
        for i, cup in self.cups.items():
            out[f"fill_link{i:02d}"] = fr[i][0] @ frame_z(cup.pocket_centre, np.asarray(cup.axis, float))
        return out


def _pin_masses(p: BennettParams, lay: Layout, bodies: dict) -> dict[int, list[tuple[float, np.ndarray]]]:
    """Each pin's mass (a stock length), counted with the bottom member of its stack: its centre lies
    on the joint axis, which every member shares, so this is exact however the pin turns.
    link -> [(g, body point)]."""
    out: dict[int, list] = {i: [] for i in range(0, 13)}
    for j in bbf.JOINTS:
        st = stack(p, lay, j)
        lo, hi = st.pin
        m = p.pin_density * math.pi * p.pin_radius ** 2 * st.length
        owner = st.members[0]
        if owner == BASE:
            out[BASE].append((m, np.array([0.0, 0.0, (lo + hi) / 2])))
            continue
        pt, ax = bodies[owner][j]
        out[owner].append((m, pt + (lo + hi) / 2 * ax))
    return out


def fill_points(kit: BennettKit, binder: bool = True, short: int | None = None) -> dict[int, list[tuple[float, np.ndarray]]]:
    """Each pocket's fill as point masses in its link's body frame: the slugs and the binder at the
    pocket's centre (the pocket is full); ``binder`` False leaves the binder out; ``short`` = a link
    whose pocket is one slug short (the top one, at the pocket's mouth, missing)."""
    out = {}
    for i, f in kit.fills.items():
        cup = kit.cups[i]
        pts = [(f.steel_mass + (f.binder_mass if binder else 0.0), cup.pocket_centre)]
        if short == i:
            axis = np.asarray(cup.axis, float) / np.linalg.norm(cup.axis)
            pts.append((-f.slug_mass, cup.pocket_centre + axis * (f.depth - f.length) / 2))
        out[i] = pts
    return out


def _combine(masses, pins, scale=None):
    """Link mass and centre with its pins (and an optional mass scale per link, for seeded faults)."""
    m, c = {}, {}
    for i, (mi, ci) in masses.items():
        mi = mi * (scale or {}).get(i, 1.0)
        tot, mom = mi, mi * np.asarray(ci, float)
        for mp, pp in pins.get(i, []):
            tot, mom = tot + mp, mom + mp * pp
        m[i], c[i] = tot, mom / tot
    return m, c


def com_deviation(kit: BennettKit, model: str, q1, q4, fill: dict | None = None, infill: float | None = None,
                  scale: dict[int, float] | None = None) -> np.ndarray:
    """(n,) distance (mm) of the common centre of mass from S, links + pins + pocket fills, under the
    'solid' or 'fdm' mass model (optionally at another infill fraction); ``fill``: link -> point
    masses [(g, body point)] instead of the fills as built (``fill_points``)."""
    p = kit.params
    masses = {}
    for i, lm in kit.masses.items():
        if model == "solid":
            masses[i] = (lm.solid_mass, lm.solid_centre)
        elif infill is None:
            masses[i] = (lm.fdm_mass, lm.fdm_centre)
        else:
            # shell and interior keep their centres; only the interior's mass changes
            shell_c = (lm.solid_centre * (lm.shell_volume + lm.interior_volume)
                       - lm.interior_centre * lm.interior_volume) / lm.shell_volume
            ms = p.density * lm.shell_volume
            mi = p.density * infill * lm.interior_volume
            masses[i] = (ms + mi, (ms * shell_c + mi * lm.interior_centre) / (ms + mi))
    m, c = _combine(masses, kit.pins, scale)
    for i, pts in (fill if fill is not None else fill_points(kit)).items():
        for f, cp in pts:
            m[i], c[i] = m[i] + f, (m[i] * c[i] + f * np.asarray(cp, float)) / (m[i] + f)
    P = bbf.pose(p.bb, q1, q4)
    return np.linalg.norm(bbf.centre_of_mass(P, m, c), axis=1)


def build_bennett(p: BennettParams, progress=None, lay: Layout | None = None) -> BennettKit:
    """Lay out the stacks (``lay``, the config's fixed layout, or a search), build the links and the
    base, weigh them (solid and FDM) and size the counterweights.

    A searched layout is searched with guessed pockets at their nominal points, the kit sized, the
    layout refined with the pockets as sized, and the kit built again from that layout — by the very
    path a fixed layout takes (parts already built are reused), so the kit folder's design.yaml
    rebuilds it byte for byte."""
    say = progress or (lambda s: None)
    cache = _PartMemo(p)
    if lay is None and p.fixed_layout is not None:
        lay = Layout({BASE: 0, **p.fixed_layout[0]}, dict(p.fixed_layout[1]))
    if lay is not None:
        return _build(p, lay, say, {"layout_source": "given"}, cache)
    what = pickle.dumps(p, protocol=5)  # the search's answer is remembered (core.cache) under the resolved design
    known = recall("bennett-layout", what)
    if known is not None:
        lay = Layout({int(k): int(v) for k, v in known["layer"]}, {str(k): float(v) for k, v in known["shift"]})
        return _build(p, lay, say, known["figures"], cache)
    kit = _search_and_build(p, say, cache)
    lay = kit.layout
    remember("bennett-layout", what, {"layer": sorted(lay.layer.items()), "shift": sorted(lay.shift.items()),
                                      "figures": {k: kit.figures[k] for k in ("layout_source", "search_clearance_mm")}})
    return kit


class _PartMemo:
    """The parts built and weighed in this process (a bounded LRU shared by every build of it), under
    the key ``_build`` gives a part (its features and facets) with the design's numbers that weighing
    and laying it on the bed read (density, overhang rule, least bed contact, walls, skin, infill).
    A kit built again in one process (a kit folder checked after its build, auto play's kits at the
    start value, a sweep's neighbours) reuses a part whose inputs are the same: the very objects the
    first build made, so its files are the same bytes. Nothing is kept across processes."""

    _parts: "OrderedDict[tuple, _Built]" = OrderedDict()
    SIZE = 96  # parts (a kit has 13): a few kits' worth

    def __init__(self, p: BennettParams):
        self._with = (p.overhang_angle, p.min_contact, p.density, p.print_wall, p.print_skin, p.infill)

    def get(self, key):
        hit = self._parts.get((key, self._with))
        if hit is not None:
            self._parts.move_to_end((key, self._with))
        return hit

    def __contains__(self, key) -> bool:
        return self.get(key) is not None

    def __getitem__(self, key):
        hit = self.get(key)
        if hit is None:
            raise KeyError(key)
        return hit

    def __setitem__(self, key, built: "_Built") -> None:
        self._parts[(key, self._with)] = built
        self._parts.move_to_end((key, self._with))
        while len(self._parts) > self.SIZE:
            self._parts.popitem(last=False)


def _search_and_build(p: BennettParams, say, cache: dict) -> BennettKit:
    """The searched layout's kit (``build_bennett``)."""
    lay, bodies, angles, _, guessed = search_layout(p, say)
    # size the pockets roughly: one round places them to a millimetre or so
    rough = _build(p, lay, say, {}, cache, rounds=1).figures["next_pockets"]
    coarse = coarse_samples(angles)
    sized = min(v for v, _ in Sweep(p, coarse, bodies, rough).all(lay).values())
    figures = {"layout_source": "auto", "search_clearance_mm": {"guessed_pockets": guessed, "sized_pockets": sized}}
    if quantise(sized) >= quantise(min(guessed, p.bar_radius)):  # the pockets as sized cost no clearance that matters
        return _build(p, lay, say, figures, cache)
    # the sized pockets came closer to something: move the pocket links and their stacks again, with
    # the pockets where they are; sizing the new layout moves them again, so keep whichever is better
    lay2, _ = choose_offsets(p, coarse, bodies, say, p.layers, start=lay, pockets=rough, only=set(p.cw_links))
    rough2 = _build(p, lay2, say, {}, cache, rounds=1).figures["next_pockets"]
    sized2 = min(v for v, _ in Sweep(p, coarse, bodies, rough2).all(lay2).values())
    figures["search_clearance_mm"]["refined_sized_pockets"] = sized2
    return _build(p, lay2 if quantise(sized2) > quantise(sized) else lay, say, figures, cache)  # a tie keeps lay


def _cup_solid(cup: Cup) -> tuple[float, np.ndarray]:
    """Volume (mm³) and centroid (3,) of a cup as a solid: its cylinder less its pocket."""
    axis = np.asarray(cup.axis, float) / np.linalg.norm(cup.axis)
    base = np.asarray(cup.point, float)
    vc, vp = math.pi * cup.outer_radius ** 2 * cup.height, math.pi * cup.pocket_radius ** 2 * cup.pocket_depth
    cc, cp = base + axis * cup.height / 2, base + axis * (cup.height - cup.pocket_depth / 2)
    return vc - vp, (vc * cc - vp * cp) / (vc - vp)


def _print_pose(solid: Solid, p: BennettParams) -> tuple[PrintPose, np.ndarray]:
    """The orientation with the least support among the part's flat faces (``best_orientation``),
    bed at z = 0; and print_from_body (3, 4)."""
    v, f = mesh_arrays(solid)
    o = best_orientation(v, f, math.degrees(p.overhang_angle), p.min_contact)
    z0 = float((v @ o.rotation[2]).min())
    pfb = np.eye(4)
    pfb[:3, :3] = o.rotation
    pfb[2, 3] = -z0
    return PrintPose(np.linalg.inv(pfb), o.overhang_mm2, o.contact_mm2, o.height_mm), pfb[:3]


def _lay(solid: Solid, p: BennettParams) -> tuple[Solid, PrintPose]:
    """The part laid on the bed, and how."""
    pose, pfb = _print_pose(solid, p)
    return solid.transform(pfb), pose


def _weigh(solid: Solid, p: BennettParams) -> tuple[Solid, PrintPose, LinkMass]:
    """The part laid on the bed, how, and its masses (centres back in the body frame)."""
    on_bed, pose = _lay(solid, p)
    return on_bed, pose, _mass(on_bed, pose, p)


def _mass(on_bed: Solid, pose: PrintPose, p: BennettParams) -> LinkMass:
    """The masses of a part laid on the bed, centres back in the body frame."""
    mm = printed_mass(on_bed, p.density, print_settings(p))
    T = pose.body_from_print
    back = lambda c: T[:3, :3] @ np.asarray(c, float) + T[:3, 3]  # noqa: E731
    return LinkMass(mm.solid_mass, back(mm.solid_centre), mm.mass, back(mm.centre), mm.shell_volume,
                    mm.interior_volume, back(mm.interior_centre))


def _build(p: BennettParams, lay: Layout, say, figures: dict, cache: dict, rounds: int = 8) -> BennettKit:
    """The kit of one layout: links built and weighed, pockets filled and placed (at most ``rounds``
    rounds: fewer give a kit whose pockets are only near their place, for the layout search)."""
    bodies = bbf.body_joints(p.bb)
    q1g, q4g = grid(p)
    P = bbf.pose(p.bb, q1g, q4g)
    links: dict[int, _Built] = {}

    def make(i: int, pocket) -> None:
        bosses, bars, cw = link_features(p, i, lay, bodies[i], pocket)
        key = ("link", tuple(bosses), tuple(bars), tuple(cw), p.segments)
        hit = cache.get(key)
        if hit is None:
            for phase in LINK_PHASES:  # the first whose STL, as written, stays one shell (weighed once, after)
                solid = link_solid(bosses, bars, cw, p.segments, phase)
                on_bed, pose = _lay(solid, p)
                if float32_sound(*print_arrays(on_bed)[:2]):
                    break
            lm = _mass(on_bed, pose, p)
            moving = 0.0
            if cw:  # the cup (a cylinder less its pocket) and the tube from its bar's exit to it (ends flat there)
                c, carry = cw[0], bars[-1]
                length = float(np.linalg.norm(np.subtract(carry.p1, carry.p0)))
                moving = p.density * math.pi * (c.outer_radius ** 2 * c.height - c.pocket_radius ** 2 * c.pocket_depth
                                                + carry.radius ** 2 * length)
            hit = cache[key] = _Built(solid, on_bed, pose, lm, cw[0] if cw else None, moving)
        links[i] = hit

    def props():
        return _combine({i: (b.mass.fdm_mass, b.mass.fdm_centre) for i, b in links.items()}, pins)

    pins = _pin_masses(p, lay, bodies)
    for i in range(1, 13):
        say(f"link {i}")
        make(i, None)
    # the masses that need the smallest offsets, with the search's guessed pockets; whole slugs
    nominal = {i: cw_nominal(p, i, bodies[i], lay) for i in p.cw_links}
    m, c = props()
    masses, _, _ = bbf.solve_counterweights(P, m, c, list(nominal.items()))
    fills = {i: choose_fill(p, float(x)) for i, x in zip(p.cw_links, masses)}
    at = [(i, nominal[i], fills[i].mass) for i in p.cw_links]
    # the first placement: each link with its guessed cup swapped for the one its fill needs (as
    # printed plastic at the cups' centres) and that cup moving with the pocket
    m0, c0, moving = dict(m), dict(c), {}
    for i in p.cw_links:
        b = links[i]
        ratio = b.mass.fdm_mass / b.mass.solid_mass
        real = cup_of(fills[i], np.asarray(b.cup.pocket_centre), np.asarray(b.cup.axis, float), p.cw_wall)
        (vg, cg), (vr, cr) = _cup_solid(b.cup), _cup_solid(real)
        mom = m0[i] * c0[i] + p.density * ratio * (vr * cr - vg * cg)
        m0[i] = m0[i] + p.density * ratio * (vr - vg)
        c0[i] = mom / m0[i]
        moving[i] = (b.moving * ratio + p.density * ratio * (vr - vg), np.zeros(3))
    d, _ = bbf.solve_offsets(P, m0, c0, at, moving)
    delta = {i: d[k] for k, i in enumerate(p.cw_links)}
    history = []
    for rnd in range(rounds):
        say(f"counterweights, round {rnd + 1}")
        built = dict(delta)
        for i in p.cw_links:
            make(i, (delta[i], fills[i]))
        m, c = props()
        # the cup and the bar that carries it move with the pocket: a Newton step on the links' moment
        moving = {i: (links[i].moving * links[i].mass.fdm_mass / links[i].mass.solid_mass, delta[i]) for i in p.cw_links}
        d, _ = bbf.solve_offsets(P, m, c, at, moving)
        new = {i: d[k] for k, i in enumerate(p.cw_links)}
        history.append(max(float(np.linalg.norm(new[i] - delta[i])) for i in p.cw_links))
        # how far the kit as built (pockets at delta) is from the balance, at most (mm)
        total = sum(m.values()) + sum(f.mass for f in fills.values())
        off = sum((fills[i].mass + moving[i][0]) * np.linalg.norm(new[i] - delta[i]) for i in p.cw_links) / total
        if off <= p.tolerance / 100:
            break
        delta = new
    figures["next_pockets"] = {i: (new[i], fills[i]) for i in p.cw_links}  # where the balance wants them now
    delta = built  # where the pockets are as built
    say("base")
    columns, bore = base_features(p, lay)
    key = ("base", tuple(columns), bore, p.segments)
    if key not in cache:
        solid = base_solid(columns, bore, p.segments)
        cache[key] = _Built(solid, *_weigh(solid, p), None)
    base = cache[key]
    figures.update({"pocket_offsets_mm": {i: [round(float(x), 3) for x in delta[i]] for i in p.cw_links},
                    "pocket_moves_per_round_mm": history})
    parts = [Part(f"link{i:02d}", "bennett_link", links[i].printed) for i in range(1, 13)]
    parts.append(Part("base", "bennett_base", base.printed))
    printing = {f"link{i:02d}": links[i].pose for i in range(1, 13)}
    printing["base"] = base.pose
    solids = {i: links[i].solid for i in range(1, 13)}
    solids[BASE] = base.solid
    cups = {i: links[i].cup for i in p.cw_links}
    kit = BennettKit(p, lay, tuple(parts), bodies, {i: links[i].mass for i in range(1, 13)}, pins, cups, fills, delta,
                     solids, printing, base.mass, figures)
    return _with_bought(kit)


def _with_bought(kit: BennettKit) -> BennettKit:
    """The kit with its bought parts: a stock pin per joint and each pocket's fill, each saying where
    it goes (its centre and axis in the STL frame of the part it sits in) and what it weighs."""
    p, lay = kit.params, kit.layout
    bought = []
    for j in bbf.JOINTS:
        st = stack(p, lay, j)
        owner = st.members[0]
        name = "base" if owner == BASE else f"link{owner:02d}"
        pt, ax = (np.zeros(3), np.array([0.0, 0.0, 1.0])) if owner == BASE else kit.bodies[owner][j]
        centre, axis = _in_print(kit, name, pt + sum(st.pin) / 2 * ax, ax)
        mass = p.pin_density * math.pi * p.pin_radius ** 2 * st.length
        bought.append(Part(f"pin_{j}", "pin", pin_solid(st.length, p.pin_radius, p.segments), printed=False,
                           info=(("diameter_mm", 2 * p.pin_radius), ("length_mm", st.length), ("material", p.pin_kind),
                                 ("joint", j), ("mass_g", round(mass, 6)), ("counted_with", name),
                                 ("centre_mm", centre), ("axis", axis),
                                 ("stack", ["base" if i == BASE else f"link{i:02d}" for i in st.members])),
                           stock=(Stock(f"{p.pin_kind} pin", 1, f"Ø{2 * p.pin_radius:.4g} × {float(st.length):.1f} mm"),)))
    for i, f in kit.fills.items():
        cup = kit.cups[i]
        name = f"link{i:02d}"
        centre, axis = _in_print(kit, name, cup.pocket_centre, np.asarray(cup.axis, float))
        solid = cylinder(f.depth, f.bore_radius, p.segments, True)
        bought.append(Part(f"fill_{name}", "counterweight fill", solid, printed=False, info=(
            ("part", name), ("slugs", {"count": f.count, "kind": p.slug_kind, "diameter_mm": f.diameter,
                                       "length_mm": f.length, "mass_g_each": round(f.slug_mass, 6)}),
            ("binder", {"name": p.binder_name, "volume_cm3": round(f.binder_volume / 1000, 6),
                        "mass_g": round(f.binder_mass, 6)}),
            ("pocket", {"diameter_mm": 2 * f.bore_radius, "depth_mm": f.depth}),
            ("mass_g", round(f.mass, 6)), ("centre_mm", centre), ("axis", axis)),
            stock=(Stock(f"{p.slug_kind} slug", int(f.count), f"Ø{f.diameter:.4g} × {f.length:.4g} mm", name),
                   Stock(str(p.binder_name), 1, f"{round(f.binder_volume / 1000, 6):.2f} cm³", name))))
    return BennettKit(p, lay, kit.parts + tuple(bought), kit.bodies, kit.masses, kit.pins, kit.cups, kit.fills,
                      kit.delta, kit.solids, kit.printing, kit.base_mass, kit.figures)


def _in_print(kit: BennettKit, name: str, point: np.ndarray, axis: np.ndarray) -> tuple[list, list]:
    """A body-frame point and axis in the STL frame of part ``name`` (rounded for the manifest)."""
    T = np.linalg.inv(kit.printing[name].body_from_print)
    return ([round(float(x), 6) for x in T[:3, :3] @ point + T[:3, 3]],
            [round(float(x), 9) for x in T[:3, :3] @ axis])


def grid(p: BennettParams) -> tuple[np.ndarray, np.ndarray]:
    """The balance grid: q1 over a full turn × the shape angle over the workspace (flattened)."""
    nq, ns = p.grid
    q1 = np.linspace(0, 2 * np.pi, nq, endpoint=False)
    ang = np.linspace(*p.workspace, ns)
    Q1, A = np.meshgrid(q1, ang, indexing="ij")
    return home_inputs(A.ravel(), Q1.ravel())


# --- the protocol's kit members: build, refuse, what the kit folder holds -----------------------------
def build(spec: BennettParams, progress=None) -> BennettKit:
    try:
        kit = build_bennett(spec, progress)
    except DesignError as e:
        raise DesignError(e.problem, e.key_path or "counterweights") from None
    return kit


def refuse(spec: BennettParams, kit: BennettKit) -> None:
    from ...geometry.measure import oversize

    for part, ext in oversize(kit.parts, spec.printer.envelope, tol=0.0):
        raise DesignError(f"{part.name} measures {ext.round(1)} mm and does not fit the printer in any orientation",
                          "linkage.a_mm")


def layout_yaml(kit: BennettKit) -> dict:
    """The kit's stack layout as the config's ``parts.layout`` (so a kit folder rebuilds without a search)."""
    return {"layers": {i: int(kit.layout.layer[i]) for i in range(1, 13)},
            "shifts_mm": {j: float(v) for j, v in sorted(kit.layout.shift.items()) if v}}


def _r(x, nd=4):
    return [round(float(v), nd) for v in x] if np.ndim(x) else round(float(x), nd)


def bill(kit: BennettKit) -> list[dict]:
    """Every printed part: its masses (g) solid and as printed (FDM) with their centres in its STL
    frame, its pocket's fill and its pins (g), how it prints (support mm², bed contact mm², height)."""
    rows = []
    parts = [(f"link{i:02d}", kit.masses[i], kit.layout.layer[i], kit.pins[i]) for i in range(1, 13)]
    parts.append(("base", kit.base_mass, 0, kit.pins[BASE]))
    for name, lm, layer, pins in parts:
        pose = kit.printing[name]
        T = np.linalg.inv(pose.body_from_print)
        stl = lambda c: T[:3, :3] @ np.asarray(c, float) + T[:3, 3]  # noqa: E731
        i = None if name == "base" else int(name[4:])
        rows.append({"part": name, "layer": layer, "solid_g": lm.solid_mass, "solid_centre_mm": _r(stl(lm.solid_centre)),
                     "printed_g": lm.fdm_mass, "printed_centre_mm": _r(stl(lm.fdm_centre)),
                     "fill_g": kit.fills[i].mass if i in kit.fills else 0.0, "pins_g": sum(m for m, _ in pins),
                     "support_mm2": round(pose.overhang_mm2, 1), "bed_contact_mm2": round(pose.contact_mm2, 1),
                     "print_height_mm": round(pose.height_mm, 1)})
    return rows


def bought(kit: BennettKit) -> list[dict]:
    """What to buy: the pins by stock length, each pocket's slugs and the binder (quantity, stock size)."""
    p = kit.params
    pins: dict[float, list[str]] = {}
    for part in kit.parts:
        if part.role == "pin":
            info = dict(part.info)
            pins.setdefault(info["length_mm"], []).append(info["joint"])
    rows = [{"item": f"{p.pin_kind} Ø{2 * p.pin_radius:g} × {L:g} mm", "quantity": len(js), "for": ", ".join(js),
             "mass_g": len(js) * p.pin_density * math.pi * p.pin_radius ** 2 * L} for L, js in sorted(pins.items())]
    slugs: dict[float, list[tuple[str, int]]] = {}
    for i, f in sorted(kit.fills.items()):
        slugs.setdefault(f.length, []).append((f"link{i:02d}", f.count))
    for L, uses in sorted(slugs.items()):
        f = _slug_fill(kit, L)
        rows.append({"item": f"{p.slug_kind} Ø{f.diameter:g} × {L:g} mm", "quantity": sum(n for _, n in uses),
                     "for": ", ".join(f"{n} in {name}" for name, n in uses),
                     "mass_g": sum(n for _, n in uses) * f.slug_mass})
    binder = sum(f.binder_volume for f in kit.fills.values())
    rows.append({"item": p.binder_name, "quantity": f"{binder / 1000:.2f} cm³",
                 "for": "the slugs' clearance in the three pockets", "mass_g": sum(f.binder_mass for f in kit.fills.values())})
    return rows


def _slug_fill(kit: BennettKit, length: float):
    return next(f for f in kit.fills.values() if f.length == length)


def design_summary(kit: BennettKit) -> dict:
    """The manifest's "design": the linkage, the layout, the counterweights, the bill, what to buy, the balance."""
    from .checks import balance_figures

    p = kit.params
    bal = {k: v for k, v in balance_figures(kit).items() if k not in ("trace", "grid")}
    fills = {}
    for part in kit.parts:
        if part.role == "counterweight fill":
            info = dict(part.info)
            fills[info["part"]] = {k: v for k, v in info.items() if k != "part"}
            fills[info["part"]]["pocket_offset_mm"] = kit.figures["pocket_offsets_mm"][int(info["part"][4:])]
    return {"name": p.name, "kind": "bennett_butterfly",
            "a_mm": p.bb.a, "b_mm": p.bb.b, "alpha_deg": math.degrees(p.bb.alpha), "beta_deg": math.degrees(p.bb.beta),
            "scales": [1.0, p.bb.s2, p.bb.s3, p.bb.s4], "home_angle_deg": math.degrees(p.home),
            "workspace_deg": [math.degrees(x) for x in p.workspace], "layout": layout_yaml(kit),
            "counterweights": fills, "bill": bill(kit), "bought": bought(kit), "infill_percent": 100 * p.infill,
            "overhang_angle_deg": math.degrees(p.overhang_angle), "balance_tolerance_mm": p.tolerance,
            "balance_mm": bal, **{k: v for k, v in kit.figures.items() if k not in ("pocket_offsets_mm", "next_pockets")}}


def kit_files(spec: BennettParams, kit: BennettKit, raw: LoadedDesign) -> dict[str, bytes]:
    """design.yaml with the chosen layout pinned (a kit folder rebuilds without a search), printer.yaml."""
    data = raw.document()
    data["printer"] = "printer.yaml"
    data.setdefault("parts", {})["layout"] = layout_yaml(kit)
    return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document())}
