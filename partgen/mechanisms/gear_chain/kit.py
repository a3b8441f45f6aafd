"""The kit of a gear-coupled chain: every part built for its place in the stack, and its pose at any
crank angle.

Stacking (z up, the base's top face at z = 0; g = axial gap, f = face width, t = plate thickness):
gear layer j (j = 0..n-1) spans [L_j, L_j + f] with L_j = g + j·(f + 2g + t); plate j
(j = 1..n) spans [P_j, P_j + t] with P_j = L_{j-1} + f + g. Layer 0 holds G1 and the drive
gear; layer j holds D_j, M_j and G_{j+1}. Every gear rests on a thrust ring (height g) of what is
under it: rings on the base and plate tops, or, for D_j, the top of G_j's boss, which stands g
proud of plate j. G_j's collar (height g) spaces plate j above D_{j-1} and M_{j-1}.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from ...core.background import SharedMap
from ...core.parts import Bore, Contact, Stock
from ...core.quantise import r6
from ...core.protocol import ParamsKit
from ...core.transforms import pose_z, poses_z
from ...design.kinematics import clockings, gear_tracks, joint_positions_over, link_angles_over
from ...design.mechanism import PEN_BORE_CLEARANCE, ChainDesign
from .params import KitParams
from ...config.yamlio import dump_yaml
from ...errors import ConfigError, DesignError
from ...geometry.measure import empty_parts
from ...geometry import parts as P
from ...geometry.parts import DFit, Part
from ...geometry.printing import least_support_flip
from ...geometry.solid import pack, unpack

if TYPE_CHECKING:  # annotations only: the resolver builds on these parameters
    from ...config.loader import LoadedDesign
    from .resolve import ChainSpec

__all__ = ["Stack", "Kit", "build_kit", "build", "refuse", "design_summary", "kit_files", "size_key", "oversize_parts"]

UP, DOWN = (0.0, 0.0, 1.0), (0.0, 0.0, -1.0)

FEATURE_TOL = 0.01  # mm: chord tolerance of round features that are not gear flanks
CRANK_THICKNESS = 6.0
HANDLE_R, HANDLE_LEN = 5.0, 30.0
LEG_R = 8.0
PEN_WALL = 2.0
PEN_FLOOR = 2.0  # mm of solid under the pen in its holder
MIN_AXLE = 2 * (P.FLAT_DEPTH + 1.0)  # mm: a D-flat 1 mm deep with 1 mm of axle left past it


@dataclass(frozen=True)
class Stack:
    """z-levels of the stack, mm."""

    gap: float
    face: float
    plate: float

    @property
    def pitch(self) -> float:
        return self.face + 2 * self.gap + self.plate

    def layer(self, j: int) -> float:
        """Bottom of gear layer j (0 = G1 and the drive gear)."""
        return self.gap + j * self.pitch

    def plate_z(self, j: int) -> float:
        """Bottom of plate j (1-based)."""
        return self.layer(j - 1) + self.face + self.gap




@dataclass(frozen=True)
class Kit(ParamsKit):
    """Parts of a mechanism, and where each one is at any crank angle."""

    mechanism: ChainDesign
    params: KitParams
    stack: Stack
    parts: tuple[Part, ...]
    static: dict = field(default_factory=dict)  # name -> (4, 4) pose of parts fixed to the base
    clock: dict = field(default_factory=dict)
    contacts: tuple[Contact, ...] = ()
    _posed: dict = field(default_factory=dict, init=False, compare=False, repr=False)  # θ -> poses (not copied by replace)

    def poses(self, theta: float) -> dict[str, np.ndarray]:
        """name -> (4, 4) world-from-local pose of every part at crank angle θ (rad)."""
        theta = float(theta)
        if theta not in self._posed:
            if len(self._posed) > 4096:
                self._posed.clear()
            self._posed[theta] = {name: T[0] for name, T in self.poses_over([theta]).items()}
            for T in self._posed[theta].values():
                T.flags.writeable = False  # shared by every caller: read only
        return dict(self._posed[theta])

    def poses_over(self, ts) -> dict[str, np.ndarray]:
        """name -> (N, 4, 4) poses of every part at the N crank angles ``ts`` (rad), at once."""
        mech, st = self.mechanism, self.stack
        ts = np.atleast_1d(np.asarray(ts, dtype=float))
        n = len(mech.chain.links)
        a = link_angles_over(mech, ts)
        J = joint_positions_over(mech, ts, a)
        gp = gear_tracks(mech, ts, self.clock)
        out = {name: np.broadcast_to(T, (len(ts), 4, 4)) for name, T in self.static.items()}
        for j in range(1, n + 1):
            out[f"B{j}"] = poses_z(J[:, j - 1, 0], J[:, j - 1, 1], st.plate_z(j), a[:, j])
        out["pen_holder"] = poses_z(J[:, -1, 0], J[:, -1, 1], st.plate_z(n), a[:, -1])
        for name, p in gp.items():
            layer = 0 if name in ("G1", "drive") else int(name[1:]) - (1 if name[0] == "G" else 0)
            out[name] = poses_z(p.centre[:, 0], p.centre[:, 1], st.layer(layer), p.angle)
        for s in mech.belt_stages:  # a belt keeps its shape in its link's frame
            out[f"belt{s.j}"] = poses_z(J[:, s.j - 1, 0], J[:, s.j - 1, 1], st.layer(s.j), a[:, s.j])
        drive = gp["drive"]
        for name in ("drive_axle", "crank"):
            z = 0.0 if name == "drive_axle" else -self.params.base_thickness - st.gap
            out[name] = poses_z(drive.centre[:, 0], drive.centre[:, 1], z, drive.angle)
        return out


def build_kit(mech: ChainDesign, params: KitParams, progress=None, clock_error: dict | None = None) -> Kit:
    """Build every part of the kit. ``progress(name)`` is called as each part is made.

    ``clock_error`` (name -> rad) makes fixed gears with their teeth turned that far off the
    clocking the mesh needs, as a badly made part would be: for fault studies."""
    say = progress or (lambda name: None)
    if params.joints.axle_diameter < MIN_AXLE:
        raise DesignError(f"{params.joints.axle_diameter:g} mm leaves no room for the D-flats that fix gears and plates "
                          f"(a flat {P.FLAT_DEPTH:g} mm deep): use at least {MIN_AXLE:g} mm", "joints.axle_diameter_mm")
    st = Stack(params.joints.axial_gap, params.face_width, params.plate_thickness)
    g, f, t = st.gap, st.face, st.plate
    tol = params.system.chord_tolerance
    jn = params.joints
    ra = jn.axle_diameter / 2
    bore_r = params.bore / 2
    # a boss or collar keeps its wall round the largest running bore a joint has of its own
    wall_r = max([bore_r] + [params.bore_of(name) / 2 for name, _ in jn.running_by])
    post = DFit(ra, jn.press_clearance)
    # G's D-boss: the wall under its flat is half the hub wall (the flat cuts FLAT_DEPTH deep)
    # (at least the printer's thinnest wall, with the bore polygon's excess over its circle)
    boss = DFit(wall_r + P.FLAT_DEPTH + max(params.hub_wall / 2, params.printer.min_wall + 2 * FEATURE_TOL),
                jn.press_clearance)
    # a collar keeps at least the boss's wall around the bore
    collar_min = wall_r + max(params.hub_wall / 2, params.printer.min_wall + 2 * FEATURE_TOL)
    rb = boss.radius
    n = len(mech.chain.links)
    clock = clockings(mech)
    for name, err in (clock_error or {}).items():
        clock[name] += err
    parts: list[Part] = []

    def add(part: Part):
        say(part.name)
        if part.printed:  # it lies on its larger flat face unless the other needs less support
            part = replace(part, print_flip=least_support_flip(part.solid, params.printer.overhang_deg))
        parts.append(part)

    # gears. The fixed gears (each clocked: no two alike) are made by a forked child (core.background)
    # while the rest of the kit is made here, which then helps with the last of them; they take their
    # places in the part list at the end
    fixed_specs = {"G1": mech.G1, **{f"G{s.j + 1}": s.G for s in mech.stages}}

    def fixed_solid(name: str) -> dict:
        spec = fixed_specs[name]
        collar_r = max(min(rb + 2.0, spec.root_radius - 0.5), collar_min)
        return pack(P.fixed_gear(spec, f, params.bore_of(name) / 2, (collar_r, g), boss, t + g, clock[name], tol))

    with SharedMap(fixed_solid, list(fixed_specs)) as made:
        slots: dict[str, int] = {}

        def fixed(name: str):
            say(name)
            slots[name] = len(parts)
            parts.append(None)  # filled once the child has made it

        # G's round bore runs through teeth, collar and boss: the post comes up into it from below
        hub_bore = Bore("post", (0.0, 0.0, 0.0), UP, 2 * ra, f + g + t + g)
        gear_bores = {"D": Bore("axle", (0.0, 0.0, 0.0), UP, post.pin_diameter, f),
                      "round": Bore("post", (0.0, 0.0, 0.0), UP, 2 * ra, f)}

        holes = {"D": post.hole(FEATURE_TOL)}

        def hole_of(name: str, hole: str):
            """A part's bore: the D-hole, or the round running bore of its own joint's clearance."""
            if hole == "D":
                return holes["D"]
            r = params.bore_of(name) / 2
            if r not in holes:
                holes[r] = P.disc(r, FEATURE_TOL, hole=True)
            return holes[r]

        bored: dict = {}  # identical gears share one solid (the kit prints it `count` times)

        def loose(name: str, spec, hole: str):
            key = (spec, hole, params.bore_of(name) if hole == "round" else None)
            if key not in bored:
                bored[key] = P.bored_gear(spec, f, hole_of(name, hole))
            add(Part(name, "gear", bored[key], gear=spec, bores=(gear_bores[hole],)))

        fixed("G1")
        loose("drive", mech.drive, "D")
        for s in mech.stages:
            loose(f"D{s.j}", s.D, "D")
            loose(f"M{s.j}", s.M, "round")
            fixed(f"G{s.j + 1}")
        params_belts = mech.belt_stages and _belts(mech)
        for s in mech.belt_stages:
            bs = params_belts
            prof = s.D.profile
            for name, pulley, hole in ((f"D{s.j}", s.D, "D"), (f"G{s.j + 1}", s.G, "round")):
                section = P.pulley_outline(pulley.teeth, prof.pitch, prof.pitch_line_offset, prof.groove_depth,
                                           prof.groove_radius, FEATURE_TOL)
                body = P.pulley_body(section, pulley.outside_radius + bs.flange_height, bs.flange_thickness, f,
                                     hole_of(name, hole), FEATURE_TOL)
                if name[0] == "G":
                    collar_r = max(min(rb + 2.0, pulley.root_radius - 0.5), collar_min)
                    body = P.fixed_hub(body, f, params.bore_of(name) / 2, (collar_r, g), boss, t + g, 0.0, FEATURE_TOL)
                add(Part(name, "pulley", body, info=(("teeth", pulley.teeth), ("profile", prof.name),
                                                     ("pitch_diameter_mm", round(2 * pulley.pitch_radius, 4))),
                         bores=(hub_bore if name[0] == "G" else gear_bores[hole],)))
            if s.tensioner is not None:
                r, rt = s.tensioner_radius, params.bore_of(f"T{s.j}") / 2
                roller = P.prisms([(P.annulus(rt, r + bs.flange_height, FEATURE_TOL), 0.0, bs.flange_thickness),
                                   (P.annulus(rt, r, FEATURE_TOL), bs.flange_thickness, f - bs.flange_thickness),
                                   (P.annulus(rt, r + bs.flange_height, FEATURE_TOL), f - bs.flange_thickness, f)])
                add(Part(f"T{s.j}", "idler", roller, bores=(gear_bores["round"],)))
            _, path = belt_path_of(s, prof)
            z0 = bs.flange_thickness + 0.1
            band = P.belt_band(path, prof.pitch_line_offset + prof.groove_depth, prof.back_height, z0, z0 + prof.width)
            add(Part(f"belt{s.j}", "belt", band, printed=False,
                     info=(("profile", prof.name), ("teeth", s.belt_teeth), ("length_mm", s.belt_teeth * prof.pitch),
                           ("width_mm", prof.width)),
                     stock=(Stock(f"{prof.name} closed timing belt", 1, f"{s.belt_teeth} teeth, "
                                  f"{s.belt_teeth * prof.pitch:.4g} mm pitch length, {prof.width:.4g} mm wide"),)))

        # link plates
        if params.pen_holder_height < PEN_FLOOR + 1.0:
            raise DesignError(f"{params.pen_holder_height:g} mm leaves no bore above the holder's {PEN_FLOOR:g} mm floor: "
                              f"make it at least {PEN_FLOOR + 1.0:g} mm", "pen.holder_height_mm")
        pen_spigot = DFit(params.pen_diameter / 2 + PEN_WALL, jn.press_clearance)
        prox_r = rb + jn.press_clearance / 2 + params.boss_wall
        for j, link in enumerate(mech.chain.links, 1):
            S, Pz = link.length, st.plate_z(j)
            feats, idler, distal_hole, posts = [], None, None, []
            if j < n:
                stage = (mech.stages or mech.belt_stages)[j - 1]
                top = st.layer(j + 1) if j + 1 < n else st.plate_z(j + 1) + t + g
                # thrust rings are discs the post or pin runs through: an annulus would share its inner
                # wall with the post's, and two coincident walls unite into a zero-width crack
                feats += [(P.disc(rb, FEATURE_TOL, (S, 0.0)), t, t + g)]
                posts.append(P.shaft(post, [("round", t, top - Pz)] + ([("D", top - Pz, top - Pz + f)] if j + 1 < n else []),
                                     FEATURE_TOL, (S, 0.0)))
                c = stage.idler if mech.stages else stage.tensioner
                if c is not None:
                    feats += [(P.disc(rb, FEATURE_TOL, c), t, t + g), (P.disc(ra, FEATURE_TOL, c), t, t + g + f)]
                    idler = (c, ra + params.boss_wall)
                distal = (S, ra + params.boss_wall)
            else:
                distal_hole = P.translate2d(pen_spigot.hole(FEATURE_TOL), S, 0.0)
                distal = (S, pen_spigot.radius + jn.press_clearance / 2 + params.boss_wall)
            solid = P.link_plate(S, t, boss.hole(FEATURE_TOL), prox_r, distal, idler, feats, FEATURE_TOL, distal_hole, posts)
            # G_j's D-boss presses up into the proximal hole; the pen holder's spigot down into the last distal one
            bores = (Bore("G boss", (0.0, 0.0, 0.0), UP, boss.pin_diameter, t),)
            if distal_hole is not None:
                bores += (Bore("pen spigot", (S, 0.0, t), DOWN, pen_spigot.pin_diameter, t),)
            add(Part(f"B{j}", "link", solid, bores=bores))

        # base, legs, drive axle, crank, pen holder
        bt = params.base_thickness
        dx, dy = mech.drive_centre
        a_drive = math.hypot(dx, dy)
        u = np.array([dx, dy]) / a_drive
        v = np.array([-u[1], u[0]])
        sweep = params.crank_radius + HANDLE_R + 4.0
        w = sweep + LEG_R + 2.0
        legs = [tuple(float(q) for q in s * u + sgn * w * v) for s in (-LEG_R, a_drive + LEG_R) for sgn in (1, -1)]
        crank_depth = g + CRANK_THICKNESS + HANDLE_LEN
        if params.leg_height < crank_depth + 3.0:
            raise DesignError(f"legs of {params.leg_height:g} mm leave no room under the base for the crank "
                              f"(needs {crank_depth + 3.0:g} mm)", "base.leg_height_mm")
        outline = P.hull_of_discs([((0.0, 0.0), ra + params.boss_wall + 4.0), ((dx, dy), rb + params.boss_wall)]
                                  + [(c, LEG_R + 2.0) for c in legs], FEATURE_TOL)
        holes = [P.disc(params.bore_of("drive_axle") / 2, FEATURE_TOL, (dx, dy), hole=True)] + [
            P.disc(ra + jn.press_clearance / 2, FEATURE_TOL, c, hole=True)
                                                                       for c in legs]
        outline = outline.difference(P.union2d(holes))
        top1 = st.layer(1) if n > 1 else st.plate_z(1) + t + g
        feats = [(P.disc(rb, FEATURE_TOL), 0.0, g), (P.annulus(params.bore_of("drive_axle") / 2, rb + 1.0, FEATURE_TOL, (dx, dy)), 0.0, g)]
        ground_post = P.shaft(post, [("round", 0.0, top1)] + ([("D", top1, top1 + f)] if n > 1 else []), FEATURE_TOL)
        base_bores = (Bore("drive axle", (dx, dy, g), DOWN, 2 * ra, g + bt),) + tuple(
            Bore(f"leg{i + 1} peg", (c[0], c[1], -bt), UP, 2 * ra, bt) for i, c in enumerate(legs))
        add(Part("base", "base", P.base_plate(outline, bt, feats, [ground_post]), bores=base_bores))
        leg_solid = P.leg(LEG_R, params.leg_height, ra, bt, FEATURE_TOL)  # the hole carries the clearance
        for i in range(len(legs)):
            add(Part(f"leg{i + 1}", "leg", leg_solid))
        zc = -bt - g
        add(Part("drive_axle", "axle", P.drive_axle(post, [("D", zc - CRANK_THICKNESS, zc), ("round", zc, g), ("D", g, g + f)],
                                                    FEATURE_TOL)))
        add(Part("crank", "crank", P.crank(post, params.crank_radius, CRANK_THICKNESS, ra + params.boss_wall, HANDLE_R,
                                           HANDLE_LEN, FEATURE_TOL),
                 bores=(Bore("drive axle", (0.0, 0.0, 0.0), DOWN, post.pin_diameter, CRANK_THICKNESS),)))
        add(Part("pen_holder", "pen_holder", P.pen_holder(pen_spigot, t, pen_spigot.radius + 1.5, params.pen_holder_height,
                                                          (params.pen_diameter + PEN_BORE_CLEARANCE) / 2, PEN_FLOOR, FEATURE_TOL),
                 bores=(Bore("pen", (0.0, 0.0, t + params.pen_holder_height), DOWN, params.pen_diameter,
                                              params.pen_holder_height - PEN_FLOOR),)))

        for name, data in zip(fixed_specs, made.results()):
            part = Part(name, "gear", unpack(data), gear=fixed_specs[name], clocking=clock[name], bores=(hub_bore,))
            parts[slots[name]] = replace(part, print_flip=least_support_flip(part.solid, params.printer.overhang_deg))
    contacts = _contacts(mech, params, st, len(legs))
    static = {"base": pose_z()}
    static.update({f"leg{i + 1}": pose_z(c[0], c[1], -bt) for i, c in enumerate(legs)})
    return Kit(mech, params, st, tuple(parts), static, clock, contacts)


def _contacts(mech: ChainDesign, params: KitParams, st: Stack, n_legs: int) -> tuple[Contact, ...]:
    """Every pair of parts the design means to touch: fits on axles, D-fits, thrust faces, meshes."""
    g, f, t = st.gap, st.face, st.plate
    press = params.joints.press_clearance / 2
    run_of = lambda name: params.joints.running_of(name) / 2  # noqa: E731  (radial)
    bt = params.base_thickness
    n = len(mech.chain.links)
    body = lambda j: (st.layer(j), st.layer(j) + f)  # noqa: E731
    plate = lambda j: (st.plate_z(j), st.plate_z(j) + t)  # noqa: E731
    out = [Contact("G1", "base", "running", body(0), run_of("G1")), Contact("G1", "B1", "press", plate(1), press),
           Contact("G1", "drive", "mesh"), Contact("drive", "drive_axle", "press", body(0), press),
           Contact("drive", "base", "thrust"), Contact("drive_axle", "base", "running", (-bt, 0.0), run_of("drive_axle")),
           Contact("crank", "drive_axle", "press", (-bt - g - 6.0, -bt - g), press),
           Contact("pen_holder", f"B{n}", "press", plate(n), press)]
    out += [Contact(f"leg{i + 1}", "base", "press", (-bt, 0.0), press) for i in range(n_legs)]
    for s in mech.stages:
        j = s.j
        carrier = "base" if j == 1 else f"B{j - 1}"
        out += [Contact(f"D{j}", carrier, "press", body(j), press), Contact(f"D{j}", f"G{j}", "thrust"),
                Contact(f"M{j}", f"B{j}", "running", body(j), run_of(f"M{j}")),
                Contact(f"G{j + 1}", f"B{j}", "running", body(j), run_of(f"G{j + 1}")),
                Contact(f"G{j + 1}", f"B{j + 1}", "press", plate(j + 1), press),
                Contact(f"D{j}", f"M{j}", "mesh"), Contact(f"M{j}", f"G{j + 1}", "mesh")]
    for s in mech.belt_stages:
        j = s.j
        carrier = "base" if j == 1 else f"B{j - 1}"
        out += [Contact(f"D{j}", carrier, "press", body(j), press), Contact(f"D{j}", f"G{j}", "thrust"),
                Contact(f"G{j + 1}", f"B{j}", "running", body(j), run_of(f"G{j + 1}")),
                Contact(f"G{j + 1}", f"B{j + 1}", "press", plate(j + 1), press),
                Contact(f"belt{j}", f"D{j}", "belt"), Contact(f"belt{j}", f"G{j + 1}", "belt")]
        if s.tensioner is not None:
            out += [Contact(f"T{j}", f"B{j}", "running", body(j), run_of(f"T{j}")), Contact(f"belt{j}", f"T{j}", "belt")]
    return tuple(out)


def _belts(mech: ChainDesign):
    """The belt settings a belt mechanism was made with (flanges, tensioner): kept on its stages."""
    return mech.belt_stages[0].settings


def belt_path_of(stage, profile):
    """The pitch path of a belt stage in its link frame: around D, the tensioner (if any) and G."""
    from ...design.belt import belt_path
    D = ((0.0, 0.0), stage.D.pitch_radius, 1)
    G = ((stage.length, 0.0), stage.G.pitch_radius, 1)
    if stage.tensioner is None:
        return belt_path([D, G])
    T = (stage.tensioner, stage.tensioner_radius + profile.back_height, -1)
    return belt_path([D, T, G] if stage.tensioner[1] < 0 else [G, T, D])


# ---------------------------------------------------------------- the kit as the pipeline takes it

def size_key(spec: "ChainSpec", name: str) -> str:
    """The config key a part's size traces back to."""
    mech = spec.mechanism
    if name.startswith("B"):
        j = int(name[1:])
        return {"curve": "curve.scale_mm_per_unit", "drawing": "curve.scale"}.get(mech.source, f"links[{j - 1}].length_mm")
    if name in ("G1", "drive"):
        return "drive.teeth"
    if name[0] in "DMG" and name[1:].isdigit():
        j = int(name[1:]) - (1 if name[0] == "G" else 0)
        return "teeth" if mech.auto_teeth else f"teeth[{j - 1}].{name[0]}"
    return {"base": "base", "crank": "base.crank_radius_mm", "pen_holder": "pen"}.get(name, name)


def oversize_parts(spec: "ChainSpec", kit: Kit) -> list[tuple[str, str, np.ndarray]]:
    """Parts that print on the printer in no way (``export.prints.too_large``: larger than its envelope
    in every axis order, and, laid as they print, wider than its bed at every turn — a long link may
    lie on the diagonal — or taller than it): (name, key, extents)."""
    from ...export.prints import too_large

    return [(p.name, size_key(spec, p.name), ext) for p, ext in too_large(kit, kit.params.checks.plate_margin)]


def build(spec: "ChainSpec", progress=None) -> Kit:
    """``build_kit`` of a resolved design; a design error names its key."""
    try:
        kit = build_kit(spec.mechanism, spec.params, progress)
    except DesignError as e:
        raise ConfigError(spec.path, e.key_path, e.problem) from None
    return kit

def refuse(spec: "ChainSpec", kit: Kit) -> None:
    """``build`` writes no kit with an empty part or a part larger than the printer (``check`` reports them)."""
    for part in empty_parts(kit.parts):
        raise ConfigError(spec.path, size_key(spec, part.name), f"part {part.name} comes out empty: a size in the "
                          "design leaves it no material")
    big = oversize_parts(spec, kit)
    if big:
        name, key, ext = big[0]
        env = " × ".join(f"{x:g}" for x in spec.params.printer.envelope)
        raise ConfigError(spec.path, key, f"part {name} measures {' × '.join(f'{x:.1f}' for x in ext[::-1])} mm "
                          f"and does not fit the printer's {env} mm envelope in any orientation, nor its bed at any turn"
                          + (f" (and {len(big) - 1} more parts)" if len(big) > 1 else ""))


def design_summary(spec: "ChainSpec", kit: Kit, kind: str) -> dict:
    """The manifest's "design" entry: chain, stages, drive, stack, findings."""
    from ...design.trace import crank_turns

    mech, params = spec.mechanism, spec.params
    return {
        "name": params.name,
        "kind": kind,
        "config": spec.path.name,
        "printer": params.printer.name,
        "material": params.material,
        "density_g_cm3": r6(params.density * 1000),
        "crank_angle_rad": 0.0,
        "crank_turns_per_drawing": str(crank_turns(mech)),
        "module_mm": params.system.module,
        "pressure_angle_deg": r6(math.degrees(params.system.pressure_angle)),
        "teeth_mode": "auto" if mech.auto_teeth else "explicit",
        "ground_offset_mm": [r6(mech.chain.offset.real), r6(mech.chain.offset.imag)],
        "links": [{"j": j, "name": l.name, "speed": l.speed, "length_mm": r6(l.length),
                   "initial_angle_deg": r6(math.degrees(l.phase))} for j, l in enumerate(mech.chain.links, 1)],
        "stages": [{"j": s.j, "ratio": str(s.ratio), "teeth": {"D": s.D.teeth, "M": s.M.teeth, "G": s.G.teeth},
                    "profile_shift": {"D": r6(s.D.profile_shift), "M": r6(s.M.profile_shift),
                                      "G": r6(s.G.profile_shift)},
                    "a_DM_mm": r6(s.a_DM), "a_MG_mm": r6(s.a_MG),
                    "idler_mm": [r6(s.idler[0]), r6(s.idler[1])]} for s in mech.stages],
        "drive": {"teeth": mech.drive.teeth, "centre_mm": [r6(c) for c in mech.drive_centre]},
        "stack_mm": {"axial_gap": kit.stack.gap, "face_width": kit.stack.face, "plate": kit.stack.plate,
                     "layers": [r6(kit.stack.layer(j)) for j in range(len(mech.stages) + 1)],
                     "plates": [r6(kit.stack.plate_z(j)) for j in range(1, len(mech.chain.links) + 1)]},
        "findings": [{"severity": f.severity, "code": f.rule, "key": f.key, "message": f.message}
                     for f in mech.findings],
    }

def kit_files(spec: "ChainSpec", kit: Kit, raw: "LoadedDesign") -> dict[str, bytes]:
    """The design and its printer profile, as a kit folder keeps them: design.yaml names
    printer.yaml beside it."""
    data = raw.document()
    data["printer"] = "printer.yaml"
    if isinstance(data.get("gears"), dict) and data["gears"].get("module_mm") == "auto":
        data["gears"]["module_mm"] = spec.params.system.module  # the module auto chose, pinned
    c = raw.design.curve
    if c is not None and c.drawn and c.scale == "auto":
        data["curve"] = {**data["curve"], "scale": spec.mechanism.drawing.scale}  # the scale auto chose, pinned
    files = {}
    if c is not None and c.drawn and (c.svg is not None or isinstance(c.points, str)):
        from ...config.drawing import curve_file

        key, suffix = ("svg", ".svg") if c.svg is not None else ("points", ".csv")
        src = curve_file(getattr(c, key), raw.path, f"curve.{key}", suffix)
        data["curve"] = {**data["curve"], key: f"curve{suffix}"}  # the kit keeps its own copy
        files[f"curve{suffix}"] = src.read_bytes()
    return {"design.yaml": dump_yaml(data), "printer.yaml": dump_yaml(raw.printer_document()), **files}
